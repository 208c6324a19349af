// The generated rod-rough-floor headers for Poisson's and the energetic law (tests/codegen/laws/
// rod-rough-floor-*.json: the named class with the rod's centre and inertia as inputs) against
//   - the closed form of symbolic/routh.hpp, exact at rational points (GiNaC numbers, the one
//     phase sequence decided exactly), to a few ulps of double;
//   - the numeric reference numeric/process_integrator.hpp (small normal-impulse steps, Eigen,
//     independent of the closed form) and the exact closed form (the doubles taken as rationals)
//     on the same 20,000 seeded random problems per law, a third of them near a phase boundary;
// the status values on bad inputs, float / long double / the unchecked variant, and the header
// the same byte for byte when generated again in this process.
#include "codegen/codegen.hpp"
#include "numeric/process_integrator.hpp"
#include "symbolic/problem.hpp"
#include "symbolic/routh.hpp"

#include "rod_rough_floor.hpp" // generated/: the named class
#include "rod_rough_floor_energetic.hpp"
#include "rod_rough_floor_poisson.hpp"
#include "rod_slip_reverses_energetic.hpp"
#include "rod_slip_reverses_poisson.hpp"

#include <gtest/gtest.h>
#include <unsupported/Eigen/AutoDiff>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

namespace
{
namespace gen = impactgen::generated;
using gen::friction_status;

// The rod (mass m, inertia J, centre (x, y)) touching the floor at the origin, normal +y:
// r = O - C = (-x, -y), K = I/m + (y, -x)(y, -x)^T / J in (x, y); u = v + w z x r.
struct rod {
    double e, mu, m, J, x, y, vt, vn, w;
    double Ktt() const { return 1 / m + y * y / J; }
    double Ktn() const { return -x * y / J; }
    double Knn() const { return 1 / m + x * x / J; }
    double ut() const { return vt + w * y; }
    double un() const { return vn - w * x; }
};

enum class law { poisson, energetic };

template <typename T> struct outcome {
    friction_status status;
    T N, Ft, energy_lost;
    gen::impact_regime regime;
};

template <typename T, bool unchecked = false> outcome<T> run(law l, const rod &r)
{
    const T a[9] = {T(r.e), T(r.mu), T(r.m), T(r.J), T(r.x), T(r.y), T(r.vt), T(r.vn), T(r.w)};
    if (l == law::poisson) {
        gen::rod_rough_floor_poisson_result<T> o{};
        friction_status s =
            unchecked
                ? gen::rod_rough_floor_poisson_unchecked<T>(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], o)
                : gen::rod_rough_floor_poisson<T>(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], o);
        return {s, o.normal_impulse, o.tangential_impulse_x, o.energy_lost, o.regime};
    }
    gen::rod_rough_floor_energetic_result<T> o{};
    friction_status s =
        unchecked ? gen::rod_rough_floor_energetic_unchecked<T>(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], o)
                  : gen::rod_rough_floor_energetic<T>(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], o);
    return {s, o.normal_impulse, o.tangential_impulse_x, o.energy_lost, o.regime};
}

impactgen::numeric::process_result<double> reference(law l, const rod &r)
{
    Eigen::Matrix2d W;
    W << r.Knn(), r.Ktn(), r.Ktn(), r.Ktt();
    const Eigen::Vector2d c(r.un(), r.ut());
    return impactgen::numeric::integrate_process<double>(
        W, c, r.mu, r.e,
        l == law::poisson ? impactgen::numeric::process_law::poisson : impactgen::numeric::process_law::energetic);
}

