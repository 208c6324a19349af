# One step of the package tests, run with cmake -P (see CMakeLists.txt here).
#
#   -DSTEP=install   cmake --install BUILD_DIR into PREFIX (emptied first) and
#                    check that the package files are there
#   -DSTEP=consumer  configure CONSUMER_SOURCE in CONSUMER_BUILD (emptied first)
#                    against PACKAGE_DIR and build it
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

if(STEP STREQUAL "install")
  file(REMOVE_RECURSE "${PREFIX}")
  run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}")
  foreach(f bin/impactgen
            lib/cmake/impactgen/impactgenConfig.cmake
            lib/cmake/impactgen/impactgenConfigVersion.cmake
            lib/cmake/impactgen/impactgenTargets.cmake
            lib/cmake/impactgen/impactgenGenerate.cmake
            include/impactgen/symbolic/problem.hpp
            include/impactgen/print/formulas.hpp
            include/impactgen/numeric/momentum_solver.hpp
            include/impactgen/generated/central_direct.hpp)
    if(NOT EXISTS "${PREFIX}/${f}")
      message(FATAL_ERROR "package test: ${PREFIX}/${f} was not installed")
    endif()
  endforeach()

elseif(STEP STREQUAL "consumer")
  file(REMOVE_RECURSE "${CONSUMER_BUILD}")
  # Only PACKAGE_DIR may provide impactgen: no package registries, and
  # impactgen_DIR pinned so that a system-wide install cannot stand in.
  run("${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE}" -B "${CONSUMER_BUILD}" -G "${GENERATOR}"
      "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
      -DCMAKE_BUILD_TYPE=Release
      "-Dimpactgen_DIR=${PACKAGE_DIR}"
      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
      -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF
      "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
      "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}"
      ${CONSUMER_OPTIONS})
  run("${CMAKE_COMMAND}" --build "${CONSUMER_BUILD}" --parallel 2)

else()
  message(FATAL_ERROR "package test: unknown STEP '${STEP}'")
endif()
