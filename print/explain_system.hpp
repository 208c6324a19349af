// The explanation of a system (explain_system.cpp, explain_system_solution.cpp): the parts
// the two files share. Private to the print library.
#pragma once

#include "explain.hpp"

#include <string>
#include <vector>

namespace impactgen::print::detail
{

/// The candidates (simultaneous impacts) or the chain (sequential), then the results; for a
/// symbolic problem with a worked example, the candidates in symbols and then the example's
/// verdict, results and the other model of impacts.
std::vector<section> system_solution_sections(const derivation &d, const worked_example *example);
/// The one-page summary: the set-up (given), the figure, the results in a box.
document system_summary(const derivation &d, section setup, const worked_example *example);
/// "one joint", "two contacts", "no pivot": a count in words (up to nine) with the noun it counts.
std::string count_of(std::size_t n, const std::string &one, const std::string &many);
/// Rows of a candidate's normal impulses and velocities after impact.
void system_candidate_values(section &s, const derivation &d, const system_candidate &c);
/// A value in running text (with its decimal digits where they help).
paragraph &system_value(paragraph &q, const GiNaC::ex &v);
/// symbol = value, with the value's decimal digits and a note.
math_row system_value_row(const GiNaC::ex &lhs, const GiNaC::ex &rhs, const std::string &note);
/// A body as a heading or a reference: its name, or "body 1" where the name is a number.
std::string body_label(const std::string &name);

} // namespace impactgen::print::detail
