// The printer over the canonical tree (expr/tree.hpp): one walk of the tree, four
// syntaxes that differ only where the format does.
//   text    Unicode for a terminal: ω for an angular velocity's w, τ for tau, ε for eps, ′ for ',
//           · for products, ², ³ for small powers, √ for square roots, a/b.
//           The text form of a node is also its order key in the tree.
//   latex   for amsmath: \frac, \sqrt, symbols by their TeX names. A power of
//           a subscripted name is r_{t1}^{2}; a name with a superscript or a
//           prime is braced first, {v'_{x1}}^{2}, or TeX sees two superscripts.
//   parser  ASCII that GiNaC's parser reads back (* ^ sqrt(), symbol names as
//           they are).
//   mathml  presentation MathML: <mn> <mi> <mo> <mfrac> <msqrt> <msup> <msub>
//           <msubsup> <mrow>; a product's factors joined by an invisible times
//           (U+2062); symbols and constants through the caller's TeX to MathML
//           converter, so MathML and LaTeX show the same letters; abs(x) is |x|;
//           all text XML-escaped.
// An expression no syntax can print (a matrix, a relation, a complex number, a
// product with a coefficient that is not rational) is an error
// (std::invalid_argument), never silently wrong output.
#pragma once

#include "roles.hpp"
#include "tree.hpp"

#include <string>
#include <utility>
#include <vector>

namespace impactgen::expr
{

enum class syntax { text, latex, parser, mathml };

/// TeX to one MathML element (print/tex_to_mathml), for symbols and constants in MathML.
using tex_to_mathml_fn = std::string (*)(const std::string &tex);

/// The node as written in the syntax (MathML: a sequence of elements). abs_as_bars:
/// abs(x) written |x| in text and LaTeX too, as the documents write it (MathML always does).
printed print(tree &t, int id, syntax s, tex_to_mathml_fn mathml = nullptr, bool abs_as_bars = false);
/// The node read as a product (a term of a sum without its sign).
printed print_product(tree &t, int id, syntax s, tex_to_mathml_fn mathml = nullptr);
/// A factor of a product, base^exponent (exponent > 0).
printed print_factor(tree &t, const factor &f, syntax s, tex_to_mathml_fn mathml = nullptr);
/// The terms of a sum node as written, each (negative, text without its sign).
std::vector<std::pair<bool, std::string>> print_terms(tree &t, int id, syntax s, tex_to_mathml_fn mathml = nullptr);

/// A symbol's name for a terminal: tau -> τ, eps -> ε, rho -> ρ, ' -> ′, and for an angular
/// velocity (the role, never the name: expr/roles.hpp) its leading w -> ω.
std::string symbol_text(const std::string &name, symbol_role role = symbol_role::none);
/// The symbol's name for a terminal, with the role the model gave it.
std::string symbol_text(const GiNaC::symbol &s);
/// A symbol's TeX name, with multi-character subscripts braced.
std::string symbol_latex(const GiNaC::symbol &s);
/// MathML elements as one element (an <mrow> around several).
std::string mathml_one(const std::string &elements);

} // namespace impactgen::expr
