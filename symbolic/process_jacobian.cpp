#include "process_jacobian.hpp"

#include <set>

namespace impactgen
{
using namespace GiNaC;

std::vector<symbol> jacobian_inputs(const problem &p, const std::vector<std::string> &wrt)
{
    const std::vector<symbol> all = p.parameters();
    if (wrt.empty()) {
        if (all.empty())
            throw input_error("--jacobian: the problem has no symbol to differentiate by (its numbers decide one "
                              "answer: 'impactgen solve' answers it)");
        return all;
    }
    std::vector<symbol> out;
    std::set<std::string> seen;
    for (const std::string &name : wrt) {
        if (!seen.insert(name).second)
            throw input_error("--wrt: " + name + " is named twice");
        const symbol *found = nullptr;
        for (const symbol &x : all)
            if (x.get_name() == name)
                found = &x;
        if (!found)
            throw input_error("--wrt: " + name + " is not a symbol of the problem");
        out.push_back(*found);
    }
    return out;
}

namespace
{

// The outputs of a candidate: the impulses along n and e_t, then each movable body's velocity
// after impact (planar: x, y and the spin).
std::vector<std::pair<std::string, ex>> outputs_of(const problem &p, const regime_case &c)
{
    std::vector<std::pair<std::string, ex>> out{{"normal_impulse", c.sol.normal_impulse},
                                                {"tangential_impulse", c.tangential_scalar}};
    const char *ax[3] = {"x", "y", "z"};
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        if (p.bodies[b].infinite_mass)
            continue;
        for (int k = 0; k < 2; ++k)
            out.push_back({"v'_" + std::string(ax[k]) + "," + p.bodies[b].name, c.sol.after[b].velocity[k]});
        if (!p.bodies[b].particle)
            out.push_back({"w'_z," + p.bodies[b].name, c.sol.after[b].angular_velocity[2]});
    }
    return out;
}

} // namespace

bool solution_follows_process(const impact_solution &s)
{
    return !s.cases.empty() && !s.cases.front().process.empty();
}

step_gradients differentiate_steps(const std::vector<step> &steps, const std::vector<symbol> &wrt)
{
    step_gradients g;
    const std::size_t nw = wrt.size();
    g.of_step.assign(steps.size(), std::vector<ex>(nw, 0));
    for (std::size_t k = 0; k < steps.size(); ++k)
        for (std::size_t w = 0; w < nw; ++w) {
            ex v = steps[k].value.diff(wrt[w]);
            for (std::size_t i = 0; i < k; ++i)
                if (!g.of_step[i][w].is_zero())
                    v += steps[k].value.diff(steps[i].sym) * g.of_step[i][w];
            v = tidy(v);
            if (v.is_zero() || is_a<numeric>(v)) {
                g.of_step[k][w] = v;
                continue;
            }
            const std::string name = "d" + steps[k].sym.get_name() + "_d" + wrt[w].get_name();
            step st{
                symbol_named(name, "\\partial " + steps[k].sym.get_TeX_name() + "/\\partial " + wrt[w].get_TeX_name()),
                v,
                "derivative of " + steps[k].sym.get_name() + " by " + wrt[w].get_name(),
                steps[k].role,
                steps[k].body,
                steps[k].row,
                steps[k].column};
            g.derivative_steps.push_back(st);
            g.of_step[k][w] = st.sym;
        }
    return g;
}

ex chain_derivative(const ex &v, const std::vector<step> &steps, const step_gradients &g,
                    const std::vector<symbol> &wrt, std::size_t j)
{
    ex d = v.diff(wrt[j]);
    for (std::size_t k = 0; k < steps.size(); ++k)
        if (!g.of_step[k][j].is_zero())
            d += v.diff(steps[k].sym) * g.of_step[k][j];
    return tidy(d);
}

process_jacobian process_jacobian_of(const derivation &d, const impact_solution &s, const std::vector<std::string> &wrt)
{
    process_jacobian j;
    j.wrt = jacobian_inputs(d.prob, wrt);
    j.steps = s.shared.steps;
    const step_gradients g = differentiate_steps(j.steps, j.wrt);
    j.derivative_steps = g.derivative_steps;
    for (const regime_case &c : s.cases) {
        sequence_jacobian q;
        q.sequence = c.name;
        q.conditions = c.process_conditions;
        const auto outs = outputs_of(d.prob, c);
        if (j.outputs.empty())
            for (const auto &o : outs)
                j.outputs.push_back(o.first);
        for (const auto &o : outs) {
            std::vector<ex> row;
            for (std::size_t w = 0; w < j.wrt.size(); ++w)
                row.push_back(chain_derivative(o.second, j.steps, g, j.wrt, w));
            q.entries.push_back(row);
        }
        j.sequences.push_back(q);
    }
    return j;
}

} // namespace impactgen
