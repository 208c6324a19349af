// The engine-convention headers against a hand-written engine formula specialised the same
// way, per call, with the project's compiler and with the other of g++ and clang++ in one
// process (engine_kernels.hpp):
//   engine-<compiler>/<class>/checked    <name>(...), every check (the default entry point)
//   engine-<compiler>/<class>/unchecked  <name>_unchecked(...), the validate-once fast path
//   engine-<compiler>/<class>/hand       the hand-written formula (same normal, 1/m, I^{-1})
// for planar-engine and noncentral-3d-engine, on the same 4096 random valid impacts (seeded;
// rows the checked function accepts). Before timing, the three variants' impulses are
// compared on every impact (the checked and unchecked bit for bit, the hand formula within
// 1e-12 relative) (exit 1 naming the case otherwise). Counter: ns_per_impact.
// bench/engine_ratios.sh prints the medians and the ratios from one run.
#include "engine_kernels.hpp"
#include "noncentral_3d_engine.hpp"
#include "planar_engine.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace gen = impactgen::generated;

namespace {

constexpr int kImpacts = 4096;

// Random valid rows: inverse masses in [0.1, 2], inverse inertia 1/I in [0.1, 2] (planar) or
// a symmetric positive-definite I^{-1} = A A^T + 0.1 (3-D), centres of mass and velocities in
// [-1, 1], e in [0, 1]; kept when the checked function accepts them (approaching contacts).
template <typename Result, typename F> std::vector<double> make_rows(int inputs, bool tensor, F checked, unsigned seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1), pos(0.1, 2), e01(0, 1);
    std::vector<double> rows;
    std::vector<double> x(static_cast<std::size_t>(inputs));
    const int per_body = (inputs - 1) / 2;
    for (int kept = 0; kept < kImpacts;) {
        x[0] = e01(rng);
        for (int b = 0; b < 2; ++b) {
            double* p = x.data() + 1 + b * per_body;
            p[0] = pos(rng);
            int next = 2;
            if (tensor) {
                double a[9];
                for (double& v : a)
                    v = u(rng);
                const int idx[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
                for (int k = 0; k < 6; ++k) {
                    const int i = idx[k][0], j = idx[k][1];
                    p[1 + k] = a[3 * i] * a[3 * j] + a[3 * i + 1] * a[3 * j + 1] + a[3 * i + 2] * a[3 * j + 2] + (i == j ? 0.1 : 0);
                }
                next = 7;
            } else
                p[1] = pos(rng);
            for (int k = next; k < per_body; ++k)
                p[k] = u(rng);
        }
        Result r;
        if (checked(x.data(), r) == gen::impact_status::ok) {
            rows.insert(rows.end(), x.begin(), x.end());
            ++kept;
        }
    }
    return rows;
}

void per_impact(benchmark::State& state, long impacts)
{
    state.counters["ns_per_impact"] =
        benchmark::Counter(static_cast<double>(impacts), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.SetItemsProcessed(state.iterations() * impacts);
}

struct engine_class {
    const char* name;
    std::shared_ptr<std::vector<double>> rows;
    long stride;
    /// Where every variant writes its result: allocated once, 64-byte aligned, the same
    /// address in every repetition (a buffer allocated per repetition, 16-byte aligned, made
    /// the medians of g++'s planar_engine bimodal, 3.6 or 6.4 ns for the same code).
    std::shared_ptr<double> out{static_cast<double*>(std::aligned_alloc(64, 256)), std::free};
};

// Checks that the variants agree, then registers the three benchmarks of one compiler's set.
void register_class(const char* id, const engine_class& c, impactgen_engine_kernel checked, impactgen_engine_kernel unchecked,
                    impactgen_engine_kernel hand)
{
    std::vector<double> a(kImpacts), b(kImpacts), h(kImpacts);
    checked(kImpacts, c.rows->data(), c.stride, c.out.get(), a.data());
    unchecked(kImpacts, c.rows->data(), c.stride, c.out.get(), b.data());
    hand(kImpacts, c.rows->data(), c.stride, c.out.get(), h.data());
    for (int i = 0; i < kImpacts; ++i)
        if (!(a[i] > 0) || !(a[i] == b[i]) || !(std::abs(a[i] - h[i]) <= 1e-12 * a[i])) {
            std::fprintf(stderr, "engine-%s/%s: impact %d: the impulses disagree: checked %.17g, unchecked %.17g, hand %.17g\n",
                         id, c.name, i, a[i], b[i], h[i]);
            std::exit(1);
        }
    const std::pair<const char*, impactgen_engine_kernel> variants[] = {{"checked", checked}, {"unchecked", unchecked}, {"hand", hand}};
    for (const auto& [variant, kernel] : variants) {
        const std::string name = std::string("engine-") + id + "/" + c.name + "/" + variant;
        benchmark::RegisterBenchmark(name.c_str(), [c, kernel = kernel](benchmark::State& st) {
            for (auto _ : st)
                kernel(kImpacts, c.rows->data(), c.stride, c.out.get(), nullptr);
            per_impact(st, kImpacts);
        });
    }
}

void register_set(const impactgen_engine_kernel_set* k, const engine_class& planar, const engine_class& noncentral)
{
    std::printf("engine-%s: %s\n", k->id, k->compiler);
    register_class(k->id, planar, k->planar_checked, k->planar_unchecked, k->planar_hand);
    register_class(k->id, noncentral, k->noncentral_checked, k->noncentral_unchecked, k->noncentral_hand);
}

} // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    const engine_class planar{"planar-engine",
                              std::make_shared<std::vector<double>>(make_rows<gen::planar_engine_result<double>>(
                                  gen::planar_engine_input_count, false,
                                  [](const double* x, gen::planar_engine_result<double>& r) { return gen::planar_engine(x, r); }, 12345)),
                              gen::planar_engine_input_count};
    const engine_class noncentral{
        "noncentral-3d-engine",
        std::make_shared<std::vector<double>>(make_rows<gen::noncentral_3d_engine_result<double>>(
            gen::noncentral_3d_engine_input_count, true,
            [](const double* x, gen::noncentral_3d_engine_result<double>& r) { return gen::noncentral_3d_engine(x, r); }, 12345)),
        gen::noncentral_3d_engine_input_count};
    register_set(impactgen_engine_kernels_main(), planar, noncentral);
#ifdef IMPACTGEN_BENCH_OTHER_KERNELS
    register_set(impactgen_engine_kernels_other(), planar, noncentral);
#endif
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
