// The structure-of-arrays batch loops of planar (masses and inertia as inputs, and the
// engine convention 1/m, 1/I), without and with energy_lost, as out-of-line functions:
// batch_kernels.cpp is compiled once by the project's compiler and once by the other of
// g++ and clang++ (bench/CMakeLists.txt), so that both run in one benchmark process
// with the same harness (batch-gcc/<class>, batch-clang/<class>).
#pragma once

extern "C" {

/// One compiler's build of the kernels.
struct impactgen_bench_kernel_set {
    const char* id;       ///< the compiler family, in the benchmarks' names: gcc, clang
    const char* compiler; ///< e.g. "g++ 12.2.0", "clang++ 14.0.6"
    /// planar_batch<double, false> and <double, true> (tensor inputs), planar_engine_batch
    /// likewise: n impacts, in[j][i] input j of impact i, out[j][i], status[i] (impact_status)
    void (*planar)(long n, const double* const* in, double* const* out, void* status);
    void (*planar_energy)(long n, const double* const* in, double* const* out, void* status);
    void (*planar_engine)(long n, const double* const* in, double* const* out, void* status);
    void (*planar_engine_energy)(long n, const double* const* in, double* const* out, void* status);
};

// Defined by batch_kernels.cpp: built by the project's compiler (main) and by the other
// compiler (-DIMPACTGEN_BENCH_KERNEL_SET=other, only where bench/CMakeLists.txt found one:
// then IMPACTGEN_BENCH_OTHER_KERNELS is defined for the benchmark).
const impactgen_bench_kernel_set* impactgen_bench_kernels_main();
const impactgen_bench_kernel_set* impactgen_bench_kernels_other();
}
