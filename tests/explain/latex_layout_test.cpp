// The LaTeX layout of explain: a document a teacher prints unedited. Every named
// class and every example and test problem compiles with pdflatex with no
// overfull box and no undefined reference; long rows are broken into lines that
// each fit the text width, with their \left( \right) balanced on every line;
// tags of any text get labels that are safe identifiers.
#include "latex_tools.hpp"
#include "print/explain.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/named_systems.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <iostream>

using namespace impactgen;
using namespace impactgen::print;
using namespace GiNaC;
namespace fs = std::filesystem;

namespace {

// A document to print: a named class (with the notes' worked example where
// there is one) or a problem file (examples/problems, tests/explain), with
// Coulomb friction or without, as `impactgen explain` builds it.
document explain_any(const problem& p, const std::string& class_name)
{
    derivation d = derive(p);
    if (p.is_system())
        return explain_system(d);
    worked_example ex;
    bool has = !class_name.empty() && notes_example(class_name, ex);
    return explain(d, solve_impact(d), has ? &ex : nullptr);
}

const std::string source_dir = IMPACTGEN_SOURCE_DIR;

// The problem files, sorted: examples/problems/*.json, examples/friction/*.json, examples/laws/*.json,
// examples/systems/*.json, tests/explain/*.json.
std::vector<fs::path> problem_files()
{
    std::vector<fs::path> out;
    for (const char* dir : {"/examples/problems", "/examples/friction", "/examples/laws", "/examples/systems", "/tests/explain"}) {
        std::vector<fs::path> here;
        for (const auto& entry : fs::directory_iterator(source_dir + dir))
            if (entry.path().extension() == ".json")
                here.push_back(entry.path());
        std::sort(here.begin(), here.end());
        out.insert(out.end(), here.begin(), here.end());
    }
    return out;
}

// The name of every document: the classes, then the problem files by stem, then
// hostile-names with friction (every special character of LaTeX in body names).
std::vector<std::string> document_names()
{
    std::vector<std::string> out;
    for (const named_class& c : named_classes())
        out.push_back(c.name);
    for (const named_class& c : friction_classes())
        out.push_back(c.name);
    for (const fs::path& f : problem_files())
        out.push_back(f.stem().string());
    out.push_back("hostile-names-friction");
    return out;
}

document build(const std::string& name)
{
    // The smooth and friction classes by name; a named system class shares its name with the
    // example file of the same system (examples/systems), which is the document meant here.
    const named_class* c = find_named_class(name);
    for (const named_class& s : system_classes())
        c = s.name == name ? nullptr : c;
    if (c)
        return explain_any(c->build(), name);
    if (name == "hostile-names-friction") {
        std::string hostile = latex_tools::read_file(source_dir + "/tests/explain/hostile-names.json");
        const std::string normal = "\"normal\": [1, 0]}";
        std::size_t at = hostile.find(normal);
        if (at == std::string::npos)
            throw std::runtime_error("tests/explain/hostile-names.json has no " + normal);
        hostile.replace(at, normal.size(), "\"normal\": [1, 0], \"friction\": \"errno\"}");
        return explain_any(read_problem(hostile, "hostile-names-friction.json"), "");
    }
    for (const fs::path& f : problem_files())
        if (f.stem().string() == name)
            return explain_any(read_problem(latex_tools::read_file(f), f.filename().string()), "");
    throw std::runtime_error("no document " + name);
}

std::string test_name(const std::string& name)
{
    std::string n = name;
    for (char& c : n)
        if (!std::isalnum(static_cast<unsigned char>(c)))
            c = '_';
    return n;
}

// The lines of the first environment `env` in `tex` (split at \\), without tags and labels.
std::vector<std::string> environment_lines(const std::string& tex, const std::string& env)
{
    std::vector<std::string> lines;
    const std::string begin = "\\begin{" + env + "}", end = "\\end{" + env + "}";
    std::size_t a = tex.find(begin);
    if (a == std::string::npos)
        return lines;
    a += begin.size();
    std::size_t b = tex.find(end, a);
    std::string body = tex.substr(a, b - a);
    std::size_t from = 0;
    while (true) {
        std::size_t at = body.find("\\\\", from);
        lines.push_back(body.substr(from, at == std::string::npos ? std::string::npos : at - from));
        if (at == std::string::npos)
            break;
        from = at + 2;
    }
    // Without \tag{...}, \label{...}, and a leading "*" or "[...]" (what follows "\\").
    // (Plain code, not <regex>: std::regex costs minutes to compile under ASan.)
    for (std::string& l : lines) {
        for (const char* command : {"\\tag{", "\\label{"})
            for (std::size_t at = l.find(command); at != std::string::npos; at = l.find(command, at)) {
                std::size_t end = l.find('}', at);
                l.erase(at, end == std::string::npos ? std::string::npos : end + 1 - at);
            }
        if (!l.empty() && l[0] == '*')
            l.erase(0, 1);
        else if (!l.empty() && l[0] == '[' && l.find(']') != std::string::npos)
            l.erase(0, l.find(']') + 1);
    }
    return lines;
}

// \left and \right (whole commands) on a line.
int count_command(const std::string& s, const std::string& command)
{
    int n = 0;
    for (std::size_t at = s.find(command); at != std::string::npos; at = s.find(command, at + 1))
        if (at + command.size() >= s.size() || !std::isalpha(static_cast<unsigned char>(s[at + command.size()])))
            ++n;
    return n;
}

bool braces_balanced(const std::string& s)
{
    int depth = 0;
    for (std::size_t k = 0; k < s.size(); ++k) {
        if (s[k] == '\\') {
            ++k; // \{ \}
            continue;
        }
        depth += s[k] == '{' ? 1 : s[k] == '}' ? -1 : 0;
        if (depth < 0)
            return false;
    }
    return depth == 0;
}

document one_row(const math_row& r)
{
    document doc{"A long row", {}};
    section sec{"The row", {}};
    sec.para(paragraph().w("The row ").ref(r.tag).w(" is long:"));
    sec.rows({r});
    doc.sections.push_back(sec);
    return doc;
}

// 40 long terms: m_{body k} v_{t,body k} w_{n,body k} r_{b,body k}.
ex long_sum(int terms)
{
    ex sum = 0;
    for (int k = 1; k <= terms; ++k) {
        std::string b = "body" + std::to_string(k);
        sum += symbol("m_" + b, "m_{" + b + "}") * symbol("v_t" + b, "v_{t," + b + "}") *
               symbol("w_n" + b, "\\omega_{n," + b + "}") * symbol("r_b" + b, "r_{b," + b + "}");
    }
    return sum;
}

// Every line of the displayed row fits the width model's budget, and is balanced.
void expect_broken_and_balanced(const std::string& tex, const std::string& env, std::size_t min_lines)
{
    std::vector<std::string> lines = environment_lines(tex, env);
    ASSERT_GE(lines.size(), min_lines) << tex;
    for (const std::string& line : lines) {
        EXPECT_LE(layout::estimated_width_em(line), layout::row_budget_em()) << line;
        EXPECT_EQ(count_command(line, "\\left"), count_command(line, "\\right")) << line;
        EXPECT_TRUE(braces_balanced(line)) << line;
    }
}

} // namespace

