// The named system classes (symbolic/named_systems.hpp): each is found by name, is a symbolic
// system whose worked example is the example file's problem, and carries the published
// results in its closed form -- the compass gait's two conserved angular momenta, the three
// balls' simultaneous and sequential answers, the double pendulum's impulse as derived by hand.
#include "print/answer.hpp"
#include "print/formulas.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/derivation.hpp"
#include "symbolic/named_systems.hpp"
#include "symbolic/system.hpp"
#include "symbolic/system_jacobian.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <chrono>
#include <cstdio>
#include <random>
#include <sys/wait.h>

using namespace impactgen;
using GiNaC::ex;

namespace {

problem from_file(const std::string& name)
{
    return load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/" + name);
}

bool same(const ex& a, const ex& b) { return GiNaC::normal(GiNaC::expand(a - b)).is_zero(); }

const system_candidate& candidate(const std::vector<system_candidate>& cs, const std::string& name)
{
    for (const system_candidate& c : cs)
        if (c.name() == name)
            return c;
    throw std::runtime_error("no candidate " + name);
}

ex S(const std::string& name) { return symbol_named(name); }

// Angular momentum about O (z component) of body b of p with velocity v and spin w.
ex H(const problem& p, std::size_t b, const vec3& O, const vec3& v, const vec3& w)
{
    const body& B = p.bodies[b];
    return B.inertia[2][2] * w[2] + cross(B.position - O, B.mass * v)[2];
}

} // namespace

// Every class is found by name, is a symbolic system, and its worked example gives every
// symbol a number.
TEST(NamedSystems, FoundByNameSymbolicWithAWorkedExample)
{
    ASSERT_EQ(system_classes().size(), 4u);
    for (const named_class& c : system_classes()) {
        SCOPED_TRACE(c.name);
        ASSERT_EQ(find_named_class(c.name), &c);
        const problem p = c.build();
        EXPECT_TRUE(p.is_system());
        EXPECT_FALSE(p.is_numeric());
        validate(p);
        const problem q = substitute(p, system_class_example_values(c.name));
        EXPECT_TRUE(q.is_numeric()) << "the example leaves symbols";
        validate(q);
        EXPECT_NO_THROW(solve_system(q));
    }
    EXPECT_TRUE(system_class_example("central-direct").empty());
}

// The worked example of each class is the example file of the same system: the same answer,
// exactly (the file was written independently, with its own numbers).
TEST(NamedSystems, WorkedExampleIsTheExampleFile)
{
    const std::pair<const char*, const char*> pairs[] = {{"compass-gait", "compass-gait.json"},
                                                         {"three-balls", "three-balls-simultaneous.json"},
                                                         {"double-pendulum-struck", "double-pendulum-struck.json"},
                                                         {"two-corner-landing", "two-corner-landing.json"}};
    for (const auto& [name, file] : pairs) {
        SCOPED_TRACE(name);
        const problem q = substitute(find_named_class(name)->build(), system_class_example_values(name));
        const problem f = from_file(file);
        const system_answer a = solve_system(q), b = solve_system(f);
        ASSERT_EQ(a.result.velocity.size(), b.result.velocity.size());
        for (std::size_t k = 0; k < a.result.velocity.size(); ++k)
            for (int i = 0; i < 3; ++i) {
                EXPECT_TRUE(same(a.result.velocity[k][i], b.result.velocity[k][i]));
                EXPECT_TRUE(same(a.result.angular_velocity[k][i], b.result.angular_velocity[k][i]));
            }
        for (std::size_t i = 0; i < a.result.normal_impulse.size(); ++i)
            EXPECT_TRUE(same(a.result.normal_impulse[i], b.result.normal_impulse[i]));
        EXPECT_EQ(a.result.regimes, b.result.regimes);
    }
}

