// Systems (problem format version 3): joints, several contacts, sequential impacts. Classic
// results derived by hand (the derivation in each test's comment), the derived equations'
// residuals, and the closed form against the independent Eigen reference
// (numeric/system_reference.hpp) on seeded random systems.
#include "numeric/system_reference.hpp"
#include "print/answer.hpp"
#include "print/expression.hpp"
#include "print/formulas.hpp"
#include "sampling.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/derivation.hpp"
#include "symbolic/system.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace impactgen;
using GiNaC::ex;
using rational = GiNaC::numeric;

namespace {

problem from_text(const std::string& text) { return read_problem(text, "system.json"); }

problem from_file(const std::string& name)
{
    return load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/" + name);
}

std::string three_balls(const std::string& e, bool sequential)
{
    return std::string(R"({"dimension": 2, "restitution": )") + e + (sequential ? R"(, "impacts": "sequential")" : "") +
           R"(, "bodies": [
        {"name": "a", "mass": 1, "position": [0, 0], "velocity": [1, 0]},
        {"name": "b", "mass": 1, "position": [2, 0], "velocity": [0, 0]},
        {"name": "c", "mass": 1, "position": [4, 0], "velocity": [0, 0]}],
      "contacts": [{"bodies": ["a", "b"], "point": [1, 0], "normal": [1, 0]},
                   {"bodies": ["b", "c"], "point": [3, 0], "normal": [1, 0]}]})";
}

// Every derived equation holds at the answer, and each contact's law in its regime.
void expect_residuals_zero(const problem& p, const system_candidate& c)
{
    const derivation d = derive(p);
    ASSERT_TRUE(d.system);
    const GiNaC::lst values = system_unknown_values(d, c);
    for (const equation& eq : d.equations)
        EXPECT_TRUE(tidy(GiNaC::expand((eq.lhs - eq.rhs).subs(values))).is_zero())
            << eq.reason << ": " << (eq.lhs - eq.rhs).subs(values);
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        if (c.regimes[i] == contact_regime::open) {
            EXPECT_TRUE(c.normal_impulse[i].is_zero()) << "contacts[" << i << "] open with an impulse";
            continue;
        }
        const auto& law = d.system_laws[i];
        const std::size_t checked = c.regimes[i] == contact_regime::stick ? law.size() : 1;
        for (std::size_t k = 0; k < checked; ++k)
            EXPECT_TRUE(tidy(GiNaC::expand((law[k].lhs - law[k].rhs).subs(values))).is_zero()) << law[k].reason;
    }
}

} // namespace

// Three equal balls in a row, a strikes b and c at rest (b and c touching), e for both.
// Simultaneous: both contacts act. Momentum v_a' + v_b' + v_c' = v; contact 0 restitution
// v_b' - v_a' = e v; contact 1 approaches at 0, so v_c' - v_b' = -e * 0 = 0. Hence
// v_b' = v_c' = (1 + e) v / 3, v_a' = (1 - 2e) v / 3, and P_1 = m v_c' >= 0, P_0 = m (v - v_a') >= 0.
TEST(Systems, ThreeBallsSimultaneous)
{
    for (const char* e : {"0", "1/2", "1"}) {
        const problem p = from_text(three_balls(std::string("\"") + e + "\"", false));
        const ex ev = p.restitution;
        const system_answer a = solve_system(p);
        EXPECT_EQ(a.result.velocity[0][0], (1 - 2 * ev) / 3) << e;
        EXPECT_EQ(a.result.velocity[1][0], (1 + ev) / 3) << e;
        EXPECT_EQ(a.result.velocity[2][0], (1 + ev) / 3) << e;
        EXPECT_EQ(a.result.normal_impulse[1], (1 + ev) / 3) << e;
        EXPECT_TRUE(a.impulses_unique);
        expect_residuals_zero(p, a.result);
    }
}

