// The HTML format of explain: the TeX-to-MathML translator (unit cases and
// every notation string of every document), the canonical printer's MathML,
// and the page explain_html writes (structure, anchors, escaping, figures).
// Rendering in a browser is browser_test.cpp.
#include "print/canonical.hpp"
#include "print/explain.hpp"
#include "print/tex_to_mathml.hpp"
#include "names/escape.hpp"
#include "symbolic/named_classes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace impactgen;
using namespace impactgen::print;
using namespace GiNaC;
namespace fs = std::filesystem;

namespace {

std::string read_file(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream os;
    os << in.rdbuf();
    return os.str();
}

// The document the CLI prints for a problem (smooth, or with friction).
document document_of(const problem& p, const std::string& class_name = "")
{
    derivation d = derive(p);
    worked_example ex;
    bool has = !class_name.empty() && notes_example(class_name, ex);
    return explain(d, solve_impact(d), has ? &ex : nullptr);
}

// Every document: the named classes, the friction classes, the example
// problems and the problem files of tests/explain (hostile names included).
std::vector<std::pair<std::string, document>> every_document()
{
    std::vector<std::pair<std::string, document>> docs;
    for (const named_class& c : named_classes())
        docs.push_back({c.name, document_of(c.build(), c.name)});
    for (const named_class& c : friction_classes())
        docs.push_back({c.name, document_of(c.build(), c.name)});
    std::vector<fs::path> files;
    for (const char* dir : {"examples/problems", "examples/friction", "examples/laws", "tests/explain"})
        for (const auto& entry : fs::directory_iterator(fs::path(IMPACTGEN_SOURCE_DIR) / dir))
            if (entry.path().extension() == ".json")
                files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files)
        docs.push_back({f.filename().string(), document_of(read_problem(read_file(f), f.filename().string()))});
    return docs;
}

// Every TeX string of notation in a document: note spans and rows' lhs_note.
std::vector<std::string> notation_of(const document& doc)
{
    std::vector<std::string> out;
    auto from = [&](const paragraph& p) {
        for (const span& s : p.spans)
            if (s.k == span::note)
                out.push_back(s.formula.tex);
    };
    for (const section& sec : doc.sections)
        for (const block& b : sec.blocks) {
            from(b.para);
            for (const paragraph& item : b.items)
                from(item);
            for (const math_row& r : b.math) {
                if (!r.lhs_note.text.empty())
                    out.push_back(r.lhs_note.tex);
                from(r.note);
            }
        }
    return out;
}

// Tags of generated markup are balanced (every element closed in order, no
// stray '<' in text): a small well-formedness check of XML fragments.
::testing::AssertionResult balanced(const std::string& xml)
{
    std::vector<std::string> open;
    for (std::size_t k = 0; k < xml.size(); ++k) {
        if (xml[k] == '>')
            return ::testing::AssertionFailure() << "a stray '>' at " << k << " in " << xml.substr(0, 300);
        if (xml[k] != '<')
            continue;
        std::size_t end = xml.find('>', k);
        if (end == std::string::npos)
            return ::testing::AssertionFailure() << "an unclosed tag in " << xml.substr(0, 300);
        std::string t = xml.substr(k + 1, end - k - 1);
        std::string name = t.substr(t[0] == '/' ? 1 : 0);
        name = name.substr(0, name.find_first_of(" /"));
        if (t[0] == '/') {
            if (open.empty() || open.back() != name)
                return ::testing::AssertionFailure() << "</" << name << "> closes " << (open.empty() ? "nothing" : open.back())
                                                     << " in " << xml.substr(0, 300);
            open.pop_back();
        } else if (t.back() != '/') {
            open.push_back(name);
        }
        k = end;
    }
    if (!open.empty())
        return ::testing::AssertionFailure() << "<" << open.back() << "> is never closed in " << xml.substr(0, 300);
    return ::testing::AssertionSuccess();
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// What a prime, an underline and a hat look like in the translator's MathML.
const std::string prime = "<mpadded voffset=\"-0.3em\"><mo mathsize=\"130%\">′</mo></mpadded>";
const std::string under = "<mo stretchy=\"true\">‾</mo>";
const std::string hat = "<mo>ˆ</mo>";

// The anchor of a tag: (3) is eq-3, (8') is eq-8', (e = 0) is eq-e-=-0.
std::string eq_id(const std::string& tag)
{
    std::string id = "eq-";
    for (char c : tag)
        if (!std::isspace(static_cast<unsigned char>(c)))
            id += c;
        else if (id.back() != '-')
            id += '-';
    return id;
}

std::size_t count(const std::string& s, const std::string& part)
{
    std::size_t n = 0;
    for (std::size_t k = s.find(part); k != std::string::npos; k = s.find(part, k + 1))
        ++n;
    return n;
}

} // namespace

