// impactgen explain: content, determinism, golden files, LaTeX.
#include "expr/roles.hpp"
#include "print/canonical.hpp"
#include "print/explain.hpp"
#include "print/explain_detail.hpp"
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

using namespace impactgen;
using namespace impactgen::print;
using namespace GiNaC;
namespace fs = std::filesystem;
using latex_tools::read_file;
using latex_tools::run;

namespace {

struct explained {
    derivation d;
    solution s;
    document doc;
};

explained explain_problem(const problem& p, bool with_example)
{
    derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    worked_example ex;
    bool has = with_example && notes_example(p.source, ex);
    document doc = explain(d, s, has ? &ex : nullptr);
    return {d, s.cases.front().sol, doc};
}

explained explain_class(const std::string& name) { return explain_problem(find_named_class(name)->build(), true); }

// Every displayed row of a section whose title starts with `prefix`.
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

// The value the last row with lhs a symbol of that name shows in the checks section.
ex last_value(const document& doc, const std::string& name)
{
    ex v;
    bool found = false;
    for (const math_row& r : rows_of(doc, "5."))
        if (r.lhs_note.text.empty() && is_a<symbol>(r.lhs) && ex_to<symbol>(r.lhs).get_name() == name && r.rel == "=") {
            v = r.has_then ? r.then : r.rhs;
            found = true;
        }
    EXPECT_TRUE(found) << name;
    return v;
}

const char* formats[] = {"text", "markdown", "latex", "html"};
std::string extension(const std::string& format)
{
    return format == "text" ? "txt" : format == "markdown" ? "md" : format == "html" ? "html" : "tex";
}
std::string print_as(const document& doc, const std::string& format)
{
    return format == "text"       ? explain_text(doc)
           : format == "markdown" ? explain_markdown(doc)
           : format == "html"     ? explain_html(doc)
                                  : explain_latex(doc);
}

} // namespace

// The notes' worked example: ball 0.5 kg at 5 m/s, rod 2 kg, 1 m, e = 0.8.
TEST(WorkedExample, PinnedPlanarClassReachesTheNotesNumbers)
{
    explained e = explain_class("pinned-planar");
    EXPECT_EQ(last_value(e.doc, "v'_x1"), numeric(-1, 7));
    EXPECT_EQ(last_value(e.doc, "w'_z2"), numeric(27, 7));
    EXPECT_EQ(last_value(e.doc, "N"), numeric(18, 7));
    EXPECT_EQ(last_value(e.doc, "R_x2"), numeric(9, 7));
    // The text shows the same numbers; parse them back.
    std::string text = explain_text(e.doc);
    for (const auto& [name, value] : std::vector<std::pair<std::string, numeric>>{
             {"v′_x1", numeric(-1, 7)}, {"ω′_z2", numeric(27, 7)}, {"R_x2", numeric(9, 7)}}) {
        std::string key = "  " + name + " = ";
        std::size_t at = text.rfind(key);
        ASSERT_NE(at, std::string::npos) << name;
        std::string number = text.substr(at + key.size(), text.find('\n', at) - at - key.size());
        parser reader;
        EXPECT_TRUE((reader(number) - value).is_zero()) << name << " printed as " << number;
    }
    EXPECT_NE(text.find("every equation (1)-(8) holds exactly"), std::string::npos);
}

TEST(WorkedExample, HingedRodFileShowsExactNumbers)
{
    problem p = load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json");
    explained e = explain_problem(p, false);
    EXPECT_EQ(last_value(e.doc, "v'_x,ball"), numeric(-1, 7));
    EXPECT_EQ(last_value(e.doc, "w'_z,rod"), numeric(27, 7));
    EXPECT_EQ(last_value(e.doc, "N"), numeric(18, 7));
    EXPECT_EQ(last_value(e.doc, "R_x,rod"), numeric(9, 7));
    EXPECT_EQ(last_value(e.doc, "T_lost"), numeric(9, 7));
    EXPECT_NE(explain_text(e.doc).find("holds exactly"), std::string::npos);
}