// A random approaching rod: mu 0..2, e 0..1, m 1e-4..1e4, J / (m |r|^2) 1e-4..1e4 (the ratio of
// the translational to the rotational mass at the contact), the rod at any angle above the floor.
// kind 1: mu within 1e-9 relative of the sticking ratio |K_tn| / K_tt; kind 2: the slip stops
// within 1e-9 relative of the end of compression.
rod random_rod(std::mt19937_64 &g, int kind)
{
    std::uniform_real_distribution<double> U(0, 1);
    rod r{};
    for (;;) {
        r.e = U(g);
        r.mu = 2 * U(g);
        r.m = std::pow(10.0, -4 + 8 * U(g));
        const double th = 0.05 + 3.04 * U(g), len = std::pow(10.0, -1 + 2 * U(g));
        r.x = len * std::cos(th);
        r.y = len * std::sin(th);
        r.J = r.m * len * len * std::pow(10.0, -4 + 8 * U(g));
        r.w = (2 * U(g) - 1) * 3 / len;
        r.vt = 2 * U(g) - 1;
        r.vn = -U(g) - 0.05 + r.w * r.x;
        const double d = (2 * U(g) - 1) * 1e-9;
        if (kind == 1)
            r.mu = std::abs(r.Ktn()) / r.Ktt() * (1 + d);
        if (kind == 2) {
            const double a = r.Ktn() - r.mu * r.Ktt(), b = r.Knn() - r.mu * r.Ktn();
            if (!(a < 0 && b > 0))
                continue;
            r.vt = r.un() * a / b * (1 + d) - r.w * r.y; // u_t = u_n a / b: stops where u_n = 0
        }
        if (r.un() < 0 && std::abs(r.ut()) > 1e-12)
            return r;
    }
}

// A double as the exact rational it is (m 2^k).
GiNaC::numeric exact(double d)
{
    int k = 0;
    const double m = std::frexp(d, &k);
    return GiNaC::numeric(static_cast<long>(std::ldexp(m, 53))) * GiNaC::numeric(2).power(k - 53);
}

// The closed form of symbolic/routh.hpp at the rod's doubles taken as exact rationals (every
// decision exact): its N and P_t rounded to double, or false when it wedges.
bool closed_form(law l, const rod &r, double &N, double &Pt)
{
    using GiNaC::numeric;
    const numeric m = exact(r.m), J = exact(r.J), x = exact(r.x), y = exact(r.y), w = exact(r.w);
    impactgen::process_inputs in;
    in.Ktt = 1 / m + y * y / J;
    in.Ktn = -x * y / J;
    in.Knn = 1 / m + x * x / J;
    in.ut = exact(r.vt) + w * y;
    in.un = exact(r.vn) - w * x;
    in.mu = exact(r.mu);
    in.e = exact(r.e);
    in.law = l == law::poisson ? impactgen::restitution_law{impactgen::poisson_restitution{}}
                               : impactgen::restitution_law{impactgen::energetic_restitution{}};
    std::vector<impactgen::process_sequence> seq;
    try {
        seq = impactgen::routh_process(in, "test");
    } catch (const std::exception &) {
        return false; // wedges
    }
    N = GiNaC::ex_to<numeric>(GiNaC::evalf(seq.at(0).normal_impulse)).to_double();
    Pt = GiNaC::ex_to<numeric>(GiNaC::evalf(seq.at(0).tangential_impulse)).to_double();
    return true;
}

// Closed form (exact), numeric integration and generated code on the same 20,000 problems.
void agree_with_reference(law l)
{
    std::mt19937_64 g(l == law::poisson ? 2323 : 2324);
    double worst = 0, worst_exact = 0;
    int compared = 0;
    for (int i = 0; i < 20000; ++i) {
        const rod r = random_rod(g, i % 3);
        const auto ref = reference(l, r);
        const outcome<double> o = run<double>(l, r);
        if (!ref.ok) { // the contact wedges: the header finds no sequence either
            EXPECT_EQ(o.status, friction_status::no_solution) << i;
            continue;
        }
        ASSERT_EQ(o.status, friction_status::ok) << i << " mu " << r.mu << " e " << r.e;
        // The integrator is exact within each linear step; its error is the rounding of
        // thousands of steps (each ~1e-16 of the impulse, ~1e-12 in all) and its slip threshold:
        // a slip below 1e-11 of the velocity scale counts as stopped, which moves the phase
        // boundary by 1e-11 V / |du_t/dP_n|, large relative to the impulse where the slip
        // decelerates slowly (measured: up to 8e-8 on these seeds, near the stick boundary).
        // 1e-6 bounds it; a wrong phase sequence away from a boundary is off by O(mu) relative,
        // and near one (kinds 1 and 2, within 1e-9) by about 1e-9.
        const double size = std::abs(ref.normal_impulse) + std::abs(ref.tangential);
        const double err = std::max(std::abs(o.N - ref.normal_impulse), std::abs(o.Ft - ref.tangential)) / size;
        worst = std::max(worst, err);
        // The exact closed form at the same numbers: the header differs by its rounding (a few ulps
        // times the formulas' condition), and within 1e-9 of a boundary (kinds 1, 2) its rounded
        // decision may take the neighbouring sequence, whose value differs there by about 1e-9
        // relative (the map is continuous): 1e-8 bounds both.
        double cN = 0, cPt = 0;
        ASSERT_TRUE(closed_form(l, r, cN, cPt)) << i;
        const double err_exact = std::max(std::abs(o.N - cN), std::abs(o.Ft - cPt)) / size;
        worst_exact = std::max(worst_exact, err_exact);
        EXPECT_LE(err_exact, 1e-8) << i << " N " << o.N << " vs exact " << cN;
        EXPECT_LE(err, 1e-6) << i << " mu " << r.mu << " e " << r.e << " N " << o.N << " vs " << ref.normal_impulse
                             << " Pt " << o.Ft << " vs " << ref.tangential;
        const bool sticks = ref.phases.back() == impactgen::numeric::process_phase_kind::stick;
        if (i % 3 == 0) { // away from the boundaries the regime is the last phase's
            EXPECT_EQ(o.regime == gen::impact_regime::stick, sticks) << i;
        }
        if (l == law::energetic) { // Stronge's law never creates energy
            EXPECT_GE(o.energy_lost, -1e-9 * r.m * (r.vt * r.vt + r.vn * r.vn) - 1e-9 * r.J * r.w * r.w) << i;
        }
        ++compared;
    }
    EXPECT_GT(compared, 19000);
    std::printf("[ %s ] %d problems, worst relative difference to the integrator %.3g, to the exact closed form %.3g\n",
                l == law::poisson ? "poisson" : "energetic", compared, worst, worst_exact);
}

