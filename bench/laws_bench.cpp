// Restitution followed through the impact (Routh's process with Coulomb friction): the
// generated rod-rough-floor header for each law (straight-line closed forms of every phase
// sequence, the first whose conditions hold) vs the numeric integration of the same process
// in small normal-impulse steps (numeric/process_integrator.hpp), on the same 1024 seeded
// random approaching rods (mu 0..2, e 0..1, masses 1e-4..1e4, any angle). One impact per
// iteration: the time per iteration is the time per impact (the checked function and its
// _unchecked variant). The ratio is integrator / header.
#include "numeric/process_integrator.hpp"
#include "rod_rough_floor_energetic.hpp"
#include "rod_rough_floor_poisson.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

namespace
{
namespace gen = impactgen::generated;

struct rod {
    double e, mu, m, I, x, y, vt, vn, w;
};

const std::vector<rod> &rods()
{
    static const std::vector<rod> r = [] {
        std::mt19937_64 g(23);
        std::uniform_real_distribution<double> U(0, 1);
        std::vector<rod> v;
        while (v.size() < 1024) {
            rod a{};
            a.e = U(g);
            a.mu = 2 * U(g);
            a.m = std::pow(10.0, -4 + 8 * U(g));
            const double th = 0.05 + 3.04 * U(g), len = std::pow(10.0, -1 + 2 * U(g));
            a.x = len * std::cos(th);
            a.y = len * std::sin(th);
            a.I = a.m * len * len * std::pow(10.0, -2 + 4 * U(g));
            a.w = (2 * U(g) - 1) * 3 / len;
            a.vt = 2 * U(g) - 1;
            a.vn = -U(g) - 0.05 + a.w * a.x;
            if (a.vn - a.w * a.x < 0)
                v.push_back(a);
        }
        return v;
    }();
    return r;
}

template <typename Result, typename F> void generated(benchmark::State &state, F f)
{
    const std::vector<rod> &v = rods();
    std::size_t i = 0;
    Result out{};
    for (auto _ : state) {
        const rod &a = v[i++ & 1023];
        benchmark::DoNotOptimize(f(a.e, a.mu, a.m, a.I, a.x, a.y, a.vt, a.vn, a.w, out));
        benchmark::DoNotOptimize(out);
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void gen_poisson(benchmark::State &s)
{
    generated<gen::rod_rough_floor_poisson_result<double>>(s, [](double e, double mu, double m, double I, double x,
                                                                 double y, double vt, double vn, double w,
                                                                 gen::rod_rough_floor_poisson_result<double> &o) {
        return gen::rod_rough_floor_poisson<double, true>(e, mu, m, I, x, y, vt, vn, w, o);
    });
}
void gen_poisson_unchecked(benchmark::State &s)
{
    generated<gen::rod_rough_floor_poisson_result<double>>(s, [](double e, double mu, double m, double I, double x,
                                                                 double y, double vt, double vn, double w,
                                                                 gen::rod_rough_floor_poisson_result<double> &o) {
        return gen::rod_rough_floor_poisson_unchecked<double, true>(e, mu, m, I, x, y, vt, vn, w, o);
    });
}
void gen_energetic(benchmark::State &s)
{
    generated<gen::rod_rough_floor_energetic_result<double>>(s, [](double e, double mu, double m, double I, double x,
                                                                   double y, double vt, double vn, double w,
                                                                   gen::rod_rough_floor_energetic_result<double> &o) {
        return gen::rod_rough_floor_energetic<double, true>(e, mu, m, I, x, y, vt, vn, w, o);
    });
}
void gen_energetic_unchecked(benchmark::State &s)
{
    generated<gen::rod_rough_floor_energetic_result<double>>(s, [](double e, double mu, double m, double I, double x,
                                                                   double y, double vt, double vn, double w,
                                                                   gen::rod_rough_floor_energetic_result<double> &o) {
        return gen::rod_rough_floor_energetic_unchecked<double, true>(e, mu, m, I, x, y, vt, vn, w, o);
    });
}

// The same rod as a contact response and velocity in (n, t) for the integrator (assembling
// them is part of the impact, as it is in the header).
void integrated(benchmark::State &state, impactgen::numeric::process_law law)
{
    const std::vector<rod> &v = rods();
    std::size_t i = 0;
    for (auto _ : state) {
        const rod &a = v[i++ & 1023];
        Eigen::Matrix2d W;
        W << 1 / a.m + a.x * a.x / a.I, -a.x * a.y / a.I, -a.x * a.y / a.I, 1 / a.m + a.y * a.y / a.I;
        const Eigen::Vector2d c(a.vn - a.w * a.x, a.vt + a.w * a.y);
        auto r = impactgen::numeric::integrate_process<double>(W, c, a.mu, a.e, law);
        benchmark::DoNotOptimize(r.normal_impulse);
        benchmark::DoNotOptimize(r.tangential);
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
void int_poisson(benchmark::State &s)
{
    integrated(s, impactgen::numeric::process_law::poisson);
}
void int_energetic(benchmark::State &s)
{
    integrated(s, impactgen::numeric::process_law::energetic);
}

} // namespace

BENCHMARK(gen_poisson);
BENCHMARK(gen_poisson_unchecked);
BENCHMARK(int_poisson);
BENCHMARK(gen_energetic);
BENCHMARK(gen_energetic_unchecked);
BENCHMARK(int_energetic);
BENCHMARK_MAIN();