class EveryClass : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryClass, CountsMatchAndEveryEquationAppears)
{
    explained e = explain_class(GetParam());
    ASSERT_EQ(e.d.count_equations(), e.d.count_unknowns());
    std::string text = explain_text(e.doc);
    EXPECT_NE(text.find(std::to_string(e.d.count_equations()) + " equations for " + std::to_string(e.d.count_unknowns()) +
                        " unknowns: the count matches"),
              std::string::npos);
    EXPECT_NE(text.find("Number of unknowns: "), std::string::npos);
    std::vector<math_row> rows = rows_of(e.doc, "3.");
    for (const equation& eq : e.d.equations) {
        bool found = false;
        for (const math_row& r : rows)
            if (r.tag == eq.label && (r.lhs - eq.lhs).expand().is_zero() && (r.rhs - eq.rhs).expand().is_zero())
                found = true;
        EXPECT_TRUE(found) << GetParam() << ": equation (" << eq.label << ") is not shown";
        EXPECT_NE(text.find("(" + eq.label + ")  "), std::string::npos);
    }
    // Every remark (a principle without a usable equation) is explained, about its body.
    for (const remark& r : e.d.remarks)
        EXPECT_NE(text.find(impactgen::print::detail::body_ref(e.d.prob, r.body)), std::string::npos) << r.text;
    EXPECT_EQ(e.d.remarks.empty(), text.find("Where a principle gives no usable equation") == std::string::npos);
    // Every unknown is listed in the set-up with its meaning.
    const std::vector<ex> setup = listed_symbols(e.doc, "1.");
    for (const unknown& u : e.d.unknowns) {
        bool listed = false;
        for (const ex& s : setup)
            listed = listed || s.is_equal(u.sym);
        EXPECT_TRUE(listed) << u.sym;
    }
}

TEST_P(EveryClass, EnergyCheckIsRight)
{
    explained e = explain_class(GetParam());
    bool at_one_found = false;
    for (const math_row& r : rows_of(e.doc, "5.")) {
        std::ostringstream note;
        note << explain_text(document{"", {section{"", {block{block::text, r.note, {}, {}, {}}}}}});
        if (note.str().find("at e = 1") == std::string::npos)
            continue;
        at_one_found = true;
        if (GetParam() == "massive-3d")
            EXPECT_FALSE(r.rhs.is_zero()); // a moving infinite mass does work
        else
            EXPECT_TRUE(r.rhs.is_zero()) << r.rhs;
    }
    EXPECT_TRUE(at_one_found);
}

TEST_P(EveryClass, LatexCompiles)
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

INSTANTIATE_TEST_SUITE_P(Classes, EveryClass,
                         ::testing::Values("central-direct", "central-oblique", "noncentral-3d", "massive-3d", "planar",
                                           "pinned-planar"),
                         [](const auto& info) {
                             std::string n = info.param;
                             for (char& c : n)
                                 if (c == '-')
                                     c = '_';
                             return n;
                         });

