// Systems (format version 3): the generated solver (codegen of examples/systems/*.json with the
// bodies' velocities as inputs, rule system_sets) vs the numeric LCP reference
// numeric/system_reference.hpp (Eigen: the whole constrained system per active set, what a
// numeric engine would run), per example system, on the same 4096 seeded impacts:
//   generated/<system>  the generated function (with_energy_lost = false)
//   reference/<system>  solve_reference on the same velocities
// Inputs: every velocity component uniform in [-1, 1], then moved (least change) so that the
// joints and pivots hold before impact, as the problem format requires. Counter: ns_per_impact.
// bench/system_ratios.sh prints the ratios and the targets.
#include "box_four_corners.hpp"
#include "compass_gait.hpp"
#include "double_pendulum_struck.hpp"
#include "three_balls_simultaneous.hpp"

#include "numeric/system_reference.hpp"

#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

namespace gen = impactgen::bench_system;
namespace ref = impactgen::numeric::systems;
using V3 = Eigen::Vector3d;

namespace
{

constexpr int kImpacts = 4096;

ref::sys_body free_body(double m, double I, V3 r, bool particle = false)
{
    ref::sys_body b;
    b.mass = m;
    b.particle = particle;
    b.inertia = Eigen::Matrix3d::Identity() * I;
    b.position = r;
    return b;
}

ref::sys_body ground(V3 r)
{
    ref::sys_body b;
    b.infinite_mass = true;
    b.position = r;
    return b;
}

// The example files (examples/systems/*.json) as the reference takes them.
ref::sys_problem compass_gait_problem()
{
    ref::sys_problem p;
    p.bodies = {ground({0, 0, 0}), free_body(5, 5 * 0.97 / 12, {0.2, 0.45, 0}),
                free_body(5, 5 * 0.97 / 12, {0.6, 0.45, 0})};
    p.links = {{1, 2, {0.4, 0.9, 0}}};
    p.contacts = {{0, 2, {0.8, 0, 0}, {0, 1, 0}, 0, true}, {0, 1, {0, 0, 0}, {0, 1, 0}, 0, true}};
    return p;
}

ref::sys_problem double_pendulum_problem()
{
    ref::sys_problem p;
    p.bodies = {free_body(1, 1.0 / 12, {0, -0.5, 0}), free_body(1, 1.0 / 12, {0, -1.5, 0}),
                free_body(1, 0, {-0.1, -2, 0}, true)};
    p.links = {{ref::fixed_frame, 0, {0, 0, 0}}, {0, 1, {0, -1, 0}}};
    p.contacts = {{2, 1, {0, -2, 0}, {1, 0, 0}, 0.5, false}};
    return p;
}

ref::sys_problem three_balls_problem()
{
    ref::sys_problem p;
    p.bodies = {free_body(1, 0, {0, 0, 0}, true), free_body(1, 0, {2, 0, 0}, true), free_body(1, 0, {4, 0, 0}, true)};
    p.contacts = {{0, 1, {1, 0, 0}, {1, 0, 0}, 1, false}, {1, 2, {3, 0, 0}, {1, 0, 0}, 1, false}};
    return p;
}

ref::sys_problem box_four_corners_problem()
{
    ref::sys_problem p;
    p.dimension = 3;
    ref::sys_body box = free_body(3, 0, {0, 0.5, 0});
    box.inertia = Eigen::Vector3d(3 * 5.0 / 12, 3 * 8.0 / 12, 3 * 5.0 / 12).asDiagonal();
    p.bodies = {ground({0, -1, 0}), box};
    for (const V3 &c : {V3(-1, 0, -1), V3(1, 0, -1), V3(1, 0, 1), V3(-1, 0, 1)})
        p.contacts.push_back({0, 1, c, {0, 1, 0}, 0.5, false});
    return p;
}

// The header's inputs of a body state: per body of finite mass its velocity, then its spin.
std::vector<double> inputs_of(const ref::sys_problem &p)
{
    std::vector<double> x;
    for (const ref::sys_body &b : p.bodies) {
        if (b.infinite_mass)
            continue;
        for (int k = 0; k < p.dimension; ++k)
            x.push_back(b.velocity[k]);
        if (!b.particle)
            for (int k = p.dimension == 2 ? 2 : 0; k < 3; ++k)
                x.push_back(b.angular_velocity[k]);
    }
    return x;
}

// Seeded impacts: velocities uniform in [-1, 1] made to satisfy the joints and pivots.
struct impacts {
    std::vector<ref::sys_problem> problems;
    std::vector<std::vector<double>> inputs;
};
impacts make(const ref::sys_problem &base, unsigned seed)
{
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> U(-1, 1);
    impacts out;
    const Eigen::Index n = 6 * static_cast<Eigen::Index>(base.bodies.size());
    for (int i = 0; i < kImpacts; ++i) {
        ref::sys_problem p = base;
        Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
        std::vector<Eigen::Index> dof;
        for (std::size_t b = 0; b < p.bodies.size(); ++b) {
            if (p.bodies[b].infinite_mass)
                continue;
            const Eigen::Index o = 6 * static_cast<Eigen::Index>(b);
            for (int k = 0; k < p.dimension; ++k)
                dof.push_back(o + k);
            if (!p.bodies[b].particle)
                for (int k = p.dimension == 2 ? 2 : 0; k < 3; ++k)
                    dof.push_back(o + 3 + k);
        }
        for (Eigen::Index d : dof)
            v(d) = U(g);
        if (!p.links.empty()) {
            Eigen::MatrixXd A(static_cast<Eigen::Index>(p.links.size()) * p.dimension, n);
            A.setZero();
            Eigen::Index r = 0;
            for (const ref::sys_link &l : p.links)
                for (int k = 0; k < p.dimension; ++k, ++r) {
                    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
                    double c = 0;
                    ref::detail::add_point(p, row, c, l.body2, l.point, V3::Unit(k), 1);
                    ref::detail::add_point(p, row, c, l.body1, l.point, V3::Unit(k), -1);
                    A.row(r) = row;
                }
            v -= A.completeOrthogonalDecomposition().solve(A * v);
        }
        for (std::size_t b = 0; b < p.bodies.size(); ++b) {
            p.bodies[b].velocity = v.segment<3>(6 * static_cast<Eigen::Index>(b));
            p.bodies[b].angular_velocity = v.segment<3>(6 * static_cast<Eigen::Index>(b) + 3);
        }
        out.inputs.push_back(inputs_of(p));
        out.problems.push_back(p);
    }
    return out;
}

template <typename Fn> void generated(benchmark::State &state, const impacts &im, Fn fn)
{
    int i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(fn(im.inputs[static_cast<std::size_t>(i)].data()));
        i = (i + 1) % kImpacts;
    }
    state.counters["ns_per_impact"] = benchmark::Counter(static_cast<double>(state.iterations()),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void reference(benchmark::State &state, const impacts &im)
{
    int i = 0;
    for (auto _ : state) {
        const ref::sys_answer a = ref::solve_reference(im.problems[static_cast<std::size_t>(i)]);
        benchmark::DoNotOptimize(a.velocity.data());
        i = (i + 1) % kImpacts;
    }
    state.counters["ns_per_impact"] = benchmark::Counter(static_cast<double>(state.iterations()),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

#define IMPACTGEN_SYSTEM_BENCH(label, fn, problem, seed, probe)                                                        \
    const impacts fn##_impacts = make(problem(), seed);                                                                \
    void BM_generated_##fn(benchmark::State &state)                                                                    \
    {                                                                                                                  \
        generated(state, fn##_impacts, [](const double *in) {                                                          \
            gen::fn##_result<double> r;                                                                                \
            const auto s = gen::fn<double, false>(in, r);                                                              \
            return r.probe + static_cast<double>(s);                                                                   \
        });                                                                                                            \
    }                                                                                                                  \
    void BM_reference_##fn(benchmark::State &state)                                                                    \
    {                                                                                                                  \
        reference(state, fn##_impacts);                                                                                \
    }                                                                                                                  \
    BENCHMARK(BM_generated_##fn)->Name("generated/" label);                                                            \
    BENCHMARK(BM_reference_##fn)->Name("reference/" label);

IMPACTGEN_SYSTEM_BENCH("compass-gait", compass_gait, compass_gait_problem, 1, v_x_swing)
IMPACTGEN_SYSTEM_BENCH("double-pendulum-struck", double_pendulum_struck, double_pendulum_problem, 2, v_x_ball)
IMPACTGEN_SYSTEM_BENCH("three-balls-simultaneous", three_balls_simultaneous, three_balls_problem, 3, v_xa)
IMPACTGEN_SYSTEM_BENCH("box-four-corners", box_four_corners, box_four_corners_problem, 4, v_y_box)

} // namespace

BENCHMARK_MAIN();
