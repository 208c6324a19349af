#include "friction.hpp"
#include "contact_law.hpp"
#include "system.hpp"

#include "decide.hpp"
#include "names/escape.hpp"
#include "response.hpp"
#include "routh.hpp"

#include <cctype>
#include <cmath>
#include <functional>
#include <sstream>

namespace impactgen
{
using namespace GiNaC;

const char *regime_name(regime r)
{
    switch (r) {
    case regime::smooth:
        return "smooth";
    case regime::stick:
        return "stick";
    case regime::slide:
        return "slide";
    }
    return "?";
}

namespace
{

// One body of the contact: its response (response.hpp) with the inverse inertia as the
// steps keep it.
using side = contact_side;

// Change of the contact point's velocity for the impulse P on this body.
vec3 point_response(const side &sd, const vec3 &P)
{
    return point_velocity_change(sd.r, sd.inv, P);
}

vec3 unit_axis(int a)
{
    vec3 e = zero_vec();
    e[a] = 1;
    return e;
}

// The shared part: sides, K, u, u_n (steps in s).
struct shared_part {
    std::array<side, 2> sides;
    mat3 K = zero_mat(); // entries: steps or inline values
    vec3 u = zero_vec(); // relative velocity of the contact points, world
    ex un;               // u . n_hat (step)
};

shared_part build_shared(const derivation &d, solution &s, step_builder &sb)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const vec3 &O = p.contact().point;
    shared_part sh;
    sh.sides[0].r = response_of(p, p.contact().body1, O);
    sh.sides[0].sign = -1;
    sh.sides[1].r = response_of(p, p.contact().body2, O);
    sh.sides[1].sign = 1;
    for (side &sd : sh.sides) {
        const std::size_t index = sd.r.index;
        const body &b = p.bodies[index];
        if (!sd.r.movable || sd.r.particle)
            continue;
        const std::string L = b.label;
        const mat3 &J = sd.r.inertia;
        if (dim == 2) {
            ex Iz = sd.r.pinned
                        ? sb.add(step_role::pivot_inertia, index, 2, 2, "I_E" + label_subscript(L),
                                 "I_{E" + label_subscript_tex(L) + "}", J[2][2],
                                 "moment of inertia of " + display_name(b) + " about its pivot E: I_C + m |C - E|^2")
                        : J[2][2];
            sd.inv[2][2] = 1 / Iz;
            continue;
        }
        bool diagonal = true;
        for (int a = 0; a < 3; ++a)
            for (int c = a + 1; c < 3; ++c)
                diagonal = diagonal && tidy(J[a][c]).is_zero() && tidy(J[c][a]).is_zero();
        if (diagonal) {
            for (int a = 0; a < 3; ++a)
                sd.inv[a][a] = 1 / tidy(J[a][a]);
            continue;
        }
        mat3 Js;
        for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c)
                Js[a][c] = tidy(J[a][c]);
        const mat3 adj = adjugate(Js);
        ex D = sb.add(step_role::inertia_determinant, sd.r.index, -1, -1, "D_" + L,
                      "D_{" + label_subscript_tex(L) + "}", det(Js),
                      "determinant of the inertia tensor of " + display_name(b) + (sd.r.pinned ? " about E" : ""));
        for (int a = 0; a < 3; ++a)
            for (int c = a; c < 3; ++c) {
                ex v = sb.add(step_role::inverse_inertia, sd.r.index, a, c,
                              "J_" + p.axes[a] + p.axes[c] + label_subscript(L),
                              "J_{" + p.axes[a] + p.axes[c] + label_subscript_tex(L) + "}", adj[a][c] / D,
                              "inverse inertia tensor of " + display_name(b) + (sd.r.pinned ? " about E" : "") +
                                  ", entry " + p.axes[a] + p.axes[c]);
                sd.inv[a][c] = v;
                sd.inv[c][a] = v;
            }
    }
    // K = K_1 + K_2, symmetric: u' = u + K P.
    for (int b = 0; b < dim; ++b) {
        vec3 col = point_response(sh.sides[0], unit_axis(b)) + point_response(sh.sides[1], unit_axis(b));
        for (int a = 0; a <= b; ++a) {
            ex v = sb.add(step_role::contact_response, no_body, a, b, "K_" + p.axes[a] + p.axes[b],
                          "K_{" + p.axes[a] + p.axes[b] + "}", tidy(col[a]),
                          "contact response K_" + p.axes[a] + p.axes[b] +
                              ": change of the relative contact velocity along " + p.axes[a] +
                              " per unit impulse along " + p.axes[b] + " on body 2 (and its opposite on body 1)",
                          true);
            sh.K[a][b] = v;
            sh.K[b][a] = v;
        }
    }
    // A normal along +e_a: u's component a is the normal velocity of approach itself, one
    // step u_n (not u_n and an alias of it, u_n_ = u_n, where the world axes are t, n, b).
    int normal_axis = -1;
    for (int a = 0; a < dim; ++a)
        if (d.n_hat[a].is_equal(1))
            normal_axis = a;
    for (int a = 0; a < dim; ++a)
        if (a == normal_axis)
            sh.u[a] = sh.un =
                sb.add(step_role::approach_velocity, no_body, -1, -1, "u_n", "u_{n}", tidy(d.vB[a] - d.vA[a]),
                       "normal velocity of approach u.n before impact (negative for an impact)", true);
        else
            sh.u[a] =
                sb.add(step_role::relative_velocity, no_body, a, -1, "u_" + p.axes[a], "u_{" + p.axes[a] + "}",
                       tidy(d.vB[a] - d.vA[a]),
                       "relative velocity v_B - v_A of the contact points before impact, " + p.axes[a] + " component");
    if (normal_axis < 0)
        sh.un = sb.add(step_role::approach_velocity, no_body, -1, -1, "u_n", "u_{n}", tidy(dot(sh.u, d.n_hat)),
                       "normal velocity of approach u.n before impact (negative for an impact)", true);
    (void)s;
    return sh;
}

