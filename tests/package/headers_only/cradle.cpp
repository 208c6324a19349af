// Header-only use of impactgen: a checked-in solver (no generation, no GiNaC,
// no Eigen). Two equal balls, e = 1: the velocities are exchanged; a second
// header in the same translation unit shares the namespace's preamble.
#include "generated/central_direct.hpp"
#include "generated/planar.hpp"

#include <cmath>
#include <cstdio>

namespace gen = impactgen::generated;

int main()
{
    gen::central_direct_result<double> out;
    const gen::impact_status s = gen::central_direct(1.0, 0.2, 0.01, 1.5, 0.2, 0.01, -0.5, out);
    if (s != gen::impact_status::ok) {
        std::printf("FAIL: %s\n", gen::to_string(s));
        return 1;
    }
    const bool ok = std::fabs(out.v_n1 + 0.5) < 1e-12 && std::fabs(out.v_n2 - 1.5) < 1e-12;
    std::printf("%s: v_n1 %g, v_n2 %g\n", ok ? "ok" : "FAIL", out.v_n1, out.v_n2);
    return ok ? 0 : 1;
}