// ------------------------------------------------------------ tex_to_mathml

TEST(TexToMathml, TheNotationOfTheNotes)
{
    // A vector with a prime and a subscript: one <msubsup> around the underlined v.
    EXPECT_EQ(tex_to_mathml("\\underline{v}'_{C_1}"),
              "<msubsup><munder accentunder=\"true\"><mi>v</mi>" + under + "</munder><msub><mi>C</mi><mn>1</mn></msub>" + prime +
                  "</msubsup>");
    EXPECT_EQ(tex_to_mathml("\\hat{\\underline{e}}_n"),
              "<msub><mover accent=\"true\"><munder accentunder=\"true\"><mi>e</mi>" + under + "</munder>" + hat +
                  "</mover><mi>n</mi></msub>");
    EXPECT_EQ(tex_to_mathml("\\int N\\,dt"), "<mo>∫</mo><mi>N</mi><mspace width=\"0.1667em\"></mspace><mi>d</mi><mi>t</mi>");
    EXPECT_EQ(tex_to_mathml("\\frac{1}{m_i}"), "<mfrac><mn>1</mn><msub><mi>m</mi><mi>i</mi></msub></mfrac>");
    EXPECT_EQ(tex_to_mathml("\\underline{\\underline{I}}_i^{-1}"),
              "<msubsup><munder accentunder=\"true\"><munder accentunder=\"true\"><mi>I</mi>" + under + "</munder>" + under +
                  "</munder><mi>i</mi><mrow><mo form=\"prefix\">−</mo><mn>1</mn></mrow></msubsup>");
    // \left \right stretch around something tall only (Chromium would pick a wider glyph).
    EXPECT_EQ(tex_to_mathml("\\left|x\\right|"), "<mrow><mo stretchy=\"false\">|</mo><mi>x</mi><mo stretchy=\"false\">|</mo></mrow>");
    EXPECT_EQ(tex_to_mathml("\\left(\\frac{1}{2}\\right."), "<mrow><mo stretchy=\"true\">(</mo><mfrac><mn>1</mn><mn>2</mn></mfrac></mrow>");
    // A sign after a relation or an opening is a prefix sign; between terms it is binary.
    EXPECT_EQ(tex_to_mathml("a = -b - c"), "<mi>a</mi><mo>=</mo><mo form=\"prefix\">−</mo><mi>b</mi><mo>−</mo><mi>c</mi>");
    EXPECT_EQ(tex_to_mathml("-\\frac{a}{b}"), "<mo form=\"prefix\">−</mo><mfrac><mi>a</mi><mi>b</mi></mfrac>");
    EXPECT_EQ(tex_to_mathml("a/b"), "<mi>a</mi><mo lspace=\"0\" rspace=\"0\">/</mo><mi>b</mi>");
    // Bars open where a sign would be a prefix and close elsewhere.
    EXPECT_EQ(tex_to_mathml("|F| \\le \\mu N"),
              "<mo form=\"prefix\" stretchy=\"false\">|</mo><mi>F</mi><mo form=\"postfix\" stretchy=\"false\">|</mo><mo>≤</mo>"
              "<mi>μ</mi><mi>N</mi>");
    EXPECT_EQ(tex_to_mathml("\\det K"), "<mrow><mi>det</mi><mspace width=\"0.1667em\"></mspace></mrow><mi>K</mi>");
    EXPECT_EQ(tex_to_mathml("\\cos(x)"), "<mi>cos</mi><mo stretchy=\"false\">(</mo><mi>x</mi><mo stretchy=\"false\">)</mo>");
    EXPECT_EQ(tex_to_mathml("\\mu^*"), "<msup><mi>μ</mi><mo>∗</mo></msup>");
    EXPECT_EQ(tex_to_mathml("x^23"), "<msup><mi>x</mi><mn>2</mn></msup><mn>3</mn>"); // as TeX reads it
    EXPECT_EQ(tex_to_mathml("0.142857 + 12"), "<mn>0.142857</mn><mo>+</mo><mn>12</mn>");
    EXPECT_EQ(tex_to_mathml("\\omega'_{z2}"), "<msubsup><mi>ω</mi><mrow><mi>z</mi><mn>2</mn></mrow>" + prime + "</msubsup>");
    EXPECT_EQ(tex_to_mathml("v''"), "<msup><mi>v</mi><mrow>" + prime + prime + "</mrow></msup>");
    EXPECT_EQ(tex_to_mathml("\\cos\\theta"), "<mrow><mi>cos</mi><mspace width=\"0.1667em\"></mspace></mrow><mi>θ</mi>");
    EXPECT_EQ(tex_to_mathml("\\sum m"), "<mo>∑</mo><mi>m</mi>");
    EXPECT_EQ(tex_to_mathml("I^{1}_{nb}"), "<msubsup><mi>I</mi><mrow><mi>n</mi><mi>b</mi></mrow><mn>1</mn></msubsup>");
    EXPECT_EQ(tex_to_mathml("T_{\\mathrm{lost}}"), "<msub><mi>T</mi><mi>lost</mi></msub>");
    EXPECT_EQ(tex_to_mathml("\\mathrm{d}"), "<mi mathvariant=\"normal\">d</mi>");
    EXPECT_EQ(tex_to_mathml("\\Omega"), "<mi mathvariant=\"normal\">Ω</mi>");
    // \text keeps its spaces (as no-break spaces at the ends, which MathML would trim).
    EXPECT_EQ(tex_to_mathml("\\text{stick: } u"), "<mtext>stick:\u00A0</mtext><mi>u</mi>");
}

