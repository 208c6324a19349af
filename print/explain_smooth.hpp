// The smooth contact's chapter of the document (explain_law_frictionless.cpp puts these
// sections in their slots; explain_sections.cpp writes them): small helpers and the
// sections after the set-up. Private to the print library; explain_detail.hpp holds what
// every chapter shares.
#pragma once

#include "explain_detail.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace impactgen::print::detail
{

/// A letter or a digit.
bool alnum(char c);
std::string number_word(std::size_t n);
/// Print-only symbols: names for quantities that are not GiNaC symbols of the problem.
GiNaC::symbol show(const std::string &name, const std::string &tex);
const step *find_step(const solution &s, step_role role, std::size_t body = no_body);
/// Substitutes the steps of the given roles (and only those), latest first.
GiNaC::ex expand_some(const solution &s, const GiNaC::ex &e, const std::vector<step_role> &roles);

/// The impulses (the law's statement).
section impulse_section(const derivation &d);
/// The equations.
section equations_section(const derivation &d);
/// The count and the solution.
section solution_section(const derivation &d, const solution &s);
/// The checks (and the notes' worked example, when given).
section checks_section(const derivation &d, const solution &s, const worked_example *example);

} // namespace impactgen::print::detail
