// impactgen explain for the restitution laws followed through the impact (Routh's process):
// the numbers the document shows are the solver's (the phases' ends, the end of compression,
// the impulses, the energy), the path of the figure ends at the solver's velocity after, and
// the three laws side by side are each law's own answer; Newton's energy gain is explained
// only when the answer gains energy.
#include "print/canonical.hpp"
#include "print/explain.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/routh.hpp"

#include "latex_tools.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

using namespace impactgen;
using namespace impactgen::print;
using namespace GiNaC;

namespace
{

problem example(const std::string &name)
{
    const std::string file = "examples/laws/" + name + ".json";
    return read_problem(latex_tools::read_file(std::string(IMPACTGEN_SOURCE_DIR) + "/" + file), file);
}

// The rows of the sections whose title contains `title`, by the text of their left side.
std::vector<math_row> rows_named(const document &doc, const std::string &title, const std::string &lhs)
{
    std::vector<math_row> out;
    for (const section &sec : doc.sections)
        if (sec.title.find(title) != std::string::npos)
            for (const block &b : sec.blocks)
                for (const math_row &r : b.math)
                    if (r.lhs_note.text == lhs)
                        out.push_back(r);
    return out;
}

double to_double(const ex &x)
{
    const ex v = x.evalf();
    EXPECT_TRUE(is_a<numeric>(v)) << x;
    return is_a<numeric>(v) ? ex_to<numeric>(v).to_double() : 0.0;
}

std::string words_of(const document &doc, const std::string &title)
{
    std::string out;
    for (const section &sec : doc.sections)
        if (sec.title.find(title) != std::string::npos)
            for (const block &b : sec.blocks)
                for (const paragraph &p : b.items)
                    for (const span &s : p.spans)
                        out += s.k == span::note ? s.formula.text : s.text;
    return out;
}

std::string six(double x)
{
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

} // namespace

TEST(ProcessExplain, NumbersAreTheSolversAnswer)
{
    const problem p = example("rod-slip-reverses");
    const derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    ASSERT_EQ(s.cases.size(), 1u);
    const regime_case &c = s.cases.front();
    const document doc = explain(d, s);

    // each phase's end, in order, as the candidate gives it
    const std::vector<math_row> ends = rows_named(doc, "The phases", "P_n");
    ASSERT_EQ(ends.size(), c.process.size() + 1); // each phase's end, then the end of the impact
    for (std::size_t k = 0; k < c.process.size(); ++k)
        EXPECT_NEAR(to_double(ends[k].rhs), to_double(c.process[k].normal_impulse_end), 1e-15) << k;
    EXPECT_NEAR(to_double(ends.back().rhs), to_double(c.sol.normal_impulse), 1e-15);
    // the figure for this rod under the energetic law
    EXPECT_NEAR(to_double(c.sol.normal_impulse), 1.456, 5e-4);

    // the end of compression: u_n(P_c) = 0 on the phase that contains it
    solution scratch;
    const std::vector<process_sequence> q = routh_process(process_inputs_of(d, scratch), "contact.friction");
    ASSERT_EQ(q.size(), 1u);
    const std::vector<math_row> pc = rows_named(doc, "The phases", "P_c");
    ASSERT_EQ(pc.size(), 1u);
    EXPECT_NEAR(to_double(pc[0].rhs), to_double(q[0].compression_impulse), 1e-15);

    // the results: the impulses and the energy lost
    const std::vector<math_row> pn = rows_named(doc, "Results", "P_n"), pt = rows_named(doc, "Results", "P_t"),
                                lost = rows_named(doc, "Results", "T - T'");
    ASSERT_EQ(pn.size(), 1u);
    ASSERT_EQ(pt.size(), 1u);
    ASSERT_EQ(lost.size(), 1u);
    EXPECT_NEAR(to_double(pn[0].rhs), to_double(c.sol.normal_impulse), 1e-15);
    EXPECT_NEAR(to_double(pt[0].rhs), to_double(c.tangential_scalar), 1e-15);
    EXPECT_NEAR(to_double(lost[0].rhs),
                to_double(c.sol.expand_steps(c.sol.energy_before - c.sol.energy_after)), 1e-15);
    EXPECT_GT(to_double(lost[0].rhs), 0); // the energetic law never creates energy

    // the figure: a path in each format, ending at the velocity after impact
    bool figure = false;
    for (const section &sec : doc.sections)
        for (const block &b : sec.blocks)
            if (b.k == block::figure && b.art.alt.find("(u_t, u_n)") != std::string::npos) {
                figure = true;
                EXPECT_NE(b.art.tikz.find("\\begin{tikzpicture}"), std::string::npos);
                EXPECT_NE(b.art.svg.find("<polyline"), std::string::npos);
                char after[80];
                std::snprintf(after, sizeof after, "after impact (%.3f, %.3f)", to_double(c.sliding_speed),
                              to_double(q[0].normal_velocity));
                EXPECT_NE(b.art.alt.find(after), std::string::npos) << b.art.alt;
            }
    EXPECT_TRUE(figure);
}

TEST(ProcessExplain, NewtonGainExplainedAndLawsSideBySide)
{
    const problem p = example("rod-gains-energy");
    const derivation d = derive(p);
    const document doc = explain(d, solve_impact(d));
    bool gain = false;
    for (const section &sec : doc.sections)
        gain = gain || sec.title.find("Why Newton's law gains energy") != std::string::npos;
    EXPECT_TRUE(gain);
    // each law's normal impulse and energy lost, solved here without the printer
    const std::string table = words_of(doc, "side by side");
    for (const restitution_law law : {restitution_law{newton_restitution{}}, restitution_law{poisson_restitution{}},
                                      restitution_law{energetic_restitution{}}}) {
        problem q = p;
        q.contact().law_of_restitution = law;
        const derivation dq = derive(q);
        const regime_case c = select_candidate(dq, solve_impact(dq));
        for (const ex &x : {c.sol.normal_impulse, c.tangential_scalar,
                            c.sol.expand_steps(c.sol.energy_before - c.sol.energy_after)})
            EXPECT_NE(table.find(six(to_double(c.sol.expand_steps(x)))), std::string::npos)
                << law_name(law) << " " << six(to_double(c.sol.expand_steps(x))) << " in " << table;
    }
    EXPECT_NE(table.find("Newton "), std::string::npos);
    EXPECT_NE(table.find("energetic "), std::string::npos);
}

TEST(ProcessExplain, NoGainSectionWhenNewtonLosesEnergy)
{
    // the rod that slips back, under Newton's law: it loses energy, so no gain section, but the table
    problem p = example("rod-slip-reverses");
    p.contact().law_of_restitution = newton_restitution{};
    const derivation d = derive(p);
    const document doc = explain(d, solve_impact(d));
    bool gain = false, table = false;
    for (const section &sec : doc.sections) {
        gain = gain || sec.title.find("gains energy") != std::string::npos;
        table = table || sec.title.find("side by side") != std::string::npos;
    }
    EXPECT_FALSE(gain);
    EXPECT_TRUE(table);
}

TEST(ProcessExplain, SymbolicSequencesCarryTheirConditions)
{
    const problem p = find_named_class("rod-rough-floor")->build();
    const derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    ASSERT_GT(s.cases.size(), 1u);
    const document doc = explain(d, s);
    std::size_t sequences = 0;
    for (const section &sec : doc.sections)
        if (sec.title.find("Phase sequence") != std::string::npos) {
            const regime_case &c = s.cases[sequences++];
            std::size_t conditions = 0;
            for (const block &b : sec.blocks)
                for (const math_row &r : b.math)
                    conditions += r.rel == ">" || r.rel == "≥";
            EXPECT_EQ(conditions, c.process_conditions.size()) << sec.title;
        }
    EXPECT_EQ(sequences, s.cases.size());
}
