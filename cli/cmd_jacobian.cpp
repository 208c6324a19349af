// impactgen formulas --jacobian: the derivatives of the impact map, printed
// after the closed form (text, LaTeX or JSON). They are the ones the generated
// <name>_jacobian computes: codegen's plan, chain rule through the steps.
#include "cli/commands.hpp"
#include "codegen/codegen.hpp"
#include "names/escape.hpp"
#include "print/answer.hpp"
#include "print/canonical.hpp"
#include "print/formulas.hpp"
#include "symbolic/friction_jacobian.hpp"
#include "symbolic/process_jacobian.hpp"
#include "symbolic/routh.hpp"

#include <nlohmann/json.hpp>

#include <iostream>
#include <sstream>

namespace impactgen::cli
{
using namespace GiNaC;

namespace
{

} // namespace

void split_wrt(const std::string &s, std::vector<std::string> &out)
{
    if (s.empty())
        return;
    std::string item;
    std::istringstream is(s + ",");
    while (std::getline(is, item, ',')) {
        if (item.empty())
            throw input_error("--wrt: \"" + names::display_text(s) +
                              "\" has an empty item (expected input names separated by commas)");
        out.push_back(item);
    }
}

namespace
{

// d(output)/d(input) in the notation of the format.
// The closed form's own step for an output (N, u, T_lost: named clear of the problem's symbols).
const step *step_of(const codegen::plan &pl, const codegen::output_value &ov)
{
    switch (ov.kind) {
    case codegen::output_value::normal_impulse:
        return pl.sol.find(step_role::normal_impulse);
    case codegen::output_value::approach_velocity:
        return pl.sol.find(step_role::approach_velocity);
    case codegen::output_value::energy_lost:
        return pl.sol.find(step_role::energy_lost);
    default:
        return nullptr;
    }
}

// (a velocity after impact is primed, as in the closed form)
std::string entry_name(const codegen::plan &pl, const codegen::output_value &ov, const symbol &x, bool latex)
{
    const bool after = ov.kind == codegen::output_value::velocity || ov.kind == codegen::output_value::angular_velocity;
    const std::string out = ov.field + (after ? "'" : "");
    if (!latex)
        return "d " + out + " / d " + print::symbol_text(x);
    std::string tex;
    if (const step *st = step_of(pl, ov)) {
        tex = print::symbol_latex(st->sym);
    } else {
        tex = print::symbol_latex(symbol(ov.field));
        const std::size_t sub = tex.find('_');
        if (after)
            tex.insert(sub == std::string::npos ? tex.size() : sub, "'");
    }
    return "\\frac{\\partial " + tex + "}{\\partial " + print::symbol_latex(x) + "}";
}

} // namespace

codegen::plan jacobian_plan_for(const problem &p, const std::string &wrt)
{
    require_newton_for_output(p, "formulas --jacobian");
    codegen::options o;
    o.name = "formulas";
    o.jacobian = true;
    split_wrt(wrt, o.wrt);
    try {
        return codegen::make_plan(p, o);
    } catch (const codegen::option_error &e) {
        throw input_error(std::string("--") + codegen::option_error::option_name(e.which) + ": " + e.what());
    }
}

std::string jacobian_text(const codegen::plan &pl)
{
    std::ostringstream os;
    const codegen::jacobian_plan &j = pl.jac;
    os << "\nJacobian of the impact map, d(output after impact)/d(input), by the chain rule through the steps above\n";
    os << "(inputs: ";
    for (std::size_t k = 0; k < j.wrt.size(); ++k)
        os << (k ? ", " : "") << print::symbol_text(j.wrt[k]);
    os << ")\n\n";
    for (const step &st : j.steps)
        os << print::symbol_text(st.sym) << " = " << print::canonical_text(st.value) << "\n    (" << st.meaning
           << ")\n";
    std::size_t zeros = 0;
    for (std::size_t o = 0; o < pl.outputs.size(); ++o)
        for (std::size_t k = 0; k < j.wrt.size(); ++k) {
            if (j.entries[o][k].is_zero()) {
                ++zeros;
                continue;
            }
            os << entry_name(pl, pl.outputs[o], j.wrt[k], false) << " = " << print::canonical_text(j.entries[o][k])
               << "\n";
        }
    os << "(" << zeros << " of the " << pl.outputs.size() * j.wrt.size() << " entries are 0 and not listed)\n";
    return os.str();
}

std::string jacobian_latex(const codegen::plan &pl)
{
    std::ostringstream os;
    const codegen::jacobian_plan &j = pl.jac;
    os << "% Jacobian of the impact map (chain rule through the steps)\n\\begin{align*}\n";
    std::vector<std::string> lines;
    for (const step &st : j.steps)
        lines.push_back(print::symbol_latex(st.sym) + " &= " + print::canonical_latex(st.value));
    for (std::size_t o = 0; o < pl.outputs.size(); ++o)
        for (std::size_t k = 0; k < j.wrt.size(); ++k)
            if (!j.entries[o][k].is_zero()) {
                const std::string lhs = entry_name(pl, pl.outputs[o], j.wrt[k], true),
                                  rhs = print::canonical_latex(j.entries[o][k]);
                if (lhs != rhs) // dN/de is a step already
                    lines.push_back(lhs + " &= " + rhs);
            }
    for (std::size_t k = 0; k < lines.size(); ++k)
        os << "  " << lines[k] << (k + 1 < lines.size() ? " \\\\" : "") << "\n";
    os << "\\end{align*}\n";
    return os.str();
}

nlohmann::ordered_json jacobian_json(const codegen::plan &pl)
{
    const codegen::jacobian_plan &j = pl.jac;
    nlohmann::ordered_json r;
    r["wrt"] = nlohmann::ordered_json::array();
    for (const symbol &x : j.wrt)
        r["wrt"].push_back(x.get_name());
    r["outputs"] = nlohmann::ordered_json::array();
    for (const codegen::output_value &ov : pl.outputs)
        r["outputs"].push_back(ov.field);
    // The closed form's own steps first: the derivatives are written in them.
    r["closed_form_steps"] = nlohmann::ordered_json::array();
    for (const step &st : pl.sol.steps)
        r["closed_form_steps"].push_back(
            {{"name", st.sym.get_name()}, {"value", print::canonical_parser(st.value)}, {"meaning", st.meaning}});
    r["steps"] = nlohmann::ordered_json::array();
    for (const step &st : j.steps)
        r["steps"].push_back(
            {{"name", st.sym.get_name()}, {"value", print::canonical_parser(st.value)}, {"meaning", st.meaning}});
    r["entries"] = nlohmann::ordered_json::array();
    for (std::size_t o = 0; o < pl.outputs.size(); ++o) {
        nlohmann::ordered_json row = nlohmann::ordered_json::array();
        for (std::size_t k = 0; k < j.wrt.size(); ++k)
            row.push_back(print::canonical_parser(j.entries[o][k]));
        r["entries"].push_back(row);
    }
    return r;
}

namespace
{
std::string expr(const ex &e, bool latex)
{
    return latex ? print::canonical_latex(e) : print::canonical_text(e);
}

std::string process_jacobian_text(const process_jacobian &j, bool latex)
{
    std::ostringstream os;
    const std::string c = latex ? "% " : "";
    os << "\n"
       << c << "Jacobian of the impact map per phase sequence of Routh's process, d(output)/d(input) by the chain\n"
       << c << "rule through the contact's steps (inputs:";
    for (const symbol &x : j.wrt)
        os << " " << print::symbol_text(x);
    os << "). Inside a sequence (every condition strict) the map is smooth; on a boundary between two\n"
       << c << "sequences (a condition = 0) it is continuous and its derivative one-sided: each neighbour's own.\n\n";
    for (const step &st : j.derivative_steps)
        os << c << print::symbol_text(st.sym) << " = " << expr(st.value, latex) << "\n";
    for (const sequence_jacobian &q : j.sequences) {
        os << "\n" << c << "Sequence " << q.sequence << (q.conditions.empty() ? " (the one that holds)" : "") << ":\n";
        for (const process_condition &k : q.conditions)
            os << c << "  where " << expr(k.value, false) << (k.strict ? " > 0" : " >= 0") << "  (" << k.meaning
               << ")\n";
        std::size_t zeros = 0;
        for (std::size_t o = 0; o < j.outputs.size(); ++o)
            for (std::size_t w = 0; w < j.wrt.size(); ++w) {
                if (q.entries[o][w].is_zero()) {
                    ++zeros;
                    continue;
                }
                os << c << "  d " << j.outputs[o] << " / d " << print::symbol_text(j.wrt[w]) << " = "
                   << expr(q.entries[o][w], latex) << "\n";
            }
        os << c << "  (" << zeros << " of the " << j.outputs.size() * j.wrt.size()
           << " entries are 0 and not listed)\n";
    }
    return os.str();
}

nlohmann::ordered_json process_jacobian_json(const process_jacobian &j)
{
    nlohmann::ordered_json out, wrt = nlohmann::ordered_json::array(), steps = nlohmann::ordered_json::object(),
                                seqs = nlohmann::ordered_json::array();
    for (const symbol &x : j.wrt)
        wrt.push_back(x.get_name());
    for (const step &st : j.derivative_steps)
        steps[st.sym.get_name()] = print::canonical_text(st.value);
    for (const sequence_jacobian &q : j.sequences) {
        nlohmann::ordered_json s, conds = nlohmann::ordered_json::array(), m = nlohmann::ordered_json::object();
        s["sequence"] = q.sequence;
        for (const process_condition &k : q.conditions)
            conds.push_back({{"value", print::canonical_text(k.value)}, {"strict", k.strict}, {"meaning", k.meaning}});
        s["conditions"] = conds;
        for (std::size_t o = 0; o < j.outputs.size(); ++o) {
            nlohmann::ordered_json row = nlohmann::ordered_json::object();
            for (std::size_t w = 0; w < j.wrt.size(); ++w)
                row[j.wrt[w].get_name()] = print::canonical_text(q.entries[o][w]);
            m[j.outputs[o]] = row;
        }
        s["matrix"] = m;
        seqs.push_back(s);
    }
    out["wrt"] = wrt;
    out["steps"] = steps;
    out["sequences"] = seqs;
    out["boundary"] = "on a boundary between sequences (a condition = 0) the derivative is one-sided";
    return out;
}

// The derivatives of one regime: its conditions, its derivative steps, its nonzero entries.
void regime_jacobian_text(std::ostream &os, const friction_jacobian &j, std::size_t k, bool latex)
{
    const regime_jacobian &r = j.regimes[k];
    const std::string c = latex ? "% " : "";
    os << "\n" << c << "Regime " << k + 1 << ": " << r.name << "\n";
    for (const regime_condition &k : r.conditions)
        os << c << "  where " << expr(k.value, false) << (k.strict ? " > 0" : " >= 0") << "  (" << k.meaning << ")\n";
    if (r.through_angle)
        os << c << "  " << print::symbol_text(r.dir_c) << " = cos(theta), " << print::symbol_text(r.dir_s)
           << " = sin(theta): theta a root of the angle equation g = 0, found for the numbers;\n"
           << c << "  through the implicit function theorem dtheta/dx = -(dg/dx)/(dg/dtheta), where dg/dtheta != 0\n"
           << c << "  (a simple root; at a double root the sliding direction is not differentiable)\n";
    for (const step &st : r.derivative_steps)
        os << c << "  " << print::symbol_text(st.sym) << " = " << expr(st.value, latex) << "\n";
    std::size_t zeros = 0;
    for (std::size_t o = 0; o < j.outputs.size(); ++o)
        for (std::size_t w = 0; w < j.wrt.size(); ++w) {
            if (r.entries[o][w].is_zero()) {
                ++zeros;
                continue;
            }
            os << c << "  d " << j.outputs[o] << " / d " << print::symbol_text(j.wrt[w]) << " = "
               << expr(r.entries[o][w], latex) << "\n";
        }
    os << c << "  (" << zeros << " of the " << j.outputs.size() * j.wrt.size() << " entries are 0 and not listed)\n";
}

std::string friction_jacobian_text(const friction_jacobian &j, bool latex)
{
    std::ostringstream os;
    const std::string c = latex ? "% " : "";
    os << "\n"
       << c << "Jacobian of the impact map per regime, d(output)/d(input) by the chain rule through the regime's\n"
       << c << "steps (inputs:";
    for (const symbol &x : j.wrt)
        os << " " << print::symbol_text(x);
    os << "). Inside a regime (every condition strict) the map is smooth; on a boundary between two\n"
       << c << "regimes (a condition = 0) it is continuous and its derivative one-sided: each neighbour's own.\n"
       << (j.derivative_steps.empty() ? "" : "\n");
    for (const step &st : j.derivative_steps)
        os << c << print::symbol_text(st.sym) << " = " << expr(st.value, latex) << "\n";
    for (std::size_t k = 0; k < j.regimes.size(); ++k)
        regime_jacobian_text(os, j, k, latex);
    return os.str();
}

nlohmann::ordered_json friction_jacobian_json(const friction_jacobian &j)
{
    auto steps_json = [](const std::vector<step> &steps) {
        nlohmann::ordered_json m = nlohmann::ordered_json::object();
        for (const step &st : steps)
            m[st.sym.get_name()] = print::canonical_text(st.value);
        return m;
    };
    nlohmann::ordered_json out, wrt = nlohmann::ordered_json::array(), regimes = nlohmann::ordered_json::array();
    for (const symbol &x : j.wrt)
        wrt.push_back(x.get_name());
    for (const regime_jacobian &r : j.regimes) {
        nlohmann::ordered_json g, conds = nlohmann::ordered_json::array(), m = nlohmann::ordered_json::object();
        g["regime"] = r.name;
        for (const regime_condition &k : r.conditions)
            conds.push_back({{"value", print::canonical_text(k.value)}, {"strict", k.strict}, {"meaning", k.meaning}});
        g["conditions"] = conds;
        g["through_angle"] = r.through_angle;
        if (r.through_angle) {
            g["cos_theta"] = r.dir_c.get_name();
            g["sin_theta"] = r.dir_s.get_name();
        }
        g["steps"] = steps_json(r.derivative_steps);
        for (std::size_t o = 0; o < j.outputs.size(); ++o) {
            nlohmann::ordered_json row = nlohmann::ordered_json::object();
            for (std::size_t w = 0; w < j.wrt.size(); ++w)
                row[j.wrt[w].get_name()] = print::canonical_text(r.entries[o][w]);
            m[j.outputs[o]] = row;
        }
        g["matrix"] = m;
        regimes.push_back(g);
    }
    out["wrt"] = wrt;
    out["steps"] = steps_json(j.derivative_steps);
    out["regimes"] = regimes;
    out["boundary"] = "on a boundary between regimes (a condition = 0) the derivative is one-sided";
    return out;
}
} // namespace

int process_jacobian_formulas(const problem &p, const std::string &format, const std::string &wrt)
{
    std::vector<std::string> names;
    split_wrt(wrt, names);
    const derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    const process_jacobian j = process_jacobian_of(d, s, names);
    if (format == "json") {
        nlohmann::ordered_json a = print::formulas_json(d, s);
        a["jacobian"] = process_jacobian_json(j);
        std::cout << a.dump(2) << "\n";
    } else {
        std::cout << (format == "latex" ? print::formulas_latex(d, s) : print::formulas_text(d, s))
                  << process_jacobian_text(j, format == "latex");
    }
    return 0;
}

int friction_jacobian_formulas(const problem &p, const std::string &format, const std::string &wrt)
{
    std::vector<std::string> names;
    split_wrt(wrt, names);
    const derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    const friction_jacobian j = friction_jacobian_of(d, s, names);
    if (format == "json") {
        nlohmann::ordered_json a = print::formulas_json(d, s);
        a["jacobian"] = friction_jacobian_json(j);
        std::cout << a.dump(2) << "\n";
    } else {
        std::cout << (format == "latex" ? print::formulas_latex(d, s) : print::formulas_text(d, s))
                  << friction_jacobian_text(j, format == "latex");
    }
    return 0;
}

int system_jacobian_formulas(const problem &p, const std::string &format, const std::string &wrt)
{
    std::vector<std::string> names;
    split_wrt(wrt, names);
    const system_jacobian j = system_jacobian_of(p, names);
    if (format == "json") {
        nlohmann::ordered_json a = print::system_formulas_json(p);
        a["jacobian"] = print::system_jacobian_json(p, j);
        std::cout << a.dump(2) << "\n";
    } else {
        std::cout << print::system_formulas_text(p, format == "latex")
                  << print::system_jacobian_text(p, j, format == "latex");
    }
    return 0;
}

} // namespace impactgen::cli