// Bodies after impact, pivot impulses and energies for the impulse P (world, on body 2).
void finish_case(const derivation &d, const shared_part &sh, regime_case &c)
{
    apply_impulse(d, sh.sides, c, false);
}

void add_tangential(const derivation &d, regime_case &c, step_builder &sb, const ex &Pn)
{
    const problem &p = d.prob;
    for (int a = 0; a < 3; ++a)
        c.tangential_impulse[a] = 0;
    if (p.dimension == 2) {
        for (int a = 0; a < 2; ++a)
            c.tangential_impulse[a] = c.tangential_scalar * d.t_dir[a];
        return;
    }
    for (int a = 0; a < 3; ++a)
        c.tangential_impulse[a] =
            sb.add(step_role::tangential_impulse, no_body, a, -1, "F_" + p.axes[a], "F_{" + p.axes[a] + "}",
                   c.impulse[a] - Pn * d.n_hat[a],
                   "tangential (friction) impulse P - N n on body 2, " + p.axes[a] + " component");
}

// The stick candidate, or false with `why` set when the contact response K is singular.
bool stick_case(const derivation &d, const solution &shared_steps, const shared_part &sh, const ex &mu, regime_case &c,
                std::string &why)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    c.kind = regime::stick;
    c.name = "stick";
    c.sol.steps = shared_steps.steps;
    step_builder sb(c.sol, p);
    const ex e = p.restitution;
    const vec3 &n = d.n_hat;
    // K P = -(u + e u_n n): u'_t = 0 and u'_n = -e u_n.
    vec3 rhs = zero_vec();
    for (int a = 0; a < dim; ++a)
        rhs[a] = -(sh.u[a] + e * sh.un * n[a]);
    mat3 K = sh.K;
    if (dim == 2)
        K[2][2] = 1; // the 2x2 block: det and adjugate of diag(K2, 1)
    const ex detK = det(K);
    const std::string where = p.source.empty() ? std::string("contact") : names::display_text(p.source) + ": contact";
    if (vanishes_identically(c.sol, detK, where + ": the determinant of the contact response K")) {
        // K P = rhs solvable (rhs in the range of K: adj(K) rhs = 0): sticking holds with an
        // impulse that is not determined (the pivot takes any friction impulse in the cone).
        const vec3 residue = mul(adjugate(K), rhs);
        bool consistent = true;
        for (int a = 0; a < dim && consistent; ++a)
            consistent = vanishes_identically(c.sol, residue[a], where + ": the stick system");
        if (consistent)
            throw input_error(where + ".friction: the contact response K is singular (a body pinned at a fixed point "
                                      "against a body that cannot move) and the contact point cannot move "
                                      "tangentially: the velocities after impact are those without friction, but "
                                      "the tangential impulse is not determined (the pivot takes any friction "
                                      "impulse inside the cone); solve it without friction");
        why = "the contact response K is singular (a body pinned at a fixed point against a body that cannot "
              "move: its contact point can only move across the line from the pivot), so no impulse stops the "
              "tangential slip while the normal velocity obeys restitution: sticking is not a candidate";
        return false;
    }
    ex D = sb.add(step_role::response_determinant, no_body, -1, -1, "D_K", "D_{K}", detK,
                  "determinant of the contact response K (stick: K P = -(u + e u_n n))", true);
    const mat3 adj = adjugate(K);
    vec3 P = zero_vec();
    for (int a = 0; a < dim; ++a) {
        ex v = 0;
        for (int b = 0; b < dim; ++b)
            v += adj[a][b] * rhs[b];
        P[a] = sb.add(step_role::impulse_component, no_body, a, -1, "P_" + p.axes[a], "P_{" + p.axes[a] + "}", v / D,
                      "contact impulse on body 2 when sticking, " + p.axes[a] + " component", true);
    }
    c.impulse = P;
    ex Pn = sb.add(step_role::normal_impulse, no_body, -1, -1, "N", "N", dot(P, n),
                   "normal impulse P.n, on body 2 along +n, on body 1 along -n", true);
    c.sol.normal_impulse = Pn;
    if (dim == 2) {
        c.tangential_scalar = sb.add(step_role::tangential_impulse, no_body, -1, -1, "F", "F", dot(P, d.t_dir),
                                     "tangential (friction) impulse P.e_t on body 2", true);
        add_tangential(d, c, sb, Pn);
        c.conditions.push_back({mu * Pn - c.tangential_scalar, false,
                                "mu N - F >= 0 (the impulse inside the friction cone)", condition_kind::cone_below});
        c.conditions.push_back({mu * Pn + c.tangential_scalar, false,
                                "mu N + F >= 0 (the impulse inside the friction cone)", condition_kind::cone_above});
    } else {
        c.tangential_scalar = 0;
        add_tangential(d, c, sb, Pn);
        c.conditions.push_back({Pn, false, "N >= 0 (the contact pushes)", condition_kind::pushes});
        c.conditions.push_back({mu * mu * Pn * Pn - dot(c.tangential_impulse, c.tangential_impulse), false,
                                "mu^2 N^2 - |F|^2 >= 0 (the impulse inside the friction cone)", condition_kind::cone});
    }
    c.direction = zero_vec();
    c.sliding_speed = 0;
    finish_case(d, sh, c);
    return true;
}

