// NAME_jacobian of the headers with Coulomb friction (codegen --jacobian; writer
// codegen/writer_jacobian*.cpp), on seeded random impacts of planar-friction,
// ball-floor-friction, noncentral-3d-friction, a sphere on a floor in 3-D, a box on a floor whose
// normal is an input (its tangent basis computed at run time) and a pinned rod without a stick
// candidate:
//  - against the symbolic Jacobian the header was generated from (the code plan's
//    symbolic/friction_jacobian.hpp, itself checked against central differences of the closed
//    form in FrictionJacobian.*), evaluated by CLN at 30 digits at the very inputs, for the regime
//    the header selected (the 3-D slide without a closed form at the sliding direction the header
//    returned): every entry to 1e-7 relative (double rounding of a closed form, amplified by
//    the condition of K, stays below 1e-10 for these inputs; a wrong entry is O(1) off);
//  - against central differences of the header's own value function in long double
//    (h = 1e-6 (1 + |x|): truncation ~1e-12, rounding ~1e-13), where the regime is the same a
//    step either side: to 1e-6 relative; mu = 0 (regime smooth) in one draw in ten, its column
//    by mu left out (mu >= 0: one-sided);
//  - the status: ambiguous exactly on the stick/slide boundary mu = mu* (the stick impulse's
//    |F|/N), ok a relative 1e-4 either side; a failing call passes its status through with jac
//    zero.
// IMPACTGEN_SAMPLES caps the counts (20 impacts per header against the symbolic Jacobian, 40 against
// central differences); IMPACTGEN_SEED moves the seed.
#include "ball_floor_friction_jac.hpp"
#include "noncentral_3d_friction_jac.hpp"
#include "pinned_rod_struck_symbolic_jac.hpp"
#include "planar_friction_jac.hpp"
#include "sphere_floor_3d_jac.hpp"
#include "tilted_box_friction_jac.hpp"

#include "codegen/code_plan.hpp"
#include "symbolic/named_classes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

namespace gen = impactgen::generated;
using namespace GiNaC;

