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

process_jacobian process_jacobian_of(const derivation &d, const impact_solution &s, const std::vector<std::string> &wrt)
{
    process_jacobian j;
    j.wrt = jacobian_inputs(d.prob, wrt);
    j.steps = s.shared.steps;
    const std::size_t nw = j.wrt.size();
    // ds_k/dx_j by the chain rule through the earlier steps; a nonzero one becomes a step symbol.
    std::vector<std::vector<ex>> ds(j.steps.size(), std::vector<ex>(nw, 0));
    for (std::size_t k = 0; k < j.steps.size(); ++k)
        for (std::size_t w = 0; w < nw; ++w) {
            ex v = j.steps[k].value.diff(j.wrt[w]);
            for (std::size_t i = 0; i < k; ++i)
                v += j.steps[k].value.diff(j.steps[i].sym) * ds[i][w];
            v = tidy(v);
            if (v.is_zero() || is_a<numeric>(v)) {
                ds[k][w] = v;
                continue;
            }
            const std::string name = "d" + j.steps[k].sym.get_name() + "_d" + j.wrt[w].get_name();
            step st{symbol_named(name, "\\partial " + j.steps[k].sym.get_TeX_name() + "/\\partial " +
                                           j.wrt[w].get_TeX_name()),
                    v,
                    "derivative of " + j.steps[k].sym.get_name() + " by " + j.wrt[w].get_name(),
                    j.steps[k].role,
                    j.steps[k].body,
                    j.steps[k].row,
                    j.steps[k].column};
            j.derivative_steps.push_back(st);
            ds[k][w] = st.sym;
        }
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
            for (std::size_t w = 0; w < nw; ++w) {
                ex v = o.second.diff(j.wrt[w]);
                for (std::size_t k = 0; k < j.steps.size(); ++k)
                    if (!ds[k][w].is_zero())
                        v += o.second.diff(j.steps[k].sym) * ds[k][w];
                row.push_back(tidy(v));
            }
            q.entries.push_back(row);
        }
        j.sequences.push_back(q);
    }
    return j;
}

} // namespace impactgen