// Problem files, including body names full of LaTeX's special characters
// (50% a_b#{x}, ~^\end{document}): every name is escaped, the document compiles.
TEST(ProblemFiles, LatexCompiles)
{
    if (std::system("command -v pdflatex > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "\n*** pdflatex NOT FOUND: the LaTeX output of explain is NOT CHECKED. "
                        "Install it with: apt-get install --no-install-recommends texlive-latex-base ***\n";
    for (const char* file : {"/tests/explain/hostile-names.json", "/examples/problems/hinged-rod.json",
                             "/examples/problems/puck-block-34.json", "/examples/problems/wall-oblique-3d.json",
                             "/examples/problems/pinned-3d.json"}) {
        explained e = explain_problem(load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + file), false);
        fs::path dir = fs::temp_directory_path() / ("impactgen-explain-file-" + std::to_string(::getpid()));
        fs::create_directories(dir);
        std::ofstream(dir / "doc.tex") << explain_latex(e.doc);
        int status = 0;
        std::string log = run("cd '" + dir.string() + "' && pdflatex -interaction=nonstopmode -halt-on-error doc.tex 2>&1", status);
        EXPECT_EQ(status, 0) << file << ": " << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
        fs::remove_all(dir);
    }
}

// Golden files: every named class in every format. IMPACTGEN_REGENERATE_GOLDEN=1
// (or `make regenerate-golden-explain`) rewrites them.
TEST(Golden, EveryClassEveryFormat)
{
    const bool regenerate = std::getenv("IMPACTGEN_REGENERATE_GOLDEN") != nullptr;
    const fs::path dir = IMPACTGEN_GOLDEN_DIR;
    // The named classes, and the example problems (examples/problems, named by file name
    // alone so that the output does not depend on where the tree is).
    std::vector<std::pair<std::string, explained>> docs;
    for (const named_class& c : named_classes())
        docs.push_back({c.name, explain_class(c.name)});
    for (const auto& f : fs::directory_iterator(fs::path(IMPACTGEN_SOURCE_DIR) / "examples/problems"))
        if (f.path().extension() == ".json") {
            const std::string name = f.path().filename().string();
            docs.push_back({f.path().stem().string(), explain_problem(read_problem(read_file(f.path()), name), false)});
        }
    std::sort(docs.begin(), docs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [name, e] : docs) {
        for (const std::string format : formats) {
            fs::path file = dir / (name + "." + extension(format));
            std::string out = print_as(e.doc, format);
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
}

// GiNaC orders terms by hash, which differs between processes: the CLI must not.
TEST(Golden, ByteStableAcrossProcesses)
{
    for (const std::string what : {"noncentral-3d", "pinned-planar"}) {
        for (const std::string format : {"text", "latex"}) {
            int status = 0;
            std::string first = run(std::string(IMPACTGEN_CLI) + " explain " + what + " --format " + format, status);
            ASSERT_EQ(status, 0);
            for (int k = 0; k < 3; ++k) {
                std::string again = run(std::string(IMPACTGEN_CLI) + " explain " + what + " --format " + format, status);
                EXPECT_EQ(first, again) << what << " " << format;
            }
            if (format == "text") {
                EXPECT_EQ(first, read_file(fs::path(IMPACTGEN_GOLDEN_DIR) / (what + ".txt")));
            }
        }
    }
}

TEST(Cli, BadInputIsOneLineAndExitOne)
{
    int status = 0;
    std::string err = run(std::string(IMPACTGEN_CLI) + " explain no-such-class 2>&1 >/dev/null", status);
    EXPECT_EQ(WEXITSTATUS(status), 1);
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find("no-such-class"), std::string::npos);
    fs::path bad = fs::temp_directory_path() / ("impactgen-bad-" + std::to_string(::getpid()) + ".json");
    std::ofstream(bad) << "{ \"dimension\": 2, ";
    err = run(std::string(IMPACTGEN_CLI) + " explain " + bad.string() + " 2>&1 >/dev/null", status);
    EXPECT_EQ(WEXITSTATUS(status), 1);
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    fs::remove(bad);
    err = run(std::string(IMPACTGEN_CLI) + " explain planar --format pdf 2>&1 >/dev/null", status);
    EXPECT_NE(WEXITSTATUS(status), 0);
    // A body named with a character LaTeX cannot set (μ, ö): refused for --format latex,
    // naming the character, and nothing written -- never a document pdflatex stops on
    // (the name reached \text{} and the figure's labels unescaped).
    for (const char* name : {"\u03bc", "K\u00f6rper", "x\u2032"}) {
        fs::path greek = fs::temp_directory_path() / ("impactgen-greek-" + std::to_string(::getpid()) + ".json");
        std::ofstream(greek) << R"({"dimension": 2, "restitution": 0.5, "bodies": [
            {"name": "a", "mass": 1, "position": [0, 0], "velocity": [1, 0]},
            {"name": ")" << name << R"(", "mass": 2, "position": [1, 0], "velocity": [0, 0]}],
            "contact": {"bodies": ["a", ")" << name << R"("], "point": [0.5, 0], "normal": [3, 4]}})";
        std::string out = run(std::string(IMPACTGEN_CLI) + " explain " + greek.string() + " --format latex 2>/dev/null", status);
        EXPECT_EQ(WEXITSTATUS(status), 1) << name;
        EXPECT_TRUE(out.empty()) << name << ": " << out.substr(0, 200);
        err = run(std::string(IMPACTGEN_CLI) + " explain " + greek.string() + " --format latex 2>&1 >/dev/null", status);
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
        EXPECT_NE(err.find("no rendering for the character"), std::string::npos) << err;
        // the other formats take the name as it is
        run(std::string(IMPACTGEN_CLI) + " explain " + greek.string() + " --format html >/dev/null 2>&1", status);
        EXPECT_EQ(WEXITSTATUS(status), 0) << name;
        fs::remove(greek);
    }
}

