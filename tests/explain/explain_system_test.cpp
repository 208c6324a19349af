// impactgen explain of a system (format version 3): the numbers of the document are
// solve_system's answer, the equations it shows hold at that answer, the candidate the
// document says holds is the solver's, the sequential chain step by step and the other model, a symbolic
// double pendulum's candidates with their conditions, golden files in every format.
#include "print/explain.hpp"
#include "symbolic/derivation.hpp"
#include "symbolic/named_systems.hpp"
#include "symbolic/system.hpp"
#include "symbolic/system_process.hpp"

#include "latex_tools.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

const fs::path systems_dir = fs::path(IMPACTGEN_SOURCE_DIR) / "examples/systems";

problem load_example(const std::string& stem)
{
    return read_problem(read_file(systems_dir / (stem + ".json")), stem + ".json");
}

std::vector<std::string> example_stems()
{
    std::vector<std::string> out;
    for (const auto& f : fs::directory_iterator(systems_dir))
        if (f.path().extension() == ".json")
            out.push_back(f.path().stem().string());
    std::sort(out.begin(), out.end());
    return out;
}

const section* section_titled(const document& doc, const std::string& words)
{
    for (const section& s : doc.sections)
        if (s.title.find(words) != std::string::npos)
            return &s;
    return nullptr;
}

std::vector<math_row> rows_of(const section& s)
{
    std::vector<math_row> out;
    for (const block& b : s.blocks)
        out.insert(out.end(), b.math.begin(), b.math.end());
    return out;
}

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

bool equal(const ex& a, const ex& b) { return normal(a - b).is_zero(); }

// The row whose left side is `sym`, or null.
const math_row* row_for(const std::vector<math_row>& rows, const ex& sym)
{
    for (const math_row& r : rows)
        if (r.lhs_note.text.empty() && r.lhs.is_equal(sym))
            return &r;
    return nullptr;
}

// The row whose left side is a symbol named as `sym` (each derivation makes its own symbols).
const math_row* row_named(const std::vector<math_row>& rows, const ex& sym)
{
    for (const math_row& r : rows)
        if (r.lhs_note.text.empty() && is_a<symbol>(r.lhs) &&
            ex_to<symbol>(r.lhs).get_name() == ex_to<symbol>(sym).get_name())
            return &r;
    return nullptr;
}

const math_row* note_row_for(const std::vector<math_row>& rows, const std::string& text)
{
    for (const math_row& r : rows)
        if (r.lhs_note.text == text)
            return &r;
    return nullptr;
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

} // namespace

// Every example: each velocity after impact, each impulse and the energies in the Results
// section are exactly solve_system's, and every equation the document numbers holds there.
TEST(SystemExplain, NumbersAreSolveSystemsAnswer)
{
    for (const std::string& stem : example_stems()) {
        SCOPED_TRACE(stem);
        const problem p = load_example(stem);
        const derivation d = derive(p);
        const document doc = explain_system(d);
        const system_answer a = solve_system(p);
        const section* res = section_titled(doc, "Results");
        ASSERT_NE(res, nullptr);
        const std::vector<math_row> rows = rows_of(*res);
        std::size_t checked = 0;
        for (std::size_t b = 0; b < p.bodies.size(); ++b)
            for (int k = 0; k < 3; ++k) {
                if (is_a<symbol>(d.velocity_after[b][k])) {
                    const math_row* r = row_for(rows, d.velocity_after[b][k]);
                    ASSERT_NE(r, nullptr) << d.velocity_after[b][k];
                    EXPECT_TRUE(equal(r->rhs, a.result.velocity[b][k])) << r->rhs << " vs " << a.result.velocity[b][k];
                    ++checked;
                }
                if (is_a<symbol>(d.angular_velocity_after[b][k])) {
                    const math_row* r = row_for(rows, d.angular_velocity_after[b][k]);
                    ASSERT_NE(r, nullptr);
                    EXPECT_TRUE(equal(r->rhs, a.result.angular_velocity[b][k]));
                    ++checked;
                }
            }
        for (std::size_t i = 0; i < p.contacts.size(); ++i) {
            const math_row* r = row_for(rows, d.system_normal_impulse[i]);
            ASSERT_NE(r, nullptr);
            EXPECT_TRUE(equal(r->rhs, a.result.normal_impulse[i]));
            ++checked;
        }
        EXPECT_GT(checked, p.contacts.size());
        const math_row* T = note_row_for(rows, "T");
        const math_row* T2 = note_row_for(rows, "T′");
        ASSERT_TRUE(T && T2);
        EXPECT_TRUE(equal(T->rhs, a.energy_before));
        EXPECT_TRUE(equal(T2->rhs, a.energy_after));
        // The numbered equations of the bodies and joints hold at the answer.
        const lst at = system_unknown_values(d, a.result);
        std::size_t numbered = 0;
        for (const section& s : doc.sections)
            for (const math_row& r : rows_of(s))
                if (!r.tag.empty() && r.rel == "=") {
                    EXPECT_TRUE(equal(r.lhs.subs(at), r.rhs.subs(at))) << s.title << " (" << r.tag << ")";
                    ++numbered;
                }
        EXPECT_EQ(numbered, d.equations.size());
    }
}

