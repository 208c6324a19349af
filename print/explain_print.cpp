// The printers of an explanation document: text, Markdown, LaTeX. Each one
// only decides how a span, a list and a displayed row look; the content is the
// document's, and every expression goes through the canonical printer.
#include "canonical.hpp"
#include "explain.hpp"
#include "explain_detail.hpp"
#include "tex_layout.hpp"

#include "names/escape.hpp"

#include <cctype>
#include <set>
#include <sstream>
#include <stdexcept>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{
using namespace tex_layout;

constexpr std::size_t width = 100;
// Spaces inside a formula must not break a line: held as this byte while wrapping.
constexpr char hard_space = '\x01';

std::size_t columns(const std::string &s)
{
    std::size_t n = 0;
    for (unsigned char c : s)
        if ((c & 0xC0) != 0x80)
            ++n;
    return n;
}

std::string harden(std::string s)
{
    for (char &c : s)
        if (c == ' ')
            c = hard_space;
    return s;
}

std::string math_text(const ex &e)
{
    return canonical(e, syntax::text, true); // abs(x) as |x|
}
} // namespace

std::string tex_layout::math_latex(const ex &e)
{
    return canonical(e, syntax::latex, true); // abs(x) as \left|x\right|
}

namespace
{

// Greedy wrap at `width` columns; `first` and `rest` are the line prefixes.
std::string wrap(const std::string &text, const std::string &first, const std::string &rest)
{
    std::istringstream in(text);
    std::string word, out, line = first;
    bool empty = true;
    while (in >> word) {
        if (!empty && columns(line) + 1 + columns(word) > width) {
            out += line + "\n";
            line = rest;
            empty = true;
        }
        line += (empty ? "" : " ") + word;
        empty = false;
    }
    out += line + "\n";
    for (char &c : out)
        if (c == hard_space)
            c = ' ';
    return out;
}

// ---------------------------------------------------------------- text

std::string text_spans(const paragraph &p)
{
    std::string out;
    for (const span &s : p.spans) {
        if (s.k == span::words)
            out += s.text;
        else if (s.k == span::math)
            out += harden(math_text(s.expr));
        else if (s.k == span::ref)
            out += "(" + s.text + ")";
        else
            out += harden(s.formula.text);
    }
    return out;
}

std::string text_row_left(const math_row &r)
{
    return r.lhs_note.text.empty() ? math_text(r.lhs) : r.lhs_note.text;
}

// ---------------------------------------------------------------- LaTeX

// Running text for LaTeX: escapes and the few Unicode signs the notes use.
// Anything else outside ASCII is an error, never silently wrong output.
std::string tex_words(const std::string &s)
{
    static const std::pair<const char *, const char *> map[] = {
        {"≤", "$\\le$"},
        {"≥", "$\\ge$"},
        {"∫", "$\\int$"},
        {"→", "$\\to$"},
        {"′", "$'$"},
        {"ω", "$\\omega$"},
        {"·", "$\\cdot$"},
        {"×", "$\\times$"},
        {"∞", "$\\infty$"},
        {"≈", "$\\approx$"},
        {"²", "$^2$"},
        {"⁻¹", "$^{-1}$"},
        {"ε", "$\\varepsilon$"},
        {"±", "$\\pm$"},
        {"τ", "$\\tau$"},
        {"|", "$|$"},
        {"<", "$<$"},
        {">", "$>$"},
        {"μ", "$\\mu$"},
        {"λ", "$\\lambda$"},
        {"θ", "$\\theta$"},
        {"≠", "$\\ne$"},
        {"√", "$\\surd$"},
        {"∓", "$\\mp$"},
        {"⁺", "$^+$"},
        {"é", "\\'{e}"},
    };
    std::string out;
    for (std::size_t i = 0; i < s.size();) {
        bool done = false;
        for (const auto &[from, to] : map) {
            std::size_t n = std::char_traits<char>::length(from);
            if (s.compare(i, n, from) == 0) {
                out += to;
                i += n;
                done = true;
                break;
            }
        }
        if (done)
            continue;
        unsigned char c = static_cast<unsigned char>(s[i]);
        if (c >= 0x80) {
            std::size_t n = 1;
            while (i + n < s.size() && (static_cast<unsigned char>(s[i + n]) & 0xC0) == 0x80)
                ++n;
            throw std::invalid_argument("the LaTeX output has no rendering for the character \"" +
                                        names::display_text(s.substr(i, n)) + "\" (in \"" + names::display_text(s, 60) +
                                        "\"); use ASCII names for --format latex");
        }
        switch (c) {
        case '_':
            out += "\\_";
            break;
        case '&':
            out += "\\&";
            break;
        case '%':
            out += "\\%";
            break;
        case '#':
            out += "\\#";
            break;
        case '$':
            out += "\\$";
            break;
        case '{':
            out += "\\{";
            break;
        case '}':
            out += "\\}";
            break;
        case '^':
            out += "\\^{}";
            break;
        case '~':
            out += "\\~{}";
            break;
        case '\\':
            out += "\\textbackslash{}";
            break;
        default:
            out += static_cast<char>(c);
        }
        ++i;
    }
    return out;
}

} // namespace

