// Generated system headers (rule system_sets) against the numeric LCP reference
// (numeric/system_reference.hpp: doubles, Eigen, every active set's whole constrained system,
// 2-D Coulomb friction per contact with its mu: the two-corner landing) on every seeded random
// input, and against the exact closed form (solve_system, CLN) on a subset.
// The cases -- a problem file or a named class, and the inputs chosen with --params -- are
// listed once in tests/codegen/CMakeLists.txt (SYSTEM_CASES), which writes systems_cases.inc:
// adding a class is one line there.
//
// Inputs: masses and moments of inertia log-uniform in [1e-2, 1e2] (mass ratios 1e-4..1e4),
// velocities uniform in [-2, 2] then projected onto the joints and pivots (the bodies' points at
// a joint move together before impact, as the format requires), coefficients uniform in [0, 1],
// other quantities (points) their value in the file. One sample in ten lies on the boundary
// between two candidate sets: the segment between two samples whose sets differ, bisected 50
// times.
#include "systems_cases.inc"

#include "codegen/codegen.hpp"
#include "numeric/system_reference.hpp"
#include "print/expression.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/system.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
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
    const char *const *set_names;
    /// status (0 ok), the outputs, the set and impulses_unique.
    std::function<int(const double *, double *, int &, bool &)> call;
};

std::vector<generated> cases()
{
    std::vector<generated> r;
#define IMPACTGEN_SYSTEM_CASE(fn, source, params)                                                                      \
    r.push_back({#fn, source, params, impactgen::generated::fn##_input_count, impactgen::generated::fn##_output_count, \
                 impactgen::generated::fn##_input_names, impactgen::generated::fn##_output_names,                      \
                 impactgen::generated::fn##_set_names, [](const double *in, double *out, int &set, bool &unique) {     \
                     impactgen::generated::fn##_result<double> res{};                                                  \
                     const int s = static_cast<int>(impactgen::generated::fn<double>(in, res));                        \
                     impactgen::generated::fn##_to_array(res, out);                                                    \
                     set = res.set;                                                                                    \
                     unique = res.impulses_unique;                                                                     \
                     return s;                                                                                         \
                 }});
    IMPACTGEN_SYSTEM_CASES(IMPACTGEN_SYSTEM_CASE)
#undef IMPACTGEN_SYSTEM_CASE
    return r;
}

int env_int(const char *name, int fallback)
{
    const char *s = std::getenv(name);
    return s ? std::atoi(s) : fallback;
}

problem load(const std::string &source)
{
    if (source.size() > 5 && source.substr(source.size() - 5) == ".json")
        return load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/" + source);
    const named_class *c = find_named_class(source);
    if (!c)
        throw std::runtime_error("no class " + source);
    return c->build();
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
        r.contacts.push_back({c.body1, c.body2, dv(c.point), dv(c.normal), print::to_double(p.restitution_of(i)),
                              c.rough, c.rough ? 0.0 : print::to_double(c.friction())});
    }
    return r;
}

// One case: the problem with its parameters as symbols, the sampler, the comparisons.
class system_case
{
public:
    explicit system_case(const generated &g) : g_(g)
    {
        codegen::options o;
        o.params_given = true;
        o.params = split(g.params);
        sym_ = codegen::specialise(load(g.source), o);
        for (const std::string &nm : o.params)
            for (const GiNaC::symbol &s : sym_.parameters())
                if (s.get_name() == nm)
                    symbols_.push_back(s);
        EXPECT_EQ(static_cast<int>(symbols_.size()), g.n_in);
        for (int i = 0; i < g.n_in; ++i)
            EXPECT_EQ(symbols_[static_cast<std::size_t>(i)].get_name(), g.in_names[i]);
    }

    problem numeric(const std::vector<double> &x) const
    {
        GiNaC::lst values;
        for (std::size_t i = 0; i < symbols_.size(); ++i)
            values.append(symbols_[i] == exact(x[i]));
        return substitute(sym_, values);
    }

    std::vector<double> sample(std::mt19937_64 &rng) const
    {
        std::uniform_real_distribution<double> u(0, 1);
        std::vector<double> x;
        for (const GiNaC::symbol &s : symbols_) {
            const std::string n = s.get_name();
            if (n[0] == 'm' && n.rfind("mu", 0) != 0)
                x.push_back(std::pow(10.0, -2 + 4 * u(rng)));
            else if (n[0] == 'I')
                x.push_back(std::pow(10.0, -2 + 4 * u(rng)));
            else if (n[0] == 'v' || n[0] == 'w')
                x.push_back(-2 + 4 * u(rng));
            else
                x.push_back(u(rng));
        }
        return project(x);
    }

