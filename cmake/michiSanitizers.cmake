# Sanitizer and fuzzing builds (docs/reliability.md).
#
#   -DMICHI_SANITIZE=address  AddressSanitizer + UndefinedBehaviorSanitizer on every michi target (libraries, the
#                             `michi` command, tests): -fsanitize=address,undefined -fno-omit-frame-pointer and
#                             -DEIGEN_MALLOC_ALREADY_ALIGNED=1 (without it Eigen's handmade aligned allocation in
#                             michi's instrumented code and in the uninstrumented OMPL library disagree, and ASan
#                             reports bad frees of Eigen objects that cross the boundary).
#   -DMICHI_SANITIZE=thread   ThreadSanitizer on every michi target; only the tests that start threads
#                             (MICHI_TSAN_TESTS in tests/CMakeLists.txt) are registered with ctest, label `tsan`.
#   -DMICHI_FUZZ=ON           (clang only) libFuzzer targets in tests/fuzz/ linked with -fsanitize=fuzzer, and the
#                             libraries instrumented for coverage (-fsanitize=fuzzer-no-link) so the fuzzer sees
#                             into the readers. Combine with MICHI_SANITIZE=address: one build serves the ASan+UBSan
#                             test run and the fuzz run (scripts/sanitizers.sh does this).
#
# The flags are applied to the targets themselves (michi_apply_sanitizers(), called at the end of
# tests/CMakeLists.txt once every target exists), not through CMAKE_CXX_FLAGS, so the setting lives in one place.
set(MICHI_SANITIZE "" CACHE STRING "Sanitizer build: '' (none), 'address' (ASan+UBSan) or 'thread' (TSan)")
set_property(CACHE MICHI_SANITIZE PROPERTY STRINGS "" address thread)
option(MICHI_FUZZ "Build the libFuzzer targets in tests/fuzz with clang (-fsanitize=fuzzer)" OFF)

if(MICHI_SANITIZE STREQUAL "address")
    set(MICHI_SANITIZER_COMPILE_OPTIONS -fsanitize=address,undefined -fno-omit-frame-pointer -gline-tables-only)
    set(MICHI_SANITIZER_LINK_OPTIONS -fsanitize=address,undefined)
    set(MICHI_SANITIZER_DEFINITIONS EIGEN_MALLOC_ALREADY_ALIGNED=1)
elseif(MICHI_SANITIZE STREQUAL "thread")
    set(MICHI_SANITIZER_COMPILE_OPTIONS -fsanitize=thread -fno-omit-frame-pointer -gline-tables-only)
    set(MICHI_SANITIZER_LINK_OPTIONS -fsanitize=thread)
    set(MICHI_SANITIZER_DEFINITIONS EIGEN_MALLOC_ALREADY_ALIGNED=1)
elseif(NOT MICHI_SANITIZE STREQUAL "")
    message(FATAL_ERROR "MICHI_SANITIZE must be empty, 'address' or 'thread' (got '${MICHI_SANITIZE}')")
endif()

if(MICHI_FUZZ)
    if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
        message(FATAL_ERROR "MICHI_FUZZ=ON needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++ "
            "(Debian packages clang and libclang-rt-14-dev)")
    endif()
    if(MICHI_SANITIZE STREQUAL "thread")
        message(FATAL_ERROR "MICHI_FUZZ=ON goes with MICHI_SANITIZE=address (or none), not thread")
    endif()
    if(MICHI_SANITIZE STREQUAL "")
        # a fuzz build is always an ASan+UBSan build: a fuzzer without them finds only segfaults
        set(MICHI_SANITIZER_COMPILE_OPTIONS -fsanitize=address,undefined -fno-omit-frame-pointer -gline-tables-only)
        set(MICHI_SANITIZER_LINK_OPTIONS -fsanitize=address,undefined)
        set(MICHI_SANITIZER_DEFINITIONS EIGEN_MALLOC_ALREADY_ALIGNED=1)
    endif()
    list(APPEND MICHI_SANITIZER_COMPILE_OPTIONS -fsanitize=fuzzer-no-link)
endif()

# every buildsystem target defined in \e dir and below
function(_michi_collect_targets dir out)
    get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
    get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
    foreach(sub ${subdirs})
        _michi_collect_targets(${sub} sub_targets)
        list(APPEND targets ${sub_targets})
    endforeach()
    set(${out} ${targets} PARENT_SCOPE)
endfunction()

# Adds the sanitizer flags to every compiled michi target (call once, after all targets are defined).
function(michi_apply_sanitizers)
    if(NOT MICHI_SANITIZER_COMPILE_OPTIONS)
        return()
    endif()
    _michi_collect_targets(${PROJECT_SOURCE_DIR} targets)
    foreach(t ${targets})
        get_target_property(type ${t} TYPE)
        if(type MATCHES "^(EXECUTABLE|SHARED_LIBRARY|STATIC_LIBRARY|MODULE_LIBRARY|OBJECT_LIBRARY)$")
            target_compile_options(${t} PRIVATE ${MICHI_SANITIZER_COMPILE_OPTIONS})
            target_compile_definitions(${t} PRIVATE ${MICHI_SANITIZER_DEFINITIONS})
            if(NOT type MATCHES "^(STATIC_LIBRARY|OBJECT_LIBRARY)$")
                target_link_options(${t} PRIVATE ${MICHI_SANITIZER_LINK_OPTIONS})
            endif()
        endif()
    endforeach()
    message(STATUS "michi: sanitizer flags (${MICHI_SANITIZER_COMPILE_OPTIONS}) on every michi target")
endfunction()
