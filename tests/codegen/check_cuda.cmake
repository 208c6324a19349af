# Every header in generated/ compiled by nvcc into __global__ kernels that call its batch form
# (which calls the per-impact function and every helper it needs) for double and for float,
# as included (IMPACTGEN_HOST_DEVICE defaults to __host__ __device__ under nvcc) and with the
# hooks given explicitly (IMPACTGEN_FUNC, IMPACTGEN_MEMBER), every warning an error
# (-Werror all-warnings), for the newest architecture the compiler lists. No GPU is needed.
# -D: NVCC HEADER_DIR WORK
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${NVCC} --list-gpu-arch OUTPUT_VARIABLE arches RESULT_VARIABLE rc)
string(REGEX MATCHALL "compute_[0-9]+" arches "${arches}")
if(NOT rc EQUAL 0 OR NOT arches)
  message(FATAL_ERROR "${NVCC} --list-gpu-arch listed no architecture")
endif()
set(newest 0)
foreach(a IN LISTS arches)
  string(REPLACE "compute_" "" n "${a}")
  if(n GREATER newest)
    set(newest ${n})
  endif()
endforeach()
file(GLOB headers ${HEADER_DIR}/generated/*.hpp)
foreach(header IN LISTS headers)
  get_filename_component(name ${header} NAME_WE)
  file(READ ${header} text)
  if(text MATCHES "friction_status\\* status, int\\* set")
    # a system's batch form: the status and the index of the set of regimes that holds
    set(extra ", impactgen::generated::friction_status* st, int* set")
    set(call "st, set")
  elseif(text MATCHES "friction_status\\* status")
    set(extra ", impactgen::generated::friction_status* st, impactgen::generated::impact_regime* rg")
    set(call "st, rg")
  else()
    set(extra ", impactgen::generated::impact_status* st")
    set(call "st")
  endif()
  file(WRITE ${WORK}/${name}.cu
"#include \"${header}\"
__global__ void kernel_double(long n, const double* const* in, double* const* out${extra})
{
    impactgen::generated::${name}_batch<double>(n, in, out, ${call});
}
__global__ void kernel_float(long n, const float* const* in, float* const* out${extra})
{
    impactgen::generated::${name}_batch<float>(n, in, out, ${call});
}
")
  foreach(hooks "" "-DIMPACTGEN_FUNC=__host__ __device__ inline;-DIMPACTGEN_MEMBER=__host__ __device__")
    execute_process(COMMAND ${NVCC} -std=c++17 -arch=sm_${newest} -Werror all-warnings ${hooks} -c ${WORK}/${name}.cu
                            -o ${WORK}/${name}.o
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${name}: nvcc -arch=sm_${newest} ${hooks} failed:\n${out}${err}")
    endif()
  endforeach()
endforeach()
list(LENGTH headers count)
message(STATUS "${count} headers compiled into device kernels for sm_${newest}")