    // The velocities moved (least change) so that every joint and pivot holds before impact.
    std::vector<double> project(std::vector<double> x) const
    {
        const ref::sys_problem p = reference_of(numeric(x));
        const Eigen::Index n = 6 * static_cast<Eigen::Index>(p.bodies.size());
        std::vector<Eigen::RowVectorXd> rows;
        std::vector<double> constants;
        for (const ref::sys_link &l : p.links)
            for (int k = 0; k < p.dimension; ++k) {
                Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
                double c = 0;
                ref::detail::add_point(p, r, c, l.body2, l.point, ref::vec3::Unit(k), 1);
                ref::detail::add_point(p, r, c, l.body1, l.point, ref::vec3::Unit(k), -1);
                rows.push_back(r);
                constants.push_back(c);
            }
        if (rows.empty())
            return x;
        // The velocity inputs' slots in the generalized velocities.
        std::vector<std::pair<std::size_t, Eigen::Index>> free;
        for (std::size_t i = 0; i < symbols_.size(); ++i) {
            const std::string n = symbols_[i].get_name();
            for (std::size_t b = 0; b < sym_.bodies.size(); ++b)
                for (int c = 0; c < 3; ++c) {
                    if (sym_.bodies[b].velocity[c].is_equal(symbols_[i]))
                        free.push_back({i, 6 * static_cast<Eigen::Index>(b) + c});
                    if (sym_.bodies[b].angular_velocity[c].is_equal(symbols_[i]))
                        free.push_back({i, 6 * static_cast<Eigen::Index>(b) + 3 + c});
                }
        }
        Eigen::VectorXd v(n);
        for (std::size_t b = 0; b < p.bodies.size(); ++b) {
            v.segment<3>(6 * static_cast<Eigen::Index>(b)) = p.bodies[b].velocity;
            v.segment<3>(6 * static_cast<Eigen::Index>(b) + 3) = p.bodies[b].angular_velocity;
        }
        Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(free.size()));
        Eigen::VectorXd gap(static_cast<Eigen::Index>(rows.size()));
        for (std::size_t r = 0; r < rows.size(); ++r) {
            gap(static_cast<Eigen::Index>(r)) = rows[r].dot(v) + constants[r];
            for (std::size_t k = 0; k < free.size(); ++k)
                A(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = rows[r](free[k].second);
        }
        const Eigen::VectorXd d = A.completeOrthogonalDecomposition().solve(-gap);
        for (std::size_t k = 0; k < free.size(); ++k)
            x[free[k].first] += d(static_cast<Eigen::Index>(k));
        return x;
    }

    struct run {
        int status = -1, set = -1;
        bool unique = true;
        std::vector<double> out;
    };
    run call(const std::vector<double> &x) const
    {
        run r;
        r.out.assign(static_cast<std::size_t>(g_.n_out), 0.0);
        r.status = g_.call(x.data(), r.out.data(), r.set, r.unique);
        return r;
    }

    // The velocity outputs in the order the header writes them, from per-body velocities.
    std::vector<double> velocities(const problem &p, const std::vector<ref::vec3> &v,
                                   const std::vector<ref::vec3> &w) const
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

    const generated &gen() const { return g_; }

private:
    const generated &g_;
    problem sym_;
    std::vector<GiNaC::symbol> symbols_;
};

// The largest difference of the velocity outputs relative to the largest speed before or after.
double velocity_error(const std::vector<double> &a, const std::vector<double> &b, const problem &p)
{
    double scale = 0, err = 0;
    for (const body &B : p.bodies)
        for (int c = 0; c < 3; ++c)
            scale = std::max(
                {scale, std::abs(print::to_double(B.velocity[c])), std::abs(print::to_double(B.angular_velocity[c]))});
    for (std::size_t i = 0; i < a.size(); ++i) {
        scale = std::max({scale, std::abs(a[i]), std::abs(b[i])});
        err = std::max(err, std::abs(a[i] - b[i]));
    }
    return scale > 0 ? err / scale : err;
}

// What the exact closed form says of a numeric problem, for messages.
std::string closed_form_verdict(const problem &p)
{
    std::string conditions;
    for (const system_candidate &c : system_candidates(p)) {
        conditions += "\n  " + c.name() + ":";
        for (const system_condition &k : c.conditions)
            conditions += " " + std::to_string(print::to_double(k.value));
    }
    try {
        return solve_system(p).result.name() + conditions;
    } catch (const std::exception &e) {
        return e.what() + conditions;
    }
}