// A slide along the unit tangent direction dir (world; may contain dir_c, dir_s).
regime_case slide_case(const derivation &d, const solution &shared_steps, const shared_part &sh, const ex &mu,
                       const vec3 &dir, const std::string &name, int sign, bool needs_angle, const symbol *cs = nullptr)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    regime_case c;
    c.kind = regime::slide;
    c.sign = sign;
    c.name = name;
    c.needs_angle = needs_angle;
    if (cs) {
        c.dir_c = cs[0];
        c.dir_s = cs[1];
    }
    c.sol.steps = shared_steps.steps;
    step_builder sb(c.sol, p);
    const ex e = p.restitution;
    const vec3 &n = d.n_hat;
    c.direction = dir;
    vec3 m = zero_vec(); // n - mu d: the direction of P
    for (int a = 0; a < dim; ++a)
        m[a] = n[a] - mu * dir[a];
    const vec3 Q = mul(sh.K, m); // u' = u + P_n Q
    ex D = sb.add(step_role::slide_denominator, no_body, -1, -1, "D_s", "D_{s}", dot(n, Q),
                  "normal response while sliding: n.K(n - mu d) (must be > 0)", true);
    ex Pn = sb.add(step_role::normal_impulse, no_body, -1, -1, "N", "N", -(1 + e) * sh.un / D,
                   "normal impulse -(1 + e) u_n / D_s, on body 2 along +n", true);
    c.sol.normal_impulse = Pn;
    vec3 P = zero_vec();
    for (int a = 0; a < dim; ++a)
        P[a] = sb.add(step_role::impulse_component, no_body, a, -1, "P_" + p.axes[a], "P_{" + p.axes[a] + "}",
                      Pn * m[a], "contact impulse N (n - mu d) on body 2, " + p.axes[a] + " component", true);
    c.impulse = P;
    if (dim == 2) {
        c.tangential_scalar =
            sb.add(step_role::tangential_impulse, no_body, -1, -1, "F", "F", -ex(sign) * mu * Pn,
                   "tangential (friction) impulse on body 2 along e_t: -mu N times the sign of u'_t", true);
        for (int a = 0; a < 3; ++a)
            c.tangential_impulse[a] = 0;
        for (int a = 0; a < 2; ++a)
            c.tangential_impulse[a] = c.tangential_scalar * d.t_dir[a];
    } else {
        c.tangential_scalar = 0;
        for (int a = 0; a < 3; ++a)
            c.tangential_impulse[a] = -mu * Pn * dir[a];
    }
    vec3 after = zero_vec();
    for (int a = 0; a < dim; ++a)
        after[a] = sh.u[a] + Pn * Q[a];
    c.sliding_speed = sb.add(step_role::separation_velocity, no_body, -1, -1, "lambda", "\\lambda", dot(after, dir),
                             "sliding speed u'.d after impact (must be > 0)", true);
    c.conditions.push_back({D, true, "D_s > 0 (the normal impulse N is positive)", condition_kind::slide_denominator});
    c.conditions.push_back({c.sliding_speed, true, "lambda = u'_t.d > 0 (the contact slides along d after impact)",
                            condition_kind::slides});
    if (needs_angle) {
        // g = n.(h x d), h = D u + a K (n - mu d): u'_t parallel to d.
        const ex Dv = dot(n, Q);
        const ex a = -(1 + e) * sh.un;
        vec3 h = zero_vec();
        for (int k = 0; k < 3; ++k)
            h[k] = Dv * sh.u[k] + a * Q[k];
        c.angle_equation = dot(n, cross(h, dir));
    }
    finish_case(d, sh, c);
    return c;
}