TEST(Canonical, SignsAndForms)
{
    symbol a("a"), b("b"), c("c"), d("d"), e("e");
    const symbol w = expr::symbol_with_role("w'_z1", "", expr::symbol_role::angular_velocity);
    EXPECT_EQ(canonical_text((a - b) / (c - d)), canonical_text((b - a) / (d - c)));
    EXPECT_EQ(canonical_text(pow(a, 2) / 2), "a²/2");
    EXPECT_EQ(canonical_text(1 - e * e), "1 - e²");
    EXPECT_EQ(canonical_text(-(1 + e) * a / c), "-(1 + e)·a/c");
    EXPECT_EQ(canonical_text(sqrt(a)), "√a");
    EXPECT_EQ(canonical_text(w), "ω′_z1");
    EXPECT_EQ(canonical_text(symbol("w'_z1")), "w′_z1"); // no role, no ω
    EXPECT_EQ(canonical_text(symbol("w_1")), "w_1");
    EXPECT_EQ(canonical_latex(numeric(-1, 7)), "-\\frac{1}{7}");
    EXPECT_EQ(canonical_latex(pow(symbol("v'_x1", "v'_{x1}"), 2)), "{v'_{x1}}^{2}");
    // The printed text reads back as the same expression.
    parser reader;
    symtab table{{"a", a}, {"b", b}, {"c", c}, {"e", e}};
    parser reader2(table);
    ex f = (a - 2 * b) * pow(c, 3) / (3 * (a + e)) - numeric(5, 7);
    std::string t = canonical_text(f);
    for (std::size_t k; (k = t.find("·")) != std::string::npos;)
        t.replace(k, std::string("·").size(), "*");
    for (std::size_t k; (k = t.find("³")) != std::string::npos;)
        t.replace(k, std::string("³").size(), "^3");
    EXPECT_TRUE((reader2(t) - f).normal().is_zero()) << t;
    EXPECT_THROW(canonical_text(lst{a, b}), std::invalid_argument);
}

// A user's quantities print as the user wrote them: ω is the role of the angular velocities the
// model names (expr/roles.hpp), never a name pattern. Masses named w and weight, a velocity named
// w_x1 and bodies named t1 and n2 (whose effective inverse masses are w_t1, w_n2) once printed
// w_x1 as ω_x1 and w_t1 as ω_t1; these particles have no angular velocity at all.
TEST(Canonical, UserQuantitiesNamedLikeASpinPrintAsWritten)
{
    // Symbols are shared by name across a process (symbol_named): the classes that name their
    // spin w (with the TeX name \omega) are built first, so that this file's w is theirs, as it
    // would be in any process that built them, and so that later tests see their w unchanged.
    for (const char* cls : {"ball-floor-friction", "rod-rough-floor", "two-corner-landing"})
        find_named_class(cls)->build();
    const problem p = read_problem(R"({"dimension": 2, "restitution": "e",
        "bodies": [{"name": "t1", "mass": "w", "position": [-1, 0], "velocity": ["w_x1", 0]},
                   {"name": "n2", "mass": "weight", "position": [1, 0], "velocity": [0, 0]}],
        "contact": {"bodies": ["t1", "n2"], "point": [0, 0], "normal": [1, 0]}})",
                                   "user.json");
    const derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    const std::string formulas = formulas_text(d, s);
    EXPECT_NE(formulas.find("w_x1"), std::string::npos) << formulas;
    EXPECT_NE(formulas.find("weight"), std::string::npos) << formulas;
    EXPECT_NE(formulas.find("w_t1 = "), std::string::npos) << formulas;
    EXPECT_EQ(formulas.find("ω"), std::string::npos) << formulas;
    const std::string text = explain_text(explain(d, s));
    EXPECT_NE(text.find("w_x1"), std::string::npos);
    EXPECT_EQ(text.find("ω"), std::string::npos) << text;
    const std::string latex = formulas_latex(d, s);
    EXPECT_NE(latex.find("w_{x1}"), std::string::npos) << latex;
    EXPECT_EQ(latex.find("omega_{x1}"), std::string::npos) << latex;
    // The model's own angular velocities keep their ω: a rigid body's after impact.
    const derivation planar = derive(find_named_class("planar")->build());
    EXPECT_NE(formulas_text(planar, solve_impact(planar)).find("ω′_b1 = "), std::string::npos);
}
