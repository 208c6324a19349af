#include "friction_jacobian.hpp"

#include "process_jacobian.hpp"

#include <map>

namespace impactgen
{
using namespace GiNaC;

namespace
{

using derivatives = std::map<ex, ex, ex_is_less>; // symbol (input, step, c or s) -> its derivative

// The total derivative of e along one direction: every symbol of e whose derivative is known,
// by the chain rule (the others are held fixed).
ex total(const ex &e, const derivatives &known)
{
    exset syms;
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it))
            syms.insert(*it);
    ex v = 0;
    for (const ex &x : syms) {
        const auto it = known.find(x);
        if (it != known.end() && !it->second.is_zero())
            v += e.diff(ex_to<symbol>(x)) * it->second;
    }
    return tidy(v);
}

// Differentiates steps[from, to) along the direction `known` (extended with each step's
// derivative); a derivative that is not a number becomes a step named d<step>_d<by>.
void differentiate_steps(const std::vector<step> &steps, std::size_t from, std::size_t to, const std::string &by,
                         const std::string &by_tex, derivatives &known, std::vector<step> &out)
{
    for (std::size_t k = from; k < to; ++k) {
        const step &st = steps[k];
        const ex v = total(st.value, known);
        if (v.is_zero() || is_a<numeric>(v) || is_a<symbol>(v)) { // (a symbol: another step's, as it is)
            known[st.sym] = v;
            continue;
        }
        step d{symbol_named("d" + st.sym.get_name() + "_d" + by,
                            "\\partial " + st.sym.get_TeX_name() + "/\\partial " + by_tex),
               v,
               "derivative of " + st.sym.get_name() + " by " + by,
               st.role,
               st.body,
               st.row,
               st.column};
        out.push_back(d);
        known[st.sym] = d.sym;
    }
}

// The Jacobian of one candidate: its own steps differentiated along each input (and, for the
// slide without a closed form, along theta), then its outputs.
regime_jacobian candidate_jacobian(const regime_case &c, std::size_t shared, const std::vector<symbol> &wrt,
                                   const std::vector<derivatives> &shared_known, const candidate_outputs &outputs_of)
{
    regime_jacobian r;
    r.name = c.name;
    r.kind = c.kind;
    r.sign = c.sign;
    r.conditions = c.conditions;
    const std::vector<step> &steps = c.sol.steps;
    std::vector<derivatives> known = shared_known;
    for (std::size_t w = 0; w < wrt.size(); ++w)
        differentiate_steps(steps, shared, steps.size(), wrt[w].get_name(), wrt[w].get_TeX_name(), known[w],
                            r.derivative_steps);
    std::vector<ex> angle_rate(wrt.size(), 0); // dtheta/dx_j
    derivatives along_angle;
    if (c.needs_angle) {
        r.through_angle = true;
        r.dir_c = c.dir_c;
        r.dir_s = c.dir_s;
        along_angle[c.dir_c] = -c.dir_s; // d cos(theta) = -sin(theta) dtheta
        along_angle[c.dir_s] = c.dir_c;
        differentiate_steps(steps, shared, steps.size(), "theta", "\\theta", along_angle, r.derivative_steps);
        const step slope{symbol_named("dg_dtheta", "\\partial g/\\partial \\theta"),
                         total(c.angle_equation, along_angle),
                         "derivative of the angle equation g by the sliding angle (nonzero at a simple root)"};
        r.derivative_steps.push_back(slope);
        r.angle_slope = slope.sym;
        for (std::size_t w = 0; w < wrt.size(); ++w) {
            const ex gx = total(c.angle_equation, known[w]);
            if (gx.is_zero())
                continue;
            const step rate{
                symbol_named("dtheta_d" + wrt[w].get_name(), "\\partial \\theta/\\partial " + wrt[w].get_TeX_name()),
                tidy(-gx / slope.sym),
                "derivative of the sliding angle by " + wrt[w].get_name() +
                    " (implicit function theorem: -(dg/dx)/(dg/dtheta))"};
            r.derivative_steps.push_back(rate);
            angle_rate[w] = rate.sym;
        }
    }
    for (const auto &o : outputs_of(c)) {
        std::vector<ex> row;
        for (std::size_t w = 0; w < wrt.size(); ++w) {
            ex v = total(o.second, known[w]);
            if (c.needs_angle && !angle_rate[w].is_zero())
                v = tidy(v + total(o.second, along_angle) * angle_rate[w]);
            row.push_back(v);
        }
        r.entries.push_back(row);
    }
    return r;
}

} // namespace

std::vector<std::pair<std::string, ex>> friction_outputs(const problem &p, const regime_case &c)
{
    std::vector<std::pair<std::string, ex>> out{{"normal_impulse", c.sol.normal_impulse}};
    if (p.dimension == 2)
        out.push_back({"tangential_impulse", c.tangential_scalar});
    else
        for (int a = 0; a < 3; ++a)
            out.push_back({"tangential_impulse_" + p.axes[static_cast<std::size_t>(a)], c.tangential_impulse[a]});
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        if (p.bodies[b].infinite_mass)
            continue;
        for (int a = 0; a < p.dimension; ++a)
            out.push_back(
                {"v'_" + p.axes[static_cast<std::size_t>(a)] + "," + p.bodies[b].name, c.sol.after[b].velocity[a]});
        if (p.bodies[b].particle)
            continue;
        for (int a = p.dimension == 2 ? 2 : 0; a < 3; ++a)
            out.push_back({"w'_" + p.axes[static_cast<std::size_t>(a)] + "," + p.bodies[b].name,
                           c.sol.after[b].angular_velocity[a]});
    }
    return out;
}

friction_jacobian friction_jacobian_of(const impact_solution &s, const std::vector<symbol> &wrt,
                                       const candidate_outputs &outputs_of)
{
    friction_jacobian j;
    j.wrt = wrt;
    j.steps = s.shared.steps;
    std::vector<derivatives> known(j.wrt.size());
    for (std::size_t w = 0; w < j.wrt.size(); ++w) {
        known[w][j.wrt[w]] = 1;
        differentiate_steps(j.steps, 0, j.steps.size(), j.wrt[w].get_name(), j.wrt[w].get_TeX_name(), known[w],
                            j.derivative_steps);
    }
    for (const regime_case &c : s.cases) {
        if (j.outputs.empty())
            for (const auto &o : outputs_of(c))
                j.outputs.push_back(o.first);
        j.regimes.push_back(candidate_jacobian(c, j.steps.size(), j.wrt, known, outputs_of));
    }
    return j;
}

friction_jacobian friction_jacobian_of(const derivation &d, const impact_solution &s,
                                       const std::vector<std::string> &wrt)
{
    const problem &p = d.prob;
    return friction_jacobian_of(s, jacobian_inputs(p, wrt),
                                [&p](const regime_case &c) { return friction_outputs(p, c); });
}

} // namespace impactgen
