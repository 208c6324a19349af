#include "solution.hpp"
#include "system.hpp"

#include "names/escape.hpp"

#include <cctype>

#include "decide.hpp"
#include "response.hpp"

#include <random>
#include <set>
#include <sstream>
#include <variant>

namespace impactgen
{
using namespace GiNaC;

ex kinetic_energy(const problem &p, const std::vector<vec3> &v, const std::vector<vec3> &w)
{
    ex T = 0;
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body &b = p.bodies[i];
        if (b.infinite_mass)
            continue;
        T += b.mass * dot(v[i], v[i]) / 2;
        if (!b.particle)
            T += dot(w[i], mul(b.inertia, w[i])) / 2;
    }
    return T;
}

namespace
{

bool atomic(const ex &e)
{
    return is_a<numeric>(e) || is_a<symbol>(e) ||
           (is_a<GiNaC::mul>(e) && e.nops() == 2 && is_a<numeric>(e.op(1)) && is_a<symbol>(e.op(0)));
}

} // namespace

step_builder::step_builder(solution &s, const problem &p) : s_(s)
{
    for (const symbol &x : p.parameters())
        taken_.insert(x.get_name());
    for (const step &st : s.steps)
        taken_.insert(st.sym.get_name());
}

ex step_builder::add(step_role role, std::size_t body, int row, int column, const std::string &name,
                     const std::string &tex, const ex &value, const std::string &meaning, bool force)
{
    if (!force && atomic(value))
        return value;
    std::string n = name, t = tex;
    while (taken_.count(n)) {
        n += "_";
        t += "{}'";
    }
    taken_.insert(n);
    symbol sym(n, t);
    s_.steps.push_back({sym, value, meaning, role, body, row, column});
    return sym;
}

const step *solution::find(step_role role, std::size_t body, int row, int column) const
{
    for (const step &st : steps)
        if (st.role == role && (body == no_body || st.body == body) && (row < 0 || st.row == row) &&
            (column < 0 || st.column == column))
            return &st;
    return nullptr;
}

step *solution::find(step_role role, std::size_t body, int row, int column)
{
    return const_cast<step *>(static_cast<const solution &>(*this).find(role, body, row, column));
}

ex solution::expand_steps(const ex &e) const
{
    ex r = e;
    for (auto it = steps.rbegin(); it != steps.rend(); ++it)
        r = r.subs(it->sym == it->value);
    return r;
}

lst solution::step_values(const ex &input_values) const
{
    lst values;
    for (const step &st : steps) {
        ex v = st.value.subs(input_values).subs(values);
        values.append(st.sym == v);
    }
    return values;
}

