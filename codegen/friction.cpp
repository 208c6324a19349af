// Code generation for impacts with Coulomb friction (friction.hpp).
//
// The emitted function, in order:
//   1. stage A, one straight-line program (CSE over everything in it): the shared steps
//      (K = K_1 + K_2 as the sum of the bodies' responses 1/m + (I^-1 (r x e)) x r, u, u_n),
//      the validity checks of the smooth headers (restitution, masses, inertia, normal,
//      approach, then det K > 0 for the stick candidate: status singular), every
//      closed-form candidate (stick; planar: slides along +e_t and -e_t; 3-D isotropic: the
//      slide along u_t) with its impulse and the values of its conditions, and for a 3-D
//      slide without closed form the five coefficients of its angle equation
//        g(theta) = a0 + a1 cos theta + b1 sin theta + a2 cos 2 theta + b2 sin 2 theta,
//      derived here from symbolic/friction.hpp's g(c, s) (c = cos theta, s = sin theta;
//      the coefficients of c^i s^j by differentiation at 0, then c^2 = (1 + cos 2 theta)/2,
//      s^2 = (1 - cos 2 theta)/2, c s = sin 2 theta / 2), and those of lambda D, the
//      sliding speed times the normal response, of the same form: the filter with which
//      the root finder leaves out the arcs where no slide can hold (lambda D < 0);
//   2. mu = 0 (unless mu is a constant): the frictionless impact (stage S), regime smooth;
//   3. else the regime selection: each candidate holds when its conditions do (as
//      derived: > 0 or >= 0); the closed forms are selected without a branch (the first
//      that holds); the roots of g (detail::trig2_roots, codegen/runtime/friction_runtime.hpp) each
//      give a slide candidate (stage B, a program in cos theta and sin theta) with its
//      conditions; exactly one candidate holding is the answer, none is no_solution,
//      several ambiguous -- but at the stick/slide boundary within rounding, where the
//      stick candidate and a slide are one solution (impulses equal to within eps^(2/3)
//      relative): there the answer is stick when nothing else holds; and a candidate or
//      condition that is not finite makes the status overflow. Without a stick candidate
//      (K singular identically: a body pinned at a fixed point struck by one that cannot
//      move) the slides are the candidates: regime slide, no det K check, no boundary merge;
//   4. the post-impact state for the impulse of that candidate (stage C, linear in it: the
//      stick candidate's formulas, or without one symbolic/response.hpp's), the energy lost
//      as minus the work of the contact impulse (1/2 P.(a + a') per free body), the
//      finiteness of the result.
// Values stages B, C and S need from stage A (its steps, and for B and C the powers with
// negative or fractional exponents of stage A's values: 1/m, 1/I, 1/|n|, so that no
// division or square root is done twice) are stage A outputs ("links"), named in a
// canonical order. Every name goes through one identifier scope (names/identifier.hpp);
// every expression is printed by emit_cpp from canonical trees (canonical.hpp), never in
// GiNaC's order: the header is the same byte for byte in every process.
#include "friction_writer.hpp"

namespace impactgen::codegen
{
namespace friction_detail
{

// ---------------------------------------------------------------------------
// Helpers

void add_counts(op_counts &a, const op_counts &b)
{
    a.add += b.add;
    a.mul += b.mul;
    a.div += b.div;
    a.sqrt += b.sqrt;
}

std::string indent(const std::string &code, const std::string &by)
{
    std::istringstream lines(code);
    std::string line, r;
    while (std::getline(lines, line))
        r += (line.empty() ? "" : by) + line + "\n";
    return r;
}

bool depends_on(const ex &e, const exset &syms)
{
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it) && syms.count(*it))
            return true;
    return false;
}

void collect_symbols(const ex &e, exset &out)
{
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it))
            out.insert(*it);
}

header friction_writer::run()
{
    name_everything();
    build_stages();
    emit_stages();
    banner();
    preamble();
    result_struct();
    formula_block();
    unchanged_function();
    main_function();
    array_form();
    struct_form();
    batch_form();
    tables();
    header h;
    h.text = h_.str();
    h.formula = total_;
    h.checks = a_.em.checks;
    h.inputs = input_names_;
    for (const out_field &of : outs_)
        h.outputs.push_back(of.field);
    return h;
}

