// The one header writer (writer.hpp), a plan with a selection rule (first_that_holds,
// sliding_angle): the straight-line programs of the function (stages A, B, S, C and the
// unchanged state), their links and their checks.
//
// The emitted function, in order:
//   1. stage A, one straight-line program (CSE over everything in it): the shared steps
//      (K = K_1 + K_2 as the sum of the bodies' responses 1/m + (I^-1 (r x e)) x r, u, u_n),
//      the validity checks of the smooth headers (restitution, masses, inertia, normal,
//      approach, n.K n > 0: status singular; det K as a value: the stick candidate exists
//      where det K > 0, else only it is dropped -- stick_possible), every
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
#include "writer.hpp"

namespace impactgen::codegen::writer_detail
{

void writer::build_stages()
{
    const problem &q = q_;
    const int dim = q.dimension;
    split_steps();

    name_selected();

    // Stage C: the state after the impulse sel_P, the impulses, the approach velocity and
    // the energy lost.
    const after_state after = state_after_selected();
    const step *un = nullptr;
    for (const step &st : f_.shared.steps)
        if (st.role == step_role::approach_velocity)
            un = &st;
    if (!un)
        throw std::logic_error("codegen friction: no approach velocity step");
    std::vector<ex> c_values = stage_c_values(after, un);
    if (!scale_.is_zero()) { // the candidates' impulses are sigma times the impulse
        lst unscale;
        unscale.append(sel_N_ == sel_N_ / scale_);
        for (std::size_t a = 0; a < sel_P_.size(); ++a) {
            unscale.append(sel_P_[a] == sel_P_[a] / scale_);
            unscale.append(sel_F_[a] == sel_F_[a] / scale_);
        }
        for (ex &v : c_values)
            v = v.subs(unscale);
    }
    // Stage S: mu = 0, the frictionless impact: N = -(1 + e) u_n / (n.K n), P = N n.
    const vec3 &n = d_.n_hat;
    mat3 K = zero_mat();
    for (const step &st : f_.shared.steps)
        if (st.role == step_role::contact_response)
            K[static_cast<std::size_t>(st.row)][static_cast<std::size_t>(st.column)] =
                K[static_cast<std::size_t>(st.column)][static_cast<std::size_t>(st.row)] = st.sym;
    const ex D0 = dot(n, mul(K, n));
    symbol N0("friction_N0");
    s_D0_ = D0;
    s_N0_value_ = -(1 + q.restitution) * un->sym / D0;
    s_N0_ = N0;

    // Links: stage A values that stages B, C and S use.
    auto link = [&](const ex &e) { return linkify(e); };
    for (ex &v : c_values)
        v = link(v);
    c_values_ = c_values;
    // (stage S, for mu = 0 only, computes its own reciprocals: links are computed on every call)
    s_P0_.clear();
    for (int a = 0; a < dim; ++a)
        s_P0_.push_back(N0 * n[static_cast<std::size_t>(a)]);
    if (angle_ >= 0) {
        const regime_case &c = f_.cases[static_cast<std::size_t>(angle_)];
        for (step st : b_steps_) {
            st.value = link(st.value);
            b_steps_linked_.push_back(st);
        }
        b_N_ = link(c.sol.normal_impulse);
        for (int a = 0; a < dim; ++a) {
            b_P_.push_back(link(c.impulse[static_cast<std::size_t>(a)]));
            b_F_.push_back(link(c.tangential_impulse[static_cast<std::size_t>(a)]));
        }
        for (const regime_condition &rc : c.conditions)
            b_cond_.push_back(link(rc.value));
    }
    name_links();

    build_stage_a();
    build_stage_b();
    build_stage_s();
    build_stage_c();
    build_unchanged();
}

void writer::split_steps()
{
    // Steps: stage A (every step of every case that does not depend on the sliding
    // angle, each once) and stage B (the angle case's own steps).
    exset shared;
    for (const step &st : f_.cases.front().sol.steps) {
        bool everywhere = true;
        for (const regime_case &c : f_.cases) {
            bool found = false;
            for (const step &s2 : c.sol.steps)
                found = found || s2.sym.is_equal(st.sym);
            everywhere = everywhere && found;
        }
        if (everywhere)
            shared.insert(st.sym);
    }
    exset seen;
    if (angle_ >= 0) {
        local_.insert(f_.cases[static_cast<std::size_t>(angle_)].dir_c);
        local_.insert(f_.cases[static_cast<std::size_t>(angle_)].dir_s);
    }
    for (std::size_t i = 0; i < f_.cases.size(); ++i) {
        const regime_case &c = f_.cases[i];
        for (const step &st : c.sol.steps) {
            if (!seen.insert(st.sym).second)
                continue;
            const bool in_b = static_cast<int>(i) == angle_ && depends_on(st.value, local_);
            const std::string nm = scope_.claim((shared.count(st.sym) ? "" : case_prefix(c)) + st.sym.get_name());
            if (in_b) {
                local_.insert(st.sym);
                b_steps_.push_back(st);
                b_step_names_.push_back(nm);
            } else {
                a_steps_.push_back(st);
                a_step_names_.push_back(nm);
                a_step_syms_.insert(st.sym);
            }
        }
    }
    for (std::size_t i = 0; i < a_steps_.size(); ++i)
        step_name_[a_steps_[i].sym] = a_step_names_[i];
    // K as the sum of the bodies' responses, 1/m + (I^{-1} (r x e_b)) x r (as the smooth
    // headers compute w = 1/m + (r x n).I^{-1}(r x n)), rather than the one fraction
    // symbolic/friction.hpp keeps for it (I1 I2 m1 m2 in its denominator under- or
    // overflows where the sum does not).
    for (step &st : a_steps_)
        if (st.role == step_role::contact_response)
            st.value = response_entry(f_.shared, st.row, st.column);
    scale_response();
}

// K scaled by sigma = n.K n (> 0 whenever a body can move; the smooth header's k, which
// overflows where it does): the candidates see
// K~ = K / sigma, so that det K~ neither under- nor overflows where K's entries are in
// range (masses of 1e200 made det K about 1e-400: singular where the smooth header gives
// the impact). Every candidate's impulse scales as K^-1 (it comes out sigma times the
// impulse), its conditions keep their signs (each homogeneous in K and the impulse), and
// the selected impulse is divided by sigma before the state after it (stage C). A sigma of
// 0 or infinity makes K~ NaN: det K~ > 0 fails (singular), as k > 0 does in the smooth header.
void writer::scale_response()
{
    auto first = std::find_if(a_steps_.begin(), a_steps_.end(),
                              [](const step &st) { return st.role == step_role::contact_response; });
    if (first == a_steps_.end())
        return;
    step sc;
    sc.sym = symbol("friction_K_scale");
    sc.role = step_role::contact_inverse_mass;
    sc.meaning = "n.K n, the scale of the contact response K";
    sc.value = 0;
    for (const step &st : a_steps_)
        if (st.role == step_role::contact_response) {
            // (each entry as K has it: one fraction of the products of masses and inertia
            // would under- or overflow where the sum does not)
            const ex nn = tidy((st.row == st.column ? 1 : 2) * d_.n_hat[static_cast<std::size_t>(st.row)] *
                               d_.n_hat[static_cast<std::size_t>(st.column)]);
            if (!nn.is_zero())
                sc.value += nn * st.value;
        }
    for (step &st : a_steps_)
        if (st.role == step_role::contact_response)
            st.value = st.value / sc.sym;
    const std::size_t at = static_cast<std::size_t>(first - a_steps_.begin());
    a_step_names_.insert(a_step_names_.begin() + static_cast<std::ptrdiff_t>(at), scope_.claim("K_scale"));
    a_steps_.insert(a_steps_.begin() + static_cast<std::ptrdiff_t>(at), sc);
    a_step_syms_.insert(sc.sym);
    step_name_[sc.sym] = a_step_names_[at];
    scale_ = sc.sym;
}

// The selected impulse (world, on body 2), normal impulse and tangential impulse.
void writer::name_selected()
{
    const problem &q = q_;
    const int dim = q.dimension;
    for (int a = 0; a < dim; ++a) {
        const std::string ax = q.axes[static_cast<std::size_t>(a)];
        sel_P_.push_back(symbol("friction_P_" + ax));
        sel_F_.push_back(symbol("friction_F_" + ax));
        sel_P_names_.push_back(scope_.claim("sel_P_" + ax));
        sel_F_names_.push_back(scope_.claim("sel_F_" + ax));
    }
    sel_N_name_ = scope_.claim("sel_N");
    for (int a = 0; a < dim; ++a) {
        local_.insert(sel_P_[static_cast<std::size_t>(a)]);
        local_.insert(sel_F_[static_cast<std::size_t>(a)]);
    }
    local_.insert(sel_N_);
}

// Stage C's outputs: the state after the impulse sel_P, the impulses, the approach
// velocity and the energy lost.
std::vector<ex> writer::stage_c_values(const after_state &after, const step *un) const
{
    std::vector<ex> c_values(outs_.size());
    for (std::size_t k = 0; k < outs_.size(); ++k) {
        const code_output &of = outs_[k];
        if (of.tangential) {
            c_values[k] = sel_F_[static_cast<std::size_t>(of.axis)];
            continue;
        }
        switch (of.kind) {
        case output_value::velocity:
            c_values[k] = after.velocity[of.index][of.component];
            break;
        case output_value::angular_velocity:
            c_values[k] = after.angular_velocity[of.index][of.component];
            break;
        case output_value::pivot_impulse:
            c_values[k] = after.pivot_impulses[of.index][of.component];
            break;
        case output_value::normal_impulse:
            c_values[k] = sel_N_;
            break;
        case output_value::approach_velocity:
            c_values[k] = un->sym;
            break;
        case output_value::energy_lost:
            c_values[k] = energy_lost(after);
            break;
        }
    }
    return c_values;
}

// Entry (a, b) of the contact response K = K_1 + K_2: the change of the relative
// velocity of the contact points along a per unit impulse along b on body 2 (and its
// opposite on body 1): K_i P = P/m_i + (I_i^{-1} (r_i x P)) x r_i (a pinned body: about
// its pivot, without the first term), with the inverse inertia as the solution has it
// (its steps for a full tensor, 1/I for a diagonal one).
ex writer::response_entry(const solution &s, int a, int b) const
{
    const problem &q = q_;
    ex k = 0;
    for (std::size_t i : {q.contact().body1, q.contact().body2}) {
        if (q.immovable(i))
            continue;
        const body &bd = q.bodies[i];
        const pivot *pv = q.pivot_of(i);
        const vec3 lever = pv ? q.contact().point - pv->point : q.contact().point - bd.position;
        if (!pv && a == b)
            k += 1 / bd.mass;
        if (bd.particle)
            continue;
        const mat3 inv = inverse_inertia(s, i);
        vec3 e = zero_vec();
        e[static_cast<std::size_t>(b)] = 1;
        k += cross(mul(inv, cross(lever, e)), lever)[static_cast<std::size_t>(a)];
    }
    return k;
}

// The inverse inertia of movable body i, not a particle (about its pivot when pinned), as
// the solution s has it: its steps for a full tensor (or adj(J) / det(J) itself for a
// tensor too simple to be a step), 1/I for a diagonal one.
mat3 writer::inverse_inertia(const solution &s, std::size_t i) const
{
    const problem &q = q_;
    const body &bd = q.bodies[i];
    const pivot *pv = q.pivot_of(i);
    mat3 inv = zero_mat();
    if (q.dimension == 2) {
        const step *ie = s.find(step_role::pivot_inertia, i, 2, 2);
        ex Iz = bd.inertia[2][2];
        if (pv)
            Iz = ie ? ex(ie->sym) : inertia_about(bd, pv->point)[2][2];
        inv[2][2] = 1 / Iz;
        return inv;
    }
    const mat3 J = pv ? inertia_about(bd, pv->point) : bd.inertia;
    bool diagonal = true;
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t c = r + 1; c < 3; ++c)
            diagonal = diagonal && tidy(J[r][c]).is_zero() && tidy(J[c][r]).is_zero();
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t c = 0; c < 3; ++c) {
            if (diagonal) {
                inv[r][c] = r == c ? 1 / tidy(J[r][r]) : ex(0);
                continue;
            }
            const step *js = s.find(step_role::inverse_inertia, i, static_cast<int>(std::min(r, c)),
                                    static_cast<int>(std::max(r, c)));
            if (js) {
                inv[r][c] = js->sym;
                continue;
            }
            mat3 Jt;
            for (std::size_t a2 = 0; a2 < 3; ++a2)
                for (std::size_t c2 = 0; c2 < 3; ++c2)
                    Jt[a2][c2] = tidy(J[a2][c2]);
            inv[r][c] = tidy(adjugate(Jt)[r][c] / det(Jt));
        }
    return inv;
}