std::string tex_layout::tex_rel(const std::string &rel)
{
    if (rel == "→")
        return "\\to";
    if (rel == "≤")
        return "\\le";
    if (rel == "≥")
        return "\\ge";
    return rel;
}

namespace
{

// Inline math: as one $...$ when it is short; a long formula as several, one
// per piece of at most a quarter of the line, so that the paragraph can break
// between them, inside \left( \right) too. Between two pieces, a break that
// may leave its line ragged (by up to a third of it): stretch that a break keeps at
// the end of the line and that cancels out when there is no break.
std::string inline_math(const std::string &tex)
{
    if (tex_width(tex) <= 0.45 * text_width_em)
        return "$" + tex + "$";
    std::string out;
    for (const std::string &part : fill_lines(pieces_of(tex), 0.25 * text_width_em, 0.25 * text_width_em))
        out += (out.empty() ? "$" : "$\\nobreak\\hskip 0pt plus 15em\\penalty0\\hskip 0pt plus -15em\\relax$") + part;
    return out + "$";
}

// A label key for a tag: letters and digits as they are, any other byte (and
// 'z', the escape) as "z" and two hex digits: 3' -> 3z27. Distinct tags get
// distinct keys, and every key is safe in \label and \eqref.
std::string label_key(const std::string &tag)
{
    static const char hex[] = "0123456789abcdef";
    std::string out = "eq:";
    for (unsigned char c : tag) {
        if (std::isalnum(c) && c < 0x80 && c != 'z') {
            out += static_cast<char>(c);
        } else {
            out += 'z';
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    return out;
}

std::string tex_spans(const paragraph &p, bool markdown)
{
    std::string out;
    for (const span &s : p.spans) {
        if (s.k == span::words) {
            if (markdown) {
                std::string w;
                for (char c : s.text)
                    w += (c == '_' || c == '*') ? std::string("\\") + c : std::string(1, c);
                out += w;
            } else {
                out += tex_words(s.text);
            }
        } else if (s.k == span::math) {
            out += markdown ? "$" + math_latex(s.expr) + "$" : inline_math(math_latex(s.expr));
        } else if (s.k == span::ref) {
            out += markdown ? "(" + s.text + ")" : "\\eqref{" + label_key(s.text) + "}";
        } else {
            out += markdown ? "$" + s.formula.tex + "$" : inline_math(s.formula.tex);
        }
    }
    return out;
}

// A displayed row for Markdown ($$...$$, MathJax or KaTeX): one line when it
// fits the same width as in LaTeX, else broken the same way inside aligned.
std::string markdown_row(const math_row &r)
{
    row_tex parts = tex_row_parts(r);
    std::string tag = r.tag.empty() ? "" : " \\tag{" + r.tag + "}";
    const double budget = row_budget_em - (r.tag.empty() ? 0 : tex_width("(" + r.tag + ")", 1, true) + 1.5);
    std::string line = one_line(parts);
    if (tex_width(line) <= budget)
        return "$$" + line + tag + "$$";
    std::string out = "$$\\begin{aligned}";
    std::vector<std::string> lines = break_row(parts, budget);
    for (std::size_t k = 0; k < lines.size(); ++k)
        out += (k ? " \\\\ " : "") + lines[k];
    return out + "\\end{aligned}" + tag + "$$";
}

// " \tag{3}\label{eq:3}": the label only where the tag first appears (the
// worked example shows the equations again under their tags; a reference
// goes to the equation as first stated).
// A tag's TeX: its primes in math mode ("8''" is 8″, not a closing quote).
std::string tag_words(const std::string &tag)
{
    std::string out;
    for (std::size_t k = 0; k < tag.size();) {
        if (tag[k] != '\'') {
            std::size_t j = tag.find('\'', k);
            out += tex_words(tag.substr(k, j == std::string::npos ? std::string::npos : j - k));
            k = j == std::string::npos ? tag.size() : j;
            continue;
        }
        std::size_t j = tag.find_first_not_of('\'', k);
        if (j == std::string::npos)
            j = tag.size();
        out += "$" + tag.substr(k, j - k) + "$";
        k = j;
    }
    return out;
}

std::string tag_tex(const std::string &tag, std::set<std::string> &labelled)
{
    if (tag.empty())
        return "";
    std::string out = " \\tag{" + tag_words(tag) + "}";
    if (labelled.insert(label_key(tag)).second)
        out += "\\label{" + label_key(tag) + "}";
    return out;
}

// The room a tag takes at the end of a line: "(3)" and the space before it.
double tag_width_em(const std::string &tag)
{
    return tag.empty() ? 0 : tex_width("(" + tag_words(tag) + ")", 1, true) + 1.5;
}

// The width of the box a note under a row is set in: as wide as the note
// (the estimate is generous), at most what is left of the line after
// `column` and at most five eighths of the text width, which keeps a long
// note a compact paragraph under its formula.
std::string note_box(const std::string &note, double column)
{
    const double width =
        std::min({row_budget_em - column - 1, 0.625 * text_width_em, tex_width(note, 0.92, true) + 0.5});
    const long tenths = static_cast<long>(width * 10);
    return "\\parbox[t]{" + std::to_string(tenths / 10) + "." + std::to_string(tenths % 10) + "em}";
}

// A note under a row of an align*: the next line, in the column of the
// relations (`column`: the width of the lhs column). \\* keeps it on the
// page of its row.
std::string note_line(const std::string &note, double column)
{
    return " \\\\*\n  &" + note_box(note, column) + "{\\small\\raggedright " + note + "}";
}

// A displayed row for LaTeX, alone. One line: equation*, a short note beside
// it (before the tag); a long note centred under it (gather*). Too wide:
// align*, broken into lines (allowdisplaybreaks lets a long row continue on
// the next page), the note under the relations.
std::string latex_row(const math_row &r, std::set<std::string> &labelled)
{
    row_tex parts = tex_row_parts(r);
    const std::string tag = tag_tex(r.tag, labelled);
    const double tag_width = tag_width_em(r.tag);
    const std::string note = tex_spans(r.note, false);
    const double budget = row_budget_em - tag_width;
    const std::string line = one_line(parts);
    const double width = tex_width(line);
    if (width <= budget) {
        if (note.empty() || width + 2 + tex_width(note, 0.92, true) <= budget) {
            std::string beside = note.empty() ? "" : "\\qquad\\text{\\small " + note + "}";
            return "\\begin{equation*}\n  " + line + beside + tag + "\n\\end{equation*}\n";
        }
        return "\\begin{gather*}\n  " + line + tag + " \\\\*\n  " + note_box(note, 0) + "{\\small\\centering " + note +
               "}\n\\end{gather*}\n";
    }
    // the lhs column: a short lhs, or nothing (as break_row decides)
    const double left = tex_width(parts.left);
    std::vector<std::string> lines = break_row(parts, budget);
    std::string out = "\\begin{align*}\n";
    for (std::size_t k = 0; k < lines.size(); ++k)
        out += "  " + lines[k] + (k + 1 < lines.size() ? " \\\\\n" : tag);
    if (!note.empty())
        out += note_line(note, short_lhs(left) ? left : 0);
    return out + "\n\\end{align*}\n";
}

// A block of displayed rows for LaTeX. Several rows are one align*, aligned
// on their relations (a long lhs goes into the formula's lines), each with
// its tag; a row too wide for one line broken as in break_row; the notes in a
// column of their own beside the rows when every row is one line and they all
// fit there, else each under its row. One row alone: latex_row.
std::string latex_rows(const std::vector<math_row> &rows, std::set<std::string> &labelled)
{
    if (rows.size() == 1)
        return latex_row(rows.front(), labelled);
    struct laid {
        row_tex parts;
        std::string tag, note; // the tag as the row has it
        double left = 0, right = 0, tag_width = 0;
    };
    std::vector<laid> all;
    double column = 0, right = 0, tags = 0, notes = 0;
    for (const math_row &r : rows) {
        laid l;
        l.parts = tex_row_parts(r);
        l.tag = r.tag;
        l.tag_width = tag_width_em(r.tag);
        l.note = tex_spans(r.note, false);
        l.left = tex_width(l.parts.left);
        l.right = tex_width(one_line(l.parts)) - l.left;
        // a row that fits on one line joins the lhs column, however long its lhs
        if (l.left + l.right + l.tag_width <= row_budget_em)
            column = std::max(column, l.left);
        tags = std::max(tags, l.tag_width);
        if (!l.note.empty())
            // a margin for inline math in a note, which runs wider than its estimate
            notes =
                std::max(notes, (l.note.find('$') == std::string::npos ? 1.0 : 1.2) * tex_width(l.note, 0.92, true));
        all.push_back(l);
    }
    // one line each: a short lhs and its right side beside the lhs column, with the tag
    bool one_line_each = true;
    for (const laid &l : all) {
        one_line_each = one_line_each && column + l.right + l.tag_width <= row_budget_em;
        right = std::max(right, l.right);
    }
    const bool beside = one_line_each && notes > 0 && column + right + 2 + notes + tags <= row_budget_em;
    std::string out = "\\begin{align*}\n";
    for (std::size_t k = 0; k < all.size(); ++k) {
        const laid &l = all[k];
        std::vector<std::string> lines;
        if (l.left <= column && column + l.right + l.tag_width <= row_budget_em) {
            std::string line = l.parts.left + " &";
            for (std::size_t j = 0; j < l.parts.rights.size(); ++j)
                line += (j ? " " : "") + l.parts.rights[j].first + " " + l.parts.rights[j].second;
            lines.push_back(line);
        } else {
            lines = break_row(l.parts, row_budget_em - l.tag_width, column);
        }
        for (std::size_t j = 0; j + 1 < lines.size(); ++j)
            out += "  " + lines[j] + " \\\\\n";
        out += "  " + lines.back();
        if (beside && !l.note.empty())
            out += " &&\\text{\\small " + l.note + "}";
        out += tag_tex(l.tag, labelled);
        if (!beside && !l.note.empty())
            out += note_line(l.note, column);
        // rows with notes under them a little apart, so that each note reads with its row
        out += k + 1 < all.size() ? (notes > 0 && !beside ? " \\\\[1ex]\n" : " \\\\[0.3ex]\n") : "\n";
    }
    return out + "\\end{align*}\n";
}

// Rows each in a frame (\\boxed) with its note beside it, as many a line as fit (the results
// of a summary); the display may break between lines.
std::string latex_boxed(const std::vector<math_row> &rows, bool boxed = true)
{
    std::vector<std::string> lines;
    double width = 0;
    for (const math_row &r : rows) {
        const std::string note = tex_spans(r.note, false), formula = one_line(tex_row_parts(r));
        const std::string item =
            (boxed ? "\\boxed{" + formula + "}" : formula) + (note.empty() ? "" : "\\ \\text{\\small " + note + "}");
        const double w = tex_width(formula) + 1 + (note.empty() ? 0 : tex_width(note, 0.92, true) + 1);
        if (!lines.empty() && width + 3 + w <= row_budget_em) {
            lines.back() += " \\qquad " + item;
            width += 3 + w;
        } else {
            lines.push_back(item);
            width = w;
        }
    }
    std::string out = "\\begin{gather*}\n";
    for (std::size_t k = 0; k < lines.size(); ++k)
        out += "  " + lines[k] + (k + 1 < lines.size() ? " \\\\\n" : "\n");
    return out + "\\end{gather*}\n";
}

bool has_figures(const document &doc)
{
    for (const section &sec : doc.sections)
        for (const block &b : sec.blocks)
            if (b.k == block::figure)
                return true;
    return false;
}

// Rows for a terminal: tag, formula, and the note beside a short definition or under the row.
std::string text_rows(const std::vector<math_row> &rows)
{
    std::ostringstream os;
    std::size_t tag_width = 0;
    for (const math_row &r : rows)
        tag_width = std::max(tag_width, r.tag.empty() ? std::size_t(0) : columns(r.tag) + 2);
    for (const math_row &r : rows) {
        std::string tag = r.tag.empty() ? "" : "(" + r.tag + ")";
        std::string line =
            "  " + tag + std::string(tag_width - columns(tag) + (tag_width ? 2 : 0), ' ') + text_row_left(r);
        if (!r.rel.empty())
            line += " " + r.rel + " " + math_text(r.rhs);
        if (r.has_then)
            line += " = " + math_text(r.then);
        std::string note = text_spans(r.note);
        if (note.empty()) {
            os << line << "\n";
        } else if (r.rel.empty() && r.lhs_note.text.empty() && columns(line) < 22) {
            os << wrap(harden(line + std::string(22 - columns(line), ' ')) + note, "", std::string(24, ' '));
        } else {
            os << line << "\n" << wrap(note, std::string(tag_width + 8, ' '), std::string(tag_width + 8, ' '));
        }
    }
    return os.str();
}

// Lines in a frame of box-drawing characters (the results of a summary).
std::string text_box(const std::string &lines)
{
    std::vector<std::string> all;
    std::size_t width = 0, from = 0;
    while (from < lines.size()) {
        std::size_t to = lines.find('\n', from);
        if (to == std::string::npos)
            to = lines.size();
        all.push_back(lines.substr(from, to - from));
        width = std::max(width, columns(all.back()));
        from = to + 1;
    }
    std::string bar;
    for (std::size_t k = 0; k < width + 2; ++k)
        bar += "\u2500";
    std::string out = "  \u250c" + bar + "\u2510\n";
    for (const std::string &l : all)
        out += "  \u2502 " + l + std::string(width - columns(l), ' ') + " \u2502\n";
    return out + "  \u2514" + bar + "\u2518\n";
}

} // namespace

std::string explain_text(const document &doc)
{
    std::ostringstream os;
    os << doc.title << "\n" << std::string(columns(doc.title), '=') << "\n";
    if (!doc.description.empty())
        os << "\n" << wrap(doc.description, "", "");
    for (const section &sec : doc.sections) {
        os << "\n" << sec.title << "\n" << std::string(columns(sec.title), '-') << "\n";
        for (const block &b : sec.blocks) {
            switch (b.k) {
            case block::text:
                os << "\n" << wrap(text_spans(b.para), "", "");
                break;
            case block::list:
                os << "\n";
                for (const paragraph &item : b.items)
                    os << wrap(text_spans(item), "  - ", "    ");
                break;
            case block::figure:
                os << "\n" << wrap("[Figure: " + b.art.alt + "]", "", "");
                break;
            case block::rows: {
                os << "\n";
                if (b.boxed) {
                    os << text_box(text_rows(b.math));
                    break;
                }
                os << text_rows(b.math);
                break;
            }
            }
        }
    }
    return os.str();
}

std::string explain_markdown(const document &doc)
{
    std::ostringstream os;
    os << "# " << doc.title << "\n";
    if (!doc.description.empty())
        os << "\n" << doc.description << "\n";
    for (const section &sec : doc.sections) {
        os << "\n## " << sec.title << "\n";
        for (const block &b : sec.blocks) {
            switch (b.k) {
            case block::text:
                os << "\n" << tex_spans(b.para, true) << "\n";
                break;
            case block::list:
                os << "\n";
                for (const paragraph &item : b.items)
                    os << "- " << tex_spans(item, true) << "\n";
                break;
            case block::figure:
                os << "\n*Figure: " << b.art.alt << "*\n";
                break;
            case block::rows:
                os << "\n";
                if (b.boxed) { // a quoted block, one row a line, every formula in one $$ line
                    for (const math_row &r : b.math) {
                        std::string note = tex_spans(r.note, true);
                        os << "> $$" << one_line(tex_row_parts(r)) << "$$" << (note.empty() ? "" : " " + note)
                           << "\n>\n";
                    }
                    break;
                }
                for (const math_row &r : b.math) {
                    std::string note = tex_spans(r.note, true);
                    if (r.rel.empty() && r.tag.empty()) {
                        os << "- $" << one_line(tex_row_parts(r)) << "$" << (note.empty() ? "" : ": " + note) << "\n";
                        continue;
                    }
                    os << markdown_row(r) << "\n";
                    if (!note.empty())
                        os << "\n> " << note << "\n";
                    os << "\n";
                }
                break;
            }
        }
    }
    return os.str();
}

namespace
{

// The preamble of a hand-out: 10 pt on A4 with 2 cm margins (row_budget_em assumes that text
// width), Computer Modern in its Type 1 outlines (OT1: T1 would need cm-super or lmodern, which
// texlive-latex-base does not have, and fall back to bitmaps), emergency stretch for paragraphs
// with long formulas in them. Every package is in texlive-latex-base, tikz (only with a figure)
// in texlive-pictures.
std::string latex_preamble(const document &doc, bool figures)
{
    std::ostringstream os;
    os << "% Written by impactgen explain. Compile with pdflatex (needs amsmath, geometry, hyperref"
       << (figures ? "; tikz for the figure" : "") << ").\n"
       << "\\documentclass[10pt,a4paper]{article}\n"
          "\\usepackage[margin=2cm]{geometry}\n"
       << "\\usepackage{amsmath}\n";
    if (figures)
        os << "\\usepackage{tikz}\n"
              "\\newsavebox{\\figurebox}\n";
    os << "\\usepackage[hidelinks]{hyperref}\n"; // equation references link to their equations
    os << "\\setlength{\\parindent}{0pt}\n"
          "\\setlength{\\emergencystretch}{3em}\n"
          "\\allowdisplaybreaks\n";
    // a hand-out: a plain title line, less space around displays and headings (a summary: one page)
    os << "\\makeatletter\\renewcommand\\@maketitle{\\begin{center}{\\LARGE\\@title\\par}\\end{center}}"
          "\\renewcommand\\section{\\@startsection{section}{1}{0pt}{1.2ex plus .5ex}{0.6ex}{\\large\\bfseries}}"
          "\\makeatother\n"
          "\\AtBeginDocument{\\setlength{\\abovedisplayskip}{4pt}\\setlength{\\belowdisplayskip}{4pt}}\n"
          "\\setlength{\\parskip}{0.3em}\n"
          // lists set tightly: a list item is a line of the hand-out, not a paragraph
          "\\makeatletter\\def\\@listi{\\leftmargin\\leftmargini\\topsep 2pt plus 1pt\\parsep 0pt\\itemsep 1pt plus "
          "1pt}\\let\\@listI\\@listi\\makeatother\n";
    os << "\\title{" << tex_words(doc.title)
       << "}\n\\author{}\n\\date{}\n"
          "\\begin{document}\n\\maketitle\n";
    if (!doc.description.empty())
        os << "\\begin{center}\n\\itshape " << tex_words(doc.description) << "\n\\end{center}\n";
    return os.str();
}

// A figure, scaled down to the line when it is wider, never up.
std::string latex_figure(const block &b, level depth)
{
    std::ostringstream os;
    os << "\n\\begin{center}\n\\sbox{\\figurebox}{%\n" << b.art.tikz << "%\n}%\n";
    // at most 4 cm high in a summary, 5 cm in a full document
    os << (depth == level::summary ? "\\ifdim\\ht\\figurebox>4cm\\sbox{\\figurebox}{\\resizebox{!}{4cm}"
                                     "{\\usebox{\\figurebox}}}\\fi\n"
                                   : "\\ifdim\\ht\\figurebox>5cm\\sbox{\\figurebox}{\\resizebox{!}{5cm}"
                                     "{\\usebox{\\figurebox}}}\\fi\n");
    os << "\\ifdim\\wd\\figurebox>\\linewidth\\resizebox{\\linewidth}{!}{\\usebox{\\figurebox}}"
          "\\else\\usebox{\\figurebox}\\fi\n";
    if (!b.art.caption.empty())
        os << "\\par{\\small " << tex_words(b.art.caption) << "}\n";
    os << "\\end{center}\n";
    return os.str();
}

// Displayed rows: boxed or packed when they fit, a gather of bare rows, a list of plain ones,
// else numbered and broken to the line (latex_rows).
std::string latex_math(const block &b, std::set<std::string> &labelled)
{
    bool fits = true; // a row wider than the line is broken by latex_rows, unboxed
    for (const math_row &r : b.math)
        fits = fits && tex_width(one_line(tex_row_parts(r))) <= row_budget_em;
    if ((b.boxed || b.packed) && fits) // each row (in a \\boxed), its note beside it, several a line
        return latex_boxed(b.math, b.boxed);
    std::ostringstream os;
    if (detail::rows_are_bare(b.math)) {
        os << "\\begin{gather*}\n";
        for (std::size_t k = 0; k < b.math.size(); ++k)
            os << "  " << one_line(tex_row_parts(b.math[k])) << (k + 1 < b.math.size() ? " \\\\\n" : "\n");
        os << "\\end{gather*}\n";
        return os.str();
    }
    if (detail::rows_are_plain(b.math)) {
        os << "\n\\begin{itemize}\n";
        for (const math_row &r : b.math) {
            std::string note = tex_spans(r.note, false);
            os << "  \\item " << inline_math(one_line(tex_row_parts(r))) << (note.empty() ? "" : ": " + note) << "\n";
        }
        os << "\\end{itemize}\n";
        return os.str();
    }
    return latex_rows(b.math, labelled);
}

// Every character outside ASCII has been mapped (tex_words) or escaped; one that has not (a
// body named μ set in \\text{} or in the figure's labels) would stop pdflatex with an error:
// refuse it here, as tex_words does, naming it.
void require_ascii(const std::string &out)
{
    for (std::size_t k = 0; k < out.size(); ++k)
        if (static_cast<unsigned char>(out[k]) >= 0x80) {
            std::size_t n = 1;
            while (k + n < out.size() && (static_cast<unsigned char>(out[k + n]) & 0xC0) == 0x80)
                ++n;
            const std::size_t from = out.rfind('\n', k), to = out.find('\n', k);
            const std::string line =
                out.substr(from == std::string::npos ? 0 : from + 1,
                           (to == std::string::npos ? out.size() : to) - (from == std::string::npos ? 0 : from + 1));
            throw std::invalid_argument("the LaTeX output has no rendering for the character \"" +
                                        names::display_text(out.substr(k, n)) + "\" (in \"" +
                                        names::display_text(line, 60) + "\"); use ASCII names for --format latex");
        }
}

// One block of a LaTeX document.
void latex_block(std::ostream &os, const document &doc, const block &b, std::set<std::string> &labelled)
{
    switch (b.k) {
    case block::text:
        os << "\n" << tex_spans(b.para, false) << "\n";
        break;
    case block::list:
        os << "\n\\begin{itemize}\n";
        for (const paragraph &item : b.items)
            os << "  \\item " << tex_spans(item, false) << "\n";
        os << "\\end{itemize}\n";
        break;
    case block::figure:
        os << latex_figure(b, doc.depth);
        break;
    case block::rows:
        os << latex_math(b, labelled);
        break;
    }
}

/// A figure set beside the blocks that follow it (a short set-up: the figure on the right, the
/// text on the left), each in a minipage aligned at its top.
void latex_figure_beside(std::ostream &os, const document &doc, const std::vector<block> &beside, const block &fig,
                         std::set<std::string> &labelled)
{
    os << "\n\\noindent\\begin{minipage}[t]{0.6\\linewidth}\\vspace{0pt}\n";
    for (const block &b : beside)
        latex_block(os, doc, b, labelled);
    os << "\\end{minipage}\\hfill\\begin{minipage}[t]{0.37\\linewidth}\\vspace{0pt}\\centering\n";
    os << "\\sbox{\\figurebox}{%\n" << fig.art.tikz << "%\n}%\n";
    os << "\\ifdim\\ht\\figurebox>5cm\\sbox{\\figurebox}{\\resizebox{!}{5cm}{\\usebox{\\figurebox}}}\\fi\n";
    os << "\\ifdim\\wd\\figurebox>\\linewidth\\resizebox{\\linewidth}{!}{\\usebox{\\figurebox}}"
          "\\else\\usebox{\\figurebox}\\fi\n";
    if (!fig.art.caption.empty())
        os << "\\par{\\small " << tex_words(fig.art.caption) << "}\n";
    os << "\\end{minipage}\n";
}

} // namespace

std::string explain_latex(const document &doc)
{
    std::set<std::string> labelled;
    std::ostringstream os;
    os << latex_preamble(doc, has_figures(doc));
    for (const section &sec : doc.sections) {
        os << "\n\\section*{" << tex_words(sec.title) << "}\n";
        for (std::size_t k = 0; k < sec.blocks.size(); ++k) {
            const block &b = sec.blocks[k];
            if (b.k == block::figure && b.beside > 0 && k + b.beside < sec.blocks.size()) {
                const std::vector<block> next(sec.blocks.begin() + static_cast<std::ptrdiff_t>(k) + 1,
                                              sec.blocks.begin() + static_cast<std::ptrdiff_t>(k + 1 + b.beside));
                latex_figure_beside(os, doc, next, b, labelled);
                k += b.beside;
                continue;
            }
            latex_block(os, doc, b, labelled);
        }
    }
    os << "\n\\end{document}\n";
    const std::string out = os.str();
    require_ascii(out);
    return out;
}

} // namespace impactgen::print

// The width model of the LaTeX layout, for its tests (tests/explain/latex_tools.hpp
// declares the first two), and its row breaking for the HTML page (explain_html.cpp).
namespace impactgen::print::layout
{
double estimated_width_em(const std::string &tex)
{
    return tex_width(tex);
}
double row_budget_em()
{
    return print::row_budget_em;
}
std::vector<std::string> broken_row_lines(const math_row &r, double budget)
{
    const row_tex parts = tex_row_parts(r);
    if (tex_width(one_line(parts)) <= budget)
        return {};
    return break_row(parts, budget);
}
} // namespace impactgen::print::layout