void friction_writer::prepare(const problem &p)
{
    if (o_.inverse_inertia)
        throw option_error(
            option_error::inverse_inertia,
            "the engine input convention is not offered for problems with friction (give masses and inertia)");
    if (o_.inverse_mass)
        throw option_error(option_error::inverse_mass,
                           "the engine input convention is not offered for problems with friction (give masses)");
    if (o_.jacobian || !o_.wrt.empty())
        throw option_error(option_error::jacobian, "Jacobians are not offered for problems with friction (the regime "
                                                   "selection makes the impact map piecewise)");
    problem p0 = p;
    // --params mu with a numeric coefficient: mu becomes the parameter.
    if (o_.params_given && std::find(o_.params.begin(), o_.params.end(), "mu") != o_.params.end() &&
        is_a<numeric>(p0.contact().friction())) {
        bool taken = false;
        for (const symbol &s : p0.parameters())
            taken = taken || s.get_name() == "mu";
        if (!taken)
            p0.contact().set_friction(symbol_named("mu", "\\mu"));
    }
    q_ = specialise(p0, o_);
    if (!q_.has_friction())
        throw input_error(
            (q_.source.empty() ? std::string("contact") : names::display_text(q_.source) + ": contact") +
            ".friction: the coefficient of friction is 0: generate the smooth header (codegen::generate)");
    // The smooth plan of the same problem without friction: the inputs in the smooth
    // headers' order with their meanings, the outputs, the vector views, the state a
    // failed call returns.
    problem sq = q_;
    sq.contact().set_friction(0);
    std::set<std::string> rest;
    for (const symbol &s : sq.parameters())
        rest.insert(s.get_name());
    exset fsyms;
    collect_symbols(q_.contact().friction(), fsyms);
    std::set<std::string> friction_only;
    for (const ex &s : fsyms)
        if (!rest.count(ex_to<symbol>(s).get_name()))
            friction_only.insert(ex_to<symbol>(s).get_name());
    options so = o_;
    so.set.clear();
    so.params.clear();
    for (const std::string &nm : o_.params)
        if (!friction_only.count(nm))
            so.params.push_back(nm);
    pl_ = make_plan(sq, so);
    derive_options how;
    how.unit_normal = o_.unit_normal;
    how.runtime_tangent_basis = true;
    d_ = derive(q_, how);
    f_ = solve_friction(d_);

    order_inputs(friction_only);
    order_outputs();
}

// The inputs: the parameters in the order given, else the smooth order with the
// symbols of mu right after those of e.
void friction_writer::order_inputs(const std::set<std::string> &friction_only)
{
    std::map<std::string, symbol> by_name;
    for (const symbol &s : q_.parameters())
        by_name.emplace(s.get_name(), s);
    const std::string mu_meaning = is_a<symbol>(q_.contact().friction())
                                       ? "coefficient of friction mu >= 0 (Coulomb: |P_t| <= mu P_n)"
                                       : "appears in the coefficient of friction mu";
    auto smooth_meaning = [&](const symbol &s) -> std::string {
        for (std::size_t i = 0; i < pl_.inputs.size(); ++i)
            if (pl_.inputs[i].is_equal(s))
                return pl_.input_meaning[i];
        return mu_meaning;
    };
    if (o_.params_given) {
        for (const std::string &nm : o_.params) {
            const symbol &s = by_name.at(nm);
            inputs_.push_back(s);
            input_meaning_.push_back(smooth_meaning(s));
        }
    } else {
        std::size_t at = 0;
        exset esyms;
        collect_symbols(q_.restitution, esyms);
        for (std::size_t i = 0; i < pl_.inputs.size(); ++i)
            if (esyms.count(pl_.inputs[i]))
                at = i + 1;
        for (std::size_t i = 0; i < pl_.inputs.size(); ++i) {
            if (i == at)
                for (const std::string &nm : friction_only) {
                    inputs_.push_back(by_name.at(nm));
                    input_meaning_.push_back(mu_meaning);
                }
            inputs_.push_back(pl_.inputs[i]);
            input_meaning_.push_back(pl_.input_meaning[i]);
        }
        if (at >= pl_.inputs.size())
            for (const std::string &nm : friction_only) {
                inputs_.push_back(by_name.at(nm));
                input_meaning_.push_back(mu_meaning);
            }
    }
}

