#!/usr/bin/env bash
# Runs every libFuzzer target (tests/fuzz/, docs/reliability.md) for a bounded time in a MICHI_FUZZ=ON build
# (scripts/sanitizers.sh makes one in build-asan; any clang build with -DMICHI_FUZZ=ON will do).
#   scripts/fuzz.sh                       every target, MICHI_FUZZ_SECONDS (default: the build's setting, 20 s) each
#   MICHI_FUZZ_SECONDS=3600 scripts/fuzz.sh urdf pgm     longer runs of some targets
# New corpus entries stay in <build>/tests/fuzz/work/<target>/, crash inputs in <build>/tests/fuzz/artifacts/<target>/:
# copy a crash input into tests/fuzz/regressions/<target>/ (named for the bug) so every build replays it.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${MICHI_FUZZ_BUILD_DIR:-build-asan}
jobs=$(nproc 2>/dev/null || echo 2)
if [[ ! -f "$dir/CMakeCache.txt" ]] || ! grep -q '^MICHI_FUZZ:BOOL=ON' "$dir/CMakeCache.txt"; then
    echo "fuzz: $dir is not a -DMICHI_FUZZ=ON build (run scripts/sanitizers.sh asan first)" >&2
    exit 2
fi
if [[ -n "${MICHI_FUZZ_SECONDS:-}" ]]; then
    cmake -S . -B "$dir" -DMICHI_FUZZ_SECONDS="$MICHI_FUZZ_SECONDS" >/dev/null
fi
targets=()
for t in "$@"; do targets+=("fuzz_${t}_fuzzer"); done
if [[ ${#targets[@]} -eq 0 ]]; then
    cmake --build "$dir" -j"$jobs"
    regex='^fuzz_'
else
    cmake --build "$dir" -j"$jobs" --target "${targets[@]}"
    regex="^fuzz_($(IFS='|'; echo "$*"))\$"
fi
ctest --test-dir "$dir" --output-on-failure -j"$jobs" -L libfuzzer -R "$regex"
