# A generated header under -ffast-math: refused with the header's own #error
# (its NaN checks would not hold), compiled when IMPACTGEN_ALLOW_FAST_MATH says so;
# IMPACTGEN_FUNC, the user's hook for function attributes, is honoured.
# -D: CXX HEADER_DIR WORK
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/fast_math.cpp "#include \"generated/planar.hpp\"\nint main()\n{\n    impactgen::generated::planar_result<double> r;\n    return static_cast<int>(impactgen::generated::planar<double>(0.5, 1, 1, 0, -1, 0, 1, 0, 1, 1, 0, 1, 0, 0, 0, r));\n}\n")
execute_process(COMMAND ${CXX} -std=c++17 -ffast-math -I${HEADER_DIR} -c ${WORK}/fast_math.cpp -o ${WORK}/fast_math.o
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "ffast-math removes the NaN and infinity checks")
  message(FATAL_ERROR "-ffast-math: expected the header's #error, got rc=${rc}: ${err}")
endif()
execute_process(COMMAND ${CXX} -std=c++17 -ffast-math -DIMPACTGEN_ALLOW_FAST_MATH -I${HEADER_DIR} -c ${WORK}/fast_math.cpp -o ${WORK}/fast_math.o
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "-ffast-math with IMPACTGEN_ALLOW_FAST_MATH: rc=${rc}: ${err}")
endif()
execute_process(COMMAND ${CXX} -std=c++17 -Wall -Wextra -Wpedantic -Werror "-DIMPACTGEN_FUNC=static inline" -I${HEADER_DIR}
                        -c ${WORK}/fast_math.cpp -o ${WORK}/fast_math.o
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "IMPACTGEN_FUNC=static inline: rc=${rc}: ${err}")
endif()
