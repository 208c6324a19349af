// impactgen explain with Coulomb friction: the equations hold for every closed form,
// the rolling threshold, the numbers of a numeric problem against select_regime,
// the refusal explained, the energy, golden files, LaTeX, byte stability.
#include "print/canonical.hpp"
#include "print/explain.hpp"
#include "print/formulas.hpp"
#include "symbolic/named_classes.hpp"

#include "latex_tools.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

using namespace impactgen;
using namespace impactgen::print;
using namespace GiNaC;
namespace fs = std::filesystem;
using latex_tools::read_file;
using latex_tools::run;

namespace {

struct explained {
    derivation d;
    friction_solution f;
    document doc;
};

explained explain_problem(const problem& p)
{
    derivation d = derive(p);
    friction_solution f = solve_impact(d); // the law's solver: Routh's process for poisson and energetic
    document doc = explain(d, f);
    return {d, f, doc};
}

explained explain_class(const std::string& name) { return explain_problem(find_named_class(name)->build()); }

std::string source(const std::string& file) { return std::string(IMPACTGEN_SOURCE_DIR) + "/tests/explain/" + file; }


// A problem file of tests/explain, named by its file name alone (as `cd tests/explain &&
// impactgen explain FILE` names it): the output does not depend on where the tree is.
explained explain_file(const std::string& file) { return explain_problem(read_problem(read_file(source(file)), file)); }

std::vector<math_row> rows_of(const document& doc, const std::string& prefix)
{
    std::vector<math_row> out;
    for (const section& sec : doc.sections)
        if (sec.title.compare(0, prefix.size(), prefix) == 0)
            for (const block& b : sec.blocks)
                for (const math_row& r : b.math)
                    out.push_back(r);
    return out;
}

// The symbols a list item of a section whose title starts with `prefix` opens with (the
// set-up's unknowns: "v'_t1, v'_n1: velocity of ...").
std::vector<ex> listed_symbols(const document& doc, const std::string& prefix)
{
    std::vector<ex> out;
    for (const section& sec : doc.sections)
        if (sec.title.compare(0, prefix.size(), prefix) == 0)
            for (const block& b : sec.blocks)
                for (const paragraph& item : b.items)
                    for (const span& s : item.spans) {
                        if (s.k == span::math && is_a<symbol>(s.expr))
                            out.push_back(s.expr);
                        else if (s.k == span::words && s.text.find(':') != std::string::npos)
                            break; // the meaning begins
                    }
    return out;
}

// The text with its line breaks and indentation as single spaces: phrases wrap anywhere.
std::string flat(const std::string& text)
{
    std::string out;
    bool space = false;
    for (char c : text) {
        if (c == '\n' || c == ' ') {
            space = true;
            continue;
        }
        if (space && !out.empty())
            out += ' ';
        space = false;
        out += c;
    }
    return out;
}

std::string print_as(const document& doc, const std::string& format)
{
    return format == "text"       ? explain_text(doc)
           : format == "markdown" ? explain_markdown(doc)
           : format == "html"     ? explain_html(doc)
                                  : explain_latex(doc);
}
std::string extension(const std::string& format)
{
    return format == "text" ? "txt" : format == "markdown" ? "md" : format == "html" ? "html" : "tex";
}

// The document prints mu as a symbol named μ: map it back to the problem's.
ex undisplay(const ex& e, const ex& mu)
{
    exmap m;
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it) && ex_to<symbol>(*it).get_name() == "μ")
            m[*it] = mu;
    return m.empty() ? e : e.subs(m);
}

// The print symbols of the impulses, listed in the set-up after the derivation's unknowns.
std::vector<ex> impulse_symbols(const explained& e)
{
    std::vector<ex> out;
    for (const ex& s : listed_symbols(e.doc, "1.")) {
        bool known = false;
        for (const unknown& u : e.d.unknowns)
            known = known || s.is_equal(u.sym);
        if (!known)
            out.push_back(s);
    }
    return out;
}