TEST(TexToMathml, TextModeEscapesOfNamesComeBackAsCharacters)
{
    // names::latex_text("50% a_b#{x}") and ("~^\\end{document}") inside \text.
    EXPECT_EQ(tex_to_mathml("\\omega_{z,\\text{50\\% a\\_b\\#\\{x\\}}}"),
              "<msub><mi>ω</mi><mrow><mi>z</mi><mo>,</mo><mtext>50% a_b#{x}</mtext></mrow></msub>");
    EXPECT_EQ(tex_to_mathml("\\text{\\textasciitilde{}\\textasciicircum{}\\textbackslash{}end\\{document\\}}"),
              "<mtext>~^\\end{document}</mtext>");
    // Markup in a name is text: & < > " ' as entities, nothing becomes an element.
    EXPECT_EQ(tex_to_mathml("\\text{<script>alert('&amp;')</script>}"),
              "<mtext>&lt;script&gt;alert(&#39;&amp;amp;&#39;)&lt;/script&gt;</mtext>");
    EXPECT_EQ(tex_to_mathml("<script>"), "<mo>&lt;</mo><mi>s</mi><mi>c</mi><mi>r</mi><mi>i</mi><mi>p</mi><mi>t</mi><mo>&gt;</mo>");
    EXPECT_EQ(tex_to_mathml("&amp;"), "<mo>&amp;</mo><mi>a</mi><mi>m</mi><mi>p</mi><mo>;</mo>");
    EXPECT_EQ(tex_to_mathml("v_{ball\\_x}"),
              "<msub><mi>v</mi><mrow><mi>b</mi><mi>a</mi><mi>l</mi><mi>l</mi><mi>_</mi><mi>x</mi></mrow></msub>");
}