// Whether the header's set, as the exact closed form has it, holds within rounding (each condition
// >= -1e-7 times its scale: the largest speed before impact for a velocity; for an impulse the
// set's largest contact impulse or that speed times 1 / W_nn of its contact, the larger) and has the header's
// velocities: on a boundary where two sets hold, or where the exact decision finds none by a margin below rounding, the
// header's answer is then a solution of the law to within rounding.
bool nearly_holds(const problem &p, int set, const std::vector<double> &mine, std::string &why)
{
    const std::vector<system_candidate> all = system_candidates(p);
    if (set < 0 || static_cast<std::size_t>(set) >= all.size())
        return why = "no set", false;
    const system_candidate &c = all[static_cast<std::size_t>(set)];
    double vs = 0, is = 0;
    for (const body &b : p.bodies)
        for (int k = 0; k < 3; ++k)
            vs = std::max(
                {vs, std::abs(print::to_double(b.velocity[k])), std::abs(print::to_double(b.angular_velocity[k]))});
    for (std::size_t i = 0; i < c.normal_impulse.size(); ++i) {
        is = std::max(is, std::abs(print::to_double(c.normal_impulse[i])));
        for (int k = 0; k < 3; ++k)
            is = std::max(is, std::abs(print::to_double(c.tangential_impulse[i][k])));
    }
    const system_delassus del = system_delassus_of(p);
    auto unit_mass = [&](std::size_t contact) {
        for (std::size_t r = 0; r < del.rows.size(); ++r)
            if (del.rows[r] == "n" + std::to_string(contact))
                return 1 / print::to_double(del.W[r][r]);
        return 0.0;
    };
    for (const system_condition &k : c.conditions)
        if (print::to_double(k.value) < -1e-7 * (k.velocity ? vs : std::max(is, vs * unit_mass(k.contact))))
            return why = c.name() + ": " + k.meaning + " fails by " + std::to_string(print::to_double(k.value)), false;
    if (mine.empty())
        return true;
    std::vector<ref::vec3> v, w;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        v.push_back(dv(c.velocity[b]));
        w.push_back(dv(c.angular_velocity[b]));
    }
    std::vector<double> theirs;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        if (p.bodies[b].infinite_mass)
            continue;
        for (int k = 0; k < p.dimension; ++k)
            theirs.push_back(v[b][k]);
        if (!p.bodies[b].particle)
            for (int k = p.dimension == 2 ? 2 : 0; k < 3; ++k)
                theirs.push_back(w[b][k]);
    }
    double err = 0, scale = vs;
    for (std::size_t i = 0; i < theirs.size(); ++i) {
        err = std::max(err, std::abs(theirs[i] - mine[i]));
        scale = std::max(scale, std::abs(theirs[i]));
    }
    if (err > 1e-6 * scale)
        return why = c.name() + ": the header's velocities differ by " + std::to_string(err), false;
    return true;
}

// A point on the boundary between two candidate sets: the segment from a to b bisected.
std::vector<double> boundary(const system_case &sc, std::vector<double> a, std::vector<double> b)
{
    const int sa = sc.call(a).set;
    for (int it = 0; it < 50; ++it) {
        std::vector<double> m(a.size());
        for (std::size_t i = 0; i < a.size(); ++i)
            m[i] = (a[i] + b[i]) / 2;
        (sc.call(m).set == sa ? a : b) = m;
    }
    return sc.project(b);
}

// Relative tolerance of the velocities: the contact systems at mass ratios up to 1e4 (and lever
// arms of order one) have condition numbers up to about 1e8, so double's rounding (1.1e-16)
// gives relative errors up to about 1e-8 in the generated code and in the reference; 1e-6 leaves
// a factor 100. At a boundary the two sets' solutions agree (the law's solution is continuous
// there when it is unique), so the same bound applies. With Coulomb friction (two-corner landing:
// mu in [0, 1], m / I from 1e-4 to 1e4, lever arms 1 and 1/2) a sliding contact's row carries
// -s mu times its tangent row, so the slide sets' matrices are not symmetric; with mu <= 1 they
// are as well conditioned as the stick sets' (the reference's worst difference is about 1e-12),
// and at a zero-slip set the velocities are the stick set's, so 1e-6 holds there too.
constexpr double velocity_tolerance = 1e-6;
constexpr int no_solution_status = 10; // friction_status::no_solution
constexpr int ambiguous_status = 11;   // friction_status::ambiguous

class SystemHeaders : public ::testing::TestWithParam<std::size_t>
{
};