// The bodies' velocities and the pivots' impulses after the impulse sel_P (on body 2;
// -sel_P on body 1), linear in it: the stick candidate's formulas with its impulse
// replaced when there is one, else the response layer's (symbolic/response.hpp, as
// symbolic/friction.cpp finishes every candidate) with the shared steps' inverse inertia.
after_state writer::state_after_selected() const
{
    const problem &q = q_;
    after_state r;
    if (const regime_case *stick = f_.stick()) {
        lst to_sel;
        for (std::size_t a = 0; a < sel_P_.size(); ++a)
            to_sel.append(stick->impulse[a] == sel_P_[a]);
        auto subs = [&](const vec3 &v) {
            vec3 x;
            for (std::size_t a = 0; a < 3; ++a)
                x[a] = v[a].subs(to_sel);
            return x;
        };
        for (const auto &b : stick->sol.after) {
            r.velocity.push_back(subs(b.velocity));
            r.angular_velocity.push_back(subs(b.angular_velocity));
        }
        for (const vec3 &R : stick->sol.pivot_impulses)
            r.pivot_impulses.push_back(subs(R));
        return r;
    }
    for (const body &b : q.bodies) {
        r.velocity.push_back(b.velocity);
        r.angular_velocity.push_back(b.angular_velocity);
    }
    r.pivot_impulses.assign(q.pivots.size(), zero_vec());
    vec3 P = zero_vec();
    for (std::size_t a = 0; a < sel_P_.size(); ++a)
        P[a] = sel_P_[a];
    for (std::size_t i : {q.contact().body1, q.contact().body2}) {
        const body &b = q.bodies[i];
        if (b.infinite_mass)
            continue;
        const body_response br = response_of(q, i, q.contact().point);
        const vec3 Pi = ex(i == q.contact().body1 ? -1 : 1) * P;
        const mat3 inv = br.movable && !br.particle ? inverse_inertia(f_.shared, i) : zero_mat();
        const vec3 dw = spin_change(br, inv, Pi), dv = centre_velocity_change(br, Pi, dw);
        r.velocity[i] = b.velocity + dv;
        r.angular_velocity[i] = b.angular_velocity + dw;
        if (const pivot *pv = q.pivot_of(i)) {
            vec3 &R = r.pivot_impulses[static_cast<std::size_t>(pv - q.pivots.data())];
            R = pivot_impulse(br, Pi, dv);
            if (q.dimension == 2)
                R[2] = 0;
        }
    }
    return r;
}

