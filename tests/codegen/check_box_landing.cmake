# examples/consumer/box_landing.cpp against impactgen's exact answer of the two-corner landing:
# the post-impact velocities and normal impulses of `impactgen solve --json` passed to the
# example, whose sequential-impulse loop (impactgen's contact rows) must converge to them.
execute_process(COMMAND ${IMPACTGEN} solve ${PROBLEM} --json OUTPUT_VARIABLE out RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "impactgen solve failed: ${err}")
endif()
string(JSON vx GET "${out}" bodies box velocity 0)
string(JSON vy GET "${out}" bodies box velocity 1)
string(JSON w GET "${out}" bodies box angular_velocity)
string(JSON n1 GET "${out}" contacts 0 normal_impulse)
string(JSON n2 GET "${out}" contacts 1 normal_impulse)
execute_process(COMMAND ${EXAMPLE} ${vx} ${vy} ${w} ${n1} ${n2} RESULT_VARIABLE rc OUTPUT_VARIABLE text)
message(STATUS "${text}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "box_landing does not converge to the exact answer (${vx} ${vy} ${w} ${n1} ${n2}):\n${text}")
endif()
