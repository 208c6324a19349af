// A contact response K that is singular within rounding drops only the stick candidate of a
// generated header with friction: the slides may still hold (codegen/writer_select.cpp,
// stick_possible). The case of Friction.PinnedBodyStruckByAnImmovableOneSlides (a rod pinned
// at its centre struck by a wall) with the wall's mass M an input: from M = 1e16 on det K
// rounds to <= 0 (the header said singular there), and the answer is the slide of the wall of
// infinite mass (N = 5/4, F = 3/8, w' = 3) to within 1/M. The same for a plate on a ball joint
// struck by a ram (3-D, the sliding-angle solve).
#include "pinned_plate_struck_3d.hpp"
#include "pinned_plate_struck_massive_3d.hpp"
#include "pinned_rod_struck_massive.hpp"
#include "pinned_rod_struck_symbolic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>

namespace
{

namespace gen = impactgen::generated;

double rel(double a, double b)
{
    return std::fabs(a - b) / std::fmax(1.0, std::fabs(b));
}

TEST(friction_singular, a_pinned_rod_struck_by_a_wall_of_huge_mass_slides)
{
    gen::pinned_rod_struck_symbolic_result<double> inf;
    ASSERT_EQ(gen::pinned_rod_struck_symbolic(0.5, 0.3, -1.0, inf), gen::friction_status::ok);
    ASSERT_EQ(inf.regime, gen::impact_regime::slide);
    ASSERT_EQ(inf.normal_impulse, 1.25);
    for (double M : {1e3, 1e8, 1e15, 1e16, 1e17, 1e20, 1e50, 1e100, 1e200, 1e300, 1e307}) {
        gen::pinned_rod_struck_massive_result<double> r;
        ASSERT_EQ(gen::pinned_rod_struck_massive(0.5, 0.3, M, -1.0, r), gen::friction_status::ok) << "M = " << M;
        EXPECT_EQ(r.regime, gen::impact_regime::slide) << "M = " << M;
        gen::pinned_rod_struck_massive_result<double> u;
        ASSERT_EQ(gen::pinned_rod_struck_massive_unchecked(0.5, 0.3, M, -1.0, u), gen::friction_status::ok);
        EXPECT_EQ(u.normal_impulse, r.normal_impulse);
        // The exact answer differs from the wall of infinite mass by O(1/M) relative.
        const double tol = 1e-14 + 40 / M;
        EXPECT_LE(rel(r.normal_impulse, inf.normal_impulse), tol) << "M = " << M;
        EXPECT_LE(rel(r.tangential_impulse_y, inf.tangential_impulse_y), tol) << "M = " << M;
        EXPECT_LE(rel(r.w_z_rod, inf.w_z_rod), tol) << "M = " << M;
        EXPECT_LE(rel(r.R_x_rod, inf.R_x_rod), tol) << "M = " << M;
        EXPECT_LE(rel(r.R_y_rod, inf.R_y_rod), tol) << "M = " << M;
    }
    // mu = 5: no slide holds; with a finite K (M = 1000) the contact sticks, with K singular
    // within rounding there is no stick candidate: singular (the wall of infinite mass: no
    // regime holds).
    gen::pinned_rod_struck_massive_result<double> r;
    EXPECT_EQ(gen::pinned_rod_struck_massive(0.5, 5.0, 1e3, -1.0, r), gen::friction_status::ok);
    EXPECT_EQ(r.regime, gen::impact_regime::stick);
    EXPECT_EQ(gen::pinned_rod_struck_massive(0.5, 5.0, 1e300, -1.0, r), gen::friction_status::singular);
    EXPECT_EQ(r.normal_impulse, 0.0);
    EXPECT_EQ(gen::pinned_rod_struck_symbolic(0.5, 5.0, -1.0, inf), gen::friction_status::no_solution);
    // mu = 0 needs only n.K n > 0: the smooth impact, N = -(1 + e) u_n / K_nn = 1/2.
    ASSERT_EQ(gen::pinned_rod_struck_massive(0.5, 0.0, 1e300, -1.0, r), gen::friction_status::ok);
    EXPECT_EQ(r.regime, gen::impact_regime::smooth);
    EXPECT_DOUBLE_EQ(r.normal_impulse, 0.5);
}

TEST(friction_singular, a_pinned_plate_struck_by_a_ram_of_huge_mass_slides_in_3d)
{
    for (double mu : {0.1, 0.3}) {
        gen::pinned_plate_struck_3d_result<double> inf;
        ASSERT_EQ(gen::pinned_plate_struck_3d(0.5, mu, -1.0, inf), gen::friction_status::ok);
        ASSERT_EQ(inf.regime, gen::impact_regime::slide);
        for (double M : {1e3, 1e15, 1e17, 1e20, 1e100, 1e300}) {
            gen::pinned_plate_struck_massive_3d_result<double> r;
            ASSERT_EQ(gen::pinned_plate_struck_massive_3d(0.5, mu, M, -1.0, r), gen::friction_status::ok)
                << "M = " << M << ", mu = " << mu;
            EXPECT_EQ(r.regime, gen::impact_regime::slide);
            const double tol = 1e-12 + 1e3 / M;
            EXPECT_LE(rel(r.normal_impulse, inf.normal_impulse), tol) << "M = " << M;
            EXPECT_LE(rel(r.tangential_impulse_x, inf.tangential_impulse_x), tol) << "M = " << M;
            EXPECT_LE(rel(r.tangential_impulse_z, inf.tangential_impulse_z), tol) << "M = " << M;
            EXPECT_LE(rel(r.w_x_plate, inf.w_x_plate), tol) << "M = " << M;
            EXPECT_LE(rel(r.w_y_plate, inf.w_y_plate), tol) << "M = " << M;
            EXPECT_LE(rel(r.w_z_plate, inf.w_z_plate), tol) << "M = " << M;
            EXPECT_LE(rel(r.R_y_plate, inf.R_y_plate), tol) << "M = " << M;
        }
    }
}

} // namespace