// The energy lost by the bodies of finite mass for the impulse sel_P: minus the work
// of the contact impulse, 1/2 Pi.(a + a') for a free body (Pi its impulse, a and a'
// the velocities of its material point at O before and after), and for a pinned body
// 1/2 m dv.(v + v') + 1/2 dw.I (w + w') (its pivot's impulse may work too).
ex writer::energy_lost(const after_state &after) const
{
    const problem &q = q_;
    ex work = 0;
    for (std::size_t i : {q.contact().body1, q.contact().body2}) {
        const body &b = q.bodies[i];
        if (b.infinite_mass || q.immovable(i))
            continue;
        const ex s = i == q.contact().body1 ? ex(-1) : ex(1);
        const vec3 &v1 = after.velocity[i], &w1 = after.angular_velocity[i];
        if (q.pivot_of(i)) {
            const vec3 dv = v1 - b.velocity, dw = w1 - b.angular_velocity;
            work += b.mass * dot(dv, v1 + b.velocity) / 2 + dot(dw, mul(b.inertia, w1 + b.angular_velocity)) / 2;
            continue;
        }
        vec3 Pi = zero_vec();
        for (std::size_t a = 0; a < sel_P_.size(); ++a)
            Pi[a] = s * sel_P_[a];
        const vec3 before = point_velocity(b, b.velocity, b.angular_velocity, q.contact().point);
        const vec3 after = point_velocity(b, v1, w1, q.contact().point);
        work += dot(Pi, before + after) / 2;
    }
    return -work;
}