// The candidate the document says holds is the one solve_system chose; every other
// candidate is said to fail, naming a condition.
TEST(SystemExplain, HoldingCandidateIsTheSolvers)
{
    for (const std::string stem : {"compass-gait", "three-balls-simultaneous", "two-corner-landing"}) {
        SCOPED_TRACE(stem);
        const problem p = load_example(stem);
        const document doc = explain_system(derive(p));
        const system_answer a = solve_system(p);
        const std::string text = flat(explain_text(doc));
        EXPECT_NE(text.find("The law holds for " + a.result.name() + "."), std::string::npos) << text;
        std::size_t fails = 0, holds = 0;
        for (const system_candidate& c : system_candidates(p)) {
            const bool ok = system_candidate_failure(c) < 0;
            const std::string line = c.name() + (ok ? ": holds" : ": fails");
            EXPECT_NE(text.find(line), std::string::npos) << line;
            (ok ? holds : fails) += 1;
        }
        EXPECT_GE(holds, 1u);
        EXPECT_GE(fails, 1u);
    }
}

// Sequential impacts: one step per contact that acted, in the solver's order, each with its
// impulse; the three balls at e = 1 end with (0, 0, v).
TEST(SystemExplain, SequentialChainStepByStep)
{
    const problem p = load_example("three-balls-sequential");
    const derivation d = derive(p);
    const document doc = explain_system(d);
    const system_answer a = solve_system(p);
    ASSERT_EQ(a.sequence.size(), 2u);
    const section* chain = section_titled(doc, "chain");
    ASSERT_NE(chain, nullptr);
    EXPECT_EQ(section_titled(doc, "candidate sets"), nullptr);
    const std::string text = flat(explain_text(doc));
    for (std::size_t k = 0; k < a.sequence.size(); ++k)
        EXPECT_NE(text.find("Step " + std::to_string(k + 1) + ": contact " + std::to_string(a.sequence[k]) +
                            " approaches and acts"),
                  std::string::npos);
    // each step's impulse row is that step's impulse
    const std::vector<math_row> rows = rows_of(*chain);
    std::size_t seen = 0;
    for (const math_row& r : rows)
        if (r.lhs.is_equal(d.system_normal_impulse[0]) || r.lhs.is_equal(d.system_normal_impulse[1])) {
            const std::size_t step = seen / 2, i = seen % 2;
            EXPECT_TRUE(equal(r.rhs, a.steps[step].normal_impulse[i]));
            ++seen;
        }
    EXPECT_EQ(seen, 2 * a.steps.size());
    const math_row* vc = row_for(rows_of(*section_titled(doc, "Results")), d.velocity_after[2][0]);
    ASSERT_NE(vc, nullptr);
    EXPECT_TRUE(equal(vc->rhs, 1));
    // the other model (simultaneous), as solve_system gives it: ((1 - 2e)/3, (1 + e)/3, (1 + e)/3) v at e = 1
    problem at_once = p;
    at_once.sequential = false;
    const system_answer s = solve_system(at_once);
    const section* other = section_titled(doc, "other model");
    ASSERT_NE(other, nullptr);
    for (std::size_t b = 0; b < 3; ++b) {
        const math_row* r = row_for(rows_of(*other), d.velocity_after[b][0]);
        ASSERT_NE(r, nullptr);
        EXPECT_TRUE(equal(r->rhs, s.result.velocity[b][0]));
        EXPECT_TRUE(equal(r->rhs, b == 0 ? ex(-1) / 3 : ex(2) / 3));
    }
    EXPECT_NE(text.find("They differ."), std::string::npos);
}

