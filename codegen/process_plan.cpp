// The candidates of Routh's process for the code plan (selection rule `process`): the phase
// sequences of symbolic/routh.hpp with the process's inputs written in the shared steps of
// the friction solution (K = K_1 + K_2 and u in world axes), so that the one writer emits
// them as it does the Newton candidates: every sequence's closed form and conditions in one
// straight-line program, the first whose conditions hold selected without a branch.
#include "code_plan.hpp"

#include "names/escape.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/process_jacobian.hpp"
#include "symbolic/routh.hpp"

#include <array>

namespace impactgen::codegen
{
using namespace GiNaC;

namespace
{

// The process's inputs from the friction solution's shared steps: K = K_1 + K_2 and u in world
// axes (steps), read in the contact frame (e_t, n).
process_inputs contact_inputs(const derivation &d, const impact_solution &f)
{
    const problem &p = d.prob;
    mat3 K = zero_mat();
    vec3 u = zero_vec();
    ex un;
    for (const step &st : f.shared.steps) {
        if (st.role == step_role::contact_response && st.row >= 0 && st.column >= 0)
            K[static_cast<std::size_t>(st.row)][static_cast<std::size_t>(st.column)] =
                K[static_cast<std::size_t>(st.column)][static_cast<std::size_t>(st.row)] = st.sym;
        if (st.role == step_role::relative_velocity && st.row >= 0 && st.column < 0)
            u[static_cast<std::size_t>(st.row)] = st.sym;
        if (st.role == step_role::approach_velocity)
            un = st.sym;
    }
    // u's components as solve_friction has them: a step, or (atomic) the value itself; the
    // normal axis's is the approach velocity's step.
    std::array<bool, 3> found{false, false, false};
    for (const step &st : f.shared.steps)
        if (st.role == step_role::relative_velocity && st.row >= 0 && st.column < 0)
            found[static_cast<std::size_t>(st.row)] = true;
    for (std::size_t a = 0; a < static_cast<std::size_t>(p.dimension); ++a)
        if (!found[a])
            u[a] = d.n_hat[a].is_equal(1) && !un.is_zero() ? un : tidy(d.vB[a] - d.vA[a]);
    const vec3 &n = d.n_hat, &t = d.t_dir;
    process_inputs in;
    in.Ktt = dot(t, mul(K, t));
    in.Ktn = dot(t, mul(K, n));
    in.Knn = dot(n, mul(K, n));
    in.ut = dot(u, t);
    in.un = un.is_zero() ? dot(u, n) : un;
    in.mu = p.contact().friction();
    in.e = p.restitution;
    in.law = p.contact().law_of_restitution;
    return in;
}

} // namespace

impact_solution process_candidates(const derivation &d)
{
    const problem &p = d.prob;
    impact_solution f = solve_friction(d); // its shared steps: K and u in world axes
    f.cases.clear();
    f.no_stick.clear();
    f.law = p.contact().law_of_restitution;
    const vec3 &n = d.n_hat, &t = d.t_dir;
    const process_inputs in = contact_inputs(d, f);
    const std::string where =
        (p.source.empty() ? std::string("contact") : names::display_text(p.source) + ": contact") + ".friction";
    std::vector<process_sequence> sequences = routh_process(in, where);
    if (!in.ut.is_zero() && !is_constant(in.ut)) {
        // The walk takes a u_t in symbols to slip (u_t > 0 or < 0); a contact that does not slip
        // before impact (u_t = 0 at run time: u_t >= 0 and -u_t >= 0) starts as the walk without
        // slip says.
        process_inputs still = in;
        still.ut = 0;
        for (process_sequence q : routh_process(still, where)) {
            q.conditions.insert(q.conditions.begin(),
                                {{in.ut, false, process_test::initial_slip, "no initial slip: u_t >= 0"},
                                 {-in.ut, false, process_test::initial_slip, "no initial slip: -u_t >= 0"}});
            sequences.push_back(q);
        }
    }
    for (const process_sequence &q : sequences) {
        if (q.wedges)
            continue;
        regime_case c;
        c.kind = regime::slide; // the writer's stick candidate is Newton's; the regime is the last phase
        c.sign = 0;
        c.process = q.phases;
        c.process_conditions = q.conditions;
        c.name = "process:";
        for (const process_phase &ph : q.phases)
            c.name += std::string(c.name.size() > 8 ? ", " : " ") + phase_name(ph.kind);
        c.sol.steps = f.shared.steps;
        c.sol.normal_impulse = q.normal_impulse;
        c.tangential_scalar = q.tangential_impulse;
        for (std::size_t a = 0; a < 3; ++a) {
            c.impulse[a] = q.normal_impulse * n[a] + q.tangential_impulse * t[a];
            c.tangential_impulse[a] = q.tangential_impulse * t[a];
            c.direction[a] = 0;
        }
        c.sliding_speed = q.tangential_velocity;
        for (const process_condition &pc : q.conditions)
            c.conditions.push_back({pc.value, pc.strict, pc.meaning, condition_kind::pushes});
        f.cases.push_back(c);
    }
    if (f.cases.empty())
        throw input_error(where + ": the contact wedges for every value (no finite impulse ends the compression)");
    return f;
}

void process_jacobian_plan(code_plan &cp, const std::vector<std::string> &wrt)
{
    const derivation &d = cp.deriv;
    for (const ex &x : d.n_hat)
        if (!is_constant(x))
            throw option_error(option_error::jacobian, "a normal given as inputs is not differentiated under a "
                                                       "restitution law followed through the impact");
    candidates_jacobian &cj = cp.jacobian;
    cj.on = true;
    cj.wrt = jacobian_inputs(cp.inputs, wrt);
    impact_solution &f = cp.candidates;
    const process_inputs in = contact_inputs(d, f);
    cj.process = candidates_jacobian::rounding{sqrt(in.ut * in.ut + in.un * in.un), (1 + in.mu) * (in.Ktt + in.Knn)};
    cj.steps = f.shared.steps;
    const step_gradients g = differentiate_steps(cj.steps, cj.wrt);
    cj.rows = candidate_rows(cp);
    const std::array<contact_side, 2> sides = process_sides(d.prob);
    for (std::size_t i = 0; i < f.cases.size(); ++i) {
        regime_case c = f.cases[i];
        apply_impulse(d, sides, c, false);
        candidate_jacobian cand;
        for (std::size_t k : cj.rows) {
            const ex v = candidate_output(cp, k, c);
            std::vector<ex> row;
            for (std::size_t j = 0; j < cj.wrt.size(); ++j)
                row.push_back(chain_derivative(v, cj.steps, g, cj.wrt, j));
            cand.entries.push_back(row);
        }
        cand.same_as = i;
        for (std::size_t k = 0; k < i && cand.same_as == i; ++k)
            if (f.cases[k].sol.normal_impulse.is_equal(c.sol.normal_impulse) &&
                f.cases[k].tangential_scalar.is_equal(c.tangential_scalar))
                cand.same_as = k;
        cj.candidates.push_back(std::move(cand));
    }
    cj.steps.insert(cj.steps.end(), g.derivative_steps.begin(), g.derivative_steps.end());
}

} // namespace impactgen::codegen