// Powers of stage A values with a negative or fractional exponent become links; so do
// the stage A steps an expression of stage B, C or S uses (linked in name_links).
ex writer::linkify(const ex &e)
{
    if (is_a<power>(e) && is_a<numeric>(e.op(1))) {
        const numeric x = ex_to<numeric>(e.op(1));
        if ((x.is_negative() || !x.is_integer()) && !depends_on(e.op(0), local_)) {
            exset syms;
            collect_symbols(e, syms);
            if (!syms.empty()) {
                for (const auto &[value, sym] : power_links_)
                    if (value.is_equal(e))
                        return sym;
                symbol s("friction_link");
                power_links_.push_back({e, s});
                return s;
            }
        }
    }
    if (is_a<symbol>(e) || is_a<numeric>(e) || e.nops() == 0)
        return e;
    struct mapper : map_function {
        writer *w;
        explicit mapper(writer *w_) : w(w_) {}
        ex operator()(const ex &x) override { return w->linkify(x); }
    } m(this);
    return e.map(m);
}

// Names the links in a canonical order: by the canonical key of their values.
void writer::name_links()
{
    canonical_pool scratch;
    std::map<ex, std::string, ex_is_less> names = input_ident_;
    for (const auto &[sym, nm] : step_name_)
        names[sym] = nm;
    scratch.set_input_names(names);
    std::vector<std::pair<std::string, std::size_t>> keyed;
    for (std::size_t i = 0; i < power_links_.size(); ++i) {
        const scaled s = scratch.convert(power_links_[i].first);
        keyed.push_back({number_text(s.scale) + "*" + (s.node >= 0 ? scratch.at(s.node).key : std::string()), i});
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t k = 0; k < keyed.size(); ++k) {
        const auto &pl = power_links_[keyed[k].second];
        link_names_[pl.second] = scope_.claim("lk_" + std::to_string(k + 1));
        link_order_.push_back(pl.second);
        link_value_[pl.second] = pl.first;
    }
    // The stage A steps used downstream, in stage A's order.
    exset used;
    auto collect = [&](const ex &e) { collect_symbols(e, used); };
    for (const ex &v : c_values_)
        collect(v);
    if (!is_a<numeric>(q_.contact().friction())) { // stage S is written only when mu may be 0
        collect(s_D0_);
        collect(s_N0_value_);
        for (const ex &v : s_P0_)
            collect(v);
    }
    for (const step &st : b_steps_linked_)
        collect(st.value);
    collect(b_N_);
    for (const ex &v : b_P_)
        collect(v);
    for (const ex &v : b_F_)
        collect(v);
    for (const ex &v : b_cond_)
        collect(v);
    for (std::size_t i = 0; i < a_steps_.size(); ++i)
        if (used.count(a_steps_[i].sym)) {
            link_names_[a_steps_[i].sym] = scope_.claim("lk_" + a_step_names_[i]);
            link_order_.push_back(a_steps_[i].sym);
            link_value_[a_steps_[i].sym] = a_steps_[i].sym;
        }
}

