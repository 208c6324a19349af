// A generated header instantiated with a minimal forward-mode dual number whose
// interface is as narrow as ceres::Jet's: construction from a scalar is explicit,
// there is no conversion back, comparisons look at the value, sqrt is found by
// argument-dependent lookup. Its derivative part equals the generated Jacobian.
#include "box_floor_dual.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

struct dual {
    double a = 0, v = 0; // value, derivative along one seed direction
    dual() = default;
    explicit dual(double x, double dx = 0) : a(x), v(dx) {}
    friend dual operator+(dual x, dual y) { return dual(x.a + y.a, x.v + y.v); }
    friend dual operator-(dual x, dual y) { return dual(x.a - y.a, x.v - y.v); }
    friend dual operator*(dual x, dual y) { return dual(x.a * y.a, x.v * y.a + x.a * y.v); }
    friend dual operator/(dual x, dual y) { return dual(x.a / y.a, (x.v * y.a - x.a * y.v) / (y.a * y.a)); }
    friend dual operator-(dual x) { return dual(-x.a, -x.v); }
    friend bool operator<(dual x, dual y) { return x.a < y.a; }
    friend bool operator>(dual x, dual y) { return x.a > y.a; }
    friend bool operator<=(dual x, dual y) { return x.a <= y.a; }
    friend bool operator>=(dual x, dual y) { return x.a >= y.a; }
    friend bool operator==(dual x, dual y) { return x.a == y.a; }
    friend bool operator!=(dual x, dual y) { return x.a != y.a; }
    friend dual sqrt(dual x)
    {
        const double r = std::sqrt(x.a);
        return dual(r, x.v / (2 * r));
    }
};

} // namespace

namespace std {
template <> class numeric_limits<dual> : public numeric_limits<double> {
public:
    static dual min() noexcept { return dual(numeric_limits<double>::min()); }
    static dual epsilon() noexcept { return dual(numeric_limits<double>::epsilon()); }
};
} // namespace std

namespace ig = impactgen::generated;

// box-floor.json (a symbolic normal: the header normalises it with sqrt), every input.
TEST(Dual, NarrowAutodiffTypeMatchesTheJacobian)
{
    constexpr int n = ig::box_floor_dual_input_count;
    static_assert(ig::box_floor_dual_wrt_count == n, "the Jacobian by every input");
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int compared = 0;
    for (int trial = 0; trial < 50; ++trial) {
        double x[n];
        for (int k = 0; k < n; ++k)
            x[k] = u(rng);
        x[0] = 0.5 + 0.4 * u(rng); // e
        x[1] = 2 + u(rng);         // m
        x[2] = 3 + u(rng);         // Ixx, Ixy, Ixz, Iyy, Iyz, Izz: diagonally dominant
        x[3] = 0.3 * u(rng);
        x[4] = 0.3 * u(rng);
        x[5] = 3 + u(rng);
        x[6] = 0.3 * u(rng);
        x[7] = 3 + u(rng);
        ig::box_floor_dual_jacobian_result<double> jac;
        const ig::impact_status s = ig::box_floor_dual_jacobian(static_cast<const double*>(x), jac);
        for (int j = 0; j < n; ++j) {
            dual d[n];
            for (int k = 0; k < n; ++k)
                d[k] = dual(x[k], k == j ? 1.0 : 0.0);
            ig::box_floor_dual_result<dual> r;
            const ig::impact_status sd = ig::box_floor_dual(static_cast<const dual*>(d), r);
            ASSERT_EQ(s, sd);
            if (s != ig::impact_status::ok)
                break;
            dual out[ig::box_floor_dual_output_count];
            ig::box_floor_dual_to_array(r, out);
            for (int i = 0; i < ig::box_floor_dual_output_count; ++i) {
                // Two double evaluations of the same derivative along different operation orders
                // (the dual's product and quotient rules vs the chain rule through the steps), on
                // well-conditioned inputs (diagonally dominant inertia, |values| <= 4): a few
                // hundred roundings apart, ~1e-13; 1e-11 leaves room, a wrong term is O(1).
                EXPECT_NEAR(out[i].v, jac.d[i][j], 1e-11 * (1 + std::fabs(jac.d[i][j]))) << "d output " << i << " / d input " << j;
                ++compared;
            }
        }
    }
    EXPECT_GT(compared, 1000);
}