const char* friction_files[] = {"ball-floor.json", "rod-energy-gain.json", "block-several-regimes.json"};

} // namespace

class FrictionClass : public ::testing::TestWithParam<std::string> {};

// Section 3's equations hold for the closed form of every regime (the sliding angle's
// aside): substitute the unknowns, N and F of the case, and check in its steps.
TEST_P(FrictionClass, EquationsHoldForEveryRegime)
{
    explained e = explain_class(GetParam());
    const int dim = e.d.prob.dimension;
    std::vector<ex> imp = impulse_symbols(e);
    ASSERT_EQ(imp.size(), static_cast<std::size_t>(dim)) << "N and the friction components in the set-up";
    std::vector<math_row> rows = rows_of(e.doc, "3.");
    std::size_t momentum = 0, stick_law = 0, slide_law = 0;
    for (const math_row& r : rows)
        if (!r.tag.empty())
            (r.tag.back() == '\'' ? slide_law : (r.note.spans.size() && r.note.spans[0].text.rfind("stick", 0) == 0 ? stick_law : momentum))++;
    EXPECT_EQ(stick_law, static_cast<std::size_t>(dim - 1));
    EXPECT_EQ(slide_law, dim == 2 ? 2u : 2u);
    // the count: equations + law = unknowns
    EXPECT_EQ(momentum + stick_law, e.d.count_unknowns() + imp.size());
    const vec3 e_t = dim == 2 ? e.d.t_dir : e.f.e_t;
    for (const regime_case& c : e.f.cases) {
        if (c.needs_angle)
            continue;
        lst values;
        for (std::size_t k = 0; k < e.d.unknowns.size(); ++k)
            values.append(e.d.unknowns[k].sym == c.sol.unknown_values.op(k).rhs());
        values.append(imp[0] == c.sol.normal_impulse);
        if (dim == 2) {
            values.append(imp[1] == c.tangential_scalar);
        } else {
            values.append(imp[1] == dot(c.tangential_impulse, e.f.e_t));
            values.append(imp[2] == dot(c.tangential_impulse, e.f.e_b));
        }
        bool law_found = false;
        for (const math_row& r : rows) {
            if (r.tag.empty())
                continue;
            const bool is_slide_law = r.tag.back() == '\'';
            const bool is_stick_law = !is_slide_law && r.note.spans.size() && r.note.spans[0].text.rfind("stick", 0) == 0;
            if ((is_stick_law && c.kind != regime::stick) || (is_slide_law && c.kind != regime::slide))
                continue;
            if (is_slide_law && dim == 3)
                continue; // in the print symbols d_t, d_b
            const ex residual = undisplay(r.lhs - r.rhs, e.f.mu).subs(values);
            const bool zero = vanishes_identically(c.sol, residual, "test");
            if (is_slide_law) {
                law_found = law_found || zero; // one of the two signs
                continue;
            }
            EXPECT_TRUE(zero) << GetParam() << ", " << c.name << ": equation (" << r.tag << ")";
            law_found = law_found || is_stick_law;
        }
        EXPECT_TRUE(law_found || (dim == 3 && c.kind == regime::slide)) << GetParam() << ", " << c.name << ": Coulomb's law";
    }
    std::string text = flat(explain_text(e.doc));
    EXPECT_NE(text.find("the count matches"), std::string::npos);
    EXPECT_NE(text.find("angular momentum of"), std::string::npos);
    EXPECT_NE(text.find("smooth-contact equations fail"), std::string::npos);
}

// Every regime's energy loss is shown (each is checked against T - T' before it is printed).
TEST_P(FrictionClass, EnergyOfEveryRegime)
{
    explained e = explain_class(GetParam());
    std::size_t lost = 0;
    for (const math_row& r : rows_of(e.doc, "7."))
        if (r.lhs_note.text.empty() && is_a<symbol>(r.lhs) && ex_to<symbol>(r.lhs).get_name() == "T_lost")
            ++lost;
    EXPECT_EQ(lost, e.f.cases.size());
}

