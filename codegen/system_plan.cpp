// The code plan of a system (code_plan.hpp, rule system_sets): the problem specialised by the
// options, every candidate of its law (symbolic/system.hpp's system_candidates, in the order
// solve_system tries them) as the values of the header's outputs with its conditions, the
// state a failed call returns and the energy lost in the selected velocities.
#include "code_plan.hpp"

#include "names/escape.hpp"
#include "names/identifier.hpp"

#include <algorithm>
#include <functional>

namespace impactgen::codegen
{
using namespace GiNaC;

namespace
{

std::string label_suffix(const std::string &label)
{
    return label.size() == 1 ? label : "_" + names::mangle(label);
}

// The options a system does not take, each refused naming its option.
void refuse_system_options(const problem &p, const options &o)
{
    if (p.sequential && (o.jacobian || !o.wrt.empty()))
        throw option_error(o.jacobian ? option_error::jacobian : option_error::wrt,
                           "the Jacobian is not offered for sequential impacts (the chain's steps depend on the "
                           "inputs)");
    const std::string why = " is not offered for systems (give masses and inertia)";
    if (o.inverse_inertia)
        throw option_error(option_error::inverse_inertia, "the engine input convention" + why);
    if (o.inverse_mass)
        throw option_error(option_error::inverse_mass, "the engine input convention" + why);
    if (o.unit_normal)
        throw option_error(option_error::unit_normal,
                           "the unit-normal convention is not offered for systems (the normals are used as given)");
}

struct output_source {
    std::function<ex(const system_candidate &)> value;
    ex unchanged;
};

// The outputs in the header's order: per body of finite mass its velocity and spin after,
// per contact its normal and (with friction) tangential impulse, per joint and pivot its
// impulse, the energy lost.
void system_outputs(code_plan &cp, std::vector<output_source> &src)
{
    const problem &q = cp.prob;
    const auto &ax = q.axes;
    const int dim = q.dimension;
    system_code &sc = cp.system;
    auto add = [&](output_value::kind_t kind, std::size_t index, int c, const std::string &field,
                   const std::string &meaning, output_source s) {
        code_output of;
        of.kind = kind;
        of.index = index;
        of.component = c;
        of.field = field;
        of.meaning = meaning;
        of.base = cp.outputs.size();
        if (kind == output_value::velocity || kind == output_value::angular_velocity)
            sc.velocities.push_back(cp.outputs.size());
        else if (kind != output_value::energy_lost)
            sc.all_impulses.push_back(cp.outputs.size());
        cp.outputs.push_back(of);
        src.push_back(std::move(s));
    };
    for (std::size_t i = 0; i < q.bodies.size(); ++i) {
        const body &b = q.bodies[i];
        if (b.infinite_mass)
            continue;
        const std::string sub = label_suffix(b.label);
        for (int c = 0; c < dim; ++c)
            add(output_value::velocity, i, c, "v_" + ax[c] + sub,
                "velocity of the centre of mass of " + b.name + " after impact, " + ax[c],
                {[i, c](const system_candidate &k) { return k.velocity[i][c]; }, b.velocity[c]});
        if (!b.particle)
            for (int c = dim == 2 ? 2 : 0; c < 3; ++c)
                add(output_value::angular_velocity, i, c, "w_" + ax[c] + sub,
                    "angular velocity of " + b.name + " after impact, " + ax[c],
                    {[i, c](const system_candidate &k) { return k.angular_velocity[i][c]; }, b.angular_velocity[c]});
    }
    for (std::size_t k = 0; k < q.contacts.size(); ++k) {
        const contact_spec &ct = q.contacts[k];
        const std::string s = "_c" + std::to_string(k), who = "contacts[" + std::to_string(k) + "]";
        const std::string b1 = q.bodies[ct.body1].name, b2 = q.bodies[ct.body2].name;
        sc.impulses.push_back(cp.outputs.size());
        add(output_value::normal_impulse, k, 0, "normal_impulse" + s,
            "normal impulse of " + who + " >= 0 along its unit normal: on " + b2 + " along +n, on " + b1 + " along -n",
            {[k](const system_candidate &c) { return c.normal_impulse[k]; }, 0});
        if (!ct.rough && ct.friction().is_zero())
            continue;
        for (int c = 0; c < dim; ++c) {
            sc.impulses.push_back(cp.outputs.size());
            add(output_value::normal_impulse, k, c, "tangential_impulse_" + ax[c] + s,
                "tangential (friction) impulse of " + who + " on " + b2 + " (on " + b1 + " its opposite), world " +
                    ax[c],
                {[k, c](const system_candidate &x) { return x.tangential_impulse[k][c]; }, 0});
        }
    }
    for (std::size_t j = 0; j < q.joints.size(); ++j)
        for (int c = 0; c < dim; ++c)
            add(output_value::pivot_impulse, j, c, "joint_impulse_" + ax[c] + "_j" + std::to_string(j),
                "impulse of joints[" + std::to_string(j) + "] on " + q.bodies[q.joints[j].body2].name + " (on " +
                    q.bodies[q.joints[j].body1].name + " its opposite), " + ax[c],
                {[j, c](const system_candidate &x) { return x.joint_impulses[j][c]; }, 0});
    for (std::size_t j = 0; j < q.pivots.size(); ++j)
        for (int c = 0; c < dim; ++c)
            add(output_value::pivot_impulse, j, c, "R_" + ax[c] + label_suffix(q.bodies[q.pivots[j].body].label),
                "impulse of the pivot on " + q.bodies[q.pivots[j].body].name + ", " + ax[c],
                {[j, c](const system_candidate &x) { return x.pivot_impulses[j][c]; }, 0});
    code_output e;
    e.kind = output_value::energy_lost;
    e.field = "energy_lost";
    e.meaning = "kinetic energy lost, T - T' (bodies of finite mass)";
    e.base = cp.outputs.size();
    cp.outputs.push_back(e);
    src.push_back({nullptr, 0});
}

// The energy lost in the inputs and the selected velocities (symbols sel).
void energy_lost(code_plan &cp)
{
    const problem &q = cp.prob;
    system_code &sc = cp.system;
    std::vector<vec3> v, w, v2, w2;
    for (const body &b : q.bodies) {
        v.push_back(b.velocity);
        w.push_back(b.angular_velocity);
    }
    v2 = v;
    w2 = w;
    for (std::size_t k = 0; k < cp.outputs.size(); ++k) {
        const code_output &of = cp.outputs[k];
        if (of.kind == output_value::velocity)
            v2[of.index][static_cast<std::size_t>(of.component)] = sc.sel[k];
        else if (of.kind == output_value::angular_velocity)
            w2[of.index][static_cast<std::size_t>(of.component)] = sc.sel[k];
    }
    sc.energy_lost = system_kinetic_energy(q, v, w) - system_kinetic_energy(q, v2, w2);
}

// The checks of the inputs: each e in [0, 1], each mu >= 0, masses and planar inertia > 0.
void system_checks(code_plan &cp)
{
    const problem &q = cp.prob;
    system_code &sc = cp.system;
    sc.checks.push_back({q.restitution, "invalid_restitution"});
    for (std::size_t k = 0; k < q.contacts.size(); ++k) {
        if (q.contacts[k].own_restitution)
            sc.checks.push_back({q.contacts[k].restitution, "invalid_restitution"});
        if (!q.contacts[k].friction().is_zero())
            sc.checks.push_back({q.contacts[k].friction(), "invalid_friction"});
    }
    for (const body &b : q.bodies) {
        if (b.infinite_mass)
            continue;
        sc.checks.push_back({b.mass, "invalid_mass"});
        if (!b.particle && q.dimension == 2)
            sc.checks.push_back({b.inertia[2][2], "invalid_inertia"});
        if (!b.particle && q.dimension == 3)
            for (int r = 0; r < 3; ++r)
                sc.checks.push_back({b.inertia[r][r], "invalid_inertia"});
    }
}

// The Jacobian of the velocities after impact by the inputs named (every input when none is),
// per set: each set's closed form differentiated exactly.
void system_jacobian(code_plan &cp, const std::vector<std::string> &wrt)
{
    const system_code &sc = cp.system;
    candidates_jacobian &cj = cp.jacobian;
    cj.on = true;
    cj.wrt = jacobian_inputs(cp.inputs, wrt);
    cj.rows = sc.velocities;
    for (const system_code_set &s : sc.sets) {
        candidate_jacobian cand;
        cand.same_as = cj.candidates.size();
        for (std::size_t j : sc.velocities) {
            std::vector<ex> row;
            for (const symbol &x : cj.wrt)
                row.push_back(normal(s.values[j].diff(x)));
            cand.entries.push_back(row);
        }
        cj.candidates.push_back(std::move(cand));
    }
}

// Sequential impacts with friction are refused naming the contact's key (the problem
// specialised: a coefficient --set to 0 is frictionless).
void refuse_sequential_friction(const problem &q)
{
    for (std::size_t k = 0; k < q.contacts.size(); ++k)
        if (q.contacts[k].rough || !q.contacts[k].friction().is_zero())
            throw input_error((q.source.empty() ? std::string() : names::display_text(q.source) + ": ") + "contacts[" +
                              std::to_string(k) +
                              "].friction: sequential impacts are generated for frictionless contacts only ('impactgen "
                              "solve' follows the chain with friction)");
}

// The chain of sequential impacts: the velocity outputs become the state symbols, and per
// contact its single-contact impact in that state (the acting candidate: smooth).
void sequence_plan(code_plan &cp, const std::vector<output_source> &src)
{
    system_code &sc = cp.system;
    sc.sequential = true;
    problem s = cp.prob;
    sc.sequence.state.assign(cp.outputs.size(), symbol("state_unused"));
    for (std::size_t j : sc.velocities) {
        const code_output &of = cp.outputs[j];
        const symbol x("state_" + of.field);
        sc.sequence.state[j] = x;
        vec3 &v = of.kind == output_value::velocity ? s.bodies[of.index].velocity : s.bodies[of.index].angular_velocity;
        v[static_cast<std::size_t>(of.component)] = x;
    }
    const system_delassus del = system_delassus_of(s);
    for (std::size_t i = 0; i < s.contacts.size(); ++i) {
        const auto at = std::find(del.rows.begin(), del.rows.end(), "n" + std::to_string(i)) - del.rows.begin();
        sc.sequence.speeds.push_back(del.u[static_cast<std::size_t>(at)]);
        system_code_set st;
        st.name = "{" + std::to_string(i) + " smooth}";
        for (const system_candidate &c : system_step_candidates(s, i)) {
            if (c.regimes[i] != contact_regime::smooth)
                continue;
            st.name = c.name();
            for (const output_source &os : src)
                st.values.push_back(os.value ? os.value(c) : ex(0));
            for (const system_condition &k : c.conditions)
                st.conditions.push_back({k.value, k.velocity, k.contact, k.meaning, k.value.is_zero(), k.strict});
            break;
        }
        sc.sequence.steps.push_back(st);
    }
    sc.sets = sc.sequence.steps;
}

} // namespace

code_plan system_code_plan(const problem &p, const options &o)
{
    refuse_system_options(p, o);
    code_plan cp;
    cp.rule = selection_rule::system_sets;
    cp.prob = specialise(p, o);
    const problem &q = cp.prob;
    cp.base.prob = q;
    order_plan_inputs(cp.base, o);
    cp.inputs = cp.base.inputs;
    cp.input_meaning = cp.base.input_meaning;
    std::vector<output_source> src;
    system_outputs(cp, src);
    system_code &sc = cp.system;
    for (std::size_t k = 0; k < cp.outputs.size(); ++k) {
        sc.unchanged.push_back(src[k].unchanged);
        sc.sel.push_back(symbol("sel_" + cp.outputs[k].field));
        cp.base_index.push_back(k);
    }
    const system_delassus del = system_delassus_of(q);
    sc.speeds = del.u;
    sc.redundant_joints = del.redundant_joints;
    for (std::size_t i = 0; i < q.contacts.size(); ++i) {
        const auto at = std::find(del.rows.begin(), del.rows.end(), "n" + std::to_string(i)) - del.rows.begin();
        const ex w = del.W[static_cast<std::size_t>(at)][static_cast<std::size_t>(at)];
        sc.unit_mass.push_back(w.is_zero() ? ex(0) : normal(1 / w));
    }
    if (q.sequential) {
        refuse_sequential_friction(q);
        sequence_plan(cp, src);
    }
    for (const system_candidate &c : q.sequential ? std::vector<system_candidate>() : system_candidates(q)) {
        system_code_set s;
        s.name = c.name();
        for (const output_source &os : src)
            s.values.push_back(os.value ? os.value(c) : ex(0));
        for (const system_condition &k : c.conditions)
            s.conditions.push_back({k.value, k.velocity, k.contact, k.meaning, k.value.is_zero(), k.strict});
        for (std::size_t i = 0; i < c.regimes.size(); ++i) {
            if (c.regimes[i] != contact_regime::stick || !q.contacts[i].rough)
                continue;
            std::pair<std::size_t, std::vector<std::size_t>> rs;
            for (std::size_t k = 0; k < cp.outputs.size(); ++k)
                if (cp.outputs[k].kind == output_value::normal_impulse && cp.outputs[k].index == i) {
                    if (cp.outputs[k].field.rfind("normal_impulse", 0) == 0)
                        rs.first = k;
                    else
                        rs.second.push_back(k);
                }
            s.rough_sticks.push_back(rs);
        }
        sc.sets.push_back(std::move(s));
    }
    energy_lost(cp);
    system_checks(cp);
    if (o.jacobian || !o.wrt.empty())
        system_jacobian(cp, o.wrt);
    return cp;
}

} // namespace impactgen::codegen
