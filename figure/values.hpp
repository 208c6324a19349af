// Internal to figure/: step 1 of draw(), the numbers (values.cpp).
#pragma once

#include "symbolic/problem.hpp"

#include <vector>

namespace impactgen::figure::detail
{

/// The value of e with the illustrative values substituted, as a double; the fallback when
/// it does not evaluate to a finite real number.
double number(const GiNaC::ex &e, const GiNaC::exmap &values, double fallback);

/// The symbols an expression contains (ordered, so the walk is deterministic).
std::vector<GiNaC::symbol> symbols_in(const GiNaC::ex &e);

/// The illustrative value of every symbol of the problem (empty for a numeric problem): for a
/// named class the values it gave its quantities (problem::illustrative), for a problem file a
/// value by each symbol's first role; never by a symbol's name.
GiNaC::exmap illustrative_values(const problem &p);

} // namespace impactgen::figure::detail