TEST_P(SystemHeaders, AgreeWithReferenceAndClosedForm)
{
    static const std::vector<generated> all = cases();
    const generated &g = all.at(GetParam());
    SCOPED_TRACE(g.name + " (" + g.source + " --params " + g.params + ")");
    const system_case sc(g);
    const int n = env_int("IMPACTGEN_SAMPLES", 20000);
    const int n_exact = env_int("IMPACTGEN_EXACT_SAMPLES", 300);
    std::mt19937_64 rng(static_cast<unsigned long long>(env_int("IMPACTGEN_SEED", 20261127)) + GetParam());
    int compared = 0, exact = 0, boundaries = 0, not_ok = 0, ambiguous = 0, alternatives = 0, none = 0;
    double worst = 0, worst_exact = 0;
    for (int s = 0; s < n; ++s) {
        std::vector<double> x = sc.sample(rng);
        bool on_boundary = false;
        if (s % 10 == 9) {
            const std::vector<double> y = sc.sample(rng);
            if (sc.call(x).set != sc.call(y).set) {
                x = boundary(sc, x, y);
                on_boundary = true;
                ++boundaries;
            }
        }
        const system_case::run r = sc.call(x);
        const problem p = sc.numeric(x);
        const std::vector<double> mine(
            r.out.begin(), r.out.begin() + static_cast<long>(sc.velocities(p, std::vector<ref::vec3>(p.bodies.size()),
                                                                           std::vector<ref::vec3>(p.bodies.size()))
                                                                 .size()));
        {
            const ref::sys_answer a = ref::solve_reference(reference_of(p), 1e-9);
            if (a.holding == 0) {
                // No set holds in the reference: the header finds none, or one that holds within rounding.
                std::string why;
                ASSERT_TRUE(r.status == no_solution_status || (r.status == 0 && nearly_holds(p, r.set, mine, why)))
                    << "sample " << s << ": the reference finds no set, the header returns " << r.status << " " << why;
                ++not_ok;
                continue;
            }
            if (r.status == no_solution_status) {
                // The reference's tolerance may accept a set the exact decision rejects: then the
                // closed form must find none either.
                const std::string verdict = closed_form_verdict(p);
                ASSERT_NE(verdict.find("no set"), std::string::npos) << "sample " << s << ": " << verdict;
                ++none;
                continue;
            }
            if (r.status == ambiguous_status) {
                // Two sets hold with different velocities: the closed form must say so too, or on a
                // boundary two sets hold within rounding.
                int near = 0;
                std::string why;
                for (int k = 0; on_boundary && k < static_cast<int>(system_candidates(p).size()); ++k)
                    near += nearly_holds(p, k, {}, why) ? 1 : 0;
                if (near >= 2) {
                    ++ambiguous;
                    continue;
                }
                const std::string verdict = closed_form_verdict(p);
                ASSERT_NE(verdict.find("more than one set"), std::string::npos) << "sample " << s << ": " << verdict;
                ASSERT_GE(a.holding, 2) << "sample " << s;
                ++ambiguous;
                continue;
            }
            ASSERT_EQ(r.status, 0) << "sample " << s << ": the reference solves it (" << a.holding
                                   << " sets hold), the header returns " << r.status
                                   << "; the closed form: " << closed_form_verdict(p);
            const double err = velocity_error(mine, sc.velocities(p, a.velocity, a.angular_velocity), p);
            std::string why;
            if (err > velocity_tolerance && on_boundary && a.holding >= 2) {
                // Two sets hold on this boundary (with different velocities): the header's is one of them.
                ASSERT_TRUE(nearly_holds(p, r.set, mine, why)) << "sample " << s << ": " << why;
                ++alternatives;
                continue;
            }
            worst = std::max(worst, err);
            ASSERT_LE(err, velocity_tolerance) << "sample " << s << ", set " << g.set_names[r.set];
            ++compared;
        }
        if (s % std::max(1, n / std::max(1, n_exact)) == 0) {
            system_answer a;
            try {
                a = solve_system(p);
            } catch (const input_error &e) {
                // On a boundary the header may see one of two sets that hold exactly as its answer.
                std::string why;
                ASSERT_TRUE(r.status == ambiguous_status || (r.status == 0 && nearly_holds(p, r.set, mine, why)))
                    << "sample " << s << ": the closed form refuses (" << e.what() << ") and the header returns "
                    << r.status << " " << why;
                ++alternatives;
                continue;
            }
            ASSERT_EQ(r.status, 0) << "sample " << s << ": the closed form answers " << a.result.name();
            std::vector<ref::vec3> v, w;
            for (std::size_t b = 0; b < p.bodies.size(); ++b) {
                v.push_back(dv(a.result.velocity[b]));
                w.push_back(dv(a.result.angular_velocity[b]));
            }
            const double err = velocity_error(mine, sc.velocities(p, v, w), p);
            worst_exact = std::max(worst_exact, err);
            ASSERT_LE(err, velocity_tolerance)
                << "sample " << s << ": " << a.result.name() << " vs " << g.set_names[r.set];
            ++exact;
        }
    }
    std::cout << g.name << ": " << compared << " compared with the reference (worst " << worst << "), " << exact
              << " with the closed form (worst " << worst_exact << "), " << boundaries << " on a boundary, " << not_ok
              << " with no solution in the reference, " << ambiguous << " ambiguous, " << none << " with no solution, "
              << alternatives << " where the header's set holds within rounding and the exact decision differs\n";
    EXPECT_GE(exact, std::min(n_exact, n) / 2);
    EXPECT_EQ(compared + ambiguous + alternatives + none + not_ok, n);
    EXPECT_GE(compared, n / 2);
    EXPECT_LE(alternatives, n / 100);
    EXPECT_GT(boundaries, 0);
}

