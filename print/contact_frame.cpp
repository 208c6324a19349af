#include "contact_frame.hpp"

#include "expr/roles.hpp"
#include "symbolic/decide.hpp"

#include <algorithm>
#include <map>
#include <set>

namespace impactgen::print
{

using namespace GiNaC;

namespace
{

const char *const frame_axes[3] = {"t", "n", "b"};

// The same in every run: GiNaC's choice of signs is not counted (expression_size).
int nodes(const ex &x)
{
    return expression_size(x, 1 << 24);
}

ex simplified(const ex &x)
{
    return tidy_expand(x);
}

// How many terms x.expand() would have, at most (capped): the view expands the derivation's
// equations, and a hostile input such as a contact point (a + b + ... + q)^12 must not make
// that take minutes.
double expanded_terms(const ex &x)
{
    constexpr double cap = 1e9;
    if (is_a<add>(x)) {
        double n = 0;
        for (std::size_t k = 0; k < x.nops(); ++k)
            n = std::min(cap, n + expanded_terms(x.op(k)));
        return n;
    }
    if (is_a<GiNaC::mul>(x)) {
        double n = 1;
        for (std::size_t k = 0; k < x.nops(); ++k)
            n = std::min(cap, n * expanded_terms(x.op(k)));
        return n;
    }
    if (is_a<power>(x) && is_a<numeric>(x.op(1)) && ex_to<numeric>(x.op(1)).is_pos_integer()) {
        const double t = expanded_terms(x.op(0)), e = ex_to<numeric>(x.op(1)).to_double();
        double n = 1; // C(t + e - 1, e), the monomials of degree e in t terms
        for (double k = 1; k <= e && n < cap; ++k)
            n = n * (t + e - k) / k;
        return std::min(cap, n);
    }
    return 1;
}

// What a body's vector is, written from its kind and owner (never from the derivation's
// world-axis sentence): "velocity of the centre of mass of puck after impact"; the component's
// axis travels beside it (frame_component::axis).
std::string frame_meaning(const problem &p, unknown_kind kind, std::size_t body, bool after)
{
    const std::string who = display_name(p.bodies[body]);
    const std::string when = after ? " after impact" : " before impact";
    switch (kind) {
    case unknown_kind::velocity:
        return "velocity of the centre of mass of " + who + when;
    case unknown_kind::angular_velocity:
        return "angular velocity of " + who + when;
    case unknown_kind::pivot_impulse:
        return "impulse of the pivot on " + who;
    case unknown_kind::normal_impulse:
        break;
    }
    return "normal impulse"; // not a vector: the view never names its components
}

// The last three equations of v (a body's angular momentum along e_t, e_n, e_b) have
// the inertia tensor's frame entries as the coefficients of the spin: e_a·I ω′ =
// sum_l (e_a·I e_l) ω′_l. Where such a coefficient is a combination of the world
// entries (a rotated tensor), it is named, I_tn,box = e_t·I e_n, on both sides
// (symmetric: I_nt is I_tn), and defined in v.inertia.
void name_inertia(contact_frame_view &v, const derivation &d, std::size_t which, const std::vector<symbol> &after,
                  const std::vector<symbol> &before)
{
    const body &b = d.prob.bodies[which];
    std::map<std::pair<int, int>, std::pair<symbol, ex>> named;
    const std::size_t first = v.equations.size() - 3;
    for (int a = 0; a < 3; ++a) {
        framed_equation &f = v.equations[first + static_cast<std::size_t>(a)];
        for (int l = 0; l < 3; ++l) {
            const ex c = f.lhs.coeff(after[static_cast<std::size_t>(l)], 1);
            if (c.is_zero() || is_a<symbol>(c) || is_a<numeric>(c) || has(c, after[0]) || has(c, after[1]) ||
                has(c, after[2]))
                continue;
            const auto key = std::make_pair(std::min(a, l), std::max(a, l));
            auto it = named.find(key);
            if (it == named.end()) {
                const std::string axes = std::string(frame_axes[key.first]) + frame_axes[key.second];
                const symbol s(quantity_name("I", axes, b.label, false), quantity_tex("I", axes, b.label, false));
                it = named.emplace(key, std::make_pair(s, c)).first;
                v.inertia.push_back(
                    {s, c, "inertia tensor of " + display_name(b) + " about C in the contact frame, " + axes + " entry",
                     ""});
            } else if (!(c - it->second.second).expand().is_zero()) {
                continue;
            }
            const symbol &s = it->second.first;
            f.lhs = (f.lhs - c * after[static_cast<std::size_t>(l)] + s * after[static_cast<std::size_t>(l)]).expand();
            if (!before.empty()) {
                const ex cb = f.rhs.coeff(before[static_cast<std::size_t>(l)], 1);
                if ((cb - c).expand().is_zero())
                    f.rhs = (f.rhs - c * before[static_cast<std::size_t>(l)] + s * before[static_cast<std::size_t>(l)])
                                .expand();
            }
        }
    }
}

} // namespace

ex contact_frame_view::apply(const ex &x) const
{
    for (const auto &[world, frame] : to_frame)
        if (x.has(world))
            return simplified(x.subs(to_frame));
    return x; // as it was (a step such as N = -(1 + e) u/k keeps its form)
}

namespace
{
// An equation of the derivation is linear in the velocities, spins and impulses, with
// coefficients of low degree in the masses, inertias and e: expanding it is cheap, and
// it is what makes the radicals of the frame cancel (sqrt(2) sqrt(2) -> 2).
ex rewritten(const contact_frame_view &v, const ex &x)
{
    return merge_roots(x.subs(v.to_frame).expand()).expand();
}
// m1 v′_t - m1 v_t -> m1 (v′_t - v_t), as the derivation writes impulse-momentum.
ex factored(const ex &x)
{
    return is_a<add>(x) ? collect_common_factors(x) : x;
}

// A world vector to write through frame components: base, TeX base, body label, after impact,
// the components' role (an angular velocity's are ω in text).
struct framed_vector {
    const vec3 &world;
    const std::string &base, &base_tex, &label;
    bool after;
    expr::symbol_role role;
};

// Names x's frame components (v′_t1 = e_t · v′_1, ...) into `into` and writes x's world
// symbols through them in v.to_frame; frame gets the new symbols. False (nothing named)
// unless x is dim distinct plain symbols not named already.
bool name_in_frame(contact_frame_view &v, int dim, const framed_vector &x, const std::vector<std::string> &meanings,
                   std::vector<frame_component> &into, std::vector<symbol> &frame)
{
    const vec3 &world = x.world;
    frame.clear();
    for (int c = 0; c < dim; ++c)
        if (!is_a<symbol>(world[c]) || v.to_frame.count(world[c]))
            return false;
    for (int c = 0; c < dim; ++c)
        for (int k = 0; k < c; ++k)
            if (world[c].is_equal(world[k]))
                return false;
    for (int k = 0; k < dim; ++k) {
        frame.push_back(expr::symbol_with_role(quantity_name(x.base, frame_axes[k], x.label, x.after),
                                               quantity_tex(x.base_tex, frame_axes[k], x.label, x.after), x.role));
        ex combination = 0;
        for (int c = 0; c < dim; ++c)
            combination += v.e[k][c] * world[c];
        into.push_back({frame.back(), combination, meanings[static_cast<std::size_t>(k)], frame_axes[k]});
    }
    for (int c = 0; c < dim; ++c) {
        ex combination = 0;
        for (int k = 0; k < dim; ++k)
            combination += v.e[k][c] * frame[static_cast<std::size_t>(k)];
        v.to_frame[world[c]] = combination;
    }
    return true;
}

// The derivation's equations into v: scalar ones rewritten, each vector equation projected
// on e_t, e_n, e_b (a body's inertia entries in the frame named). False when a vector
// equation's components are not the frame's to project; before and after count the nodes.
bool project_equations(contact_frame_view &v, const derivation &d, const ex &inv_t_len,
                       std::map<std::size_t, std::vector<symbol>> &spin_after,
                       std::map<std::size_t, std::vector<symbol>> &spin_before, int &before, int &after)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    for (std::size_t k = 0; k < d.equations.size();) {
        const equation &first = d.equations[k];
        if (first.component < 0) {
            // The smooth-contact equations are along e_t and e_b as the derivation's
            // directions, not of length 1 in general: written for the unit vectors here.
            const ex scale = first.why == principle::smooth_contact ? inv_t_len : ex(1);
            framed_equation f{&first, rewritten(v, first.lhs * scale), rewritten(v, first.rhs * scale), ""};
            before += nodes(first.lhs) + nodes(first.rhs);
            after += nodes(f.lhs) + nodes(f.rhs);
            v.equations.push_back(f);
            ++k;
            continue;
        }
        std::size_t j = k;
        std::set<int> components;
        while (j < d.equations.size() && d.equations[j].why == first.why && d.equations[j].bodies == first.bodies &&
               d.equations[j].component >= 0)
            components.insert(d.equations[j++].component);
        if (dim == 2 && components == std::set<int>{2}) { // a spin in plane motion: along z = e_b
            for (; k < j; ++k) {
                const equation &eq = d.equations[k];
                framed_equation f{&eq, rewritten(v, eq.lhs), rewritten(v, eq.rhs), p.axes[2]};
                before += nodes(eq.lhs) + nodes(eq.rhs);
                after += nodes(f.lhs) + nodes(f.rhs);
                v.equations.push_back(f);
            }
            continue;
        }
        if (j - k != static_cast<std::size_t>(dim) || static_cast<int>(components.size()) != dim ||
            *components.begin() != 0 || *components.rbegin() != dim - 1)
            return false;
        vec3 lhs = zero_vec(), rhs = zero_vec();
        for (std::size_t q = k; q < j; ++q) {
            const equation &eq = d.equations[q];
            lhs[static_cast<std::size_t>(eq.component)] = eq.lhs;
            rhs[static_cast<std::size_t>(eq.component)] = eq.rhs;
            before += nodes(eq.lhs) + nodes(eq.rhs);
        }
        for (int a = 0; a < dim; ++a) {
            ex l = 0, r = 0;
            for (int c = 0; c < dim; ++c) {
                l += v.e[a][c] * lhs[static_cast<std::size_t>(c)];
                r += v.e[a][c] * rhs[static_cast<std::size_t>(c)];
            }
            // The equations keep their numbers (the steps cite them): the a-th of the group.
            v.equations.push_back(
                {&d.equations[k + static_cast<std::size_t>(a)], rewritten(v, l), rewritten(v, r), frame_axes[a]});
        }
        if (first.why == principle::angular_momentum && first.bodies.size() == 1 && spin_after.count(first.bodies[0]))
            name_inertia(v, d, first.bodies[0], spin_after[first.bodies[0]], spin_before[first.bodies[0]]);
        for (std::size_t q = v.equations.size() - static_cast<std::size_t>(dim); q < v.equations.size(); ++q)
            after += nodes(v.equations[q].lhs) + nodes(v.equations[q].rhs);
        k = j;
    }
    return true;
}

// Each equation as the derivation writes it, "after = before", and common factors taken out.
void knowns_to_the_right(contact_frame_view &v)
{
    for (framed_equation &f : v.equations) {
        // "after = before" as the derivation writes it: where the projection left knowns
        // beside the unknowns on the left of "= 0" (a pinned body's partner), they go right.
        if (f.rhs.is_zero() && is_a<add>(f.lhs)) {
            ex unknown_part = 0, known_part = 0;
            for (const ex &term : f.lhs) {
                bool has_unknown = false;
                for (const frame_component &u : v.unknowns)
                    has_unknown = has_unknown || term.has(u.sym);
                (has_unknown ? unknown_part : known_part) += term;
            }
            if (!unknown_part.is_zero() && !known_part.is_zero()) {
                f.lhs = unknown_part;
                f.rhs = -known_part;
            }
        }
        f.lhs = factored(f.lhs);
        f.rhs = factored(f.rhs);
    }
}
} // namespace

