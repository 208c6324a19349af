# Benchmark of the headers for restitution followed through the impact (laws_bench.cpp): the
# generated rod-rough-floor for Poisson's and the energetic law (tests/codegen/laws/*.json,
# generated at build time) vs the numeric integration numeric/process_integrator.hpp.
# Included from bench/CMakeLists.txt (after bench_flags is set): include(laws.cmake).
set(laws_dir ${CMAKE_CURRENT_BINARY_DIR}/laws)
set(laws_headers)
foreach(law poisson energetic)
  set(json ${PROJECT_SOURCE_DIR}/tests/codegen/laws/rod-rough-floor-${law}.json)
  add_custom_command(OUTPUT ${laws_dir}/rod_rough_floor_${law}.hpp
    COMMAND $<TARGET_FILE:impactgen> --time-limit 0 codegen ${json} --name rod_rough_floor_${law}
            --output ${laws_dir}/rod_rough_floor_${law}.hpp
    DEPENDS impactgen ${json} VERBATIM)
  list(APPEND laws_headers ${laws_dir}/rod_rough_floor_${law}.hpp)
endforeach()
add_executable(impactgen_laws_bench ${CMAKE_CURRENT_LIST_DIR}/laws_bench.cpp ${laws_headers})
target_include_directories(impactgen_laws_bench PRIVATE ${laws_dir} ${PROJECT_SOURCE_DIR})
target_link_libraries(impactgen_laws_bench PRIVATE impactgen_numeric Eigen3::Eigen benchmark::benchmark)
target_compile_options(impactgen_laws_bench PRIVATE ${bench_flags})