// A symbolic double pendulum struck by a ball: every candidate of system_candidates with its
// closed form and its conditions (the open contact's and the acting one's), and no results.
TEST(SystemExplain, SymbolicDoublePendulumCandidatesWithConditions)
{
    const std::string json = R"({
      "dimension": 2, "restitution": "e",
      "bodies": [
        { "name": "upper", "mass": "m", "inertia": "m*l^2/12", "position": [0, "-l/2"], "velocity": [0, 0], "angular_velocity": 0 },
        { "name": "lower", "mass": "m", "inertia": "m*l^2/12", "position": [0, "-3*l/2"], "velocity": [0, 0], "angular_velocity": 0 },
        { "name": "ball", "mass": "M", "position": ["-r", "-2*l"], "velocity": ["v", 0] }
      ],
      "pivots": [ { "body": "upper", "point": [0, 0] } ],
      "joints": [ { "bodies": ["upper", "lower"], "point": [0, "-l"] } ],
      "contacts": [ { "bodies": ["ball", "lower"], "point": [0, "-2*l"], "normal": [1, 0] } ]
    })";
    const problem p = read_problem(json, "double-pendulum-symbolic.json");
    ASSERT_FALSE(p.is_numeric());
    const derivation d = derive(p);
    const document doc = explain_system(d);
    EXPECT_EQ(section_titled(doc, "Results"), nullptr);
    const section* cands = section_titled(doc, "candidate sets");
    ASSERT_NE(cands, nullptr);
    const std::vector<system_candidate> cs = system_candidates(p);
    ASSERT_EQ(cs.size(), 2u); // open, smooth
    const std::string text = flat(explain_text(doc));
    const std::vector<math_row> rows = rows_of(*cands);
    for (const system_candidate& c : cs) {
        EXPECT_NE(text.find("Candidate " + c.name() + ":"), std::string::npos) << c.name();
        ASSERT_FALSE(c.conditions.empty());
        for (const system_condition& k : c.conditions) {
            bool found = false;
            for (const math_row& r : rows)
                found = found || (r.rel == "≥" && equal(r.lhs, k.value));
            EXPECT_TRUE(found) << k.words;
            EXPECT_NE(text.find(k.words), std::string::npos);
        }
        bool impulse = false;
        for (const math_row& r : rows)
            impulse = impulse || (r.lhs.is_equal(d.system_normal_impulse[0]) && equal(r.rhs, c.normal_impulse[0]));
        EXPECT_TRUE(impulse) << c.name();
    }
    // the smooth candidate's impulse depends on the symbols (a closed form, not a number)
    EXPECT_FALSE(is_a<numeric>(cs[1].normal_impulse[0]));
    EXPECT_NE(text.find("Delassus"), std::string::npos);
}

// Golden files: four examples of systems in every format. IMPACTGEN_REGENERATE_GOLDEN=1 (or
// `make regenerate-golden-explain`) rewrites them.
TEST(SystemGolden, ExamplesEveryFormat)
{
    const bool regenerate = std::getenv("IMPACTGEN_REGENERATE_GOLDEN") != nullptr;
    const fs::path dir = IMPACTGEN_GOLDEN_DIR;
    for (const std::string stem :
         {"compass-gait", "three-balls-sequential", "three-balls-simultaneous", "double-pendulum-struck"}) {
        const document doc = explain_system(derive(load_example(stem)));
        for (const std::string format : {"text", "markdown", "latex", "html"}) {
            const fs::path file = dir / ("system-" + stem + "." + extension(format));
            const std::string out = print_as(doc, format);
            if (regenerate) {
                if (!fs::exists(file) || read_file(file) != out)
                    std::ofstream(file, std::ios::binary) << out;
                continue;
            }
            ASSERT_TRUE(fs::exists(file)) << file << " is missing: run make regenerate-golden-explain";
            EXPECT_EQ(read_file(file), out) << file << " differs from the output: regenerate and review the diff";
        }
    }
}