TEST(codegen_laws, poisson_agrees_with_the_integrator)
{
    agree_with_reference(law::poisson);
}
TEST(codegen_laws, energetic_agrees_with_the_integrator)
{
    agree_with_reference(law::energetic);
}

// Exact: the closed form at rational points (every decision exact), then the double header.
void agree_exactly(law l)
{
    using GiNaC::ex;
    using GiNaC::numeric;
    std::mt19937_64 g(l == law::poisson ? 77 : 78);
    std::uniform_int_distribution<int> D(1, 9), S(-9, 9);
    int compared = 0;
    for (int i = 0; i < 300; ++i) {
        const numeric e(D(g) - 1, 8), mu(D(g) - 1, 4), m(D(g), 2), J(D(g), 12), x(S(g), 4), y(D(g), 4), vt(S(g), 2),
            w(S(g), 3);
        const numeric un = numeric(-D(g), 2);
        const numeric vn = un + w * x; // u_n = v_n - w x
        const numeric ut = vt + w * y;
        if (ut.is_zero())
            continue;
        impactgen::process_inputs in;
        in.Ktt = 1 / m + y * y / J;
        in.Ktn = -x * y / J;
        in.Knn = 1 / m + x * x / J;
        in.ut = ut;
        in.un = un;
        in.mu = mu;
        in.e = e;
        in.law = l == law::poisson ? impactgen::restitution_law{impactgen::poisson_restitution{}}
                                   : impactgen::restitution_law{impactgen::energetic_restitution{}};
        std::vector<impactgen::process_sequence> seq;
        try {
            seq = impactgen::routh_process(in, "test");
        } catch (const std::exception &) {
            continue; // wedges
        }
        ASSERT_EQ(seq.size(), 1u);
        const double N = GiNaC::ex_to<numeric>(GiNaC::evalf(seq[0].normal_impulse)).to_double();
        const double Pt = GiNaC::ex_to<numeric>(GiNaC::evalf(seq[0].tangential_impulse)).to_double();
        const rod r{e.to_double(), mu.to_double(), m.to_double(),  J.to_double(), x.to_double(),
                    y.to_double(), vt.to_double(), vn.to_double(), w.to_double()};
        const outcome<double> o = run<double>(l, r);
        ASSERT_EQ(o.status, friction_status::ok) << i;
        const double size = std::abs(N) + std::abs(Pt);
        EXPECT_LE(std::abs(o.N - N), 1e-13 * size) << i;
        EXPECT_LE(std::abs(o.Ft - Pt), 1e-13 * size) << i;
        EXPECT_EQ(o.regime == gen::impact_regime::stick, seq[0].phases.back().kind == impactgen::phase_kind::stick)
            << i;
        const outcome<long double> ol = run<long double>(l, r);
        EXPECT_LE(std::abs(static_cast<double>(ol.N) - N), 1e-14 * size) << i;
        const outcome<float> of = run<float>(l, r);
        if (of.status == friction_status::ok) { // float: near a boundary a phase may differ
            EXPECT_LE(std::abs(static_cast<double>(of.N) - N), 1e-3 * size) << i;
        }
        const outcome<double> ou = run<double, true>(l, r);
        EXPECT_EQ(ou.status, friction_status::ok);
        EXPECT_EQ(ou.N, o.N); // bit for bit
        EXPECT_EQ(ou.Ft, o.Ft);
        ++compared;
    }
    EXPECT_GT(compared, 200);
}