// Heel strike, in symbols (m, I_C, a, h, w1, w2): in the candidate where the swing foot S sticks
// and the stance foot lifts off, only S's impulse acts on the walker, so its angular momentum
// about S is conserved, and only the hip's impulse acts on the trailing (stance) leg, so its
// angular momentum about the hip is conserved -- the two balances of the walking literature
// (Goswami, Thuilot and Espiau 1998, for point masses; here with the legs' inertia). Both are
// substituted and simplified to zero; S is at rest after impact (plastic, no slip).
TEST(NamedSystems, CompassGaitConservesTheTwoAngularMomenta)
{
    const problem p = find_named_class("compass-gait")->build();
    const std::vector<system_candidate> cs = system_candidates(p);
    const system_candidate& c = candidate(cs, "{0 stick, 1 open}");
    const vec3 S = p.contacts[0].point, hip = p.joints[0].point;
    const ex before = H(p, 1, S, p.bodies[1].velocity, p.bodies[1].angular_velocity) +
                      H(p, 2, S, p.bodies[2].velocity, p.bodies[2].angular_velocity);
    const ex after = H(p, 1, S, c.velocity[1], c.angular_velocity[1]) + H(p, 2, S, c.velocity[2], c.angular_velocity[2]);
    EXPECT_TRUE(same(before, after)) << before << " vs " << after;
    EXPECT_TRUE(same(H(p, 1, hip, p.bodies[1].velocity, p.bodies[1].angular_velocity),
                     H(p, 1, hip, c.velocity[1], c.angular_velocity[1])));
    const vec3 foot = point_velocity(p.bodies[2], c.velocity[2], c.angular_velocity[2], S);
    EXPECT_TRUE(same(foot[0], 0) && same(foot[1], 0));
    // The balances do not hold for a wrong answer: the velocities before impact.
    EXPECT_FALSE(same(H(p, 2, S, p.bodies[2].velocity, p.bodies[2].angular_velocity),
                      H(p, 2, S, c.velocity[2], c.angular_velocity[2])));
}

// Three equal balls, the first at v: simultaneous, both contacts act and the closed form is
// ((1 - 2e)/3, (1 + e)/3, (1 + e)/3) v (momentum, and u' = e u at both contacts with u_1 = 0);
// sequential at e = 1 (each collision of equal balls exchanges their velocities) (0, 0, v),
// for any m and v > 0.
TEST(NamedSystems, ThreeBallsPublishedResults)
{
    const problem p = find_named_class("three-balls")->build();
    const ex e = S("e"), v = S("v");
    const std::vector<system_candidate> cs = system_candidates(p);
    const system_candidate& c = candidate(cs, "{0 smooth, 1 smooth}");
    EXPECT_TRUE(same(c.velocity[0][0], (1 - 2 * e) * v / 3)) << c.velocity[0][0];
    EXPECT_TRUE(same(c.velocity[1][0], (1 + e) * v / 3)) << c.velocity[1][0];
    EXPECT_TRUE(same(c.velocity[2][0], (1 + e) * v / 3)) << c.velocity[2][0];
    for (const char* m : {"1", "7/3", "1/1000"})
        for (const char* speed : {"1", "5/2"}) {
            problem q = substitute(p, GiNaC::lst{S("m") == parse_value(m, true, "m"), S("R") == 1,
                                                 v == parse_value(speed, true, "v"), e == 1});
            q.sequential = true;
            const system_answer a = solve_system(q);
            const ex V = parse_value(speed, true, "v");
            EXPECT_EQ(a.result.velocity[0][0], 0);
            EXPECT_EQ(a.result.velocity[1][0], 0);
            EXPECT_EQ(a.result.velocity[2][0], V);
            EXPECT_EQ(a.sequence, (std::vector<std::size_t>{0, 1}));
        }
}

// Double pendulum (rods m, l; ball M at v; e), derived by hand with the rods' angular
// velocities w1 (upper), w2 (lower): a point at depth s on a hanging rod moves at s w along x,
// so the tip moves at l (w1 + w2) and the lower centre at l (w1 + w2/2). The kinetic energy
//   T = 1/2 [ (m l^2/3) w1^2 + m l^2 (w1 + w2/2)^2 + (m l^2/12) w2^2 ]
// gives the mass matrix m l^2 [[4/3, 1/2], [1/2, 1/3]] (det 7/36), inverse
// [[12/7, -18/7], [-18/7, 48/7]]/(m l^2). The impulse P at the tip along x is the generalized
// impulse (l P, l P): dw = P/(m l) (-6/7, 30/7), the tip gains 24 P/(7 m), the ball loses P/M.
// Restitution (the tip at rest, the ball at v: u' = e v): 24 P/(7 m) + P/M = (1 + e) v, so
//   P = 7 m M (1 + e) v / (24 M + 7 m),  w1' = -6 P/(7 m l),  w2' = 30 P/(7 m l),  V' = v - P/M.
TEST(NamedSystems, DoublePendulumAgreesWithTheHandDerivation)
{
    const problem p = find_named_class("double-pendulum-struck")->build();
    const ex m = S("m"), l = S("l"), M = S("M"), v = S("v"), e = S("e");
    const std::vector<system_candidate> cs = system_candidates(p);
    const system_candidate& c = candidate(cs, "{0 smooth}");
    const ex P = 7 * m * M * (1 + e) * v / (24 * M + 7 * m);
    EXPECT_TRUE(same(c.normal_impulse[0], P)) << c.normal_impulse[0];
    EXPECT_TRUE(same(c.angular_velocity[0][2], -6 * P / (7 * m * l)));
    EXPECT_TRUE(same(c.angular_velocity[1][2], 30 * P / (7 * m * l)));
    EXPECT_TRUE(same(c.velocity[2][0], v - P / M));
    EXPECT_FALSE(same(c.velocity[2][0], v));
}

