#include "canonical.hpp"

#include "tex_to_mathml.hpp"

#include "expr/tree.hpp"

namespace impactgen::print
{
using namespace GiNaC;

namespace
{

std::string mathml_of_tex(const std::string &tex)
{
    return tex_to_mathml(tex);
}

} // namespace

std::string symbol_text(const symbol &s)
{
    return expr::symbol_text(s);
}

std::string symbol_latex(const symbol &s)
{
    return expr::symbol_latex(s);
}

std::string symbol_mathml(const symbol &s)
{
    return expr::mathml_one(tex_to_mathml(symbol_latex(s)));
}

std::vector<std::pair<bool, std::string>> canonical_terms(const ex &e, syntax s)
{
    if (!is_a<add>(e))
        return {{false, canonical(e, s)}};
    const expr::shared_tree shared;
    expr::tree &t = shared.get();
    return expr::print_terms(t, t.of(e), s, mathml_of_tex);
}

std::string canonical(const ex &e, syntax s, bool abs_as_bars)
{
    const expr::shared_tree shared;
    expr::tree &t = shared.get();
    std::string out = expr::print(t, t.of(e), s, mathml_of_tex, abs_as_bars).s;
    if (s == syntax::mathml) // one element: a leading minus is first in its row, a prefix sign
        out = expr::mathml_one(out);
    return out;
}

} // namespace impactgen::print