namespace
{

long env_or(const char *name, long fallback)
{
    const char *v = std::getenv(name);
    return v && *v ? std::strtol(v, nullptr, 10) : fallback;
}

// One header's functions, with the inputs and outputs as arrays.
struct header_fns {
    std::string problem;          // named class or file under tests/codegen/friction
    std::vector<std::string> wrt; // --wrt it was generated with (empty: every input)
    int n_in, n_out, n_wrt, n_rows;
    const char *const *in_names, *const *out_names, *const *wrt_names, *const *row_names;
    gen::friction_status (*jacobian)(const double *, double *out, int *regime, double *jac);
    gen::friction_status (*value)(const long double *, long double *out, int *regime);
};

#define HEADER_FNS(FN, PROBLEM, WRT)                                                                                   \
    header_fns                                                                                                         \
    {                                                                                                                  \
        PROBLEM, WRT, gen::FN##_input_count, gen::FN##_output_count, gen::FN##_wrt_count,                              \
            gen::FN##_jacobian_row_count, gen::FN##_input_names, gen::FN##_output_names, gen::FN##_wrt_names,          \
            gen::FN##_jacobian_row_names,                                                                              \
            [](const double *x, double *o, int *regime, double *jac) {                                                 \
                gen::FN##_result<double> r{};                                                                          \
                const gen::friction_status s = gen::FN##_jacobian(x, r, jac);                                          \
                gen::FN##_to_array(r, o);                                                                              \
                *regime = static_cast<int>(r.regime);                                                                  \
                return s;                                                                                              \
            },                                                                                                         \
            [](const long double *x, long double *o, int *regime) {                                                    \
                gen::FN##_result<long double> r{};                                                                     \
                const gen::friction_status s = gen::FN(x, r);                                                          \
                gen::FN##_to_array(r, o);                                                                              \
                *regime = static_cast<int>(r.regime);                                                                  \
                return s;                                                                                              \
            }                                                                                                          \
    }

std::string friction_file(const char *name)
{
    return std::string(IMPACTGEN_SOURCE_DIR) + "/tests/codegen/friction/" + name;
}

std::vector<header_fns> headers()
{
    using names = std::vector<std::string>;
    // (noncentral-3d-friction by 9 of its 34 inputs, as tests/codegen/CMakeLists.txt generates it)
    const names some{"mu", "e", "m1", "I1_tn", "I2_bb", "r_b1", "v_t2", "v_n1", "w_b2"};
    return {HEADER_FNS(planar_friction_jac, "planar-friction", names{}),
            HEADER_FNS(ball_floor_friction_jac, "ball-floor-friction", names{}),
            HEADER_FNS(noncentral_3d_friction_jac, "noncentral-3d-friction", some),
            HEADER_FNS(sphere_floor_3d_jac, friction_file("sphere-floor-3d.json"), names{}),
            HEADER_FNS(tilted_box_friction_jac, friction_file("tilted-box-friction.json"), names{}),
            HEADER_FNS(pinned_rod_struck_symbolic_jac, friction_file("pinned-rod-struck-symbolic.json"), names{})};
}

// Inputs by name: e in [0.2, 0.8], mu in [0.05, 1.5] (0 in one draw in ten when zero_mu),
// masses and a radius in [0.5, 2], inertia tensors diagonally dominant, a normal's
// components with |n_z| >= 0.5, the rest in [-1, 1].
std::vector<double> draw(std::mt19937_64 &g, const header_fns &h, bool zero_mu)
{
    std::uniform_real_distribution<double> U(0, 1);
    std::vector<double> x(static_cast<std::size_t>(h.n_in));
    for (int j = 0; j < h.n_in; ++j) {
        const std::string nm = h.in_names[j];
        double v = 2 * U(g) - 1;
        if (nm == "e")
            v = 0.2 + 0.6 * U(g);
        else if (nm == "mu")
            v = zero_mu ? 0 : 0.05 + 1.45 * U(g);
        else if ((nm[0] == 'm' && nm.find('_') == std::string::npos) || nm == "R")
            v = 0.5 + 1.5 * U(g);
        else if (nm[0] == 'I') {
            const bool diagonal = nm.size() >= 2 && (nm.size() == 2 || nm[nm.size() - 1] == nm[nm.size() - 2] ||
                                                     nm.find('_') == std::string::npos);
            v = diagonal ? 2.5 + U(g) : 0.4 * (2 * U(g) - 1);
        } else if (nm == "nz")
            v = 0.5 + 0.5 * U(g);
        x[static_cast<std::size_t>(j)] = v;
    }
    return x;
}

int index_of(const char *const *names, int n, const std::string &name)
{
    for (int k = 0; k < n; ++k)
        if (name == names[k])
            return k;
    return -1;
}

// A double as the exact rational it is.
numeric exact(double x)
{
    int e2 = 0;
    const double m = std::frexp(x, &e2);
    const auto mant = static_cast<long>(std::ldexp(m, 53));
    return numeric(mant) * numeric(2).power(numeric(e2 - 53));
}

numeric num(const ex &e, const exmap &at)
{
    const ex v = e.subs(at).evalf();
    if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
        throw std::runtime_error("not a real number");
    return ex_to<numeric>(v);
}

void evaluate(const std::vector<impactgen::step> &steps, exmap &at)
{
    for (const impactgen::step &st : steps)
        at[st.sym] = num(st.value, at);
}

// The candidate the header selected: stick, else the closed-form slide whose conditions hold,
// else the slide without a closed form at the direction of the tangential impulse returned.
int selected(const impactgen::codegen::code_plan &cp, int regime, exmap &at, const std::vector<double> &out,
             const header_fns &h)
{
    const auto &cases = cp.candidates.cases;
    for (std::size_t k = 0; k < cases.size(); ++k)
        if (regime == static_cast<int>(gen::impact_regime::stick) && cases[k].kind == impactgen::regime::stick)
            return static_cast<int>(k);
    if (regime == static_cast<int>(gen::impact_regime::stick))
        return -1;
    for (std::size_t k = 0; k < cases.size(); ++k) {
        if (cases[k].kind == impactgen::regime::stick)
            continue;
        exmap m = at;
        if (cases[k].needs_angle) {
            const impactgen::problem &q = cp.prob;
            const int N = index_of(h.out_names, h.n_out, "normal_impulse");
            numeric ct = 0, st = 0;
            for (int a = 0; a < q.dimension; ++a) {
                const int F =
                    index_of(h.out_names, h.n_out, "tangential_impulse_" + q.axes[static_cast<std::size_t>(a)]);
                const numeric da = -exact(out[static_cast<std::size_t>(F)]) /
                                   (num(q.contact().friction(), at) * exact(out[static_cast<std::size_t>(N)]));
                ct += da * num(cp.deriv.e_t[static_cast<std::size_t>(a)], at);
                st += da * num(cp.deriv.e_b[static_cast<std::size_t>(a)], at);
            }
            m[cases[k].dir_c] = ct;
            m[cases[k].dir_s] = st;
        }
        evaluate(cases[k].sol.steps, m);
        bool holds = true;
        for (const impactgen::regime_condition &c : cases[k].conditions)
            holds = holds && num(c.value, m) > 0;
        if (holds) {
            at = m;
            return static_cast<int>(k);
        }
    }
    return -1;
}

} // namespace

