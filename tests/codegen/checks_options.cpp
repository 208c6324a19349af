// The options behind the generated checks: --unit-normal (refused for a constant
// normal of another length; no normalisation in the plan), --inverse-inertia for
// tensors of numbers and single symbols (the issue's ["Ixx", "Iyy", "Izz"]), and
// the diagonal tensor's closed form without a determinant step.
#include "codegen/codegen.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/solution.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

namespace codegen = impactgen::codegen;
using namespace GiNaC;
using impactgen::problem;

namespace {

// A box (symbolic mass, velocities) against a wall, with the given inertia and normal (JSON).
problem box(const std::string& inertia, const std::string& normal = R"(["nx", "ny", "nz"])")
{
    const std::string json = R"({"dimension": 3, "restitution": "e", "bodies": [
        {"name": "box", "mass": "m", "inertia": )" + inertia + R"(,
         "position": [0.1, 0.7, -0.2], "velocity": ["vx", "vy", "vz"], "angular_velocity": ["wx", "wy", "wz"]},
        {"name": "wall", "mass": "inf", "position": [0, 0, 0], "velocity": [0.3, -0.2, 0.5], "angular_velocity": [0, 0, 0]}],
      "contact": {"bodies": ["box", "wall"], "point": [0.2, 0.1, 0.3], "normal": )" + normal + "}}";
    return impactgen::read_problem(json, "box.json");
}

codegen::options opts(bool inverse_inertia = false, bool unit_normal = false)
{
    codegen::options o;
    o.name = "f";
    o.source = "test";
    o.version = "x";
    o.inverse_inertia = inverse_inertia;
    o.unit_normal = unit_normal;
    return o;
}

std::vector<std::string> input_names(const codegen::plan& pl)
{
    std::vector<std::string> r;
    for (const symbol& x : pl.inputs)
        r.push_back(x.get_name());
    return r;
}

bool has(const std::vector<std::string>& v, const std::string& x) { return std::find(v.begin(), v.end(), x) != v.end(); }

// The option_error a generation throws (its option and message), or fails the test.
codegen::option_error refusal(const problem& p, const codegen::options& o)
{
    try {
        codegen::make_plan(p, o);
    } catch (const codegen::option_error& e) {
        return e;
    }
    ADD_FAILURE() << "no option_error";
    return codegen::option_error(codegen::option_error::set, "");
}

// The header without its banner's command line (which names the options given).
std::string without_command(const std::string& text)
{
    std::istringstream is(text);
    std::string line, r;
    while (std::getline(is, line))
        if (line.find("impactgen codegen ") == std::string::npos)
            r += line + "\n";
    return r;
}

} // namespace

TEST(UnitNormal, RefusedForAConstantNormalOfAnotherLength)
{
    problem p = impactgen::load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/wall-oblique-3d.json");
    codegen::option_error e = refusal(p, opts(false, true));
    EXPECT_EQ(e.which, codegen::option_error::unit_normal);
    EXPECT_NE(std::string(e.what()).find("length 3, not 1"), std::string::npos) << e.what();
    // (3, 4)/5 in 2-D is fine, (3, 4) is not.
    problem q = impactgen::load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/puck-block-34.json");
    EXPECT_EQ(refusal(q, opts(false, true)).which, codegen::option_error::unit_normal);
}

TEST(UnitNormal, AConstantUnitNormalChangesNothing)
{
    // The named classes' normal (0, 1, 0), and an exact irrational unit normal.
    for (const impactgen::named_class& c : impactgen::named_classes()) {
        const problem p = c.build();
        const std::string plain = codegen::generate(p, opts()).text, unit = codegen::generate(p, opts(false, true)).text;
        EXPECT_EQ(without_command(plain), without_command(unit)) << c.name;
    }
    const problem p = box(R"(["Ixx", "Iyy", "Izz"])", R"(["sqrt(2)/2", 0, "-sqrt(2)/2"])");
    EXPECT_EQ(without_command(codegen::generate(p, opts()).text), without_command(codegen::generate(p, opts(false, true)).text));
}

