// The LaTeX layout of the explanation printers (explain_print.cpp): the width model of
// canonical LaTeX and the breaking of formulas and rows into lines (tex_layout.cpp).
// Private to the print library.
#pragma once

#include "explain.hpp"

#include <string>
#include <utility>
#include <vector>

namespace impactgen::print::tex_layout
{

/// An expression as canonical LaTeX (explain_print.cpp).
std::string math_latex(const GiNaC::ex &e);
/// A row's relation as TeX ("→" as \to, ...) (explain_print.cpp).
std::string tex_rel(const std::string &rel);

// Widths are in em of the 10pt body font.
constexpr double em_pt = 10.0;
// The text width: A4 with 2 cm margins (geometry), 170 mm = 483.7 pt.
constexpr double text_width_em = 483.69 / em_pt;
// What a displayed row may fill: the text width less a margin for what the
// glyph model cannot know (kerning, large delimiters).
constexpr double row_budget_em = text_width_em - 1.5;

/// The estimated width of TeX, in em (math mode unless text_mode).
double tex_width(const std::string &s, double scale = 1, bool text_mode = false);

// One item of a formula at one level of its nesting.
struct tex_item {
    enum kind { atom, op, group, frac } k = atom;
    std::string tex;             ///< atom: its TeX; op: "+" or "-"; group: the opening delimiter; frac: the denominator
    std::string close;           ///< group: the closing delimiter
    std::vector<tex_item> inner; ///< group: the contents; frac: the numerator
    double width = 0;            ///< estimated, em
};
using tex_seq = std::vector<tex_item>;
double seq_width(const tex_seq &seq);
std::string render(const tex_seq &seq);

// A unit of line filling: one term of a sum at some depth, with the TeX that
// opens its enclosing groups before it (head) or closes them after it (tail).
struct piece {
    std::string op;   ///< "+" or "-" before it; "" for the first term of a formula
    std::string head; ///< e.g. "m_{1} \left(" when the term starts a group
    tex_seq term;
    std::string tail; ///< e.g. "\right) \omega_{t1}" when it ends one
    int open = 0;     ///< \left groups open where a line may break before it

    double width() const
    {
        return (op.empty() ? 0 : 1.24) + tex_width(head) + seq_width(term) + (term.size() > 1 ? 0.2 : 0) +
               tex_width(tail);
    }
    std::string tex(bool line_start) const
    {
        std::string body = head;
        std::string t = render(term);
        if (!t.empty())
            body += (body.empty() ? "" : " ") + t;
        if (!tail.empty())
            body += (body.empty() ? "" : " ") + tail;
        if (op.empty())
            return body;
        // {}+ keeps the sign binary (its spaces) at the start of a line
        return (line_start ? "{}" : "") + op + " " + body;
    }
};

std::vector<piece> pieces_of(const std::string &tex);
/// The pieces set greedily as lines of `first` em, then `rest` em.
std::vector<std::string> fill_lines(std::vector<piece> pieces, double first, double rest);

// A displayed row as TeX: its parts and where the printers put it.
struct row_tex {
    std::string left;                                        ///< lhs (or its notation)
    std::vector<std::pair<std::string, std::string>> rights; ///< (relation, rhs), then ("=", then)
};

row_tex tex_row_parts(const math_row &r);
std::string one_line(const row_tex &row);
bool short_lhs(double width);
std::vector<std::string> break_row(const row_tex &row, double budget, double column = 0);

} // namespace impactgen::print::tex_layout
