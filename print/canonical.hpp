// A deterministic printer for GiNaC expressions.
//
// GiNaC orders the operands of sums and products by hash, and hashes depend
// on addresses: the same expression prints in different orders from run to
// run. This printer walks add / mul / power / symbol / numeric / function and
// sorts the operands of every sum and product by their own canonical text, so
// the same expression prints the same bytes in every process (golden files
// depend on it). Signs are canonical too: a sum raised to an odd integer power
// is printed with its first term (in that order) positive, and the sign moved
// to the coefficient, so (a - b)/(c - d) and (b - a)/(d - c) print alike.
//
// Three syntaxes, differing only where the format does:
//   text    Unicode for a terminal: ω for w, τ for tau, ε for eps, ′ for ',
//           · for products, ², ³ for small powers, √ for square roots, a/b.
//   latex   for amsmath: \frac, \sqrt, symbols by their TeX names.
//   parser  ASCII that GiNaC's parser reads back (* ^ sqrt(), symbol names as
//           they are): the JSON answers and the exact numbers of `solve`.
// An expression of a kind the printer does not know (a matrix, a relation, a
// series) is an error (std::invalid_argument), never silently wrong output.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace impactgen::print {

enum class syntax { text, latex, parser };

std::string canonical(const GiNaC::ex& e, syntax s);
inline std::string canonical_text(const GiNaC::ex& e) { return canonical(e, syntax::text); }
inline std::string canonical_latex(const GiNaC::ex& e) { return canonical(e, syntax::latex); }
inline std::string canonical_parser(const GiNaC::ex& e) { return canonical(e, syntax::parser); }

/// A symbol's name for a terminal: w -> ω, tau -> τ, eps -> ε, ' -> ′.
std::string symbol_text(const std::string& name);
/// A symbol's TeX name, with multi-character subscripts braced.
std::string symbol_latex(const GiNaC::symbol& s);

} // namespace impactgen::print
