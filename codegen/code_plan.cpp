// The code plan (code_plan.hpp): the smooth plan of the problem, and with a law of several
// candidates its derivation, candidates and selection rule, the inputs and outputs in the
// header's order.
#include "code_plan.hpp"

#include "names/escape.hpp"
#include "symbolic/friction_jacobian.hpp"
#include "symbolic/named_classes.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <variant>

namespace impactgen::codegen
{
using namespace GiNaC;

void collect_symbols(const ex &e, exset &out)
{
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it))
            out.insert(*it);
}

std::vector<std::size_t> candidate_rows(const code_plan &cp)
{
    std::vector<std::size_t> rows;
    for (std::size_t k = 0; k < cp.outputs.size() && !cp.candidates.cases.empty(); ++k) {
        const code_output &of = cp.outputs[k];
        if (of.tangential || of.kind == output_value::velocity || of.kind == output_value::angular_velocity ||
            of.kind == output_value::normal_impulse)
            rows.push_back(k);
    }
    return rows;
}

ex candidate_output(const code_plan &cp, std::size_t k, const regime_case &c)
{
    const code_output &of = cp.outputs[k];
    const auto a = static_cast<std::size_t>(of.tangential ? of.axis : of.component);
    return of.tangential                               ? c.tangential_impulse[a]
           : of.kind == output_value::velocity         ? c.sol.after[of.index].velocity[a]
           : of.kind == output_value::angular_velocity ? c.sol.after[of.index].angular_velocity[a]
                                                       : c.sol.normal_impulse;
}