TEST(friction_jacobian, agrees_with_the_symbolic_jacobian)
{
    const long saved = Digits;
    Digits = 30;
    const long want = std::min(env_or("IMPACTGEN_SAMPLES", 20L), 20L);
    for (const header_fns &h : headers()) {
        if (h.problem.find("tilted-box") != std::string::npos)
            continue; // (its tangent basis is computed at run time: the central differences check it)
        const impactgen::named_class *nc = impactgen::find_named_class(h.problem);
        const impactgen::problem p = nc ? nc->build() : impactgen::load_problem_file(h.problem);
        impactgen::codegen::options o;
        o.name = "f";
        o.jacobian = true;
        o.wrt = h.wrt;
        const impactgen::codegen::code_plan cp = impactgen::codegen::make_code_plan(p, o);
        ASSERT_EQ(static_cast<int>(cp.jacobian.wrt.size()), h.n_wrt);
        std::mt19937_64 g(static_cast<unsigned>(env_or("IMPACTGEN_SEED", 20261207)) + 41u);
        long compared = 0;
        for (int trial = 0; trial < 2000 && compared < want; ++trial) {
            const std::vector<double> x = draw(g, h, false);
            std::vector<double> out(static_cast<std::size_t>(h.n_out)),
                jac(static_cast<std::size_t>(h.n_rows * h.n_wrt));
            int regime = 0;
            if (h.jacobian(x.data(), out.data(), &regime, jac.data()) != gen::friction_status::ok)
                continue;
            exmap at;
            for (int j = 0; j < h.n_in; ++j)
                at[cp.inputs[static_cast<std::size_t>(j)]] = exact(x[static_cast<std::size_t>(j)]);
            evaluate(cp.candidates.shared.steps, at);
            const int k = selected(cp, regime, at, out, h);
            ASSERT_GE(k, 0) << h.problem << ": no candidate holds where the header answered";
            const auto &r = cp.jacobian.candidates[static_cast<std::size_t>(k)];
            const std::string &name = cp.candidates.cases[static_cast<std::size_t>(k)].name;
            evaluate(cp.jacobian.steps, at);
            evaluate(r.steps, at); // the candidate's steps, then the derivative steps
            for (int i = 0; i < h.n_rows; ++i)
                for (int w = 0; w < h.n_wrt; ++w) {
                    const double exact = num(r.entries[static_cast<std::size_t>(i)][static_cast<std::size_t>(w)], at)
                                             .to_double(),
                                 got = jac[static_cast<std::size_t>(i * h.n_wrt + w)];
                    EXPECT_NEAR(got, exact, 1e-7 * (1 + std::fabs(exact)))
                        << h.problem << " " << name << ": d " << h.row_names[i] << " / d " << h.wrt_names[w];
                }
            ++compared;
        }
        EXPECT_GE(compared, want) << h.problem;
    }
    Digits = saved;
}

