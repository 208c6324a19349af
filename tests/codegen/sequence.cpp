// Generated headers of sequential impacts (system_code::sequential: the chain of single-contact
// impacts in a bounded loop) against the exact chain (solve_system, CLN) and against an
// independent numeric chain written here: one contact at a time, each step the Eigen reference
// (numeric/system_reference.hpp's solve_reference) of the system with that contact alone.
// The cases -- three balls, Newton's cradles of 4 and 5 balls, and a double pendulum on a pivot
// struck by a ball, whose upper rod then strikes a second ball (a joint and a pivot acting in
// every step), the inputs chosen with --params
// -- are listed once in tests/codegen/CMakeLists.txt (SEQUENCE_CASES), which writes
// sequence_cases.inc.
//
// Inputs: masses and moments of inertia log-uniform in [1e-2, 1e2] (mass ratios up to 1e4), velocities uniform in
// [-2, 2], each coefficient of restitution uniform in [0, 1] with one draw in ten exactly 0 and
// one in five exactly 1 (e = 0 gives the longest chains: often without end, which solve refuses
// after 64 exact steps, the costliest samples).
#include "sequence_cases.inc"

#include "codegen/codegen.hpp"
#include "numeric/system_reference.hpp"
#include "print/expression.hpp"
#include "symbolic/system.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using namespace impactgen;
namespace ref = impactgen::numeric::systems;

struct generated {
    std::string name, source, params;
    int n_in, n_out;
    const char *const *in_names;
    const char *const *out_names;
    /// status (0 ok), the outputs, the set (the last step's contact) and the number of steps.
    std::function<int(const double *, double *, int &, int &)> call;
};

std::vector<generated> cases()
{
    std::vector<generated> r;
#define IMPACTGEN_SEQUENCE_CASE(fn, source, params)                                                                    \
    r.push_back({#fn, source, params, impactgen::generated::fn##_input_count, impactgen::generated::fn##_output_count, \
                 impactgen::generated::fn##_input_names, impactgen::generated::fn##_output_names,                      \
                 [](const double *in, double *out, int &set, int &steps) {                                             \
                     impactgen::generated::fn##_result<double> res{};                                                  \
                     const int s = static_cast<int>(impactgen::generated::fn<double>(in, res));                        \
                     impactgen::generated::fn##_to_array(res, out);                                                    \
                     set = res.set;                                                                                    \
                     steps = res.steps;                                                                                \
                     return s;                                                                                         \
                 }});
    IMPACTGEN_SEQUENCE_CASES(IMPACTGEN_SEQUENCE_CASE)
#undef IMPACTGEN_SEQUENCE_CASE
    return r;
}

std::vector<std::string> split(const std::string &s)
{
    std::vector<std::string> r;
    std::stringstream is(s);
    std::string item;
    while (std::getline(is, item, ','))
        r.push_back(item);
    return r;
}

// A double as the exact rational it is.
GiNaC::ex exact(double x)
{
    int e = 0;
    const double m = std::frexp(x, &e);
    const long long k = static_cast<long long>(std::ldexp(m, 53));
    return GiNaC::numeric(k) * GiNaC::pow(GiNaC::numeric(2), e - 53);
}

ref::vec3 dv(const vec3 &v)
{
    return {print::to_double(v[0]), print::to_double(v[1]), print::to_double(v[2])};
}

ref::sys_problem reference_of(const problem &p)
{
    ref::sys_problem r;
    r.dimension = p.dimension;
    for (const body &b : p.bodies) {
        ref::sys_body s;
        s.infinite_mass = b.infinite_mass;
        s.particle = b.particle;
        s.mass = b.infinite_mass ? 1 : print::to_double(b.mass);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                s.inertia(i, j) = print::to_double(b.inertia[i][j]);
        s.position = dv(b.position);
        s.velocity = dv(b.velocity);
        s.angular_velocity = dv(b.angular_velocity);
        r.bodies.push_back(s);
    }
    for (const pivot &pv : p.pivots)
        r.links.push_back({ref::fixed_frame, pv.body, dv(pv.point)});
    for (const joint &j : p.joints)
        r.links.push_back({j.body1, j.body2, dv(j.point)});
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const contact_spec &c = p.contacts[i];
        r.contacts.push_back(
            {c.body1, c.body2, dv(c.point), dv(c.normal), print::to_double(p.restitution_of(i)), c.rough, 0.0});
    }
    return r;
}

