// The teaching prose of explain: symbols in math mode (prose_notation), user text never
// read as notation, and what the hand-out adds to the notes' reasoning -- a numeric problem
// taught in symbols first, units, the energy before and after, the centre of percussion,
// contact-frame components, a figure in every document.
#include "print/canonical.hpp"
#include "print/explain.hpp"
#include "print/explain_detail.hpp"
#include "symbolic/named_classes.hpp"

#include "latex_tools.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <fstream>
#include <sstream>
#include <stdexcept>

using namespace impactgen;
using namespace impactgen::print;
using namespace GiNaC;
namespace fs = std::filesystem;

namespace {

document explain_of(const problem& p)
{
    derivation d = derive(p);
    worked_example example;
    const bool has = notes_example(p.source, example);
    return explain(d, solve_impact(d), has ? &example : nullptr);
}

std::vector<std::pair<std::string, problem>> every_problem()
{
    std::vector<std::pair<std::string, problem>> out;
    for (const auto& c : named_classes())
        out.push_back({c.name, c.build()});
    for (const auto& c : friction_classes())
        out.push_back({c.name, c.build()});
    for (const char* dir : {"examples/problems", "examples/friction", "examples/laws", "tests/explain"})
        for (const auto& f : fs::directory_iterator(fs::path(IMPACTGEN_SOURCE_DIR) / dir))
            if (f.path().extension() == ".json")
                out.push_back({f.path().filename().string(), read_problem(latex_tools::read_file(f.path()), f.path().filename().string())});
    return out;
}

// The LaTeX outside math: displays, inline $...$, figures and \text{...} of rows removed.
std::string prose_outside_math(std::string tex)
{
    auto drop_between = [&](const std::string& open, const std::string& close) {
        for (std::size_t at = tex.find(open); at != std::string::npos; at = tex.find(open, at)) {
            std::size_t end = tex.find(close, at + open.size());
            if (end == std::string::npos)
                break;
            tex.erase(at, end + close.size() - at);
        }
    };
    for (const char* env : {"equation*", "multline*", "align*", "gather*", "tikzpicture", "aligned", "split"})
        drop_between(std::string("\\begin{") + env + "}", std::string("\\end{") + env + "}");
    // A quoted program message (the refusal of a problem) is quoted verbatim: not prose.
    for (std::size_t at = tex.find("\n\""); at != std::string::npos; at = tex.find("\n\"", at)) {
        std::size_t end = tex.find('\n', at + 1);
        tex.erase(at + 1, (end == std::string::npos ? tex.size() : end) - at - 1);
        ++at;
    }
    std::string out;
    bool math = false;
    for (std::size_t i = 0; i < tex.size(); ++i) {
        if (tex[i] == '\\' && i + 1 < tex.size() && tex[i + 1] == '$') {
            if (!math)
                out += "\\$";
            ++i;
            continue;
        }
        if (tex[i] == '$') {
            math = !math;
            continue;
        }
        if (!math)
            out += tex[i];
    }
    return out;
}

// The text with its line breaks as spaces and runs of spaces as one: phrases wrap anywhere.
std::string flat(const std::string& s)
{
    std::string out;
    for (char ch : s)
        if (!(ch == '\n' || ch == ' ') || (!out.empty() && out.back() != ' '))
            out += (ch == '\n' ? ' ' : ch);
    return out;
}

const math_row* find_row(const document& doc, const std::function<bool(const math_row&)>& pred)
{
    for (const section& sec : doc.sections)
        for (const block& b : sec.blocks)
            for (const math_row& r : b.math)
                if (pred(r))
                    return &r;
    return nullptr;
}

bool is_symbol_named(const ex& e, const std::string& name) { return is_a<symbol>(e) && ex_to<symbol>(e).get_name() == name; }

} // namespace