// The sign of a condition's value. decide() refuses a value whose terms' magnitude bound
// leaves double's range (a term of 10^-400 inside a condition of size 3, from a tiny mu);
// a condition's value is never printed, only its sign: then CLN floats decide it, at 60
// and 120 digits (their exponent range is unbounded), when both agree to 30 digits.
decision condition_sign(const ex &v)
{
    decision d = decide(v);
    if (d != decision::out_of_range && d != decision::undecided)
        return d;
    const long saved = Digits;
    ex a, b;
    try {
        Digits = 60;
        a = v.evalf();
        Digits = 120;
        b = v.evalf();
    } catch (...) {
        Digits = saved;
        return d;
    }
    Digits = saved;
    if (!is_a<numeric>(a) || !is_a<numeric>(b) || !ex_to<numeric>(a).is_real() || !ex_to<numeric>(b).is_real())
        return d;
    const numeric x = ex_to<numeric>(a), y = ex_to<numeric>(b);
    if (y.is_zero() || abs(x - y) > abs(y) * numeric(1, 10).power(30))
        return d;
    return y.is_positive() ? decision::positive : decision::negative;
}

// Evaluates the case's steps in order for the input values (none for a numeric
// problem) and decides its conditions; stops at the first denominator that is not
// positive. Returns false when the case does not hold; throws when undecidable.
// `values` receives the step values.
bool holds(const regime_case &c, const ex &inputs, lst &values, const std::string &where, double margin_scale = 0)
{
    for (const step &st : c.sol.steps) {
        ex v = st.value.subs(inputs).subs(values);
        v = is_constant(v) ? tidy(v) : v;
        values.append(st.sym == v);
        if (st.role == step_role::slide_denominator) {
            decision dd = margin_scale > 0 ? decide(v.evalf()) : condition_sign(v);
            if (dd == decision::not_real || dd == decision::out_of_range || dd == decision::undecided)
                throw input_error(where + ": the sign of the sliding denominator D_s " + decision_text(dd));
            if (dd != decision::positive)
                return false;
            if (margin_scale > 0 && std::abs(ex_to<numeric>(v.evalf()).to_double()) <= margin_scale)
                throw input_error(where + ": the sliding denominator D_s is too close to 0 to decide the regime");
        }
    }
    for (const regime_condition &rc : c.conditions) {
        ex v = rc.value.subs(inputs).subs(values);
        v = tidy(v);
        if (margin_scale > 0) {
            ex f = v.evalf();
            if (!is_a<numeric>(f))
                throw input_error(where + ": cannot evaluate the condition " + rc.meaning);
            double x = ex_to<numeric>(f).to_double();
            if (std::abs(x) <= margin_scale)
                throw input_error(where + ": the condition " + rc.meaning +
                                  " is too close to its boundary to decide the regime");
            if (x < 0)
                return false;
            continue;
        }
        decision dd = condition_sign(v);
        if (dd == decision::not_real || dd == decision::out_of_range || dd == decision::undecided)
            throw input_error(where + ": whether " + rc.meaning + " holds " + decision_text(dd));
        if (dd == decision::negative || (rc.strict && dd == decision::zero))
            return false;
    }
    return true;
}

// The case with every value replaced by its number (steps kept for the record).
regime_case substituted(const regime_case &c, const ex &inputs, const lst &values, bool floats = false)
{
    regime_case r = c;
    auto fix = [&](const ex &x) {
        ex v = x.subs(inputs).subs(values);
        if (floats)
            return v.evalf();
        return is_constant(v) ? tidy(v) : v;
    };
    auto fixv = [&](vec3 &v) {
        for (ex &x : v)
            x = fix(x);
    };
    for (body_state &bs : r.sol.after) {
        fixv(bs.velocity);
        fixv(bs.angular_velocity);
    }
    r.sol.normal_impulse = fix(r.sol.normal_impulse);
    for (vec3 &R : r.sol.pivot_impulses)
        fixv(R);
    fixv(r.impulse);
    fixv(r.tangential_impulse);
    fixv(r.direction);
    r.tangential_scalar = fix(r.tangential_scalar);
    r.sliding_speed = fix(r.sliding_speed);
    r.sol.energy_before = fix(r.sol.energy_before);
    r.sol.energy_after = fix(r.sol.energy_after);
    r.sol.energy_after_direct = fix(r.sol.energy_after_direct);
    r.sol.energy_lost = fix(r.sol.energy_lost);
    lst uv;
    for (const ex &rel : r.sol.unknown_values)
        uv.append(rel.lhs() == fix(rel.rhs()));
    r.sol.unknown_values = uv;
    return r;
}

} // namespace

