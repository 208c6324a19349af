#include "formulas.hpp"

#include "canonical.hpp"
#include "expression.hpp"

#include <sstream>

namespace impactgen::print {
using namespace GiNaC;

namespace {

// One formula document, printed by a format-specific line writer.
struct formula_line {
    std::string name_text, name_tex;
    ex value;
    std::string meaning;
};

std::vector<formula_line> collect(const derivation& d, const solution& s)
{
    std::vector<formula_line> lines;
    for (const step& st : s.steps)
        lines.push_back({st.sym.get_name(), symbol_latex(st.sym), st.value, st.meaning});
    for (std::size_t k = 0; k < d.unknowns.size(); ++k) {
        const unknown& u = d.unknowns[k];
        if (u.kind == unknown_kind::normal_impulse)
            continue; // N is already a step
        ex v = s.unknown_values.op(k).rhs();
        lines.push_back({u.sym.get_name(), symbol_latex(u.sym), v, u.meaning});
    }
    return lines;
}

std::string header(const derivation& d)
{
    std::ostringstream os;
    os << d.prob.source << ": " << d.count_unknowns() << " unknowns, " << d.count_equations() << " equations";
    return os.str();
}

} // namespace

std::string formulas_text(const derivation& d, const solution& s)
{
    std::ostringstream os;
    os << header(d) << "\n";
    if (!d.frame_is_world || d.prob.contact.normal != vec3{0, 1, 0})
        os << "unit normal n = (" << canonical_text(d.n_hat[0]) << ", " << canonical_text(d.n_hat[1])
           << (d.prob.dimension == 3 ? ", " + canonical_text(d.n_hat[2]) : "") << ")\n";
    os << "\n";
    for (const formula_line& l : collect(d, s))
        os << symbol_text(l.name_text) << " = " << canonical_text(l.value) << "\n    (" << l.meaning << ")\n";
    return os.str();
}

std::string formulas_latex(const derivation& d, const solution& s)
{
    std::ostringstream os;
    os << "% impactgen formulas -- " << header(d) << "\n";
    os << "\\begin{align*}\n";
    auto lines = collect(d, s);
    for (std::size_t k = 0; k < lines.size(); ++k)
        os << "  " << lines[k].name_tex << " &= " << canonical_latex(lines[k].value) << (k + 1 < lines.size() ? " \\\\" : "") << "\n";
    os << "\\end{align*}\n";
    return os.str();
}

} // namespace impactgen::print
