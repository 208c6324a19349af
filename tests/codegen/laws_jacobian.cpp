// codegen --jacobian under a restitution law followed through the impact (Poisson, energetic):
// the generated NAME_jacobian (tests/codegen/laws/rod-rough-floor-*.json generated with
// --jacobian) against
//   - the exact derivatives `formulas --jacobian` prints (symbolic/process_jacobian.hpp: each
//     phase sequence's closed form differentiated through the contact's steps), evaluated with
//     40 digits at the doubles of the point, the sequence being the one whose conditions hold
//     there (decided in those 40 digits, not taken from the header);
//   - central differences of the generated value function in long double;
// at seeded random points, every phase sequence that random rods reach hit many times; and the
// boundary status: a point within rounding of a phase boundary is reported not differentiable.
#include "codegen/codegen.hpp"
#include "symbolic/derivation.hpp"
#include "symbolic/friction.hpp"
#include "symbolic/problem.hpp"
#include "symbolic/process_jacobian.hpp"

#include "rod_jac_energetic.hpp"
#include "rod_jac_energetic_wrt.hpp"
#include "rod_jac_poisson.hpp"

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <unsupported/Eigen/AutoDiff>

#include <cmath>
#include <map>
#include <random>
#include <set>

namespace
{
namespace gen = impactgen::generated;
using gen::friction_status;
using namespace GiNaC;

constexpr int n_in = 9, n_out = 6; // e, mu, m, I1, x, y, v_t, v_n, w; v_x, v_y, w_z, P_n, P_t x, y

enum class law { poisson, energetic };

struct point {
    double v[n_in];
};

// A rod on the floor (as laws.cpp draws them): mass ratios over 8 decades, any angle, the
// contact approaching and slipping. Near: the slip stops near where compression ends.
point random_point(std::mt19937_64 &g)
{
    std::uniform_real_distribution<double> U(0, 1);
    for (;;) {
        const double e = U(g), mu = 2 * U(g), m = std::pow(10.0, -2 + 4 * U(g));
        const double th = 0.05 + 3.04 * U(g), len = std::pow(10.0, -1 + 2 * U(g));
        const double x = len * std::cos(th), y = len * std::sin(th);
        const double J = m * len * len * std::pow(10.0, -2 + 4 * U(g));
        const double w = (2 * U(g) - 1) * 3 / len, vt = 2 * U(g) - 1, vn = -U(g) - 0.05 + w * x;
        if (std::abs(vt + w * y) > 1e-6)
            return {{e, mu, m, J, x, y, vt, vn, w}};
    }
}

// The energetic header generated with --wrt e,mu: NAME_jacobian's two columns, d/de and d/dmu.
template <typename T> friction_status energetic_wrt_jacobian(const T *a, T *jac, int &sequence, T *value)
{
    gen::rod_jac_energetic_wrt_result<T> o{};
    const friction_status s =
        gen::rod_jac_energetic_wrt_jacobian<T>(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], o, jac);
    sequence = o.sequence;
    const T vals[n_out] = {
        o.v_x_rod, o.v_y_rod, o.w_z_rod, o.normal_impulse, o.tangential_impulse_x, o.tangential_impulse_y};
    std::copy(vals, vals + n_out, value);
    return s;
}

template <typename T> friction_status jacobian(law l, const T *a, T *jac, int &sequence, bool &boundary, T *value)
{
    if (l == law::energetic) {
        gen::rod_jac_energetic_result<T> o{};
        const friction_status s =
            gen::rod_jac_energetic_jacobian<T>(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], o, jac);
        sequence = o.sequence, boundary = o.boundary;
        const T vals[n_out] = {
            o.v_x_rod, o.v_y_rod, o.w_z_rod, o.normal_impulse, o.tangential_impulse_x, o.tangential_impulse_y};
        std::copy(vals, vals + n_out, value);
        return s;
    }
    gen::rod_jac_poisson_result<T> o{};
    const friction_status s =
        gen::rod_jac_poisson_jacobian<T>(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], o, jac);
    sequence = o.sequence, boundary = o.boundary;
    const T vals[n_out] = {
        o.v_x_rod, o.v_y_rod, o.w_z_rod, o.normal_impulse, o.tangential_impulse_x, o.tangential_impulse_y};
    std::copy(vals, vals + n_out, value);
    return s;
}

