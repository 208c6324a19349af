// The contact-frame view of explain (print/contact_frame.hpp): where the normal is not a
// world axis, the equations are printed in t, n, b components. What must hold:
//   - the printed equations are the derivation's: with the frame symbols replaced by their
//     definitions and the unknowns by the solution, every one vanishes identically;
//   - they read as in the notes: a smooth-contact equation is v′_t = v_t (one symbol each
//     side), the system momentum along e_n has only n components;
//   - a normal along a world axis, a named class (axes t, n, b) and a symbolic normal keep
//     the world components.
#include "print/contact_frame.hpp"
#include "print/explain.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/named_classes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

using namespace impactgen;
using namespace impactgen::print;
using namespace GiNaC;

namespace {

struct frame_case {
    const char* name;
    const char* json;
    bool active; ///< the view must be active (false: either, the equivalence is checked anyway)
};

// Planar and 3-D, free and pinned, symbols and numbers, rational and irrational normals.
const frame_case cases[] = {
    {"planar-34",
     R"({"dimension": 2, "restitution": "e", "bodies": [
          {"name": "a", "mass": "m1", "inertia": "I1", "position": [0, 0], "velocity": ["p", "q"], "angular_velocity": "w1"},
          {"name": "b", "mass": "m2", "inertia": "I2", "position": [0.5, 0.6], "velocity": ["r", "s"], "angular_velocity": "w2"}],
        "contact": {"bodies": ["a", "b"], "point": [0.03, 0.04], "normal": [3, 4]}})",
     true},
    {"planar-diagonal",
     R"({"dimension": 2, "restitution": "e", "bodies": [
          {"name": "a", "mass": "m1", "inertia": "I1", "position": [0, 0], "velocity": ["p", "q"], "angular_velocity": "w1"},
          {"name": "b", "mass": "m2", "inertia": "I2", "position": [1, 2], "velocity": ["r", "s"], "angular_velocity": "w2"}],
        "contact": {"bodies": ["a", "b"], "point": [0.5, 0.25], "normal": [1, 1]}})",
     true},
    {"planar-pinned-512",
     R"({"dimension": 2, "restitution": "e", "bodies": [
          {"name": "ball", "mass": "m1", "position": [0.5, -1], "velocity": ["p", "q"]},
          {"name": "rod", "mass": "m2", "inertia": "I2", "position": [0, -0.5], "velocity": [0, 0], "angular_velocity": 0}],
        "contact": {"bodies": ["ball", "rod"], "point": [0.5, -1], "normal": [5, 12]},
        "pivots": [{"body": "rod", "point": [0, 0]}]})",
     true},
    {"planar-numbers",
     R"({"dimension": 2, "restitution": 0.5, "bodies": [
          {"name": "a", "mass": 1, "inertia": 0.25, "position": [0, 0], "velocity": [2, 1], "angular_velocity": 1},
          {"name": "b", "mass": 3, "inertia": 2, "position": [0.5, 0.6], "velocity": [-1, 0], "angular_velocity": 0}],
        "contact": {"bodies": ["a", "b"], "point": [0.03, 0.04], "normal": [0.6, 0.8]}})",
     true},
    {"3d-122",
     R"({"dimension": 3, "restitution": "e", "bodies": [
          {"name": "a", "mass": "m1", "inertia": [["A", "F", "E"], ["F", "B", "D"], ["E", "D", "C"]],
           "position": [0.1, 0.7, -0.2], "velocity": ["p", "q", "r"], "angular_velocity": ["wx", "wy", "wz"]},
          {"name": "b", "mass": "m2", "inertia": ["J1", "J2", "J3"], "position": [1, 2, 1],
           "velocity": ["s", "t", "u"], "angular_velocity": [0, 0, 1]}],
        "contact": {"bodies": ["a", "b"], "point": [0.2, 0.1, 0.3], "normal": [1, 2, 2]}})",
     true},
    {"3d-236-pinned",
     R"({"dimension": 3, "restitution": "e", "bodies": [
          {"name": "ball", "mass": "m1", "position": [0.5, -1, 0.25], "velocity": ["u1", "u2", "u3"]},
          {"name": "plate", "mass": "m2", "inertia": ["A", "B", "C"], "position": [0, -0.5, 0.1],
           "velocity": [0, 0, 0], "angular_velocity": [0, 0, 0]}],
        "contact": {"bodies": ["ball", "plate"], "point": [0.5, -1, 0.25], "normal": [2, 3, 6]},
        "pivots": [{"body": "plate", "point": [0, 0, 0]}]})",
     true},
    {"3d-111",
     R"({"dimension": 3, "restitution": "e", "bodies": [
          {"name": "a", "mass": "m1", "inertia": ["A", "B", "C"], "position": [0, 0, 0], "velocity": ["p", "q", "r"],
           "angular_velocity": ["wx", "wy", "wz"]},
          {"name": "b", "mass": "inf", "position": [1, 1, 1], "velocity": [0, 0, 0], "angular_velocity": [0, 0, 0]}],
        "contact": {"bodies": ["a", "b"], "point": [0.5, 0.25, 0.5], "normal": [1, 1, 1]}})",
     false},
};

