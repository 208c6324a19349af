// explain --level summary: the results boxed in every format, the classic closed form of
// direct central impact, the numbers equal to the full document's, one page of LaTeX for
// every named class, and golden files of every named class's summary (golden/summary/).
#include "print/explain.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/problem.hpp"

#include "latex_tools.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

using namespace impactgen;
using namespace impactgen::print;
using namespace GiNaC;
namespace fs = std::filesystem;

namespace
{

document summary_of(const std::string &name, level depth = level::summary)
{
    const problem p = find_named_class(name)->build();
    const derivation d = derive(p);
    worked_example ex;
    const bool has = notes_example(name, ex);
    return explain(d, solve_impact(d), has ? &ex : nullptr, depth);
}

std::vector<math_row> boxed_rows(const document &doc)
{
    std::vector<math_row> out;
    for (const section &sec : doc.sections)
        for (const block &b : sec.blocks)
            if (b.k == block::rows && b.boxed)
                out.insert(out.end(), b.math.begin(), b.math.end());
    return out;
}

// The symbol of that name in e.
ex symbol_in(const ex &e, const std::string &name)
{
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it) && ex_to<symbol>(*it).get_name() == name)
            return *it;
    ADD_FAILURE() << "no symbol " << name << " in " << e;
    return 0;
}

} // namespace

// The textbook's v′₁ = ((m₁ - e m₂) v₁ + (1 + e) m₂ v₂)/(m₁ + m₂), and v′₂ likewise, in the box.
TEST(Summary, CentralDirectShowsTheClassicClosedForm)
{
    const document doc = summary_of("central-direct");
    int found = 0;
    for (const math_row &r : boxed_rows(doc)) {
        if (!is_a<symbol>(r.lhs) || !r.lhs_note.text.empty())
            continue;
        const std::string name = ex_to<symbol>(r.lhs).get_name();
        if (name != "v'_n1" && name != "v'_n2")
            continue;
        const ex m1 = symbol_in(r.rhs, "m1"), m2 = symbol_in(r.rhs, "m2"), e = symbol_in(r.rhs, "e");
        const ex v1 = symbol_in(r.rhs, "v_n1"), v2 = symbol_in(r.rhs, "v_n2");
        const ex classic = name == "v'_n1" ? ((m1 - e * m2) * v1 + (1 + e) * m2 * v2) / (m1 + m2)
                                           : ((m2 - e * m1) * v2 + (1 + e) * m1 * v1) / (m1 + m2);
        EXPECT_TRUE(normal(r.rhs - classic).is_zero()) << name << " = " << r.rhs;
        // in the problem's symbols alone: no step (N, k, u) left in it
        for (const char *step : {"N", "k", "u", "w_1", "w_2"})
            for (const_preorder_iterator it = r.rhs.preorder_begin(); it != r.rhs.preorder_end(); ++it)
                EXPECT_FALSE(is_a<symbol>(*it) && ex_to<symbol>(*it).get_name() == step) << name << " uses " << step;
        ++found;
    }
    EXPECT_EQ(found, 2);
}

// The worked example's numbers in the box are the full document's (its numbers walk).
TEST(Summary, NumbersEqualTheFullDocuments)
{
    const document sum = summary_of("pinned-planar"), full = summary_of("pinned-planar", level::full);
    int compared = 0;
    for (const math_row &r : boxed_rows(sum)) {
        if (!is_a<symbol>(r.lhs) || !is_a<numeric>(r.rhs))
            continue;
        const std::string name = ex_to<symbol>(r.lhs).get_name();
        ex last;
        bool seen = false;
        for (const section &sec : full.sections)
            for (const block &b : sec.blocks)
                for (const math_row &f : b.math)
                    if (is_a<symbol>(f.lhs) && f.lhs_note.text.empty() && ex_to<symbol>(f.lhs).get_name() == name &&
                        is_a<numeric>(f.has_then ? f.then : f.rhs)) {
                        last = f.has_then ? f.then : f.rhs;
                        seen = true;
                    }
        ASSERT_TRUE(seen) << name << " has no number in the full document";
        EXPECT_TRUE((last - r.rhs).is_zero()) << name << ": " << r.rhs << " vs " << last;
        ++compared;
    }
    EXPECT_GE(compared, 4);
}