// The command line explains a system.
TEST(Cli, SystemExplains)
{
    int status = 0;
    const std::string file = (systems_dir / "compass-gait.json").string();
    const std::string out = run(std::string(IMPACTGEN_CLI) + " explain '" + file + "' --format latex 2>&1", status);
    EXPECT_EQ(WEXITSTATUS(status), 0) << out;
    EXPECT_NE(out.find("Delassus"), std::string::npos);
    EXPECT_NE(out.find("\\documentclass"), std::string::npos);
}

// A body's spin after impact is named as one contact names it, with its axis (ω′_z,stance in
// the plane), never with an empty axis (the stray "ω′_,stance" of a first version).
TEST(SystemExplain, SpinNamesCarryTheirAxis)
{
    for (const std::string& stem : example_stems()) {
        SCOPED_TRACE(stem);
        const document doc = explain_system(derive(load_example(stem)));
        for (const char* format : {"text", "latex"}) {
            const std::string out = print_as(doc, format);
            EXPECT_EQ(out.find("_,"), std::string::npos) << format;
            EXPECT_EQ(out.find("_{,"), std::string::npos) << format;
        }
    }
}

// A system's document is a hand-out: its conditions are in words, with no key of the problem
// file (contacts[0]) and no word about the software (the solver's formulas text had both).
TEST(SystemExplain, ConditionsInWordsWithoutFileKeys)
{
    for (const std::string& stem : example_stems()) {
        SCOPED_TRACE(stem);
        const std::string out = print_as(explain_system(derive(load_example(stem))), "text");
        EXPECT_EQ(out.find("contacts["), std::string::npos);
        EXPECT_EQ(out.find("impactgen"), std::string::npos);
        EXPECT_EQ(out.find(">= 0 ("), std::string::npos);
    }
}

namespace {

// The document `impactgen explain CLASS [--level summary]` prints for a named system class.
document class_document(const std::string& name, level depth = level::full)
{
    worked_example ex;
    EXPECT_TRUE(system_example(name, ex)) << name;
    return explain_system(derive(find_named_class(name)->build()), &ex, depth);
}

} // namespace

// Golden files of every named system class, the full document and the summary, in every format.
TEST(SystemGolden, NamedClassesEveryFormat)
{
    const bool regenerate = std::getenv("IMPACTGEN_REGENERATE_GOLDEN") != nullptr;
    const fs::path dir = IMPACTGEN_GOLDEN_DIR;
    for (const named_class& c : system_classes())
        for (const level depth : {level::full, level::summary}) {
            const document doc = class_document(c.name, depth);
            for (const std::string format : {"text", "markdown", "latex", "html"}) {
                const fs::path file = dir / ((depth == level::summary ? "summary/system-" : "system-class-") + c.name +
                                             "." + extension(format));
                const std::string out = print_as(doc, format);
                if (regenerate) {
                    if (!fs::exists(file) || read_file(file) != out)
                        std::ofstream(file, std::ios::binary) << out;
                    continue;
                }
                ASSERT_TRUE(fs::exists(file)) << file << " is missing: run make regenerate-golden-explain";
                EXPECT_EQ(read_file(file), out) << file << " differs from the output: regenerate and review the diff";
                if (read_file(file) != out)
                    std::ofstream(fs::temp_directory_path() / file.filename(), std::ios::binary) << out;
            }
        }
}

