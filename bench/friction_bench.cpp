// Impacts with Coulomb friction (the writer codegen/writer.hpp), per named friction class, on the
// same 4096 seeded random impacts:
//   generated/<class>   the generated function (with_energy_lost = false: the outputs the
//                       reference computes: velocities, impulses, regime, status)
//   generated+energy/<class>  the same with energy_lost too
//   eigen/<class>       the independent Eigen reference numeric/friction_solver.hpp
//                       (friction_contact assembly, enumeration and, in 3-D, its
//                       semismooth Newton method: what a numeric engine would run)
//   batch/planar-friction  the batch form over structure-of-arrays inputs of 1024 impacts
// Inputs as tests/codegen/friction.cpp draws them: masses log-uniform in [1e-3, 1e3],
// inertia m s^2 (0.1..1) (planar) or m s^2 R diag(0.2..1) R^T (3-D), positions, velocities
// and spins uniform in [-1, 1] (flipped when the contact points separate), e uniform in
// [0, 1], mu uniform in [0.05, 1.5] (a mix of sticking and sliding impacts).
// Counters: ns_per_impact. bench/friction_ratios.sh prints the ratios and the targets.
#include "ball_floor_friction.hpp"
#include "noncentral_3d_friction.hpp"
#include "planar_friction.hpp"

#include "numeric/friction_solver.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace gen = impactgen::generated;
namespace nm = impactgen::numeric;
using V3 = Eigen::Vector3d;