// The outputs: the smooth ones with the tangential impulse after the normal impulse.
void friction_writer::order_outputs()
{
    const int dim = q_.dimension;
    for (std::size_t k = 0; k < pl_.outputs.size(); ++k) {
        const output_value &ov = pl_.outputs[k];
        out_field of;
        of.field = ov.field;
        of.meaning = ov.meaning;
        of.kind = ov.kind;
        of.index = ov.index;
        of.component = ov.component;
        of.smooth = k;
        if (ov.kind == output_value::normal_impulse)
            of.meaning = "normal impulse P.n >= 0 along the unit normal: on " + q_.bodies[q_.contact().body2].name +
                         " along +n, on " + q_.bodies[q_.contact().body1].name + " along -n";
        if (ov.kind == output_value::approach_velocity)
            of.meaning = "(v_B - v_A).n before impact along the unit normal (< 0)";
        smooth_index_[k] = outs_.size();
        outs_.push_back(of);
        if (ov.kind == output_value::normal_impulse)
            for (int a = 0; a < dim; ++a) {
                out_field tf;
                tf.field = "tangential_impulse_" + q_.axes[static_cast<std::size_t>(a)];
                tf.meaning = "tangential (friction) impulse P - (P.n) n on " + q_.bodies[q_.contact().body2].name +
                             " (on " + q_.bodies[q_.contact().body1].name + " its opposite), world " +
                             q_.axes[static_cast<std::size_t>(a)];
                tf.kind = output_value::normal_impulse;
                tf.tangential = true;
                tf.axis = a;
                tangential_index_.push_back(outs_.size());
                outs_.push_back(tf);
            }
    }
}

void friction_writer::name_everything()
{
    for (const std::string &r : reserved())
        if (names::is_safe_identifier(r))
            scope_.reserve(r);
    for (names::identifier_scope *sc : {&in_members_, &members_})
        for (const char *own : {"view", "T", "regime"})
            sc->reserve(own);
    for (const char *suffix : {"", "_result", "_input", "_unchanged", "_batch", "_input_count", "_output_count",
                               "_input_names", "_output_names", "_to_array"})
        scope_.reserve(o_.name + suffix);
    for (const symbol &x : inputs_) {
        input_names_.push_back(scope_.claim(x.get_name()));
        input_ident_[x] = input_names_.back();
    }
    // The tangent basis computed at run time (a normal given as inputs): locals that the
    // stages read as they read inputs.
    for (const symbol &x : d_.tangent_basis_symbols) {
        basis_names_.push_back(scope_.claim(x.get_name()));
        input_ident_[x] = basis_names_.back();
    }
    if (!basis_names_.empty()) {
        basis_t_name_ = scope_.claim("basis_t");
        basis_b_name_ = scope_.claim("basis_b");
        nb_.pool.set_input_names(input_ident_);
        for (int a = 0; a < 3; ++a)
            nb_.output(scope_.claim("basis_n_" + q_.axes[static_cast<std::size_t>(a)]),
                       q_.contact().normal[static_cast<std::size_t>(a)]);
    }
    for (out_field &of : outs_)
        of.field = members_.claim(of.field);
    for (const std::string &nm : input_names_)
        in_members_.claim(nm);
    for (const group &g : pl_.input_groups)
        in_views_.push_back(in_members_.claim(g.name));
    for (const group &g : pl_.output_groups)
        out_views_.push_back(members_.claim(g.name));
    if (q_.dimension >= 2)
        tangential_view_ = members_.claim("tangential_impulse");
}

std::string friction_writer::case_prefix(const regime_case &c) const
{
    if (c.kind == regime::stick)
        return "stick_";
    if (c.sign > 0)
        return "slide_pos_";
    if (c.sign < 0)
        return "slide_neg_";
    return "slide_";
}

} // namespace friction_detail

using friction_detail::friction_writer;

bool has_friction(const problem &p, const options &o)
{
    if (!p.has_friction())
        return false;
    try {
        options so = o;
        so.params_given = false; // only --set can make mu 0
        so.params.clear();
        return specialise(p, so).has_friction();
    } catch (const std::exception &) {
        return true;
    }
}

header generate_friction(const problem &p, const options &o)
{
    form_text::check_names(o);
    return friction_writer(p, o).run();
}

} // namespace impactgen::codegen
