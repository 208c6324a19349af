// The solvers impactgen ships for its named classes need no generation and no
// GiNaC: link impactgen::generated and include "generated/<class>.hpp".
// A Newton's cradle of five equal steel balls, resolved pair by pair with the
// central direct impact: with e = 1 the first ball's velocity passes to the last.
#include "generated/central_direct.hpp"

#include <cmath>
#include <cstdio>

namespace gen = impactgen::generated;

int main()
{
    const int n = 5;
    const double m = 0.1, R = 0.0125, e = 1.0;
    double v[n] = {1.0, 0, 0, 0, 0}; // m/s along the row
    const double p0 = m * v[0], t0 = m * v[0] * v[0] / 2;

    // Collisions in sequence: ball i strikes ball i + 1 (normal from i into i + 1).
    for (int i = 0; i + 1 < n; ++i) {
        gen::central_direct_result<double> out;
        const gen::impact_status s = gen::central_direct(e, m, R, v[i], m, R, v[i + 1], out);
        if (s != gen::impact_status::ok) {
            std::printf("FAIL: collision %d-%d: %s\n", i, i + 1, gen::to_string(s));
            return 1;
        }
        v[i] = out.v_n1;
        v[i + 1] = out.v_n2;
    }
    double p = 0, t = 0;
    for (int i = 0; i < n; ++i) {
        std::printf("ball %d: %+.15f m/s\n", i + 1, v[i]);
        p += m * v[i];
        t += m * v[i] * v[i] / 2;
    }
    // Equal masses, e = 1: an exact exchange up to rounding of a few operations
    // per collision (1e-12 absolute on velocities of order 1 m/s).
    bool ok = std::fabs(v[n - 1] - 1.0) < 1e-12 && std::fabs(p - p0) < 1e-12 && std::fabs(t - t0) < 1e-12;
    for (int i = 0; i + 1 < n; ++i)
        ok = ok && std::fabs(v[i]) < 1e-12;
    std::printf("%s: momentum %.15f (was %.15f), energy %.15f (was %.15f)\n", ok ? "ok" : "FAIL", p, p0, t, t0);
    return ok ? 0 : 1;
}