TEST(friction_jacobian, agrees_with_central_differences_of_the_value_function)
{
    const long want = std::min(env_or("IMPACTGEN_SAMPLES", 40L), 40L);
    for (const header_fns &h : headers()) {
        std::mt19937_64 g(static_cast<unsigned>(env_or("IMPACTGEN_SEED", 20261207)) + 43u);
        long compared = 0;
        int zero_mu = 0;
        for (int trial = 0; trial < 2000 && compared < want; ++trial) {
            const bool mu0 = trial % 10 == 9;
            const std::vector<double> x = draw(g, h, mu0);
            std::vector<double> out(static_cast<std::size_t>(h.n_out)),
                jac(static_cast<std::size_t>(h.n_rows * h.n_wrt));
            int regime = 0;
            if (h.jacobian(x.data(), out.data(), &regime, jac.data()) != gen::friction_status::ok)
                continue;
            bool counted = false;
            for (int w = 0; w < h.n_wrt; ++w) {
                const int j = index_of(h.in_names, h.n_in, h.wrt_names[w]);
                if (mu0 && std::string(h.wrt_names[w]) == "mu")
                    continue;
                const long double step = 1e-6L * (1 + std::fabs(x[static_cast<std::size_t>(j)]));
                std::vector<long double> xp(x.begin(), x.end()), xm(x.begin(), x.end());
                xp[static_cast<std::size_t>(j)] += step;
                xm[static_cast<std::size_t>(j)] -= step;
                std::vector<long double> op(static_cast<std::size_t>(h.n_out)), om(op);
                int rp = 0, rm = 0;
                if (h.value(xp.data(), op.data(), &rp) != gen::friction_status::ok ||
                    h.value(xm.data(), om.data(), &rm) != gen::friction_status::ok || rp != regime || rm != regime)
                    continue; // a regime boundary within the step
                for (int i = 0; i < h.n_rows; ++i) {
                    const auto o = static_cast<std::size_t>(index_of(h.out_names, h.n_out, h.row_names[i]));
                    const double fd = static_cast<double>((op[o] - om[o]) / (2 * step)),
                                 got = jac[static_cast<std::size_t>(i * h.n_wrt + w)];
                    EXPECT_NEAR(got, fd, 1e-6 * (1 + std::fabs(fd)))
                        << h.problem << " trial " << trial << ": d " << h.row_names[i] << " / d " << h.wrt_names[w];
                }
                counted = true;
            }
            compared += counted;
            zero_mu += counted && mu0;
        }
        EXPECT_GE(compared, want) << h.problem;
        EXPECT_GE(zero_mu, 1) << h.problem << ": no impact with mu = 0 compared";
    }
}

TEST(friction_jacobian, status_says_when_the_input_is_on_a_regime_boundary)
{
    for (const header_fns &h : headers()) {
        if (h.problem.find("pinned") != std::string::npos)
            continue; // (no stick candidate: no stick/slide boundary)
        const int mu = index_of(h.in_names, h.n_in, "mu"), N = index_of(h.out_names, h.n_out, "normal_impulse");
        std::mt19937_64 g(static_cast<unsigned>(env_or("IMPACTGEN_SEED", 20261207)) + 47u);
        int boundaries = 0;
        for (int trial = 0; trial < 400 && boundaries < 5; ++trial) {
            std::vector<double> x = draw(g, h, false);
            std::vector<double> out(static_cast<std::size_t>(h.n_out)),
                jac(static_cast<std::size_t>(h.n_rows * h.n_wrt));
            int regime = 0;
            x[static_cast<std::size_t>(mu)] = 1e3; // the stick impulse
            if (h.jacobian(x.data(), out.data(), &regime, jac.data()) != gen::friction_status::ok ||
                regime != static_cast<int>(gen::impact_regime::stick))
                continue;
            double F2 = 0;
            for (int k = 0; k < h.n_out; ++k)
                if (std::string(h.out_names[k]).rfind("tangential_impulse_", 0) == 0)
                    F2 += out[static_cast<std::size_t>(k)] * out[static_cast<std::size_t>(k)];
            const double mu_star = std::sqrt(F2) / out[static_cast<std::size_t>(N)];
            if (!(mu_star > 0.05 && mu_star < 2))
                continue;
            x[static_cast<std::size_t>(mu)] = mu_star;
            EXPECT_EQ(h.jacobian(x.data(), out.data(), &regime, jac.data()), gen::friction_status::ambiguous)
                << h.problem << " at mu = mu* = " << mu_star;
            for (double side : {1 + 1e-4, 1 - 1e-4}) {
                x[static_cast<std::size_t>(mu)] = mu_star * side;
                EXPECT_EQ(h.jacobian(x.data(), out.data(), &regime, jac.data()), gen::friction_status::ok)
                    << h.problem << " at mu = mu* (1 " << (side > 1 ? "+" : "-") << " 1e-4)";
                EXPECT_EQ(regime, static_cast<int>(side > 1 ? gen::impact_regime::stick : gen::impact_regime::slide));
            }
            ++boundaries;
        }
        EXPECT_GE(boundaries, 5) << h.problem;
        // A failing call: its status, jac zero.
        std::vector<double> x = draw(g, h, false), out(static_cast<std::size_t>(h.n_out)),
                            jac(static_cast<std::size_t>(h.n_rows * h.n_wrt), 1.0);
        x[static_cast<std::size_t>(index_of(h.in_names, h.n_in, "e"))] = 2;
        int regime = 0;
        EXPECT_EQ(h.jacobian(x.data(), out.data(), &regime, jac.data()), gen::friction_status::invalid_restitution);
        for (double v : jac)
            EXPECT_EQ(v, 0.0) << h.problem;
    }
}