TEST(codegen_laws, poisson_is_the_exact_closed_form)
{
    agree_exactly(law::poisson);
}
TEST(codegen_laws, energetic_is_the_exact_closed_form)
{
    agree_exactly(law::energetic);
}

TEST(codegen_laws, status_values_on_bad_inputs)
{
    for (law l : {law::poisson, law::energetic}) {
        const rod good{0.5, 0.2, 1, 1.0 / 12, 0.3, 0.4, 1, -2, 0};
        EXPECT_EQ(run<double>(l, good).status, friction_status::ok);
        rod r = good;
        r.e = 1.5;
        EXPECT_EQ(run<double>(l, r).status, friction_status::invalid_restitution);
        r = good;
        r.mu = -0.1;
        EXPECT_EQ(run<double>(l, r).status, friction_status::invalid_friction);
        r = good;
        r.m = 0;
        EXPECT_EQ(run<double>(l, r).status, friction_status::invalid_mass);
        r = good;
        r.J = -1;
        EXPECT_EQ(run<double>(l, r).status, friction_status::invalid_inertia);
        r = good;
        r.vn = 2;
        EXPECT_EQ(run<double>(l, r).status, friction_status::not_approaching);
        r = good;
        r.vt = std::nan("");
        EXPECT_EQ(run<double>(l, r).status, friction_status::non_finite_input);
        r = good;
        r.mu = 0; // the smooth impact: N = -(1 + e) u_n / K_nn
        const outcome<double> s = run<double>(l, r);
        EXPECT_EQ(s.status, friction_status::ok);
        EXPECT_EQ(s.regime, gen::impact_regime::smooth);
        EXPECT_NEAR(s.N, 1.5 * 2 / r.Knn(), 1e-14);
    }
}

// examples/laws/rod-slip-reverses.json: the figures N = 1.436 (Poisson), 1.456 (energetic).
TEST(codegen_laws, rod_slip_reverses_example)
{
    const rod r{0.5, 0.2, 1, 1.0 / 12, 0.3, 0.4, 1, -2, 0};
    EXPECT_NEAR(run<double>(law::poisson, r).N, 1.436, 5e-4);
    EXPECT_NEAR(run<double>(law::energetic, r).N, 1.456, 5e-4);
}

// A contact that does not slip before impact (u_t = 0 at run time): the sequences that start
// without slip (stick inside the cone, else a slide along sign K_tn), as the integrator does.
TEST(codegen_laws, no_initial_slip)
{
    std::mt19937_64 g(5);
    int compared = 0;
    for (law l : {law::poisson, law::energetic})
        for (int i = 0; i < 2000; ++i) {
            rod r = random_rod(g, 0);
            r.w = 0;
            r.vt = 0; // u_t = v_t + w y = 0 exactly
            if (!(r.un() < 0))
                continue;
            const auto ref = reference(l, r);
            const outcome<double> o = run<double>(l, r);
            if (!ref.ok)
                continue;
            ASSERT_EQ(o.status, friction_status::ok) << i;
            const double size = std::abs(ref.normal_impulse) + std::abs(ref.tangential);
            EXPECT_LE(std::abs(o.N - ref.normal_impulse), 1e-6 * size) << i;
            EXPECT_LE(std::abs(o.Ft - ref.tangential), 1e-6 * size) << i;
            ++compared;
        }
    EXPECT_GT(compared, 2000);
}

