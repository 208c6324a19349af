#include "derivation.hpp"
#include "contact_law.hpp"
#include "decide.hpp"

#include "expr/roles.hpp"
#include "names/escape.hpp"

#include <cctype>
#include <set>

namespace impactgen
{
using namespace GiNaC;

const char *principle_name(principle p)
{
    switch (p) {
    case principle::smooth_contact:
        return "smooth contact";
    case principle::system_momentum:
        return "linear momentum of the system";
    case principle::angular_momentum:
        return "angular momentum";
    case principle::linear_impulse:
        return "linear impulse-momentum";
    case principle::pivot_fixed:
        return "pivot fixed";
    case principle::restitution:
        return "restitution";
    case principle::stick:
        return "Coulomb's law, sticking";
    case principle::slide:
        return "Coulomb's law, sliding";
    }
    return "?";
}

namespace
{
// A one-letter or one-digit label joins its axis directly (v_t1); any other is set apart (v_x,ball).
bool single_char_label(const std::string &s)
{
    return s.size() == 1 && std::isalnum(static_cast<unsigned char>(s[0]));
}
} // namespace

std::string label_subscript(const std::string &label)
{
    return single_char_label(label) ? label : "," + label;
}

std::string label_subscript_tex(const std::string &label)
{
    return single_char_label(label) ? label : "\\text{" + names::latex_text(label) + "}";
}

std::string quantity_name(const std::string &base, const std::string &axis, const std::string &label, bool after)
{
    std::string sub = single_char_label(label) ? axis + label : axis + "," + label;
    return base + (after ? "'" : "") + "_" + sub;
}

std::string quantity_tex(const std::string &base_tex, const std::string &axis, const std::string &label, bool after)
{
    std::string sub = single_char_label(label) ? axis + label : axis + ",\\text{" + names::latex_text(label) + "}";
    return base_tex + (after ? "'" : "") + "_{" + sub + "}";
}

lst derivation::unknown_symbols() const
{
    lst l;
    for (const unknown &u : unknowns)
        l.append(u.sym);
    return l;
}

namespace
{

bool is_axis(const vec3 &n, int &axis)
{
    int nonzero = 0;
    for (int i = 0; i < 3; ++i)
        if (!n[i].is_zero()) {
            ++nonzero;
            axis = i;
        }
    return nonzero == 1;
}

// e_t and e_b for the contact normal: world axes when n lies along one,
// otherwise the projection of the world axis least parallel to n.
void contact_frame(derivation &d)
{
    const vec3 &n = d.n_hat;
    int k = 0;
    if (d.prob.dimension == 2) {
        d.t_dir = {n[1], -n[0], 0};
        d.b_dir = zero_vec();
        d.frame_is_world = is_axis(n, k);
        return;
    }
    if (is_axis(n, k)) {
        vec3 t = zero_vec();
        t[(k + 2) % 3] = 1;
        d.t_dir = t;
        d.b_dir = cross(t, n);
        d.frame_is_world = true;
        return;
    }
    int pick = -1;
    for (int i = 0; i < 3 && pick < 0; ++i)
        if (n[i].is_zero())
            pick = i;
    if (pick < 0) {
        bool numeric_n = is_a<numeric>(n[0].evalf()) && is_a<numeric>(n[1].evalf()) && is_a<numeric>(n[2].evalf());
        pick = 2;
        if (numeric_n) {
            double best = 2;
            for (int i = 0; i < 3; ++i) {
                double c = std::abs(ex_to<numeric>(n[i].evalf()).to_double());
                if (c < best) {
                    best = c;
                    pick = i;
                }
            }
        }
    }
    vec3 a = zero_vec();
    a[pick] = 1;
    vec3 t = a - dot(a, n) * n;
    for (ex &c : t)
        c = tidy(c);
    d.t_dir = t;
    d.b_dir = cross(t, n);
    for (ex &c : d.b_dir)
        c = merge_roots(tidy(c));
}

symbol fresh(const std::string &name, const std::string &tex)
{
    return symbol(name, tex);
}

} // namespace

vec3 friction_equations::impulse(int dimension, const vec3 &n_hat) const
{
    vec3 P = zero_vec();
    for (int a = 0; a < dimension; ++a) {
        P[a] = N * n_hat[a];
        for (std::size_t k = 0; k < F.size(); ++k)
            P[a] += F[k] * tangents[k][a];
    }
    return P;
}

namespace
{

// The unit normal n_hat (n/|n|, or n as given when declared unit) and the tangents e_t, e_b
// (symbols for a normal of inputs when the code computes the basis at run time).
void unit_normal_and_frame(derivation &d, const derive_options &options)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const auto &ax = p.axes;
    d.normal_assumed_unit = options.unit_normal;
    if (options.unit_normal) {
        d.normal_length = 1;
        for (int i = 0; i < 3; ++i)
            d.n_hat[i] = tidy(p.contact().normal[i]);
    } else {
        const ex length2 = tidy(dot(p.contact().normal, p.contact().normal));
        d.normal_length = root_of(length2);
        // A rational normal scaled to its primitive integer direction first ((1e6, 1e6) ->
        // (1, 1), (0.6, 0.8) -> (3, 4)), so that the root of its length stays small.
        vec3 direction = p.contact().normal;
        bool rational = true;
        numeric denominators = 1, numerators = 0;
        for (const ex &c : direction) {
            rational = rational && is_a<numeric>(c) && ex_to<numeric>(c).is_rational();
            if (rational && !c.is_zero()) {
                denominators = lcm(denominators, ex_to<numeric>(c).denom());
                numerators = gcd(numerators, ex_to<numeric>(c).numer());
            }
        }
        if (rational && !numerators.is_zero())
            for (ex &c : direction)
                c = c * denominators / numerators;
        const ex inverse = inverse_root_of(tidy(dot(direction, direction))); // (1, 1) -> sqrt(2)/2, not 2^(-1/2)
        for (int i = 0; i < 3; ++i)
            d.n_hat[i] = merge_roots(tidy(direction[i] * inverse));
    }
    contact_frame(d);
    const ex inverse_t = inverse_root_of(tidy(dot(d.t_dir, d.t_dir)));
    for (int i = 0; i < 3; ++i)
        d.e_t[i] = merge_roots(tidy(d.t_dir[i] * inverse_t));
    d.e_b = dim == 3 ? cross(d.e_t, d.n_hat) : zero_vec();
    for (ex &c : d.e_b)
        c = merge_roots(tidy(c));
    if (options.runtime_tangent_basis && dim == 3 && !p.contact().normal[0].is_zero() &&
        !p.contact().normal[1].is_zero() && !p.contact().normal[2].is_zero() &&
        !(is_constant(p.contact().normal[0]) && is_constant(p.contact().normal[1]) &&
          is_constant(p.contact().normal[2]))) {
        for (int k = 0; k < 6; ++k) {
            const std::string name = std::string(k < 3 ? "e_t_" : "e_b_") + ax[static_cast<std::size_t>(k % 3)];
            d.tangent_basis_symbols.push_back(
                fresh(name, std::string(k < 3 ? "e_{t," : "e_{b,") + ax[static_cast<std::size_t>(k % 3)] + "}"));
        }
        for (int a = 0; a < 3; ++a) {
            d.e_t[a] = d.tangent_basis_symbols[static_cast<std::size_t>(a)];
            d.e_b[a] = d.tangent_basis_symbols[static_cast<std::size_t>(a + 3)];
        }
    }
}

// The unknowns (velocities and spins after impact of the movable bodies in contact; with a
// pivot the normal impulse and the pivot impulses too) and the velocities after impact in them.
void unknowns_of(derivation &d)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const auto &ax = p.axes;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    // Unknowns and post-impact velocities.
    d.velocity_after.resize(p.bodies.size());
    d.angular_velocity_after.resize(p.bodies.size());
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body &b = p.bodies[i];
        d.velocity_after[i] = b.velocity;
        d.angular_velocity_after[i] = b.angular_velocity;
        bool in_contact = i == i1 || i == i2;
        if (!in_contact || p.immovable(i))
            continue;
        for (int c = 0; c < dim; ++c) {
            symbol s = fresh(quantity_name("v", ax[c], b.label, true), quantity_tex("v", ax[c], b.label, true));
            d.unknowns.push_back(
                {s, unknown_kind::velocity, i, c,
                 "velocity of the centre of mass of " + display_name(b) + " after impact, " + ax[c] + " component"});
            d.velocity_after[i][c] = s;
        }
        if (!b.particle) {
            for (int c = (dim == 2 ? 2 : 0); c < 3; ++c) {
                symbol s = expr::symbol_with_role(quantity_name("w", ax[c], b.label, true),
                                                  quantity_tex("\\omega", ax[c], b.label, true),
                                                  expr::symbol_role::angular_velocity);
                d.unknowns.push_back(
                    {s, unknown_kind::angular_velocity, i, c,
                     "angular velocity of " + display_name(b) + " after impact, " + ax[c] + " component"});
                d.angular_velocity_after[i][c] = s;
            }
        }
    }
    if (d.impulse_form) {
        symbol N = fresh("N", "N");
        d.unknowns.push_back({N, unknown_kind::normal_impulse, 0, 0,
                              "normal impulse (integral of N dt), on " + display_name(p.bodies[i2]) +
                                  " along +n and on " + display_name(p.bodies[i1]) + " along -n"});
        d.normal_impulse = N;
        for (std::size_t k = 0; k < p.pivots.size(); ++k) {
            vec3 R = zero_vec();
            if (p.pivots[k].body != i1 && p.pivots[k].body != i2) { // a bystander: no impulse reaches it
                d.pivot_impulse.push_back(R);
                continue;
            }
            const std::string &lbl = p.bodies[p.pivots[k].body].label;
            for (int c = 0; c < dim; ++c) {
                symbol s = fresh(quantity_name("R", ax[c], lbl, false), quantity_tex("R", ax[c], lbl, false));
                d.unknowns.push_back({s, unknown_kind::pivot_impulse, k, c,
                                      "impulse of the pivot on " + display_name(p.bodies[p.pivots[k].body]) + ", " +
                                          ax[c] + " component"});
                R[c] = s;
            }
            d.pivot_impulse.push_back(R);
        }
    } else {
        d.normal_impulse = 0;
    }
}