// The symbolic side: the problem file's Jacobian per phase sequence (formulas --jacobian).
struct exact_side {
    impactgen::problem prob;
    impactgen::process_jacobian jac;
    std::vector<symbol> inputs; // in the header's order
};

exact_side exact_of(law l)
{
    exact_side s;
    s.prob = impactgen::load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/tests/codegen/laws/rod-rough-floor-" +
                                          (l == law::poisson ? "poisson" : "energetic") + ".json");
    const impactgen::derivation d = impactgen::derive(s.prob);
    s.jac = impactgen::process_jacobian_of(d, impactgen::solve_impact(d), {});
    for (const char *nm : {"e", "mu", "m", "I1", "x", "y", "v_t", "v_n", "w"})
        for (const symbol &x : s.jac.wrt)
            if (x.get_name() == nm)
                s.inputs.push_back(x);
    return s;
}

// The exact derivatives at a point, 40 digits: the steps evaluated in order, the sequence whose
// conditions hold, its entries in the header's row order. False when no sequence holds clearly
// (a condition within 1e-30 of 0: on a boundary).
bool exact_at(const exact_side &s, const point &p, std::vector<double> &out, std::string &sequence)
{
    Digits = 40;
    exmap at;
    for (int j = 0; j < n_in; ++j)
        at[s.inputs[static_cast<std::size_t>(j)]] = numeric(p.v[j]);
    for (const impactgen::step &st : s.jac.steps)
        at[st.sym] = evalf(st.value.subs(at));
    for (const impactgen::step &st : s.jac.derivative_steps)
        at[st.sym] = evalf(st.value.subs(at));
    for (const impactgen::sequence_jacobian &q : s.jac.sequences) {
        bool holds = true;
        for (const impactgen::process_condition &c : q.conditions) {
            const ex v = evalf(c.value.subs(at));
            if (!is_a<numeric>(v) || std::abs(ex_to<numeric>(v).to_double()) < 1e-30)
                return false;
            holds = holds && ex_to<numeric>(v).is_positive();
        }
        if (!holds)
            continue;
        // rows: formulas' outputs are P_n, P_t, v_x, v_y, w_z; the header's v_x, v_y, w_z, P_n, P_t e_t (x), 0 (y)
        const int row_of[n_out] = {2, 3, 4, 0, 1, -1};
        out.assign(n_out * n_in, 0.0);
        for (int i = 0; i < n_out; ++i)
            for (int j = 0; j < n_in && row_of[i] >= 0; ++j) {
                std::size_t col = 0;
                while (!s.jac.wrt[col].is_equal(s.inputs[static_cast<std::size_t>(j)]))
                    ++col;
                out[static_cast<std::size_t>(i * n_in + j)] =
                    ex_to<numeric>(evalf(q.entries[static_cast<std::size_t>(row_of[i])][col].subs(at))).to_double();
            }
        sequence = q.sequence;
        return true;
    }
    return false;
}