// The input names of a downstream stage: the inputs, the links, and extra locals.
void writer::downstream_names(stage &s, const std::map<ex, std::string, ex_is_less> &extra)
{
    std::map<ex, std::string, ex_is_less> names = input_ident_;
    for (const auto &[sym, nm] : link_names_)
        names[sym] = nm;
    for (const auto &[sym, nm] : extra)
        names[sym] = nm;
    s.pool.set_input_names(names);
}

void writer::build_stage_a()
{
    const problem &q = q_;
    const int dim = q.dimension;
    a_.pool.set_input_names(input_ident_);
    for (std::size_t i = 0; i < a_steps_.size(); ++i)
        a_.bind_step(a_steps_[i], a_step_names_[i]);
    add_checks(a_, a_steps_);
    if (!det_K_.is_zero()) {
        // det K as a value: the stick candidate exists where it is > 0 (only that candidate is
        // dropped where it is not); K itself must be in range: n.K n > 0, finite (singular, as
        // the smooth header's k > 0), so that K scaled by it is finite.
        add_check(a_, s_D0_, check::positive, "singular", "n.K n > 0, finite (the contact response in range)");
        det_K_name_ = scope_.claim("stick_det_K");
        a_.output(det_K_name_, det_K_);
    }
    // mu as a value (when it is not simply an input or a number)
    const ex &mu = q.contact().friction();
    if (is_a<symbol>(mu) && input_ident_.count(mu)) {
        mu_name_ = input_ident_.at(mu);
    } else if (is_a<numeric>(mu)) {
        mu_name_.clear();
    } else {
        mu_name_ = scope_.claim("mu_value");
        a_.output(mu_name_, mu);
    }
    if (process_jacobian()) { // the scales of the conditions' rounding
        speed_name_ = scope_.claim("scale_speed");
        a_.output(speed_name_, cp_.jacobian.process->speed);
        response_name_ = scope_.claim("scale_response");
        a_.output(response_name_, cp_.jacobian.process->response);
    }
    // Candidates in closed form and the conditions of each.
    for (std::size_t i = 0; i < f_.cases.size(); ++i) {
        const regime_case &c = f_.cases[i];
        case_names cn;
        cn.prefix = case_prefix(c);
        if (static_cast<int>(i) == angle_) {
            names_.push_back(cn);
            continue;
        }
        cn.N = scope_.claim("c_" + cn.prefix + "N");
        a_.output(cn.N, c.sol.normal_impulse);
        for (int a = 0; a < dim; ++a) {
            const std::string ax = q.axes[static_cast<std::size_t>(a)];
            cn.P.push_back(scope_.claim("c_" + cn.prefix + "P_" + ax));
            a_.output(cn.P.back(), c.impulse[static_cast<std::size_t>(a)]);
            cn.F.push_back(scope_.claim("c_" + cn.prefix + "F_" + ax));
            a_.output(cn.F.back(), c.tangential_impulse[static_cast<std::size_t>(a)]);
        }
        for (std::size_t j = 0; j < c.conditions.size(); ++j) {
            cn.cond.push_back(scope_.claim("c_" + cn.prefix + "cond" + std::to_string(j + 1)));
            a_.output(cn.cond.back(), c.conditions[j].value);
        }
        names_.push_back(cn);
    }
    // The angle equation's coefficients.
    if (angle_ >= 0)
        angle_outputs();
    // Links: aliases of stage A values.
    for (const ex &s : link_order_)
        a_.output(link_names_.at(s), link_value_.at(s));
}

