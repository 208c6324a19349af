# Every generated header compiles on its own: for each header that the DRIVERS (the
# translation units of check_compile.cmake's folded tests, joined by "|") include, a
# translation unit of one line, #include "header", checked by CXX -std=STD -fsyntax-only
# under the strict warnings of check_compile.cmake. Folded, a header that misses an
# #include or a declaration could be rescued by one included before it; here it cannot.
# -D: CXX STD DRIVERS WORK. Every header is tried; the failure names all that fail.
include(${CMAKE_CURRENT_LIST_DIR}/strict_flags.cmake)
string(REPLACE "|" ";" drivers "${DRIVERS}")
file(MAKE_DIRECTORY ${WORK})
set(count 0)
set(failed)
set(messages)
foreach(driver IN LISTS drivers)
  file(STRINGS ${driver} header_lines REGEX "^#include \".*\\.hpp\"$")
  foreach(line IN LISTS header_lines)
    string(REGEX REPLACE "^#include \"(.*)\"$" "\\1" header "${line}")
    get_filename_component(stem ${header} NAME_WE)
    set(tu ${WORK}/${stem}.cpp)
    file(WRITE ${tu} "#include \"${header}\"\n")
    execute_process(COMMAND ${CXX} -std=${STD} ${IMPACTGEN_STRICT_FLAGS} -fsyntax-only ${tu}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    math(EXPR count "${count} + 1")
    if(NOT rc EQUAL 0)
      list(APPEND failed ${header})
      string(APPEND messages "${out}${err}")
    endif()
  endforeach()
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "no header found in ${DRIVERS}")
endif()
if(failed)
  list(JOIN failed "\n  " failed)
  message(FATAL_ERROR "${CXX} -std=${STD} does not compile these headers on their own:\n  ${failed}\n${messages}")
endif()
message(STATUS "${count} headers compile on their own with ${CXX} -std=${STD}")