TEST(ProseNotation, SymbolsGoToMathByRule)
{
    EXPECT_EQ(prose_notation("e_n").tex, "\\hat{\\underline{e}}_n");
    EXPECT_EQ(prose_notation("e_n").text, "e_n");
    EXPECT_EQ(prose_notation("C1").tex, "C_1");
    EXPECT_EQ(prose_notation("~v′_C").tex, "\\underline{v}'_C");
    EXPECT_EQ(prose_notation("~v′_C").text, "v′_C");
    EXPECT_EQ(prose_notation("~~I_E").tex, "\\underline{\\underline{I}}_E");
    EXPECT_EQ(prose_notation("∫N dt").tex, "\\int N\\,dt");
    EXPECT_EQ(prose_notation("T_lost").tex, "T_{\\mathrm{lost}}");
    EXPECT_EQ(prose_notation("v_Bn").tex, "v_{Bn}");
    EXPECT_EQ(prose_notation("μ ≥ μ*").tex, "\\mu\\ge \\mu^{*}");
    EXPECT_EQ(prose_notation("m2 → ∞").tex, "m_2\\to \\infty");
}

TEST(ProseNotation, WhatItDoesNotKnowIsAnError)
{
    EXPECT_THROW(prose_notation("EC"), std::logic_error);       // two points: words, not one name
    EXPECT_THROW(prose_notation("x # y"), std::logic_error);    // a character it has no rule for
    EXPECT_THROW(prose_notation("~~~v"), std::logic_error);     // three marks
    EXPECT_THROW(prose_notation("v_"), std::logic_error);       // an empty subscript
    EXPECT_THROW(paragraph().t("the $e_n"), std::logic_error);  // an unpaired dollar
}

TEST(ProseNotation, UserTextIsNeverNotation)
{
    // w() keeps a user's text as words, dollars and all; LaTeX escapes them.
    paragraph p;
    p.w("$e_n$ \\input{x}");
    ASSERT_EQ(p.spans.size(), 1u);
    EXPECT_EQ(p.spans[0].k, span::words);
    document doc{"t", {section{"s", {block{block::text, p, {}, {}, {}}}}}};
    const std::string tex = explain_latex(doc);
    EXPECT_NE(tex.find("\\$e\\_n\\$"), std::string::npos);
    EXPECT_EQ(tex.find("\\input{x}"), std::string::npos);
}

// Every class and example: no symbol left in text mode (no "\_" outside math: an e_n or v_C
// set as text), none of the ASCII the notes would not write, and one figure.
TEST(Prose, EverySymbolInMathModeAndOneFigure)
{
    for (const auto& [name, p] : every_problem()) {
        if (name == "hostile-names.json")
            continue; // its names are escaped text by design: tested in UserTextIsNeverNotation
        const document doc = explain_of(p);
        const std::string tex = explain_latex(doc);
        const std::string prose = prose_outside_math(tex);
        for (const char* leak : {"\\_", "normal()", " x r", "r x n", ").n", "v'_C", "w' x"})
            EXPECT_EQ(prose.find(leak), std::string::npos) << name << ": \"" << leak << "\" in the prose near \""
                                                             << prose.substr(prose.find(leak) > 60 ? prose.find(leak) - 60 : 0, 120) << "\"";
        int figures = 0;
        for (const section& sec : doc.sections)
            for (const block& b : sec.blocks)
                if (b.k == block::figure) {
                    ++figures;
                    EXPECT_NE(b.art.tikz.find("\\begin{tikzpicture}"), std::string::npos) << name;
                    EXPECT_NE(b.art.svg.find("<svg"), std::string::npos) << name;
                    EXPECT_FALSE(b.art.alt.empty()) << name;
                }
        // the impact's figure; a numeric process (poisson, energetic with friction) adds its velocity path
        const bool path = p.is_numeric() && !p.contact().friction().is_zero() && follows_process(p.contact().law_of_restitution);
        EXPECT_EQ(figures, path ? 2 : 1) << name;
    }
}