// Stage A's outputs for the slide without closed form: the coefficients of its angle
// equation, of the filter lambda D, and the values that show the solution unique.
void writer::angle_outputs()
{
    const problem &q = q_;
    const regime_case &c = f_.cases[static_cast<std::size_t>(angle_)];
    // g is a polynomial of degree 2 in (c, s) (g = n.(h x d), h and d of degree 1): its
    // coefficients by differentiation at c = s = 0, which keeps the factored form of
    // the closed form (expanding it multiplies out every product of sums).
    const ex &g = c.angle_equation;
    const lst zero{c.dir_c == 0, c.dir_s == 0};
    auto at0 = [&](const ex &x) { return x.subs(zero); };
    const ex gc = g.diff(c.dir_c), gs = g.diff(c.dir_s);
    const ex c00 = at0(g), c10 = at0(gc), c01 = at0(gs), c20 = at0(gc.diff(c.dir_c)) / 2,
             c02 = at0(gs.diff(c.dir_s)) / 2, c11 = at0(gc.diff(c.dir_s));
    const ex coef[5] = {c00 + (c20 + c02) / 2, c10, c01, (c20 - c02) / 2, c11 / 2};
    const char *nm[5] = {"trig_a0", "trig_a1", "trig_b1", "trig_a2", "trig_b2"};
    for (int k = 0; k < 5; ++k) {
        trig_names_.push_back(scope_.claim(nm[k]));
        a_.output(trig_names_.back(), coef[k]);
    }
    // The filter: lambda D = D (u.d) + a (Q.d), Q = K (n - mu d), D = n.Q, a = -(1 + e) u_n,
    // of the same form; a slide holds only where it is > 0 (lambda > 0 and D > 0), so
    // the root finder may leave out the arcs where it is negative throughout.
    mat3 K = zero_mat();
    ex un;
    for (const step &x : f_.shared.steps) {
        if (x.role == step_role::contact_response)
            K[static_cast<std::size_t>(x.row)][static_cast<std::size_t>(x.column)] =
                K[static_cast<std::size_t>(x.column)][static_cast<std::size_t>(x.row)] = x.sym;
        if (x.role == step_role::approach_velocity)
            un = x.sym;
    }
    vec3 u = zero_vec(), dir = zero_vec(), m = zero_vec();
    for (std::size_t a = 0; a < 3; ++a) {
        u[a] = tidy(d_.vB[a] - d_.vA[a]);
        dir[a] = c.dir_c * f_.e_t[a] + c.dir_s * f_.e_b[a];
        m[a] = d_.n_hat[a] - q.contact().friction() * dir[a];
    }
    const vec3 Q = mul(K, m);
    const ex Lambda = dot(d_.n_hat, Q) * dot(u, dir) - (1 + q.restitution) * un * dot(Q, dir);
    const ex Lc = Lambda.diff(c.dir_c), Ls = Lambda.diff(c.dir_s);
    const ex l00 = at0(Lambda), l10 = at0(Lc), l01 = at0(Ls), l20 = at0(Lc.diff(c.dir_c)) / 2,
             l02 = at0(Ls.diff(c.dir_s)) / 2, l11 = at0(Lc.diff(c.dir_s));
    const ex lcoef[5] = {l00 + (l20 + l02) / 2, l10, l01, (l20 - l02) / 2, l11 / 2};
    for (int k = 0; k < 5; ++k) {
        keep_names_.push_back(scope_.claim("keep_" + std::to_string(k)));
        a_.output(keep_names_.back(), lcoef[k]);
    }
    // When the solution is provably unique (detail::slide_direction): with
    // a = -(1 + e) u_n, tau = P_t / N (|tau| <= mu), D(tau) = K_nn + K_nt.tau and
    // N = a / D(tau), u'_t / N = (b + M tau) / a with b = a K_tn + u_t K_nn and
    // M = a K_tt + u_t K_nt^T (tangential axes t, b). A solution (N > 0) has
    // -(b + M tau) in the normal cone of the disc |tau| <= mu at tau, so it solves the
    // variational inequality of b + M tau on the disc cut to D(tau) >= delta (any
    // delta below its D): if M + M^T is positive definite that inequality has one
    // solution only, so the law has at most one. Tested with a margin
    // (31 M11 M22 >= 32 ((M12 + M21) / 2)^2) so that rounding cannot pass a problem
    // that is not; then a stick candidate that holds is the answer, and otherwise the
    // slide's direction is the root of one monotone scalar equation.
    const vec3 nh = d_.n_hat;
    const ex a = -(1 + q.restitution) * un;
    auto Kdot = [&](const vec3 &x, const vec3 &y) { return dot(x, mul(K, y)); };
    const ex Knn = Kdot(nh, nh), Knt = Kdot(f_.e_t, nh), Knb = Kdot(f_.e_b, nh);
    const ex Ktt = Kdot(f_.e_t, f_.e_t), Ktb = Kdot(f_.e_t, f_.e_b), Kbb = Kdot(f_.e_b, f_.e_b);
    const ex ut = dot(u, f_.e_t), ub = dot(u, f_.e_b);
    const ex &mu = q.contact().friction();
    const ex M11 = a * Ktt + ut * Knt, M12 = a * Ktb + ut * Knb, M21 = a * Ktb + ub * Knt, M22 = a * Kbb + ub * Knb;
    const ex fast[7] = {mu * M11,
                        mu * M12,
                        mu * M21,
                        mu * M22,
                        a * Knt + ut * Knn,
                        a * Knb + ub * Knn,
                        31 * M11 * M22 - 8 * (M12 + M21) * (M12 + M21)};
    const char *fnm[7] = {"slide_m11", "slide_m12", "slide_m21",      "slide_m22",
                          "slide_b1",  "slide_b2",  "unique_monotone"};
    for (int k = 0; k < 7; ++k) {
        fast_names_.push_back(scope_.claim(fnm[k]));
        a_.output(fast_names_.back(), fast[k]);
    }
}

