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

int process_jacobian_formulas(const problem &p, const std::string &format, const std::string &wrt)
{
    std::vector<std::string> names;
    split_wrt(wrt, names);
    const derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    const process_jacobian j = process_jacobian_of(d, s, names);
    if (format == "json") {
        nlohmann::ordered_json a = print::formulas_json(d, s);
        a["jacobian"] = print::process_jacobian_json(j);
        std::cout << a.dump(2) << "\n";
    } else {
        std::cout << (format == "latex" ? print::formulas_latex(d, s) : print::formulas_text(d, s))
                  << print::process_jacobian_text(j, format == "latex");
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
        a["jacobian"] = print::friction_jacobian_json(j);
        std::cout << a.dump(2) << "\n";
    } else {
        std::cout << (format == "latex" ? print::formulas_latex(d, s) : print::formulas_text(d, s))
                  << print::friction_jacobian_text(j, format == "latex");
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