TEST(UnitNormal, TheNormalIsNotNormalised)
{
    const problem p = box(R"(["Ixx", "Iyy", "Izz"])");
    const codegen::plan pl = codegen::make_plan(p, opts(false, true));
    EXPECT_TRUE(pl.deriv.normal_assumed_unit);
    EXPECT_TRUE(pl.deriv.normal_length.is_equal(ex(1)));
    for (int c = 0; c < 3; ++c)
        EXPECT_TRUE(pl.deriv.n_hat[c].is_equal(pl.prob.contact().normal[c])) << c;
    const codegen::plan plain = codegen::make_plan(p, opts());
    EXPECT_FALSE(plain.deriv.normal_assumed_unit);
    EXPECT_FALSE(plain.deriv.n_hat[0].is_equal(plain.prob.contact().normal[0]));
    // The meaning of the normal's inputs says what the header checks.
    for (std::size_t i = 0; i < pl.inputs.size(); ++i)
        if (pl.inputs[i].get_name() == "nx")
            EXPECT_NE(pl.input_meaning[i].find("unit vector"), std::string::npos) << pl.input_meaning[i];
}

TEST(DiagonalInertia, NoDeterminantStep)
{
    auto determinant_steps = [](const problem& p) {
        impactgen::solution s = impactgen::solve(impactgen::derive(p));
        return std::count_if(s.steps.begin(), s.steps.end(),
                             [](const impactgen::step& st) { return st.role == impactgen::step_role::inertia_determinant; });
    };
    EXPECT_EQ(determinant_steps(box(R"(["Ixx", "Iyy", "Izz"])")), 0);
    EXPECT_EQ(determinant_steps(box(R"(["I1", "I1", "I1"])")), 0);
    EXPECT_EQ(determinant_steps(box(R"([["Ixx", 0, 0], [0, "Iyy", 0], [0, 0, 3]])")), 0);
    EXPECT_EQ(determinant_steps(box(R"([["Ixx", "Ixy", 0], ["Ixy", "Iyy", 0], [0, 0, "Izz"]])")), 1);
    // Pinned with the centre of mass on an axis through the pivot: I_E is diagonal too.
    const std::string pinned = R"({"dimension": 3, "restitution": "e", "bodies": [
        {"name": "ball", "mass": "m1", "position": [0.5, -1, 0.25], "velocity": ["u1", "u2", "u3"]},
        {"name": "plate", "mass": "m2", "inertia": ["A", "B", "C"], "position": [0, -0.5, 0],
         "velocity": [0, 0, 0], "angular_velocity": [0, 0, 0]}],
      "contact": {"bodies": ["ball", "plate"], "point": [0.5, -1, 0.25], "normal": [0, 0, 1]},
      "pivots": [{"body": "plate", "point": [0, 0, 0]}]})";
    const problem pp = impactgen::read_problem(pinned, "pinned.json");
    EXPECT_EQ(determinant_steps(pp), 0);
    // The closed form without the determinant still satisfies every equation.
    for (const problem& p : {box(R"(["Ixx", "Iyy", "Izz"])"), pp}) {
        const impactgen::derivation d = impactgen::derive(p);
        for (const ex& r : impactgen::residuals(d, impactgen::solve(d)))
            EXPECT_TRUE(r.is_zero()) << r;
    }
}