// A numeric problem is taught in symbols first: its steps are formulas, then the numbers.
TEST(Prose, NumericProblemInSymbolsFirst)
{
    const problem p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json");
    const document doc = explain_of(p);
    const std::string text = explain_text(doc);
    EXPECT_NE(text.find("The problem's numbers: substitute"), std::string::npos);
    // N as a formula in the steps (not a number), and its value 18/7 at the end
    const math_row* formula = find_row(doc, [](const math_row& r) { return is_symbol_named(r.lhs, "N") && !is_a<numeric>(r.rhs) && !r.has_then; });
    ASSERT_NE(formula, nullptr);
    EXPECT_TRUE(formula->rhs.has(symbol_named("e")) || !formula->rhs.info(info_flags::numeric));
    const math_row* value = find_row(doc, [](const math_row& r) { return is_symbol_named(r.lhs, "N") && r.has_then; });
    ASSERT_NE(value, nullptr);
    EXPECT_EQ(value->then, numeric(18, 7));
}

TEST(Prose, UnitsFollowNumbersOnly)
{
    const problem p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json");
    ASSERT_EQ(p.units, "SI");
    const std::string text = explain_text(explain_of(p));
    EXPECT_NE(text.find("≈ 3.85714 rad/s"), std::string::npos);  // ω′ = 27/7
    EXPECT_NE(text.find("≈ 2.57143 N·s"), std::string::npos);    // N = 18/7
    EXPECT_NE(text.find("≈ 1.28571 J -- lost"), std::string::npos);
    EXPECT_EQ(text.find("m_ball kg"), std::string::npos);         // never after a symbol
    // Without the key, no units.
    const std::string plain = explain_text(explain_of(find_named_class("pinned-planar")->build()));
    EXPECT_EQ(plain.find("rad/s"), std::string::npos); // (its caption quotes the notes: "5 m/s")
    // Another unit system is refused, naming the key.
    std::string json = latex_tools::read_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json");
    json.replace(json.find("\"SI\""), 4, "\"imperial\"");
    try {
        read_problem(json, "x.json");
        FAIL() << "units imperial read";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("units"), std::string::npos) << e.what();
    }
}

TEST(Prose, EnergyBeforeAndAfter)
{
    const problem p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json");
    const document doc = explain_of(p);
    const math_row* before = find_row(doc, [](const math_row& r) { return is_symbol_named(r.lhs, "T"); });
    const math_row* after = find_row(doc, [](const math_row& r) { return is_symbol_named(r.lhs, "T'"); });
    ASSERT_TRUE(before && after);
    EXPECT_EQ(before->rhs, numeric(25, 4));   // 1/2 * 0.5 * 5^2
    EXPECT_EQ(after->rhs, numeric(139, 28));  // 25/4 - 9/7
}

// The rod hung from its end: the centre of percussion is at 2l/3 from the pivot.
TEST(Prose, CentreOfPercussionOfTheHangingRod)
{
    const document doc = explain_of(find_named_class("pinned-planar")->build());
    const math_row* star = find_row(doc, [](const math_row& r) { return r.lhs_note.text == "s*"; });
    ASSERT_NE(star, nullptr);
    const ex l = symbol_named("l");
    EXPECT_TRUE((star->rhs - 2 * l / 3).expand().is_zero()) << star->rhs;
}

// A normal (3, 4): the smooth-contact equations say v′_t = v_t in the contact frame.
TEST(Prose, ContactFrameComponents)
{
    const problem p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/puck-block-34.json");
    const document doc = explain_of(p);
    // The rows with the numbers (the set-up defines v_t,puck in symbols first).
    const math_row* vt = find_row(doc, [](const math_row& r) { return is_symbol_named(r.lhs, "v_t,puck") && is_a<numeric>(r.rhs); });
    const math_row* vt_after = find_row(doc, [](const math_row& r) { return is_symbol_named(r.lhs, "v'_t,puck") && !r.rel.empty() && is_a<numeric>(r.rhs); });
    ASSERT_TRUE(vt && vt_after);
    EXPECT_EQ(vt->rhs, numeric(7, 10)); // (2, 3/2)·(4/5, -3/5)
    EXPECT_EQ(vt_after->rhs, vt->rhs);
}

