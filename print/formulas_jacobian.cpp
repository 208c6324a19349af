// formulas --jacobian of a contact law with candidates: the derivatives of each candidate
// (Routh's phase sequences, Coulomb's regimes) after the closed form, as text, LaTeX comments
// or JSON. A system's are in formulas.cpp (system_jacobian_text).
#include "print/canonical.hpp"
#include "print/formulas.hpp"

#include <sstream>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{
std::string expr(const ex &e, bool latex)
{
    return latex ? canonical_latex(e) : canonical_text(e);
}

using matrix = std::vector<std::vector<ex>>;

// A candidate's conditions, one "where" line each (text even in LaTeX: they are comments).
template <class Condition>
void conditions_text(std::ostream &os, const std::vector<Condition> &conds, const std::string &c)
{
    for (const Condition &k : conds)
        os << c << "  where " << expr(k.value, false) << (k.strict ? " > 0" : " >= 0") << "  (" << k.meaning << ")\n";
}

// A candidate's nonzero entries, then how many are 0.
template <class J>
void entries_text(std::ostream &os, const J &j, const matrix &entries, const std::string &c, bool latex)
{
    std::size_t zeros = 0;
    for (std::size_t o = 0; o < j.outputs.size(); ++o)
        for (std::size_t w = 0; w < j.wrt.size(); ++w) {
            if (entries[o][w].is_zero()) {
                ++zeros;
                continue;
            }
            os << c << "  d " << j.outputs[o] << " / d " << symbol_text(j.wrt[w]) << " = " << expr(entries[o][w], latex)
               << "\n";
        }
    os << c << "  (" << zeros << " of the " << j.outputs.size() * j.wrt.size() << " entries are 0 and not listed)\n";
}

// The opening paragraph: what is differentiated per candidate ("one", plural "ones"), by what,
// and what a boundary means.
template <class J>
void opening_text(std::ostream &os, const J &j, const std::string &per, const std::string &through,
                  const std::string &one, const std::string &c)
{
    os << "\n"
       << c << "Jacobian of the impact map per " << per << ", d(output)/d(input) by the chain" << through
       << " (inputs:";
    for (const symbol &x : j.wrt)
        os << " " << symbol_text(x);
    os << "). Inside a " << one << " (every condition strict) the map is smooth; on a boundary between two\n"
       << c << one << "s (a condition = 0) it is continuous and its derivative one-sided: each neighbour's own.\n";
}

void steps_text(std::ostream &os, const std::vector<step> &steps, const std::string &indent, bool latex)
{
    for (const step &st : steps)
        os << indent << symbol_text(st.sym) << " = " << expr(st.value, latex) << "\n";
}

nlohmann::ordered_json steps_json(const std::vector<step> &steps)
{
    nlohmann::ordered_json m = nlohmann::ordered_json::object();
    for (const step &st : steps)
        m[st.sym.get_name()] = canonical_text(st.value);
    return m;
}

template <class Condition> nlohmann::ordered_json conditions_json(const std::vector<Condition> &conds)
{
    nlohmann::ordered_json a = nlohmann::ordered_json::array();
    for (const Condition &k : conds)
        a.push_back({{"value", canonical_text(k.value)}, {"strict", k.strict}, {"meaning", k.meaning}});
    return a;
}

// {output: {input: derivative}}
template <class J> nlohmann::ordered_json matrix_json(const J &j, const matrix &entries)
{
    nlohmann::ordered_json m = nlohmann::ordered_json::object();
    for (std::size_t o = 0; o < j.outputs.size(); ++o) {
        nlohmann::ordered_json row = nlohmann::ordered_json::object();
        for (std::size_t w = 0; w < j.wrt.size(); ++w)
            row[j.wrt[w].get_name()] = canonical_text(entries[o][w]);
        m[j.outputs[o]] = row;
    }
    return m;
}