namespace {

constexpr int kImpacts = 4096;
constexpr int kBatch = 1024;

struct input_set {
    std::vector<std::string> names;
    std::vector<std::vector<double>> rows;
    double at(int i, const std::string& n) const
    {
        for (std::size_t j = 0; j < names.size(); ++j)
            if (names[j] == n)
                return rows[static_cast<std::size_t>(i)][j];
        std::fprintf(stderr, "no input %s\n", n.c_str());
        std::abort();
    }
};

std::array<double, 6> spd(std::mt19937_64& g, double m)
{
    std::uniform_real_distribution<double> U(-1, 1), D(0.2, 1), S(0.1, 1);
    double q[4], l = 0;
    for (double& a : q) {
        a = U(g);
        l += a * a;
    }
    l = std::sqrt(l);
    for (double& a : q)
        a /= l;
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    const double s = S(g), d[3] = {D(g), D(g), D(g)};
    double I[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            I[r][c] = 0;
            for (int k = 0; k < 3; ++k)
                I[r][c] += R[r][k] * d[k] * R[c][k];
            I[r][c] *= m * s * s;
        }
    return {I[0][0], I[0][1], I[0][2], I[1][1], I[1][2], I[2][2]};
}

template <typename F> input_set make_inputs(const char* const* names, int n_in, F status_of, unsigned seed)
{
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> U(0, 1);
    input_set s;
    for (int j = 0; j < n_in; ++j)
        s.names.push_back(names[j]);
    while (static_cast<int>(s.rows.size()) < kImpacts) {
        std::vector<double> x(static_cast<std::size_t>(n_in));
        std::map<std::string, double> mass;
        std::map<std::string, std::array<double, 6>> tensor;
        for (int j = 0; j < n_in; ++j)
            if (s.names[static_cast<std::size_t>(j)][0] == 'm')
                mass[s.names[static_cast<std::size_t>(j)].substr(1)] = x[static_cast<std::size_t>(j)] = std::pow(10.0, -3 + 6 * U(g));
        for (int j = 0; j < n_in; ++j) {
            const std::string& n = s.names[static_cast<std::size_t>(j)];
            double& v = x[static_cast<std::size_t>(j)];
            if (n == "e")
                v = U(g);
            else if (n == "mu")
                v = 0.05 + 1.45 * U(g);
            else if (n[0] == 'm')
                continue;
            else if (n == "R")
                v = std::pow(10.0, -2 + 2 * U(g));
            else if (n[0] == 'I' && n.find('_') == std::string::npos) {
                const double sz = 0.1 + 0.9 * U(g);
                v = mass.at(n.substr(1)) * sz * sz * (0.1 + 0.9 * U(g));
            } else if (n[0] == 'I') {
                const std::string b = n.substr(1, n.find('_') - 1), ax = n.substr(n.find('_') + 1);
                if (!tensor.count(b))
                    tensor[b] = spd(g, mass.at(b));
                const char* order[6] = {"tt", "tn", "tb", "nn", "nb", "bb"};
                for (int k = 0; k < 6; ++k)
                    if (ax == order[k])
                        v = tensor[b][static_cast<std::size_t>(k)];
            } else
                v = 2 * U(g) - 1;
        }
        if (status_of(x.data()) == gen::friction_status::not_approaching) {
            for (int j = 0; j < n_in; ++j)
                if (s.names[static_cast<std::size_t>(j)][0] == 'v' || s.names[static_cast<std::size_t>(j)][0] == 'w')
                    x[static_cast<std::size_t>(j)] = -x[static_cast<std::size_t>(j)];
        }
        if (status_of(x.data()) != gen::friction_status::ok)
            continue;
        s.rows.push_back(x);
    }
    return s;
}

// The reference's problems from the same inputs (the classes as symbolic/named_classes.cpp builds them).
nm::problem<double> eigen_problem(const std::string& cls, const input_set& s, int i)
{
    auto v = [&](const std::string& n) { return s.at(i, n); };
    nm::problem<double> p;
    p.point.setZero();
    p.normal = V3(0, 1, 0);
    p.restitution = v("e");
    p.friction = v("mu");
    if (cls == "ball-floor-friction") {
        p.dimension = 2;
        const double R = v("R"), m = v("m");
        nm::body<double> floor, ball;
        floor.infinite_mass = true;
        floor.mass = 0;
        floor.position = V3(0, -R, 0);
        ball.mass = m;
        ball.particle = false;
        ball.inertia(2, 2) = 2 * m * R * R / 5;
        ball.position = V3(0, R, 0);
        ball.velocity = V3(v("v_t"), v("v_n"), 0);
        ball.angular_velocity = V3(0, 0, v("w"));
        p.bodies = {floor, ball};
        return p;
    }
    const char* ax = "tnb";
    p.dimension = cls == "planar-friction" ? 2 : 3;
    for (const char* b : {"1", "2"}) {
        const std::string k = b;
        nm::body<double> bd;
        bd.mass = v("m" + k);
        bd.particle = false;
        for (int c = 0; c < p.dimension; ++c) {
            bd.position[c] = v(std::string("r_") + ax[c] + k);
            bd.velocity[c] = v(std::string("v_") + ax[c] + k);
        }
        if (p.dimension == 2) {
            bd.inertia(2, 2) = v("I" + k);
            bd.angular_velocity = V3(0, 0, v("w_b" + k));
        } else {
            for (int c = 0; c < 3; ++c)
                bd.angular_velocity[c] = v(std::string("w_") + ax[c] + k);
            for (int r = 0; r < 3; ++r)
                for (int c = r; c < 3; ++c)
                    bd.inertia(r, c) = bd.inertia(c, r) = v("I" + k + "_" + ax[r] + ax[c]);
        }
        p.bodies.push_back(bd);
    }
    return p;
}

void per_impact(benchmark::State& state, long impacts)
{
    state.counters["ns_per_impact"] =
        benchmark::Counter(static_cast<double>(impacts), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.SetItemsProcessed(state.iterations() * impacts);
}

struct class_data {
    input_set in;
    std::vector<nm::problem<double>> eigen;
    std::vector<std::vector<double>> soa_in, soa_out;
    std::map<int, int> regimes;
};

#define REGISTER_FRICTION(CLS, FN)                                                                                    \
    {                                                                                                                 \
        static class_data d;                                                                                          \
        d.in = make_inputs(                                                                                           \
            gen::FN##_input_names, gen::FN##_input_count,                                                             \
            [](const double* x) {                                                                                     \
                gen::FN##_result<double> r;                                                                           \
                return gen::FN(x, r);                                                                                 \
            },                                                                                                        \
            20261207u);                                                                                               \
        for (int i = 0; i < kImpacts; ++i) {                                                                          \
            d.eigen.push_back(eigen_problem(CLS, d.in, i));                                                           \
            gen::FN##_result<double> r;                                                                               \
            gen::FN(d.in.rows[static_cast<std::size_t>(i)].data(), r);                                                \
            ++d.regimes[int(r.regime)];                                                                               \
        }                                                                                                             \
        std::printf("%-24s %d impacts: stick %d, slide %d\n", CLS, kImpacts, d.regimes[int(gen::impact_regime::stick)], \
                    d.regimes[int(gen::impact_regime::slide)]);                                                       \
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
        benchmark::RegisterBenchmark("eigen/" CLS, [](benchmark::State& st) {                                         \
            for (auto _ : st)                                                                                         \
                for (int i = 0; i < kImpacts; ++i) {                                                                  \
                    auto a = nm::solve_friction(d.eigen[static_cast<std::size_t>(i)]);                                \
                    benchmark::DoNotOptimize(a);                                                                      \
                }                                                                                                     \
            per_impact(st, kImpacts);                                                                                 \
        });                                                                                                           \
        d.soa_in.assign(static_cast<std::size_t>(gen::FN##_input_count), std::vector<double>(kBatch));                \
        d.soa_out.assign(static_cast<std::size_t>(gen::FN##_output_count), std::vector<double>(kBatch));              \
        for (int j = 0; j < gen::FN##_input_count; ++j)                                                               \
            for (int i = 0; i < kBatch; ++i)                                                                          \
                d.soa_in[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] =                                  \
                    d.in.rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];                              \
        benchmark::RegisterBenchmark("batch/" CLS, [](benchmark::State& st) {                                         \
            std::vector<const double*> in;                                                                            \
            std::vector<double*> out;                                                                                 \
            for (auto& a : d.soa_in)                                                                                  \
                in.push_back(a.data());                                                                               \
            for (auto& a : d.soa_out)                                                                                 \
                out.push_back(a.data());                                                                              \
            std::vector<gen::friction_status> status(kBatch);                                                         \
            std::vector<gen::impact_regime> regime(kBatch);                                                           \
            for (auto _ : st) {                                                                                       \
                gen::FN##_batch<double, false>(kBatch, in.data(), out.data(), status.data(), regime.data());          \
                benchmark::ClobberMemory();                                                                           \
            }                                                                                                         \
            per_impact(st, kBatch);                                                                                   \
        });                                                                                                           \
    }

} // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    REGISTER_FRICTION("planar-friction", planar_friction)
    REGISTER_FRICTION("ball-floor-friction", ball_floor_friction)
    REGISTER_FRICTION("noncentral-3d-friction", noncentral_3d_friction)
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
