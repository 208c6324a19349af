# impactgen codegen for problems with friction, from the outside: the same header from
# separate processes (GiNaC's term order moves with ASLR; the header must not), mu = 0
# with --set falls back to the smooth header, clear refusals. -D: IMPACTGEN FRICTION WORK.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
foreach(input planar-friction ball-floor-friction noncentral-3d-friction ${FRICTION}/sphere-floor-3d.json
              ${FRICTION}/rod-hinge-friction.json ${FRICTION}/tilted-box-friction.json)
  set(first)
  foreach(run RANGE 1 6)
    execute_process(COMMAND ${IMPACTGEN} codegen ${input} OUTPUT_VARIABLE text RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "codegen ${input} failed: ${err}")
    endif()
    string(SHA256 h "${text}")
    if(run EQUAL 1)
      set(first ${h})
      if(NOT text MATCHES "friction_status" OR NOT text MATCHES "impact_regime")
        message(FATAL_ERROR "codegen ${input}: not a header with friction")
      endif()
    elseif(NOT h STREQUAL first)
      message(FATAL_ERROR "codegen ${input}: run ${run} differs from run 1 (non-deterministic output)")
    endif()
  endforeach()
endforeach()

# mu = 0 given with --set: the smooth header (no regime).
execute_process(COMMAND ${IMPACTGEN} codegen planar-friction --set mu=0 OUTPUT_VARIABLE text RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR text MATCHES "friction_status" OR NOT text MATCHES "impact_status planar_friction\\(")
  message(FATAL_ERROR "codegen planar-friction --set mu=0: expected the smooth header, rc=${rc}: ${err}")
endif()
# --params mu with a numeric coefficient of friction lifts it to the parameter mu.
execute_process(COMMAND ${IMPACTGEN} codegen ${FRICTION}/tilted-box-friction.json --set mu=1/2 OUTPUT_VARIABLE text RESULT_VARIABLE rc
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT text MATCHES "friction_status" OR text MATCHES "T mu,")
  message(FATAL_ERROR "codegen tilted-box-friction --set mu=1/2: expected a header with mu fixed, rc=${rc}: ${err}")
endif()

function(expect_error what)
  execute_process(COMMAND ${IMPACTGEN} codegen ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  if(rc EQUAL 0 OR NOT err MATCHES "${what}")
    message(FATAL_ERROR "codegen ${ARGN}: expected an error matching '${what}', got rc=${rc}: ${err}")
  endif()
endfunction()
expect_error("--wrt: nx is a component of the normal" ${FRICTION}/tilted-box-friction.json --wrt e,nx)
expect_error("--wrt: q is not an input of the generated function \\(its inputs: e, mu, m1, I1, " planar-friction --wrt e,q)
expect_error("--wrt: e is named twice" planar-friction --wrt e,e)
expect_error("--wrt: q is not an input of the generated function \\(its inputs: e, mu, l, m, theta, " rod-rough-floor --wrt q)
# A system without inputs has nothing to differentiate by, as one contact has not.
expect_error("--jacobian: the generated function has no input to differentiate by"
             ${FRICTION}/../../../examples/systems/two-corner-landing.json --jacobian)
expect_error("--inverse-mass: the engine input convention is not offered" planar-friction --inverse-mass)
expect_error("--inverse-inertia: the engine input convention is not offered" noncentral-3d-friction --inverse-inertia)
expect_error("--params: symbol mu is neither a parameter nor given a value" planar-friction --params e,m1,I1,r_t1,r_n1,v_t1,v_n1,w_b1,m2,I2,r_t2,r_n2,v_t2,v_n2,w_b2)
expect_error("--set: q: the problem has no symbol q" ball-floor-friction --set q=1)
expect_error("--name: \"1x\" is not a usable C" ball-floor-friction --name 1x)
message(STATUS "codegen with friction: deterministic across processes, mu = 0 smooth, clear refusals")