TEST(InverseInertia, TensorsOfNumbersAndSymbols)
{
    // The issue's diagonal tensor (it was refused: "the inertia entry xy ... is neither a number nor a single symbol").
    auto names = input_names(codegen::make_plan(box(R"(["Ixx", "Iyy", "Izz"])"), opts(true)));
    for (const char* x : {"inv_Ixx", "inv_Iyy", "inv_Izz"})
        EXPECT_TRUE(has(names, x)) << x;
    EXPECT_FALSE(has(names, "Ixx"));
    // Numbers on the diagonal beside symbols.
    names = input_names(codegen::make_plan(box(R"(["Ixx", 2, "Izz"])"), opts(true)));
    EXPECT_TRUE(has(names, "inv_Ixx") && has(names, "inv_Izz"));
    // Isotropic: one symbol, one input.
    names = input_names(codegen::make_plan(box(R"(["I1", "I1", "I1"])"), opts(true)));
    EXPECT_EQ(std::count_if(names.begin(), names.end(), [](const std::string& x) { return x.rfind("inv_", 0) == 0; }), 1);
    // Zero off-diagonal entries: a 2x2 block of symbols and one apart.
    names = input_names(codegen::make_plan(box(R"([["Ixx", "Ixy", 0], ["Ixy", "Iyy", 0], [0, 0, "Izz"]])"), opts(true)));
    for (const char* x : {"inv_Ixx", "inv_Ixy", "inv_Iyy", "inv_Izz"})
        EXPECT_TRUE(has(names, x)) << x;
    // A block of numbers with a non-zero off-diagonal entry, inverted exactly; a symbol apart.
    const codegen::plan pl = codegen::make_plan(box(R"([[2, 0.5, 0], [0.5, 3, 0], [0, 0, "Izz"]])"), opts(true));
    const impactgen::mat3& K = pl.inverse_tensor.at(0);
    EXPECT_TRUE(K[0][0].is_equal(ex(numeric(12, 23))));
    EXPECT_TRUE(K[0][1].is_equal(ex(numeric(-2, 23))));
    EXPECT_TRUE(K[1][1].is_equal(ex(numeric(8, 23))));
    EXPECT_TRUE(K[0][2].is_zero() && K[1][2].is_zero());
    EXPECT_TRUE(has(input_names(pl), "inv_Izz"));
}

TEST(InverseInertia, ClearRefusals)
{
    // Numbers and symbols in one coupled block: the inverse's entries there are neither.
    codegen::option_error e = refusal(box(R"([["Ixx", 0.1, 0], [0.1, "Iyy", 0], [0, 0, "Izz"]])"), opts(true));
    EXPECT_EQ(e.which, codegen::option_error::inverse_inertia);
    const std::string m = e.what();
    EXPECT_NE(m.find("couples the axes xy"), std::string::npos) << m;
    EXPECT_NE(m.find("xy = 1/10"), std::string::npos) << m;
    EXPECT_NE(m.find("I_box_xy in --params"), std::string::npos) << m;
    // A zero inside a block that couples all three axes is such a number too.
    e = refusal(box(R"([["Ixx", 0, "Ixz"], [0, "Iyy", "Iyz"], ["Ixz", "Iyz", "Izz"]])"), opts(true));
    EXPECT_NE(std::string(e.what()).find("couples the axes xyz"), std::string::npos) << e.what();
    // Lifting the number to a symbol, as the message says, works.
    codegen::options o = opts(true);
    o.params_given = true;
    o.params = {"e", "m", "Ixx", "I_box_xy", "Iyy", "Izz", "vx", "vy", "vz", "wx", "wy", "wz", "nx", "ny", "nz"};
    EXPECT_TRUE(has(input_names(codegen::make_plan(box(R"([["Ixx", 0.1, 0], [0.1, "Iyy", 0], [0, 0, "Izz"]])"), o)),
                    "inv_I_box_xy"));
    // A symbol of a block that stands for another quantity too.
    e = refusal(box(R"([["Ixx", "m", 0], ["m", "Iyy", 0], [0, 0, "Izz"]])"), opts(true));
    EXPECT_NE(std::string(e.what()).find("also appears in m_box"), std::string::npos) << e.what();
    // An expression entry.
    e = refusal(box(R"(["2*Ixx", "Iyy", "Izz"])"), opts(true));
    EXPECT_NE(std::string(e.what()).find("neither a number nor a single symbol"), std::string::npos) << e.what();
}
