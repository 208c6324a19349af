# Compiles MAIN with the generated HEADER under strict warnings with compiler
# CXX and standard STD, then runs it. -D: CXX STD HEADER MAIN DEFINE WORK.
set(flags -std=${STD} -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Werror -O1)
get_filename_component(stem ${HEADER} NAME_WE)
get_filename_component(cxx_name ${CXX} NAME)
set(exe ${WORK}/${stem}_${cxx_name}_${STD})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${CXX} ${flags} "-DGEN_HEADER=\"${HEADER}\"" -D${DEFINE} ${MAIN} -o ${exe}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${CXX} -std=${STD} does not compile ${HEADER}:\n${out}${err}")
endif()
execute_process(COMMAND ${exe} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${exe} failed:\n${out}${err}")
endif()
message(STATUS "${out}")