lst contact_frame_view::with_inputs(const ex &values) const
{
    lst out;
    for (const ex &v : values)
        out.append(v);
    for (const auto *list : {&inputs, &inertia})
        for (const frame_component &c : *list)
            out.append(c.sym == simplified(c.world.subs(values)));
    return out;
}

frame_component unknown_component(const problem &p, const unknown &u)
{
    if (u.kind == unknown_kind::normal_impulse || u.component < 0 || u.component > 2)
        return {u.sym, u.sym, u.meaning, ""};
    const std::size_t body = u.kind == unknown_kind::pivot_impulse ? p.pivots[u.owner].body : u.owner;
    return {u.sym, u.sym, frame_meaning(p, u.kind, body, true), p.axes[static_cast<std::size_t>(u.component)]};
}

contact_frame_view world_components_view(const derivation &d)
{
    contact_frame_view w;
    for (const unknown &u : d.unknowns)
        w.unknowns.push_back(unknown_component(d.prob, u));
    for (const equation &eq : d.equations)
        w.equations.push_back(
            {&eq, eq.lhs, eq.rhs, eq.component >= 0 ? d.prob.axes[static_cast<std::size_t>(eq.component)] : ""});
    return w;
}

contact_frame_view contact_frame_view_of(const derivation &d)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    contact_frame_view v;
    auto world_only = [&]() { return world_components_view(d); };
    if (d.frame_is_world || p.axes[0] != "x")
        return world_only();

    // Unit e_t, e_n, e_b: fixed directions only.
    v.count = dim;
    // The smooth-contact equations are dotted with t_dir and b_dir, of length |t_dir| each
    // (b_dir = t_dir × e_n): 1/|t_dir| makes them the unit frame's.
    const ex inv_t_len = inverse_root_of(tidy(dot(d.t_dir, d.t_dir)));
    v.e[0] = d.e_t;
    v.e[1] = d.n_hat;
    v.e[2] = dim == 3 ? d.e_b : vec3{0, 0, 1};
    for (const vec3 &e : v.e)
        for (const ex &c : e)
            if (!is_constant(c))
                return world_only();

    // The world symbols to write through frame components: a vector of dim unknown
    // symbols, or of dim distinct plain symbols given as an input.
    // A body's spin components in the frame (3-D): after impact (unknowns), before (renamed inputs).
    std::map<std::size_t, std::vector<symbol>> spin_after, spin_before;
    std::vector<symbol> frame;
    auto rename = [&](const vec3 &world, const std::string &base, const std::string &base_tex, const std::string &label,
                      bool after, const std::vector<std::string> &meanings, std::vector<frame_component> &into,
                      expr::symbol_role role = expr::symbol_role::none) {
        return name_in_frame(v, dim, {world, base, base_tex, label, after, role}, meanings, into, frame);
    };

    // Unknowns, in the derivation's order: the world components of one vector are
    // consecutive (velocity, angular velocity in 3-D, pivot impulse).
    for (std::size_t i = 0; i < d.unknowns.size();) {
        const unknown &u = d.unknowns[i];
        const bool vector_kind = u.kind == unknown_kind::velocity || u.kind == unknown_kind::pivot_impulse ||
                                 (u.kind == unknown_kind::angular_velocity && dim == 3);
        if (!vector_kind || i + static_cast<std::size_t>(dim) > d.unknowns.size()) {
            v.unknowns.push_back(unknown_component(p, u));
            ++i;
            continue;
        }
        vec3 world = zero_vec();
        const std::size_t owner_body = u.kind == unknown_kind::pivot_impulse ? p.pivots[u.owner].body : u.owner;
        std::vector<std::string> meanings;
        for (int c = 0; c < dim; ++c) {
            const unknown &uc = d.unknowns[i + static_cast<std::size_t>(c)];
            if (uc.kind != u.kind || uc.owner != u.owner || uc.component != c)
                return world_only();
            world[c] = uc.sym;
            meanings.push_back(frame_meaning(p, u.kind, owner_body, true));
        }
        const std::string &label = p.bodies[owner_body].label;
        const bool ok =
            u.kind == unknown_kind::velocity ? rename(world, "v", "v", label, true, meanings, v.unknowns)
            : u.kind == unknown_kind::angular_velocity
                ? rename(world, "w", "\\omega", label, true, meanings, v.unknowns, expr::symbol_role::angular_velocity)
                : rename(world, "R", "R", label, false, meanings, v.unknowns);
        if (!ok)
            return world_only();
        if (u.kind == unknown_kind::angular_velocity)
            spin_after[u.owner] = frame;
        i += static_cast<std::size_t>(dim);
    }

    // Inputs before impact given as plain symbols.
    for (std::size_t i : {p.contact().body1, p.contact().body2}) {
        const body &b = p.bodies[i];
        std::vector<std::string> meanings;
        for (int k = 0; k < dim; ++k)
            meanings.push_back(frame_meaning(p, unknown_kind::velocity, i, false));
        rename(b.velocity, "v", "v", b.label, false, meanings, v.inputs);
        if (dim == 3) {
            meanings.clear();
            for (int k = 0; k < dim; ++k)
                meanings.push_back(frame_meaning(p, unknown_kind::angular_velocity, i, false));
            if (rename(b.angular_velocity, "w", "\\omega", b.label, false, meanings, v.inputs,
                       expr::symbol_role::angular_velocity))
                spin_before[i] = frame;
        }
    }

    // The equations: scalar ones rewritten, vector ones projected on the frame -- if that
    // is cheap (each equation, written through the frame, at most a few thousand terms).
    for (const equation &eq : d.equations)
        if (expanded_terms(eq.lhs.subs(v.to_frame)) + expanded_terms(eq.rhs.subs(v.to_frame)) > 4000)
            return world_only();
    int before = 0, after = 0;
    if (!project_equations(v, d, inv_t_len, spin_after, spin_before, before, after))
        return world_only();
    // Unlike radicals in the frame may not cancel: keep the world components when the
    // equations come out more than half as long again
    // (a rational frame shortens them; an irrational one such as that of (2, 3, 6), whose e_t
    // has sqrt(5), lengthens them a little; unlike radicals that do not cancel, several times)
    if (2 * after > 3 * before)
        return world_only();
    knowns_to_the_right(v);
    v.active = true;
    return v;
}

} // namespace impactgen::print
