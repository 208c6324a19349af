// Per named class, on the same 4096 random impacts (seeded):
//   generated/<class>    the generated function (inputs as the class names them:
//                        masses and inertia tensors), with_energy_lost = false: the
//                        outputs Eigen and the hand-written formulas compute (post-impact
//                        velocities, impulse; approach velocity too), status and checks
//   generated+energy/<class>  the same with the default with_energy_lost = true (all outputs)
//   eigen/<class>        numeric::solve_momentum_system, PartialPivLU, assembly included
//   handwritten/<class>  an engine-style impulse formula: effective mass from the
//                        inverse inertia, P = -(1+e) v_n / k, then the velocity jumps;
//                        same inputs as generated/<class> (it inverts the tensors itself)
//   batch/<class>        the generated SoA batch form over arrays of 1024 impacts (fits L2;
//                        every array 64-byte aligned), with_energy_lost = false like
//                        generated/<class>: every other output and the status written
//   batch+energy/<class> the same with energy_lost computed and written too
// and the engine input convention (1/m and I^{-1} given, as physics engines store them):
//   <kind>/noncentral-3d-engine and <kind>/planar-engine, generated and hand-written on the
//   same inputs.
// Also (jacobian_bench.cpp) jacobian/<class> and autodiff/<class> for noncentral-3d,
// noncentral-3d-engine and planar: the generated Jacobian against forward-mode autodiff of
// the generated function, checked to agree before they run; and (batch_kernels.cpp)
// batch-<compiler>/planar[-engine] and batch+energy-<compiler>/planar[-engine]: the batch
// loop built out of line by the project's compiler and by the other of g++ and clang++.
// Counters: ns_per_impact; the operation counts of each generated function are
// printed first (from the constexpr <name>_ops of its header).
#include "central_direct.hpp"
#include "central_oblique.hpp"
#include "massive_3d.hpp"
#include "noncentral_3d.hpp"
#include "noncentral_3d_engine.hpp"
#include "pinned_planar.hpp"
#include "planar.hpp"
#include "planar_engine.hpp"
#include "numeric/momentum_solver.hpp"

#include "batch_kernels.hpp"
#include "jacobian_bench.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace gen = impactgen::generated;
namespace nm = impactgen::numeric;
using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