namespace
{

// One body of the contact in the smooth closed form.
struct smooth_side {
    std::size_t index;
    ex sign;
    ex w = 0;            // effective inverse mass at the contact point along n
    vec3 g = zero_vec(); // angular velocity change per unit impulse along s n: I^{-1} (r x n)
    body_response r;     // lever (about C or E), arm d = C - E, inertia about C or E
    bool pinned = false;
};

// Planar: the lever arm tau = (r x n)_z, I about C or E, g = tau / I, w = 1/m + tau^2 / I.
void planar_response(const problem &p, step_builder &sb, smooth_side &sd, const vec3 &tau, const std::string &where)
{
    const body &b = p.bodies[sd.index];
    const std::string L = b.label;
    const mat3 &J = sd.r.inertia;
    ex t = sb.add(step_role::lever_arm, sd.index, 2, -1, "tau_" + L, "\\tau_{" + label_subscript_tex(L) + "}",
                  tidy(tau[2]), "lever arm of the normal about " + where + " of " + display_name(b) + ": (r x n)_z");
    ex Iz = sd.pinned ? sb.add(step_role::pivot_inertia, sd.index, 2, 2, "I_E" + label_subscript(L),
                               "I_{E" + label_subscript_tex(L) + "}", tidy(J[2][2]),
                               "moment of inertia of " + display_name(b) + " about its pivot E: I_C + m |C - E|^2")
                      : J[2][2];
    sd.g = {0, 0, t / Iz};
    sd.w = (sd.pinned ? ex(0) : 1 / b.mass) + t * t / Iz;
}

// 3-D: the lever arm tau = r x n, I about C or E (steps when pinned), g = I^{-1} tau,
// w = 1/m + tau.g.
void spatial_response(const problem &p, step_builder &sb, smooth_side &sd, const vec3 &tau, const std::string &where)
{
    const body &b = p.bodies[sd.index];
    const std::string L = b.label;
    const mat3 &J = sd.r.inertia;
    vec3 t;
    for (int c = 0; c < 3; ++c)
        t[c] = sb.add(step_role::lever_arm, sd.index, c, -1, "tau_" + p.axes[c] + label_subscript(L),
                      "\\tau_{" + p.axes[c] + label_subscript_tex(L) + "}", tidy(tau[c]),
                      "lever arm r x n of the normal about " + where + " of " + display_name(b) + ", " + p.axes[c] +
                          " component");
    mat3 Js = J;
    if (sd.pinned)
        for (int a = 0; a < 3; ++a)
            for (int c = a; c < 3; ++c) {
                ex v =
                    sb.add(step_role::pivot_inertia, sd.index, a, c, "I_E" + p.axes[a] + p.axes[c] + label_subscript(L),
                           "I_{E," + p.axes[a] + p.axes[c] + label_subscript_tex(L) + "}", tidy(J[a][c]),
                           "inertia tensor of " + display_name(b) + " about its pivot E: I_C + m (|d|^2 1 - d d^T)");
                Js[a][c] = v;
                Js[c][a] = v;
            }
    // A diagonal tensor (every off-diagonal entry identically zero) is inverted
    // entry by entry: g_c = t_c / J_cc, with no determinant (J_xx J_yy J_zz, whose
    // cube of the scale leaves float's range at I ~ 1e13 or 4e-15); otherwise
    // g = adj(J) t / det(J).
    bool diagonal = true;
    for (int a = 0; a < 3; ++a)
        for (int c = a + 1; c < 3; ++c)
            diagonal = diagonal && tidy(Js[a][c]).is_zero() && tidy(Js[c][a]).is_zero();
    vec3 at = t;
    ex D = 1;
    if (!diagonal) {
        mat3 adj = adjugate(Js);
        D = sb.add(step_role::inertia_determinant, sd.index, -1, -1, "D_" + L, "D_{" + label_subscript_tex(L) + "}",
                   det(Js), "determinant of the inertia tensor of " + display_name(b) + (sd.pinned ? " about E" : ""));
        at = mul(adj, t);
    }
    for (int c = 0; c < 3; ++c)
        sd.g[c] = sb.add(step_role::angular_response, sd.index, c, -1, "g_" + p.axes[c] + label_subscript(L),
                         "g_{" + p.axes[c] + label_subscript_tex(L) + "}", diagonal ? t[c] / Js[c][c] : at[c] / D,
                         "I^{-1} (r x n) for " + display_name(b) + ", " + p.axes[c] +
                             " component: change of angular velocity per unit impulse" +
                             (diagonal ? std::string(" (a diagonal tensor: (r x n) component over the diagonal entry)")
                                       : std::string()));
    sd.w = (sd.pinned ? ex(0) : 1 / b.mass) + dot(t, sd.g);
}

} // namespace

lst unknown_values(const derivation &d, const solution &s)
{
    lst values;
    for (const unknown &un : d.unknowns) {
        ex v;
        switch (un.kind) {
        case unknown_kind::velocity:
            v = s.after[un.owner].velocity[un.component];
            break;
        case unknown_kind::angular_velocity:
            v = s.after[un.owner].angular_velocity[un.component];
            break;
        case unknown_kind::normal_impulse:
            v = s.normal_impulse;
            break;
        case unknown_kind::pivot_impulse:
            v = s.pivot_impulses[un.owner][un.component];
            break;
        }
        values.append(un.sym == v);
    }
    return values;
}

