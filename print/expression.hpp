// Expressions in the output formats. Term order follows GiNaC and may differ
// between runs: compare expressions mathematically, never as strings.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace impactgen::print {

/// GiNaC's own syntax: what GiNaC's parser reads back (also the text format).
std::string parser_syntax(const GiNaC::ex& e);
/// A number as a decimal with 15 significant digits; throws when e is not a number.
std::string decimal(const GiNaC::ex& e);
double to_double(const GiNaC::ex& e);
/// Fully expanded steps may still be large: normalise only what is cheap.
GiNaC::ex tidy(const GiNaC::ex& e);

} // namespace impactgen::print