// A named system class is taught in symbols (every candidate with its conditions), then with
// its worked example's numbers: the candidate the document says holds is solve_system's for
// those numbers, and the results are its answer.
TEST(SystemExplain, NamedClassesTeachTheirWorkedExample)
{
    for (const named_class& c : system_classes()) {
        SCOPED_TRACE(c.name);
        const problem p = c.build();
        worked_example ex;
        ASSERT_TRUE(system_example(c.name, ex));
        const problem q = substitute(p, ex.values);
        const system_answer a = solve_system(q);
        const document doc = class_document(c.name);
        const std::string text = flat(explain_text(doc));
        EXPECT_NE(text.find("The law holds for " + a.result.name() + "."), std::string::npos);
        for (const system_candidate& k : system_candidates(p))
            EXPECT_NE(text.find("Candidate " + k.name() + ":"), std::string::npos) << k.name();
        const section* res = section_titled(doc, "Results of the worked example");
        ASSERT_NE(res, nullptr);
        const derivation dq = derive(q);
        for (std::size_t b = 0; b < q.bodies.size(); ++b)
            for (int k = 0; k < 3; ++k)
                if (is_a<symbol>(dq.velocity_after[b][k])) {
                    const math_row* r = row_named(rows_of(*res), dq.velocity_after[b][k]);
                    ASSERT_NE(r, nullptr);
                    EXPECT_TRUE(equal(r->rhs, a.result.velocity[b][k]));
                }
        // a figure, drawn with the example's numbers
        bool figure = false;
        for (const block& b : doc.sections.front().blocks)
            figure = figure || b.k == block::figure;
        EXPECT_TRUE(figure);
    }
}

// three-balls: the document teaches both models -- the simultaneous closed form in symbols,
// the worked example (e = 1) at the same time, and the chain of the sequential model step by
// step, ending with (0, 0, v) -- and why they differ.
TEST(SystemExplain, ThreeBallsTeachesBothModelsAndWhyTheyDiffer)
{
    const document doc = class_document("three-balls");
    const std::string text = flat(explain_text(doc));
    const section* other = section_titled(doc, "other model");
    ASSERT_NE(other, nullptr);
    const std::string other_text = flat(explain_text(document{"", {*other}}));
    EXPECT_NE(other_text.find("one at a time, in sequence"), std::string::npos);
    EXPECT_NE(other_text.find("Step 1: contact 0 approaches and acts"), std::string::npos) << other_text;
    EXPECT_NE(other_text.find("Step 2: contact 1 approaches and acts"), std::string::npos);
    EXPECT_NE(other_text.find("They differ."), std::string::npos);
    EXPECT_NE(other_text.find("do not fix the outcome"), std::string::npos);
    const derivation d = derive(find_named_class("three-balls")->build());
    const std::vector<math_row> rows = rows_of(*other);
    // the first rows are the sequential velocities: 0, 0, 1 (v = 1)
    const math_row* v3 = row_named(rows, d.velocity_after[2][0]);
    ASSERT_NE(v3, nullptr);
    EXPECT_TRUE(equal(v3->rhs, 1));
    const math_row* v1 = row_named(rows, d.velocity_after[0][0]);
    ASSERT_NE(v1, nullptr);
    EXPECT_TRUE(equal(v1->rhs, 0));
}

// A system's document never quotes a key of the problem file or writes "(s)" for a count.
TEST(SystemExplain, HandOutWordsNoFileKeysNoPluralsInParentheses)
{
    std::vector<document> docs;
    for (const std::string& stem : example_stems())
        docs.push_back(explain_system(derive(load_example(stem))));
    for (const named_class& c : system_classes()) {
        docs.push_back(class_document(c.name));
        docs.push_back(class_document(c.name, level::summary));
    }
    for (const document& doc : docs) {
        SCOPED_TRACE(doc.title);
        const std::string out = explain_text(doc);
        for (const char* word : {"(s)", "\"friction\"", "\"inf\"", "\"impacts\"", "energy_gain", "\"sequential\"",
                                 "\"simultaneous\"", "the answer's", "solver", "impactgen", "contacts["})
            EXPECT_EQ(out.find(word), std::string::npos) << word;
    }
}