void apply_impulse(const derivation &d, const std::array<contact_side, 2> &sides, regime_case &c, bool tidied)
{
    auto clean = [tidied](const ex &x) { return tidied ? tidy(x) : x; };
    const problem &p = d.prob;
    solution &s = c.sol;
    s.after.resize(p.bodies.size());
    for (std::size_t i = 0; i < p.bodies.size(); ++i)
        s.after[i] = {p.bodies[i].velocity, p.bodies[i].angular_velocity};
    s.pivot_impulses.assign(p.pivots.size(), zero_vec());
    for (const contact_side &sd : sides) {
        const body &b = p.bodies[sd.r.index];
        if (b.infinite_mass)
            continue;
        const vec3 Pi = ex(sd.sign) * c.impulse;
        const vec3 dw = spin_change(sd.r, sd.inv, Pi), dv = centre_velocity_change(sd.r, Pi, dw);
        for (int a = 0; a < 3; ++a) {
            s.after[sd.r.index].velocity[a] = clean(b.velocity[a] + dv[a]);
            s.after[sd.r.index].angular_velocity[a] = clean(b.angular_velocity[a] + dw[a]);
        }
        if (const pivot *pv = p.pivot_of(sd.r.index)) {
            const std::size_t k = static_cast<std::size_t>(pv - p.pivots.data());
            s.pivot_impulses[k] = pivot_impulse(sd.r, Pi, dv);
            if (p.dimension == 2)
                s.pivot_impulses[k][2] = 0;
        }
    }
    s.unknown_values = unknown_values(d, s);
    set_energies(p, s);
    s.energy_after = s.energy_after_direct;
    s.energy_lost = clean(s.energy_before - s.energy_after_direct);
}

friction_solution solve_friction(const derivation &d)
{
    const problem &p = d.prob;
    friction_solution f;
    f.mu = p.contact().friction();
    f.n_hat = d.n_hat;
    solution shared;
    step_builder sb(shared, p);
    shared_part sh = build_shared(d, shared, sb);
    const int dim = p.dimension;
    const std::string where = p.source.empty() ? std::string("contact") : names::display_text(p.source) + ": contact";
    f.shared = shared;
    regime_case stick;
    if (stick_case(d, shared, sh, f.mu, stick, f.no_stick))
        f.cases.push_back(stick);
    if (dim == 2) {
        f.e_t = d.t_dir;
        f.e_b = zero_vec();
        f.cases.push_back(slide_case(d, shared, sh, f.mu, d.t_dir, "slide along +e_t", 1, false));
        f.cases.push_back(slide_case(d, shared, sh, f.mu, ex(-1) * d.t_dir, "slide along -e_t", -1, false));
        return f;
    }
    // The unit tangent frame.
    f.e_t = d.e_t;
    f.e_b = d.e_b;
    // Isotropic and uncoupled: t.K n = b.K n = t.K b = 0 and t.K t |b|^2 = b.K b |t|^2.
    const vec3 Kn = mul(sh.K, d.n_hat), Kt = mul(sh.K, d.t_dir), Kb = mul(sh.K, d.b_dir);
    const ex tests[4] = {dot(d.t_dir, Kn), dot(d.b_dir, Kn), dot(d.t_dir, Kb),
                         dot(d.t_dir, Kt) * dot(d.b_dir, d.b_dir) - dot(d.b_dir, Kb) * dot(d.t_dir, d.t_dir)};
    f.isotropic = true;
    for (const ex &t : tests)
        f.isotropic = f.isotropic && vanishes_identically(shared, t, where + ": the isotropy of the contact response");
    if (f.isotropic) {
        // Sliding keeps the direction of u_t: d = u_t / |u_t|.
        vec3 ut = zero_vec();
        for (int a = 0; a < 3; ++a)
            ut[a] = sh.u[a] - sh.un * d.n_hat[a];
        const ex ut2 = dot(ut, ut);
        if (vanishes_identically(shared, ut2, where + ": the tangential relative velocity"))
            return f; // no tangential motion: only sticking (with P_t = 0) can hold
        solution with_speed = shared;
        step_builder sb2(with_speed, p);
        ex speed = sb2.add(step_role::relative_velocity, no_body, -1, -1, "u_s", "u_{s}", sqrt(ut2),
                           "tangential speed |u - u_n n| of the contact points before impact", true);
        vec3 dir = zero_vec();
        for (int a = 0; a < 3; ++a)
            dir[a] = sb2.add(step_role::slide_direction, no_body, a, -1, "d_" + p.axes[a], "d_{" + p.axes[a] + "}",
                             ut[a] / speed, "sliding direction u_t / |u_t|, " + p.axes[a] + " component", true);
        regime_case c = slide_case(d, with_speed, sh, f.mu, dir, "slide along u_t", 0, false);
        c.conditions.insert(c.conditions.begin(), {speed, true, "u_s > 0 (the contact points move tangentially)"});
        f.cases.push_back(c);
        return f;
    }
    symbol cs[2] = {symbol("c_d", "c_{d}"), symbol("s_d", "s_{d}")};
    vec3 dir = zero_vec();
    for (int a = 0; a < 3; ++a)
        dir[a] = cs[0] * f.e_t[a] + cs[1] * f.e_b[a];
    f.cases.push_back(slide_case(d, shared, sh, f.mu, dir, "slide", 0, true, cs));
    return f;
}

