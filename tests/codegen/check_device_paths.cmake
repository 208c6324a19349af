# Every header in generated/ as a device compiler's device pass sees it (__CUDA_ARCH__ defined,
# IMPACTGEN_HOST_DEVICE then __host__ __device__), without a GPU toolkit: the host
# compiler's preprocessor gives the header's own text for that pass, and none of it may hold a
# host-only call or a long double: std::numeric_limits<...>::f() (constexpr host functions,
# refused by nvcc without --expt-relaxed-constexpr), a compiler builtin (__builtin_ctz), the
# type long double or a long double literal (1.5L). clang's CUDA mode accepts some of these,
# so the text is searched rather than compiled. Fails on a header that has one, naming it.
# -D: CXX HEADER_DIR WORK
file(MAKE_DIRECTORY ${WORK})
file(GLOB headers ${HEADER_DIR}/generated/*.hpp)
list(LENGTH headers count)
if(count LESS 5)
  message(FATAL_ERROR "expected the headers of generated/ in ${HEADER_DIR}/generated, found ${count}")
endif()
set(failures "")
foreach(header IN LISTS headers)
  get_filename_component(name ${header} NAME_WE)
  execute_process(COMMAND ${CXX} -std=c++17 -E -D__CUDA_ARCH__=900 -D__CUDACC__ -D__host__= -D__device__=
                          -x c++ ${header}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE text ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: the preprocessor failed: ${err}")
  endif()
  # Keep the lines that come from the header itself (line markers name the file they follow).
  string(REPLACE ";" "\\;" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  set(own "")
  set(inside FALSE)
  foreach(line IN LISTS lines)
    if(line MATCHES "^# [0-9]+ \"([^\"]*)\"")
      if(CMAKE_MATCH_1 STREQUAL header)
        set(inside TRUE)
      else()
        set(inside FALSE)
      endif()
    elseif(inside)
      string(APPEND own "${line}\n")
    endif()
  endforeach()
  string(LENGTH "${own}" own_length)
  if(own_length LESS 1000)
    message(FATAL_ERROR "${name}: found only ${own_length} characters of the header's own text")
  endif()
  file(WRITE ${WORK}/${name}.device.hpp "${own}")
  foreach(pattern "numeric_limits<[^>]*>::[a-z_]+ *\\(" "__builtin_[a-z_]+" "long double" "[0-9.]L[^A-Za-z0-9_]")
    string(REGEX MATCH "[^\n]*${pattern}[^\n]*" hit "${own}")
    if(hit)
      string(STRIP "${hit}" hit)
      list(APPEND failures "${name}: host-only in its device pass (/${pattern}/): ${hit}")
    endif()
  endforeach()
endforeach()
if(failures)
  string(REPLACE ";" "\n" failures "${failures}")
  message(FATAL_ERROR "${failures}")
endif()
message(STATUS "${count} headers: no host-only call or long double in their device pass")