// The summary of a system: one page of LaTeX for every named system class and example file.
TEST(SystemSummary, LatexCompilesToOnePage)
{
    if (!latex_tools::have_pdflatex())
        GTEST_SKIP() << latex_tools::no_pdflatex_message();
    for (const named_class& c : system_classes()) {
        const latex_tools::compiled out =
            latex_tools::compile(explain_latex(class_document(c.name, level::summary)), "system-summary-" + c.name);
        ASSERT_EQ(out.status, 0) << c.name;
        EXPECT_EQ(out.pages, 1) << c.name;
        EXPECT_EQ(out.overfull_hbox, 0) << c.name << latex_tools::around(out.log, "Overfull \\hbox");
    }
}

// The summary boxes the answer: every velocity after impact of a numeric system, its impulses,
// and which contacts act.
TEST(SystemSummary, BoxesTheAnswer)
{
    for (const std::string& stem : example_stems()) {
        SCOPED_TRACE(stem);
        const problem p = load_example(stem);
        const derivation d = derive(p);
        const document doc = explain_system(d, nullptr, level::summary);
        const system_answer a = solve_system(p);
        std::vector<math_row> boxed;
        for (const section& s : doc.sections)
            for (const block& b : s.blocks)
                if (b.boxed)
                    boxed.insert(boxed.end(), b.math.begin(), b.math.end());
        const lst values = system_unknown_values(d, a.result);
        std::size_t nonzero = 0;
        const std::string text = flat(explain_text(doc));
        for (const ex& v : values) {
            const math_row* r = row_for(boxed, v.lhs());
            if (v.rhs().is_zero()) { // not boxed: named in the line of zeros
                EXPECT_EQ(r, nullptr) << v.lhs();
                continue;
            }
            ++nonzero;
            ASSERT_NE(r, nullptr) << v.lhs();
            EXPECT_TRUE(equal(r->rhs, v.rhs()));
        }
        EXPECT_EQ(boxed.size(), nonzero);
        EXPECT_EQ(text.find("Zero: ") != std::string::npos, nonzero < values.nops());
        EXPECT_NE(text.find("Which contacts act:"), std::string::npos);
    }
}

// The full document of every named system class compiles with pdflatex, with no overfull box.
TEST(SystemExplain, NamedClassesLatexCompiles)
{
    if (!latex_tools::have_pdflatex())
        GTEST_SKIP() << latex_tools::no_pdflatex_message();
    for (const named_class& c : system_classes()) {
        const latex_tools::compiled out = latex_tools::compile(explain_latex(class_document(c.name)), "system-" + c.name);
        ASSERT_EQ(out.status, 0) << c.name;
        EXPECT_EQ(out.overfull_hbox, 0) << c.name << latex_tools::around(out.log, "Overfull \\hbox");
        EXPECT_EQ(out.undefined_refs, 0) << c.name;
    }
}

// A body's name with LaTeX's special characters is escaped in the unknowns' LaTeX names too
// (the velocities were not: "v'_{x,st%a_n#c}" commented out the rest of the line), and the
// HTML's MathML translation takes every name.
TEST(SystemExplain, HostileBodyNamesAreEscapedInTheUnknowns)
{
    std::ifstream in(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/compass-gait.json");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const auto &[from, to] : {std::pair<std::string, std::string>{"\"stance\"", "\"st%a_n#c\""},
                                   {"\"swing\"", "\"sw\\\\ing~^\""}})
        for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
            text.replace(at, from.size(), to);
    const document doc = explain_system(derive(read_problem(text, "hostile.json")));
    const std::string tex = explain_latex(doc);
    EXPECT_EQ(tex.find("st%a"), std::string::npos);
    EXPECT_NE(tex.find("v'_{x,\\text{st\\%a\\_n\\#c}}"), std::string::npos);
    EXPECT_NO_THROW(explain_html(doc));
}

namespace {

problem energetic_double_pendulum()
{
    const fs::path file = fs::path(IMPACTGEN_SOURCE_DIR) / "tests/explain/systems/double-pendulum-energetic.json";
    return read_problem(read_file(file), "double-pendulum-energetic.json");
}

} // namespace

