#!/usr/bin/env bash
# Quick start (2): set up, build, and run the test suite (ctest; tests labelled `slow` are left out, run them with
# `ctest --test-dir build -L slow`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"$jobs" -LE slow