// Numbers the equations in the order written; a vector equation gives its world components.
struct equation_writer {
    derivation &d;
    int label = 0;
    void add(ex lhs, ex rhs, principle why, std::string reason, std::vector<std::size_t> bodies, int component = -1)
    {
        d.equations.push_back(
            {std::to_string(++label), lhs, rhs, why, std::move(reason), std::move(bodies), component});
    }
    void world_components(const vec3 &lhs, const vec3 &rhs, principle why, const std::string &reason,
                          std::vector<std::size_t> bodies, bool angular)
    {
        const int dim = d.prob.dimension;
        const int first = angular && dim == 2 ? 2 : 0, last = angular || dim == 3 ? 3 : 2;
        for (int c = first; c < last; ++c)
            add(lhs[c], rhs[c], why, reason, bodies, c);
    }
};

// Free bodies (the notes' unconstrained impact): smooth contact, the system's momentum along n,
// angular momentum about O.
void free_body_equations(derivation &d, equation_writer &w)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    const std::size_t contact_bodies[2] = {i1, i2};
    // (a) Smooth contact: no impulse along e_t, e_b.
    for (std::size_t i : contact_bodies) {
        if (p.immovable(i))
            continue;
        const body &b = p.bodies[i];
        w.add(dot(d.velocity_after[i], d.t_dir), dot(b.velocity, d.t_dir), principle::smooth_contact,
              "the bodies are smooth, so no impulse acts on " + display_name(b) +
                  " along e_t: its centre-of-mass velocity along e_t is unchanged",
              {i});
        if (dim == 3)
            w.add(dot(d.velocity_after[i], d.b_dir), dot(b.velocity, d.b_dir), principle::smooth_contact,
                  "no impulse acts on " + display_name(b) +
                      " along e_b: its centre-of-mass velocity along e_b is unchanged",
                  {i});
    }
    // (b) Linear momentum of the system along n.
    if (!p.bodies[i1].infinite_mass && !p.bodies[i2].infinite_mass) {
        ex before = 0, after = 0;
        for (std::size_t i : contact_bodies) {
            before += p.bodies[i].mass * dot(p.bodies[i].velocity, d.n_hat);
            after += p.bodies[i].mass * dot(d.velocity_after[i], d.n_hat);
        }
        w.add(after, before, principle::system_momentum,
              "the impulse N n is internal to the system of both bodies, so their linear momentum along n is "
              "conserved",
              {i1, i2});
    } else {
        std::size_t inf = p.bodies[i1].infinite_mass ? i1 : i2;
        d.remarks.push_back(
            {remark_kind::momentum_infinite_mass, inf,
             "Linear momentum of the system along n is not useful: " + display_name(p.bodies[inf]) +
                 " has infinite mass, so m (v'_n - v_n) on its side is finite but unknown (infinity times zero)."});
        d.remarks.push_back({remark_kind::infinite_mass_unchanged, inf,
                             "The velocities of " + display_name(p.bodies[inf]) +
                                 " are unchanged: a finite impulse cannot change the motion of an infinite mass, "
                                 "so it gives no angular momentum equation either."});
    }
    // (c) Angular momentum about O, each body separately.
    for (std::size_t i : contact_bodies) {
        const body &b = p.bodies[i];
        if (p.immovable(i))
            continue;
        if (b.particle) {
            d.remarks.push_back({remark_kind::particle_no_rotation, i,
                                 display_name(b) +
                                     " is a particle (no rotational inertia): it has no angular velocity unknowns "
                                     "and its angular momentum about O gives no new equation."});
            continue;
        }
        vec3 r = b.position - p.contact().point; // r_{C O}: C relative to O
        vec3 Hb = mul(b.inertia, b.angular_velocity) + cross(r, b.mass * b.velocity);
        vec3 Ha = mul(b.inertia, d.angular_velocity_after[i]) + cross(r, b.mass * d.velocity_after[i]);
        w.world_components(Ha, Hb, principle::angular_momentum,
                           "the impulse on " + display_name(b) +
                               " passes through O, which is fixed in the inertial frame, so its angular momentum "
                               "about O is conserved",
                           {i}, true);
    }
}