// A system whose one contact follows Routh's process (a struck double pendulum, friction, the
// energetic law) is taught: the bodies' impulse-momentum, the Delassus matrix, the contact's
// response K in (t, n) from it, then the process as for one contact. Its phases and numbers are
// the library's answer (system_process_candidates, what `solve` prints), its equations numbered
// on from the bodies' and joints', and its golden files in every format.
TEST(SystemProcess, EnergeticDoublePendulumIsTaught)
{
    const problem p = energetic_double_pendulum();
    const derivation d = derive(p);
    const document doc = explain_system(d);
    const std::string text = explain_text(doc);
    std::vector<std::string> titles;
    for (const section& s : doc.sections)
        titles.push_back(s.title.substr(s.title.find(". ") + 2));
    auto at = [&](const std::string& t) { return std::find(titles.begin(), titles.end(), t) - titles.begin(); };
    for (const char* t : {"Impulse and momentum of each body", "The Delassus matrix",
                          "The contact's response in its frame", "Routh's process",
                          "The relative velocity as a function of the impulse", "Results"})
        EXPECT_LT(at(t), static_cast<long>(titles.size())) << t;
    EXPECT_LT(at("Impulse and momentum of each body"), at("The Delassus matrix"));
    EXPECT_LT(at("The Delassus matrix"), at("The contact's response in its frame"));
    EXPECT_LT(at("The contact's response in its frame"), at("Routh's process"));
    // The phases and the answer are the library's.
    const std::vector<system_candidate> cs = system_process_candidates(p);
    const system_candidate* c = nullptr;
    for (const system_candidate& k : cs)
        if (!k.process.empty())
            c = &k;
    ASSERT_NE(c, nullptr);
    std::string phases;
    for (const process_phase& ph : c->process)
        phases += (phases.empty() ? "" : ", ") + std::string(phase_name(ph.kind));
    EXPECT_LT(at("The phases: " + phases), static_cast<long>(titles.size())) << phases;
    std::ostringstream pn;
    pn << "P_0 = " << c->normal_impulse[0];
    EXPECT_NE(text.find(pn.str()), std::string::npos) << pn.str();
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        std::ostringstream v;
        v << "v′_x," << p.bodies[b].name << " = " << c->velocity[b][0];
        EXPECT_NE(text.find(v.str()), std::string::npos) << v.str();
    }
    // The process's rows are numbered after the bodies' and joints' equations.
    EXPECT_NE(text.find("(" + std::to_string(d.equations.size()) + ")"), std::string::npos);
    EXPECT_NE(text.find("(" + std::to_string(d.equations.size() + 1) + ")  dP_t = -s μ dP_n"), std::string::npos);
    EXPECT_EQ(text.find("(1)  dP_t"), std::string::npos);
    // Golden files.
    const bool regenerate = std::getenv("IMPACTGEN_REGENERATE_GOLDEN") != nullptr;
    for (const std::string format : {"text", "markdown", "latex", "html"}) {
        const fs::path file = fs::path(IMPACTGEN_GOLDEN_DIR) / ("system-double-pendulum-energetic." + extension(format));
        const std::string out = print_as(doc, format);
        if (regenerate) {
            if (!fs::exists(file) || read_file(file) != out)
                std::ofstream(file, std::ios::binary) << out;
            continue;
        }
        ASSERT_TRUE(fs::exists(file)) << file << " is missing: run make regenerate-golden-explain";
        EXPECT_EQ(read_file(file), out) << file << " differs from the output: regenerate and review the diff";
    }
}

// Its LaTeX compiles with pdflatex, with no overfull box.
TEST(SystemProcess, EnergeticDoublePendulumLatexCompiles)
{
    if (!latex_tools::have_pdflatex())
        GTEST_SKIP() << latex_tools::no_pdflatex_message();
    const latex_tools::compiled out =
        latex_tools::compile(explain_latex(explain_system(derive(energetic_double_pendulum()))), "system-process");
    ASSERT_EQ(out.status, 0);
    EXPECT_EQ(out.overfull_hbox, 0) << latex_tools::around(out.log, "Overfull \\hbox");
    EXPECT_EQ(out.undefined_refs, 0);
}
