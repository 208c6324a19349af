// Derivatives of the impact map for code generation: the chain rule applied
// step by step to the solution's straight-line closed form (forward mode, exact,
// by GiNaC's diff), so the Jacobian costs a multiple of the values, not of the
// fully expanded formulas.
#include "code_plan.hpp"

#include "names/escape.hpp"

#include <algorithm>
#include <set>

namespace impactgen::codegen
{
using namespace GiNaC;

namespace
{

// A derivative that is a number or a bare symbol stays inline; anything else is named.
bool trivial(const ex &e)
{
    return is_a<numeric>(e) || is_a<symbol>(e);
}

std::string tex(const symbol &s)
{
    const std::string t = s.get_TeX_name();
    return t.empty() ? s.get_name() : t;
}

} // namespace

std::vector<symbol> jacobian_inputs(const std::vector<symbol> &inputs, const std::vector<std::string> &wrt)
{
    std::vector<symbol> out = wrt.empty() ? inputs : std::vector<symbol>{};
    for (const std::string &name : wrt) {
        auto it = std::find_if(inputs.begin(), inputs.end(), [&](const symbol &x) { return x.get_name() == name; });
        if (it == inputs.end()) {
            std::string all;
            for (const symbol &x : inputs)
                all += (all.empty() ? "" : ", ") + x.get_name();
            throw option_error(
                option_error::wrt,
                names::display_text(name) + " is not an input of the generated function (its inputs: " +
                    (all.empty() ? std::string("none: name it in --params") : names::display_text(all, 400)) + ")");
        }
        if (std::find(out.begin(), out.end(), *it) != out.end())
            throw option_error(option_error::wrt, names::display_text(name) + " is named twice");
        out.push_back(*it);
    }
    if (out.empty())
        throw option_error(option_error::jacobian, "the generated function has no input to differentiate by");
    return out;
}

jacobian_plan plan_jacobian(const plan &pl, const std::vector<std::string> &wrt)
{
    jacobian_plan jp;
    jp.wrt = jacobian_inputs(pl.inputs, wrt);
    const std::vector<step> &steps = pl.sol.steps;
    const std::size_t nw = jp.wrt.size();
    // Derivative steps are named d<step>_d<input>, clear of every name the problem and
    // its closed form use (a symbol called dN_dm1 stays the symbol), with a trailing _.
    std::set<std::string> taken;
    for (const symbol &x : pl.prob.parameters())
        taken.insert(x.get_name());
    for (const symbol &x : pl.inputs)
        taken.insert(x.get_name());
    for (const step &st : steps)
        taken.insert(st.sym.get_name());
    auto fresh = [&](std::string name) {
        while (taken.count(name))
            name += "_";
        taken.insert(name);
        return name;
    };
    // grad[k][j] = d step_k / d wrt_j (0, a number, an input, or a derivative step's symbol).
    std::vector<std::vector<ex>> grad(steps.size(), std::vector<ex>(nw, 0));
    // The earlier steps each step (or output) uses directly.
    auto used_steps = [&](const ex &v, std::size_t before) {
        std::vector<std::size_t> r;
        for (std::size_t m = 0; m < before; ++m)
            if (v.has(steps[m].sym))
                r.push_back(m);
        return r;
    };
    auto derivative = [&](const ex &v, const std::vector<std::size_t> &uses, std::size_t j) {
        ex d = v.diff(jp.wrt[j]);
        for (std::size_t m : uses)
            if (!grad[m][j].is_zero())
                d += v.diff(steps[m].sym) * grad[m][j];
        return d;
    };
    for (std::size_t k = 0; k < steps.size(); ++k) {
        const std::vector<std::size_t> uses = used_steps(steps[k].value, k);
        for (std::size_t j = 0; j < nw; ++j) {
            ex d = derivative(steps[k].value, uses, j);
            if (trivial(d)) {
                grad[k][j] = d;
                continue;
            }
            step ds;
            ds.sym = symbol(fresh("d" + steps[k].sym.get_name() + "_d" + jp.wrt[j].get_name()),
                            "\\frac{\\partial " + tex(steps[k].sym) + "}{\\partial " + tex(jp.wrt[j]) + "}");
            ds.value = d;
            ds.meaning = "d " + steps[k].sym.get_name() + " / d " + jp.wrt[j].get_name();
            ds.role = steps[k].role;
            ds.body = steps[k].body;
            ds.row = steps[k].row;
            ds.column = steps[k].column;
            jp.steps.push_back(ds);
            grad[k][j] = ds.sym;
        }
    }
    for (const output_value &ov : pl.outputs) {
        const std::vector<std::size_t> uses = used_steps(ov.value, steps.size());
        std::vector<ex> row;
        for (std::size_t j = 0; j < nw; ++j)
            row.push_back(derivative(ov.value, uses, j));
        jp.entries.push_back(row);
    }
    return jp;
}

} // namespace impactgen::codegen