class LatexLayout : public ::testing::TestWithParam<std::string> {};

// The whole document: pdflatex twice (references), no overfull box, every
// reference defined, every label once; the page count for the record.
TEST_P(LatexLayout, CompilesCleanly)
{
    if (!latex_tools::have_pdflatex())
        GTEST_SKIP() << latex_tools::no_pdflatex_message();
    const std::string tex = explain_latex(build(GetParam()));
    latex_tools::compiled c = latex_tools::compile(tex, test_name(GetParam()));
    ASSERT_EQ(c.status, 0) << GetParam() << ":\n" << c.log.substr(c.log.size() > 3000 ? c.log.size() - 3000 : 0);
    EXPECT_EQ(c.overfull_hbox, 0) << GetParam() << ":\n" << latex_tools::around(c.log, "Overfull \\hbox");
    EXPECT_EQ(c.overfull_vbox, 0) << GetParam() << ":\n" << latex_tools::around(c.log, "Overfull \\vbox");
    EXPECT_EQ(c.undefined_refs, 0) << GetParam() << ":\n" << latex_tools::around(c.log, "LaTeX Warning: Reference");
    EXPECT_EQ(c.multiply_defined, 0) << GetParam() << ":\n" << latex_tools::around(c.log, "multiply defined");
    // Every label is a safe identifier.
    for (std::size_t at = tex.find("\\label{"); at != std::string::npos; at = tex.find("\\label{", at + 1)) {
        const std::size_t start = at + 7, end = tex.find('}', start);
        ASSERT_NE(end, std::string::npos);
        const std::string key = tex.substr(start, end - start);
        bool safe = key.size() > 3 && key.compare(0, 3, "eq:") == 0;
        for (std::size_t k = 3; k < key.size(); ++k)
            safe = safe && std::isalnum(static_cast<unsigned char>(key[k]));
        EXPECT_TRUE(safe) << key;
    }
    std::cout << "[ latex    ] " << GetParam() << ": " << c.pages << " pages, overfull hbox " << c.overfull_hbox
              << ", overfull vbox " << c.overfull_vbox << ", undefined references " << c.undefined_refs << "\n";
}

INSTANTIATE_TEST_SUITE_P(Documents, LatexLayout, ::testing::ValuesIn(document_names()),
                         [](const auto& info) { return test_name(info.param); });