// What the exact decision (solve_system, as 'impactgen solve --json' reports it) says: the
// status the header would return for it, the index of its set among the closed form's
// candidates (the first that holds, in the order the header lists them) and impulses_unique;
// with every candidate and whether it holds exactly.
struct exact_verdict {
    int status = 0, set = -1;
    bool unique = true;
    std::string what;
    std::vector<system_candidate> all;
    std::vector<bool> holds;
};

exact_verdict exact_decision(const problem &p)
{
    exact_verdict v;
    try {
        const system_answer a = solve_system(p);
        v.unique = a.impulses_unique;
        v.what = a.result.name();
        v.all = system_candidates(p);
        for (std::size_t k = 0; k < v.all.size(); ++k) {
            v.holds.push_back(system_candidate_failure(v.all[k]) < 0);
            if (v.holds.back() && v.set < 0)
                v.set = static_cast<int>(k);
        }
    } catch (const input_error &e) {
        v.what = e.what();
        v.status = v.what.find("no set") != std::string::npos              ? no_solution_status
                   : v.what.find("more than one set") != std::string::npos ? ambiguous_status
                                                                           : -1;
    }
    return v;
}

// The contact impulses of a candidate, and their largest magnitude.
std::vector<double> contact_impulses(const system_candidate &c, double &scale)
{
    std::vector<double> r;
    for (std::size_t i = 0; i < c.normal_impulse.size(); ++i) {
        r.push_back(print::to_double(c.normal_impulse[i]));
        for (int t = 0; t < 3; ++t)
            r.push_back(print::to_double(c.tangential_impulse[i][t]));
    }
    for (double x : r)
        scale = std::max(scale, std::abs(x));
    return r;
}

// Whether a set that holds exactly with impulses other than the exact set's (impulses_unique
// false) holds clearly: each of its conditions that is not exactly 0 at least 1e-7 times its
// scale (the largest speed before impact for a velocity, the set's largest contact impulse for
// an impulse). On a bisected boundary a set that holds by less than that holds on one side of it
// only, within rounding of the header's inputs.
bool another_split_holds_clearly(const problem &p, const exact_verdict &v)
{
    double vs = 0, is = 0;
    for (const body &b : p.bodies)
        for (int k = 0; k < 3; ++k)
            vs = std::max(
                {vs, std::abs(print::to_double(b.velocity[k])), std::abs(print::to_double(b.angular_velocity[k]))});
    const std::vector<double> mine = contact_impulses(v.all.at(static_cast<std::size_t>(v.set)), is);
    for (std::size_t k = 0; k < v.all.size(); ++k) {
        if (!v.holds[k])
            continue;
        double ks = 0, diff = 0;
        const std::vector<double> theirs = contact_impulses(v.all[k], ks);
        for (std::size_t i = 0; i < mine.size(); ++i)
            diff = std::max(diff, std::abs(mine[i] - theirs[i]));
        bool clear = diff > 1e-7 * std::max(is, ks);
        for (const system_condition &c : v.all[k].conditions) {
            const double x = print::to_double(c.value);
            clear = clear && (x == 0 || x >= 1e-7 * (c.velocity ? vs : ks));
        }
        if (clear)
            return true;
    }
    return false;
}

