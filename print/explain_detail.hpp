// What explain.cpp (smooth impacts) and explain_friction.cpp (Coulomb friction)
// share: the set-up section and the small builders of rows and spans.
#pragma once

#include "explain.hpp"

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impactgen::print::detail
{

/// "body 1", "body 2 (ball)", ...
std::string body_ref(const problem &p, std::size_t i);
/// (a, b[, c]) with every component through the canonical printer.
paragraph &vector_span(paragraph &p, const vec3 &v, int n);
/// Small enough to print as one formula (fewer than `limit` nodes).
bool printable(const GiNaC::ex &e, int limit = 400);
math_row row(const GiNaC::ex &lhs, const GiNaC::ex &rhs, const std::string &tag = "", const std::string &note = "");
math_row note_row(const std::string &text, const std::string &tex, const GiNaC::ex &rhs, const std::string &note = "");
/// A notation row without a value: the formula itself (text and TeX), and a note
/// (teaching prose, see paragraph::t, or a paragraph built by the caller).
math_row formula_row(const std::string &text, const std::string &tex, const char *note = "");
math_row formula_row(const std::string &text, const std::string &tex, const paragraph &note);
/// "≈ 0.142857142857143" for an exact number that is not an integer, else "".
std::string decimal_note(const GiNaC::ex &v);

/// The figure of the impact (figure/), drawn from the derivation's problem and frame.
figure_art figure_of(const derivation &d);

/// A step's meaning in teaching prose, from its role, body and component (typed),
/// not from the solution's ASCII sentence.
paragraph step_note(const problem &p, const step &st);

/// What a number measures, for its unit when the problem gives "units": "SI".
enum class quantity { mass, inertia, length, velocity, angular_velocity, impulse, energy };
/// " kg", " m/s", ... (with the leading space), or "" when the problem gives no units.
std::string unit(const problem &p, quantity q);
/// The units of a problem in words: "SI (masses in kg, ...)".
std::string units_key(const problem &p);

/// With friction, the set-up also names Coulomb's coefficient and the impulses
/// that become unknowns: N (unless the derivation has it already) and F.
struct friction_setup {
    GiNaC::ex mu;
    /// The coefficient's own name, when the document writes it otherwise (μ for a
    /// coefficient the problem names f).
    std::optional<notation> mu_in_problem;
    std::vector<std::pair<GiNaC::ex, paragraph>> impulses; ///< unknown symbol, meaning
};

/// A numeric problem's twin with symbols for its masses, inertias, velocities, e and μ
/// (geometry kept), for teaching in symbols first; values gets symbol == number and
/// units the unit of each (" kg", or "").
problem symbolized(const problem &p, GiNaC::lst &values, std::vector<std::string> &units);

/// A numeric problem taught in symbols first: its symbolized twin derived as d was (the
/// same normal convention), teach(twin, values, units) builds the document, and the
/// figure is drawn from the numbers. Empty when there is no number to name, or when the
/// twin cannot be derived or taught (a decision that needs the numbers).
std::optional<document> taught_in_symbols(const derivation &d,
                                          const std::function<document(const derivation &twin, const GiNaC::lst &values,
                                                                       const std::vector<std::string> &units)> &teach);

/// Section 1: bodies, contact frame, unknowns and their count.
section setup_section(const derivation &d, const friction_setup *friction = nullptr);

/// Rows without a relation and without equation tags: definitions (a symbol and its meaning).
inline bool rows_are_plain(const std::vector<math_row> &rows)
{
    for (const math_row &r : rows)
        if (!r.rel.empty() || !r.tag.empty())
            return false;
    return true;
}
/// Plain rows without notes: formulas displayed one per line.
inline bool rows_are_bare(const std::vector<math_row> &rows)
{
    if (!rows_are_plain(rows))
        return false;
    for (const math_row &r : rows)
        if (!r.note.spans.empty())
            return false;
    return true;
}

} // namespace impactgen::print::detail
