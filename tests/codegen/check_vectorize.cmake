# The batch form's first loop vectorises: compiled at -O3 with the compiler's
# vectorisation report, the report must name that loop as vectorised (g++:
# "loop vectorized", clang++: "vectorized loop"), for float and double.
# -D: CXX HEADER (a generated header with function planar) WORK
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/vectorize.cpp "#include \"${HEADER}\"\nusing namespace impactgen::generated;\n"
  "void run_d(long n, const double* const* in, double* const* out, impact_status* s) { planar_batch(n, in, out, s); }\n"
  "void run_f(long n, const float* const* in, float* const* out, impact_status* s) { planar_batch(n, in, out, s); }\n")
execute_process(COMMAND ${CXX} --version OUTPUT_VARIABLE version)
if(version MATCHES "clang")
  set(report -Rpass=loop-vectorize)
  set(pattern "vectorized loop")
else()
  set(report -fopt-info-vec-optimized)
  set(pattern "loop vectorized")
endif()
execute_process(COMMAND ${CXX} -std=c++17 -O3 ${report} -c ${WORK}/vectorize.cpp -o ${WORK}/vectorize.o
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "compiling the batch form failed: ${err}")
endif()
# The first pass is the first `for` of planar_batch: its line in the header.
file(STRINGS ${HEADER} lines)
set(n 0)
set(batch_seen FALSE)
set(loop_line "")
foreach(line IN LISTS lines)
  math(EXPR n "${n} + 1")
  if(line MATCHES "unsigned planar_batch_pass\\(")
    set(batch_seen TRUE)
  endif()
  if(batch_seen AND loop_line STREQUAL "" AND line MATCHES "^    for \\(long i = 0")
    set(loop_line ${n})
  endif()
endforeach()
if(loop_line STREQUAL "")
  message(FATAL_ERROR "no batch loop found in ${HEADER}")
endif()
string(REGEX MATCHALL "[^\n]*:${loop_line}:[0-9]+:[^\n]*${pattern}[^\n]*" hits "${out}${err}")
list(LENGTH hits count)
if(count LESS 2)
  message(FATAL_ERROR "${CXX}: the batch loop at line ${loop_line} was vectorised ${count} time(s) of 2 (float, double):\n${out}${err}")
endif()
message(STATUS "${CXX}: batch loop vectorised (${count} reports)")

# Where a type does not vectorise (long double; a symbolic normal's sqrt under
# math-errno, SQRT_HEADER) the batch form still compiles without a warning under
# -Werror at -O3: nothing forces the vectoriser.
file(WRITE ${WORK}/no_warning.cpp "#include \"${HEADER}\"\n#include \"${SQRT_HEADER}\"\nusing namespace impactgen::generated;\n"
  "void run_l(long n, const long double* const* in, long double* const* out, impact_status* s) { planar_batch(n, in, out, s); }\n"
  "template <typename T> void run_s(long n, const T* const* in, T* const* out, impact_status* s) { box_floor_sqrt_batch(n, in, out, s); }\n"
  "template void run_s<float>(long, const float* const*, float* const*, impact_status*);\n"
  "template void run_s<double>(long, const double* const*, double* const*, impact_status*);\n"
  "template void run_s<long double>(long, const long double* const*, long double* const*, impact_status*);\n")
execute_process(COMMAND ${CXX} -std=c++17 -O3 -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Werror -c ${WORK}/no_warning.cpp
                        -o ${WORK}/no_warning.o RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${CXX}: a batch form that does not vectorise does not compile cleanly:\n${err}")
endif()