namespace {

constexpr int kImpacts = 4096;
constexpr int kBatch = 1024;

// ---------------------------------------------------------------------------
// Random valid impacts, described by input name.
struct input_set {
    int n_in = 0;
    std::vector<std::string> names;
    std::vector<std::vector<double>> rows; // rows[i][j]: input j of impact i
    double at(int i, const std::string& name) const
    {
        for (int j = 0; j < n_in; ++j)
            if (names[static_cast<std::size_t>(j)] == name)
                return rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
        return 0;
    }
};

template <typename Result, typename F>
input_set make_inputs(const char* const* names, int n_in, F fn, unsigned seed, bool inverse = false)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0, 1);
    input_set s;
    s.n_in = n_in;
    for (int j = 0; j < n_in; ++j)
        s.names.push_back(names[j]);
    auto idx = [&](const std::string& nm_) {
        for (int j = 0; j < n_in; ++j)
            if (s.names[static_cast<std::size_t>(j)] == nm_)
                return j;
        return -1;
    };
    while (static_cast<int>(s.rows.size()) < kImpacts) {
        std::vector<double> x(static_cast<std::size_t>(n_in));
        std::map<std::string, double> mass;
        for (int j = 0; j < n_in; ++j) {
            const std::string& n = s.names[static_cast<std::size_t>(j)];
            double v = 2 * U(rng) - 1;
            if (n == "e")
                v = U(rng);
            else if (n == "l" || n == "R1" || n == "R2")
                v = 0.2 + U(rng);
            x[static_cast<std::size_t>(j)] = v;
        }
        for (const char* b : {"1", "2"}) {
            double m = std::pow(10.0, -3 + 6 * U(rng));
            int jm = idx(std::string("m") + b), jim = idx(std::string("inv_m") + b);
            if (jm >= 0)
                x[static_cast<std::size_t>(jm)] = m;
            if (jim >= 0)
                x[static_cast<std::size_t>(jim)] = 1 / m;
            int jI = idx(std::string("I") + b), jiI = idx(std::string("inv_I") + b);
            if (jI >= 0)
                x[static_cast<std::size_t>(jI)] = m * (0.05 + U(rng));
            if (jiI >= 0) // planar, engine convention: 1/I
                x[static_cast<std::size_t>(jiI)] = 1 / (m * (0.05 + U(rng)));
            // 3-D tensors: m * (diagonally dominant symmetric)
            const char* ax = "tnb";
            M3 I = M3::Zero();
            for (int r = 0; r < 3; ++r)
                for (int c = r; c < 3; ++c)
                    I(r, c) = I(c, r) = m * (r == c ? 0.5 + 0.5 * U(rng) : 0.1 * (2 * U(rng) - 1));
            M3 K = I.inverse();
            for (int r = 0; r < 3; ++r)
                for (int c = r; c < 3; ++c) {
                    std::string e = std::string(b) + "_" + ax[r] + ax[c];
                    int j = idx("I" + e), ji = idx("inv_I" + e);
                    if (j >= 0)
                        x[static_cast<std::size_t>(j)] = I(r, c);
                    if (ji >= 0)
                        x[static_cast<std::size_t>(ji)] = K(r, c);
                }
        }
        Result r;
        if (fn(x.data(), r) != gen::impact_status::ok) {
            for (int j = 0; j < n_in; ++j)
                if (s.names[static_cast<std::size_t>(j)][0] == 'v' || s.names[static_cast<std::size_t>(j)][0] == 'w')
                    x[static_cast<std::size_t>(j)] = -x[static_cast<std::size_t>(j)];
            if (fn(x.data(), r) != gen::impact_status::ok)
                continue;
        }
        s.rows.push_back(x);
    }
    (void)inverse;
    return s;
}

// ---------------------------------------------------------------------------
// Eigen problems from the same inputs (class structure as in symbolic/named_classes.cpp).
nm::problem<double> eigen_problem(const std::string& cls, const input_set& s, int i)
{
    auto v = [&](const std::string& n) { return s.at(i, n); };
    nm::problem<double> p;
    p.point.setZero();
    p.normal = V3(0, 1, 0);
    p.restitution = v("e");
    const char* ax = "tnb";
    for (const char* b : {"1", "2"}) {
        nm::body<double> bd;
        std::string k = b;
        bd.mass = v("m" + k);
        for (int c = 0; c < 3; ++c) {
            bd.position[c] = v(std::string("r_") + ax[c] + k);
            bd.velocity[c] = v(std::string("v_") + ax[c] + k);
            bd.angular_velocity[c] = v(std::string("w_") + ax[c] + k);
        }
        if (cls == "planar") {
            bd.particle = false;
            bd.inertia(2, 2) = v("I" + k);
            bd.angular_velocity = V3(0, 0, v("w_b" + k));
            bd.position[2] = bd.velocity[2] = 0;
        } else if (cls == "noncentral-3d" || (cls == "massive-3d" && k == "1")) {
            bd.particle = false;
            for (int r = 0; r < 3; ++r)
                for (int c = r; c < 3; ++c)
                    bd.inertia(r, c) = bd.inertia(c, r) = v("I" + k + "_" + ax[r] + ax[c]);
        }
        if (cls == "central-direct" || cls == "central-oblique")
            bd.position = V3(0, k == "1" ? -v("R1") : v("R2"), 0);
        if (cls == "massive-3d" && k == "2") {
            bd.infinite_mass = true;
            bd.mass = 0;
        }
        p.bodies.push_back(bd);
    }
    p.dimension = cls == "planar" || cls == "central-direct" || cls == "pinned-planar" ? 2 : 3;
    if (cls == "pinned-planar") {
        const double l = v("l"), m1 = v("m1"), m2 = v("m2");
        p.normal = V3(1, 0, 0);
        p.point = V3(0, -l, 0);
        p.bodies[0] = nm::body<double>{};
        p.bodies[0].mass = m1;
        p.bodies[0].position = V3(0, -l, 0);
        p.bodies[0].velocity = V3(v("v1"), 0, 0);
        p.bodies[1] = nm::body<double>{};
        p.bodies[1].mass = m2;
        p.bodies[1].particle = false;
        p.bodies[1].inertia(2, 2) = m2 * l * l / 12;
        p.bodies[1].position = V3(0, -l / 2, 0);
        p.pivots.push_back({1, V3::Zero()});
    }
    return p;
}