// lhs - rhs of a printed equation with every symbol of the view replaced by what it stands
// for, and the unknowns by the solution: zero for an equation the solution satisfies.
ex residual(const contact_frame_view& v, const framed_equation& f, const solution& s)
{
    exmap back;
    for (const auto* list : {&v.unknowns, &v.inputs, &v.inertia})
        for (const frame_component& c : *list)
            back[c.sym] = c.world;
    ex r = (f.lhs - f.rhs).subs(back);
    r = r.subs(s.unknown_values);
    // the steps, latest first: each is defined through earlier ones
    for (auto it = s.steps.rbegin(); it != s.steps.rend(); ++it)
        r = r.subs(it->sym == it->value);
    return r;
}

class ContactFrame : public ::testing::TestWithParam<frame_case> {};

TEST_P(ContactFrame, PrintedEquationsAreTheDerivationsAndReadAsInTheNotes)
{
    const frame_case& c = GetParam();
    const problem p = read_problem(c.json, c.name);
    const derivation d = derive(p);
    const solution s = solve(d);
    const contact_frame_view v = contact_frame_view_of(d);
    if (c.active) {
        EXPECT_TRUE(v.active) << c.name;
    }
    ASSERT_EQ(v.equations.size(), d.equations.size());
    ASSERT_EQ(v.unknowns.size(), d.unknowns.size());
    std::set<std::string> labels;
    for (const framed_equation& f : v.equations) {
        labels.insert(f.source->label);
        EXPECT_TRUE(identically_zero(residual(v, f, s))) << c.name << " (" << f.source->label << "): " << f.lhs << " = " << f.rhs;
    }
    EXPECT_EQ(labels.size(), d.equations.size()) << "every equation keeps its own number";
    if (!v.active)
        return;
    for (const framed_equation& f : v.equations) {
        if (f.source->why == principle::smooth_contact && !v.inputs.empty()) {
            // v′_t = v_t: the unknown and the input, one symbol on each side.
            EXPECT_TRUE(is_a<symbol>(f.lhs) && is_a<symbol>(f.rhs)) << c.name << ": " << f.lhs << " = " << f.rhs;
        }
        if (f.source->why == principle::system_momentum) {
            // m1 v′_n1 + m2 v′_n2 = ...: no tangential component.
            for (const frame_component& u : v.unknowns)
                if (u.axis == "t" || u.axis == "b") {
                    EXPECT_FALSE(f.lhs.has(u.sym)) << c.name << ": " << f.lhs;
                }
        }
        for (const auto& [world, frame] : v.to_frame) {
            EXPECT_FALSE(f.lhs.has(world)) << c.name << ": world symbol " << world << " left in " << f.lhs;
            EXPECT_FALSE(f.rhs.has(world)) << c.name << ": world symbol " << world << " left in " << f.rhs;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Problems, ContactFrame, ::testing::ValuesIn(cases),
                         [](const ::testing::TestParamInfo<frame_case>& i) {
                             std::string n = i.param.name;
                             for (char& ch : n)
                                 if (ch == '-')
                                     ch = '_';
                             return n;
                         });

TEST(ContactFrame, WorldAxisNormalsAndNamedClassesKeepWorldComponents)
{
    for (const auto& c : named_classes()) {
        const derivation d = derive(c.build());
        EXPECT_FALSE(contact_frame_view_of(d).active) << c.name;
    }
    const problem axis = read_problem(R"({"dimension": 2, "restitution": "e", "bodies": [
          {"name": "a", "mass": "m1", "position": [0, 0], "velocity": ["p", "q"]},
          {"name": "b", "mass": "m2", "position": [0, 1], "velocity": ["r", "s"]}],
        "contact": {"bodies": ["a", "b"], "point": [0, 0.5], "normal": [0, -2]}})",
                                      "axis");
    EXPECT_FALSE(contact_frame_view_of(derive(axis)).active);
    const problem symbolic = read_problem(R"({"dimension": 2, "restitution": "e", "bodies": [
          {"name": "a", "mass": "m1", "position": [0, 0], "velocity": ["p", "q"]},
          {"name": "b", "mass": "m2", "position": [0, 1], "velocity": ["r", "s"]}],
        "contact": {"bodies": ["a", "b"], "point": [0, 0.5], "normal": ["c", "d"]}})",
                                          "symbolic-normal");
    EXPECT_FALSE(contact_frame_view_of(derive(symbolic)).active);
    // A contact point (a + ... + q)^12: expanding the equations in the frame would take
    // minutes; the view keeps the world components (and returns at once).
    const problem hostile = load_problem_file(IMPACTGEN_SOURCE_DIR "/tests/core/edges/power-of-sum-in-point.json");
    EXPECT_FALSE(contact_frame_view_of(derive(hostile)).active);
}