nlohmann::ordered_json wrt_json(const std::vector<symbol> &wrt)
{
    nlohmann::ordered_json a = nlohmann::ordered_json::array();
    for (const symbol &x : wrt)
        a.push_back(x.get_name());
    return a;
}

} // namespace

std::string process_jacobian_text(const process_jacobian &j, bool latex)
{
    std::ostringstream os;
    const std::string c = latex ? "% " : "";
    opening_text(os, j, "phase sequence of Routh's process", "\n" + c + "rule through the contact's steps", "sequence",
                 c);
    os << "\n";
    steps_text(os, j.derivative_steps, c, latex);
    for (const sequence_jacobian &q : j.sequences) {
        os << "\n" << c << "Sequence " << q.sequence << (q.conditions.empty() ? " (the one that holds)" : "") << ":\n";
        conditions_text(os, q.conditions, c);
        entries_text(os, j, q.entries, c, latex);
    }
    return os.str();
}

nlohmann::ordered_json process_jacobian_json(const process_jacobian &j)
{
    nlohmann::ordered_json out, seqs = nlohmann::ordered_json::array();
    for (const sequence_jacobian &q : j.sequences) {
        nlohmann::ordered_json s;
        s["sequence"] = q.sequence;
        s["conditions"] = conditions_json(q.conditions);
        s["matrix"] = matrix_json(j, q.entries);
        seqs.push_back(s);
    }
    out["wrt"] = wrt_json(j.wrt);
    out["steps"] = steps_json(j.derivative_steps);
    out["sequences"] = seqs;
    out["boundary"] = "on a boundary between sequences (a condition = 0) the derivative is one-sided";
    return out;
}

std::string friction_jacobian_text(const friction_jacobian &j, bool latex)
{
    std::ostringstream os;
    const std::string c = latex ? "% " : "";
    opening_text(os, j, "regime", " rule through the regime's\n" + c + "steps", "regime", c);
    os << (j.derivative_steps.empty() ? "" : "\n");
    steps_text(os, j.derivative_steps, c, latex);
    for (std::size_t k = 0; k < j.regimes.size(); ++k) {
        const regime_jacobian &r = j.regimes[k];
        os << "\n" << c << "Regime " << k + 1 << ": " << r.name << "\n";
        conditions_text(os, r.conditions, c);
        if (r.through_angle)
            os << c << "  " << symbol_text(r.dir_c) << " = cos(theta), " << symbol_text(r.dir_s)
               << " = sin(theta): theta a root of the angle equation g = 0, found for the numbers;\n"
               << c
               << "  through the implicit function theorem dtheta/dx = -(dg/dx)/(dg/dtheta), where dg/dtheta != 0\n"
               << c << "  (a simple root; at a double root the sliding direction is not differentiable)\n";
        steps_text(os, r.derivative_steps, c + "  ", latex);
        entries_text(os, j, r.entries, c, latex);
    }
    return os.str();
}

nlohmann::ordered_json friction_jacobian_json(const friction_jacobian &j)
{
    nlohmann::ordered_json out, regimes = nlohmann::ordered_json::array();
    for (const regime_jacobian &r : j.regimes) {
        nlohmann::ordered_json g;
        g["regime"] = r.name;
        g["conditions"] = conditions_json(r.conditions);
        g["through_angle"] = r.through_angle;
        if (r.through_angle) {
            g["cos_theta"] = r.dir_c.get_name();
            g["sin_theta"] = r.dir_s.get_name();
        }
        g["steps"] = steps_json(r.derivative_steps);
        g["matrix"] = matrix_json(j, r.entries);
        regimes.push_back(g);
    }
    out["wrt"] = wrt_json(j.wrt);
    out["steps"] = steps_json(j.derivative_steps);
    out["regimes"] = regimes;
    out["boundary"] = "on a boundary between regimes (a condition = 0) the derivative is one-sided";
    return out;
}

} // namespace impactgen::print