// The box landing on two corners: the class's corners rest and strike as its description says
// (the right corner's normal velocity is 0, the left's -2 a w), for the symbols.
TEST(NamedSystems, TwoCornerLandingOneCornerStrikesTheOtherRests)
{
    const problem p = find_named_class("two-corner-landing")->build();
    const body& box = p.bodies[1];
    const vec3 left = point_velocity(box, p.contacts[0].point), right = point_velocity(box, p.contacts[1].point);
    EXPECT_TRUE(same(right[1], 0));
    EXPECT_TRUE(same(left[1], -2 * S("a") * S("w")));
    const std::vector<system_candidate> cs = system_candidates(p);
    // open, stick, slide + and - at each corner (16 sets), the set where both stick giving more
    // than one basic solution (its impulses are not unique: the box has three degrees of freedom)
    std::set<std::string> names;
    for (const system_candidate& c : cs)
        names.insert(c.name());
    EXPECT_EQ(names.size(), 16u);
}

// Where one corner sticks the other cannot slip (both lie on the ground line and move alike
// along it), and where both stick only the sum of their friction impulses is fixed. The law
// holds whenever some split fits both friction cones; where no basic split does (neither corner
// alone can carry the whole friction impulse), a split with one impulse on its cone's edge (a
// slide with zero slip) does. A grid of landings, each decided exactly: never refused where a
// split fits, every answer obeys Coulomb's law at both corners, and the impulses are not unique.
TEST(NamedSystems, TwoCornerLandingEverySplitThatFitsIsFound)
{
    const problem p = find_named_class("two-corner-landing")->build();
    using GiNaC::numeric;
    int edge_only = 0, answered = 0;
    for (const numeric& b : {numeric(1, 2), numeric(1), numeric(2)})
        for (const numeric& mu : {numeric(1, 5), numeric(1, 2), numeric(1)})
            for (const numeric& vx : {numeric(-2), numeric(-1), numeric(0), numeric(1), numeric(2)})
                for (const numeric& w : {numeric(-2), numeric(1), numeric(2)}) {
                    const problem q = substitute(p, GiNaC::lst{S("m") == 1, S("a") == 1, S("b") == b, S("e") == numeric(1, 2),
                                                               S("mu") == mu, S("v_x") == vx, S("w") == w});
                    bool basic_stick = false;
                    for (const system_candidate& c : system_candidates(q))
                        if (c.name() == "{0 stick, 1 stick}")
                            basic_stick = basic_stick || system_candidate_failure(c) < 0;
                    system_answer a;
                    try {
                        a = solve_system(q);
                    } catch (const input_error& e) {
                        continue; // e.g. not an impact, or a foot that would have to pull
                    }
                    ++answered;
                    body after = q.bodies[1];
                    after.velocity = a.result.velocity[1];
                    after.angular_velocity = a.result.angular_velocity[1];
                    for (std::size_t i = 0; i < 2; ++i) {
                        const ex P = a.result.normal_impulse[i], F = a.result.tangential_impulse[i][0];
                        const vec3 u0 = point_velocity(q.bodies[1], q.contacts[i].point);
                        const vec3 u1 = point_velocity(after, q.contacts[i].point);
                        EXPECT_NE(decide(P), decision::negative);
                        EXPECT_NE(decide(u1[1] + numeric(1, 2) * u0[1]), decision::negative);
                        EXPECT_EQ(decide(P * (u1[1] + numeric(1, 2) * u0[1])), decision::zero);
                        EXPECT_NE(decide(mu * P - abs(F)), decision::negative) << "outside the cone";
                        if (decide(P) == decision::positive && decide(mu * P - abs(F)) == decision::positive) {
                            EXPECT_EQ(decide(u1[0]), decision::zero) << "inside the cone and slipping";
                        }
                        if (decide(u1[0]) != decision::zero) { // slipping: F opposes the slip, on the edge
                            EXPECT_EQ(decide(F + mu * P * u1[0] / abs(u1[0])), decision::zero);
                        }
                    }
                    if (!basic_stick && a.result.regimes[0] != contact_regime::open &&
                        a.result.regimes[1] != contact_regime::open &&
                        decide(point_velocity(after, q.contacts[0].point)[0]) == decision::zero) {
                        ++edge_only; // both corners stick, at a split no basic solution gives
                        // the split is unique only where both impulses are on their cones' edges
                        bool both_edges = true;
                        for (std::size_t k = 0; k < 2; ++k)
                            both_edges = both_edges && decide(mu * a.result.normal_impulse[k] -
                                                              abs(a.result.tangential_impulse[k][0])) == decision::zero;
                        EXPECT_EQ(a.impulses_unique, both_edges) << a.result.name();
                    }
                }
    EXPECT_GT(answered, 50);
    EXPECT_GT(edge_only, 0) << "the grid holds no landing whose split is only on a cone's edge";
}

