// Expressions in the output formats. Term order follows GiNaC and may differ
// between runs: compare expressions mathematically, never as strings.
#pragma once

#include <ginac/ginac.h>

#include <stdexcept>
#include <string>

namespace impactgen::print
{

/// GiNaC's own syntax: what GiNaC's parser reads back (also the text format).
std::string parser_syntax(const GiNaC::ex &e);
/// A number as a decimal with 15 significant digits; throws when e is not a number.
std::string decimal(const GiNaC::ex &e);
/// A constant whose float value no precision up to 1280 digits settles (it cancels deeper).
struct no_decimal : std::invalid_argument {
    no_decimal() : std::invalid_argument("no decimal: its exact form cancels beyond 1280 digits") {}
};
/// The value of a constant as a float, to double precision at least: evaluated at 40, 80,
/// ... 1280 digits until two evaluations agree (a cancellation in the leading digits needs
/// more than GiNaC's default); 0 where decided so. Throws no_decimal when nothing settles it.
GiNaC::ex evaluated_constant(const GiNaC::ex &e);
double to_double(const GiNaC::ex &e);
/// Fully expanded steps may still be large: normalise only what is cheap.
GiNaC::ex tidy(const GiNaC::ex &e);
/// factor(e) with every factor expanded: GiNaC's factor() returns a factor partly collected
/// in whichever variable its run-to-run order puts first ((7 + (2 a + b) c) in one run,
/// 7 + 2 a c + b c in the next); expanded, the factors are the same in every run.
GiNaC::ex factored(const GiNaC::ex &e);

} // namespace impactgen::print