// The constrained collision (a pivot): impulse-momentum with N and R unknown, angular momentum
// about the pivot (or O), the pivots' fixedness.
void constrained_equations(derivation &d, equation_writer &w)
{
    const problem &p = d.prob;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    const std::size_t contact_bodies[2] = {i1, i2};
    // Constrained collision: impulse-momentum with N and R unknown.
    for (std::size_t i : contact_bodies) {
        const body &b = p.bodies[i];
        if (b.infinite_mass)
            continue;
        const ex s = i == i1 ? -1 : 1;
        const pivot *pv = p.pivot_of(i);
        vec3 R = zero_vec();
        if (pv)
            R = d.pivot_impulse[static_cast<std::size_t>(pv - p.pivots.data())];
        vec3 impulse = (s * d.normal_impulse) * d.n_hat + R;
        vec3 dp = b.mass * (d.velocity_after[i] - b.velocity);
        w.world_components(dp, impulse, principle::linear_impulse,
                           "the change of linear momentum of " + display_name(b) + " equals the impulses on it: " +
                               (i == i1 ? "-N n" : "+N n") + (pv ? " and the pivot impulse R" : ""),
                           {i}, false);
        if (!b.particle) {
            vec3 ref = pv ? pv->point : p.contact().point;
            vec3 dH = mul(b.inertia, d.angular_velocity_after[i] - b.angular_velocity) + cross(b.position - ref, dp);
            vec3 moment = pv ? cross(p.contact().point - pv->point, (s * d.normal_impulse) * d.n_hat) : zero_vec();
            w.world_components(dH, moment, principle::angular_momentum,
                               pv ? "about the pivot E, fixed in the inertial frame, the pivot impulse has no "
                                    "moment: the change of angular momentum of " +
                                        display_name(b) + " about E is the moment of the contact impulse"
                                  : "the impulse on " + display_name(b) +
                                        " passes through O, fixed in the inertial frame, so its angular momentum "
                                        "about O is conserved",
                               {i}, true);
        }
        if (pv && !b.particle) {
            vec3 vE = d.velocity_after[i] + cross(d.angular_velocity_after[i], pv->point - b.position);
            w.world_components(vE, zero_vec(), principle::pivot_fixed,
                               "the pivot E of " + display_name(b) + " is fixed: v'_C + w' x r_{E C} = 0", {i}, false);
        }
        if (pv && b.particle)
            d.remarks.push_back({remark_kind::pinned_particle, i,
                                 display_name(b) +
                                     " is a particle pinned at a fixed point: it cannot rotate, so it cannot move, "
                                     "and its pivot takes the whole contact impulse."});
    }
    for (std::size_t i : contact_bodies)
        if (p.bodies[i].infinite_mass)
            d.remarks.push_back({remark_kind::infinite_mass_unchanged, i,
                                 "The velocities of " + display_name(p.bodies[i]) +
                                     " (infinite mass) are unchanged by the finite impulse."});
}

} // namespace