// Against a moving body of infinite mass the loss at e = 1 is shown through the named steps,
// T_lost = -2 u v_Bn/w_1 with v_Bn defined beside it, not expanded into 17 terms (massive-3d);
// and the form is the derivation's: put together, it equals the loss at e = 1.
TEST(Prose, LossAtElasticImpactAgainstAMovingWallThroughNamedSteps)
{
    const named_class* c = find_named_class("massive-3d");
    ASSERT_NE(c, nullptr);
    const document doc = explain_of(c->build());
    const math_row* vbn = find_row(doc, [](const math_row& r) { return is_symbol_named(r.lhs, "v_Bn"); });
    ASSERT_NE(vbn, nullptr);
    const math_row* lost = find_row(doc, [](const math_row& r) {
        if (!is_symbol_named(r.lhs, "T_lost"))
            return false;
        for (const_preorder_iterator it = r.rhs.preorder_begin(); it != r.rhs.preorder_end(); ++it)
            if (is_a<symbol>(*it) && ex_to<symbol>(*it).get_name() == "v_Bn")
                return true;
        return false;
    });
    ASSERT_NE(lost, nullptr);
    EXPECT_TRUE(detail::printable(lost->rhs, 12)) << lost->rhs;
    // v_Bn is B's normal velocity before impact: r_b2 w_t2 + v_n2 - r_t2 w_b2 in the class's symbols.
    EXPECT_TRUE(detail::printable(vbn->rhs, 20)) << vbn->rhs;
}

// A numeric problem with the normal (sqrt(2), 1): substituted back, a residual came out as
// sqrt(2) sqrt(3) - sqrt(6) and the document said "SOME EQUATION DOES NOT HOLD: this is a
// bug" of a right answer. residuals() now merges the roots (else evaluates at 60 digits).
TEST(Prose, RadicalNormalAnswerHoldsWhenSubstitutedBack)
{
    for (const char* normal : {R"n(["sqrt(2)", 1])n", R"n(["sqrt(2)", 1, 0])n"}) {
        const bool planar = std::string(normal).find(", 0]") == std::string::npos;
        const std::string json = std::string(R"json({"dimension": )json") + (planar ? "2" : "3") +
                                 R"json(, "restitution": 0.5, "bodies": [
            {"name": "a", "mass": 1, "inertia": )json" + (planar ? "0.1" : "[0.1, 0.1, 0.1]") +
                                 R"json(, "position": )json" + (planar ? "[-1, -0.5]" : "[-1, -0.5, 0]") +
                                 R"json(, "velocity": )json" + (planar ? "[2, 1]" : "[2, 1, 0]") + R"json(},
            {"name": "b", "mass": 2, "inertia": )json" + (planar ? "0.3" : "[0.3, 0.3, 0.3]") +
                                 R"json(, "position": )json" + (planar ? "[1, 0.3]" : "[1, 0.3, 0]") +
                                 R"json(, "velocity": )json" + (planar ? "[0, 0]" : "[0, 0, 0]") + R"json(}],
            "contact": {"bodies": ["a", "b"], "point": )json" + (planar ? "[0, 0]" : "[0, 0, 0]") +
                                 R"json(, "normal": )json" + normal + "}}";
        const document doc = explain_of(read_problem(json, "radical-normal"));
        const std::string text = explain_text(doc);
        EXPECT_EQ(text.find("DOES NOT HOLD"), std::string::npos) << normal;
        EXPECT_NE(text.find("Substituted back, every equation"), std::string::npos) << normal;
    }
}

