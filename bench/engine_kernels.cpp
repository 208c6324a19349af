// Per-call kernels of the engine comparison (see engine_kernels.hpp). Built with
// -DIMPACTGEN_BENCH_KERNEL_SET=main or =other like batch_kernels.cpp, with the same flags.
#include "engine_kernels.hpp"

#include "noncentral_3d_engine.hpp"
#include "planar_engine.hpp"

#ifndef IMPACTGEN_BENCH_KERNEL_SET
#error "define IMPACTGEN_BENCH_KERNEL_SET (main or other): which set of kernels this build is"
#endif
#define IMPACTGEN_BENCH_CAT2(a, b) a##b
#define IMPACTGEN_BENCH_CAT(a, b) IMPACTGEN_BENCH_CAT2(a, b)

namespace {

namespace gen = impactgen::generated;

// The compiler may not keep *r in registers across calls nor merge iterations (what
// benchmark::DoNotOptimize does in the other per-call benchmarks).
template <typename R> inline void fence(R& r) { asm volatile("" : : "r"(&r) : "memory"); }

// Hand-written engine formula, planar, inverse mass and inertia given, normal n = (0, 1)
// in the contact frame (t, n) as a constant, contact point at the origin: the same
// specialisation as planar_engine. r = O - C, rn = r x n, k = 1/m1 + 1/m2 + rn1^2/I1 + rn2^2/I2.
inline double hand_planar(const double* x, gen::planar_engine_result<double>& o)
{
    constexpr double nx = 0, ny = 1;
    const double e = x[0], im1 = x[1], iI1 = x[2], im2 = x[8], iI2 = x[9];
    const double r1x = -x[3], r1y = -x[4], r2x = -x[10], r2y = -x[11];
    const double rn1 = r1x * ny - r1y * nx, rn2 = r2x * ny - r2y * nx;
    const double k = im1 + im2 + rn1 * rn1 * iI1 + rn2 * rn2 * iI2;
    const double vAx = x[5] - x[7] * r1y, vAy = x[6] + x[7] * r1x;
    const double vBx = x[12] - x[14] * r2y, vBy = x[13] + x[14] * r2x;
    const double vn = (vBx - vAx) * nx + (vBy - vAy) * ny;
    if (!(vn < 0) || !(k > 0))
        return 0;
    const double P = -(1 + e) * vn / k;
    o.v_t1 = x[5] - P * im1 * nx;
    o.v_n1 = x[6] - P * im1 * ny;
    o.w_b1 = x[7] - P * rn1 * iI1;
    o.v_t2 = x[12] + P * im2 * nx;
    o.v_n2 = x[13] + P * im2 * ny;
    o.w_b2 = x[14] + P * rn2 * iI2;
    o.normal_impulse = P;
    o.approach_velocity = vn;
    o.energy_lost = 0;
    return P;
}

struct v3 {
    double x, y, z;
};
inline v3 cross(v3 a, v3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
// I^{-1} given by its 6 entries tt, tn, tb, nn, nb, bb (symmetric)
inline v3 mul_sym(const double* I, v3 a)
{
    return {I[0] * a.x + I[1] * a.y + I[2] * a.z, I[1] * a.x + I[3] * a.y + I[4] * a.z, I[2] * a.x + I[4] * a.y + I[5] * a.z};
}

// Hand-written engine formula, 3-D, two free bodies, inverse mass and inverse inertia tensor
// given, n = (0, 1, 0) in the contact frame (t, n, b) as a constant, contact point at the
// origin: the same specialisation as noncentral_3d_engine.
// layout: e, inv_m1, inv_I1(6), r1(3), v1(3), w1(3), inv_m2, inv_I2(6), r2(3), v2(3), w2(3)
inline double hand_noncentral(const double* x, gen::noncentral_3d_engine_result<double>& o)
{
    constexpr v3 n{0, 1, 0};
    const double e = x[0], im1 = x[1], im2 = x[17];
    const v3 r1{-x[8], -x[9], -x[10]}, r2{-x[24], -x[25], -x[26]}; // O - C
    const v3 v1{x[11], x[12], x[13]}, w1{x[14], x[15], x[16]};
    const v3 v2{x[27], x[28], x[29]}, w2{x[30], x[31], x[32]};
    const v3 rn1 = cross(r1, n), rn2 = cross(r2, n);
    const v3 g1 = mul_sym(x + 2, rn1), g2 = mul_sym(x + 18, rn2);
    const double k = im1 + im2 + dot(rn1, g1) + dot(rn2, g2);
    const v3 a = cross(w1, r1), b = cross(w2, r2);
    const double vn = (v2.x + b.x - v1.x - a.x) * n.x + (v2.y + b.y - v1.y - a.y) * n.y + (v2.z + b.z - v1.z - a.z) * n.z;
    if (!(vn < 0) || !(k > 0))
        return 0;
    const double P = -(1 + e) * vn / k;
    const double p1 = P * im1, p2 = P * im2;
    o.v_t1 = v1.x - p1 * n.x;
    o.v_n1 = v1.y - p1 * n.y;
    o.v_b1 = v1.z - p1 * n.z;
    o.w_t1 = w1.x - P * g1.x;
    o.w_n1 = w1.y - P * g1.y;
    o.w_b1 = w1.z - P * g1.z;
    o.v_t2 = v2.x + p2 * n.x;
    o.v_n2 = v2.y + p2 * n.y;
    o.v_b2 = v2.z + p2 * n.z;
    o.w_t2 = w2.x + P * g2.x;
    o.w_n2 = w2.y + P * g2.y;
    o.w_b2 = w2.z + P * g2.z;
    o.normal_impulse = P;
    o.approach_velocity = vn;
    o.energy_lost = 0;
    return P;
}

template <typename R, typename F> inline void loop(long n, const double* in, long stride, void* out, double* impulses, F f)
{
    R& r = *static_cast<R*>(out);
    for (long i = 0; i < n; ++i) {
        f(in + i * stride, r);
        fence(r);
        if (impulses)
            impulses[i] = r.normal_impulse;
    }
}

using PR = gen::planar_engine_result<double>;
using NR = gen::noncentral_3d_engine_result<double>;

void planar_checked(long n, const double* in, long s, void* out, double* p)
{
    loop<PR>(n, in, s, out, p, [](const double* x, PR& r) { gen::planar_engine<double, false>(x, r); });
}
void planar_unchecked(long n, const double* in, long s, void* out, double* p)
{
    loop<PR>(n, in, s, out, p, [](const double* x, PR& r) {
        gen::planar_engine_unchecked<double, false>(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8], x[9], x[10],
                                                    x[11], x[12], x[13], x[14], r);
    });
}
void planar_hand(long n, const double* in, long s, void* out, double* p)
{
    loop<PR>(n, in, s, out, p, [](const double* x, PR& r) { hand_planar(x, r); });
}
void noncentral_checked(long n, const double* in, long s, void* out, double* p)
{
    loop<NR>(n, in, s, out, p, [](const double* x, NR& r) { gen::noncentral_3d_engine<double, false>(x, r); });
}
void noncentral_unchecked(long n, const double* in, long s, void* out, double* p)
{
    loop<NR>(n, in, s, out, p, [](const double* x, NR& r) {
        gen::noncentral_3d_engine_unchecked<double, false>(
            x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8], x[9], x[10], x[11], x[12], x[13], x[14], x[15], x[16],
            x[17], x[18], x[19], x[20], x[21], x[22], x[23], x[24], x[25], x[26], x[27], x[28], x[29], x[30], x[31], x[32], r);
    });
}
void noncentral_hand(long n, const double* in, long s, void* out, double* p)
{
    loop<NR>(n, in, s, out, p, [](const double* x, NR& r) { hand_noncentral(x, r); });
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

const impactgen_engine_kernel_set kernels{id, compiler, planar_checked, planar_unchecked, planar_hand,
                                          noncentral_checked, noncentral_unchecked, noncentral_hand};

} // namespace

extern "C" const impactgen_engine_kernel_set* IMPACTGEN_BENCH_CAT(impactgen_engine_kernels_, IMPACTGEN_BENCH_KERNEL_SET)()
{
    return &kernels;
}
