# Benchmarks of the system headers (system_bench.cpp): generated (codegen of
# examples/systems/*.json with the bodies' velocities as inputs) vs the numeric LCP reference
# numeric/system_reference.hpp, per example system. Included from bench/CMakeLists.txt.
set(system_bench_dir ${CMAKE_CURRENT_BINARY_DIR}/system)
set(system_bench_headers)
foreach(spec IN ITEMS
    "compass-gait|v_x_stance,v_y_stance,w_z_stance,v_x_swing,v_y_swing,w_z_swing"
    "double-pendulum-struck|v_x_upper,v_y_upper,w_z_upper,v_x_lower,v_y_lower,w_z_lower,v_x_ball,v_y_ball"
    "three-balls-simultaneous|v_xa,v_ya,v_xb,v_yb,v_xc,v_yc"
    "box-four-corners|v_x_box,v_y_box,v_z_box,w_x_box,w_y_box,w_z_box")
  string(REPLACE "|" ";" spec "${spec}")
  list(GET spec 0 stem)
  list(GET spec 1 params)
  string(REPLACE "-" "_" fn ${stem})
  set(json ${PROJECT_SOURCE_DIR}/examples/systems/${stem}.json)
  add_custom_command(OUTPUT ${system_bench_dir}/${fn}.hpp
    COMMAND impactgen --time-limit 0 codegen ${json} --params ${params} --name ${fn} --namespace impactgen::bench_system
            --output ${system_bench_dir}/${fn}.hpp
    DEPENDS impactgen ${json} VERBATIM)
  list(APPEND system_bench_headers ${system_bench_dir}/${fn}.hpp)
endforeach()
add_executable(impactgen_system_bench ${CMAKE_CURRENT_LIST_DIR}/system_bench.cpp ${system_bench_headers})
target_include_directories(impactgen_system_bench PRIVATE ${system_bench_dir})
target_link_libraries(impactgen_system_bench PRIVATE impactgen_numeric Eigen3::Eigen benchmark::benchmark)
target_compile_options(impactgen_system_bench PRIVATE ${bench_flags})
add_custom_target(bench-system-ratios
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/system_ratios.sh $<TARGET_FILE:impactgen_system_bench>
  DEPENDS impactgen_system_bench USES_TERMINAL
  COMMENT "Benchmark: generated system headers vs the LCP reference: ratios")