// Every format frames the results: LaTeX \boxed, HTML a styled box, text a drawn frame,
// Markdown a quoted block.
TEST(Summary, EveryFormatBoxesTheResults)
{
    for (const named_class &c : named_classes()) {
        const document doc = summary_of(c.name);
        EXPECT_FALSE(boxed_rows(doc).empty()) << c.name;
        EXPECT_NE(explain_latex(doc).find("\\boxed{"), std::string::npos) << c.name;
        const std::string html = explain_html(doc);
        EXPECT_NE(html.find("<div class=\"results\">"), std::string::npos) << c.name;
        EXPECT_NE(html.find(".results {"), std::string::npos) << c.name;
        EXPECT_NE(explain_text(doc).find("\u250c"), std::string::npos) << c.name;
        EXPECT_NE(explain_markdown(doc).find("\n> $$"), std::string::npos) << c.name;
        // the full document is not a summary
        EXPECT_GT(summary_of(c.name, level::full).sections.size(), doc.sections.size()) << c.name;
    }
}

// The target: every named class's summary is one page of the LaTeX PDF, with no overfull box.
TEST(Summary, LatexCompilesToOnePageForEveryNamedClass)
{
    if (!latex_tools::have_pdflatex())
        GTEST_SKIP() << latex_tools::no_pdflatex_message();
    for (const named_class &c : named_classes()) {
        const latex_tools::compiled out = latex_tools::compile(explain_latex(summary_of(c.name)), "summary-" + c.name);
        ASSERT_EQ(out.status, 0) << c.name;
        EXPECT_EQ(out.pages, 1) << c.name;
        EXPECT_EQ(out.overfull_hbox, 0) << c.name << latex_tools::around(out.log, "Overfull \\hbox");
    }
}

// Golden files of every named class's summary in every format. IMPACTGEN_REGENERATE_GOLDEN=1
// rewrites them.
TEST(SummaryGolden, EveryClassEveryFormat)
{
    const bool regenerate = std::getenv("IMPACTGEN_REGENERATE_GOLDEN") != nullptr;
    const fs::path dir = fs::path(IMPACTGEN_GOLDEN_DIR) / "summary";
    fs::create_directories(dir);
    for (const named_class &c : named_classes()) {
        const document doc = summary_of(c.name);
        const std::pair<const char *, std::string> outs[] = {{".txt", explain_text(doc)},
                                                             {".md", explain_markdown(doc)},
                                                             {".tex", explain_latex(doc)},
                                                             {".html", explain_html(doc)}};
        for (const auto &[ext, out] : outs) {
            const fs::path file = dir / (c.name + ext);
            if (regenerate) {
                std::ofstream(file, std::ios::binary) << out;
                continue;
            }
            ASSERT_TRUE(fs::exists(file)) << file << " is missing: run make regenerate-golden-explain";
            EXPECT_EQ(latex_tools::read_file(file), out) << file << " differs: regenerate and review the diff";
        }
    }
}

// The command line: --level summary prints the summary; a level it does not know is refused
// in one line naming the option.
TEST(Cli, ExplainLevelSummaryAndRefusal)
{
    int status = 0;
    const std::string cli = IMPACTGEN_CLI;
    const std::string out =
        latex_tools::run(cli + " explain central-direct --level summary --format latex 2>&1", status);
    EXPECT_EQ(status, 0);
    EXPECT_EQ(out, explain_latex(summary_of("central-direct")));
    const std::string bad = latex_tools::run(cli + " explain central-direct --level brief 2>&1", status);
    EXPECT_NE(status, 0);
    EXPECT_NE(bad.find("--level"), std::string::npos) << bad;
}