const regime_case *impact_solution::stick() const
{
    for (const regime_case &c : cases)
        if (c.kind == regime::stick)
            return &c;
    return nullptr;
}

impact_solution solve_impact(const derivation &d)
{
    refuse_system_for(d.prob, "the one-contact solver (explain, codegen)");
    return solve_law_of(d); // the contact law's candidates (contact_law.hpp)
}

decision decide_condition(const ex &value)
{
    return condition_sign(value);
}

regime_case select_candidate(const derivation &d, const impact_solution &s)
{
    if (s.cases.size() == 1 && s.cases.front().kind == regime::smooth && s.cases.front().conditions.empty())
        return s.cases.front();
    // Routh's process of a numeric problem: its one phase sequence, decided exactly (routh.hpp).
    if (follows_process(s.law) && s.cases.size() == 1 && s.cases.front().process_conditions.empty())
        return s.cases.front();
    return select_regime(d, s);
}

std::vector<ex> condition_values(const regime_case &c, const ex &input_values)
{
    lst values;
    for (const step &st : c.sol.steps)
        values.append(st.sym == st.value.subs(input_values).subs(values));
    std::vector<ex> r;
    for (const regime_condition &rc : c.conditions)
        r.push_back(rc.value.subs(input_values).subs(values));
    return r;
}

namespace
{

// The roots in [0, 2 pi) of g(t) = a0 + a1 cos t + b1 sin t + a2 cos 2t + b2 sin 2t, at the
// current Digits. Each root is isolated with Lipschitz bounds (|g'| <= L1, |g''| <= L2): an
// interval where |g(a)| + |g(b)| > L1 (b - a) holds no root; one where g changes sign and
// |g'(a)| + |g'(b)| > L2 (b - a) holds exactly one, found by bisection. Throws when a root
// cannot be isolated (a double root: the regimes meet there).
std::vector<numeric> trig_roots(const numeric a[5], const std::string &where)
{
    const numeric two_pi = numeric(2) * ex_to<numeric>(Pi.evalf());
    auto g = [&](const numeric &t) {
        return a[0] + a[1] * cos(t) + a[2] * sin(t) + a[3] * cos(2 * t) + a[4] * sin(2 * t);
    };
    auto dg = [&](const numeric &t) {
        return -a[1] * sin(t) + a[2] * cos(t) - 2 * a[3] * sin(2 * t) + 2 * a[4] * cos(2 * t);
    };
    const numeric A1 = sqrt(a[1] * a[1] + a[2] * a[2]), A2 = sqrt(a[3] * a[3] + a[4] * a[4]);
    const numeric L1 = A1 + 2 * A2, L2 = A1 + 4 * A2;
    const numeric scale = abs(a[0]) + A1 + A2;
    if (scale.is_zero())
        throw input_error(where + ": every sliding direction satisfies the law (the sliding equation vanishes "
                                  "identically): the regimes 'stick' and 'slide' cannot be told apart");
    // The angle to 10^-(Digits - 10) radians (1e-40 at 50 digits), whatever the scale of g.
    const numeric tiny = numeric(1, 10).power(static_cast<int>(Digits) - 10);
    std::vector<numeric> roots;
    std::function<void(const numeric &, const numeric &, const numeric &, const numeric &, int)> isolate =
        [&](const numeric &lo, const numeric &hi, const numeric &glo, const numeric &ghi, int depth) {
            const numeric w = hi - lo;
            if (abs(glo) + abs(ghi) > L1 * w)
                return; // no root
            const bool change = (glo.is_negative() && ghi.is_positive()) || (glo.is_positive() && ghi.is_negative());
            if (change && abs(dg(lo)) + abs(dg(hi)) > L2 * w) {
                numeric l = lo, h = hi, gl = glo;
                for (int k = 0; k < 200 && (h - l) > tiny; ++k) {
                    numeric mid = (l + h) / 2, gm = g(mid);
                    if (gm.is_zero()) {
                        l = h = mid;
                        break;
                    }
                    if (gm.is_negative() == gl.is_negative()) {
                        l = mid;
                        gl = gm;
                    } else {
                        h = mid;
                    }
                }
                roots.push_back((l + h) / 2);
                return;
            }
            if (depth > 70) {
                throw input_error(where + ": the sliding equation has a double root (two sliding directions merge): "
                                          "the problem lies on the boundary between regimes and cannot be decided");
            }
            const numeric mid = (lo + hi) / 2, gm = g(mid);
            if (gm.is_zero()) {
                roots.push_back(mid);
                // a root exactly at mid: look on either side, clear of it
                const numeric eps = w * numeric(1, 1000000);
                isolate(lo, mid - eps, glo, g(mid - eps), depth + 1);
                isolate(mid + eps, hi, g(mid + eps), ghi, depth + 1);
                return;
            }
            isolate(lo, mid, glo, gm, depth + 1);
            isolate(mid, hi, gm, ghi, depth + 1);
        };
    const int pieces = 64;
    std::vector<numeric> ts, gs;
    for (int k = 0; k <= pieces; ++k) {
        ts.push_back(two_pi * numeric(k, pieces));
        gs.push_back(k == pieces ? gs[0] : g(ts.back()));
    }
    // A root on a grid point: g there is zero up to the rounding of cos and sin (pi/2 is
    // a grid point, and a sliding direction along e_b has it: cos(pi/2) evaluates to
    // 1e-50, not 0). Recorded there; the pieces on either side are then isolated from
    // 1e-9 away from it, or the piece without the sign change would be halved toward the
    // endpoint until it looked like a double root. A grid point where g' vanishes as well
    // is a double root.
    const numeric noise = scale * tiny;
    auto on_grid = [&](std::size_t k) { return abs(gs[k]) <= noise; };
    const numeric step = numeric(1, 1000000000);
    for (std::size_t k = 0; k < static_cast<std::size_t>(pieces); ++k) {
        numeric lo = ts[k], hi = ts[k + 1], glo = gs[k], ghi = gs[k + 1];
        if (on_grid(k)) {
            if (abs(dg(ts[k])) <= noise)
                throw input_error(where + ": the sliding equation has a double root (two sliding directions merge): "
                                          "the problem lies on the boundary between regimes and cannot be decided");
            roots.push_back(ts[k]);
            lo = ts[k] + step;
            glo = g(lo);
        }
        if (on_grid(k + 1)) {
            hi = ts[k + 1] - step;
            ghi = g(hi);
        }
        isolate(lo, hi, glo, ghi, 0);
    }
    return roots;
}

} // namespace

