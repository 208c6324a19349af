// The canonical printer of GiNaC expressions: the one canonical tree of expr/
// (expr/tree.hpp: operands in an order of their own, never GiNaC's run-to-run
// term order; canonical signs, so (a - b)/(c - d) and (b - a)/(d - c) print
// alike) written by the one printer over it (expr/print.hpp), in four syntaxes
// that differ only where the format does:
//   text    Unicode for a terminal: ω for w, τ for tau, ε for eps, ′ for ',
//           · for products, ², ³ for small powers, √ for square roots, a/b.
//   latex   for amsmath: \frac, \sqrt, symbols by their TeX names.
//   parser  ASCII that GiNaC's parser reads back (* ^ sqrt(), symbol names as
//           they are): the JSON answers and the exact numbers of `solve`.
//   mathml  presentation MathML, one element (an <mrow> around several) for a
//           <math> element that the caller writes (<math display="inline|block">).
//           A symbol is its TeX name (symbol_latex) read by tex_to_mathml, so
//           MathML and LaTeX show the same letters, subscripts, superscripts
//           and primes. All text is XML-escaped (names::xml_text).
// An expression of a kind the printer does not know (a matrix, a relation, a
// series) is an error (std::invalid_argument), never silently wrong output.
#pragma once

#include "expr/print.hpp"

#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

namespace impactgen::print
{

using syntax = expr::syntax;

/// abs_as_bars: abs(x) written |x| (\left|x\right| in LaTeX), as the documents write it;
/// MathML always writes |x|.
std::string canonical(const GiNaC::ex &e, syntax s, bool abs_as_bars = false);
inline std::string canonical_text(const GiNaC::ex &e)
{
    return canonical(e, syntax::text);
}
inline std::string canonical_latex(const GiNaC::ex &e)
{
    return canonical(e, syntax::latex);
}
inline std::string canonical_parser(const GiNaC::ex &e)
{
    return canonical(e, syntax::parser);
}
inline std::string canonical_mathml(const GiNaC::ex &e)
{
    return canonical(e, syntax::mathml);
}

/// The terms of a sum as they print, in the same order and with the same signs as
/// canonical(e, s) gives them: (negative, term without its sign). Not a sum: one
/// term, its whole text (sign included). For breaking a long sum over lines.
std::vector<std::pair<bool, std::string>> canonical_terms(const GiNaC::ex &e, syntax s);

/// A symbol's name for a terminal: tau -> τ, eps -> ε, rho -> ρ, ' -> ′; an angular velocity's
/// (the role the model gave it, expr/roles.hpp) leading w -> ω.
std::string symbol_text(const GiNaC::symbol &s);
/// A symbol's TeX name, with multi-character subscripts braced.
std::string symbol_latex(const GiNaC::symbol &s);
/// A symbol as MathML: symbol_latex through tex_to_mathml, one element.
std::string symbol_mathml(const GiNaC::symbol &s);

} // namespace impactgen::print