// The normal speed of contact k (along the unit normal) for the velocities in p.
double speed(const ref::sys_problem &p, std::size_t k)
{
    const Eigen::Index n = 6 * static_cast<Eigen::Index>(p.bodies.size());
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
    Eigen::VectorXd v(n);
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        v.segment<3>(6 * static_cast<Eigen::Index>(b)) = p.bodies[b].velocity;
        v.segment<3>(6 * static_cast<Eigen::Index>(b) + 3) = p.bodies[b].angular_velocity;
    }
    double c = 0;
    const ref::sys_contact &ct = p.contacts[k];
    const ref::vec3 nh = ct.normal.normalized();
    ref::detail::add_point(p, row, c, ct.body2, ct.point, nh, 1);
    ref::detail::add_point(p, row, c, ct.body1, ct.point, nh, -1);
    return row.dot(v) + c;
}

// The independent chain: from the velocities in p, the first contact in list order whose speed is
// below -tol times the scale acts alone (the Eigen reference of the system with only that contact),
// until none approaches; at most max_steps steps (-1 steps beyond).
struct chain {
    int steps = 0;
    bool failed = false; // a step the reference could not solve
    ref::sys_problem state;
    std::vector<double> impulse;
};
chain reference_chain(const ref::sys_problem &p, double tol, int max_steps)
{
    chain r;
    r.state = p;
    r.impulse.assign(p.contacts.size(), 0.0);
    double scale = 0;
    for (const ref::sys_body &b : p.bodies)
        scale = std::max({scale, b.velocity.cwiseAbs().maxCoeff(), b.angular_velocity.cwiseAbs().maxCoeff()});
    for (std::size_t k = 0; k < p.contacts.size(); ++k)
        scale = std::max(scale, std::abs(speed(p, k)));
    for (;;) {
        std::size_t next = p.contacts.size();
        for (std::size_t k = 0; k < p.contacts.size() && next == p.contacts.size(); ++k)
            if (speed(r.state, k) < -tol * scale)
                next = k;
        if (next == p.contacts.size())
            return r;
        if (r.steps == max_steps) {
            r.steps = -1;
            return r;
        }
        ++r.steps;
        ref::sys_problem one = r.state;
        one.contacts = {p.contacts[next]};
        const ref::sys_answer a = ref::solve_reference(one);
        if (a.holding < 1) {
            r.failed = true;
            return r;
        }
        for (std::size_t b = 0; b < p.bodies.size(); ++b) {
            r.state.bodies[b].velocity = a.velocity[b];
            r.state.bodies[b].angular_velocity = a.angular_velocity[b];
        }
        r.impulse[next] += a.normal_impulse[0];
    }
}

// The header's velocity outputs from per-body velocities (the order the header writes them).
std::vector<double> velocities(const problem &p, const std::vector<ref::vec3> &v, const std::vector<ref::vec3> &w)
{
    std::vector<double> r;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        if (p.bodies[b].infinite_mass)
            continue;
        for (int c = 0; c < p.dimension; ++c)
            r.push_back(v[b][c]);
        if (!p.bodies[b].particle)
            for (int c = p.dimension == 2 ? 2 : 0; c < 3; ++c)
                r.push_back(w[b][c]);
    }
    return r;
}

// What one case's samples showed.
struct tally {
    int samples = 0, exact_ok = 0, exact_endless = 0, endless_header_limit = 0, endless_header_ended = 0,
        not_approaching = 0, repeated = 0, steps_differ = 0, reference_steps_differ = 0;
    double exact_error = 0, reference_error = 0;
};

