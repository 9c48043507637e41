#!/usr/bin/env bash
# Quick start (2): set up, build, and run the test suite (ctest; tests labelled `slow` are left out, run them with
# `ctest --test-dir build -L slow`), then the sanitizer and fuzz jobs (scripts/sanitizers.sh, docs/reliability.md:
# ASan+UBSan tests, libFuzzer runs, TSan on the threaded tests; about half an hour on 2 cores; set
# MICHI_SKIP_SANITIZERS=1 to leave them out).
set -euo pipefail
cd "$(dirname "$0")/.."
# CI stops a landing at 90 minutes: the sanitizer stages get the time left of an 80-minute budget counted from here,
# and a stage that would not fit is skipped with a line saying so (scripts/sanitizers.sh)
export MICHI_CI_DEADLINE=${MICHI_CI_DEADLINE:-$(($(date +%s) + 80 * 60))}
bash scripts/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"$jobs" -LE slow
if [[ "${MICHI_SKIP_SANITIZERS:-0}" != 1 ]]; then
    bash scripts/sanitizers.sh all
fi
