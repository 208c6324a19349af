#!/usr/bin/env bash
# Every test: install what is missing; check the library's formatting (scripts/check-format.sh,
# before anything is built: it fails in seconds); build with g++ (warnings as errors) and run the
# tests of the generated code, the package, the adapters, the HTML pages and the Eigen
# reference; then build the library's own tests with clang++ (warnings as errors) and
# run them under ASan + UBSan. Each test program is built once, by the pass where it
# counts (IMPACTGEN_TEST_SET, tests/CMakeLists.txt), and both compilers build the library.
#   IMPACTGEN_SKIP_SANITIZE=1  run the library's tests in the release build instead of
#                              the sanitizer pass (local iterations: every test, one build)
#   IMPACTGEN_SANITIZE_ALL=1   the sanitizer pass over every test program (about 8 more
#                              minutes on 2 cores), after the release pass
#
# Time (2 cores): almost all of it is compiling. The two passes run one after the other: the
# sanitizer build run beside the release pass in the background (nice 10) made the whole run
# slower on a fresh 2-core machine (995 s against 852 s: four compilers on two cores), so it was
# taken back. Both builds use Ninja when it is installed (install-deps.sh --tests installs
# ninja-build; a build directory already configured keeps its generator): one graph of every
# target's objects, where make goes target by target.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --tests
bash scripts/check-format.sh
jobs=$(nproc)
start=$(date +%s)

# -G Ninja for a build directory not configured yet, when ninja is installed.
generator() {
  gen=()
  if [[ ! -f "$1/CMakeCache.txt" ]] && command -v ninja >/dev/null; then
    gen=(-G Ninja)
  fi
}

release_set=rest
[[ "${IMPACTGEN_SKIP_SANITIZE:-0}" == "1" ]] && release_set=all
# -O1, not CMake's -O3 for Release: about 25 % less compile time than -O2 for the library and
# the tests (GiNaC and CLN, where the tests spend their time, are Debian's optimised builds), and
# the benchmarks at -O1 too (IMPACTGEN_BENCH_OPT): CI compiles them and runs their agreement
# tests, never times them (they are measured from scripts/bench builds, bench/run_ratios.sh).
generator build
cmake -S . -B build "${gen[@]}" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
      -DIMPACTGEN_BENCH_OPT=-O1 -DIMPACTGEN_TEST_SET="$release_set" -DCMAKE_CXX_FLAGS="-Werror" >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure -j"$jobs")
echo "impactgen: release build (g++) and tests ($release_set) took $(( $(date +%s) - start )) s"

if [[ "${IMPACTGEN_SKIP_SANITIZE:-0}" != "1" ]]; then
  start=$(date +%s)
  # Test discovery runs the test programs at build time: the sanitizer options
  # hold for the build as well as for ctest.
  export ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # clang's runtimes symbolize stack traces (and LeakSanitizer's suppressed leaks at every
  # exit) with llvm-symbolizer (package llvm-14): without it each sanitized program warns
  # on stderr, which the command-line tests (one line of error) see.
  if [[ -x /usr/lib/llvm-14/bin/llvm-symbolizer ]]; then
    export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer UBSAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
  fi
  # -O1 -g1 (line tables: stack traces with file and line) compiles in half the time
  # of -O2 -g with the sanitizers on, and the sanitized tests run nearly as fast.
  # clang++ compiles the sanitized build in about 60 % of g++'s time (4 against 6.3
  # minutes on 2 cores here).
  # The library's tests (label "sanitize": tests/names, core, explain, figure and the
  # fuzzer, which drives every subcommand, codegen included, on random and hostile
  # problems) with their full sample counts.
  set=library
  [[ "${IMPACTGEN_SANITIZE_ALL:-0}" == "1" ]] && set=all
  generator build-sanitize
  cmake -S . -B build-sanitize "${gen[@]}" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DIMPACTGEN_SANITIZE=ON -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DIMPACTGEN_TEST_SET="$set" \
        -DIMPACTGEN_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS="-Werror" >/dev/null
  cmake --build build-sanitize -j"$jobs"
  if [[ "$set" == "all" ]]; then
    # Every test program; fewer random samples in the verification suites (sanitized code
    # runs 5-10x slower). The tests labelled "headers" compile generated headers with the
    # host compilers and run them, those labelled "browser" open the HTML pages in
    # Chromium: nothing sanitized runs in them, and the release pass ran them.
    (cd build-sanitize && IMPACTGEN_SAMPLES=200 ctest --output-on-failure -j"$jobs" -LE "headers|browser")
  else
    (cd build-sanitize && ctest --output-on-failure -j"$jobs")
  fi
  echo "impactgen: sanitizer build (clang++) and tests ($set) took $(( $(date +%s) - start )) s"
fi
