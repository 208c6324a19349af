# Benchmarks of the headers with Coulomb friction (friction_bench.cpp): generated vs the
# Eigen reference numeric/friction_solver.hpp per named friction class, and the batch form.
# Included from bench/CMakeLists.txt (after bench_flags is set): include(friction.cmake).
add_executable(impactgen_friction_bench ${CMAKE_CURRENT_LIST_DIR}/friction_bench.cpp)
target_include_directories(impactgen_friction_bench PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../generated)
target_link_libraries(impactgen_friction_bench PRIVATE impactgen_numeric_prebuilt Eigen3::Eigen benchmark::benchmark)
target_compile_options(impactgen_friction_bench PRIVATE ${bench_flags})
add_custom_target(bench-friction-ratios
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/friction_ratios.sh $<TARGET_FILE:impactgen_friction_bench>
  DEPENDS impactgen_friction_bench USES_TERMINAL
  COMMENT "Benchmark: generated headers with friction vs the Eigen reference: ratios")
