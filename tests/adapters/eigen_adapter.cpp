// impactgen/eigen.hpp over the views of generated structs.
#include "tied.hpp"
#include "wall.hpp"

#include <impactgen/eigen.hpp>

#include <Eigen/Dense>
#include <gtest/gtest.h>

namespace ig = impactgen::generated;

// A full inverse tensor (engine convention): six members, the transposed pair
// averaged, read back as the symmetric matrix; vectors in and out.
TEST(EigenAdapter, FullTensorAndVectors)
{
    ig::wall_input<double> in{};
    Eigen::Matrix3d k;
    k << 2.0, 0.25, -0.5, 0.25, 3.0, 0.125, -0.5, 0.125, 4.0;
    EXPECT_TRUE(impactgen::eigen::assign(in.inv_I_box(), k));
    EXPECT_EQ(in.inv_Ixx, 2.0);
    EXPECT_EQ(in.inv_Ixy, 0.25);
    EXPECT_EQ(in.inv_Ixz, -0.5);
    EXPECT_EQ(in.inv_Izz, 4.0);
    EXPECT_EQ(impactgen::eigen::to_eigen(in.inv_I_box()), k);
    // An engine's R I^-1 R^T is symmetric up to rounding: the pair's mean.
    Eigen::Matrix3d skew = k;
    skew(1, 0) = 0.5;
    EXPECT_TRUE(impactgen::eigen::assign(in.inv_I_box(), skew));
    EXPECT_EQ(in.inv_Ixy, 0.375);

    const Eigen::Vector3d v(1.0, -2.0, 0.5), w(0.1, 0.2, 0.3);
    EXPECT_TRUE(impactgen::eigen::assign(in.v_box(), v));
    EXPECT_TRUE(impactgen::eigen::assign(in.w_box(), w));
    EXPECT_EQ(in.vx, 1.0);
    EXPECT_EQ(in.vz, 0.5);
    EXPECT_EQ(in.wy, 0.2);

    // A real impact (the box moving into the wall along n = (1, 2, 2)/3): the
    // result's views are the members.
    EXPECT_TRUE(impactgen::eigen::assign(in.v_box(), Eigen::Vector3d(2.0, 3.0, 2.5)));
    in.e = 0.5;
    in.inv_m = 0.5;
    EXPECT_TRUE(impactgen::eigen::assign(in.inv_I_box(), k));
    ig::wall_result<double> out;
    ASSERT_EQ(ig::wall(in, out), ig::impact_status::ok);
    const Eigen::Vector3d v_after = impactgen::eigen::to_eigen(out.v_box());
    EXPECT_EQ(v_after.x(), out.v_x_box);
    EXPECT_EQ(v_after.z(), out.v_z_box);
    EXPECT_EQ(impactgen::eigen::to_eigen(out.w_box()).y(), out.w_y_box);
    // The positional call and the struct call agree.
    ig::wall_result<double> pos;
    ASSERT_EQ(ig::wall(in.e, in.inv_m, in.inv_Ixx, in.inv_Ixy, in.inv_Ixz, in.inv_Iyy, in.inv_Iyz, in.inv_Izz, in.vx, in.vy,
                       in.vz, in.wx, in.wy, in.wz, pos),
              ig::impact_status::ok);
    EXPECT_EQ(pos.v_x_box, out.v_x_box);
    EXPECT_EQ(pos.w_z_box, out.w_z_box);
}

// A diagonal tensor: the off-diagonal entries are fixed zeros; a matrix with
// non-zero off-diagonal entries is not the problem the header solves.
TEST(EigenAdapter, FixedEntriesMustAgree)
{
    ig::tied_input<float> in{};
    Eigen::Matrix3f diag = Eigen::Vector3f(1.0f, 2.0f, 3.0f).asDiagonal();
    EXPECT_TRUE(impactgen::eigen::assign(in.I_box(), diag));
    EXPECT_EQ(in.A, 1.0f);
    EXPECT_EQ(in.B, 2.0f);
    EXPECT_EQ(in.C, 3.0f);
    EXPECT_EQ(impactgen::eigen::to_eigen(in.I_box()), diag);
    Eigen::Matrix3f full = diag;
    full(0, 1) = full(1, 0) = 0.5f;
    EXPECT_FALSE(impactgen::eigen::assign(in.I_box(), full));
}

// The ball's velocity is ["s", "s", "c"]: its x and y must be equal.
TEST(EigenAdapter, TiedInputsMustAgree)
{
    ig::tied_input<double> in{};
    EXPECT_TRUE(impactgen::eigen::assign(in.v_ball(), Eigen::Vector3d(1.5, 1.5, -2.0)));
    EXPECT_EQ(in.s, 1.5);
    EXPECT_EQ(in.c, -2.0);
    EXPECT_FALSE(impactgen::eigen::assign(in.v_ball(), Eigen::Vector3d(1.0, 2.0, -2.0)));
    const Eigen::Vector3d back = impactgen::eigen::to_eigen(in.v_ball());
    EXPECT_EQ(back.x(), back.y());
}

// Failure leaves the state unchanged: the views read the velocities as given.
TEST(EigenAdapter, FailureKeepsTheState)
{
    ig::wall_input<double> in{};
    in.e = 0.5;
    in.inv_m = -1.0; // invalid
    Eigen::Matrix3d k = Eigen::Matrix3d::Identity();
    impactgen::eigen::assign(in.inv_I_box(), k);
    const Eigen::Vector3d v(1.0, -2.0, 0.5), w(0.1, 0.2, 0.3);
    impactgen::eigen::assign(in.v_box(), v);
    impactgen::eigen::assign(in.w_box(), w);
    ig::wall_result<double> out;
    EXPECT_EQ(ig::wall(in, out), ig::impact_status::invalid_mass);
    EXPECT_EQ(impactgen::eigen::to_eigen(out.v_box()), v);
    EXPECT_EQ(impactgen::eigen::to_eigen(out.w_box()), w);
    EXPECT_EQ(out.normal_impulse, 0.0);
    EXPECT_EQ(out.energy_lost, 0.0);
}