namespace
{

// A sliding direction along +-e_t or +-e_b (a motion in one plane: e.g. a ball sliding along
// e_b) is taken exactly when the sliding equation vanishes there exactly: the answer is then
// exact, not floats with 1e-60 in the components that are zero. True with (exact_c, exact_s).
bool exact_axis_direction(const problem &p, const regime_case &c, const numeric &t, ex &exact_c, ex &exact_s)
{
    bool exact = false;
    if (p.is_numeric()) {
        const numeric ct = cos(t), sn = sin(t);
        for (const auto &[c0, s0] : {std::pair<int, int>{1, 0}, {0, 1}, {-1, 0}, {0, -1}}) {
            if (abs(ct - c0) + abs(sn - s0) > numeric(1, 1000000))
                continue;
            lst exact_fixed;
            for (const step &st : c.sol.steps) {
                if (st.value.has(c.dir_c) || st.value.has(c.dir_s))
                    break;
                exact_fixed.append(st.sym == tidy(st.value.subs(exact_fixed)));
            }
            const ex g0 = tidy(c.angle_equation.subs(exact_fixed).subs(lst{c.dir_c == c0, c.dir_s == s0}));
            if (is_a<numeric>(g0) && g0.is_zero()) {
                exact = true;
                exact_c = c0;
                exact_s = s0;
            }
        }
    }
    return exact;
}

// The slide at the root t of the sliding equation, if its conditions hold (margin: a condition
// within `margin` of 0 is too close to call).
void slide_at_root(const problem &p, const regime_case &c, const numeric &t, double margin, const std::string &where,
                   std::vector<regime_case> &holding)
{
    ex exact_c, exact_s;
    const bool exact = exact_axis_direction(p, c, t, exact_c, exact_s);
    const lst dirv = exact ? lst{c.dir_c == exact_c, c.dir_s == exact_s} : lst{c.dir_c == cos(t), c.dir_s == sin(t)};
    lst vals;
    for (const step &st : c.sol.steps) {
        const ex v = st.value.subs(dirv).subs(vals);
        vals.append(st.sym == (exact ? tidy(v) : v.evalf()));
    }
    bool ok = true;
    for (const regime_condition &rc : c.conditions) {
        ex v = rc.value.subs(dirv).subs(vals).evalf();
        if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
            throw input_error(where + ": cannot evaluate the condition " + rc.meaning);
        const double x = ex_to<numeric>(v).to_double();
        if (std::abs(x) <= margin)
            throw input_error(where + ": the condition " + rc.meaning +
                              " is too close to its boundary to decide the regime");
        ok = ok && x > 0;
    }
    if (ok) {
        regime_case r = substituted(c, dirv, vals, !exact);
        r.needs_angle = false;
        std::ostringstream angle;
        angle.precision(6);
        angle << t.to_double();
        r.name = "slide at the angle " + angle.str() + " rad from e_t towards e_b";
        if (exact)
            r.name = exact_c.is_equal(1)    ? "slide along +e_t"
                     : exact_c.is_equal(-1) ? "slide along -e_t"
                     : exact_s.is_equal(1)  ? "slide along +e_b"
                                            : "slide along -e_b";
        r.has_angle = true;
        r.angle = t.to_double();
        holding.push_back(r);
    }
}

// The slides of a 3-D candidate without a closed form that hold: at each root of the sliding
// equation g(c, s) = 0 on the unit circle, found at 50 digits (and two more per decade of a large mu).
void holding_angles(const problem &p, const impact_solution &f, const regime_case &c, const std::string &where,
                    std::vector<regime_case> &holding)
{
    // The sliding angle: roots of g(c, s) = 0 on the unit circle, at 50 digits.
    // 50 digits, and two more per decade of a large mu: the sliding equation's coefficients
    // span mu^2, and the root must hold to 1e-40 of the smallest.
    long digits = 50;
    {
        const ex m = f.mu.evalf();
        if (is_a<numeric>(m) && abs(ex_to<numeric>(m)) > 1)
            digits += std::min(400L, 2 * static_cast<long>(std::ceil(
                                             std::log10(std::max(1.0, std::abs(ex_to<numeric>(m).to_double()))))) +
                                         2);
    }
    const digits_scope scope(digits);
    lst fixed; // the steps that do not depend on the direction, as floats
    for (const step &st : c.sol.steps) {
        if (st.value.has(c.dir_c) || st.value.has(c.dir_s))
            break;
        fixed.append(st.sym == st.value.subs(fixed).evalf());
    }
    ex g = c.angle_equation.subs(fixed).evalf().expand();
    auto coeff2 = [&](int i, int j) {
        ex v = g.coeff(c.dir_c, i).coeff(c.dir_s, j).evalf();
        if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
            throw input_error(where + ": the sliding equation has a coefficient that is not a real number");
        return ex_to<numeric>(v);
    };
    // c^2 = (1 + cos 2t)/2, s^2 = (1 - cos 2t)/2, c s = sin(2t)/2.
    const numeric c00 = coeff2(0, 0), c10 = coeff2(1, 0), c01 = coeff2(0, 1), c20 = coeff2(2, 0), c02 = coeff2(0, 2),
                  c11 = coeff2(1, 1);
    const numeric a[5] = {c00 + (c20 + c02) / 2, c10, c01, (c20 - c02) / 2, c11 / 2};
    const std::vector<numeric> roots = trig_roots(a, where);
    // Margin: a condition within 10^-30 of the problem's scale (the largest step value
    // before the direction enters) is too close to its boundary to call.
    double scale = 1;
    for (const ex &rel : fixed)
        if (is_a<numeric>(rel.rhs()))
            scale = std::max(scale, std::abs(ex_to<numeric>(rel.rhs()).to_double()));
    const double margin = scale * 1e-30;
    for (const numeric &t : roots)
        slide_at_root(p, c, t, margin, where, holding);
}

} // namespace

