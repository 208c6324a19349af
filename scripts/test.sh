#!/usr/bin/env bash
# Every test: install what is missing, build everything with g++ and warnings as
# errors, run the whole suite; then the library's tests again, built with clang++,
# under ASan + UBSan (both compilers build the library and its tests -Werror).
#   IMPACTGEN_SKIP_SANITIZE=1  skip the sanitizer pass (local iterations)
#   IMPACTGEN_SANITIZE_ALL=1   the sanitizer pass over every test program, not only the
#                              library's tests (label "sanitize")
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --tests
jobs=$(nproc)
start=$(date +%s)

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="-Werror" >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure -j"$jobs")
echo "impactgen: release build and tests took $(( $(date +%s) - start )) s"

if [[ "${IMPACTGEN_SKIP_SANITIZE:-0}" != "1" ]]; then
  start=$(date +%s)
  # Test discovery runs the test programs at build time: the sanitizer options
  # hold for the build as well as for ctest.
  export ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # -O1 -g1 (line tables: stack traces with file and line) compiles in half the time
  # of -O2 -g with the sanitizers on, and the sanitized tests run nearly as fast.
  # clang++ compiles the sanitized build in about 60 % of g++'s time (4 against 6.3
  # minutes on 2 cores), and the release pass above was g++'s: both compilers build the
  # library and its tests with warnings as errors.
  cmake -S . -B build-sanitize -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIMPACTGEN_SANITIZE=ON \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
        -DIMPACTGEN_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS="-Werror" >/dev/null
  # Sanitized code runs ~5-10x slower: fewer random samples per class (the
  # release pass above runs the full counts).
  # The tests labelled "headers" compile generated headers with the host compilers and
  # run them: nothing sanitized runs in them, and the release pass above ran them all.
  # Those labelled "browser" open the HTML pages in Chromium: the pages are byte-identical
  # to the release pass's (golden files), and the sanitized printers run in explain_tests.
  if [[ "${IMPACTGEN_SANITIZE_ALL:-0}" == "1" ]]; then
    # Every test program under the sanitizers (about 8 more minutes on 2 cores).
    cmake --build build-sanitize -j"$jobs"
    (cd build-sanitize && IMPACTGEN_SAMPLES=200 ctest --output-on-failure -j"$jobs" -LE "headers|browser")
  else
    # By default the tests labelled "sanitize": the library code (names, the reader,
    # derivation, solution, printers, figures, codegen through the command line) under
    # ASan + UBSan -- tests/names, core, explain, figure and the fuzzer, which drives
    # every subcommand, codegen included, on random and hostile problems. Left to the
    # release pass: the generated-code verification suites (tests/codegen: the headers'
    # numbers against CLN), the installed package and the adapters, whose sanitized
    # part is the same library code.
    # (explain_browser_tests is built too, though its tests do not run here: a test program
    # that is not built leaves a placeholder test without its labels.)
    cmake --build build-sanitize -j"$jobs" --target impactgen test_core test_friction_reference test_names \
          explain_tests explain_browser_tests figure_tests fuzz_cli
    (cd build-sanitize && IMPACTGEN_SAMPLES=200 ctest --output-on-failure -j"$jobs" -L sanitize -LE "headers|browser")
  fi
  echo "impactgen: sanitizer build and tests took $(( $(date +%s) - start )) s"
fi
