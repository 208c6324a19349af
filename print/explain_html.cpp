// The HTML printer of an explanation document: one self-contained HTML5 page
// (inline CSS, no script, nothing fetched), the same content as the text,
// Markdown and LaTeX printers (explain_print.cpp).
//
//   words       escaped text (names::html_text), UTF-8 kept
//   math        <math display="inline">, the canonical printer's MathML
//   notation    <math display="inline">, its TeX through tex_to_mathml
//   references  <a href="#eq-N">(N)</a>
//   rows        <math display="block"> with the tag "(N)" at the right and
//               id="eq-N" on the first row of that tag; a block of rows with
//               neither relation nor tag is a list of definitions, as in LaTeX
//   figures     <figure> with the figure's inline <svg> and a <figcaption>
//
// A table of contents links the sections (id="sec-1", ...). The CSS lays the
// page out like a printed hand-out: a serif text column of at most 50em,
// Latin Modern where the system has it, tags at the right margin, notes in a
// smaller grey type under their row.
#include "canonical.hpp"
#include "explain.hpp"
#include "explain_detail.hpp"
#include "tex_to_mathml.hpp"

#include "names/escape.hpp"

#include <cctype>
#include <set>
#include <sstream>
#include <stdexcept>

namespace impactgen::print
{

namespace
{

const char *const style = R"css(
  html { background: #fff; }
  body { max-width: 50em; margin: 2.5em auto 4em; padding: 0 1.5em; color: #1a1a1a;
         font-family: "Latin Modern Roman", "LM Roman 10", "STIX Two Text", Cambria, Georgia, "Times New Roman", serif;
         font-size: 17px; line-height: 1.5; }
  math { font-family: "Latin Modern Math", "STIX Two Math", "Cambria Math", math; }
  h1 { font-size: 1.75em; font-weight: normal; text-align: center; margin: 0 0 1.2em; }
  p.description { text-align: center; font-style: italic; margin: -0.8em 0 1.2em; }
  h2 { font-size: 1.3em; font-weight: bold; margin: 1.8em 0 0.6em; padding-bottom: 0.15em; border-bottom: 1px solid #bbb; }
  p { margin: 0.6em 0; }
  ul { margin: 0.5em 0; padding-left: 1.6em; }
  li { margin: 0.25em 0; }
  a { color: #1f4e8c; text-decoration: none; }
  a:hover { text-decoration: underline; }
  nav.toc { margin: 0 0 2em; padding: 0.6em 1.2em 0.8em; border: 1px solid #ccc; background: #f8f8f6; }
  nav.toc h2 { font-size: 1em; margin: 0 0 0.3em; border: none; padding: 0; }
  nav.toc ol { list-style: none; margin: 0; padding: 0; }
  nav.toc li { margin: 0.1em 0; }
  .eq { display: grid; grid-template-columns: 4em minmax(0, 1fr) 4em; align-items: center; margin: 0.7em 0; }
  .eq > math { grid-column: 2; overflow-x: auto; overflow-y: hidden; padding: 0.1em 0; }
  .eq > .tag { grid-column: 3; text-align: right; }
  .eq mtd { text-align: left; } /* a broken row: its lines start at the left, continuations indented */
  .eq:target { background: #fff6d5; }
  .results { border: 2px solid #222; border-radius: 0.3em; padding: 0.2em 1em; margin: 1em 0; background: #fafafa; } /* the boxed results */
  .note { margin: -0.35em 0 0.9em 4em; font-size: 0.88em; color: #555; }
  figure { margin: 1.5em 0; text-align: center; }
  figure svg { max-width: 100%; height: auto; }
  figcaption { margin-top: 0.4em; font-size: 0.9em; color: #444; }
  @media print {
    body { max-width: none; margin: 0; font-size: 11pt; }
    a { color: inherit; }
    nav.toc { background: none; }
    .eq, figure { break-inside: avoid; }
    .eq > math { overflow: visible; }
    h2 { break-after: avoid; }
  }
)css";

} // namespace

namespace layout
{
double estimated_width_em(const std::string &tex); // print/explain_print.cpp: the LaTeX layout's glyph model
// print/explain_print.cpp: a row wider than budget em as the LaTeX layout breaks it (a sum
// at its terms, a long fraction as a factor times the broken sum, a parenthesised sum
// inside its \left( ... \right.), one TeX line each with & alignment marks; {} if it fits.
std::vector<std::string> broken_row_lines(const math_row &r, double budget);
} // namespace layout

namespace
{

std::string inline_math(const std::string &mathml)
{
    return "<math display=\"inline\">" + mathml + "</math>";
}

// The id of a tag: "eq-" and the tag, each run of spaces one '-' (HTML ids
// hold no spaces): (3) is eq-3, (8') is eq-8', (e = 0) is eq-e-=-0.
std::string eq_id(const std::string &tag)
{
    std::string id = "eq-";
    for (char c : tag) {
        if (!std::isspace(static_cast<unsigned char>(c)))
            id += c;
        else if (id.back() != '-')
            id += '-';
    }
    return id;
}

std::string spans(const paragraph &p)
{
    std::string out;
    for (const span &s : p.spans) {
        switch (s.k) {
        case span::words:
            out += names::html_text(s.text);
            break;
        case span::math:
            out += inline_math(canonical_mathml(s.expr));
            break;
        case span::note:
            out += inline_math(tex_to_mathml(s.formula.tex));
            break;
        case span::ref:
            out += "<a href=\"#" + names::html_text(eq_id(s.text)) + "\">(" + names::html_text(s.text) + ")</a>";
            break;
        }
    }
    return out;
}

std::string relation(const std::string &rel)
{
    if (rel == "->" || rel == "→")
        return "<mo>→</mo>";
    if (rel == "<=" || rel == "≤")
        return "<mo>≤</mo>";
    if (rel == ">=" || rel == "≥")
        return "<mo>≥</mo>";
    return "<mo>" + names::html_text(rel) + "</mo>";
}

// lhs REL rhs [= then], as MathML children.
std::string row_math(const math_row &r)
{
    std::string out = r.lhs_note.text.empty() ? canonical_mathml(r.lhs) : tex_to_mathml(r.lhs_note.tex);
    if (!r.rel.empty())
        out += relation(r.rel) + canonical_mathml(r.rhs);
    if (r.has_then)
        out += "<mo>=</mo>" + canonical_mathml(r.then);
    return out;
}

// What a displayed row may fill before it is broken: the page's column is 50em of the
// body font; MathML has no line breaking of its own, so a wider row would run off the
// page (and be cut in print).
constexpr double html_row_em = 34;

struct piece {
    std::string mathml;
    double width; ///< em, from the LaTeX layout's glyph model
};

// A side of a row as pieces to break between: a sum's terms with their signs (as the
// canonical printer orders them), anything else whole.
void add_pieces(std::vector<piece> &out, const ex &e, const std::string &lead)
{
    const auto ml = canonical_terms(e, syntax::mathml);
    const auto tx = canonical_terms(e, syntax::latex);
    for (std::size_t k = 0; k < ml.size() && k < tx.size(); ++k) {
        std::string sign = (k == 0 && !ml[k].first) ? "" : (ml[k].first ? "<mo>−</mo>" : "<mo>+</mo>");
        out.push_back({(k == 0 ? lead : "") + sign + ml[k].second, layout::estimated_width_em(tx[k].second) + 1.2});
    }
}

// The row, broken at the terms of its sides when it is wider than the column: the
// first line holds the left side and the relation, the next lines the rest, indented.
std::string row_block(const math_row &r)
{
    std::vector<piece> pieces;
    if (r.lhs_note.text.empty())
        add_pieces(pieces, r.lhs, "");
    else
        pieces.push_back({tex_to_mathml(r.lhs_note.tex), layout::estimated_width_em(r.lhs_note.tex)});
    if (!r.rel.empty())
        add_pieces(pieces, r.rhs, relation(r.rel));
    if (r.has_then)
        add_pieces(pieces, r.then, "<mo>=</mo>");
    double total = 0;
    for (const piece &p : pieces)
        total += p.width;
    if (total <= html_row_em)
        return "<math display=\"block\">" + row_math(r) + "</math>";
    // A term wider than the column (a product such as (a + b + ...)·√105/105) cannot be
    // broken between terms: take the LaTeX layout's lines, which break inside it.
    bool wide_piece = pieces.size() < 2;
    for (const piece &p : pieces)
        wide_piece = wide_piece || p.width > html_row_em;
    if (wide_piece) {
        try {
            std::string out = "<math display=\"block\"><mtable columnalign=\"left\">";
            const std::vector<std::string> tex_lines = layout::broken_row_lines(r, html_row_em);
            for (const std::string &line : tex_lines) {
                std::string tex; // without the alignment marks (an escaped \& stays)
                for (std::size_t k = 0; k < line.size(); ++k)
                    if (line[k] != '&' || (k > 0 && line[k - 1] == '\\'))
                        tex += line[k];
                out += "<mtr><mtd><mrow>" + tex_to_mathml(tex) + "</mrow></mtd></mtr>";
            }
            if (tex_lines.size() > 1)
                return out + "</mtable></math>";
        } catch (const std::exception &) {
            // the terms below
        }
        if (pieces.size() < 2)
            return "<math display=\"block\">" + row_math(r) + "</math>";
    }
    std::vector<std::string> lines(1);
    double used = 0;
    for (const piece &p : pieces) {
        if (used > 0 && used + p.width > html_row_em) {
            lines.push_back("<mspace width=\"2em\"></mspace>");
            used = 2;
        }
        lines.back() += p.mathml;
        used += p.width;
    }
    std::string out = "<math display=\"block\"><mtable columnalign=\"left\">";
    for (const std::string &l : lines)
        out += "<mtr><mtd><mrow>" + l + "</mrow></mtd></mtr>";
    return out + "</mtable></math>";
}

} // namespace

std::string explain_html(const document &doc)
{
    std::ostringstream os;
    const std::string title = names::html_text(doc.title);
    os << "<!DOCTYPE html>\n"
          "<!-- Written by impactgen explain: one self-contained page, mathematics in MathML. -->\n"
          "<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
          "<meta name=\"generator\" content=\"impactgen explain\">\n"
       << "<title>" << title << "</title>\n<style>" << style << "</style>\n</head>\n<body>\n"
       << "<h1>" << title << "</h1>\n";
    if (!doc.description.empty())
        os << "<p class=\"description\">" << names::html_text(doc.description) << "</p>\n";

    os << "<nav class=\"toc\">\n<h2>Contents</h2>\n<ol>\n";
    for (std::size_t k = 0; k < doc.sections.size(); ++k)
        os << "<li><a href=\"#sec-" << k + 1 << "\">" << names::html_text(doc.sections[k].title) << "</a></li>\n";
    os << "</ol>\n</nav>\n";

    std::set<std::string> ids; // the first row of a tag gets its id
    for (std::size_t k = 0; k < doc.sections.size(); ++k) {
        const section &sec = doc.sections[k];
        os << "\n<section id=\"sec-" << k + 1 << "\">\n<h2>" << names::html_text(sec.title) << "</h2>\n";
        for (const block &b : sec.blocks) {
            switch (b.k) {
            case block::text:
                os << "<p>" << spans(b.para) << "</p>\n";
                break;
            case block::list:
                os << "<ul>\n";
                for (const paragraph &item : b.items)
                    os << "<li>" << spans(item) << "</li>\n";
                os << "</ul>\n";
                break;
            case block::figure:
                os << "<figure>\n" << b.art.svg << "\n";
                if (!b.art.caption.empty())
                    os << "<figcaption>" << names::html_text(b.art.caption) << "</figcaption>\n";
                os << "</figure>\n";
                break;
            case block::rows: {
                const bool plain = !b.boxed && detail::rows_are_plain(b.math),
                           bare = !b.boxed && detail::rows_are_bare(b.math);
                if (bare) {
                    for (const math_row &r : b.math)
                        os << "<div class=\"eq\">" << row_block(r) << "</div>\n";
                    break;
                }
                if (plain) { // definitions: symbol: meaning
                    os << "<ul>\n";
                    for (const math_row &r : b.math) {
                        std::string note = spans(r.note);
                        os << "<li>" << inline_math(row_math(r)) << (note.empty() ? "" : ": " + note) << "</li>\n";
                    }
                    os << "</ul>\n";
                    break;
                }
                if (b.boxed)
                    os << "<div class=\"results\">\n";
                for (const math_row &r : b.math) {
                    os << "<div class=\"eq\"";
                    if (!r.tag.empty() && ids.insert(eq_id(r.tag)).second)
                        os << " id=\"" << names::html_text(eq_id(r.tag)) << "\"";
                    os << ">" << row_block(r);
                    if (!r.tag.empty())
                        os << "<span class=\"tag\">(" << names::html_text(r.tag) << ")</span>";
                    os << "</div>\n";
                    std::string note = spans(r.note);
                    if (!note.empty())
                        os << "<p class=\"note\">" << note << "</p>\n";
                }
                if (b.boxed)
                    os << "</div>\n";
                break;
            }
            }
        }
        os << "</section>\n";
    }
    os << "</body>\n</html>\n";
    return os.str();
}

} // namespace impactgen::print