std::vector<regime_case> holding_regimes(const derivation &d, const friction_solution &f)
{
    const problem &p = d.prob;
    const std::string where =
        p.source.empty() ? std::string("contact.friction") : names::display_text(p.source) + ": contact.friction";
    if (!p.is_numeric())
        throw input_error(where + ": the regime of a problem with symbols depends on their values; "
                                  "'impactgen formulas' gives each regime with the inequalities that select it");
    std::vector<regime_case> holding;
    for (const regime_case &c : f.cases) {
        if (!c.needs_angle) {
            lst values;
            if (holds(c, lst{}, values, where))
                holding.push_back(substituted(c, lst{}, values));
            continue;
        }
        holding_angles(p, f, c, where, holding);
    }
    if (holding.size() == 1 && decide(f.mu) == decision::zero) { // mu = 0: the smooth impact (F = 0)
        holding[0].kind = regime::smooth;
        holding[0].name = "smooth";
    }
    return holding;
}

regime_case select_regime(const derivation &d, const friction_solution &f)
{
    const problem &p = d.prob;
    const std::string where =
        p.source.empty() ? std::string("contact.friction") : names::display_text(p.source) + ": contact.friction";
    std::vector<regime_case> holding = holding_regimes(d, f);
    if (holding.size() == 1)
        return holding[0];
    std::string names;
    for (const regime_case &c : (holding.empty() ? f.cases : holding))
        names += (names.empty() ? "" : ", ") + c.name;
    if (holding.empty())
        throw input_error(
            where + ": the law of restitution with Coulomb friction has no solution here: none of the regimes (" +
            names + ") satisfies its conditions (strong coupling between the normal and tangential directions)");
    throw input_error(where +
                      ": the law of restitution with Coulomb friction has more than one solution here: the regimes " +
                      names + " all hold (strong coupling between the normal and tangential directions with large mu)");
}

} // namespace impactgen
