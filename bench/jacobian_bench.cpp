// jacobian/<class>: <name>_jacobian<double>, the values and the dense Jacobian (every
//                   output by every input) the generator derives symbolically
// autodiff/<class>: <name><AutoDiffScalar<Matrix<double, K, 1>>> on the same inputs, K the
//                   number of inputs (fixed size), input j seeded with the unit vector e_j:
//                   forward mode, all outputs (energy_lost too, like the Jacobian), the
//                   seeding counted in its time
// Both on the same impacts as the other benchmarks of the class. Before they are
// registered, a check (once, untimed) that autodiff's values and derivatives equal the
// Jacobian's on every impact of the set: a benchmark that compares different things
// would be worthless, so a mismatch aborts the run with a message.
#include "jacobian_bench.hpp"

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

// Generated at build time by the impactgen just built (bench/CMakeLists.txt).
#include "noncentral_3d_engine_jacobian.hpp"
#include "noncentral_3d_jacobian.hpp"
#include "planar_jacobian.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <utility>

namespace jb = impactgen::bench_jacobian;

namespace {

// Impacts per timed iteration (the first ones of the class's set).
constexpr int kJacobianImpacts = 256;

// Relative differences accepted between autodiff and the Jacobian: both evaluate the
// same rational function in double along different operation orders (autodiff the chain
// rule through the value code, the Jacobian the symbolic derivatives with their own
// common subexpressions), so they agree to a few hundred roundings, measured against the
// largest derivative of the same output (row): an entry that cancels to nearly zero
// carries the rounding of the terms it cancels, not of its own size. The values are
// compared relative to their own size.
constexpr double kRowTolerance = 1e-12;
constexpr double kValueTolerance = 1e-12;

template <std::size_t... I, typename F> auto call_with(const double* x, F&& f, std::index_sequence<I...>)
{
    return f(x[I]...);
}

struct agreement {
    double worst_row = 0, worst_value = 0;
    long entries = 0;
};

// Values and derivatives of autodiff (ad_out: the outputs as AutoDiffScalars) against the
// Jacobian (values, d) for one impact; aborts on a mismatch beyond the tolerances.
template <int Outputs, int K, typename AD>
void compare(const char* cls, int impact, const AD (&ad_out)[Outputs], const double (&values)[Outputs],
             const double (&d)[Outputs][K], const char* const* output_names, const char* const* input_names, agreement& a)
{
    for (int i = 0; i < Outputs; ++i) {
        const double want_value = ad_out[i].value();
        const double value_diff = std::fabs(values[i] - want_value) / std::max(1.0, std::fabs(want_value));
        a.worst_value = std::max(a.worst_value, value_diff);
        if (!(value_diff <= kValueTolerance)) {
            std::fprintf(stderr, "impactgen_bench: %s, impact %d: %s = %.17g from %s_jacobian, %.17g from autodiff\n", cls,
                         impact, output_names[i], values[i], cls, want_value);
            std::abort();
        }
        double row = 0;
        for (int j = 0; j < K; ++j)
            row = std::max(row, std::fabs(ad_out[i].derivatives()(j)));
        for (int j = 0; j < K; ++j) {
            const double want = ad_out[i].derivatives()(j), got = d[i][j];
            const double diff = row > 0 ? std::fabs(got - want) / row : std::fabs(got - want);
            a.worst_row = std::max(a.worst_row, diff);
            ++a.entries;
            if (!(diff <= kRowTolerance)) {
                std::fprintf(stderr,
                             "impactgen_bench: %s, impact %d: d %s / d %s = %.17g from the Jacobian, %.17g from autodiff "
                             "(difference %.3g of the row's largest derivative %.3g; tolerance %.0e): the benchmark "
                             "would compare different things\n",
                             cls, impact, output_names[i], input_names[j], got, want, diff, row, kRowTolerance);
                std::abort();
            }
        }
    }
}

void per_impact(benchmark::State& state, long impacts)
{
    state.counters["ns_per_impact"] =
        benchmark::Counter(static_cast<double>(impacts), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.SetItemsProcessed(state.iterations() * impacts);
}

// One class: FN the generated name in impactgen::bench_jacobian.
#define JACOBIAN_CLASS(CLS, FN)                                                                                        \
    if (cls == CLS) {                                                                                                  \
        constexpr int K = jb::FN##_input_count;                                                                        \
        constexpr int Outputs = jb::FN##_output_count;                                                                 \
        static_assert(jb::FN##_wrt_count == K, "the Jacobian by every input");                                        \
        using ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, K, 1>>;                                                 \
        static const std::vector<std::vector<double>>* set = &rows;                                                    \
        if (static_cast<int>(rows.size()) < kJacobianImpacts || static_cast<int>(rows[0].size()) != K) {              \
            std::fprintf(stderr, "impactgen_bench: %s: %zu impacts of %zu inputs for the Jacobian benchmark (%d of %d " \
                                 "wanted)\n", CLS, rows.size(), rows.empty() ? std::size_t(0) : rows[0].size(),        \
                         kJacobianImpacts, K);                                                                         \
            std::abort();                                                                                              \
        }                                                                                                              \
        auto jacobian = [](const double* x, jb::FN##_jacobian_result<double>& out) {                                  \
            return call_with(x, [&](auto... a) { return jb::FN##_jacobian<double>(a..., out); },                       \
                             std::make_index_sequence<K>{});                                                          \
        };                                                                                                             \
        agreement a;                                                                                                   \
        for (int i = 0; i < static_cast<int>(rows.size()); ++i) {                                                      \
            const double* x = rows[static_cast<std::size_t>(i)].data();                                                \
            static jb::FN##_jacobian_result<double> jac;                                                               \
            const jb::impact_status s = jacobian(x, jac);                                                              \
            ad in[K];                                                                                                  \
            for (int j = 0; j < K; ++j)                                                                                \
                in[j] = ad(x[j], K, j);                                                                                \
            jb::FN##_result<ad> r;                                                                                     \
            const jb::impact_status sa = jb::FN(in, r);                                                                \
            if (s != jb::impact_status::ok || sa != jb::impact_status::ok) {                                           \
                std::fprintf(stderr, "impactgen_bench: %s, impact %d: status %s from %s_jacobian, %s from autodiff\n",  \
                             CLS, i, jb::to_string(s), #FN, jb::to_string(sa));                                        \
                std::abort();                                                                                          \
            }                                                                                                          \
            ad ad_out[Outputs];                                                                                        \
            jb::FN##_to_array(r, ad_out);                                                                              \
            double values[Outputs];                                                                                    \
            jb::FN##_to_array(jac.value, values);                                                                      \
            compare<Outputs, K>(#FN, i, ad_out, values, jac.d, jb::FN##_output_names, jb::FN##_input_names, a);        \
        }                                                                                                              \
        std::printf("%-22s autodiff = %s_jacobian on %zu impacts: %ld derivatives within %.1e of their row's "         \
                    "largest (tolerance %.0e), values within %.1e\n",                                                  \
                    CLS, #FN, rows.size(), a.entries, a.worst_row, kRowTolerance, a.worst_value);                      \
        benchmark::RegisterBenchmark("jacobian/" CLS, [](benchmark::State& st) {                                      \
            auto out = std::make_unique<jb::FN##_jacobian_result<double>>();                                           \
            for (auto _ : st)                                                                                          \
                for (int i = 0; i < kJacobianImpacts; ++i) {                                                           \
                    benchmark::DoNotOptimize(                                                                          \
                        call_with((*set)[static_cast<std::size_t>(i)].data(),                                          \
                                  [&](auto... a_) { return jb::FN##_jacobian<double>(a_..., *out); },                  \
                                  std::make_index_sequence<K>{}));                                                     \
                    benchmark::DoNotOptimize(*out);                                                                    \
                }                                                                                                      \
            per_impact(st, kJacobianImpacts);                                                                          \
        });                                                                                                            \
        benchmark::RegisterBenchmark("autodiff/" CLS, [](benchmark::State& st) {                                      \
            jb::FN##_result<ad> r;                                                                                     \
            for (auto _ : st)                                                                                          \
                for (int i = 0; i < kJacobianImpacts; ++i) {                                                           \
                    const double* x = (*set)[static_cast<std::size_t>(i)].data();                                      \
                    ad in[K];                                                                                          \
                    for (int j = 0; j < K; ++j)                                                                        \
                        in[j] = ad(x[j], K, j);                                                                        \
                    benchmark::DoNotOptimize(jb::FN(in, r));                                                           \
                    benchmark::DoNotOptimize(r);                                                                       \
                }                                                                                                      \
            per_impact(st, kJacobianImpacts);                                                                          \
        });                                                                                                            \
        return;                                                                                                        \
    }

} // namespace

void register_jacobian_benchmarks(const std::string& cls, const std::vector<std::vector<double>>& rows)
{
    JACOBIAN_CLASS("noncentral-3d", noncentral_3d)
    JACOBIAN_CLASS("noncentral-3d-engine", noncentral_3d_engine)
    JACOBIAN_CLASS("planar", planar)
    std::fprintf(stderr, "impactgen_bench: no Jacobian header for %s\n", cls.c_str());
    std::abort();
}