void agrees_with_exact_and_differences(law l)
{
    const exact_side s = exact_of(l);
    std::mt19937_64 g(l == law::poisson ? 23 : 32);
    std::map<std::string, int> hits;
    std::set<int> indices;
    double worst_exact = 0, worst_fd = 0;
    int compared = 0, boundaries = 0;
    for (int n = 0; n < 250; ++n) {
        const point p = random_point(g);
        double jac[n_out * n_in], val[n_out];
        int sequence = -2;
        bool boundary = false;
        const friction_status st = jacobian<double>(l, p.v, jac, sequence, boundary, val);
        std::vector<double> ex;
        std::string name;
        if (st == friction_status::ambiguous) {
            EXPECT_TRUE(boundary);
            ++boundaries;
            continue;
        }
        if (st != friction_status::ok || !exact_at(s, p, ex, name))
            continue; // wedges (no_solution), or exactly on a boundary
        ++hits[name];
        indices.insert(sequence);
        // Entries against the exact ones: the rounding of the closed form times its condition;
        // relative to the row's largest entry (its scale), 1e-8 leaves a wide margin over the
        // measured worst, and a wrong sequence or a missed chain-rule term is off by O(1).
        for (int i = 0; i < n_out; ++i) {
            double scale = 0;
            for (int j = 0; j < n_in; ++j)
                scale = std::max(scale, std::abs(ex[static_cast<std::size_t>(i * n_in + j)]));
            for (int j = 0; j < n_in; ++j) {
                const double d =
                    std::abs(jac[i * n_in + j] - ex[static_cast<std::size_t>(i * n_in + j)]) / std::max(scale, 1e-300);
                worst_exact = std::max(worst_exact, d);
                EXPECT_LT(d, 1e-8) << name << " d out" << i << "/d in" << j;
            }
        }
        // Central differences of the value function in long double, h = 1e-7 of each input (of
        // 1e-3 at least): the truncation error, about (h/x)^2 relative, and the rounding, 1e-19 / h,
        // are far below 1e-5 of the row's scale; a phase boundary within h would change the slope.
        long double x[n_in];
        for (int j = 0; j < n_in; ++j)
            x[j] = p.v[j];
        for (int j = 0; j < n_in; ++j) {
            const long double h = 1e-7L * std::max(std::abs(x[j]), 1e-3L);
            long double xp[n_in], xm[n_in], jp[n_out * n_in], jm[n_out * n_in], vp[n_out], vm[n_out];
            std::copy(x, x + n_in, xp);
            std::copy(x, x + n_in, xm);
            xp[j] += h;
            xm[j] -= h;
            int sp = 0, sm = 0;
            bool bp = false, bm = false;
            if (jacobian<long double>(l, xp, jp, sp, bp, vp) != friction_status::ok ||
                jacobian<long double>(l, xm, jm, sm, bm, vm) != friction_status::ok)
                continue;
            for (int i = 0; i < n_out; ++i) {
                double scale = 0;
                for (int k = 0; k < n_in; ++k)
                    scale = std::max(scale, std::abs(jac[i * n_in + k]));
                const double fd = static_cast<double>((vp[i] - vm[i]) / (2 * h));
                const double d = std::abs(fd - jac[i * n_in + j]) / std::max(scale, 1e-300);
                worst_fd = std::max(worst_fd, d);
                EXPECT_LT(d, 1e-5) << name << " d out" << i << "/d in" << j;
            }
        }
        ++compared;
    }
    std::printf("[ jacobian ] %d points, %d sequences (%zu indices), %d boundaries; worst vs exact %.2e, vs "
                "differences %.2e\n",
                compared, static_cast<int>(hits.size()), indices.size(), boundaries, worst_exact, worst_fd);
    for (const auto &[name, count] : hits)
        std::printf("    %s: %d\n", name.c_str(), count);
    EXPECT_GT(compared, 200);
    for (const char *seq : {"process: slide", "process: slide, stick", "process: slide, reverse"})
        EXPECT_GE(hits[seq], 5) << seq;
}

