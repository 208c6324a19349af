// The answer object of shared/problem-format.md: numbers (solve --json) or
// expression strings in GiNaC's syntax (formulas --format json).
#pragma once

#include "symbolic/solution.hpp"

#include <nlohmann/json.hpp>

namespace impactgen::print {

/// symbolic == false: every value a decimal number (the problem must be numeric).
/// symbolic == true: every value an expression string in the problem's symbols.
nlohmann::ordered_json answer_json(const derivation& d, const solution& s, bool symbolic);

/// The answer for a person: exact values with their decimals.
std::string answer_text(const derivation& d, const solution& s);

} // namespace impactgen::print