// A sum of 40 long terms: broken at its + signs into lines that each fit.
TEST(LatexBreaking, LongSumIsSplitIntoLinesThatFit)
{
    math_row r;
    r.tag = "1a";
    r.lhs = symbol("x");
    r.rhs = long_sum(40);
    const std::string tex = explain_latex(one_row(r));
    expect_broken_and_balanced(tex, "align*", 5);
    // Markdown: the same lines inside aligned
    const std::string md = explain_markdown(one_row(r));
    expect_broken_and_balanced(md, "aligned", 5);
}

// The same sum inside parentheses, x = k (sum): one top-level term, broken one
// level down, every line closed with \right. and reopened with \left.
TEST(LatexBreaking, ParenthesisedSumBreaksInsideWithBalancedDelimiters)
{
    math_row r;
    r.tag = "3'";
    r.lhs = symbol("x");
    r.rhs = symbol("k") * (long_sum(40) + symbol("c"));
    const std::string tex = explain_latex(one_row(r));
    expect_broken_and_balanced(tex, "align*", 5);
    EXPECT_NE(tex.find("\\right."), std::string::npos);
    EXPECT_NE(tex.find("\\left."), std::string::npos);
}

// A fraction with a long numerator, x = -2 (sum) / d: set as -2/d times the sum.
TEST(LatexBreaking, LongFractionBecomesFactorTimesBrokenSum)
{
    math_row r;
    r.tag = "z";
    r.lhs = symbol("x");
    r.rhs = -2 * (long_sum(30) + symbol("c")) / symbol("d");
    const std::string tex = explain_latex(one_row(r));
    expect_broken_and_balanced(tex, "align*", 4);
    EXPECT_NE(tex.find("\\frac{2}{d}"), std::string::npos) << tex;
}

// A long lhs and a long rhs: "lhs =" first, then the rhs on lines of its own.
TEST(LatexBreaking, LongLhsAndRhsTakeLinesOfTheirOwn)
{
    math_row r;
    r.tag = "7";
    r.lhs = long_sum(8);
    r.rhs = long_sum(12) + 1;
    const std::string tex = explain_latex(one_row(r));
    expect_broken_and_balanced(tex, "align*", 3);
    std::vector<std::string> lines = environment_lines(tex, "align*");
    std::size_t with_relation = lines.size();
    for (std::size_t k = 0; k < lines.size(); ++k)
        if (lines[k].find('=') != std::string::npos) {
            EXPECT_EQ(with_relation, lines.size()) << "a second = in " << lines[k];
            with_relation = k;
        }
    ASSERT_LT(with_relation + 1, lines.size()) << tex;
    std::string line = lines[with_relation];
    line.erase(line.find_last_not_of(" \n") + 1);
    EXPECT_EQ(line.back(), '=') << "the lhs line ends with =: " << line;
    EXPECT_NE(lines[with_relation + 1].find("1 +"), std::string::npos) << "the rhs starts the next line";
}

// The synthetic rows compile without an overfull box, and references to tags
// like 3', 1a and z resolve.
TEST(LatexBreaking, SyntheticRowsCompileAndReferencesResolve)
{
    if (!latex_tools::have_pdflatex())
        GTEST_SKIP() << latex_tools::no_pdflatex_message();
    document doc{"Long rows", {}};
    section sec{"Rows", {}};
    std::vector<math_row> rows(3);
    rows[0].tag = "1a";
    rows[0].lhs = symbol("x");
    rows[0].rhs = long_sum(40);
    rows[1].tag = "3'";
    rows[1].lhs = symbol("y");
    rows[1].rhs = symbol("k") * (long_sum(40) + symbol("c"));
    rows[2].tag = "z";
    rows[2].lhs = symbol("u");
    rows[2].rhs = -2 * (long_sum(30) + symbol("c")) / symbol("d");
    rows[2].note.w("a note under the row that is far too long to be set beside it, so it goes under it, wrapped");
    sec.para(paragraph().w("Rows ").ref("1a").w(", ").ref("3'").w(" and ").ref("z").w(", and in prose ").m(long_sum(6) * symbol("k")).w("."));
    sec.rows(rows);
    doc.sections.push_back(sec);
    latex_tools::compiled c = latex_tools::compile(explain_latex(doc), "synthetic");
    ASSERT_EQ(c.status, 0) << c.log.substr(c.log.size() > 3000 ? c.log.size() - 3000 : 0);
    EXPECT_EQ(c.overfull_hbox, 0) << latex_tools::around(c.log, "Overfull \\hbox");
    EXPECT_EQ(c.overfull_vbox, 0) << latex_tools::around(c.log, "Overfull \\vbox");
    EXPECT_EQ(c.undefined_refs, 0) << latex_tools::around(c.log, "LaTeX Warning: Reference");
    EXPECT_EQ(c.multiply_defined, 0);
}