TEST_P(FrictionClass, LatexCompiles)
{
    if (std::system("command -v pdflatex > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "\n*** pdflatex NOT FOUND: the LaTeX output of explain is NOT CHECKED. "
                        "Install it with: apt-get install --no-install-recommends texlive-latex-base ***\n";
    explained e = explain_class(GetParam());
    fs::path dir = fs::temp_directory_path() / ("impactgen-explain-" + GetParam() + "-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "doc.tex") << explain_latex(e.doc);
    int status = 0;
    std::string log = run("cd '" + dir.string() + "' && pdflatex -interaction=nonstopmode -halt-on-error doc.tex 2>&1", status);
    EXPECT_EQ(status, 0) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
    EXPECT_TRUE(fs::exists(dir / "doc.pdf"));
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Classes, FrictionClass, ::testing::Values("planar-friction", "ball-floor-friction", "noncentral-3d-friction"),
                         [](const auto& info) {
                             std::string n = info.param;
                             for (char& c : n)
                                 if (c == '-')
                                     c = '_';
                             return n;
                         });

// The ball on the floor: sticking means rolling, and the threshold is the textbook's
// mu* = 2|u_t| / (7 (1 + e) |u_n|).
TEST(FrictionExplain, BallFloorRollingThreshold)
{
    explained e = explain_class("ball-floor-friction");
    std::string text = flat(explain_text(e.doc));
    EXPECT_NE(text.find("μ* = 2·|u_t|/(7·(1 + e)·|u_n|)"), std::string::npos) << text;
    EXPECT_NE(text.find("μ* = 2·|R·w + v_t|/(7·(1 + e)·|v_n|)"), std::string::npos);
    EXPECT_NE(text.find("rolls without slipping"), std::string::npos);
    EXPECT_NE(text.find("R·ω′_b,ball + v′_t,ball = 0"), std::string::npos);
    // exactly one regime in the plane
    EXPECT_NE(text.find("exactly one solution for every μ ≥ 0"), std::string::npos);
    std::string tex = explain_latex(e.doc);
    // the threshold's right-hand side (the row may sit in an align block: "\\mu^{*} &= ...")
    EXPECT_NE(tex.find("\\frac{2 \\left|u_{t}\\right|}{7 \\left(1 + e\\right) \\left|u_{n}\\right|}"), std::string::npos);
}

// The numeric ball: every number, the regime, the answer -- as select_regime has them.
TEST(FrictionExplain, NumericBallSlidesWithSelectRegimesNumbers)
{
    explained e = explain_file("ball-floor.json");
    regime_case sel = select_regime(e.d, e.f);
    ASSERT_EQ(sel.name, "slide along +e_t");
    std::string text = flat(explain_text(e.doc));
    EXPECT_NE(text.find("μ* = 2/7"), std::string::npos);
    EXPECT_NE(text.find("μ < μ*, the stick test fails"), std::string::npos);
    EXPECT_NE(text.find("The regime that holds: slide along +e_t."), std::string::npos);
    EXPECT_NE(text.find("stick for μ ≥ 2/7"), std::string::npos);
    EXPECT_NE(text.find("slide along +e_t for 0 ≤ μ < 2/7"), std::string::npos);
    EXPECT_NE(text.find("slide along -e_t for no μ ≥ 0"), std::string::npos);
    EXPECT_NE(text.find("holds exactly"), std::string::npos);
    EXPECT_EQ(text.find("kinetic energy rises"), std::string::npos);
    // the answer rows are select_regime's values
    std::vector<math_row> answer = rows_of(e.doc, "10.");
    for (std::size_t k = 0; k < e.d.unknowns.size(); ++k) {
        bool found = false;
        for (const math_row& r : answer)
            if (is_a<symbol>(r.lhs) && ex_to<symbol>(r.lhs).get_name() == e.d.unknowns[k].sym.get_name()) { // the symbolic twin's
                found = true;
                EXPECT_TRUE((r.rhs - sel.sol.unknown_values.op(k).rhs()).is_zero()) << e.d.unknowns[k].sym;
            }
        EXPECT_TRUE(found) << e.d.unknowns[k].sym;
    }
    EXPECT_NE(text.find("v′_x,ball = 27/10"), std::string::npos);
    EXPECT_NE(text.find("ω′_z,ball = -3/4"), std::string::npos);
    EXPECT_NE(text.find("T_lost = 897/400"), std::string::npos);
}

TEST(FrictionExplain, EnergyGainIsMentionedWhenItHappens)
{
    explained e = explain_file("rod-energy-gain.json");
    regime_case sel = select_regime(e.d, e.f);
    ASSERT_EQ(sel.kind, regime::stick);
    ASSERT_TRUE(ex_to<numeric>(sel.sol.energy_lost).is_negative());
    std::string text = flat(explain_text(e.doc));
    EXPECT_NE(text.find("The kinetic energy rises in this impact"), std::string::npos);
    EXPECT_NE(text.find("T_lost = -32224/15625"), std::string::npos);
}

// A stick impulse that pulls (N < 0 whatever mu): no threshold, and the text does not claim
// that a large mu would make the contact stick.
TEST(FrictionExplain, StickThatPullsIsNotAThreshold)
{
    explained e = explain_file("rod-cannot-stick.json");
    ASSERT_FALSE(stick_can_hold(e.d, e.f));
    regime_case sel = select_regime(e.d, e.f);
    EXPECT_EQ(sel.kind, regime::slide);
    const std::string text = flat(explain_text(e.doc));
    EXPECT_NE(text.find("no μ makes the contact stick"), std::string::npos);
    EXPECT_NE(text.find("Whatever μ, the contact cannot stick"), std::string::npos);
    EXPECT_EQ(text.find("If μ ≥ μ* the contact sticks"), std::string::npos);
}

// None or several regimes: explained, not a crash; the CLI exits 0 with the explanation.
TEST(FrictionExplain, SeveralRegimesAreExplained)
{
    explained e = explain_file("block-several-regimes.json");
    EXPECT_THROW(select_regime(e.d, e.f), input_error);
    std::string text = flat(explain_text(e.doc));
    EXPECT_NE(text.find("No single regime"), std::string::npos);
    EXPECT_NE(text.find("more than one solution"), std::string::npos);
    EXPECT_NE(text.find("the regimes stick, slide at the angle"), std::string::npos);
    EXPECT_NE(text.find("the stick test passes"), std::string::npos);
    int status = 0;
    std::string out = run(std::string(IMPACTGEN_CLI) + " explain " + source("block-several-regimes.json") + " 2>/dev/null", status);
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_NE(out.find("No single regime"), std::string::npos);
}

TEST(FrictionExplain, ProblemFilesLatexCompiles)
{
    if (std::system("command -v pdflatex > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "\n*** pdflatex NOT FOUND: the LaTeX output of explain is NOT CHECKED. "
                        "Install it with: apt-get install --no-install-recommends texlive-latex-base ***\n";
    // hostile names with friction too: every name escaped, the impulse symbols renamed away from N
    std::string hostile = read_file(source("hostile-names.json"));
    const std::string normal = "\"normal\": [1, 0]}";
    ASSERT_NE(hostile.find(normal), std::string::npos);
    hostile.replace(hostile.find(normal), normal.size(), "\"normal\": [1, 0], \"friction\": \"errno\"}");
    std::vector<document> docs;
    docs.push_back(explain_problem(read_problem(hostile, "hostile-names-friction.json")).doc);
    for (const char* file : friction_files)
        docs.push_back(explain_file(file).doc);
    for (const document& doc : docs) {
        fs::path dir = fs::temp_directory_path() / ("impactgen-explain-friction-file-" + std::to_string(::getpid()));
        fs::create_directories(dir);
        std::ofstream(dir / "doc.tex") << explain_latex(doc);
        int status = 0;
        std::string log = run("cd '" + dir.string() + "' && pdflatex -interaction=nonstopmode -halt-on-error doc.tex 2>&1", status);
        EXPECT_EQ(status, 0) << doc.title << ": " << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
        fs::remove_all(dir);
    }
}

TEST(FrictionExplain, HostileNamesGetFreshImpulseSymbols)
{
    std::string hostile = read_file(source("hostile-names.json"));
    const std::string normal = "\"normal\": [1, 0]}";
    hostile.replace(hostile.find(normal), normal.size(), "\"normal\": [1, 0], \"friction\": \"errno\"}");
    explained e = explain_problem(read_problem(hostile, "hostile-names-friction.json"));
    std::vector<ex> imp = impulse_symbols(e);
    ASSERT_EQ(imp.size(), 2u);
    EXPECT_EQ(ex_to<symbol>(imp[0]).get_name(), "N_"); // the problem has a symbol N
    EXPECT_EQ(ex_to<symbol>(imp[1]).get_name(), "F");
}

// Golden files: the friction classes and the numeric examples in every format.
// IMPACTGEN_REGENERATE_GOLDEN=1 (or `make regenerate-golden-explain`) rewrites them.
TEST(FrictionGolden, EveryClassAndExampleEveryFormat)
{
    const bool regenerate = std::getenv("IMPACTGEN_REGENERATE_GOLDEN") != nullptr;
    const fs::path dir = IMPACTGEN_GOLDEN_DIR;
    std::vector<std::pair<std::string, document>> docs;
    for (const named_class& c : friction_classes())
        docs.push_back({c.name, explain_class(c.name).doc});
    for (const char* file : friction_files)
        docs.push_back({fs::path(file).stem().string(), explain_file(file).doc});
    // the example problems with friction, named by file name alone
    std::vector<fs::path> examples;
    for (const char* examples_dir : {"examples/friction", "examples/laws"})
        for (const auto& f : fs::directory_iterator(fs::path(IMPACTGEN_SOURCE_DIR) / examples_dir))
            if (f.path().extension() == ".json")
                examples.push_back(f.path());
    std::sort(examples.begin(), examples.end());
    for (const fs::path& f : examples)
        docs.push_back({f.stem().string(), explain_problem(read_problem(read_file(f), f.filename().string())).doc});
    for (const auto& [name, doc] : docs)
        for (const std::string format : {"text", "markdown", "latex", "html"}) {
            fs::path file = dir / (name + "." + extension(format));
            std::string out = print_as(doc, format);
            if (regenerate) {
                if (!fs::exists(file) || read_file(file) != out)
                    std::ofstream(file, std::ios::binary) << out;
                continue;
            }
            ASSERT_TRUE(fs::exists(file)) << file << " is missing: run make regenerate-golden-explain";
            EXPECT_EQ(read_file(file), out) << file
                                            << " differs from the output: did you forget to regenerate "
                                               "(make regenerate-golden-explain)? Review the diff.";
        }
}

// GiNaC orders terms by hash, which differs between processes: the CLI must not.
TEST(FrictionGolden, ByteStableAcrossProcesses)
{
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"ball-floor-friction", "ball-floor-friction"}, {"noncentral-3d-friction", "noncentral-3d-friction"},
        {"ball-floor.json", "ball-floor"}, {"block-several-regimes.json", "block-several-regimes"}};
    const std::string cli = "cd '" + source("") + "' && " + IMPACTGEN_CLI + " explain ";
    for (const auto& [what, golden] : cases)
        for (const std::string format : {"text", "latex"}) {
            int status = 0;
            std::string first = run(cli + what + " --format " + format + " 2>/dev/null", status);
            ASSERT_EQ(WEXITSTATUS(status), 0) << what;
            for (int k = 0; k < 2; ++k) {
                std::string again = run(cli + what + " --format " + format + " 2>/dev/null", status);
                EXPECT_EQ(first, again) << what << " " << format;
            }
            EXPECT_EQ(first, read_file(fs::path(IMPACTGEN_GOLDEN_DIR) / (golden + "." + extension(format)))) << what << " " << format;
        }
}

// A contact response K that is singular (a pinned rod against a wall): there is no stick
// candidate (no impulse stops the tangential slip while restitution holds). explain teaches
// that and the slides, and names the one that holds; it was refused before.
TEST(FrictionExplain, SingularResponseHasNoStickCandidate)
{
    fs::path file = fs::temp_directory_path() / ("impactgen-singular-" + std::to_string(::getpid()) + ".json");
    std::ofstream(file) << R"({"dimension": 2, "restitution": 0.5, "bodies": [
        {"name": "wall", "mass": "inf", "position": [2, 0], "velocity": [-1, 0]},
        {"name": "rod", "mass": 1, "inertia": "1/12", "position": [0, 0], "velocity": [0, 0]}],
      "contact": {"bodies": ["rod", "wall"], "point": [1, 0.5], "normal": [1, 0], "friction": 0.3},
      "pivots": [{"body": "rod", "point": [0, 0]}]})";
    int status = 0;
    const std::string out = run(std::string(IMPACTGEN_CLI) + " explain " + file.string() + " 2>&1", status);
    EXPECT_EQ(WEXITSTATUS(status), 0) << out;
    EXPECT_NE(out.find("Sticking is impossible"), std::string::npos) << out;
    EXPECT_EQ(out.find("Assume sticking"), std::string::npos) << out;
    EXPECT_EQ(out.find("positive definite"), std::string::npos) << out;
    EXPECT_NE(out.find("The regime that holds: slide"), std::string::npos) << out;
    EXPECT_NE(out.find("every equation (1)-"), std::string::npos) << out; // the residuals vanish
    fs::remove(file);
}

