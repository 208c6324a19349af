// Status values that agree: the same input gives the same status in every header that can
// take it. Masses and moments of inertia over the whole range of double (1e-308 ... 1e308,
// the masses of 1e308 included), and invalid values (0, < 0, NaN, infinite, e out
// of [0, 1], separating velocities): the smooth planar header, the planar friction header
// with mu = 0 (the same impact) and with mu = 0.3 (the same validity and the same
// overflow), the engine convention where its inverses are finite; the same in 3-D.
#include "noncentral_3d.hpp"
#include "noncentral_3d_friction.hpp"
#include "planar.hpp"
#include "planar_engine.hpp"
#include "planar_friction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace gen = impactgen::generated;

namespace
{

const std::vector<double> scales = {1e-308, 1e-300, 1e-200, 1e-100, 1e-10, 1, 1e10, 1e100, 1e200, 1e300, 1e308};

struct planar_in {
    double e = 0.5, m1 = 1, I1 = 1, m2 = 2, I2 = 3, v_n1 = 1, v_n2 = -1;
};

int smooth(const planar_in &x)
{
    gen::planar_result<double> r{};
    return int(
        gen::planar(x.e, x.m1, x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, x.m2, x.I2, -0.3, 0.4, -0.5, x.v_n2, 0.125, r));
}

int friction(const planar_in &x, double mu)
{
    gen::planar_friction_result<double> r{};
    return int(gen::planar_friction(x.e, mu, x.m1, x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, x.m2, x.I2, -0.3, 0.4, -0.5,
                                    x.v_n2, 0.125, r));
}

int engine(const planar_in &x)
{
    gen::planar_engine_result<double> r{};
    return int(gen::planar_engine(x.e, 1 / x.m1, 1 / x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, 1 / x.m2, 1 / x.I2, -0.3, 0.4,
                                  -0.5, x.v_n2, 0.125, r));
}

bool finite_inverses(const planar_in &x)
{
    for (double v : {x.m1, x.I1, x.m2, x.I2})
        if (!std::isfinite(v) || !std::isfinite(1 / v) || 1 / v == 0)
            return false;
    return true;
}

void expect_agree(const planar_in &x, const std::string &what)
{
    const int s = smooth(x), f0 = friction(x, 0), f = friction(x, 0.3);
    EXPECT_EQ(s, f0) << what << ": planar and planar_friction with mu = 0";
    // With friction the impact is another one: it may have no regime (or two) where the
    // smooth one is ok; every other status is the smooth header's.
    const bool regime_status = f == int(gen::friction_status::no_solution) || f == int(gen::friction_status::ambiguous);
    if (!(s == 0 && regime_status))
        EXPECT_EQ(s, f) << what << ": planar and planar_friction with mu = 0.3";
    if (finite_inverses(x))
        EXPECT_EQ(s, engine(x)) << what << ": planar and planar_engine";
}

TEST(CodegenStatusAgreement, PlanarOverTheWholeRange)
{
    for (double m : scales)
        for (double I : scales)
            for (double m2 : {1.0, 2.0}) {
                planar_in x;
                x.m1 = m, x.I1 = I, x.m2 = m2 * m, x.I2 = 3 * I;
                if (!std::isfinite(x.m2) || !std::isfinite(x.I2))
                    continue;
                expect_agree(x, "m " + std::to_string(m) + ", I " + std::to_string(I));
            }
    // The example: masses (and moments of inertia) of 1e308, where the friction header
    // said singular: the impact in both (k is denormal, the impulse about 1.4e308). Compared
    // without the energy lost: the smooth header computes it as -(u N + k N^2 / 2), whose N^2
    // overflows here (overflow), the friction header as the work of the impulse (finite).
    planar_in x;
    x.m1 = x.m2 = x.I1 = x.I2 = 1e308;
    gen::planar_result<double> a{};
    gen::planar_friction_result<double> b{};
    const auto s = gen::planar<double, false>(x.e, x.m1, x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, x.m2, x.I2, -0.3, 0.4,
                                              -0.5, x.v_n2, 0.125, a);
    const auto f = gen::planar_friction<double, false>(x.e, 0.3, x.m1, x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, x.m2, x.I2,
                                                       -0.3, 0.4, -0.5, x.v_n2, 0.125, b);
    EXPECT_EQ(int(s), int(gen::impact_status::ok));
    EXPECT_EQ(int(f), int(gen::friction_status::ok));
    EXPECT_GT(a.normal_impulse, 1e307);
}

TEST(CodegenStatusAgreement, PlanarInvalidInputs)
{
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    for (double bad : {0.0, -1.0, nan, inf}) {
        planar_in x;
        x.m1 = bad;
        expect_agree(x, "m1 = " + std::to_string(bad));
        x = planar_in{};
        x.I2 = bad;
        expect_agree(x, "I2 = " + std::to_string(bad));
    }
    for (double e : {-0.1, 1.5, nan}) {
        planar_in x;
        x.e = e;
        expect_agree(x, "e = " + std::to_string(e));
    }
    planar_in x;
    x.v_n1 = -1, x.v_n2 = 1; // separating
    expect_agree(x, "separating");
    x.v_n1 = x.v_n2 = 0; // resting
    expect_agree(x, "resting");
}

TEST(CodegenStatusAgreement, ThreeDimensionalOverTheWholeRange)
{
    for (double m : scales)
        for (double I : scales) {
            if (!std::isfinite(3 * I) || !std::isfinite(2 * m))
                continue;
            gen::noncentral_3d_result<double> a{};
            gen::noncentral_3d_friction_result<double> b{};
            const double z = 0;
            const int s = int(gen::noncentral_3d<double>(0.5, m, I, z, z, I, z, I, 0.1, -0.2, 0.05, 0.25, 1.0, z, 0.1,
                                                         z, 0.2, 2 * m, 2 * I, z, z, 3 * I, z, 2 * I, -0.3, 0.4, 0.1,
                                                         -0.5, -1.0, z, 0.125, z, z, a));
            const int f = int(gen::noncentral_3d_friction<double>(
                0.5, 0.0, m, I, z, z, I, z, I, 0.1, -0.2, 0.05, 0.25, 1.0, z, 0.1, z, 0.2, 2 * m, 2 * I, z, z, 3 * I, z,
                2 * I, -0.3, 0.4, 0.1, -0.5, -1.0, z, 0.125, z, z, b));
            EXPECT_EQ(s, f) << "m " << m << ", I " << I;
        }
}

} // namespace
