// detail::slide_direction, the sliding direction of a 3-D impact with friction whose
// solution is provably unique (the friction preamble of every generated header with
// friction; codegen/writer_stages.cpp): with m = mu M (M + M^T positive definite) and b, the
// unit d and l > 0 with (m + l 1) d = b, when the stick candidate -m^{-1} b lies outside
// the unit disc. Checked on seeded random m and b (anisotropic, non-symmetric, scaled
// over 600 decades) against the equation itself, in float, double and long double.
#include "noncentral_3d_friction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

namespace {

namespace d = impactgen::generated::detail;

struct case2 {
    long double m11, m12, m21, m22, b1, b2;
};

// m = S + W: S symmetric positive definite (eigenvalues 10^-3..10^3 apart), W skew with
// |W| up to 3 |S|; b of length such that |m^{-1} b| > 1 (the contact does not stick).
case2 draw(std::mt19937_64& g)
{
    std::uniform_real_distribution<double> U(0, 1);
    const double pi = 3.141592653589793;
    const double th = 2 * pi * U(g), k1 = std::pow(10.0, -3 + 6 * U(g)), k2 = k1 * std::pow(10.0, -3 * U(g));
    const double c = std::cos(th), s = std::sin(th), w = 3 * U(g) * (k1 + k2) * (U(g) < 0.5 ? 1 : -1);
    case2 r{};
    r.m11 = c * c * k1 + s * s * k2;
    r.m22 = s * s * k1 + c * c * k2;
    r.m12 = c * s * (k1 - k2) + w;
    r.m21 = c * s * (k1 - k2) - w;
    const double ph = 2 * pi * U(g);
    for (;;) {
        const double len = std::pow(10.0, -4 + 8 * U(g));
        r.b1 = len * std::cos(ph);
        r.b2 = len * std::sin(ph);
        const long double det = r.m11 * r.m22 - r.m12 * r.m21;
        const long double x1 = (r.m22 * r.b1 - r.m12 * r.b2) / det, x2 = (r.m11 * r.b2 - r.m21 * r.b1) / det;
        if (x1 * x1 + x2 * x2 > 1.0001L)
            return r;
    }
}

// The residual of (m + l 1) d = b for the best l (l = d.(b - m d)), relative to |b| + |m|,
// and that l.
template <typename T> long double residual(const case2& k, T c, T s, long double& l)
{
    const long double dc = c, ds = s;
    const long double r1 = k.b1 - (k.m11 * dc + k.m12 * ds), r2 = k.b2 - (k.m21 * dc + k.m22 * ds);
    l = r1 * dc + r2 * ds;
    const long double e1 = r1 - l * dc, e2 = r2 - l * ds;
    const long double scale = std::sqrt(k.b1 * k.b1 + k.b2 * k.b2) + std::fabs(k.m11) + std::fabs(k.m12) + std::fabs(k.m21) +
                              std::fabs(k.m22);
    return std::sqrt(e1 * e1 + e2 * e2) / scale;
}

template <typename T> void check_type(long double tol, int n)
{
    std::mt19937_64 g(20261123u);
    long double worst = 0;
    for (int i = 0; i < n; ++i) {
        const case2 k = draw(g);
        T c = 0, s = 0;
        ASSERT_TRUE(d::slide_direction<T>(T(k.m11), T(k.m12), T(k.m21), T(k.m22), T(k.b1), T(k.b2), c, s)) << "sample " << i;
        EXPECT_NEAR(static_cast<long double>(c) * c + static_cast<long double>(s) * s, 1.0L, 8 * tol) << "sample " << i;
        long double l = 0;
        const long double r = residual(k, c, s, l);
        worst = std::max(worst, r);
        EXPECT_LE(r, tol) << "sample " << i;
        EXPECT_GT(l, 0) << "sample " << i << ": the slide needs l > 0";
    }
    std::cout << "slide_direction<" << (sizeof(T) == 4 ? "float" : sizeof(T) == 8 ? "double" : "long double") << ">: " << n
              << " samples, worst residual / (|b| + |m|) " << static_cast<double>(worst) << "\n";
}

TEST(friction_slide_direction, solves_its_equation_in_every_type)
{
    // The root l is refined to 4 eps |b|, and d = x / |x| is then exact to a few eps: the
    // residual is a few eps of |b| + |m| times the condition of m + l 1 (up to ~1e3 for
    // these eigenvalues 1e-3 apart), so about 1e3 eps at worst: 1e-13 in double (eps 2.2e-16),
    // 1e-16 in long double (eps 1.1e-19), 1e-5 in float (eps 1.2e-7). Measured: 1.0e-15,
    // 3.6e-19, 2.6e-7.
    check_type<double>(1e-13L, 20000);
    check_type<long double>(1e-16L, 5000);
    check_type<float>(1e-5L, 5000);
}

TEST(friction_slide_direction, does_not_depend_on_the_scale)
{
    std::mt19937_64 g(7u);
    for (int i = 0; i < 2000; ++i) {
        const case2 k = draw(g);
        double c0, s0;
        ASSERT_TRUE(d::slide_direction<double>(k.m11, k.m12, k.m21, k.m22, k.b1, k.b2, c0, s0));
        for (const double f : {1e-300, 1e-150, 1e150, 1e300}) {
            const double x[6] = {double(k.m11) * f, double(k.m12) * f, double(k.m21) * f, double(k.m22) * f, double(k.b1) * f,
                                 double(k.b2) * f};
            bool finite_inputs = true;
            for (double v : x)
                finite_inputs = finite_inputs && std::isfinite(v) && (v == 0 || std::fabs(v) >= 1e-307);
            if (!finite_inputs)
                continue; // a product left double's normal range: not the same problem any more
            double c, s;
            ASSERT_TRUE(d::slide_direction<double>(x[0], x[1], x[2], x[3], x[4], x[5], c, s)) << "sample " << i << " scale " << f;
            // scaling by a power of ten rounds the inputs (relative 1.1e-16 each): the direction
            // moves by that times the condition of m + l 1 (up to ~1e3), 1e-12 covers it
            EXPECT_NEAR(c, c0, 1e-12) << "sample " << i << " scale " << f;
            EXPECT_NEAR(s, s0, 1e-12) << "sample " << i << " scale " << f;
        }
    }
}

TEST(friction_slide_direction, isotropic_response_is_the_direction_of_b)
{
    // m = k 1: d = b / |b| (the closed form of the isotropic slide), l = |b| - k.
    double c, s;
    ASSERT_TRUE(d::slide_direction<double>(0.5, 0.0, 0.0, 0.5, 3.0, -4.0, c, s));
    EXPECT_NEAR(c, 0.6, 1e-15);
    EXPECT_NEAR(s, -0.8, 1e-15);
}

TEST(friction_slide_direction, refuses_what_it_cannot_solve)
{
    double c = 7, s = 7;
    const double inf = HUGE_VAL, nan = std::nan("");
    EXPECT_FALSE(d::slide_direction<double>(nan, 0, 0, 1, 2, 0, c, s));
    EXPECT_FALSE(d::slide_direction<double>(1, 0, 0, 1, inf, 0, c, s));
    EXPECT_FALSE(d::slide_direction<double>(0, 0, 0, 0, 0, 0, c, s)); // nothing to scale by
}

} // namespace