// Eigen's AutoDiffScalar: inside a phase sequence the derivatives of N and P_t by every input
// equal central differences of the double function (where the regime is the same either side).
TEST(codegen_laws, autodiff_derivatives)
{
    using ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, 9, 1>>;
    std::mt19937_64 g(9);
    int compared = 0, differ = 0;
    for (law l : {law::poisson, law::energetic})
        for (int i = 0; i < 200; ++i) {
            const rod r = random_rod(g, 0);
            double x[9] = {r.e, r.mu, r.m, r.J, r.x, r.y, r.vt, r.vn, r.w};
            ad a[9];
            for (int j = 0; j < 9; ++j)
                a[j] = ad(x[j], 9, j);
            ad N, Ft;
            friction_status st;
            if (l == law::poisson) {
                gen::rod_rough_floor_poisson_result<ad> o{};
                st = gen::rod_rough_floor_poisson<ad>(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], o);
                N = o.normal_impulse;
                Ft = o.tangential_impulse_x;
            } else {
                gen::rod_rough_floor_energetic_result<ad> o{};
                st = gen::rod_rough_floor_energetic<ad>(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], o);
                N = o.normal_impulse;
                Ft = o.tangential_impulse_x;
            }
            const outcome<double> o0 = run<double>(l, r);
            if (st != friction_status::ok || o0.status != friction_status::ok)
                continue;
            EXPECT_EQ(N.value(), o0.N);
            for (int j = 0; j < 9; ++j) {
                const double h = 1e-6 * (1 + std::abs(x[j]));
                double xp[9], xm[9];
                std::copy(x, x + 9, xp);
                std::copy(x, x + 9, xm);
                xp[j] += h;
                xm[j] -= h;
                const rod rp{xp[0], xp[1], xp[2], xp[3], xp[4], xp[5], xp[6], xp[7], xp[8]};
                const rod rm{xm[0], xm[1], xm[2], xm[3], xm[4], xm[5], xm[6], xm[7], xm[8]};
                const outcome<double> op = run<double>(l, rp), om = run<double>(l, rm);
                if (op.status != friction_status::ok || om.status != friction_status::ok || op.regime != o0.regime ||
                    om.regime != o0.regime)
                    continue;
                const double fdN = (op.N - om.N) / (2 * h), fdF = (op.Ft - om.Ft) / (2 * h);
                // A phase boundary inside the step changes the slope (the regime alone does not
                // show it): such steps are counted, and must be rare on problems of kind 0.
                const double tolN = 1e-4 * (1 + std::abs(fdN)) * (1 + std::abs(o0.N));
                const double tolF = 1e-4 * (1 + std::abs(fdF)) * (1 + std::abs(o0.N));
                if (std::abs(N.derivatives()[j] - fdN) > tolN || std::abs(Ft.derivatives()[j] - fdF) > tolF)
                    ++differ;
                ++compared;
            }
        }
    EXPECT_GT(compared, 2000);
    EXPECT_LT(differ, compared / 100) << differ << " of " << compared;
    std::printf("[ autodiff ] %d derivatives compared, %d across a phase boundary\n", compared, differ);
}