// A singular K whose contact point cannot move tangentially at all (the line from the pivot
// is the normal): the velocities are determined, the friction impulse is not. explain refuses
// it like solve: one line naming K, exit 1.
TEST(FrictionExplain, IndeterminateFrictionImpulseIsRefusedInOneLine)
{
    fs::path file = fs::temp_directory_path() / ("impactgen-indeterminate-" + std::to_string(::getpid()) + ".json");
    std::ofstream(file) << R"({ "dimension": 2, "restitution": "1/2",
  "bodies": [ { "name": "wall", "mass": "inf", "position": [1, -1], "velocity": [0, 0] },
              { "name": "rod", "mass": 2, "inertia": "1/6", "position": [0, "-1/2"], "velocity": ["1/2", 0], "angular_velocity": 1 } ],
  "contact": { "bodies": ["wall", "rod"], "point": [0, -1], "normal": [-1, 0], "friction": "1/2" },
  "pivots": [ { "body": "rod", "point": [0, 0] } ] })";
    for (const char *cmd : {" explain ", " solve "}) {
        int status = 0;
        std::string err = run(std::string(IMPACTGEN_CLI) + cmd + file.string() + " 2>&1 >/dev/null", status);
        EXPECT_EQ(WEXITSTATUS(status), 1) << cmd;
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
        EXPECT_NE(err.find("singular"), std::string::npos) << err;
        EXPECT_NE(err.find("not determined"), std::string::npos) << err;
    }
    fs::remove(file);
}