// Issue 25, defect 6: a body of infinite mass is never "a particle (no rotational inertia)",
// and the floor at rest is a fixed body, without a centre of mass or a velocity to read.
TEST(Prose, InfiniteMassIsNotAParticle)
{
    for (const char *name : {"ball-floor-friction", "massive-3d"})
        for (level depth : {level::full, level::summary}) {
            const std::string text = explain_text(summary_of(name, depth));
            std::size_t at = text.find("infinite mass");
            ASSERT_NE(at, std::string::npos) << name;
            const std::string item = text.substr(at, text.find("\n  - ", at) - at);
            EXPECT_EQ(item.find("particle"), std::string::npos) << name << ": " << item;
            if (std::string(name) == "ball-floor-friction") {
                EXPECT_EQ(item.find("centre of mass"), std::string::npos) << item;
                EXPECT_EQ(item.find("ω"), std::string::npos) << item;
                EXPECT_NE(item.find("fixed body"), std::string::npos) << item;
            }
        }
}

namespace
{
document explain_file(const std::string &path, level depth)
{
    const problem p = read_problem(latex_tools::read_file(fs::path(IMPACTGEN_SOURCE_DIR) / path), "x.json");
    const derivation d = derive(p);
    return explain(d, solve_impact(d), nullptr, depth);
}
} // namespace

// Issue 25, defect 10 (issue 23): a slip that reverses (rod-slips: it slips along +e_t before and
// slides along -e_t after) or stops (ball-backspin sticks) carries the warning that the answer is
// Newton's law at the end of the impact and Routh's differs; a slide that keeps its direction
// (tests/explain/ball-floor.json) does not.
TEST(Prose, SlipThatStopsOrReversesIsWarnedOf)
{
    for (level depth : {level::full, level::summary}) {
        const std::string reverses = explain_text(explain_file("examples/friction/rod-slips.json", depth));
        EXPECT_NE(reverses.find("the slip of the contact points reverses"), std::string::npos);
        EXPECT_NE(reverses.find("Routh"), std::string::npos);
        const std::string stops = explain_text(explain_file("examples/friction/ball-backspin.json", depth));
        EXPECT_NE(stops.find("the slip of the contact points stops"), std::string::npos);
        const std::string keeps = explain_text(explain_file("tests/explain/ball-floor.json", depth));
        EXPECT_EQ(keeps.find("Caution: the slip"), std::string::npos);
        EXPECT_NE(keeps.find("slide along +e_t"), std::string::npos); // it does slide: the test means something
    }
}

// Issue 25, defect 5: one convention for position vectors, r_PQ = Q - P, defined once where
// vectors first appear and used by the text (the contact points as r_C1A = A - C1, no longer
// r_AC1 beside r_OC = C - O).
TEST(Prose, PositionVectorsOneDefinedConvention)
{
    std::vector<std::string> texts; // LaTeX, where a vector is \underline{r} and a coordinate r_t1 is not
    for (const named_class &c : named_classes())
        texts.push_back(explain_latex(summary_of(c.name, level::full)));
    for (const char *f : {"examples/problems/hinged-rod.json", "examples/friction/rod-slips.json"})
        texts.push_back(explain_latex(explain_file(f, level::full)));
    const std::string definition = "A position vector $\\underline{r}_{PQ}=Q-P$ goes from the point";
    for (const std::string &text : texts) {
        const std::size_t at = text.find(definition);
        ASSERT_NE(at, std::string::npos) << text.substr(0, 300);
        EXPECT_EQ(text.find(definition, at + 1), std::string::npos) << "defined twice";
        // no position vector before its definition, none in the opposite order
        EXPECT_EQ(text.substr(0, at).find("\\underline{r}"), std::string::npos);
        for (const char *reversed :
             {"\\underline{r}_{AC", "\\underline{r}_{BC", "\\underline{r}_{A", "\\underline{r}_{B"})
            EXPECT_EQ(text.find(reversed), std::string::npos) << reversed;
    }
}

