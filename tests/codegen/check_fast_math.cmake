# A generated header under -ffast-math or -ffinite-math-only: refused with the header's own
# #error (its NaN checks would not hold: with -ffinite-math-only alone a NaN input returned
# ok with a NaN impulse), compiled when IMPACTGEN_ALLOW_FAST_MATH says so; IMPACTGEN_FUNC,
# the user's hook for function attributes, is honoured. A smooth and a friction header.
# -D: CXX HEADER_DIR WORK
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/fast_math.cpp "#include \"generated/planar.hpp\"\nint main()\n{\n    impactgen::generated::planar_result<double> r;\n    return static_cast<int>(impactgen::generated::planar<double>(0.5, 1, 1, 0, -1, 0, 1, 0, 1, 1, 0, 1, 0, 0, 0, r));\n}\n")
file(WRITE ${WORK}/fast_math_friction.cpp "#include \"generated/planar_friction.hpp\"\nint main()\n{\n    impactgen::generated::planar_friction_result<double> r;\n    return static_cast<int>(impactgen::generated::planar_friction<double>(0.5, 0.3, 1, 1, 0, -1, 0, 1, 0, 1, 1, 0, 1, 0, 0, 0, r));\n}\n")
foreach(src fast_math fast_math_friction)
  foreach(flag -ffast-math -ffinite-math-only)
    execute_process(COMMAND ${CXX} -std=c++17 ${flag} -I${HEADER_DIR} -c ${WORK}/${src}.cpp -o ${WORK}/${src}.o
                    RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(rc EQUAL 0 OR NOT err MATCHES "ffast-math and -ffinite-math-only remove the NaN and infinity checks")
      message(FATAL_ERROR "${src} ${flag}: expected the header's #error, got rc=${rc}: ${err}")
    endif()
    execute_process(COMMAND ${CXX} -std=c++17 ${flag} -DIMPACTGEN_ALLOW_FAST_MATH -I${HEADER_DIR} -c ${WORK}/${src}.cpp -o ${WORK}/${src}.o
                    RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${src} ${flag} with IMPACTGEN_ALLOW_FAST_MATH: rc=${rc}: ${err}")
    endif()
  endforeach()
  # -ffast-math with the finite-math assumption taken back (neither __FAST_MATH__ nor
  # __FINITE_MATH_ONLY__ is then defined to 1) compiles, and its NaN check holds: a NaN mass
  # gives non_finite_input (status 1), not ok.
  file(READ ${WORK}/${src}.cpp text)
  string(REPLACE "(0.5, " "(0.5, std::numeric_limits<double>::quiet_NaN() * 0 + " text "${text}")
  file(WRITE ${WORK}/${src}_nan.cpp "#include <limits>\n${text}")
  execute_process(COMMAND ${CXX} -std=c++17 -O2 -ffast-math -fno-finite-math-only -I${HEADER_DIR} ${WORK}/${src}_nan.cpp
                          -o ${WORK}/${src}_nan
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${src} -ffast-math -fno-finite-math-only: rc=${rc}: ${err}")
  endif()
  execute_process(COMMAND ${WORK}/${src}_nan RESULT_VARIABLE status)
  if(NOT status EQUAL 1)
    message(FATAL_ERROR "${src} -ffast-math -fno-finite-math-only with a NaN input: status ${status}, expected 1 (non_finite_input)")
  endif()
  execute_process(COMMAND ${CXX} -std=c++17 -Wall -Wextra -Wpedantic -Werror "-DIMPACTGEN_FUNC=static inline" -I${HEADER_DIR}
                          -c ${WORK}/${src}.cpp -o ${WORK}/${src}.o
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${src} IMPACTGEN_FUNC=static inline: rc=${rc}: ${err}")
  endif()
endforeach()