// ---------------------------------------------------------------------------
// Hand-written impulse formulas of the kind physics engines use.
struct body3 {
    double inv_m;
    M3 inv_I;
    V3 c, v, w;
};

inline M3 inverse_sym(const M3& I)
{
    // adjugate / determinant of a symmetric 3x3 (6 cofactors)
    const double a = I(0, 0), b = I(0, 1), c = I(0, 2), d = I(1, 1), e = I(1, 2), f = I(2, 2);
    const double A = d * f - e * e, B = c * e - b * f, C = b * e - c * d;
    const double inv_det = 1 / (a * A + b * B + c * C);
    M3 K;
    K << A, B, C, B, a * f - c * c, b * c - a * e, C, b * c - a * e, a * d - b * b;
    return K * inv_det;
}

// Two free rigid bodies, contact point p, unit normal n from body 1 into body 2.
inline double impulse3(body3& b1, body3& b2, const V3& p, const V3& n, double e)
{
    const V3 r1 = p - b1.c, r2 = p - b2.c;
    const V3 rn1 = r1.cross(n), rn2 = r2.cross(n);
    const V3 g1 = b1.inv_I * rn1, g2 = b2.inv_I * rn2;
    const double k = b1.inv_m + b2.inv_m + rn1.dot(g1) + rn2.dot(g2);
    const double vn = (b2.v + b2.w.cross(r2) - b1.v - b1.w.cross(r1)).dot(n);
    if (!(vn < 0) || !(k > 0))
        return 0;
    const double P = -(1 + e) * vn / k;
    b1.v -= (P * b1.inv_m) * n;
    b1.w -= P * g1;
    b2.v += (P * b2.inv_m) * n;
    b2.w += P * g2;
    return P;
}

body3 load3(const double* x, int off_m, int off_I, int off_r, bool inverse)
{
    body3 b;
    b.inv_m = inverse ? x[off_m] : 1 / x[off_m];
    M3 I;
    I << x[off_I], x[off_I + 1], x[off_I + 2], x[off_I + 1], x[off_I + 3], x[off_I + 4], x[off_I + 2], x[off_I + 4], x[off_I + 5];
    b.inv_I = inverse ? I : inverse_sym(I);
    b.c = V3(x[off_r], x[off_r + 1], x[off_r + 2]);
    b.v = V3(x[off_r + 3], x[off_r + 4], x[off_r + 5]);
    b.w = V3(x[off_r + 6], x[off_r + 7], x[off_r + 8]);
    return b;
}

struct hand_out {
    double s[13];
};

// noncentral-3d layout: e, m1, I1(6), r1(3), v1(3), w1(3), m2, I2(6), r2(3), v2(3), w2(3)
inline double hand_noncentral(const double* x, bool inverse, hand_out& o)
{
    body3 b1 = load3(x, 1, 2, 8, inverse), b2 = load3(x, 17, 18, 24, inverse);
    const double P = impulse3(b1, b2, V3::Zero(), V3(0, 1, 0), x[0]);
    for (int c = 0; c < 3; ++c) {
        o.s[c] = b1.v[c];
        o.s[3 + c] = b1.w[c];
        o.s[6 + c] = b2.v[c];
        o.s[9 + c] = b2.w[c];
    }
    o.s[12] = P;
    return P;
}