// The plain-text answer and formulas of a system count in words, and a body named by a number
// is "body 1", not a bare "1:".
TEST(NamedSystems, TextCountsInWordsAndNamesNumberedBodies)
{
    const problem p = find_named_class("three-balls")->build();
    const problem q = substitute(p, GiNaC::lst{S("m") == 1, S("R") == 1, S("e") == 1, S("v") == 1});
    const std::string t = print::system_answer_text(q, solve_system(q));
    EXPECT_NE(t.find("System of three bodies, two contacts, no joint, no pivot;"), std::string::npos) << t;
    EXPECT_NE(t.find("\n  body 1:\n"), std::string::npos) << t;
    EXPECT_EQ(t.find("\n  1:"), std::string::npos) << t;
    EXPECT_EQ(t.find("(s)"), std::string::npos) << t;
    const std::string f = print::system_formulas_text(find_named_class("compass-gait")->build(), false);
    EXPECT_EQ(f.rfind("System: two contacts, one joint, no pivot. ", 0), 0u) << f.substr(0, 80);
    const std::string d = print::system_answer_text(from_file("double-pendulum-struck.json"),
                                                    solve_system(from_file("double-pendulum-struck.json")));
    EXPECT_EQ(d.rfind("System of three bodies, one contact, one joint, one pivot;", 0), 0u) << d.substr(0, 80);
}

// formulas --jacobian of a system: every candidate set's derivatives of the velocities after
// impact against central finite differences of its closed form, at seeded random rational
// points (exact arithmetic, step 1e-4 of the value: the difference's error is of order h^2
// times the third derivative, far below the 1e-5 relative bound), for two named classes; --wrt
// chooses the columns, and a name that is not a symbol is refused naming --wrt.
TEST(NamedSystems, JacobianOfEverySetMatchesCentralDifferences)
{
    using GiNaC::numeric;
    std::mt19937 g(2026);
    for (const char* name : {"compass-gait", "double-pendulum-struck"}) {
        const problem p = find_named_class(name)->build();
        const system_jacobian j = system_jacobian_of(p, {});
        ASSERT_EQ(j.wrt.size(), p.parameters().size());
        ASSERT_EQ(j.sets.size(), system_candidates(p).size());
        int checked = 0;
        for (int trial = 0; trial < 3; ++trial) {
            std::vector<numeric> x; // masses, lengths, e in (0, 1); speeds of either sign
            for (const GiNaC::symbol& s : j.wrt) {
                const numeric r(std::uniform_int_distribution<int>(1, 999)(g), 1000);
                const std::string n = s.get_name();
                const bool speed = n == "w1" || n == "w2" || n == "v" || n == "w" || n == "v_x";
                x.push_back(speed ? 2 * r - 1 : n == "e" ? r : 1 + 3 * r);
            }
            auto at = [&](std::size_t moved, const numeric& h) {
                GiNaC::lst l;
                for (std::size_t k = 0; k < x.size(); ++k)
                    l.append(j.wrt[k] == (k == moved ? x[k] + h : x[k]));
                return l;
            };
            for (const system_set_jacobian& s : j.sets)
                for (std::size_t o = 0; o < j.outputs.size(); ++o) {
                    const system_velocity_output& out = j.outputs[o];
                    const ex v = (out.angular ? s.candidate.angular_velocity : s.candidate.velocity)[out.body]
                                                                                                 [static_cast<std::size_t>(out.component)];
                    for (std::size_t w = 0; w < j.wrt.size(); ++w) {
                        const numeric h = (abs(x[w]) + 1) / 10000;
                        const ex fd = (v.subs(at(w, h)) - v.subs(at(w, -h))) / (2 * h);
                        const ex d = s.entries[o][w].subs(at(w, 0));
                        const double a = GiNaC::ex_to<numeric>(GiNaC::evalf(d)).to_double(),
                                     b = GiNaC::ex_to<numeric>(GiNaC::evalf(fd)).to_double();
                        EXPECT_NEAR(a, b, 1e-5 * (1 + std::abs(a))) << name << " " << s.candidate.name() << " d/d "
                                                                  << j.wrt[w].get_name();
                        ++checked;
                    }
                }
        }
        EXPECT_GT(checked, 100) << name;
        const system_jacobian one = system_jacobian_of(p, {j.wrt.back().get_name()});
        ASSERT_EQ(one.wrt.size(), 1u);
        EXPECT_TRUE(same(one.sets[0].entries[0][0], j.sets[0].entries[0][j.wrt.size() - 1]));
        EXPECT_THROW(system_jacobian_of(p, {"nonesuch"}), input_error);
    }
}