void set_energies(const problem &p, solution &s)
{
    std::vector<vec3> v0, w0, v1, w1;
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        v0.push_back(p.bodies[i].velocity);
        w0.push_back(p.bodies[i].angular_velocity);
        v1.push_back(s.after[i].velocity);
        w1.push_back(s.after[i].angular_velocity);
    }
    s.energy_before = kinetic_energy(p, v0, w0);
    s.energy_after_direct = kinetic_energy(p, v1, w1);
}

// Each movable body's response at the contact and its effective inverse mass w along n, as steps.
void side_responses(const derivation &d, step_builder &sb, smooth_side (&sides)[2])
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const vec3 &n = d.n_hat;
    const vec3 &O = p.contact().point;

    for (smooth_side &sd : sides) {
        const body &b = p.bodies[sd.index];
        const std::string L = b.label;
        if (p.immovable(sd.index))
            continue;
        sd.r = response_of(p, sd.index, O);
        sd.pinned = sd.r.pinned;
        // Lever of the contact normal about C (free) or about E (pinned).
        vec3 tau = cross(sd.r.lever, n);
        const std::string where = sd.pinned ? "the pivot E" : "the centre of mass";
        if (!b.particle) {
            if (dim == 2)
                planar_response(p, sb, sd, tau, where);
            else
                spatial_response(p, sb, sd, tau, where);
        } else {
            sd.w = 1 / b.mass;
        }
        sd.w =
            sb.add(step_role::effective_inverse_mass, sd.index, -1, -1, "w_" + L, "w_{" + label_subscript_tex(L) + "}",
                   sd.w, "effective inverse mass of " + display_name(b) + " at the contact point along n");
    }
}

// Every body after impact, and the pivot impulses, from the normal impulse N.
void bodies_after(const derivation &d, solution &s, const smooth_side (&sides)[2], const ex &N)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const vec3 &n = d.n_hat;
    s.after.resize(p.bodies.size());
    for (std::size_t i = 0; i < p.bodies.size(); ++i)
        s.after[i] = {p.bodies[i].velocity, p.bodies[i].angular_velocity};
    s.pivot_impulses.assign(p.pivots.size(), zero_vec());
    for (const smooth_side &sd : sides) {
        const body &b = p.bodies[sd.index];
        if (b.infinite_mass)
            continue;
        const pivot *pv = p.pivot_of(sd.index);
        vec3 dv = zero_vec(), dw = zero_vec();
        if (!p.immovable(sd.index)) {
            dw = (sd.sign * N) * sd.g;
            dv = centre_velocity_change(sd.r, (sd.sign * N) * n, dw);
        }
        for (int c = 0; c < 3; ++c) {
            s.after[sd.index].velocity[c] = b.velocity[c] + dv[c];
            s.after[sd.index].angular_velocity[c] = b.angular_velocity[c] + dw[c];
        }
        if (pv) {
            std::size_t k_index = static_cast<std::size_t>(pv - p.pivots.data());
            s.pivot_impulses[k_index] = pivot_impulse(sd.r, (sd.sign * N) * n, dv);
            if (dim == 2)
                s.pivot_impulses[k_index][2] = 0;
        }
    }
}

// The kinetic energy lost, as the work of the contact impulse on the bodies that move.
ex work_of_impulse(const derivation &d, const smooth_side (&sides)[2], const ex &N, const ex &u, const ex &k)
{
    const problem &p = d.prob;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    const vec3 &n = d.n_hat;
    ex lost = 0;
    const vec3 *contact_velocity[2] = {&d.vA, &d.vB};
    if (!p.immovable(i1) && !p.immovable(i2)) {
        lost = -N * u - N * N * k / 2;
    } else {
        for (int side_index = 0; side_index < 2; ++side_index) {
            const smooth_side &sd = sides[side_index];
            if (p.immovable(sd.index))
                continue;
            ex a = dot(*contact_velocity[side_index], n);
            lost -= sd.sign * N * a + N * N * sd.w / 2;
        }
    }
    return lost;
}