// The stick impulse is printed as the notes write it, with (1 + e) u_n, never e·u_n + u_n;
// the printed value is the step's own (the form changes, the value does not).
TEST(FrictionExplain, StickImpulseWritesOnePlusE)
{
    for (const char* name : {"planar-friction", "noncentral-3d-friction"}) {
        const explained x = explain_class(name);
        const regime_case& stick = x.f.cases.front();
        std::size_t seen = 0;
        for (const math_row& r : rows_of(x.doc, "5.")) {
            if (!is_a<symbol>(r.lhs) || ex_to<symbol>(r.lhs).get_name().rfind("P_", 0) != 0)
                continue;
            const impactgen::step* st = nullptr;
            for (const impactgen::step& s : stick.sol.steps)
                if (ex(s.sym).is_equal(r.lhs))
                    st = &s;
            ASSERT_NE(st, nullptr) << name << ": " << r.lhs;
            EXPECT_TRUE((r.rhs - st->value).expand().is_zero()) << name << ": " << r.lhs;
            bool one_plus_e = false, split = false;
            for (const_preorder_iterator it = r.rhs.preorder_begin(); it != r.rhs.preorder_end(); ++it) {
                if (!is_a<add>(*it) || it->nops() != 2)
                    continue;
                one_plus_e = one_plus_e || (*it - 1 - x.d.prob.restitution).is_zero();
                // an add of two terms, both with u_n and one with e: e·u_n + u_n
                split = split || (it->op(0).has(x.d.prob.restitution) != it->op(1).has(x.d.prob.restitution) &&
                                  (*it - it->op(0) - it->op(1)).is_zero() && it->op(0).subs(x.d.prob.restitution == 0).is_equal(it->op(1).subs(x.d.prob.restitution == 0)));
            }
            EXPECT_TRUE(one_plus_e) << name << ": " << r.lhs << " = " << r.rhs;
            EXPECT_FALSE(split) << name << ": " << r.lhs << " = " << r.rhs;
            ++seen;
        }
        EXPECT_GE(seen, 2u) << name;
    }
}