constexpr double tol = 1.4901161193847656e-08; // the header's tolerance in double, 2^-26

class sequence_case
{
public:
    explicit sequence_case(const generated &g) : g_(g)
    {
        codegen::options o;
        o.params_given = true;
        o.params = split(g.params);
        sym_ = codegen::specialise(load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/" + g.source), o);
        for (const std::string &nm : o.params)
            for (const GiNaC::symbol &s : sym_.parameters())
                if (s.get_name() == nm)
                    symbols_.push_back(s);
        EXPECT_EQ(static_cast<int>(symbols_.size()), g.n_in);
    }

    std::vector<double> sample(std::mt19937_64 &rng) const
    {
        std::uniform_real_distribution<double> u(0, 1);
        std::vector<double> x;
        for (const GiNaC::symbol &s : symbols_) {
            const std::string n = s.get_name();
            if (n[0] == 'm' || n[0] == 'I')
                x.push_back(std::pow(10.0, -2 + 4 * u(rng)));
            else if (n[0] == 'v')
                x.push_back(-2 + 4 * u(rng));
            else {
                const double pick = u(rng);
                x.push_back(pick < 0.1 ? 0.0 : pick < 0.3 ? 1.0 : u(rng));
            }
        }
        return x;
    }

    problem numeric(const std::vector<double> &x) const
    {
        GiNaC::lst values;
        for (std::size_t i = 0; i < symbols_.size(); ++i)
            values.append(symbols_[i] == exact(x[i]));
        return substitute(sym_, values);
    }

    // One sample: the header against the exact chain and the independent one.
    void check(const std::vector<double> &x, tally &t) const
    {
        ++t.samples;
        const problem p = numeric(x);
        std::vector<double> out(static_cast<std::size_t>(g_.n_out));
        int set = -1, steps = -1;
        const int status = g_.call(x.data(), out.data(), set, steps);
        const std::size_t nc = p.contacts.size();
        std::vector<ref::vec3> v0, w0;
        double scale = 0;
        for (const body &b : p.bodies) {
            v0.push_back(dv(b.velocity));
            w0.push_back(dv(b.angular_velocity));
            if (!b.infinite_mass)
                scale = std::max({scale, v0.back().cwiseAbs().maxCoeff(), w0.back().cwiseAbs().maxCoeff()});
        }
        // The outputs: velocities, each contact's normal impulse, the joints' and pivots' impulses
        // (world components), the energy lost.
        const auto nv = static_cast<long>(velocities(p, v0, w0).size());
        std::vector<double> vel(out.begin(), out.begin() + nv);
        std::vector<double> imp(out.begin() + nv, out.begin() + nv + static_cast<long>(nc));
        std::vector<double> links(out.begin() + nv + static_cast<long>(nc), out.end() - 1);
        system_answer a;
        try {
            a = solve_system(p);
        } catch (const input_error &e) {
            // The exact chain does not end within 64 steps: the header reaches its limit, or its
            // chain ends where the approach speeds fall below rounding.
            ++t.exact_endless;
            EXPECT_NE(std::string(e.what()).find("does not end within 64 steps"), std::string::npos) << e.what();
            if (status == 10) {
                ++t.endless_header_limit;
                EXPECT_EQ(steps, 65);
            } else {
                EXPECT_EQ(status, 0);
                ++t.endless_header_ended;
            }
            return;
        }
        if (a.sequence.empty()) {
            ++t.not_approaching;
            EXPECT_EQ(status, 5) << g_.name << ": no contact approaches, the header says " << status;
            return;
        }
        ++t.exact_ok;
        ASSERT_EQ(status, 0) << g_.name << ": the exact chain ends after " << a.sequence.size() << " steps";
        std::vector<bool> seen(nc, false);
        bool repeated = false;
        for (std::size_t k : a.sequence) {
            repeated = repeated || seen[k];
            seen[k] = true;
        }
        t.repeated += repeated ? 1 : 0;
        // Steps: the same, unless the exact chain has a step whose approach speed is below
        // rounding (1e-6 of the speeds before): the header does not take it.
        if (steps != static_cast<int>(a.sequence.size())) {
            ++t.steps_differ;
            EXPECT_LT(steps, static_cast<int>(a.sequence.size()));
            double slowest = scale;
            ref::sys_problem st = reference_of(p);
            for (std::size_t s = 0; s < a.sequence.size(); ++s) {
                slowest = std::min(slowest, std::abs(speed(st, a.sequence[s])));
                for (std::size_t b = 0; b < p.bodies.size(); ++b) {
                    st.bodies[b].velocity = dv(a.steps[s].velocity[b]);
                    st.bodies[b].angular_velocity = dv(a.steps[s].angular_velocity[b]);
                }
            }
            EXPECT_LT(slowest, 1e-6 * scale) << g_.name << ": " << steps << " steps, exactly " << a.sequence.size();
        } else {
            EXPECT_EQ(set, static_cast<int>(a.sequence.back()));
        }
        std::vector<ref::vec3> v, w;
        for (std::size_t b = 0; b < p.bodies.size(); ++b) {
            v.push_back(dv(a.result.velocity[b]));
            w.push_back(dv(a.result.angular_velocity[b]));
        }
        const std::vector<double> ev = velocities(p, v, w);
        double err = 0, pscale = 0, perr = 0;
        for (std::size_t i = 0; i < ev.size(); ++i)
            err = std::max(err, std::abs(ev[i] - vel[i]));
        for (std::size_t i = 0; i < nc; ++i) {
            const double P = print::to_double(a.result.normal_impulse[i]);
            pscale = std::max(pscale, std::abs(P));
            perr = std::max(perr, std::abs(P - imp[i]));
        }
        std::vector<double> exact_links;
        for (const std::vector<vec3> *list : {&a.result.joint_impulses, &a.result.pivot_impulses})
            for (const vec3 &J : *list)
                for (int c = 0; c < p.dimension; ++c)
                    exact_links.push_back(print::to_double(J[c]));
        EXPECT_EQ(exact_links.size(), links.size());
        for (std::size_t i = 0; i < std::min(exact_links.size(), links.size()); ++i) {
            pscale = std::max(pscale, std::abs(exact_links[i]));
            perr = std::max(perr, std::abs(exact_links[i] - links[i]));
        }
        if (steps == static_cast<int>(a.sequence.size()))
            t.exact_error = std::max({t.exact_error, err / scale, pscale > 0 ? perr / pscale : perr});
        // A step the header does not take (its approach below tol times the speeds before) changes
        // the velocities by at most (1 + e) times that speed and the impulses by the masses times it.
        double mmax = 0;
        for (const body &b : p.bodies)
            mmax = std::max(mmax, print::to_double(b.mass));
        const bool skipped = steps != static_cast<int>(a.sequence.size());
        EXPECT_LE(err, skipped ? 4 * tol * scale : 1e-9 * scale) << g_.name << ": velocities";
        EXPECT_LE(perr, skipped ? 4 * tol * scale * mmax : 1e-9 * pscale) << g_.name << ": impulses";
        if (skipped)
            return;
        const double T0 = print::to_double(a.energy_before), T1 = print::to_double(a.energy_after);
        EXPECT_NEAR(out.back(), T0 - T1, 1e-9 * std::max(T0, 1e-300)) << g_.name << ": energy lost";
        // The independent chain.
        const chain c = reference_chain(reference_of(p), tol, 64);
        ASSERT_FALSE(c.failed);
        ASSERT_GT(c.steps, 0);
        t.reference_steps_differ += c.steps != steps ? 1 : 0;
        std::vector<ref::vec3> rv, rw;
        for (const ref::sys_body &b : c.state.bodies) {
            rv.push_back(b.velocity);
            rw.push_back(b.angular_velocity);
        }
        const std::vector<double> cv = velocities(p, rv, rw);
        double rerr = 0, rperr = 0;
        for (std::size_t i = 0; i < cv.size(); ++i)
            rerr = std::max(rerr, std::abs(cv[i] - vel[i]));
        for (std::size_t i = 0; i < nc; ++i)
            rperr = std::max(rperr, std::abs(c.impulse[i] - imp[i]));
        t.reference_error = std::max({t.reference_error, rerr / scale, pscale > 0 ? rperr / pscale : rperr});
        EXPECT_LE(rerr, 1e-8 * scale) << g_.name << ": velocities against the reference chain";
        EXPECT_LE(rperr, 1e-8 * pscale) << g_.name << ": impulses against the reference chain";
    }

private:
    const generated &g_;
    problem sym_;
    std::vector<GiNaC::symbol> symbols_;
};

// Bounds: 1e-9 of the largest speed before (velocities) or of the largest summed impulse, against
// the exact chain: a chain of at most 64 steps of one closed form each, each step rounding the
// state by a few eps times (1 + e) / mass ratio terms up to 1e4, stays below 64 * 1e-12; 1e-8
// against the reference chain, whose LU solves add their own rounding of the same order.
TEST(SequenceHeaders, AgreeWithTheExactChainAndTheReferenceChain)
{
    for (const generated &g : cases()) {
        SCOPED_TRACE(g.name);
        const sequence_case sc(g);
        std::mt19937_64 rng(2222);
        tally t;
        for (int i = 0; i < 80; ++i)
            sc.check(sc.sample(rng), t);
        std::printf("%s: %d samples, %d chains ended exactly (%d with a contact acting twice), %d without end "
                    "(header: %d at its limit, %d ended below rounding), %d not approaching; steps fewer than "
                    "exact %d, differ from the reference chain %d; largest relative error %.2e (exact), %.2e "
                    "(reference)\n",
                    g.name.c_str(), t.samples, t.exact_ok, t.repeated, t.exact_endless, t.endless_header_limit,
                    t.endless_header_ended, t.not_approaching, t.steps_differ, t.reference_steps_differ, t.exact_error,
                    t.reference_error);
        // Coverage: the balls' chains often repeat a contact and, with e = 0, reach the limit; the
        // pendulum's ball approaches in half the samples (its velocity's sign) and rarely repeats.
        const bool balls = g.name.rfind("pendulum", 0) != 0;
        EXPECT_GE(t.exact_ok, balls ? t.samples / 2 : t.samples / 3);
        EXPECT_GE(t.repeated, balls ? 5 : 1) << "chains of several passes";
        EXPECT_LE(t.steps_differ, t.samples / 20);
        EXPECT_LE(t.reference_steps_differ, t.samples / 20);
        if (balls) {
            EXPECT_GE(t.exact_endless, 1);
            EXPECT_GE(t.endless_header_limit, 1) << "chains that reach the step limit";
        }
    }
}

// The published contrast: three equal balls at e = 1 leave as (0, 0, v); a cradle of five at e = 1
// passes the velocity on in four steps; at e = 0 the chain has no end in exact arithmetic (solve
// refuses it after 64 steps), and the header returns no_solution with steps = max_steps + 1.
TEST(SequenceHeaders, CradleAndStepLimit)
{
    using namespace impactgen::generated;
    three_balls_sequential_result<double> r3{};
    ASSERT_EQ(three_balls_sequential<double>(1.0, 1.0, 1.0, 1.0, 0.0, 1.0, 0.0, r3), friction_status::ok);
    EXPECT_EQ(r3.v_xa, 0.0);
    EXPECT_EQ(r3.v_xb, 0.0);
    EXPECT_EQ(r3.v_xc, 1.0);
    EXPECT_EQ(r3.steps, 2);
    EXPECT_EQ(r3.set, 1);
    cradle5_sequential_result<double> r{};
    ASSERT_EQ(cradle5_sequential<double>(1, 1, 1, 1, 1, 1, 1, 0, 1, 0, 1, 0, 1, 0, r), friction_status::ok);
    EXPECT_EQ(r.steps, 4);
    EXPECT_EQ(r.v_xt, 1.0);
    EXPECT_EQ(r.v_xp, 0.0);
    // The limit as a template argument: 4 steps needed, 3 allowed.
    EXPECT_EQ((cradle5_sequential<double, true, 3>(1, 1, 1, 1, 1, 1, 1, 0, 1, 0, 1, 0, 1, 0, r)),
              friction_status::no_solution);
    EXPECT_EQ(r.steps, 4);
    EXPECT_EQ(r.v_xp, 1.0) << "the state unchanged";
    EXPECT_EQ(r.normal_impulse_c0, 0.0);
    EXPECT_EQ((cradle5_sequential<double, true, 4>(1, 1, 1, 1, 1, 1, 1, 0, 1, 0, 1, 0, 1, 0, r)), friction_status::ok);
    EXPECT_EQ(cradle5_sequential_max_steps, 64);
    ASSERT_EQ(cradle5_sequential<double>(0, 0, 0, 0, 1, 1, 1, 0, 1, 0, 1, 0, 1, 0, r), friction_status::no_solution);
    EXPECT_EQ(r.steps, 65);
    problem p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/tests/codegen/sequence/cradle-5.json");
    for (contact_spec &c : p.contacts)
        c.restitution = 0;
    EXPECT_THROW(solve_system(p), input_error);
    // No contact approaches; a NaN input.
    EXPECT_EQ(cradle5_sequential<double>(1, 1, 1, 1, 1, -1, 1, 0, 1, 0, 1, 0, 1, 0, r),
              friction_status::not_approaching);
    EXPECT_EQ(cradle5_sequential<double>(1, 1, 1, 1, 1, std::nan(""), 1, 0, 1, 0, 1, 0, 1, 0, r),
              friction_status::non_finite_input);
    // float and long double: the same chain.
    cradle5_sequential_result<float> rf{};
    cradle5_sequential_result<long double> rl{};
    ASSERT_EQ(cradle5_sequential<float>(0.5f, 0.5f, 0.5f, 0.5f, 1, 1, 1, 0, 1, 0, 1, 0, 1, 0, rf), friction_status::ok);
    ASSERT_EQ(cradle5_sequential<long double>(0.5L, 0.5L, 0.5L, 0.5L, 1, 1, 1, 0, 1, 0, 1, 0, 1, 0, rl),
              friction_status::ok);
    ASSERT_EQ(cradle5_sequential<double>(0.5, 0.5, 0.5, 0.5, 1, 1, 1, 0, 1, 0, 1, 0, 1, 0, r), friction_status::ok);
    EXPECT_EQ(rf.steps, r.steps);
    EXPECT_EQ(rl.steps, r.steps);
    EXPECT_NEAR(static_cast<double>(rf.v_xt), r.v_xt, 1e-5);
    EXPECT_NEAR(static_cast<double>(rl.v_xt), r.v_xt, 1e-14);
}

// The codegen refusals of sequential impacts: friction names the contact's key; --jacobian.
TEST(SequenceHeaders, Refusals)
{
    problem p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/tests/codegen/sequence/cradle-4.json");
    p.contacts[1].law = coulomb{GiNaC::numeric(1, 2)};
    codegen::options o;
    o.name = "cradle4";
    try {
        codegen::generate(p, o);
        ADD_FAILURE() << "friction accepted";
    } catch (const input_error &e) {
        EXPECT_NE(std::string(e.what()).find("contacts[1].friction"), std::string::npos) << e.what();
    }
    p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/tests/codegen/sequence/cradle-4.json");
    o.jacobian = true;
    EXPECT_THROW(codegen::generate(p, o), codegen::option_error);
}

} // namespace