derivation derive(const problem &p, const derive_options &options)
{
    validate(p);
    derivation d;
    d.prob = p;
    if (p.is_system()) { // format version 3: bodies, joints, several contacts
        derive_system(d);
        return d;
    }
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    d.impulse_form = !p.pivots.empty();
    unit_normal_and_frame(d, options);
    unknowns_of(d);

    // Contact point velocities, v_A = v_C1 + w_1 x r_{A C1}.
    const body &A = p.bodies[i1];
    const body &B = p.bodies[i2];
    d.vA = point_velocity(A, p.contact().point);
    d.vB = point_velocity(B, p.contact().point);
    d.vA_after = point_velocity(A, d.velocity_after[i1], d.angular_velocity_after[i1], p.contact().point);
    d.vB_after = point_velocity(B, d.velocity_after[i2], d.angular_velocity_after[i2], p.contact().point);

    equation_writer w{d};
    if (!d.impulse_form)
        free_body_equations(d, w);
    else
        constrained_equations(d, w);
    // (d) Newton's restitution law on the contact points.
    w.add(
        dot(d.vB_after - d.vA_after, d.n_hat), -p.restitution * dot(d.vB - d.vA, d.n_hat), principle::restitution,
        "Newton's coefficient of restitution: the normal velocity of separation of the contact points is e times their "
        "velocity of approach",
        {i1, i2});

    for (std::size_t i = 0; i < p.bodies.size(); ++i)
        if (i != i1 && i != i2)
            d.remarks.push_back(
                {remark_kind::uninvolved, i,
                 display_name(p.bodies[i]) + " takes no part in the contact: its velocities are unchanged."});
    add_law_equations_of(d); // the contact law's (contact_law.hpp)
    return d;
}

} // namespace impactgen