// Near a phase boundary (the slip stops where compression ends: u_t = u_n a / b, within a
// relative 1e-12) the header reports ambiguous with out.boundary; 1e-3 away it is clear of it
// (the tolerance is 2^-26 relative). At mu = 0 (the smooth impact, the edge of mu's domain) the
// Jacobian is not given either.
TEST(codegen_laws_jacobian, boundary_between_phase_sequences_is_reported)
{
    std::mt19937_64 g(5);
    int near = 0, near_reported = 0, clear = 0, clear_reported = 0;
    for (law l : {law::poisson, law::energetic})
        for (int n = 0; n < 400; ++n) {
            point p = random_point(g);
            double &e = p.v[0], &mu = p.v[1], &m = p.v[2], &J = p.v[3], &x = p.v[4], &y = p.v[5], &vt = p.v[6],
                   &vn = p.v[7], &w = p.v[8];
            (void)e;
            const double Ktt = 1 / m + y * y / J, Ktn = -x * y / J, Knn = 1 / m + x * x / J;
            const double a = Ktn - mu * Ktt, b = Knn - mu * Ktn, un = vn - w * x;
            if (!(a < -1e-3 * Ktt && b > 1e-3 * Knn))
                continue;
            const bool at = n % 2 == 0;
            vt = un * a / b * (1 + (at ? 1e-12 : 1e-3)) - w * y;
            double jac[n_out * n_in], val[n_out];
            int sequence = 0;
            bool boundary = false;
            const friction_status st = jacobian<double>(l, p.v, jac, sequence, boundary, val);
            if (st != friction_status::ok && st != friction_status::ambiguous)
                continue;
            EXPECT_EQ(st == friction_status::ambiguous, boundary);
            (at ? near : clear) += 1;
            (at ? near_reported : clear_reported) += boundary ? 1 : 0;
        }
    EXPECT_GT(near, 50);
    EXPECT_GT(clear, 50);
    EXPECT_EQ(near_reported, near);
    EXPECT_EQ(clear_reported, 0);
    const double p[n_in] = {0.5, 0, 1, 0.1, 0.3, 0.4, 0.2, -1, 0.5};
    double jac[n_out * n_in], val[n_out];
    int sequence = 0;
    bool boundary = false;
    EXPECT_EQ(jacobian<double>(law::energetic, p, jac, sequence, boundary, val), friction_status::ambiguous);
    EXPECT_TRUE(boundary);
    EXPECT_EQ(sequence, -1);
    for (double d : jac)
        EXPECT_EQ(d, 0.0);
}

// NAME_jacobian instantiated with Eigen's AutoDiffScalar (as the value function is, laws.cpp), on
// the header generated with --wrt e,mu (its two columns): its entries' values are the double
// Jacobian's columns of e and mu, and the first-order derivatives the scalar carries of the
// outputs are the whole Jacobian's rows.
TEST(codegen_laws_jacobian, instantiates_with_autodiff)
{
    using ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, n_in, 1>>;
    std::mt19937_64 g(17);
    int compared = 0;
    for (int n = 0; n < 40; ++n) {
        const point p = random_point(g);
        ad a[n_in], jac[n_out * 2], val[n_out];
        for (int j = 0; j < n_in; ++j)
            a[j] = ad(p.v[j], n_in, j);
        double jd[n_out * n_in], vd[n_out];
        int sa = 0, sd = 0;
        bool bd = false;
        const friction_status st = energetic_wrt_jacobian<ad>(a, jac, sa, val);
        ASSERT_EQ(st, jacobian<double>(law::energetic, p.v, jd, sd, bd, vd));
        if (st != friction_status::ok)
            continue;
        EXPECT_EQ(sa, sd);
        for (int i = 0; i < n_out; ++i) {
            for (int j = 0; j < 2; ++j) // e and mu are the first two inputs (another header's
                // common subexpressions: the same formulas rounded in another order)
                EXPECT_NEAR(jac[i * 2 + j].value(), jd[i * n_in + j], 1e-12 * (1 + std::abs(jd[i * n_in + j])));
            for (int j = 0; j < n_in; ++j)
                EXPECT_NEAR(val[i].derivatives()[j], jd[i * n_in + j], 1e-9 * (1 + std::abs(jd[i * n_in + j])));
        }
        ++compared;
    }
    EXPECT_GT(compared, 30);
}

TEST(codegen_laws_jacobian, poisson_agrees_with_exact_derivatives_and_differences)
{
    agrees_with_exact_and_differences(law::poisson);
}

TEST(codegen_laws_jacobian, energetic_agrees_with_exact_derivatives_and_differences)
{
    agrees_with_exact_and_differences(law::energetic);
}

} // namespace