void writer::build_stage_b()
{
    if (angle_ < 0)
        return;
    const regime_case &c = f_.cases[static_cast<std::size_t>(angle_)];
    const int dim = q_.dimension;
    dir_c_name_ = scope_.claim("c_d");
    dir_s_name_ = scope_.claim("s_d");
    downstream_names(b_, {{c.dir_c, dir_c_name_}, {c.dir_s, dir_s_name_}});
    for (std::size_t i = 0; i < b_steps_linked_.size(); ++i)
        b_.bind_step(b_steps_linked_[i], b_step_names_[i]);
    case_names &cn = names_[static_cast<std::size_t>(angle_)];
    cn.N = scope_.claim("c_slide_N");
    b_.output(cn.N, b_N_);
    for (int a = 0; a < dim; ++a) {
        const std::string ax = q_.axes[static_cast<std::size_t>(a)];
        cn.P.push_back(scope_.claim("c_slide_P_" + ax));
        b_.output(cn.P.back(), b_P_[static_cast<std::size_t>(a)]);
        cn.F.push_back(scope_.claim("c_slide_F_" + ax));
        b_.output(cn.F.back(), b_F_[static_cast<std::size_t>(a)]);
    }
    for (std::size_t j = 0; j < b_cond_.size(); ++j) {
        cn.cond.push_back(scope_.claim("c_slide_cond" + std::to_string(j + 1)));
        b_.output(cn.cond.back(), b_cond_[j]);
    }
}

void writer::build_stage_s()
{
    if (mu_name_.empty())
        return; // a constant mu > 0: never smooth
    downstream_names(s_, {});
    s_D0_name_ = scope_.claim("D_0");
    step d0;
    d0.sym = symbol("friction_D0");
    d0.value = s_D0_;
    s_.bind_step(d0, s_D0_name_);
    step n0;
    n0.sym = ex_to<symbol>(s_N0_);
    n0.value = s_N0_value_.subs(s_D0_ == d0.sym);
    const std::string n0_name = scope_.claim("N_0");
    s_.bind_step(n0, n0_name);
    if (det_K_.is_zero()) // (else stage A checked it)
        add_check(s_, d0.sym, check::positive, "singular", "mu = 0: n.K n > 0, finite");
    s_.output(sel_N_name_, n0.sym);
    for (std::size_t a = 0; a < s_P0_.size(); ++a) {
        s_.output(sel_P_names_[a], s_P0_[a]);
        s_.output(sel_F_names_[a], 0);
    }
}