// central-oblique is two particles; explain says why and what the spheres that keep their
// spins would do: two solid spheres (I = 2 m R²/5), 12 unknowns. The example's solution must find
// every spin unchanged and the centres' velocities of the particle class.
TEST(Prose, SpinningSpheresKeepTheirSpinsAndMoveAsTheParticles)
{
    const problem p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/spinning-spheres.json");
    const derivation d = derive(p);
    EXPECT_EQ(d.count_unknowns(), 12u);
    const solution s = solve(d);
    ASSERT_EQ(s.after.size(), 2u);
    auto sym = [&](const char* name) {
        for (const symbol& x : p.parameters())
            if (x.get_name() == name)
                return ex(x);
        ADD_FAILURE() << "no symbol " << name;
        return ex(0);
    };
    const ex mA = sym("mA"), mB = sym("mB"), e = sym("e"), vA = sym("vyA"), vB = sym("vyB");
    const char* spins[2][3] = {{"wxA", "wyA", "wzA"}, {"wxB", "wyB", "wzB"}};
    for (std::size_t i = 0; i < 2; ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_TRUE(normal(s.expand_steps(s.after[i].angular_velocity[c]) - sym(spins[i][c])).is_zero())
                << "body " << i << " spin " << c << ": " << s.expand_steps(s.after[i].angular_velocity[c]);
    // The particles' answer: v'_A = v_A + (1 + e) mB (v_B - v_A)/(mA + mB) along e_n, and so on.
    const ex P = (1 + e) * mA * mB * (vA - vB) / (mA + mB);
    EXPECT_TRUE(normal(s.expand_steps(s.after[0].velocity[1]) - (vA - P / mA)).is_zero());
    EXPECT_TRUE(normal(s.expand_steps(s.after[1].velocity[1]) - (vB + P / mB)).is_zero());
    EXPECT_TRUE(normal(s.expand_steps(s.after[0].velocity[0]) - sym("vxA")).is_zero());
    EXPECT_TRUE(normal(s.expand_steps(s.after[1].velocity[2]) - sym("vzB")).is_zero());
    // Every equation holds with the solution substituted.
    for (const ex& r : residuals(d, s))
        EXPECT_TRUE(r.is_zero()) << r;
    // The class's own document says what the spheres would do, and names no file (a hand-out).
    const std::string text = flat(explain_text(explain_of(find_named_class("central-oblique")->build())));
    EXPECT_NE(text.find("Kept as spinning spheres instead"), std::string::npos);
    EXPECT_EQ(text.find("spinning-spheres.json"), std::string::npos);
    EXPECT_TRUE(fs::exists(fs::path(IMPACTGEN_SOURCE_DIR) / "examples/problems/spinning-spheres.json"));
}

// Against an immovable body (infinite mass) as body 1, the set-up says that the movable body
// strikes it, as the figure's caption does; otherwise body 1 strikes body 2.
TEST(Prose, TheMovableBodyStrikesTheImmovableOne)
{
    const std::string floor = flat(explain_text(explain_of(find_named_class("ball-floor-friction")->build())));
    EXPECT_NE(floor.find("point B of body 2 (ball) strikes point A of body 1 (floor)"), std::string::npos) << floor.substr(0, 400);
    EXPECT_NE(floor.find("ball (disc) strikes floor (wall)"), std::string::npos);
    const std::string planar = flat(explain_text(explain_of(find_named_class("planar")->build())));
    EXPECT_NE(planar.find("point A of body 1 strikes point B of body 2"), std::string::npos) << planar.substr(0, 400);
    // A moving bat of infinite mass (body 1) strikes a ball at rest: the bat strikes; and the
    // m2 -> infinity limit is not taken (body 2 heavy too would leave nothing to move).
    // (Found by a hostile pass: it said the ball strikes, and let the ball grow heavy.)
    const problem bat = read_problem(R"({"dimension": 2, "restitution": 0.5, "bodies": [
        {"name": "bat", "mass": "inf", "position": [-1, 0], "velocity": [5, 0]},
        {"name": "ball", "mass": 0.2, "position": [0.1, 0], "velocity": [0, 0]}],
      "contact": {"bodies": ["bat", "ball"], "point": [0, 0], "normal": [1, 0]}})",
                                     "bat.json");
    const std::string b = flat(explain_text(explain_of(bat)));
    EXPECT_NE(b.find("point A of body 1 (bat) strikes point B of body 2 (ball)"), std::string::npos) << b.substr(0, 400);
    EXPECT_NE(b.find("bat (wall) strikes ball"), std::string::npos) << b.substr(0, 1200);
    EXPECT_EQ(b.find("let body 2 grow heavy"), std::string::npos);
    EXPECT_NE(b.find("roles exchanged"), std::string::npos);
}

