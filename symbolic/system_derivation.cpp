// The equations of a system, the notes' constrained-collision method: every body separately,
// every impulse an unknown. They are written independently of the solver (system.cpp works
// with rows of the Delassus matrix; these are the textbook's equations), so substituting a
// candidate into them checks it.
#include "derivation.hpp"

#include "decide.hpp"
#include "expr/roles.hpp"

namespace impactgen
{
using namespace GiNaC;

namespace
{

const char *axis_name[3] = {"x", "y", "z"};

struct impulse_at {
    std::size_t body;
    vec3 point, value; ///< acting on the body
    bool pivot = false;
};

// Unit tangents of contact i: 2-D e_t = (-n_y, n_x)/|n|; 3-D (perfectly rough) two orthonormal ones.
std::vector<vec3> unit_tangents(const problem &p, std::size_t i, const vec3 &nh)
{
    const contact_spec &c = p.contacts[i];
    if (p.dimension == 2) {
        if (!c.rough && c.friction().is_zero())
            return {};
        return {{-nh[1], nh[0], 0}};
    }
    if (!c.rough)
        return {};
    vec3 a = zero_vec();
    a[c.normal[0].is_zero() ? 0 : c.normal[1].is_zero() ? 1 : c.normal[2].is_zero() ? 2 : 0] = 1;
    const vec3 t = cross(nh, a);
    const ex inv = inverse_root_of(tidy(dot(t, t)));
    const vec3 t1{tidy(t[0] * inv), tidy(t[1] * inv), tidy(t[2] * inv)};
    const vec3 t2 = cross(nh, t1);
    return {t1, {tidy(t2[0]), tidy(t2[1]), tidy(t2[2])}};
}

// The unknowns: velocities after of the bodies of finite mass, then every impulse.
void system_unknowns(derivation &d, std::vector<impulse_at> &impulses)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const body &B = p.bodies[b];
        d.velocity_after.push_back(B.velocity);
        d.angular_velocity_after.push_back(B.angular_velocity);
        if (B.infinite_mass)
            continue;
        for (int k = 0; k < dim; ++k) {
            // the LaTeX name escapes the body's name, as the one-contact documents do
            symbol s(quantity_name("v", axis_name[k], B.label, true), quantity_tex("v", axis_name[k], B.label, true));
            d.velocity_after[b][k] = s;
            d.system_unknowns.push_back({s, "velocity of the centre of " + display_name(B) + " after impact"});
        }
        if (B.particle)
            continue;
        for (int k = dim == 2 ? 2 : 0; k < 3; ++k) {
            // planar: the z axis, as one contact names it; omega in LaTeX as in the one-contact documents
            const symbol s = expr::symbol_with_role(quantity_name("w", axis_name[k], B.label, true),
                                                    quantity_tex("\\omega", axis_name[k], B.label, true),
                                                    expr::symbol_role::angular_velocity);
            d.angular_velocity_after[b][k] = s;
            d.system_unknowns.push_back({s, "angular velocity of " + display_name(B) + " after impact"});
        }
    }
    auto vector_unknown = [&](const std::string &base, std::size_t index, const std::string &meaning) {
        vec3 v = zero_vec();
        for (int k = 0; k < dim; ++k) {
            symbol s(base + "_" + axis_name[k] + std::to_string(index));
            v[k] = s;
            d.system_unknowns.push_back({s, meaning});
        }
        return v;
    };
    for (std::size_t k = 0; k < p.pivots.size(); ++k) {
        const vec3 R = vector_unknown("R", k, "impulse of pivot " + std::to_string(k) + " on its body");
        d.pivot_impulse.push_back(R);
        impulses.push_back({p.pivots[k].body, p.pivots[k].point, R, true});
    }
    for (std::size_t j = 0; j < p.joints.size(); ++j) {
        const vec3 J = vector_unknown("J", j, "impulse of joint " + std::to_string(j) + " on its second body");
        impulses.push_back({p.joints[j].body2, p.joints[j].point, J});
        impulses.push_back({p.joints[j].body1, p.joints[j].point, ex(-1) * J});
    }
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const contact_spec &c = p.contacts[i];
        const ex inv = inverse_root_of(tidy(dot(c.normal, c.normal)));
        const vec3 nh{tidy(c.normal[0] * inv), tidy(c.normal[1] * inv), tidy(c.normal[2] * inv)};
        symbol P("P_" + std::to_string(i));
        d.system_normal_impulse.push_back(P);
        d.system_unknowns.push_back({P, "normal impulse of contact " + std::to_string(i)});
        vec3 total = P * nh;
        d.system_tangents.push_back(unit_tangents(p, i, nh));
        d.system_tangent_impulse.emplace_back();
        for (std::size_t k = 0; k < d.system_tangents[i].size(); ++k) {
            symbol F("F_" + std::to_string(i) + (k ? "b" : "t"));
            d.system_tangent_impulse[i].push_back(F);
            d.system_unknowns.push_back({F, "tangential impulse of contact " + std::to_string(i)});
            total = total + F * d.system_tangents[i][k];
        }
        impulses.push_back({c.body2, c.point, total});
        impulses.push_back({c.body1, c.point, ex(-1) * total});
    }
}

