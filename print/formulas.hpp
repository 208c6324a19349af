// The closed form of a solution as text or LaTeX: the named intermediate
// quantities in order, then every unknown written through them.
#pragma once

#include "symbolic/solution.hpp"

#include <string>

namespace impactgen::print {

std::string formulas_text(const derivation& d, const solution& s);
std::string formulas_latex(const derivation& d, const solution& s);

} // namespace impactgen::print
