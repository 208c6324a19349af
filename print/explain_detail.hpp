// What every contact law's chapter of the document shares (explain_law.hpp): the small
// builders of rows and spans, the figure, units, the symbolized twin of a numeric problem.
#pragma once

#include "explain.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impactgen::print
{
struct frame_component;
}

namespace impactgen::print::detail
{

/// "body 1", "body 2 (ball)", ...
std::string body_ref(const problem &p, std::size_t i);
/// (a, b[, c]) with every component through the canonical printer.
paragraph &vector_span(paragraph &p, const vec3 &v, int n);
/// Small enough to print as one formula (fewer than `limit` nodes).
bool printable(const GiNaC::ex &e, int limit = 400);
math_row row(const GiNaC::ex &lhs, const GiNaC::ex &rhs, const std::string &tag = "", const std::string &note = "");
math_row row(const GiNaC::ex &lhs, const GiNaC::ex &rhs, const std::string &tag, const paragraph &note);
math_row note_row(const std::string &text, const std::string &tex, const GiNaC::ex &rhs, const std::string &note = "");
/// A notation row without a value: the formula itself (text and TeX), and a note
/// (teaching prose, see paragraph::t, or a paragraph built by the caller).
math_row formula_row(const std::string &text, const std::string &tex, const char *note = "");
math_row formula_row(const std::string &text, const std::string &tex, const paragraph &note);
/// An exact number that is not an integer to six significant digits ("-0.142857"), else "".
std::string decimal_digits(const GiNaC::ex &v);
/// "≈ -0.142857" as notation (in math where the format has it: a true minus sign), or nothing.
paragraph approx(const std::string &decimal);
/// approx(decimal_digits(v)).
paragraph decimal_note(const GiNaC::ex &v);

/// The figure of the impact (figure/), drawn from the derivation's problem and frame.
figure_art figure_of(const derivation &d);

/// The direction of a world axis named `axis` in math: e_t, e_n, e_b for the contact frame's
/// names, else the name itself ("x"); appended to q.
paragraph &along(paragraph &q, const std::string &axis);
/// The items every law's statement lists after its own: each pin's reaction impulse, that a
/// body of infinite mass keeps its motion under the contact impulse (`contact_impulse`, teaching
/// prose such as "$~P$"), and that finite forces give no impulse.
void other_impulses(std::vector<paragraph> &items, const problem &p, const char *contact_impulse);
/// A component's meaning: its words, then ", component along" its axis in math.
paragraph component_note(const frame_component &c);
/// An unknown's meaning so (unknown_component in contact_frame.hpp).
paragraph unknown_note(const problem &p, const unknown &u);
/// A step's meaning in teaching prose, from its role, body and component (typed),
/// not from the solution's ASCII sentence.
paragraph step_note(const problem &p, const step &st);

/// What a number measures, for its unit when the problem gives "units": "SI".
enum class quantity { mass, inertia, length, velocity, angular_velocity, impulse, energy };
/// " kg", " m/s", ... (with the leading space), or "" when the problem gives no units.
std::string unit(const problem &p, quantity q);
/// The unit of a step's value (" N·s", " 1/kg", ...), or "" without "units": "SI".
std::string step_unit(const problem &p, step_role role);
/// The units of a problem in words: "SI (masses in kg, ...)".
std::string units_key(const problem &p);

/// Whether the slip of the contact points stops (the answer sticks) or reverses (slides
/// against the slip before impact) during the impact, from the answer's velocities before and
/// after (a numeric problem; false when they are not numbers or nothing slips before impact).
bool slip_stops_or_reverses(const derivation &d, const regime_case &answer);
/// The warning such an answer carries: Newton's law at the end of the impact, not Routh's.
paragraph slip_warning(bool stick);

/// How many components of pivot impulses are unknowns.
std::size_t pivot_impulse_count(const derivation &d);

/// A numeric problem's twin with symbols for its masses, inertias, velocities, e and μ
/// (geometry kept), for teaching in symbols first; values gets symbol == number and
/// units the unit of each (" kg", or "").
problem symbolized(const problem &p, GiNaC::lst &values, std::vector<std::string> &units);

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