// The header's status, set index and impulses_unique against the exact decision on seeded
// random inputs (sampled as in AgreeWithReferenceAndClosedForm). Off a boundary all three are
// the same. On a boundary bisected to within 2^-50 the exact decision sees one side: where the
// header's set is the same it must agree on impulses_unique, else its set must hold within
// rounding (nearly_holds). The two-corner landing and the box on four corners have sets with a
// condition that is 0 for every input (a corner's slip that the other corner's sticking fixes at
// 0; the fourth corner's speed, fixed by the other three): wherever they hold the velocities are
// unique and the impulses are not, so impulses_unique false must be seen there.
TEST_P(SystemHeaders, StatusSetAndImpulsesUniqueAsTheExactDecision)
{
    static const std::vector<generated> all = cases();
    const generated &g = all.at(GetParam());
    SCOPED_TRACE(g.name + " (" + g.source + " --params " + g.params + ")");
    const system_case sc(g);
    const int n = env_int("IMPACTGEN_FLAG_SAMPLES", 300);
    std::mt19937_64 rng(static_cast<unsigned long long>(env_int("IMPACTGEN_SEED", 20261127)) + 7 * GetParam() + 3);
    int same = 0, not_unique = 0, refused = 0, boundaries = 0, sides = 0;
    for (int s = 0; s < n; ++s) {
        std::vector<double> x = sc.sample(rng);
        bool on_boundary = false;
        if (s % 10 == 9) {
            const std::vector<double> y = sc.sample(rng);
            if (sc.call(x).set != sc.call(y).set) {
                x = boundary(sc, x, y);
                on_boundary = true;
                ++boundaries;
            }
        }
        const system_case::run r = sc.call(x);
        const problem p = sc.numeric(x);
        const exact_verdict v = exact_decision(p);
        ASSERT_NE(v.status, -1) << "sample " << s << ": " << v.what;
        const std::string at = "sample " + std::to_string(s) + ": exact " + v.what + " (set " + std::to_string(v.set) +
                               ", unique " + std::to_string(v.unique) + "), header status " + std::to_string(r.status) +
                               " set " + std::to_string(r.set) + " unique " + std::to_string(r.unique);
        // On a boundary, sets that hold exactly on its far side by rounding's width (an impulse of
        // 1e-17 where the header computes 0) differ from the exact set's impulses by as little:
        // the header, which compares sets that hold clearly, cannot see that difference.
        const bool unique_by_rounding =
            on_boundary && v.status == 0 && r.unique && !v.unique && !another_split_holds_clearly(p, v);
        if (on_boundary && (r.status != v.status || r.set != v.set || unique_by_rounding)) {
            // One side of the boundary in the exact decision, the other within rounding in the header.
            std::string why;
            ASSERT_TRUE(r.status == ambiguous_status || v.status != 0 ||
                        (r.status == 0 && nearly_holds(p, r.set, {}, why)))
                << at << " " << why;
            ++sides;
            continue;
        }
        ASSERT_EQ(r.status, v.status) << at;
        if (v.status != 0) {
            ++refused;
            continue;
        }
        ASSERT_EQ(r.set, v.set) << at;
        ASSERT_EQ(r.unique, v.unique) << at << closed_form_verdict(p);
        not_unique += v.unique ? 0 : 1;
        ++same;
    }
    std::cout << g.name << ": " << same << " with the exact set and impulses_unique (" << not_unique
              << " of them not unique), " << refused << " refused alike, " << boundaries << " on a boundary, " << sides
              << " of them on the other side within rounding\n";
    EXPECT_EQ(same + refused + sides, n);
    EXPECT_LE(sides, boundaries);
    EXPECT_GT(boundaries, 0);
    if (g.source.find("two-corner") != std::string::npos || g.source.find("four-corners") != std::string::npos)
        EXPECT_GT(not_unique, 0) << "no sample where only the zero-slip or redundant sets hold";
}

INSTANTIATE_TEST_SUITE_P(Cases, SystemHeaders, ::testing::Range<std::size_t>(0, cases().size()),
                         [](const ::testing::TestParamInfo<std::size_t> &info) { return cases()[info.param].name; });

} // namespace

