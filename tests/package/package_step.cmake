# One step of the package tests, run with cmake -P (see CMakeLists.txt here).
#
#   -DSTEP=install   cmake --install BUILD_DIR into PREFIX (emptied first) and
#                    check that the package files are there
#   -DSTEP=configure configure CONSUMER_SOURCE in CONSUMER_BUILD (emptied first)
#                    against PACKAGE_DIR
#   -DSTEP=consumer  configure CONSUMER_SOURCE in CONSUMER_BUILD (emptied first)
#                    against PACKAGE_DIR and build it; with -DRUN=<programs>
#                    (paths in CONSUMER_BUILD) run them too
#   -DSTEP=configure_fails
#                    configure CONSUMER_SOURCE like STEP=consumer, which must
#                    fail with a message matching EXPECT (a regular expression)
#   -DSTEP=keyword   in the configured CONSUMER_BUILD of tests/package/keywords,
#                    build CASE's program, check the banner line of its header
#                    (cases/CASE.cmake: expected and absent strings, identifiers
#                    the header must name) and run the program
#   -DSTEP=skip_unless_exists
#                    print "SKIPPED: ..." (the test's SKIP_REGULAR_EXPRESSION)
#                    when FILE does not exist, else run STEP=consumer
#
# Any failure is a FATAL_ERROR, so the test fails.
cmake_minimum_required(VERSION 3.25)

function(run)
  string(REPLACE ";" " " shown "${ARGN}")
  message(STATUS "package test: ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "package test: failed (${rc}): ${shown}")
  endif()
endfunction()

# Configure CONSUMER_SOURCE in CONSUMER_BUILD (emptied first) against PACKAGE_DIR
# only: no package registries, and impactgen_DIR pinned so that a system-wide
# install cannot stand in. The result code goes to rc_var; with an output_var,
# stdout and stderr are captured there (and echoed).
function(configure_consumer rc_var output_var)
  file(REMOVE_RECURSE "${CONSUMER_BUILD}")
  set(command "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE}" -B "${CONSUMER_BUILD}" -G "${GENERATOR}"
      "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
      -DCMAKE_BUILD_TYPE=Release
      "-Dimpactgen_DIR=${PACKAGE_DIR}"
      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
      -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF
      "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
      "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}"
      ${CONSUMER_OPTIONS})
  string(REPLACE ";" " " shown "${command}")
  message(STATUS "package test: ${shown}")
  if(output_var)
    execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
    message("${out}")
    set(${output_var} "${out}" PARENT_SCOPE)
  else()
    execute_process(COMMAND ${command} RESULT_VARIABLE rc)
  endif()
  set(${rc_var} "${rc}" PARENT_SCOPE)
endfunction()

if(STEP STREQUAL "skip_unless_exists")
  if(NOT EXISTS "${FILE}")
    message("SKIPPED: ${FILE} does not exist")
    return()
  endif()
  set(STEP consumer)
endif()

if(STEP STREQUAL "install")
  file(REMOVE_RECURSE "${PREFIX}")
  run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}")
  set(expected_adapters "")
  if(EXISTS "${SOURCE_DIR}/adapters/impactgen/eigen.hpp")
    set(expected_adapters include/impactgen/eigen.hpp)
  endif()
  foreach(f bin/impactgen
            lib/cmake/impactgen/impactgenConfig.cmake
            lib/cmake/impactgen/impactgenConfigVersion.cmake
            lib/cmake/impactgen/impactgenTargets.cmake
            lib/cmake/impactgen/impactgenHeadersTargets.cmake
            lib/cmake/impactgen/impactgenGenerate.cmake
            ${expected_adapters}
            include/impactgen/symbolic/problem.hpp
            include/impactgen/print/formulas.hpp
            include/impactgen/numeric/momentum_solver.hpp
            include/impactgen/generated/central_direct.hpp)
    if(NOT EXISTS "${PREFIX}/${f}")
      message(FATAL_ERROR "package test: ${PREFIX}/${f} was not installed")
    endif()
  endforeach()

  # The header-only export set names no other package.
  file(READ "${PREFIX}/lib/cmake/impactgen/impactgenHeadersTargets.cmake" headers_targets)
  foreach(dependency PkgConfig GINAC Eigen3 nlohmann_json CLI11 impactgen::symbolic)
    if(headers_targets MATCHES "${dependency}")
      message(FATAL_ERROR "package test: impactgenHeadersTargets.cmake names ${dependency}")
    endif()
  endforeach()

elseif(STEP STREQUAL "configure" OR STEP STREQUAL "consumer")
  configure_consumer(rc "")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "package test: configuring ${CONSUMER_SOURCE} failed (${rc})")
  endif()
  if(STEP STREQUAL "configure")
    return()
  endif()
  run("${CMAKE_COMMAND}" --build "${CONSUMER_BUILD}" --parallel 2)
  foreach(program IN LISTS RUN)
    run("${CONSUMER_BUILD}/${program}")
  endforeach()

elseif(STEP STREQUAL "configure_fails")
  configure_consumer(rc output)
  if(rc EQUAL 0)
    message(FATAL_ERROR "package test: configuring ${CONSUMER_SOURCE} with ${CONSUMER_OPTIONS} succeeded; "
                        "it must fail with a message matching '${EXPECT}'")
  endif()
  # The message may be wrapped over lines: compare with blanks collapsed.
  string(REGEX REPLACE "[ \t\r\n]+" " " flat "${output}")
  if(NOT flat MATCHES "${EXPECT}")
    message(FATAL_ERROR "package test: configuring failed as it must, but without a message matching '${EXPECT}'")
  endif()
  message(STATUS "package test: failed as expected, with a message matching '${EXPECT}'")

elseif(STEP STREQUAL "keyword")
  set(case_file "${CONSUMER_BUILD}/cases/${CASE}.cmake")
  if(NOT EXISTS "${case_file}")
    message(FATAL_ERROR "package test: ${case_file} does not exist (was the keywords project configured?)")
  endif()
  include("${case_file}")
  run("${CMAKE_COMMAND}" --build "${CONSUMER_BUILD}" --target ${CASE}_use)
  file(STRINGS "${header}" lines LIMIT_COUNT 2)
  list(LENGTH lines count)
  if(count LESS 2)
    message(FATAL_ERROR "package test: ${header} has no banner line")
  endif()
  list(GET lines 1 banner)
  message(STATUS "package test: banner of ${CASE}.hpp: ${banner}")
  if(NOT banner MATCHES "^//   impactgen codegen ")
    message(FATAL_ERROR "package test: the second line of ${header} is not the command line: ${banner}")
  endif()
  set(problems "")
  foreach(text IN LISTS expect)
    string(FIND "${banner} " "${text}" at)
    if(at EQUAL -1)
      list(APPEND problems "the banner lacks '${text}'")
    endif()
  endforeach()
  foreach(text IN LISTS absent)
    string(FIND "${banner}" "${text}" at)
    if(NOT at EQUAL -1)
      list(APPEND problems "the banner has '${text}'")
    endif()
  endforeach()
  file(READ "${header}" content)
  foreach(name IN LISTS defines)
    if(NOT content MATCHES "(^|[^A-Za-z0-9_])${name}([^A-Za-z0-9_]|$)")
      list(APPEND problems "the header does not name ${name}")
    endif()
  endforeach()
  if(problems)
    list(JOIN problems "; " problems)
    message(FATAL_ERROR "package test: ${CASE}.hpp: ${problems}")
  endif()
  run("${program}")

else()
  message(FATAL_ERROR "package test: unknown STEP '${STEP}'")
endif()