solution solve(const derivation &d)
{
    const problem &p = d.prob;
    refuse_system_for(p, "the one-contact solver (explain, codegen)");
    if (!std::holds_alternative<frictionless>(p.contact().law)) { // the other laws' candidates: solve_impact
        std::ostringstream mu;
        mu << p.contact().friction();
        throw input_error(
            (p.source.empty() ? std::string("contact") : names::display_text(p.source) + ": contact") +
            ".friction: this command solves smooth impacts only; friction (mu = " + names::display_text(mu.str(), 60) +
            ") is solved by 'impactgen solve' (numbers) and 'impactgen formulas'");
    }
    solution s;
    step_builder sb(s, p);
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    const vec3 &n = d.n_hat;

    smooth_side sides[2] = {{i1, -1, 0, zero_vec(), {}, false}, {i2, 1, 0, zero_vec(), {}, false}};

    side_responses(d, sb, sides);

    ex u = sb.add(step_role::approach_velocity, no_body, -1, -1, "u", "u", tidy(dot(d.vB - d.vA, n)),
                  "normal velocity of approach (v_B - v_A).n before impact (negative for an impact)", true);
    ex k_value = sides[0].w + sides[1].w;
    const std::string where = p.source.empty() ? std::string("contact") : names::display_text(p.source) + ": contact";
    if (vanishes_identically(s, k_value, where + ": the effective inverse mass k = w_1 + w_2"))
        throw input_error(where + ": no impulse can act: neither body can move along the normal at the contact point "
                                  "(the line of impact passes through the pivot of a body that cannot otherwise move)");
    const std::string wsum = "w_" + p.bodies[i1].label + " + w_" + p.bodies[i2].label;
    ex k = sb.add(step_role::contact_inverse_mass, no_body, -1, -1, "k", "k", k_value,
                  "effective inverse mass of the contact: " + wsum);
    ex N = sb.add(step_role::normal_impulse, no_body, -1, -1, "N", "N", -(1 + p.restitution) * u / k,
                  "normal impulse: integral of N dt, on body 2 along +n, on body 1 along -n", true);
    s.normal_impulse = N;

    // Every body after impact.
    bodies_after(d, s, sides, N);

    s.unknown_values = unknown_values(d, s);
    // Energy lost, through the work of the contact impulse: a body that moves
    // under the impulse s N n at its contact point gains s N (a + a')/2 with
    // a the normal velocity of that point, a' = a + s N w; pivot impulses act at
    // fixed points and do no work.
    // When both bodies move this is -N u - N^2 k / 2 = (1 - e^2) u^2 / (2 k).
    ex lost = work_of_impulse(d, sides, N, u, k);
    set_energies(p, s);
    s.energy_lost = sb.add(step_role::energy_lost, no_body, -1, -1, "T_lost", "T_{\\mathrm{lost}}", lost,
                           "kinetic energy lost, T - T' (bodies of finite mass)", true);
    s.energy_after = s.energy_before - s.energy_lost;
    return s;
}

bool vanishes_identically(const solution &s, const ex &value, const std::string &what)
{
    exset free;
    auto collect = [&](const ex &e) {
        for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
            if (is_a<symbol>(*it))
                free.insert(*it);
    };
    collect(value);
    for (const step &st : s.steps)
        collect(st.value);
    for (const step &st : s.steps)
        free.erase(st.sym);
    if (free.empty()) {
        ex v = value.subs(s.step_values(lst{}));
        decision d = decide(v);
        if (d == decision::undecided) // unlike roots GiNaC keeps apart: sqrt(2) sqrt(3) - sqrt(6)
            d = decide(tidy(merge_roots(tidy_expand(merge_roots(v)))));
        if (d == decision::not_real || d == decision::out_of_range || d == decision::undecided)
            throw input_error(what + " " + decision_text(d));
        return d == decision::zero;
    }
    std::vector<symbol> symbols;
    for (const ex &x : free)
        symbols.push_back(ex_to<symbol>(x));
    return vanishes_at_random_points(symbols,
                                     [&](const lst &point) { return value.subs(point).subs(s.step_values(point)); });
}

