#!/usr/bin/env bash
# Sanitizer and fuzz jobs (docs/reliability.md), run by scripts/test.sh after the main test suite.
#  1. build-asan: clang, Release with -O1 -g, MICHI_SANITIZE=address (ASan+UBSan on the libraries, the `michi`
#     command and the tests) and MICHI_FUZZ=ON (the same libraries instrumented for coverage, plus the libFuzzer
#     targets). Runs the named subset MICHI_ASAN_TESTS (tests/CMakeLists.txt; `asan-all`: the whole default set,
#     about an hour on 2 cores) under ASan+UBSan, then scripts/fuzz.sh (each
#     fuzz target for MICHI_FUZZ_SECONDS seconds) in the same build.
#  2. build-tsan: clang, MICHI_SANITIZE=thread; builds and runs only the tests that start threads (MICHI_TSAN_TESTS
#     in tests/CMakeLists.txt, label tsan).
# Usage: scripts/sanitizers.sh [asan|asan-all|tsan|fuzz|all]   (default all). Build directories: $MICHI_ASAN_DIR (build-asan),
# $MICHI_TSAN_DIR (build-tsan). Findings inside OMPL/FCL are suppressed in tests/sanitizers/*.supp, with the bug named.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-all}
jobs=$(nproc 2>/dev/null || echo 2)
src=$(pwd)
asan_dir=${MICHI_ASAN_DIR:-build-asan}
tsan_dir=${MICHI_TSAN_DIR:-build-tsan}
cxx=${MICHI_SANITIZER_CXX:-clang++}
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
# -gline-tables-only: file and line in every report at a fraction of -g's compile and link time
common=(-DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -gline-tables-only -DNDEBUG" -DCMAKE_CXX_COMPILER="$cxx"
    -DMICHI_BUILD_BENCHMARKS=OFF "${launcher[@]}")
supp="$src/tests/sanitizers"
# fast_unwind_on_malloc=0: OMPL, FCL, urdfdom and assimp have no frame pointers, so the fast unwinder stops at their
# first frame and the suppressions (which name functions of those libraries) could not match
export ASAN_OPTIONS="suppressions=$supp/asan.supp:detect_leaks=1:fast_unwind_on_malloc=0:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0:fast_unwind_on_malloc=0"
export UBSAN_OPTIONS="suppressions=$supp/ubsan.supp:print_stacktrace=1:halt_on_error=1"
export TSAN_OPTIONS="suppressions=$supp/tsan.supp:halt_on_error=1:second_deadlock_stack=1"

stamp() { echo "sanitizers: $(date +%T) $*" >&2; }

# fits STAGE MINUTES: true when MICHI_CI_DEADLINE (epoch seconds, set by scripts/test.sh) leaves MINUTES for STAGE
fits() {
    [[ -z ${MICHI_CI_DEADLINE:-} ]] && return 0
    local left=$(( (MICHI_CI_DEADLINE - $(date +%s)) / 60 ))
    if (( left < $2 )); then
        stamp "SKIPPED $1: $left min left of the CI budget, the stage takes about $2 (run scripts/sanitizers.sh $1)"
        return 1
    fi
}

run_asan() {
    local all=${1:-OFF}
    stamp "configure $asan_dir (ASan+UBSan, libFuzzer; every test: $all)"
    cmake -S . -B "$asan_dir" "${common[@]}" -DMICHI_SANITIZE=address -DMICHI_FUZZ=ON -DMICHI_ASAN_ALL_TESTS="$all" \
        >/dev/null
    stamp "build $asan_dir"
    cmake --build "$asan_dir" -j"$jobs"
    stamp "ctest under ASan+UBSan (MICHI_ASAN_TESTS, or all but slow and install with asan-all)"
    # the termination tests time a planner's return to 0.1 s: a timing, not behaviour, under a 3-10x sanitizer slowdown
    ctest --test-dir "$asan_dir" --output-on-failure -j"$jobs" -LE 'slow|install|libfuzzer' --timeout 900 \
        -E 'ReturnsWithinATenthOfASecond'
}

run_fuzz() {
    stamp "fuzz targets in $asan_dir"
    MICHI_FUZZ_BUILD_DIR="$asan_dir" bash scripts/fuzz.sh
}

run_tsan() {
    stamp "configure $tsan_dir (TSan)"
    cmake -S . -B "$tsan_dir" "${common[@]}" -DMICHI_SANITIZE=thread >/dev/null
    stamp "build $tsan_dir (the threaded tests only)"
    cmake --build "$tsan_dir" -j"$jobs" --target michi_tsan_tests
    stamp "ctest under TSan (label tsan)"
    # BundledProblems.LoadWithValidStartAndGoal loads every bundled problem on one thread: no race to find, and
    # over 13 minutes under TSan
    ctest --test-dir "$tsan_dir" --output-on-failure -j"$jobs" -L tsan --timeout 900 \
        -E 'ReturnsWithinATenthOfASecond|BundledProblems.LoadWithValidStartAndGoal'
}

start=$(date +%s)
case "$what" in
    asan) run_asan ;;
    asan-all) run_asan ON ;;
    fuzz) run_fuzz ;;
    tsan) run_tsan ;;
    all)
        # the ASan build serves the fuzz stage too; estimates are for 2 cores with a cold ccache
        if fits asan 35; then
            run_asan
            if fits fuzz 4; then run_fuzz; fi
        fi
        if fits tsan 20; then run_tsan; fi
        ;;
    *) echo "usage: scripts/sanitizers.sh [asan|asan-all|tsan|fuzz|all]" >&2; exit 2 ;;
esac
stamp "done ($what) in $(( $(date +%s) - start )) s"
