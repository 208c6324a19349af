// The answer object of shared/problem-format.md: numbers (solve --json) or
// expression strings in GiNaC's syntax (formulas --format json).
#pragma once

#include "symbolic/friction.hpp"
#include "symbolic/system.hpp"

#include <nlohmann/json.hpp>

namespace impactgen::print
{

/// symbolic == false: every value a decimal number (the problem must be numeric).
/// symbolic == true: every value an expression string in the problem's symbols.
nlohmann::ordered_json answer_json(const derivation &d, const solution &s, bool symbolic);

/// A problem with friction: the smooth keys plus tangential_impulse and regime.
nlohmann::ordered_json answer_json(const derivation &d, const regime_case &c, bool symbolic);

/// The answer for a person: exact values with their decimals.
std::string answer_text(const derivation &d, const solution &s);
/// With friction: the regime and the tangential impulse as well.
std::string answer_text(const derivation &d, const regime_case &c);
/// friction may be nullptr (smooth).
std::string answer_text(const derivation &d, const solution &s, const regime_case *friction);

/// The answer of a system (format version 3, a file with several contacts, joints, sequential
/// impacts or a perfectly rough contact): bodies, contacts[], joint_impulses, pivot_impulses,
/// kinetic_energy, impulses_unique, sequence (sequential only), energy_gain (when gained).
nlohmann::ordered_json system_answer_json(const problem &p, const system_answer &a);
std::string system_answer_text(const problem &p, const system_answer &a);

} // namespace impactgen::print