// Sequential, e = 1: a strikes b alone (equal masses exchange velocities: a stops, b moves at
// v), then b strikes c (b stops, c moves at v); then nothing approaches. The last ball leaves
// with the first's speed, the others stop: a different answer from the simultaneous one.
TEST(Systems, ThreeBallsSequentialIsNewtonsCradle)
{
    const system_answer a = solve_system(from_text(three_balls("1", true)));
    EXPECT_EQ(a.result.velocity[0][0], 0);
    EXPECT_EQ(a.result.velocity[1][0], 0);
    EXPECT_EQ(a.result.velocity[2][0], 1);
    EXPECT_EQ(a.sequence, (std::vector<std::size_t>{0, 1}));
    const system_answer s = solve_system(from_text(three_balls("1", false)));
    EXPECT_NE(s.result.velocity[2][0], a.result.velocity[2][0]);
    // e = 1/2: the chain goes on until no contact approaches; momentum is kept, energy lost.
    const system_answer h = solve_system(from_text(three_balls("\"1/2\"", true)));
    EXPECT_GT(h.sequence.size(), 2u);
    EXPECT_EQ(h.result.velocity[0][0] + h.result.velocity[1][0] + h.result.velocity[2][0], 1);
    EXPECT_TRUE(h.result.velocity[0][0] <= h.result.velocity[1][0] && h.result.velocity[1][0] <= h.result.velocity[2][0]);
    EXPECT_EQ(decide(h.energy_before - h.energy_after), decision::positive);
}

// The compass gait of the format (examples/systems/compass-gait.json): plastic, no slip at the
// swing foot S. Whether the stance foot T lifts off: if it does (open), only the swing foot's
// impulse acts on the walker, so the whole walker's angular momentum about S is conserved,
// and only the hip's impulse acts on the stance leg, so the stance leg's angular momentum
// about the hip H is conserved (the walking literature's two balances, here with the legs'
// inertia). With S fixed after impact (plastic, no slip), these give the answer, and the
// stance foot's normal velocity after impact must be >= 0 for the set to hold.
TEST(Systems, CompassGaitHeelStrike)
{
    const problem p = from_file("compass-gait.json");
    const system_answer a = solve_system(p);
    ASSERT_EQ(a.result.regimes[0], contact_regime::stick);
    EXPECT_EQ(a.result.regimes[1], contact_regime::open) << "the stance foot lifts off";
    auto H = [&](std::size_t b, const vec3& O, const vec3& v, const vec3& w) {
        const body& B = p.bodies[b];
        return (B.inertia[2][2] * w[2] + cross(B.position - O, B.mass * v)[2]);
    };
    const vec3 S = p.contacts[0].point, hip = p.joints[0].point;
    const ex before = H(1, S, p.bodies[1].velocity, p.bodies[1].angular_velocity) +
                      H(2, S, p.bodies[2].velocity, p.bodies[2].angular_velocity);
    const ex after = H(1, S, a.result.velocity[1], a.result.angular_velocity[1]) +
                     H(2, S, a.result.velocity[2], a.result.angular_velocity[2]);
    EXPECT_TRUE(tidy(before - after).is_zero()) << before << " vs " << after;
    EXPECT_TRUE(tidy(H(1, hip, p.bodies[1].velocity, p.bodies[1].angular_velocity) -
                     H(1, hip, a.result.velocity[1], a.result.angular_velocity[1]))
                    .is_zero());
    const vec3 foot = point_velocity(p.bodies[2], a.result.velocity[2], a.result.angular_velocity[2], S);
    EXPECT_TRUE(foot[0].is_zero() && foot[1].is_zero());
    EXPECT_EQ(decide(a.result.normal_velocity_after[1]), decision::positive);
    expect_residuals_zero(p, a.result);
}