TEST(TexToMathml, WhatItDoesNotKnowIsAnErrorNamingIt)
{
    for (const char* bad : {"\\boldsymbol{v}", "a \\overset{x}{y}", "\\sqrt[3]{x}", "\\text{\\emph{x}}", "\\left< x \\right>"}) {
        try {
            tex_to_mathml(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const std::invalid_argument& e) {
            std::string what = e.what();
            EXPECT_TRUE(contains(what, "TeX to MathML")) << what;
            std::string name = std::string(bad).substr(std::string(bad).find('\\') + 1, 4);
            if (std::string(bad) != "\\text{\\emph{x}}" && std::string(bad) != "\\left< x \\right>") {
                EXPECT_TRUE(contains(what, "\\" + name)) << what;
            }
        }
    }
    EXPECT_THROW(tex_to_mathml("\\text{\\emph{x}}"), std::invalid_argument);
    for (const char* bad : {"{x", "x}", "\\frac{1}", "x_", "x^", "x_1_2", "x^1^2", "x^{1}'", "\\left( x", "x \\right)", "\\"})
        EXPECT_THROW(tex_to_mathml(bad), std::invalid_argument) << bad;
}

// Every notation string of every document translates, into balanced markup;
// the commands they use are the subset the translator documents.
TEST(TexToMathml, EveryNotationOfEveryDocument)
{
    std::size_t strings = 0;
    std::set<std::string> commands;
    for (const auto& [name, doc] : every_document()) {
        for (const std::string& tex : notation_of(doc)) {
            ++strings;
            std::string m;
            ASSERT_NO_THROW(m = tex_to_mathml(tex)) << name << ": " << tex;
            EXPECT_TRUE(balanced(m)) << name << ": " << tex;
            for (std::size_t k = tex.find('\\'); k != std::string::npos; k = tex.find('\\', k + 1)) {
                std::size_t e = k + 1;
                while (e < tex.size() && std::isalpha(static_cast<unsigned char>(tex[e])))
                    ++e;
                commands.insert(tex.substr(k, std::max(e, k + 2) - k));
                k = std::max(e, k + 2) - 1;
            }
        }
    }
    EXPECT_GT(strings, 100u);
    std::string used;
    for (const std::string& c : commands)
        used += c + " ";
    std::cout << "[ notation ] " << strings << " strings; commands: " << used << "\n";
    for (const char* c : {"\\underline", "\\hat", "\\frac", "\\int", "\\le", "\\times", "\\cdot", "\\text"})
        EXPECT_TRUE(commands.count(c)) << c << " is no longer used: " << used;
}

// ------------------------------------------------------------ canonical MathML

TEST(CanonicalMathml, FormsSignsAndScripts)
{
    symbol a("a"), b("b"), c("c"), d("d"), e("e");
    symbol r("r_t1", "r_{t1}"), v("v'_x1", "v'_{x1}"), I("I1_nb", "I^{1}_{nb}"), w("w_b1", "\\omega_{b1}");
    const std::string open = "<mo stretchy=\"false\">(</mo>", close = "<mo stretchy=\"false\">)</mo>";
    EXPECT_EQ(canonical_mathml(a), "<mi>a</mi>");
    // One element: a leading minus is the first child of its row (a prefix sign).
    EXPECT_EQ(canonical_mathml(numeric(-1, 7)), "<mrow><mo>−</mo><mfrac><mn>1</mn><mn>7</mn></mfrac></mrow>");
    EXPECT_EQ(canonical_mathml(1 - e * e), "<mrow><mn>1</mn><mo>−</mo><msup><mi>e</mi><mn>2</mn></msup></mrow>");
    // The same canonical signs as the other syntaxes: (a - b)/(c - d) == (b - a)/(d - c).
    EXPECT_EQ(canonical_mathml((a - b) / (c - d)), canonical_mathml((b - a) / (d - c)));
    EXPECT_EQ(canonical_mathml(-(1 + e) * a / c),
              "<mrow><mo>−</mo><mfrac><mrow><mrow>" + open + "<mn>1</mn><mo>+</mo><mi>e</mi>" + close +
                  "</mrow><mo>&#x2062;</mo><mi>a</mi></mrow><mi>c</mi></mfrac></mrow>");
    EXPECT_EQ(canonical_mathml(sqrt(a)), "<msqrt><mi>a</mi></msqrt>");
    EXPECT_EQ(canonical_mathml(2 * a), "<mrow><mn>2</mn><mo>&#x2062;</mo><mi>a</mi></mrow>");
    // Parentheses stretch around a fraction.
    EXPECT_EQ(canonical_mathml(pow(1 + a / b, 2)),
              "<msup><mrow><mo>(</mo><mn>1</mn><mo>+</mo><mfrac><mi>a</mi><mi>b</mi></mfrac><mo>)</mo></mrow><mn>2</mn></msup>");
    // A power of a subscripted symbol: one <msubsup>, and r_{t1}^{2} in LaTeX.
    EXPECT_EQ(canonical_mathml(pow(r, 2)), "<msubsup><mi>r</mi><mrow><mi>t</mi><mn>1</mn></mrow><mn>2</mn></msubsup>");
    EXPECT_EQ(canonical_latex(pow(r, 2)), "r_{t1}^{2}");
    EXPECT_EQ(canonical_latex(pow(w, 2)), "\\omega_{b1}^{2}");
    EXPECT_EQ(canonical_latex(pow(symbol("v_1"), 3)), "v_1^{3}");
    EXPECT_EQ(canonical_latex(pow(symbol("T_lost", "T_{\\text{lost}}"), 2)), "T_{\\text{lost}}^{2}");
    // A prime or a superscript in the name: braced (TeX), an <msup> around it (MathML).
    EXPECT_EQ(canonical_latex(pow(v, 2)), "{v'_{x1}}^{2}");
    EXPECT_EQ(canonical_latex(pow(I, 2)), "{I^{1}_{nb}}^{2}");
    EXPECT_EQ(canonical_mathml(pow(v, 2)), "<msup><mrow>" + open + "<msubsup><mi>v</mi><mrow><mi>x</mi><mn>1</mn></mrow>" + prime +
                                               "</msubsup>" + close + "</mrow><mn>2</mn></msup>");
    EXPECT_EQ(canonical_mathml(pow(a + b, 2)), "<msup><mrow>" + open + "<mi>a</mi><mo>+</mo><mi>b</mi>" + close + "</mrow><mn>2</mn></msup>");
    EXPECT_EQ(canonical_mathml(pow(a, numeric(1, 3))), "<msup><mi>a</mi><mfrac><mn>1</mn><mn>3</mn></mfrac></msup>");
    EXPECT_EQ(canonical_mathml(abs(a - b)),
              "<mrow><mo stretchy=\"false\">|</mo><mrow><mi>a</mi><mo>−</mo><mi>b</mi></mrow><mo stretchy=\"false\">|</mo></mrow>");
    EXPECT_EQ(canonical_mathml(sin(a)), "<mrow><mi>sin</mi><mo>&#x2061;</mo><mrow>" + open + "<mi>a</mi>" + close + "</mrow></mrow>");
    EXPECT_EQ(canonical_mathml(Pi), "<mi>π</mi>");
    // Greek names as GiNaC writes them in TeX (mu -> \mu), and the notes' eps.
    EXPECT_EQ(canonical_mathml(symbol("mu")), "<mi>μ</mi>");
    EXPECT_EQ(canonical_mathml(symbol("tau")), "<mi>τ</mi>");
    EXPECT_EQ(canonical_mathml(symbol("eps")), "<mi>ε</mi>");
    EXPECT_EQ(canonical_mathml(symbol("m_1")), "<msub><mi>m</mi><mn>1</mn></msub>");
    EXPECT_THROW(canonical_mathml(lst{a, b}), std::invalid_argument);
    EXPECT_THROW(canonical_mathml(a == b), std::invalid_argument);
}

TEST(CanonicalMathml, NamesAreInert)
{
    for (const char* name : {"<script>", "&amp;", "a\"b'c", "</math><script>x</script>"}) {
        std::string m = canonical_mathml(symbol(name) + 1);
        EXPECT_FALSE(contains(m, "<script")) << m;
        EXPECT_TRUE(balanced(m)) << m;
        EXPECT_FALSE(contains(m, "</math")) << m;
    }
    EXPECT_TRUE(contains(canonical_mathml(symbol("&amp;")), "<mo>&amp;</mo>"));
}

// The MathML of an expression has as many sums, products and fractions as
// its LaTeX: every expression of every document, compared by a count.
TEST(CanonicalMathml, AgreesWithLatexOnEveryExpression)
{
    std::size_t n = 0;
    for (const auto& [name, doc] : every_document())
        for (const section& sec : doc.sections)
            for (const block& b : sec.blocks)
                for (const math_row& r : b.math)
                    for (const ex& e : {r.lhs, r.rhs, r.then}) {
                        if (r.lhs_note.text.size() && e.is_equal(r.lhs))
                            continue;
                        std::string m = canonical_mathml(e), t = canonical_latex(e);
                        EXPECT_TRUE(balanced(m)) << name;
                        EXPECT_EQ(count(m, "<mfrac>"), count(t, "\\frac{")) << name << ": " << t;
                        EXPECT_EQ(count(m, "<msqrt>"), count(t, "\\sqrt{")) << name << ": " << t;
                        EXPECT_EQ(count(m, "<mo>+</mo>"), count(t, "+")) << name << ": " << t;
                        ++n;
                    }
    EXPECT_GT(n, 500u);
}

// ------------------------------------------------------------ explain_html

TEST(ExplainHtml, EveryDocumentIsOneSelfContainedPage)
{
    for (const auto& [name, doc] : every_document()) {
        std::string html;
        ASSERT_NO_THROW(html = explain_html(doc)) << name;
        EXPECT_EQ(html.compare(0, 15, "<!DOCTYPE html>"), 0) << name;
        EXPECT_TRUE(contains(html, "<html lang=\"en\">")) << name;
        EXPECT_TRUE(contains(html, "<meta charset=\"utf-8\">")) << name;
        EXPECT_EQ(count(html.substr(0, html.find("</head>")), "<title>"), 1u) << name;
        // Nothing is fetched and nothing runs: no script, no external resource.
        for (const char* never : {"<script", "<link", "<img", "<iframe", "<object", "<embed", "src=", "href=\"http", "@import", "url("})
            EXPECT_FALSE(contains(html, never)) << name << ": " << never;
        std::size_t body = html.find("<body>");
        ASSERT_NE(body, std::string::npos);
        EXPECT_TRUE(balanced(html.substr(body, html.find("</html>") - body))) << name;
        // The table of contents links every section.
        for (std::size_t k = 1; k <= doc.sections.size(); ++k) {
            EXPECT_TRUE(contains(html, "<a href=\"#sec-" + std::to_string(k) + "\">")) << name;
            EXPECT_TRUE(contains(html, "<section id=\"sec-" + std::to_string(k) + "\">")) << name;
        }
        // Every tag has its anchor, and every reference points to one.
        std::set<std::string> tags;
        for (const section& sec : doc.sections)
            for (const block& b : sec.blocks)
                for (const math_row& r : b.math)
                    if (!r.tag.empty())
                        tags.insert(r.tag);
        for (const std::string& t : tags) {
            EXPECT_EQ(count(html, " id=\"" + names::html_text(eq_id(t)) + "\""), 1u) << name << " (" << t << ")";
            EXPECT_TRUE(contains(html, "<span class=\"tag\">(" + names::html_text(t) + ")</span>")) << name;
        }
        for (std::size_t k = html.find("<a href=\"#eq-"); k != std::string::npos; k = html.find("<a href=\"#eq-", k + 1)) {
            std::string id = html.substr(k + 10, html.find('"', k + 10) - k - 10);
            EXPECT_TRUE(contains(html, "id=\"" + id + "\"")) << name << ": a link to " << id << " without its target";
            EXPECT_TRUE(tags.count(id.substr(3)) || contains(id, "&")) << name << ": a link to " << id;
        }
        EXPECT_GT(count(html, "<math display=\"block\">"), 3u) << name;
        EXPECT_EQ(count(html, "<math "), count(html, "</math>")) << name;
    }
}

TEST(ExplainHtml, ReferencesFiguresAndEscaping)
{
    document doc;
    doc.title = "A <b>bold</b> & \"quoted\" title";
    section sec{"1. Words & <figures>", {}};
    sec.para(paragraph().w("see ").ref("3").w(", with <i>no</i> markup: ").m(symbol("<script>")).w(" and ").n("x", "\\hat{\\underline{e}}_n"));
    figure_art art;
    art.caption = "Body 1 <strikes> body 2 & the floor";
    art.svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\"><title>two bodies</title></svg>";
    art.alt = "two bodies";
    sec.picture(art);
    math_row r;
    r.tag = "3";
    r.lhs = symbol("a");
    r.rhs = 2;
    r.note.w("a note");
    sec.rows({r, r}); // the tag twice: one id
    doc.sections.push_back(sec);
    std::string html = explain_html(doc);
    EXPECT_TRUE(contains(html, "<title>A &lt;b&gt;bold&lt;/b&gt; &amp; &quot;quoted&quot; title</title>")) << html;
    EXPECT_TRUE(contains(html, "<a href=\"#eq-3\">(3)</a>"));
    EXPECT_EQ(count(html, "id=\"eq-3\""), 1u);
    EXPECT_TRUE(contains(html, "with &lt;i&gt;no&lt;/i&gt; markup"));
    EXPECT_FALSE(contains(html, "<script"));
    EXPECT_TRUE(contains(html, "<figure>\n<svg xmlns=\"http://www.w3.org/2000/svg\""));
    EXPECT_TRUE(contains(html, "<figcaption>Body 1 &lt;strikes&gt; body 2 &amp; the floor</figcaption>\n</figure>"));
    EXPECT_TRUE(contains(html, "<p class=\"note\">a note</p>"));
    EXPECT_TRUE(contains(html, "<math display=\"block\"><mi>a</mi><mo>=</mo><mn>2</mn></math><span class=\"tag\">(3)</span>")) << html;
}

// A row wider than the column whose right side is one product, (sum of 24 terms)·x/7:
// it cannot break between terms of the side, so it takes the LaTeX layout's lines, broken
// inside the parenthesised sum; every line is MathML the browser can parse.
TEST(ExplainHtml, AWideProductIsBrokenInsideItsSum)
{
    ex sum = 0;
    for (int k = 0; k < 24; ++k)
        sum += symbol("v_" + std::to_string(k), "v_{" + std::to_string(k) + "}") * symbol("w_" + std::to_string(k), "\\omega_{" + std::to_string(k) + "}");
    const symbol x("x");
    math_row r;
    r.tag = "1";
    r.lhs = symbol("T");
    r.rhs = sum * x / 7;
    ASSERT_TRUE(is_a<GiNaC::mul>(r.rhs));
    document doc;
    section sec{"1. Wide", {}};
    sec.rows({r});
    doc.sections.push_back(sec);
    const std::string html = explain_html(doc);
    const std::size_t at = html.find("<div class=\"eq\"");
    ASSERT_NE(at, std::string::npos);
    const std::string eq = html.substr(at, html.find("</div>", at) - at);
    EXPECT_TRUE(contains(eq, "<mtable columnalign=\"left\">")) << eq;
    EXPECT_GE(count(eq, "<mtr>"), 3u) << eq; // 24 terms of about 2.5 em in a 34 em column
    EXPECT_EQ(count(eq, "<mo stretchy=\"false\">(</mo>"), 1u) << eq;
    EXPECT_EQ(count(eq, "<mo stretchy=\"false\">)</mo>"), 1u) << eq;
    for (int k = 0; k < 24; ++k)
        EXPECT_TRUE(contains(eq, "<mn>" + std::to_string(k) + "</mn>")) << k;
}

TEST(ExplainHtml, CommandLine)
{
    std::string out;
    FILE* f = popen((std::string(IMPACTGEN_CLI) + " explain pinned-planar --format html").c_str(), "r");
    ASSERT_NE(f, nullptr);
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0)
        out.append(buf.data(), n);
    EXPECT_EQ(pclose(f), 0);
    const std::string expected = explain_html(document_of(find_named_class("pinned-planar")->build(), "pinned-planar"));
    EXPECT_TRUE(out == expected) << "impactgen explain pinned-planar --format html: " << out.size() << " bytes, explain_html: "
                                 << expected.size() << " bytes";
}