namespace
{
using namespace impactgen;

problem example(const std::string &stem)
{
    return load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/" + stem + ".json");
}

// Sequential impacts with friction and the engine conventions are refused in one line naming
// the key or the option (frictionless sequential impacts are generated: sequence.cpp).
TEST(SystemCodegen, RefusesWhatItDoesNotGenerate)
{
    codegen::options o;
    o.name = "f";
    EXPECT_NO_THROW(codegen::generate(example("three-balls-sequential"), o));
    try {
        problem p = example("three-balls-sequential");
        p.contacts[1].law = coulomb{GiNaC::numeric(1, 3)};
        codegen::generate(p, o);
        ADD_FAILURE() << "sequential impacts with friction accepted";
    } catch (const input_error &e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("contacts[1].friction:"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
    for (int k = 0; k < 3; ++k) {
        codegen::options b = o;
        (k == 0 ? b.inverse_inertia : k == 1 ? b.inverse_mass : b.unit_normal) = true;
        try {
            codegen::generate(example("compass-gait"), b);
            ADD_FAILURE() << "option " << k << " accepted";
        } catch (const codegen::option_error &e) {
            EXPECT_EQ(e.which, k == 0   ? codegen::option_error::inverse_inertia
                               : k == 1 ? codegen::option_error::inverse_mass
                                        : codegen::option_error::unit_normal);
        }
    }
}

// --params and --set on a system behave as on one contact: a symbol of the file is an input or
// given a value, a quantity named in --params becomes an input, an unknown name is refused
// naming the quantities (the contacts' and joints' among them).
TEST(SystemCodegen, ParamsAndSetAsForOneContact)
{
    const std::string text = R"({"dimension": 2, "restitution": "e",
      "bodies": [{"name": "a", "mass": "m", "position": [0, 0], "velocity": ["v", 0]},
                 {"name": "b", "mass": 1, "position": [2, 0], "velocity": [0, 0]},
                 {"name": "c", "mass": 1, "position": [4, 0], "velocity": [0, 0]}],
      "contacts": [{"bodies": ["a", "b"], "point": [1, 0], "normal": [1, 0]},
                   {"bodies": ["b", "c"], "point": [3, 0], "normal": [1, 0]}]})";
    const problem p = read_problem(text, "balls.json");
    codegen::options o;
    o.name = "balls";
    const codegen::header all = codegen::generate(p, o);
    EXPECT_EQ(all.inputs, (std::vector<std::string>{"e", "m", "v"}));
    o.set = {{"e", "1"}};
    o.params_given = true;
    o.params = {"v", "m", "mb"};
    const codegen::header h = codegen::generate(p, o);
    EXPECT_EQ(h.inputs, (std::vector<std::string>{"v", "m", "mb"}));
    EXPECT_NE(h.text.find("balls_set_names[]"), std::string::npos);
    o.params = {"v", "m", "nope"};
    try {
        codegen::generate(p, o);
        ADD_FAILURE() << "an unknown name accepted";
    } catch (const codegen::option_error &e) {
        EXPECT_EQ(e.which, codegen::option_error::params);
        EXPECT_NE(std::string(e.what()).find("O_x_c1"), std::string::npos) << e.what();
    }
    o.params = {"v", "m"};
    o.wrt = {"m", "v"};
    const codegen::header j = codegen::generate(p, o);
    EXPECT_NE(j.text.find("balls_wrt_names[] = {\"m\", \"v\", nullptr}"), std::string::npos);
    o.wrt = {"e"};
    EXPECT_THROW(codegen::generate(p, o), codegen::option_error); // e is given a value, not an input
    o.wrt.clear();
    o.params = {"v"};
    try {
        codegen::generate(p, o);
        ADD_FAILURE() << "a symbol without a value accepted";
    } catch (const codegen::option_error &e) {
        EXPECT_EQ(e.symbol, "m");
    }
}

} // namespace