// The checked-in header of the named class (generated/rod_rough_floor.hpp: the energetic law, the
// rod's length l and angle theta as inputs, cos theta and sin theta evaluated in the header by
// std::cos and std::sin) against the header whose inputs are the centre and the inertia, at
// x = l cos theta / 2, y = l sin theta / 2, J = m l^2 / 12: the same closed form with the same
// phase sequence, rounded in another order. Both are within a few ulps of the exact value times
// the condition of the formulas (measured: 3e-15 relative at worst on these seeds); 1e-9 leaves
// room, and a wrong sequence is off by O(mu). AutoDiffScalar through cos and sin: d/dtheta
// against central differences of the double function.
TEST(codegen_laws, named_class_header_takes_the_angle)
{
    using ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, 1, 1>>;
    std::mt19937_64 g(31);
    std::uniform_real_distribution<double> U(0, 1);
    int compared = 0, derivatives = 0;
    double worst = 0;
    for (int i = 0; i < 3000; ++i) {
        const double e = U(g), mu = 2 * U(g), m = std::pow(10.0, -4 + 8 * U(g)), l = std::pow(10.0, -1 + 2 * U(g));
        const double th = 0.05 + 3.04 * U(g), w = (2 * U(g) - 1) * 3 / l, vt = 2 * U(g) - 1;
        const double vn = -U(g) - 0.05 + w * l * std::cos(th) / 2; // u_n < 0
        gen::rod_rough_floor_result<double> a{};
        const friction_status st = gen::rod_rough_floor<double>(e, mu, l, m, th, vt, vn, w, a);
        const rod r{e, mu, m, m * l * l / 12, l * std::cos(th) / 2, l * std::sin(th) / 2, vt, vn, w};
        const outcome<double> o = run<double>(law::energetic, r);
        ASSERT_EQ(st, o.status) << i;
        if (st != friction_status::ok)
            continue;
        const double size = std::abs(o.N) + std::abs(o.Ft);
        EXPECT_LE(std::abs(a.normal_impulse - o.N), 1e-9 * size) << i;
        EXPECT_LE(std::abs(a.tangential_impulse_t - o.Ft), 1e-9 * size) << i;
        worst = std::max(worst, std::max(std::abs(a.normal_impulse - o.N), std::abs(a.tangential_impulse_t - o.Ft)) / size);
        EXPECT_EQ(a.regime, o.regime) << i;
        EXPECT_GE(a.energy_lost, -1e-9 * m * (vt * vt + vn * vn + l * l * w * w)) << i;
        ++compared;
        if (i % 10)
            continue;
        gen::rod_rough_floor_result<ad> d{};
        ASSERT_EQ((gen::rod_rough_floor<ad>(ad(e), ad(mu), ad(l), ad(m), ad(th, 1, 0), ad(vt), ad(vn), ad(w), d)),
                  friction_status::ok);
        const double h = 1e-6;
        gen::rod_rough_floor_result<double> p{}, q{};
        if (gen::rod_rough_floor<double>(e, mu, l, m, th + h, vt, vn, w, p) != friction_status::ok ||
            gen::rod_rough_floor<double>(e, mu, l, m, th - h, vt, vn, w, q) != friction_status::ok ||
            p.regime != a.regime || q.regime != a.regime)
            continue;
        const double fd = (p.normal_impulse - q.normal_impulse) / (2 * h);
        // central difference: error h^2 |N'''| / 6 plus rounding 1e-16 |N| / h (about 1e-10 |N|)
        EXPECT_NEAR(d.normal_impulse.derivatives()[0], fd, 1e-5 * (1 + std::abs(fd)) * (1 + std::abs(a.normal_impulse)))
            << i;
        ++derivatives;
    }
    EXPECT_GT(compared, 2500);
    EXPECT_GT(derivatives, 200);
    std::printf("[ rod-rough-floor ] %d problems, worst relative difference %.3g; %d d/dtheta\n", compared, worst,
                derivatives);
}

// The same example as a numeric problem (no inputs): the sequence decided exactly at generation.
TEST(codegen_laws, numeric_problem_headers)
{
    const rod r{0.5, 0.2, 1, 1.0 / 12, 0.3, 0.4, 1, -2, 0};
    gen::rod_slip_reverses_poisson_result<double> p{};
    gen::rod_slip_reverses_energetic_result<double> en{};
    ASSERT_EQ(gen::rod_slip_reverses_poisson<double>(p), friction_status::ok);
    ASSERT_EQ(gen::rod_slip_reverses_energetic<double>(en), friction_status::ok);
    const outcome<double> ps = run<double>(law::poisson, r), es = run<double>(law::energetic, r);
    EXPECT_NEAR(p.normal_impulse, ps.N, 1e-14);
    EXPECT_NEAR(p.tangential_impulse_x, ps.Ft, 1e-14);
    EXPECT_NEAR(en.normal_impulse, es.N, 1e-14);
    EXPECT_NEAR(en.tangential_impulse_x, es.Ft, 1e-14);
    EXPECT_EQ(p.regime, gen::impact_regime::slide); // the last phase: reverse
    EXPECT_GT(en.energy_lost, 0);
}

TEST(codegen_laws, header_is_deterministic)
{
    for (const char *l : {"poisson", "energetic"}) {
        const std::string file =
            std::string(IMPACTGEN_SOURCE_DIR) + "/tests/codegen/laws/rod-rough-floor-" + l + ".json";
        const impactgen::problem p = impactgen::load_problem_file(file);
        impactgen::codegen::options o;
        o.source = file;
        o.version = IMPACTGEN_VERSION;
        o.name = std::string("rod_rough_floor_") + l;
        const std::string a = impactgen::codegen::generate(p, o).text, b = impactgen::codegen::generate(p, o).text;
        EXPECT_EQ(a, b);
        std::ifstream in(std::string(IMPACTGEN_CASE_DIR) + "/rod_rough_floor_" + l + ".hpp", std::ios::binary);
        std::stringstream built;
        built << in.rdbuf();
        EXPECT_EQ(a, built.str()) << l << ": the header made by impactgen codegen at build time differs";
    }
}

} // namespace
