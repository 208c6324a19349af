// A generated header with --jacobian under a restitution law followed through the impact
// (GEN_HEADER, function FN), compiled under strict warnings (check_compile.cmake) and run: its
// NAME_jacobian instantiated for float, double and long double at one rod whose slip reverses,
// each returning ok with finite derivatives that agree across the types to float precision.
#include GEN_HEADER

#include <cmath>
#include <cstdio>

#define IMPACTGEN_CAT2(a, b) a##b
#define IMPACTGEN_CAT(a, b) IMPACTGEN_CAT2(a, b)

using namespace impactgen::generated;

template <typename T> int run(T *jac, int &sequence)
{
    IMPACTGEN_CAT(FN, _result)<T> out{};
    // e, mu, m, I1, x, y, v_t, v_n, w
    const friction_status s = IMPACTGEN_CAT(FN, _jacobian)<T>(T(0.5), T(0.3), T(1), T(0.08), T(0.4), T(0.7), T(0.6),
                                                              T(-1), T(0.25), out, jac);
    sequence = out.sequence;
    return s == friction_status::ok ? 0 : 1;
}

int main()
{
    constexpr int n = IMPACTGEN_CAT(FN, _wrt_count) * IMPACTGEN_CAT(FN, _jacobian_output_count);
    float jf[n];
    double jd[n];
    long double jl[n];
    int sf = 0, sd = 0, sl = 0;
    if (run(jf, sf) || run(jd, sd) || run(jl, sl) || sf != sd || sd != sl) {
        std::printf("FAILED: status or sequence differ by type\n");
        return 1;
    }
    for (int k = 0; k < n; ++k)
        if (!std::isfinite(jd[k]) || std::abs(static_cast<double>(jf[k]) - jd[k]) > 1e-3 * (1 + std::abs(jd[k])) ||
            std::abs(static_cast<double>(jl[k]) - jd[k]) > 1e-12 * (1 + std::abs(jd[k]))) {
            std::printf("FAILED: entry %d: %g %g %g\n", k, static_cast<double>(jf[k]), jd[k],
                        static_cast<double>(jl[k]));
            return 1;
        }
    return 0;
}
