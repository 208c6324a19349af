// The one header writer (writer.hpp): the order of the sections, the names, the checks.
#include "writer.hpp"

namespace impactgen::codegen
{
namespace writer_detail
{

void add_counts(op_counts &a, const op_counts &b)
{
    a.add += b.add;
    a.mul += b.mul;
    a.div += b.div;
    a.sqrt += b.sqrt;
    a.trig += b.trig;
}

std::string math_usings(const emitted &e)
{
    return std::string(e.uses_sqrt ? "    using std::sqrt;\n" : "") +
           (e.uses_trig ? "    using std::cos;\n    using std::sin;\n" : "");
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

namespace
{

// A body's 3-D inertia tensor as the closed form inverts it: about its centre of mass
// (free) or about its pivot E (pinned: I_C + m (|d|^2 1 - d d^T), d = C - E), each
// entry the solution's step where it has one (the very value the code computes).
mat3 tensor_in_use(const problem &q, const solution &s, std::size_t i)
{
    const body &b = q.bodies[i];
    const pivot *pv = q.pivot_of(i);
    if (!pv)
        return b.inertia;
    mat3 J = inertia_about(b, pv->point);
    for (int r = 0; r < 3; ++r)
        for (int c = r; c < 3; ++c)
            if (const step *st = s.find(step_role::pivot_inertia, i, r, c))
                J[r][c] = J[c][r] = st->sym;
    return J;
}

} // namespace

writer::writer(code_plan cp, const options &o)
    : o_(o), cp_(std::move(cp)), pl_(cp_.base), q_(cp_.prob), d_(cp_.deriv), f_(cp_.candidates), outs_(cp_.outputs),
      angle_(cp_.angle)
{
}

// The sections in order; the function's body by the selection rule.
header writer::run()
{
    name_everything();
    if (system())
        return run_system();
    if (straight()) {
        lower_program();
        add_checks(main_, pl_.sol.steps);
        emit_forms();
    } else {
        build_stages();
        emit_stages();
        build_jacobian();
    }
    build_rows();
    banner();
    preamble();
    result_struct();
    if (straight())
        straight_formulas();
    else
        candidates_formulas();
    if (straight()) {
        unchanged_function(unchanged_);
        checked_function();
        fast_function();
        unchecked_function();
    } else {
        unchanged_function(u_.em);
        if (process_jacobian())
            system_tolerance();
        main_function(false);
        main_function(true);
    }
    forwarding_form(false);
    forwarding_form(true);
    jacobian_function();
    candidates_jacobian_function();
    rows_function();
    if (straight())
        straight_batch();
    else
        loop_batch();
    tables();
    header out;
    out.text = h_.str();
    out.formula = straight() ? em_.formula : total_;
    out.checks = straight() ? em_.checks : a_.em.checks;
    out.inputs = input_names_;
    for (const code_output &of : outs_)
        out.outputs.push_back(of.field);
    return out;
}

// A system's header: the same sections around its own function.
header writer::run_system()
{
    if (sequential())
        build_sequence();
    else
        build_system();
    build_jacobian();
    banner();
    preamble();
    result_struct();
    if (sequential())
        sequence_formulas();
    else
        system_formulas();
    unchanged_function(u_.em);
    system_tolerance();
    if (sequential())
        sequence_function();
    else
        system_function();
    forwarding_form(false);
    forwarding_form(true);
    candidates_jacobian_function();
    loop_batch();
    tables();
    header out;
    out.text = h_.str();
    out.formula = total_;
    out.checks = a_.em.checks;
    out.inputs = input_names_;
    for (const code_output &of : outs_)
        out.outputs.push_back(of.field);
    return out;
}

// Every name the header declares comes from one scope (names/identifier.hpp): the
// emitter's own names first, then inputs, steps and the locals derived from outputs and
// inputs, so no user name can shadow or collide with another.
void writer::name_everything()
{
    for (const std::string &r : reserved())
        if (names::is_safe_identifier(r))
            scope_.reserve(r);
    // A member named view or T would hide the view type or the template parameter; regime
    // is the result's member with candidates, set and impulses_unique a system's.
    for (names::identifier_scope *sc : {&in_members_, &members_}) {
        for (const char *own : {"view", "T"})
            sc->reserve(own);
        if (system()) {
            sc->reserve("set");
            sc->reserve("impulses_unique");
            sc->reserve("boundary");
            if (sequential())
                sc->reserve("steps");
        } else if (!straight()) {
            sc->reserve("regime");
            if (process_jacobian()) {
                sc->reserve("sequence");
                sc->reserve("boundary");
            }
        }
    }
    // clang-format off
    const std::vector<const char *> straight_suffixes = {
        "", "_result", "_input", "_unchanged", "_unchecked", "_jacobian", "_jacobian_result", "_wrt_count",
        "_wrt_names", "_checked", "_batch", "_batch_pass", "_input_count", "_output_count", "_input_names",
        "_output_names", "_ops", "_to_array", "_rows", "_row", "_rows_result"};
    const std::vector<const char *> candidate_suffixes = {
        "", "_result", "_input", "_unchanged", "_unchecked", "_batch", "_input_count", "_output_count",
        "_input_names", "_output_names", "_to_array", "_rows", "_row", "_rows_result"};
    // clang-format on
    for (const char *suffix : straight() ? straight_suffixes : candidate_suffixes)
        scope_.reserve(o_.name + suffix);
    if (system())
        for (const char *suffix :
             {"_set_count", "_set_names", "_tolerance", "_jacobian", "_wrt_count", "_wrt_names", "_max_steps"})
            scope_.reserve(o_.name + suffix);
    if (process_jacobian())
        for (const char *suffix : {"_tolerance", "_jacobian", "_wrt_count", "_wrt_names", "_jacobian_output_count",
                                   "_jacobian_output_names"})
            scope_.reserve(o_.name + suffix);
    for (const symbol &x : cp_.inputs) {
        input_names_.push_back(scope_.claim(x.get_name()));
        input_ident_[x] = input_names_.back();
    }
    if (!straight())
        name_basis();
    for (code_output &of : outs_)
        of.field = members_.claim(of.field);
    if (straight())
        name_straight();
    // The input struct's members are the parameters' names; the views of both structs
    // are member functions, named clear of the members.
    for (const std::string &nm : input_names_)
        in_members_.claim(nm);
    for (const group &g : pl_.input_groups)
        in_views_.push_back(in_members_.claim(g.name));
    for (const group &g : pl_.output_groups)
        out_views_.push_back(members_.claim(g.name));
    if (!straight() && !system() && q_.dimension >= 2)
        tangential_view_ = members_.claim("tangential_impulse");
}

// The tangent basis computed at run time (a normal given as inputs): locals that the
// stages read as they read inputs.
void writer::name_basis()
{
    for (const symbol &x : d_.tangent_basis_symbols) {
        basis_names_.push_back(scope_.claim(x.get_name()));
        input_ident_[x] = basis_names_.back();
    }
    if (basis_names_.empty())
        return;
    basis_t_name_ = scope_.claim("basis_t");
    basis_b_name_ = scope_.claim("basis_b");
    nb_.pool.set_input_names(input_ident_);
    for (int a = 0; a < 3; ++a)
        nb_.output(scope_.claim("basis_n_" + q_.axes[static_cast<std::size_t>(a)]),
                   q_.contact().normal[static_cast<std::size_t>(a)]);
}

// The straight-line program's names: its steps, the locals of the outputs, the batch
// form's pointers, the Jacobian's steps and entries.
void writer::name_straight()
{
    main_.pool.set_input_names(input_ident_);
    for (const step &st : pl_.sol.steps)
        step_names_.push_back(scope_.claim(st.sym.get_name()));
    for (const code_output &ov : outs_) {
        local_of_[ov.field] = scope_.claim("o_" + ov.field);
        out_ptr_[ov.field] = scope_.claim("out_" + ov.field);
    }
    for (const std::string &nm : input_names_)
        in_ptr_[nm] = scope_.claim("in_" + nm);
    if (pl_.has_jacobian) {
        for (const step &st : pl_.jac.steps)
            jac_step_names_.push_back(scope_.claim(st.sym.get_name()));
        for (const symbol &x : pl_.jac.wrt)
            wrt_names_.push_back(input_ident_.at(x));
        for (const code_output &ov : outs_) {
            std::vector<std::string> row;
            for (const std::string &w : wrt_names_)
                row.push_back(scope_.claim("d_" + ov.field + "_d_" + w));
            jac_local_.push_back(row);
        }
    }
    status_ptr_ = scope_.claim("status_out");
}

// The checks that depend on the state of each call (the contact points approach, the
// contact response is not singular): what the unchecked variant keeps.
std::vector<check> state_checks(const std::vector<check> &checks)
{
    std::vector<check> kept;
    for (const check &c : checks)
        if (c.status == "not_approaching" || c.status == "singular")
            kept.push_back(c);
    return kept;
}

std::string writer::case_prefix(const regime_case &c) const
{
    if (!c.process.empty())
        return "seq_";
    if (c.kind == regime::stick)
        return "stick_";
    if (c.sign > 0)
        return "slide_pos_";
    if (c.sign < 0)
        return "slide_neg_";
    return "slide_";
}

void writer::add_check(stage &s, const ex &value0, check::kind_t kind, const std::string &status,
                       const std::string &comment)
{
    // In the engine convention the masses (and planar inertia) are inputs only as
    // inverses: a checked value that uses them (an inertia m L^2/12) uses 1/inv_m.
    ex value = value0;
    if (!pl_.inverse_of.empty() && (!is_a<symbol>(value0) || !pl_.meaning.count(value0))) {
        lst inverses;
        for (const auto &[old, inv] : pl_.inverse_of)
            inverses.append(old == 1 / inv);
        value = value0.subs(inverses);
    }
    if (is_a<numeric>(value))
        return; // constants were validated when the problem was read
    s.checks.push_back({kind, s.lower(value, "check"), status, comment});
}

// Validity checks of the inputs and of the steps, by the steps' roles.
void writer::add_checks(stage &s, const std::vector<step> &steps)
{
    const problem &q = q_;
    add_check(s, q.restitution, check::unit_interval, "invalid_restitution", "0 <= e <= 1");
    auto inverse = [&](const ex &x) -> const symbol * {
        auto it = pl_.inverse_of.find(x);
        return it == pl_.inverse_of.end() ? nullptr : &it->second;
    };
    for (std::size_t i : {q.contact().body1, q.contact().body2}) {
        const body &b = q.bodies[i];
        if (b.infinite_mass)
            continue;
        // The engine convention: an inverse 0 is a static (or kinematic) body, or one whose
        // rotation is locked: >= 0.
        const symbol *inv_m = inverse(b.mass);
        if (inv_m)
            add_check(s, *inv_m, check::nonnegative, "invalid_mass", "inverse mass of " + b.name + " >= 0, finite");
        else
            add_check(s, b.mass, check::positive, "invalid_mass", "mass of " + b.name + " > 0, finite");
        if (!b.particle && q.dimension == 2) {
            const symbol *inv_I = inverse(b.inertia[2][2]);
            if (inv_I)
                add_check(s, *inv_I, check::nonnegative, "invalid_inertia",
                          "inverse moment of inertia of " + b.name + " >= 0, finite");
            else
                add_check(s, b.inertia[2][2], check::positive, "invalid_inertia",
                          "moment of inertia of " + b.name + " > 0, finite");
        }
    }
    // Positive definiteness of each 3-D inertia tensor the closed form inverts (about C,
    // or about the pivot E): leading principal minors, block by block; in the engine
    // convention the inverse tensor given positive semidefinite (0: a static body; singular:
    // rotation locked about some axes): every principal minor of each block >= 0. Entries
    // or minors that are numbers were validated when the problem was read; the determinant
    // is its own step below.
    for (std::size_t i : {q.contact().body1, q.contact().body2}) {
        const body &b = q.bodies[i];
        if (q.dimension != 3 || b.particle || b.infinite_mass)
            continue;
        auto inv = pl_.inverse_tensor.find(i);
        const bool inverse_given = inv != pl_.inverse_tensor.end();
        if (inverse_given) {
            for (const auto &[minor, text] : positive_semidefinite_minors(inv->second, q.axes))
                add_check(s, minor, check::nonnegative, "invalid_inertia",
                          "inverse inertia tensor of " + b.name + " positive semidefinite: " + text);
            continue;
        }
        const std::string what =
            "inertia tensor of " + b.name + (q.pivot_of(i) ? " about its pivot" : "") + " positive definite: ";
        const mat3 J = tensor_in_use(q, straight() ? pl_.sol : solution{}, i);
        for (const auto &[minor, text] : positive_definite_minors(J, q.axes, false))
            add_check(s, minor, check::positive, "invalid_inertia", what + text);
    }
    // A normal with symbols: its squared length a normal number before anything divides
    // by the length; declared unit (--unit-normal), of length 1 within 2^-17.
    const ex nn = tidy(dot(q.contact().normal, q.contact().normal));
    if (!is_constant(nn)) {
        if (straight() ? pl_.deriv.normal_assumed_unit : d_.normal_assumed_unit)
            add_check(s, nn, check::near_one, "invalid_normal", "the normal is a unit vector: |n.n - 1| <= 2^-17");
        else
            add_check(s, nn, check::normal_number, "invalid_normal",
                      "n.n a normal number: the normal neither zero, denormal nor too long");
    }
    // The steps' checks: the smooth closed form's effective inverse mass k (or the
    // denominator of N when k is too simple to be a step); with candidates det K > 0 for
    // the stick candidate.
    const bool has_k = std::any_of(steps.begin(), steps.end(),
                                   [](const step &st) { return st.role == step_role::contact_inverse_mass; });
    for (const step &st : steps) {
        switch (st.role) {
        case step_role::normal_impulse:
            if (straight() && !has_k)
                add_check(s, st.value.denom(), check::positive, "singular", "effective inverse mass k > 0, finite");
            break;
        case step_role::inertia_determinant:
            add_check(s, st.sym, check::positive, "invalid_inertia", "determinant of the inertia tensor > 0, finite");
            break;
        case step_role::approach_velocity:
            add_check(s, st.sym, check::negative, "not_approaching",
                      straight() ? "the contact points approach: u < 0" : "the contact points approach: u_n < 0");
            break;
        case step_role::contact_inverse_mass:
            if (straight())
                add_check(s, st.sym, check::positive, "singular", "effective inverse mass k > 0, finite");
            break;
        case step_role::response_determinant:
            // The stick candidate needs det K > 0; where it is not (K singular: a body pinned at
            // a fixed point struck by one many orders of magnitude heavier) only that candidate
            // is dropped (stick_possible) and the slides may still hold. Routh's process stops.
            if (cp_.rule == selection_rule::process)
                add_check(s, st.sym, check::positive, "singular", "contact response det K > 0, finite (stick)");
            else
                det_K_ = st.sym;
            break;
        default:
            break;
        }
    }
}

} // namespace writer_detail

header generate(const problem &p, const options &o)
{
    form_text::check_names(o);
    return writer_detail::writer(make_code_plan(p, o), o).run();
}

} // namespace impactgen::codegen
