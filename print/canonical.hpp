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
// Four syntaxes, differing only where the format does:
//   text    Unicode for a terminal: ω for w, τ for tau, ε for eps, ′ for ',
//           · for products, ², ³ for small powers, √ for square roots, a/b.
//   latex   for amsmath: \frac, \sqrt, symbols by their TeX names. A power of
//           a subscripted name is r_{t1}^{2}; a name with a superscript or a
//           prime is braced first, {v'_{x1}}^{2}, or TeX sees two superscripts.
//   parser  ASCII that GiNaC's parser reads back (* ^ sqrt(), symbol names as
//           they are): the JSON answers and the exact numbers of `solve`.
//   mathml  presentation MathML, one element (an <mrow> around several) for a
//           <math> element that the caller writes (<math display="inline|block">):
//           <mn> <mi> <mo> <mfrac> <msqrt> <msup> <msub> <msubsup> <mrow>;
//           a product's factors are joined by an invisible times (U+2062). A
//           symbol is its TeX name (symbol_latex) read by tex_to_mathml, so
//           MathML and LaTeX show the same letters, subscripts, superscripts
//           and primes; r_{t1}^{2} is one <msubsup>. abs(x) is |x|, as the
//           document printers show it. All text is XML-escaped
//           (names::xml_text): a symbol named <script> or &amp; prints as
//           inert characters.
// An expression of a kind the printer does not know (a matrix, a relation, a
// series) is an error (std::invalid_argument), never silently wrong output.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

namespace impactgen::print
{

enum class syntax { text, latex, parser, mathml };

std::string canonical(const GiNaC::ex &e, syntax s);
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

/// A symbol's name for a terminal: w -> ω, tau -> τ, eps -> ε, ' -> ′.
std::string symbol_text(const std::string &name);
/// A symbol's TeX name, with multi-character subscripts braced.
std::string symbol_latex(const GiNaC::symbol &s);
/// A symbol as MathML: symbol_latex through tex_to_mathml, one element.
std::string symbol_mathml(const GiNaC::symbol &s);

} // namespace impactgen::print