// Issue 25, defect 9: with "units": "SI" every intermediate step with a number carries its unit
// (hinged-rod: N·s on the normal impulse, J on the energy lost, kg⁻¹ on the inverse masses),
// and a fraction among the answers has its decimal beside it.
TEST(Prose, UnitsOnIntermediateStepsAndDecimalsBesideFractions)
{
    const std::string text = explain_text(explain_file("examples/problems/hinged-rod.json", level::full));
    const std::size_t from = text.find("Step by step"), to = text.find("The unknowns:");
    ASSERT_NE(from, std::string::npos);
    ASSERT_NE(to, std::string::npos);
    const std::string steps = text.substr(from, to - from);
    for (const char *u : {"≈ 2.57143 N·s", "≈ 1.28571 J", "≈ 1.5 kg⁻¹", "kg·m²"})
        EXPECT_NE(steps.find(u), std::string::npos) << u << " not in\n" << steps;
    // every step row's note has a unit: count the rows (a line starting "  X = ") and the units
    int rows = 0, units = 0;
    std::size_t at = 0;
    while ((at = steps.find("\n  ", at)) != std::string::npos) {
        ++at;
        const std::size_t end = steps.find('\n', at);
        const std::string line = steps.substr(at, end - at);
        if (line.rfind("        ", 0) == 0) {
            units += line.find("N·s") != std::string::npos || line.find(" J") != std::string::npos ||
                     line.find("kg") != std::string::npos || line.find("m/s") != std::string::npos;
        } else if (line.find(" = ") != std::string::npos) {
            ++rows;
        }
    }
    EXPECT_GE(rows, 5);
    EXPECT_EQ(units, rows) << steps;
    const std::string answers = text.substr(to);
    EXPECT_NE(answers.find("= 27/14"), std::string::npos);
    EXPECT_NE(answers.find("≈ 1.92857"), std::string::npos);
}

// The full document of a two-particle class is two pages (5 before issue 25's work): the figure
// beside the short set-up, the components of a vector listed once, a particle's contact point moving
// with its centre said once, the limit m2 -> infinity in one sentence, lists set tightly.
TEST(Summary, FullLatexOfATwoParticleClassCompilesToTwoPages)
{
    if (!latex_tools::have_pdflatex())
        GTEST_SKIP() << latex_tools::no_pdflatex_message();
    for (const char *name : {"central-direct", "central-oblique"}) {
        const latex_tools::compiled out =
            latex_tools::compile(explain_latex(summary_of(name, level::full)), std::string("full-") + name);
        ASSERT_EQ(out.status, 0) << name;
        EXPECT_LE(out.pages, 2) << name;
        EXPECT_EQ(out.overfull_hbox, 0) << name << latex_tools::around(out.log, "Overfull \\hbox");
    }
}

// A numeric problem under a process law (Poisson's or the energetic law) is worked with its
// numbers only: its summary boxes each result once, exact with its decimal beside it (the
// results were boxed twice, exact and then again with decimals).
TEST(Summary, NumericProcessLawBoxesEachResultOnce)
{
    for (const char *file : {"/examples/laws/rod-slip-reverses.json", "/tests/codegen/laws/rod-slip-reverses-poisson.json"}) {
        SCOPED_TRACE(file);
        const problem p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + file);
        ASSERT_TRUE(p.is_numeric());
        const derivation d = derive(p);
        const impact_solution s = solve_impact(d);
        ASSERT_TRUE(s.cases.front().process.size() > 0) << "a process law";
        const document doc = explain(d, s, nullptr, level::summary);
        std::map<std::string, int> boxed;
        for (const math_row &r : boxed_rows(doc))
            if (is_a<symbol>(r.lhs))
                ++boxed[ex_to<symbol>(r.lhs).get_name()];
        EXPECT_EQ(boxed.size(), 3u) << "v'_x, v'_y and w' of the rod";
        for (const auto &[name, times] : boxed)
            EXPECT_EQ(times, 1) << name;
        for (const math_row &r : boxed_rows(doc))
            EXPECT_TRUE(is_a<numeric>(r.rhs) || is_constant(r.rhs)) << r.rhs;
    }
}