// Coulomb's coefficient and the sliding speed are found by what they are
// (friction_solution::mu, regime_case::sliding_speed), never by their names.
namespace {
std::string ball_on_floor(const std::string& mass, const std::string& friction)
{
    return R"({"dimension": 2, "restitution": "e", "bodies": [
      {"name": "floor", "mass": "inf", "position": [0, -1], "velocity": [0, 0]},
      {"name": "ball", "mass": ")" + mass + R"(", "inertia": "2/5", "position": [0, 1], "velocity": ["v_t", "v_n"],
       "angular_velocity": 0}],
    "contact": {"bodies": ["floor", "ball"], "point": [0, 0], "normal": [0, 1], "friction": ")" + friction + R"("}})";
}
} // namespace

// A coefficient the problem names f is the μ the prose speaks of: the document is the
// one of a coefficient named mu, but for the words that give its name in the problem.
TEST(FrictionExplain, CoefficientIsMuWhateverItsName)
{
    const std::string as_mu = explain_text(explain_problem(read_problem(ball_on_floor("m", "mu"), "ball.json")).doc);
    std::string as_f = explain_text(explain_problem(read_problem(ball_on_floor("m", "f"), "ball.json")).doc);
    const std::string alias = ", written f in the problem";
    const std::size_t at = as_f.find(alias);
    ASSERT_NE(at, std::string::npos) << as_f.substr(0, 2000);
    as_f.erase(at, alias.size());
    EXPECT_EQ(flat(as_f), flat(as_mu));
}