namespace
{
using namespace impactgen;

struct jacobian_case {
    std::string name, source, params;
    int n_in, n_wrt;
    const char *const *in_names;
    /// status (0 ok, 11 ambiguous at a boundary), the outputs, the set, the Jacobian (velocities x wrt).
    std::function<int(const double *, double *, int &, double *)> call;
};

template <typename F, std::size_t... I> int apply_array(F f, const double *in, std::index_sequence<I...>)
{
    return f(in[I]...);
}

std::vector<jacobian_case> jacobian_cases()
{
    std::vector<jacobian_case> r;
#define IMPACTGEN_SYSTEM_JACOBIAN_CASE(fn, source, params)                                                             \
    r.push_back({#fn, source, params, impactgen::generated::fn##_input_count, impactgen::generated::fn##_wrt_count,    \
                 impactgen::generated::fn##_input_names, [](const double *in, double *out, int &set, double *jac) {    \
                     impactgen::generated::fn##_result<double> res{};                                                  \
                     const int s = apply_array(                                                                        \
                         [&](auto... x) {                                                                              \
                             return static_cast<int>(impactgen::generated::fn##_jacobian<double>(x..., res, jac));     \
                         },                                                                                            \
                         in, std::make_index_sequence<impactgen::generated::fn##_input_count>{});                      \
                     impactgen::generated::fn##_to_array(res, out);                                                    \
                     set = res.set;                                                                                    \
                     return s;                                                                                         \
                 }});
    IMPACTGEN_SYSTEM_JACOBIAN_CASES(IMPACTGEN_SYSTEM_JACOBIAN_CASE)
#undef IMPACTGEN_SYSTEM_JACOBIAN_CASE
    return r;
}

} // namespace

namespace
{

class SystemJacobian : public ::testing::TestWithParam<std::size_t>
{
};

// The Jacobian of the velocities after impact against central differences of the exact closed
// form (solve_system, CLN) at seeded points, each input a double taken as the rational it is:
// h = 2^-20 relative, the step exact, so the difference quotient has no rounding and its
// truncation error is of order h^2 (1e-12) times the third derivative; 1e-6 relative to the
// largest entry of the row leaves room for it. The same set must act at x - h, x and x + h
// (else the point is too near a boundary for a difference quotient and is skipped). On a
// boundary between sets (bisected as in SystemHeaders) the status is ambiguous.
TEST_P(SystemJacobian, AgreesWithCentralDifferencesOfTheClosedForm)
{
    static const std::vector<jacobian_case> all = jacobian_cases();
    const jacobian_case &jc = all.at(GetParam());
    SCOPED_TRACE(jc.name);
    generated g{jc.name, jc.source, jc.params, jc.n_in, 0, jc.in_names, nullptr, nullptr, nullptr};
    ASSERT_EQ(jc.n_wrt, jc.n_in);
    std::vector<double> out(256), jac(256 * 16);
    g.call = [&](const double *in, double *, int &set, bool &unique) {
        unique = true;
        const int st = jc.call(in, out.data(), set, jac.data());
        return st == ambiguous_status ? 0 : st;
    };
    g.n_out = 0;
    const system_case sc(g);
    std::mt19937_64 rng(static_cast<unsigned long long>(env_int("IMPACTGEN_SEED", 20261127)) + 99 + GetParam());
    const int n = env_int("IMPACTGEN_JACOBIAN_SAMPLES", 20);
    int checked = 0, boundary_checked = 0;
    for (int s = 0; s < n; ++s) {
        const std::vector<double> x = sc.sample(rng);
        int set = -1;
        const int status = jc.call(x.data(), out.data(), set, jac.data());
        if (status != 0)
            continue;
        const problem p0 = sc.numeric(x);
        std::string name0;
        try {
            name0 = solve_system(p0).result.name();
        } catch (const input_error &) {
            continue;
        }
        const std::size_t nv = [&] {
            std::size_t c = 0;
            for (const body &b : p0.bodies)
                if (!b.infinite_mass)
                    c += static_cast<std::size_t>(p0.dimension) + (b.particle ? 0 : (p0.dimension == 2 ? 1 : 3));
            return c;
        }();
        bool same_set = true;
        std::vector<std::vector<double>> fd(nv, std::vector<double>(x.size()));
        for (std::size_t j = 0; j < x.size() && same_set; ++j) {
            const double h = std::ldexp(std::max(1.0, std::abs(x[j])), -20);
            std::vector<double> lo = x, hi = x;
            lo[j] -= h;
            hi[j] += h;
            system_answer a, b;
            try {
                a = solve_system(sc.numeric(lo));
                b = solve_system(sc.numeric(hi));
            } catch (const input_error &) {
                same_set = false;
                break;
            }
            same_set = a.result.name() == name0 && b.result.name() == name0;
            std::vector<double> va, vb;
            for (std::size_t k = 0; k < p0.bodies.size(); ++k) {
                if (p0.bodies[k].infinite_mass)
                    continue;
                for (int c = 0; c < p0.dimension; ++c) {
                    va.push_back(print::to_double(a.result.velocity[k][c]));
                    vb.push_back(print::to_double(b.result.velocity[k][c]));
                }
                if (!p0.bodies[k].particle)
                    for (int c = p0.dimension == 2 ? 2 : 0; c < 3; ++c) {
                        va.push_back(print::to_double(a.result.angular_velocity[k][c]));
                        vb.push_back(print::to_double(b.result.angular_velocity[k][c]));
                    }
            }
            for (std::size_t i = 0; i < nv; ++i)
                fd[i][j] = (vb[i] - va[i]) / (2 * h);
        }
        if (!same_set)
            continue;
        for (std::size_t i = 0; i < nv; ++i) {
            double scale = 1e-300;
            for (std::size_t j = 0; j < x.size(); ++j)
                scale = std::max(scale, std::abs(fd[i][j]));
            for (std::size_t j = 0; j < x.size(); ++j)
                EXPECT_NEAR(jac[i * x.size() + j], fd[i][j], 1e-6 * scale)
                    << "sample " << s << ", velocity " << i << ", input " << j << " (" << name0 << ")";
        }
        ++checked;
    }
    // On boundaries: the status says so.
    for (int s = 0; s < 200 && boundary_checked < 5; ++s) {
        const std::vector<double> a = sc.sample(rng), b = sc.sample(rng);
        int sa = -1, sb = -1;
        if (jc.call(a.data(), out.data(), sa, jac.data()) != 0 || jc.call(b.data(), out.data(), sb, jac.data()) != 0 ||
            sa == sb)
            continue;
        const std::vector<double> m = boundary(sc, a, b);
        int sm = -1;
        const int st = jc.call(m.data(), out.data(), sm, jac.data());
        if (st == 0 || st == ambiguous_status) {
            EXPECT_EQ(st, ambiguous_status) << "a boundary between sets " << sa << " and " << sb;
            ++boundary_checked;
        }
    }
    std::cout << jc.name << ": " << checked << " points against central differences, " << boundary_checked
              << " boundaries\n";
    EXPECT_GE(checked, n / 4);
    EXPECT_GT(boundary_checked, 0);
}

INSTANTIATE_TEST_SUITE_P(Cases, SystemJacobian, ::testing::Range<std::size_t>(0, jacobian_cases().size()),
                         [](const ::testing::TestParamInfo<std::size_t> &info) {
                             return jacobian_cases()[info.param].name;
                         });

} // namespace
