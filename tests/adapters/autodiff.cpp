// A generated header instantiated with an autodiff scalar (Eigen's
// AutoDiffScalar, forward mode): it compiles under -Wconversion -Wshadow with a
// long double constant folded in (m = sqrt(2)), and its derivatives equal the
// generated Jacobian.
#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "tied.hpp"
#include "wall_sqrt2.hpp"

#include <impactgen/eigen.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ig = impactgen::generated;

TEST(Autodiff, AutoDiffScalarMatchesTheJacobian)
{
    constexpr int n = ig::wall_sqrt2_input_count;
    static_assert(ig::wall_sqrt2_wrt_count == n, "the Jacobian by every input");
    using ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, n, 1>>;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int compared = 0;
    for (int trial = 0; trial < 200; ++trial) {
        // e, a positive-definite tensor (diagonally dominant), velocities into the wall.
        double x[n];
        x[0] = 0.5 + 0.4 * u(rng);
        x[1] = 3 + u(rng);
        x[2] = 0.3 * u(rng);
        x[3] = 0.3 * u(rng);
        x[4] = 3 + u(rng);
        x[5] = 0.3 * u(rng);
        x[6] = 3 + u(rng);
        for (int k = 7; k < n; ++k)
            x[k] = 2 * u(rng);
        ig::wall_sqrt2_jacobian_result<double> jac;
        const ig::impact_status s = ig::wall_sqrt2_jacobian(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8], x[9], x[10],
                                                            x[11], x[12], jac);
        ad a[n];
        for (int k = 0; k < n; ++k)
            a[k] = ad(x[k], n, k);
        ig::wall_sqrt2_result<ad> r;
        const ig::impact_status sa = ig::wall_sqrt2(a, r);
        ASSERT_EQ(s, sa);
        if (s != ig::impact_status::ok)
            continue;
        ad out[ig::wall_sqrt2_output_count];
        ig::wall_sqrt2_to_array(r, out);
        double values[ig::wall_sqrt2_output_count];
        ig::wall_sqrt2_to_array(jac.value, values);
        for (int i = 0; i < ig::wall_sqrt2_output_count; ++i) {
            EXPECT_NEAR(out[i].value(), values[i], 1e-12 * (1 + std::fabs(values[i])));
            for (int j = 0; j < n; ++j) {
                const double want = out[i].derivatives()(j), got = jac.d[i][j];
                // Two evaluations of the same rational function in double, along different
                // operation orders: a few hundred roundings apart at most.
                EXPECT_NEAR(got, want, 1e-12 * (1 + std::fabs(want))) << "d output " << i << " / d input " << j;
                ++compared;
            }
        }
    }
    EXPECT_GT(compared, 1000);
}

// The Eigen adapter with an autodiff scalar: fixed entries (a diagonal tensor's
// zeros) compared and read back, vectors written and read, under -Wconversion.
TEST(Autodiff, EigenAdapterWithAutoDiffScalar)
{
    using ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, 2, 1>>;
    ig::tied_input<ad> in{};
    Eigen::Matrix<ad, 3, 3> inertia = Eigen::Matrix<ad, 3, 3>::Zero();
    inertia(0, 0) = ad(1.0, 2, 0);
    inertia(1, 1) = ad(2.0, 2, 1);
    inertia(2, 2) = ad(3.0);
    EXPECT_TRUE(impactgen::eigen::assign(in.I_box(), inertia));
    EXPECT_EQ(in.A.value(), 1.0);
    EXPECT_EQ(in.B.derivatives()(1), 1.0);
    const Eigen::Matrix<ad, 3, 3> back = impactgen::eigen::to_eigen(in.I_box());
    EXPECT_EQ(back(0, 1).value(), 0.0);
    EXPECT_EQ(back(2, 2).value(), 3.0);
    inertia(0, 1) = inertia(1, 0) = ad(0.5);
    EXPECT_FALSE(impactgen::eigen::assign(in.I_box(), inertia)); // not the diagonal tensor the header solves
}
