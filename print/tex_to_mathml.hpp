// A small translator from TeX math to presentation MathML, for the HTML
// printer of explanations (explain_html.cpp).
//
// It reads exactly the TeX the project writes itself: the notation of the
// explanation documents (vector identities such as
// \underline{v}'_{C_1} + \underline{\omega}'_1 \times \underline{r}_{AC_1},
// \hat{\underline{e}}_n, \int N\,dt, \frac{1}{m_i}, \underline{\underline{I}}_i^{-1},
// \left|...\right|, \le, \mu^*), symbols' TeX names (v'_{x1}, I^{1}_{nb},
// \omega_{z,\text{rod}}, with the text-mode escapes of names::latex_text inside
// \text{...}) and the canonical printer's LaTeX (\frac, \sqrt, \left( \right),
// \cdot, \operatorname{sin}). The subset:
//
//   letters, digits (a decimal number is one <mn>), + - = < > ( ) [ ] | / , ; : ! ? * & ...
//   x_a  x^a  x'  x'_a  x_a^b  (a one-character or braced argument)   {...} groups
//   \frac{a}{b}  \sqrt{a}  \hat{a}  \underline{a}  \left( \right) (also [ ] | . \{ \})
//   \text{...}  \mathrm{...}  \operatorname{...}
//   Greek letters (\alpha ... \omega, \varepsilon, \vartheta, \varpi, \varrho,
//   \varsigma, \varphi, \Gamma ... \Omega), \infty, \prime, \ell
//   \cdot \times \pm \mp \le \leq \ge \geq \ne \neq \approx \to \rightarrow \ldots \dots \cdots
//   \int \sum \colon, function names \cos \sin \tan \arctan \max \min \det
//   spaces \, \: \; \quad \qquad "\ ", and \_ \# \% \& \$ \{ \} as characters
//
// Every character of text becomes XML-escaped content (names::xml_text), so
// whatever a name holds comes out inert. A control sequence outside the
// subset, an unbalanced brace or a missing argument is an error
// (std::invalid_argument naming it), never silently dropped.
#pragma once

#include <string>

namespace impactgen::print
{

/// MathML children for a <math> element (the caller writes <math ...> and
/// </math>): a sequence of MathML elements, no wrapper.
std::string tex_to_mathml(const std::string &tex);

} // namespace impactgen::print