namespace
{

// The options a law with candidates cannot honour.
void refuse_options(const options &o)
{
    if (o.inverse_inertia)
        throw option_error(
            option_error::inverse_inertia,
            "the engine input convention is not offered for problems with friction (give masses and inertia)");
    if (o.inverse_mass)
        throw option_error(option_error::inverse_mass,
                           "the engine input convention is not offered for problems with friction (give masses)");
}

// The inputs: the parameters in the order given, else the smooth order with the
// symbols of mu right after those of e.
void order_inputs(code_plan &cp, const options &o, const std::set<std::string> &friction_only)
{
    const problem &q = cp.prob;
    const plan &pl = cp.base;
    std::map<std::string, symbol> by_name;
    for (const symbol &s : q.parameters())
        by_name.emplace(s.get_name(), s);
    const std::string mu_meaning = is_a<symbol>(q.contact().friction())
                                       ? "coefficient of friction mu >= 0 (Coulomb: |P_t| <= mu P_n)"
                                       : "appears in the coefficient of friction mu";
    auto smooth_meaning = [&](const symbol &s) -> std::string {
        for (std::size_t i = 0; i < pl.inputs.size(); ++i)
            if (pl.inputs[i].is_equal(s))
                return pl.input_meaning[i];
        return mu_meaning;
    };
    auto add_friction_only = [&]() {
        for (const std::string &nm : friction_only) {
            cp.inputs.push_back(by_name.at(nm));
            cp.input_meaning.push_back(mu_meaning);
        }
    };
    if (o.params_given) {
        for (const std::string &nm : o.params) {
            const symbol &s = by_name.at(nm);
            cp.inputs.push_back(s);
            cp.input_meaning.push_back(smooth_meaning(s));
        }
        return;
    }
    std::size_t at = 0;
    exset esyms;
    collect_symbols(q.restitution, esyms);
    for (std::size_t i = 0; i < pl.inputs.size(); ++i)
        if (esyms.count(pl.inputs[i]))
            at = i + 1;
    for (std::size_t i = 0; i < pl.inputs.size(); ++i) {
        if (i == at)
            add_friction_only();
        cp.inputs.push_back(pl.inputs[i]);
        cp.input_meaning.push_back(pl.input_meaning[i]);
    }
    if (at >= pl.inputs.size())
        add_friction_only();
}

// The outputs: the smooth ones, with a tangential impulse the world components of the
// tangential impulse right after the normal impulse.
void order_outputs(code_plan &cp)
{
    const problem &q = cp.prob;
    const bool candidates = cp.rule != selection_rule::none;
    const std::string &b1 = q.bodies[q.contact().body1].name, &b2 = q.bodies[q.contact().body2].name;
    for (std::size_t k = 0; k < cp.base.outputs.size(); ++k) {
        code_output of;
        static_cast<output_value &>(of) = cp.base.outputs[k];
        of.base = k;
        if (candidates && of.kind == output_value::normal_impulse)
            of.meaning =
                "normal impulse P.n >= 0 along the unit normal: on " + b2 + " along +n, on " + b1 + " along -n";
        if (candidates && of.kind == output_value::approach_velocity)
            of.meaning = "(v_B - v_A).n before impact along the unit normal (< 0)";
        cp.base_index.push_back(cp.outputs.size());
        cp.outputs.push_back(of);
        if (!candidates || of.kind != output_value::normal_impulse)
            continue;
        for (int a = 0; a < q.dimension; ++a) {
            const std::string &ax = q.axes[static_cast<std::size_t>(a)];
            code_output tf;
            tf.field = "tangential_impulse_" + ax;
            tf.meaning =
                "tangential (friction) impulse P - (P.n) n on " + b2 + " (on " + b1 + " its opposite), world " + ax;
            tf.kind = output_value::normal_impulse;
            tf.tangential = true;
            tf.axis = a;
            cp.tangential.push_back(cp.outputs.size());
            cp.outputs.push_back(tf);
        }
    }
}

// --jacobian with friction: the inputs named (every input when none is), each candidate's
// velocities and impulses differentiated exactly. A normal given as inputs in 3-D has its tangent
// basis computed at run time, whose derivatives the closed form does not hold: its components are
// left out of the default and refused by name.
void plan_candidates_jacobian(code_plan &cp, const std::vector<std::string> &wrt)
{
    candidates_jacobian &cj = cp.jacobian;
    cj.on = true;
    exset nsyms; // a normal given as inputs, its tangent basis computed at run time
    if (!cp.deriv.tangent_basis_symbols.empty())
        for (const ex &c : cp.prob.contact().normal)
            collect_symbols(c, nsyms);
    std::vector<symbol> inputs; // by default not the normal's
    for (const symbol &x : cp.inputs)
        if (!wrt.empty() || !nsyms.count(x))
            inputs.push_back(x);
    cj.wrt = jacobian_inputs(inputs, wrt);
    for (const symbol &x : cj.wrt)
        if (nsyms.count(x))
            throw option_error(option_error::wrt,
                               x.get_name() + " is a component of the normal, whose tangent basis the generated code "
                                              "computes at run time: the Jacobian is offered by the other inputs");
    cj.rows = candidate_rows(cp);
    const friction_jacobian jac = friction_jacobian_of(cp.candidates, cj.wrt, [&cp, &cj](const regime_case &c) {
        std::vector<std::pair<std::string, ex>> out;
        for (std::size_t k : cj.rows)
            out.push_back({cp.outputs[k].field, candidate_output(cp, k, c)});
        return out;
    });
    for (std::size_t k = 0; k < jac.regimes.size(); ++k) { // each its own program: the candidate's steps first
        const regime_case &c = cp.candidates.cases[k];
        candidate_jacobian cand;
        cand.steps = c.sol.steps;
        cand.steps.insert(cand.steps.end(), jac.derivative_steps.begin(), jac.derivative_steps.end());
        cand.steps.insert(cand.steps.end(), jac.regimes[k].derivative_steps.begin(),
                          jac.regimes[k].derivative_steps.end());
        cand.entries = jac.regimes[k].entries;
        cand.same_as = k;
        if (c.needs_angle)
            cand.angle = {c.dir_c, c.dir_s};
        cj.candidates.push_back(std::move(cand));
    }
}

// A law with candidates: the problem specialised with its law, the smooth plan of the same
// problem without it (the inputs in the smooth headers' order with their meanings, the
// outputs, the vector views, the state a failed call returns), the candidates.
code_plan candidates_plan(const problem &p, const options &o)
{
    refuse_options(o);
    code_plan cp;
    problem p0 = p;
    // --params mu with a numeric coefficient: mu becomes the parameter.
    if (o.params_given && std::find(o.params.begin(), o.params.end(), "mu") != o.params.end() &&
        is_a<numeric>(p0.contact().friction())) {
        bool taken = false;
        for (const symbol &s : p0.parameters())
            taken = taken || s.get_name() == "mu";
        if (!taken)
            p0.contact().set_friction(symbol_named("mu", "\\mu"));
    }
    cp.prob = specialise(p0, o);
    const problem &q = cp.prob;
    if (q.contact().friction().is_zero()) // --params or --set made mu 0
        throw input_error(
            (q.source.empty() ? std::string("contact") : names::display_text(q.source) + ": contact") +
            ".friction: the coefficient of friction is 0: generate the smooth header (codegen::generate)");
    problem sq = q;
    sq.contact().set_friction(0);
    std::set<std::string> rest;
    for (const symbol &s : sq.parameters())
        rest.insert(s.get_name());
    exset fsyms;
    collect_symbols(q.contact().friction(), fsyms);
    std::set<std::string> friction_only;
    for (const ex &s : fsyms)
        if (!rest.count(ex_to<symbol>(s).get_name()))
            friction_only.insert(ex_to<symbol>(s).get_name());
    options so = o;
    so.set.clear();
    so.params.clear();
    so.jacobian = false; // (the Jacobian is planned below: the candidates' or the process's)
    so.wrt.clear();
    for (const std::string &nm : o.params)
        if (!friction_only.count(nm))
            so.params.push_back(nm);
    cp.base = make_plan(sq, so);
    derive_options how;
    how.unit_normal = o.unit_normal;
    how.runtime_tangent_basis = true;
    cp.deriv = derive(q, how);
    if (follows_process(q.contact().law_of_restitution)) {
        cp.candidates = process_candidates(cp.deriv);
        cp.rule = selection_rule::process;
        order_inputs(cp, o, friction_only);
        order_outputs(cp);
        if (o.jacobian || !o.wrt.empty())
            process_jacobian_plan(cp, o.wrt);
        return cp;
    }
    cp.candidates = solve_friction(cp.deriv);
    cp.rule = selection_rule::first_that_holds;
    for (std::size_t i = 0; i < cp.candidates.cases.size(); ++i)
        if (cp.candidates.cases[i].needs_angle) {
            cp.angle = static_cast<int>(i);
            cp.rule = selection_rule::sliding_angle;
        }
    order_inputs(cp, o, friction_only);
    order_outputs(cp);
    if (o.jacobian || !o.wrt.empty())
        plan_candidates_jacobian(cp, o.wrt);
    return cp;
}

} // namespace

code_plan law_code_plan(const coulomb &, const problem &p, const options &o)
{
    return candidates_plan(p, o);
}

code_plan law_code_plan(const frictionless &, const problem &p, const options &o)
{
    code_plan cp;
    cp.base = make_plan(p, o);
    cp.prob = cp.base.prob;
    cp.inputs = cp.base.inputs;
    cp.input_meaning = cp.base.input_meaning;
    order_outputs(cp);
    return cp;
}

code_plan make_code_plan(const problem &p, const options &o)
{
    if (p.is_system())
        return system_code_plan(p, o);
    contact_law law = p.contact().law;
    try {
        options so = o;
        so.params_given = false; // only --set can make mu 0
        so.params.clear();
        law = specialise(p, so).contact().law;
    } catch (const std::exception &) {
        // the options do not fit: the plan of the problem's own law reports it
    }
    return std::visit([&](const auto &l) { return law_code_plan(l, p, o); }, law);
}

} // namespace impactgen::codegen