void add(derivation &d, const ex &lhs, const ex &rhs, principle why, const std::string &reason,
         std::vector<std::size_t> bodies, int component, std::vector<equation> *to = nullptr)
{
    std::vector<equation> &list = to ? *to : d.equations;
    list.push_back({std::to_string(d.equations.size() + 1), lhs, rhs, why, reason, std::move(bodies), component});
}

// Impulse-momentum of each body of finite mass: linear, and angular about its centre or its pivot.
void body_equations(derivation &d, const std::vector<impulse_at> &impulses)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const body &B = p.bodies[b];
        if (B.infinite_mass)
            continue;
        const pivot *pv = p.pivot_of(b);
        const vec3 O = pv ? pv->point : B.position; // the point the angular momentum is taken about
        vec3 sum = zero_vec(), moment = zero_vec();
        for (const impulse_at &q : impulses)
            if (q.body == b) {
                sum = sum + q.value;
                moment = moment + cross(q.point - O, q.value);
            }
        const vec3 dv = d.velocity_after[b] - B.velocity;
        for (int k = 0; k < dim; ++k)
            add(d, B.mass * dv[k], sum[k], principle::linear_impulse,
                "Impulse-momentum of " + display_name(B) +
                    ": the change of its momentum is the sum of the impulses on it",
                {b}, k);
        if (B.particle)
            continue;
        const vec3 dH =
            mul(B.inertia, d.angular_velocity_after[b] - B.angular_velocity) + cross(B.position - O, B.mass * dv);
        for (int k = dim == 2 ? 2 : 0; k < 3; ++k)
            add(d, dH[k], moment[k], principle::angular_momentum,
                "Angular impulse-momentum of " + display_name(B) + " about " +
                    (pv ? "its fixed pivot (the pivot's impulse has no moment there)" : "its centre of mass"),
                {b}, dim == 2 ? -1 : k);
    }
}

void constraint_equations(derivation &d)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    auto after = [&](std::size_t b, const vec3 &q) {
        return point_velocity(p.bodies[b], d.velocity_after[b], d.angular_velocity_after[b], q);
    };
    for (std::size_t j = 0; j < p.joints.size(); ++j) {
        const joint &J = p.joints[j];
        const vec3 gap = after(J.body2, J.point) - after(J.body1, J.point);
        for (int k = 0; k < dim; ++k)
            add(d, gap[k], 0, principle::pivot_fixed,
                "Joint " + std::to_string(j) + ": the two bodies' material points at the joint move together",
                {J.body1, J.body2}, k);
    }
    for (std::size_t k = 0; k < p.pivots.size(); ++k) {
        const vec3 v = after(p.pivots[k].body, p.pivots[k].point);
        for (int a = 0; a < dim; ++a)
            add(d, v[a], 0, principle::pivot_fixed, "The pivot point does not move", {p.pivots[k].body}, a);
    }
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const contact_spec &c = p.contacts[i];
        const ex inv = inverse_root_of(tidy(dot(c.normal, c.normal)));
        const vec3 u = point_velocity(p.bodies[c.body2], c.point) - point_velocity(p.bodies[c.body1], c.point);
        const vec3 u2 = after(c.body2, c.point) - after(c.body1, c.point);
        d.system_laws.emplace_back();
        add(d, dot(u2, c.normal) * inv, -p.restitution_of(i) * dot(u, c.normal) * inv, principle::restitution,
            "Contact " + std::to_string(i) +
                " while it pushes: it leaves at e times the normal speed at which it approached",
            {c.body1, c.body2}, -1, &d.system_laws[i]);
        for (const vec3 &t : d.system_tangents[i])
            add(d, dot(u2, t), 0, principle::stick, "Contact " + std::to_string(i) + " sticking: no slip after impact",
                {c.body1, c.body2}, -1, &d.system_laws[i]);
    }
}

} // namespace

void derive_system(derivation &d)
{
    d.system = true;
    d.impulse_form = true;
    std::vector<impulse_at> impulses;
    system_unknowns(d, impulses);
    body_equations(d, impulses);
    constraint_equations(d);
}

lst system_unknown_values(const derivation &d, const system_candidate &c)
{
    const problem &p = d.prob;
    lst out;
    for (std::size_t b = 0; b < p.bodies.size(); ++b)
        for (int k = 0; k < 3; ++k) {
            if (is_a<symbol>(d.velocity_after[b][k]))
                out.append(d.velocity_after[b][k] == c.velocity[b][k]);
            if (is_a<symbol>(d.angular_velocity_after[b][k]))
                out.append(d.angular_velocity_after[b][k] == c.angular_velocity[b][k]);
        }
    for (std::size_t k = 0; k < p.pivots.size(); ++k)
        for (int a = 0; a < p.dimension; ++a)
            out.append(d.pivot_impulse[k][a] == c.pivot_impulses[k][a]);
    std::size_t u = 0;
    for (const auto &s : d.system_unknowns)
        if (s.first.get_name().rfind("J_", 0) == 0) {
            const std::size_t j = u / static_cast<std::size_t>(p.dimension);
            out.append(s.first == c.joint_impulses[j][static_cast<int>(u % static_cast<std::size_t>(p.dimension))]);
            ++u;
        }
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        out.append(d.system_normal_impulse[i] == c.normal_impulse[i]);
        for (std::size_t k = 0; k < d.system_tangents[i].size(); ++k)
            out.append(d.system_tangent_impulse[i][k] == dot(c.tangential_impulse[i], d.system_tangents[i][k]));
    }
    return out;
}

} // namespace impactgen