// massive-3d layout: e, m1, I1(6), r1(3), v1(3), w1(3), r2(3), v2(3), w2(3): body 2 has infinite mass.
inline double hand_massive(const double* x, hand_out& o)
{
    body3 b1 = load3(x, 1, 2, 8, false);
    body3 b2;
    b2.inv_m = 0;
    b2.inv_I.setZero();
    b2.c = V3(x[17], x[18], x[19]);
    b2.v = V3(x[20], x[21], x[22]);
    b2.w = V3(x[23], x[24], x[25]);
    const double P = impulse3(b1, b2, V3::Zero(), V3(0, 1, 0), x[0]);
    for (int c = 0; c < 3; ++c) {
        o.s[c] = b1.v[c];
        o.s[3 + c] = b1.w[c];
    }
    o.s[12] = P;
    return P;
}

// The small classes' hand-written formulas write the generated function's own result
// struct, every field it writes (velocities, impulses, approach velocity; energy_lost 0
// like generated/<class>, which runs with_energy_lost = false), so that the harness is
// the same and only the function differs. (Writing a different struct changed the
// time of identical arithmetic by up to 1.45x here: the compiler pairs adjacent stores.)

// planar layout: e, m1, I1, r_t1, r_n1, v_t1, v_n1, w_b1, m2, I2, r_t2, r_n2, v_t2, v_n2, w_b2
// (inverse: inv_m1, inv_I1, ..., inv_m2, inv_I2 in place of m1, I1, m2, I2: engine convention)
template <bool inverse, typename R> inline double hand_planar(const double* x, R& o)
{
    const double nx = 0, ny = 1, e = x[0];
    const double im1 = inverse ? x[1] : 1 / x[1], iI1 = inverse ? x[2] : 1 / x[2];
    const double im2 = inverse ? x[8] : 1 / x[8], iI2 = inverse ? x[9] : 1 / x[9];
    const double r1x = -x[3], r1y = -x[4], r2x = -x[10], r2y = -x[11]; // O - C
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

// central-direct layout: e, m1, R1, v_n1, m2, R2, v_n2 (names looked up once)
inline double hand_central_direct(double e, double m1, double v1, double m2, double v2, gen::central_direct_result<double>& o)
{
    const double im1 = 1 / m1, im2 = 1 / m2, u = v2 - v1;
    if (!(u < 0))
        return 0;
    const double P = -(1 + e) * u / (im1 + im2);
    o.v_t1 = 0;
    o.v_n1 = v1 - P * im1;
    o.v_t2 = 0;
    o.v_n2 = v2 + P * im2;
    o.normal_impulse = P;
    o.approach_velocity = u;
    o.energy_lost = 0;
    return P;
}

// central-oblique: two particles, general normal n (here e_n)
inline double hand_central_oblique(double e, double m1, const V3& v1, double m2, const V3& v2, gen::central_oblique_result<double>& o)
{
    const V3 n(0, 1, 0);
    const double im1 = 1 / m1, im2 = 1 / m2, u = (v2 - v1).dot(n);
    if (!(u < 0))
        return 0;
    const double P = -(1 + e) * u / (im1 + im2);
    const V3 a = v1 - (P * im1) * n, b = v2 + (P * im2) * n;
    o.v_t1 = a[0];
    o.v_n1 = a[1];
    o.v_b1 = a[2];
    o.v_t2 = b[0];
    o.v_n2 = b[1];
    o.v_b2 = b[2];
    o.normal_impulse = P;
    o.approach_velocity = u;
    o.energy_lost = 0;
    return P;
}

// pinned-planar: ball (m1, speed v1) strikes the end of a rod (m2, l) hinged at the top.
inline double hand_pinned(double e, double l, double m1, double m2, double v1, gen::pinned_planar_result<double>& o)
{
    const double IE = m2 * l * l / 3, im1 = 1 / m1, iIE = 1 / IE;
    const double k = im1 + l * l * iIE, u = -v1;
    if (!(u < 0))
        return 0;
    const double P = -(1 + e) * u / k;
    const double w = P * l * iIE;
    o.v_x1 = v1 - P * im1;
    o.v_y1 = 0;
    o.w_z2 = w;               // w_z of the rod
    o.v_x2 = w * l / 2;       // v_x of its centre
    o.v_y2 = 0;
    o.normal_impulse = P;
    o.R_x2 = m2 * o.v_x2 - P; // pivot impulse, x
    o.R_y2 = 0;
    o.approach_velocity = u;
    o.energy_lost = 0;
    return P;
}

// ---------------------------------------------------------------------------
// A 64-byte aligned array of doubles (one cache line; any vector width), for the SoA batch.
struct aligned_array {
    struct free_it {
        void operator()(double* p) const { std::free(p); }
    };
    std::unique_ptr<double[], free_it> p;
    explicit aligned_array(std::size_t n)
        : p(static_cast<double*>(std::aligned_alloc(64, (n * sizeof(double) + 63) / 64 * 64)))
    {
        for (std::size_t i = 0; i < n; ++i)
            p[i] = 0;
    }
    double* data() { return p.get(); }
    double& operator[](std::size_t i) { return p[i]; }
};

struct class_data {
    input_set in;
    std::vector<nm::problem<double>> eigen;
    std::vector<aligned_array> soa_in, soa_out; // batch: [input][i], each array 64-byte aligned
};

template <typename Result, typename F>
class_data prepare(const std::string& cls, const char* const* names, int n_in, int n_out, F fn, unsigned seed)
{
    class_data d;
    d.in = make_inputs<Result>(names, n_in, fn, seed);
    if (cls.find("engine") == std::string::npos)
        for (int i = 0; i < kImpacts; ++i)
            d.eigen.push_back(eigen_problem(cls, d.in, i));
    for (int j = 0; j < n_in; ++j)
        d.soa_in.emplace_back(kBatch);
    for (int j = 0; j < n_out; ++j)
        d.soa_out.emplace_back(kBatch);
    for (int j = 0; j < n_in; ++j)
        for (int i = 0; i < kBatch; ++i)
            d.soa_in[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] = d.in.rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
    return d;
}

void per_impact(benchmark::State& state, long impacts)
{
    state.counters["ns_per_impact"] =
        benchmark::Counter(static_cast<double>(impacts), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.SetItemsProcessed(state.iterations() * impacts);
}

#define REGISTER_CLASS(CLS, FN)                                                                                       \
    {                                                                                                                 \
        static class_data d = prepare<gen::FN##_result<double>>(                                                      \
            CLS, gen::FN##_input_names, gen::FN##_input_count, gen::FN##_output_count,                                \
            [](const double* x, gen::FN##_result<double>& r) { return gen::FN(x, r); }, 12345);                       \
        std::printf("%-22s generated: %3d add/sub, %3d mul, %2d div, %d sqrt per impact\n", CLS, gen::FN##_ops.add,   \
                    gen::FN##_ops.mul, gen::FN##_ops.div, gen::FN##_ops.sqrt);                                        \
        benchmark::RegisterBenchmark("generated/" CLS, [](benchmark::State& st) {                                     \
            gen::FN##_result<double> r;                                                                               \
            for (auto _ : st)                                                                                         \
                for (int i = 0; i < kImpacts; ++i) {                                                                  \
                    benchmark::DoNotOptimize(gen::FN<double, false>(d.in.rows[static_cast<std::size_t>(i)].data(), r)); \
                    benchmark::DoNotOptimize(r);                                                                      \
                }                                                                                                     \
            per_impact(st, kImpacts);                                                                                 \
        });                                                                                                           \
        benchmark::RegisterBenchmark("generated+energy/" CLS, [](benchmark::State& st) {                              \
            gen::FN##_result<double> r;                                                                               \
            for (auto _ : st)                                                                                         \
                for (int i = 0; i < kImpacts; ++i) {                                                                  \
                    benchmark::DoNotOptimize(gen::FN(d.in.rows[static_cast<std::size_t>(i)].data(), r));              \
                    benchmark::DoNotOptimize(r);                                                                      \
                }                                                                                                     \
            per_impact(st, kImpacts);                                                                                 \
        });                                                                                                           \
        if (!d.eigen.empty())                                                                                         \
            benchmark::RegisterBenchmark("eigen/" CLS, [](benchmark::State& st) {                                     \
                for (auto _ : st)                                                                                     \
                    for (int i = 0; i < kImpacts; ++i) {                                                              \
                        auto a = nm::solve_momentum_system(d.eigen[static_cast<std::size_t>(i)]);                     \
                        benchmark::DoNotOptimize(a);                                                                  \
                    }                                                                                                 \
                per_impact(st, kImpacts);                                                                             \
            });                                                                                                       \
        benchmark::RegisterBenchmark("batch/" CLS, [](benchmark::State& st) {                                         \
            std::vector<const double*> in;                                                                            \
            std::vector<double*> out;                                                                                 \
            for (auto& a : d.soa_in)                                                                                  \
                in.push_back(a.data());                                                                               \
            for (auto& a : d.soa_out)                                                                                 \
                out.push_back(a.data());                                                                              \
            aligned_array status_mem(kBatch); /* 64-byte aligned; 8 bytes per impact >= sizeof(impact_status) */     \
            auto* status = reinterpret_cast<gen::impact_status*>(status_mem.data());                                  \
            for (auto _ : st) {                                                                                       \
                gen::FN##_batch<double, false>(kBatch, in.data(), out.data(), status);                                \
                benchmark::ClobberMemory();                                                                           \
            }                                                                                                         \
            per_impact(st, kBatch);                                                                                   \
        });                                                                                                           \
        benchmark::RegisterBenchmark("batch+energy/" CLS, [](benchmark::State& st) {                                         \
            std::vector<const double*> in;                                                                            \
            std::vector<double*> out;                                                                                 \
            for (auto& a : d.soa_in)                                                                                  \
                in.push_back(a.data());                                                                               \
            for (auto& a : d.soa_out)                                                                                 \
                out.push_back(a.data());                                                                              \
            aligned_array status_mem(kBatch); /* 64-byte aligned; 8 bytes per impact >= sizeof(impact_status) */     \
            auto* status = reinterpret_cast<gen::impact_status*>(status_mem.data());                                  \
            for (auto _ : st) {                                                                                       \
                gen::FN##_batch(kBatch, in.data(), out.data(), status);                                               \
                benchmark::ClobberMemory();                                                                           \
            }                                                                                                         \
            per_impact(st, kBatch);                                                                                   \
        });                                                                                                           \
        hand = &d;                                                                                                    \
    }

class_data* hand = nullptr;

template <typename Out = hand_out, typename F> void register_hand(const std::string& name, class_data* d, F f)
{
    benchmark::RegisterBenchmark(name.c_str(), [d, f](benchmark::State& st) {
        Out o{};
        for (auto _ : st)
            for (int i = 0; i < kImpacts; ++i) {
                benchmark::DoNotOptimize(f(d->in.rows[static_cast<std::size_t>(i)].data(), o));
                benchmark::DoNotOptimize(o);
            }
        per_impact(st, kImpacts);
    });
}

// batch-<compiler>/<class> and batch+energy-<compiler>/<class>: one compiler's out-of-line
// build of the batch loop (batch_kernels.cpp), on the arrays of batch/<class>.
void register_kernel(const std::string& name, class_data* d, void (*kernel)(long, const double* const*, double* const*, void*))
{
    benchmark::RegisterBenchmark(name.c_str(), [d, kernel](benchmark::State& st) {
        std::vector<const double*> in;
        std::vector<double*> out;
        for (auto& a : d->soa_in)
            in.push_back(a.data());
        for (auto& a : d->soa_out)
            out.push_back(a.data());
        aligned_array status_mem(kBatch); // 8 bytes per impact >= sizeof(impact_status)
        for (auto _ : st) {
            kernel(kBatch, in.data(), out.data(), status_mem.data());
            benchmark::ClobberMemory();
        }
        per_impact(st, kBatch);
    });
}

void register_kernels(const impactgen_bench_kernel_set* k, class_data* planar, class_data* planar_engine)
{
    const std::string id = k->id;
    std::printf("%-22s batch-%s: %s\n", "batch planar", k->id, k->compiler);
    register_kernel("batch-" + id + "/planar", planar, k->planar);
    register_kernel("batch+energy-" + id + "/planar", planar, k->planar_energy);
    register_kernel("batch-" + id + "/planar-engine", planar_engine, k->planar_engine);
    register_kernel("batch+energy-" + id + "/planar-engine", planar_engine, k->planar_engine_energy);
}

} // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    REGISTER_CLASS("central-direct", central_direct)
    {
        // inputs: e, m1, R1, v_n1, m2, R2, v_n2
        register_hand<gen::central_direct_result<double>>("handwritten/central-direct", hand, [](const double* x, gen::central_direct_result<double>& o) {
            return hand_central_direct(x[0], x[1], x[3], x[4], x[6], o);
        });
    }
    REGISTER_CLASS("central-oblique", central_oblique)
    {
        // inputs: e, m1, R1, v_t1, v_n1, v_b1, m2, R2, v_t2, v_n2, v_b2
        register_hand<gen::central_oblique_result<double>>("handwritten/central-oblique", hand, [](const double* x, gen::central_oblique_result<double>& o) {
            return hand_central_oblique(x[0], x[1], V3(x[3], x[4], x[5]), x[6], V3(x[8], x[9], x[10]), o);
        });
    }
    REGISTER_CLASS("noncentral-3d", noncentral_3d)
    register_hand("handwritten/noncentral-3d", hand, [](const double* x, hand_out& o) { return hand_noncentral(x, false, o); });
    register_jacobian_benchmarks("noncentral-3d", hand->in.rows);
    REGISTER_CLASS("noncentral-3d-engine", noncentral_3d_engine)
    register_hand("handwritten/noncentral-3d-engine", hand, [](const double* x, hand_out& o) { return hand_noncentral(x, true, o); });
    register_jacobian_benchmarks("noncentral-3d-engine", hand->in.rows);
    REGISTER_CLASS("massive-3d", massive_3d)
    register_hand("handwritten/massive-3d", hand, [](const double* x, hand_out& o) { return hand_massive(x, o); });
    REGISTER_CLASS("planar", planar)
    register_hand<gen::planar_result<double>>("handwritten/planar", hand, [](const double* x, gen::planar_result<double>& o) { return hand_planar<false>(x, o); });
    register_jacobian_benchmarks("planar", hand->in.rows);
    class_data* planar_data = hand;
    REGISTER_CLASS("planar-engine", planar_engine)
    register_hand<gen::planar_engine_result<double>>("handwritten/planar-engine", hand, [](const double* x, gen::planar_engine_result<double>& o) { return hand_planar<true>(x, o); });
    register_kernels(impactgen_bench_kernels_main(), planar_data, hand);
#ifdef IMPACTGEN_BENCH_OTHER_KERNELS
    register_kernels(impactgen_bench_kernels_other(), planar_data, hand);
#endif
    REGISTER_CLASS("pinned-planar", pinned_planar)
    // inputs: e, m1, l, v1, m2
    register_hand<gen::pinned_planar_result<double>>("handwritten/pinned-planar", hand, [](const double* x, gen::pinned_planar_result<double>& o) { return hand_pinned(x[0], x[2], x[1], x[4], x[3], o); });
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