namespace {
// Runs the command line; its exit status and the wall time in seconds.
int run_timed(const std::string& args, double& seconds, std::string& out)
{
    const auto t0 = std::chrono::steady_clock::now();
    FILE* f = popen((std::string(IMPACTGEN_CLI) + " " + args + " 2>&1").c_str(), "r");
    out.clear();
    char buf[4096];
    for (std::size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;)
        out.append(buf, n);
    const int status = pclose(f);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return WEXITSTATUS(status);
}
} // namespace

// A 4-body, 3-contact problem file with every mass a symbol: formulas and explain (every
// format) finish within the default time budget (10 s: the watchdog would stop them with exit 1).
TEST(Cli, FourBodiesThreeContactsWithinTheTimeBudget)
{
    const std::string file = std::string(IMPACTGEN_SOURCE_DIR) + "/tests/core/systems/four-bodies-three-contacts.json";
    for (const char* cmd : {"formulas", "formulas --format json", "explain", "explain --format latex",
                            "explain --format html", "explain --level summary --format latex"}) {
        double seconds = 0;
        std::string out;
        EXPECT_EQ(run_timed(std::string(cmd) + " '" + file + "'", seconds, out), 0) << cmd << ": " << out;
        EXPECT_LT(seconds, 10.0) << cmd;
        std::cout << "  " << cmd << ": " << seconds << " s\n";
    }
}

// solve CLASS --set: the worked example's numbers give the example file's answer; a name the
// class does not have, or a value with a symbol, is refused in one line naming --set.
TEST(Cli, SolveNamedSystemClassWithSet)
{
    double seconds = 0;
    std::string a, b;
    ASSERT_EQ(run_timed("solve compass-gait --json --set m=5,I_C=97/240,a=2/5,h=9/10,w1=-6/5,w2=2/5", seconds, a), 0) << a;
    ASSERT_EQ(run_timed("solve --json '" + std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/compass-gait.json'",
                        seconds, b),
              0);
    EXPECT_EQ(a, b);
    for (const char* bad : {"solve compass-gait --set q=1", "solve compass-gait --set m=x", "solve compass-gait --set m"}) {
        std::string out;
        EXPECT_EQ(run_timed(bad, seconds, out), 1) << bad;
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
        EXPECT_NE(out.find("--set"), std::string::npos) << out;
    }
    std::string out;
    EXPECT_EQ(run_timed("solve three-balls --set m=1,R=1,e=1", seconds, out), 1) << "v is missing";
    EXPECT_NE(out.find("v"), std::string::npos);
}

// The command: formulas --jacobian of a system prints each set's Jacobian (text, json), and a
// numeric system or an unknown --wrt is refused in one line naming --wrt.
TEST(Cli, FormulasJacobianOfASystem)
{
    double seconds = 0;
    std::string out;
    ASSERT_EQ(run_timed("formulas compass-gait --jacobian --wrt w1,w2", seconds, out), 0) << out;
    EXPECT_NE(out.find("Set {0 stick, 1 open}:"), std::string::npos) << out;
    EXPECT_NE(out.find("d w'_swing / d w2 = "), std::string::npos) << out;
    ASSERT_EQ(run_timed("formulas double-pendulum-struck --format json --wrt v", seconds, out), 0) << out;
    EXPECT_NE(out.find("\"jacobian\""), std::string::npos);
    for (const std::string& bad : std::vector<std::string>{"formulas compass-gait --wrt q",
                                  "formulas '" + std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/compass-gait.json' --jacobian"}) {
        EXPECT_EQ(run_timed(bad, seconds, out), 1) << bad;
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
        EXPECT_NE(out.find("--wrt"), std::string::npos) << out;
    }
}
