// The batch loops of planar and planar-engine behind plain function pointers, one set per
// compiler (see batch_kernels.hpp). Built with -DIMPACTGEN_BENCH_KERNEL_SET=main (the
// project's compiler) or =other (the second compiler); the same flags as the benchmark
// (-O3 -DNDEBUG, -march=native unless turned off).
#include "batch_kernels.hpp"

#include "planar.hpp"
#include "planar_engine.hpp"

#ifndef IMPACTGEN_BENCH_KERNEL_SET
#error "define IMPACTGEN_BENCH_KERNEL_SET (main or other): which set of kernels this build is"
#endif
#define IMPACTGEN_BENCH_CAT2(a, b) a##b
#define IMPACTGEN_BENCH_CAT(a, b) IMPACTGEN_BENCH_CAT2(a, b)

namespace {

namespace gen = impactgen::generated;

template <bool energy> void planar(long n, const double* const* in, double* const* out, void* status)
{
    gen::planar_batch<double, energy>(n, in, out, static_cast<gen::impact_status*>(status));
}

template <bool energy> void planar_engine(long n, const double* const* in, double* const* out, void* status)
{
    gen::planar_engine_batch<double, energy>(n, in, out, static_cast<gen::impact_status*>(status));
}

#if defined(__clang__)
constexpr const char* id = "clang";
constexpr const char* compiler = "clang++ " __clang_version__;
#elif defined(__GNUC__)
constexpr const char* id = "gcc";
constexpr const char* compiler = "g++ " __VERSION__;
#else
constexpr const char* id = "other";
constexpr const char* compiler = "unknown compiler";
#endif

const impactgen_bench_kernel_set kernels{id, compiler, planar<false>, planar<true>, planar_engine<false>, planar_engine<true>};

} // namespace

extern "C" const impactgen_bench_kernel_set* IMPACTGEN_BENCH_CAT(impactgen_bench_kernels_, IMPACTGEN_BENCH_KERNEL_SET)()
{
    return &kernels;
}