// Issue 25, defect 4: two different equations never carry the same number. Within a section
// every tag stands for one equation (the planar slide's law F = -μN and F = μN were both (8′));
// a worked example may show an equation again, with numbers, in a later section.
TEST(Prose, TwoDifferentEquationsNeverShareANumber)
{
    for (const auto& [name, p] : every_problem()) {
        const document doc = explain_of(p);
        for (const section& sec : doc.sections) {
            std::map<std::string, std::set<std::string>> equations; // tag -> the equations it stands for
            for (const block& b : sec.blocks)
                for (const math_row& r : b.math)
                    if (!r.tag.empty())
                        equations[r.tag].insert((r.lhs_note.text.empty() ? canonical_text(r.lhs) : r.lhs_note.text) +
                                                " " + r.rel + " " + canonical_text(r.rhs));
            for (const auto& [tag, eqs] : equations)
                EXPECT_EQ(eqs.size(), 1u) << name << ", " << sec.title << ": (" << tag << ") stands for " << eqs.size()
                                          << " equations, " << *eqs.begin() << " and " << *eqs.rbegin();
        }
    }
}

// Issue 25, defect 7: a student's hand-out says nothing of the software, its files, its
// refusals or how the notes count equations (the title line is the problem's: defect 1).
TEST(Prose, NoWordAboutTheSoftwareOrItsFiles)
{
    for (const auto& [name, p] : every_problem()) {
        if (name == "hostile-names.json")
            continue; // its names are chosen to look like anything
        document doc = explain_of(p);
        doc.title.clear();
        const std::string text = flat(explain_text(doc));
        for (const char* word : {"impactgen", ".json", "problem-format", "refuse", "examples/", "sources",
                                 "numbering them", "numbers 5 equations", "prints it"}) {
            const std::size_t at = text.find(word);
            EXPECT_EQ(at, std::string::npos) << name << ": \"" << word << "\" near \""
                                             << text.substr(at > 80 ? at - 80 : 0, 160) << "\"";
        }
    }
}

// Issue 25, defect 8: the notes beside displayed rows set their symbols in math too (a world
// axis, the axis of an unknown's component, |F|/N, μ ≥ μ*, the impulses R and P), and a decimal stands in math with its ≈, so that a negative one has a
// true minus sign, in LaTeX and in HTML.
TEST(Prose, SymbolsAndDecimalsOfRowNotesInMath)
{
    const std::regex axis_as_text(R"(component along [a-z]\b|, [a-z] component\b)"), decimal_as_text(R"(\$\\approx\$ ?-?[0-9])"),
        bare_symbol(R"(\$\|\$F\$\|\$|needs \$\\mu\$|impulse [RP] )");
    for (const auto& [name, p] : every_problem()) {
        const document doc = explain_of(p);
        const std::string tex = explain_latex(doc), html = explain_html(doc);
        std::smatch m;
        for (const std::regex* re : {&axis_as_text, &decimal_as_text, &bare_symbol})
            EXPECT_FALSE(std::regex_search(tex, m, *re)) << name << ": \"" << m.str() << "\" in the LaTeX";
        EXPECT_EQ(html.find("≈ -"), std::string::npos) << name << ": a negative decimal with a hyphen in the HTML";
        EXPECT_FALSE(std::regex_search(html, m, axis_as_text)) << name << ": \"" << m.str() << "\" in the HTML";
    }
}