void writer::build_stage_c()
{
    std::map<ex, std::string, ex_is_less> extra;
    for (std::size_t a = 0; a < sel_P_.size(); ++a) {
        extra[sel_P_[a]] = sel_P_names_[a];
        extra[sel_F_[a]] = sel_F_names_[a];
    }
    extra[sel_N_] = sel_N_name_;
    downstream_names(c_, extra);
    for (std::size_t k = 0; k < outs_.size(); ++k)
        c_.output(outs_[k].field, c_values_[k]);
}

void writer::build_unchanged()
{
    u_.pool.set_input_names(input_ident_);
    for (std::size_t k = 0; k < outs_.size(); ++k)
        u_.output(outs_[k].field, outs_[k].tangential ? ex(0) : pl_.unchanged[outs_[k].base]);
}

// A stage's code with its outputs placed as the function uses them; the names it
// declares are claimed.
void writer::emit_one(stage &s, const emit_options &how, bool counted)
{
    s.em = emit_cpp(s.prog, s.outs, s.checks, s.names, scope_.names(), how);
    for (const std::string &nm : s.em.declared)
        if (!scope_.taken(nm))
            scope_.claim(nm);
    if (counted)
        add_counts(total_, s.em.formula);
}

// Stages A, B and the normal's basis declare their outputs as locals; stage S assigns
// the selected impulse (declared before it); stage C writes the result, the energy
// lost under with_energy_lost.
void writer::emit_stages()
{
    emit_options locals, assign, result;
    locals.outputs = output_placement::local;
    assign.outputs = output_placement::assign;
    for (std::size_t k = 0; k < outs_.size(); ++k)
        if (outs_[k].kind == output_value::energy_lost)
            result.energy_output = static_cast<int>(k);
    if (!basis_names_.empty())
        nb_.em = emit_cpp(nb_.prog, nb_.outs, {}, {}, scope_.names(), locals);
    const std::vector<std::string> before_a = scope_.names();
    emit_one(a_, locals);
    if (angle_ >= 0)
        emit_one(b_, locals);
    if (!mu_name_.empty())
        emit_one(s_, assign);
    emit_one(c_, result);
    u_.em = emit_cpp(u_.prog, u_.outs, {}, {}, scope_.names());
    // Stage A of the unchecked variant: the same names as stage A where it declares no
    // name stage A does not (the stages after it are written with stage A's declared);
    // else names of its own.
    a_unchecked_ = emit_cpp(a_.prog, a_.outs, state_checks(a_.checks), a_.names, before_a, locals);
    const std::set<std::string> declared(a_.em.declared.begin(), a_.em.declared.end());
    if (!std::all_of(a_unchecked_.declared.begin(), a_unchecked_.declared.end(),
                     [&](const std::string &nm) { return declared.count(nm) > 0; })) {
        a_unchecked_ = emit_cpp(a_.prog, a_.outs, state_checks(a_.checks), a_.names, scope_.names(), locals);
        for (const std::string &nm : a_unchecked_.declared)
            if (!scope_.taken(nm))
                scope_.claim(nm);
    }
    count_name_ = scope_.claim("n_holding");
    stick_holds_name_ = scope_.claim("stick_holds");
    if (!det_K_name_.empty())
        stick_possible_name_ = scope_.claim("stick_possible");
    regime_name_ = scope_.claim("regime_now");
    roots_c_name_ = scope_.claim("root_c");
    roots_s_name_ = scope_.claim("root_s");
    n_roots_name_ = scope_.claim("n_roots");
    every_name_ = scope_.claim("every_direction");
    edge_name_ = scope_.claim("stick_edge");
    loop_name_ = scope_.claim("k");
    apart_name_ = scope_.claim("n_apart");
    at_stick_name_ = scope_.claim("at_stick");
    merge_name_ = scope_.claim("merge");
    near_name_ = scope_.claim("slide_near");
    slides_finite_name_ = scope_.claim("slides_finite");
    keep_array_name_ = scope_.claim("keep");
    unique_name_ = scope_.claim("unique");
    pass_name_ = scope_.claim("pass");
}

} // namespace impactgen::codegen::writer_detail
