// impactgen explain: a walk through the derivation of one impact, the way the
// lecture notes (shared/seed/impact-of-rigid-bodies.md) set it up and solve it.
//
// One seam: explain() builds an explanation document once, from the
// derivation and its solution -- sections of paragraphs, lists and displayed
// equations, where every formula is a GiNaC expression (lhs, rhs) and not
// text. Each output format is a small printer over that document; all of them
// print expressions through the deterministic canonical printer
// (canonical.hpp), so the output is byte-stable and can be kept as golden files.
#pragma once

#include "symbolic/friction.hpp"

#include <string>
#include <vector>

namespace impactgen::print
{

/// Notation that is not a GiNaC expression (vector identities, operators):
/// the same formula for a terminal and for LaTeX, side by side.
struct notation {
    std::string text, tex;
};

/// One piece of running text: words, an expression, notation, or a reference
/// to a numbered equation (text: its tag, "3"; printed "(3)", linked where the
/// format can link).
struct span {
    enum kind { words, math, note, ref } k = words;
    std::string text;
    GiNaC::ex expr;
    notation formula;
};

struct paragraph {
    std::vector<span> spans;
    paragraph &w(const std::string &t)
    {
        spans.push_back({span::words, t, 0, {}});
        return *this;
    }
    paragraph &m(const GiNaC::ex &e)
    {
        spans.push_back({span::math, "", e, {}});
        return *this;
    }
    paragraph &n(const std::string &text, const std::string &tex)
    {
        spans.push_back({span::note, "", 0, {text, tex}});
        return *this;
    }
    paragraph &ref(const std::string &tag)
    {
        spans.push_back({span::ref, tag, 0, {}});
        return *this;
    }
    /// Teaching prose written by the project itself: words with symbols set
    /// between dollars, "the impulse acts along $e_n$ on $C1$"; see
    /// prose_notation() for what may stand between them. It takes a C string
    /// so that a std::string (a user's name, a value) cannot reach it by
    /// accident: what a user writes goes through w() and stays words.
    paragraph &t(const char *prose);
};

/// The notation of one symbol group of teaching prose (the text between two
/// dollars): identifiers (a letter or Greek letter, primes, "_sub", "^sup";
/// "C1" is C with subscript 1; "~v_C" marks a vector, e_t, e_n, e_b are unit
/// vectors), numbers, and the signs + - = / ( ) , | < > ± ∓ × · ≤ ≥ → ∞ ≈ ≠ ⁻¹ ² ∫ √.
/// Anything else is a programming error (std::logic_error naming it).
notation prose_notation(const std::string &src);

/// A displayed relation lhs REL rhs with an optional tag "(3)" and a note.
struct math_row {
    std::string tag;
    GiNaC::ex lhs, rhs;
    std::string rel = "="; ///< "=", "->" (a limit), "<=", ">="
    notation lhs_note;     ///< used instead of lhs when lhs_note.text is set
    bool has_then = false; ///< lhs = rhs = then: a formula and its value
    GiNaC::ex then;
    paragraph note; ///< printed under or beside the row
};

/// A figure of the impact, already drawn in each format that shows pictures.
struct figure_art {
    std::string caption; ///< plain words (escaped by each printer)
    std::string tikz;    ///< a tikzpicture environment (LaTeX needs \usepackage{tikz})
    std::string svg;     ///< one self-contained <svg> element (HTML)
    std::string alt;     ///< a one-line description (text, Markdown, the SVG's title)
};

struct block {
    enum kind { text, list, rows, figure } k = text;
    paragraph para;               ///< text
    std::vector<paragraph> items; ///< list
    std::vector<math_row> math;   ///< rows
    figure_art art;               ///< figure
    bool boxed = false;           ///< rows: the results, set in a frame (a box in every format)
    bool packed = false;          ///< rows: definitions, as many a line as fit (LaTeX), notes beside
    std::size_t beside = 0;       ///< figure: set to the right of the next `beside` text and list blocks (LaTeX)
};

struct section {
    std::string title;
    std::vector<block> blocks;
    section &para(const paragraph &p)
    {
        blocks.push_back({block::text, p, {}, {}, {}});
        return *this;
    }
    section &list(const std::vector<paragraph> &items)
    {
        blocks.push_back({block::list, {}, items, {}, {}});
        return *this;
    }
    section &rows(const std::vector<math_row> &r)
    {
        blocks.push_back({block::rows, {}, {}, r, {}});
        return *this;
    }
    /// Rows in a box: the results a reader looks for first.
    section &boxed_rows(const std::vector<math_row> &r)
    {
        blocks.push_back({block::rows, {}, {}, r, {}, true});
        return *this;
    }
    /// Definitions set compactly: as many a line as fit, each note beside its row.
    section &packed_rows(const std::vector<math_row> &r)
    {
        blocks.push_back({block::rows, {}, {}, r, {}, false, true});
        return *this;
    }
    section &picture(const figure_art &a)
    {
        blocks.push_back({block::figure, {}, {}, {}, a});
        return *this;
    }
};

/// How much of the derivation a document shows: `summary` is one page (the set-up, the
/// figure, the results in a box and the closed forms in the problem's symbols), `full`
/// the whole derivation.
enum class level { summary, full };

struct document {
    std::string title;
    std::vector<section> sections;
    std::string description = ""; ///< shown under the title (the problem's "description"), or ""
    level depth = level::full;    ///< a summary is set more tightly (LaTeX), to keep it to one page
};

/// Values for a worked example in the symbols of a problem (symbol == value).
struct worked_example {
    std::string caption;
    GiNaC::lst values;
    bool problem_numbers = false;   ///< the values are the problem's own (a numeric problem taught in symbols first)
    std::vector<std::string> units; ///< per value: " kg", " m/s", ... or "" (empty vector: none)
};

/// The worked example of the notes for a named class, if the notes have one
/// (pinned-planar: ball 0.5 kg at 5 m/s, rod 2 kg of 1 m, e = 0.8).
bool notes_example(const std::string &class_name, worked_example &out);

/// The explanation of one impact, whatever its contact law: the set-up, then the law's
/// statement, equations, each candidate's solution, the regimes when there is more than one
/// candidate, and the results (explain_law.hpp). `example` (optional, may be null): values
/// to substitute into every step of a symbolic problem at the end. A numeric problem is
/// taught in symbols first, then with its numbers.
document explain(const derivation &d, const impact_solution &s, const worked_example *example = nullptr,
                 level depth = level::full);

/// The explanation of a system (format version 3: joints, several contacts, sequential impacts;
/// explain_system.cpp): the notes' constrained-collision method, the Delassus matrix, the
/// candidate sets (for a numeric problem, which holds and why the others fail), the results.
/// `example` (optional): numbers for a symbolic system's symbols, for its figure and for a
/// worked example after the candidates. `depth` summary: one page, the set-up, the figure and
/// the results in a box.
document explain_system(const derivation &d, const worked_example *example = nullptr, level depth = level::full);

/// The worked example of a named system class (symbolic/named_systems.hpp), if it is one.
bool system_example(const std::string &class_name, worked_example &out);

std::string explain_text(const document &doc);     ///< Unicode, wrapped at 100 columns
std::string explain_markdown(const document &doc); ///< $...$ math (GiNaC-compatible LaTeX)
std::string explain_latex(const document &doc);    ///< a complete amsmath document for pdflatex
std::string explain_html(const document &doc);     ///< one self-contained HTML5 page, mathematics in MathML

} // namespace impactgen::print