TEST(ContactFrame, ExplainPrintsTheSmoothContactEquationAsTheNotesDo)
{
    const problem p = read_problem(cases[0].json, "planar-34");
    const derivation d = derive(p);
    std::string text = explain_text(explain(d, solve_impact(d), nullptr));
    for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at)) // unwrap the prose
        if (at + 1 < text.size() && text[at + 1] != '\n' && text[at + 1] != ' ' && at > 0 && text[at - 1] != '\n')
            text[at] = ' ';
        else
            ++at;
    EXPECT_NE(text.find("(1)  v′_ta = v_ta"), std::string::npos) << text;
    EXPECT_NE(text.find("written in contact-frame components"), std::string::npos);
}

} // namespace

// The view writes the meaning of each contact-frame component from the unknown's kind and
// body, with its axis in a field of its own, not by editing the derivation's sentence: a
// body named like the end of one (", x component") reads as its name.
TEST(ContactFrame, ComponentMeaningsFromTheUnknownsKind)
{
    const problem p = read_problem(
        R"({"dimension": 2, "restitution": "e", "bodies": [
          {"name": "ball, x component", "mass": "m1", "position": [0.5, -1], "velocity": ["p", "q"]},
          {"name": "rod", "mass": "m2", "inertia": "I2", "position": [0, -0.5], "velocity": [0, 0], "angular_velocity": 0}],
        "contact": {"bodies": ["ball, x component", "rod"], "point": [0.5, -1], "normal": [5, 12]},
        "pivots": [{"body": "rod", "point": [0, 0]}]})",
        "named-like-a-component");
    const derivation d = derive(p);
    const contact_frame_view v = contact_frame_view_of(d);
    ASSERT_TRUE(v.active);
    std::vector<std::string> meanings; // words | axis
    for (const frame_component& u : v.unknowns)
        meanings.push_back(u.meaning + " | " + u.axis);
    for (const char* expected : {"velocity of the centre of mass of ball, x component after impact | t",
                                 "velocity of the centre of mass of ball, x component after impact | n",
                                 "impulse of the pivot on rod | t", "impulse of the pivot on rod | n"})
        EXPECT_NE(std::find(meanings.begin(), meanings.end(), expected), meanings.end()) << expected;
    ASSERT_EQ(v.inputs.size(), 2u);
    EXPECT_EQ(v.inputs[0].meaning, "velocity of the centre of mass of ball, x component before impact");
    EXPECT_EQ(v.inputs[0].axis, "t");
    EXPECT_EQ(v.inputs[1].meaning, "velocity of the centre of mass of ball, x component before impact");
    EXPECT_EQ(v.inputs[1].axis, "n");
}