// Two uniform rods (m = 1, l = 1, I = 1/12), the upper pinned at O = (0, 0), the lower
// joined to it at (0, -1), hang at rest; a ball (m = 1, particle) strikes the lower end
// (0, -2) at V = 1 along +x, e = 1/2. With the rods' angular velocities w1, w2 the tip moves
// at w1 + w2, and the kinetic energy T = (1/2)[(1/3) w1^2 + (w1 + w2/2)^2 + (1/12) w2^2]
// gives the mass matrix M = [[4/3, 1/2], [1/2, 1/3]], M^-1 = [[12/7, -18/7], [-18/7, 48/7]].
// The impulse P at the tip: dw = M^-1 (P, P) = P (-6/7, 30/7), the tip changes by 24/7 P,
// the ball by -P. Restitution: 24/7 P + P = (1 + e) V, so P = 7 (1 + e)/31 = 21/62:
// w1' = -9/31, w2' = 45/31, V' = 41/62.
TEST(Systems, DoublePendulumStruckAtItsLowerEnd)
{
    const problem p = from_file("double-pendulum-struck.json");
    const system_answer a = solve_system(p);
    EXPECT_EQ(a.result.normal_impulse[0], rational(21, 62));
    EXPECT_EQ(a.result.angular_velocity[0][2], rational(-9, 31));
    EXPECT_EQ(a.result.angular_velocity[1][2], rational(45, 31));
    EXPECT_EQ(a.result.velocity[2][0], rational(41, 62));
    expect_residuals_zero(p, a.result);
}

// A box (m = 2, 2a x 2b = 2 x 1) falls flat at v = 1 onto both bottom corners, no spin, e = 1/2.
// By symmetry w' = 0 and both corners act alike: u' = e v at each, so v' = e v = 1/2 up and
// the total impulse m (1 + e) v = 3 splits equally: P_0 = P_1 = 3/2. With friction the
// symmetric answer sticks with no tangential impulse.
TEST(Systems, BoxLandingOnTwoCornersSymmetric)
{
    for (const char* mu : {"0", "0.4", "\"inf\""}) {
        const std::string text = std::string(R"({"dimension": 2, "restitution": 0.5, "bodies": [
            {"name": "ground", "mass": "inf", "position": [0, -1], "velocity": [0, 0]},
            {"name": "box", "mass": 2, "inertia": "2*(4+1)/12", "position": [0, 0.5], "velocity": [0, -1]}],
          "contacts": [{"bodies": ["ground", "box"], "point": [-1, 0], "normal": [0, 1], "friction": )") +
                                 mu + R"(},
                       {"bodies": ["ground", "box"], "point": [1, 0], "normal": [0, 1], "friction": )" + mu + "}]}";
        const problem p = from_text(text);
        const system_answer a = solve_system(p);
        EXPECT_EQ(a.result.normal_impulse[0], rational(3, 2)) << mu;
        EXPECT_EQ(a.result.normal_impulse[1], rational(3, 2)) << mu;
        EXPECT_EQ(a.result.velocity[1][1], rational(1, 2)) << mu;
        EXPECT_TRUE(a.result.angular_velocity[1][2].is_zero()) << mu;
        EXPECT_TRUE(a.result.tangential_impulse[0][0].is_zero()) << mu;
        expect_residuals_zero(p, a.result);
    }
}

// A 3-D box landing flat on four corners: W has rank 3 (lift, two tilts), so the velocities are
// unique (v' = e v up, no spin) and the impulses are not: one valid choice, impulses_unique false.
TEST(Systems, BoxFlatOnFourCornersHasNonUniqueImpulses)
{
    const problem p = from_file("box-four-corners.json");
    const system_answer a = solve_system(p);
    EXPECT_FALSE(a.impulses_unique);
    EXPECT_EQ(a.result.velocity[1][1], p.restitution * 2); // falls at 2
    ex total = 0;
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_NE(decide(a.result.normal_impulse[i]), decision::negative);
        total += a.result.normal_impulse[i];
    }
    EXPECT_EQ(total, p.bodies[1].mass * (1 + p.restitution) * 2);
    for (int k = 0; k < 3; ++k)
        EXPECT_TRUE(a.result.angular_velocity[1][k].is_zero());
    expect_residuals_zero(p, a.result);
    const auto json = print::system_answer_json(p, a);
    EXPECT_EQ(json["impulses_unique"], false);
}