// A symbol of the problem named lambda (here the ball's mass) is not the sliding speed,
// and the sliding speed is not written λ where the mass already reads λ (TeX \lambda):
// it keeps its own name, lambda_. Likewise a coefficient f beside a mass named mu (TeX
// \mu) keeps its name.
TEST(FrictionExplain, SymbolsNamedLambdaOrMuAreNotTheLawsSymbols)
{
    const explained lam = explain_problem(read_problem(ball_on_floor("lambda", "mu"), "ball.json"));
    const std::string text = explain_text(lam.doc), tex = explain_latex(lam.doc);
    EXPECT_NE(text.find("lambda_"), std::string::npos);
    EXPECT_NE(tex.find("\\lambda{}'"), std::string::npos);
    for (const regime_case& rc : lam.f.cases)
        if (rc.kind == regime::slide) {
            EXPECT_FALSE(rc.sliding_speed.is_equal(lam.d.prob.bodies[1].mass));
        }

    const explained mu = explain_problem(read_problem(ball_on_floor("mu", "f"), "ball.json"));
    const std::string mu_text = flat(explain_text(mu.doc));
    EXPECT_NE(mu_text.find("Coulomb's coefficient of friction between the bodies is f (μ ≥ 0)."), std::string::npos)
        << mu_text.substr(0, 3000);
}