namespace
{

// A constant residual that normal() left non-zero because GiNaC keeps unlike roots apart
// (sqrt(2) sqrt(3) - sqrt(6) with a normal (sqrt(2), 1)): its roots merged; if it is still
// not 0, its value in 60-digit floats, for the caller's test of 40 digits.
ex settled_constant(const ex &r)
{
    if (r.is_zero() || is_a<numeric>(r) || !is_constant(r))
        return r;
    const ex merged = tidy(merge_roots(tidy_expand(r)));
    if (merged.is_zero())
        return merged;
    digits_scope digits(60);
    return merged.evalf();
}

} // namespace

std::vector<ex> residuals(const derivation &d, const solution &s, const ex &input_values)
{
    std::vector<ex> r;
    const bool numeric_inputs = !(is_a<lst>(input_values) && input_values.nops() == 0);
    if (numeric_inputs) {
        lst steps = s.step_values(input_values);
        lst unknowns;
        for (const ex &rel : s.unknown_values)
            unknowns.append(rel.lhs() == rel.rhs().subs(input_values).subs(steps));
        for (const equation &eq : d.equations)
            r.push_back(settled_constant(tidy((eq.lhs - eq.rhs).subs(input_values).subs(unknowns))));
        return r;
    }
    // A problem without symbols whose numbers are irrational (sqrt(2), Pi, exp(1)):
    // the steps' exact values, each residual simplified only where cheap; what is
    // not a plain zero then is for decide() (normal() of such constants can take
    // seconds: it treats every irrational as a variable).
    if (d.prob.is_numeric()) {
        lst steps = s.step_values(lst{});
        bool exact = true;
        for (const ex &rel : steps)
            exact = exact && is_a<numeric>(rel.rhs()) && ex_to<numeric>(rel.rhs()).is_rational();
        if (exact) { // rational inputs: every residual is an exact number
            for (const equation &eq : d.equations)
                r.push_back(tidy((eq.lhs - eq.rhs).subs(s.unknown_values).subs(steps)));
            return r;
        }
        // Irrational inputs: the steps in 60-digit floats, one after the other (the
        // exact values nest every earlier step; evaluating them as trees is exponential).
        digits_scope digits(60);
        lst floats;
        for (const step &st : s.steps)
            floats.append(st.sym == st.value.subs(floats).evalf());
        lst unknowns;
        for (const ex &rel : s.unknown_values)
            unknowns.append(rel.lhs() == rel.rhs().subs(floats).evalf());
        for (const equation &eq : d.equations) {
            // exact where simplification is cheap (one or two irrationals: sqrt(2)), else the float
            ex exact_residual = tidy((eq.lhs - eq.rhs).subs(s.unknown_values).subs(steps));
            r.push_back(exact_residual.is_zero() ? ex(0) : (eq.lhs - eq.rhs).subs(unknowns).evalf());
        }
        return r;
    }
    // Symbolic: back-substitute the steps from the last to the first,
    // normalising after each; most residuals vanish before the large
    // definitions (inverse inertia) are ever expanded.
    for (const equation &eq : d.equations) {
        ex res = (eq.lhs - eq.rhs).subs(s.unknown_values).normal();
        for (auto it = s.steps.rbegin(); it != s.steps.rend() && !res.is_zero(); ++it)
            if (res.has(it->sym))
                res = res.subs(it->sym == it->value).normal();
        r.push_back(res);
    }
    return r;
}

} // namespace impactgen
