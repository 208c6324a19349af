// Coulomb's law (contact_law coulomb; the hooks of contact_law.hpp): the contact impulse with its
// friction part in the impulse-momentum equations, the law's stick and slide equations; the
// candidates stick and the slides (solve_friction, friction.cpp), or the phase sequences of
// Routh's process when the restitution law is followed through the impact (solve_routh,
// routh.cpp).
#include "contact_law.hpp"
#include "decide.hpp"
#include "derivation.hpp"
#include "friction.hpp"
#include "routh.hpp"

#include <set>
#include <string>

namespace impactgen
{
using namespace GiNaC;

namespace
{

// A name for a symbol of the friction impulse that no symbol of the problem nor an unknown has
// (a trailing _ is added), and its TeX form (the underscores kept: N_ -> N\_).
symbol fresh_impulse_symbol(const derivation &d, const std::string &base, const std::string &tex_base)
{
    std::set<std::string> taken;
    for (const symbol &s : d.prob.parameters())
        taken.insert(s.get_name());
    for (const unknown &u : d.unknowns)
        taken.insert(u.sym.get_name());
    std::string name = base, extra;
    while (taken.count(name)) {
        name += "_";
        extra += "\\_";
    }
    return symbol(name, tex_base + extra);
}

// Impulse-momentum of the bodies in contact with the whole contact impulse P (and the pivot
// impulse), and angular momentum about the pivot or about O.
void friction_momentum(const derivation &d, friction_equations &fe, int &label)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    const vec3 P = fe.impulse(dim, d.n_hat);
    auto add = [&](const ex &lhs, const ex &rhs, principle why, const std::string &reason, std::size_t body, int a) {
        fe.equations.push_back({std::to_string(++label), lhs, rhs, why, reason, {body}, a});
    };
    for (std::size_t i : {i1, i2}) {
        const body &b = p.bodies[i];
        if (b.infinite_mass)
            continue;
        const int s = i == i1 ? -1 : 1;
        const pivot *pv = p.pivot_of(i);
        const vec3 R = pv ? d.pivot_impulse[static_cast<std::size_t>(pv - p.pivots.data())] : zero_vec();
        const vec3 dp = b.mass * (d.velocity_after[i] - b.velocity);
        const std::string name = display_name(b);
        const std::string reason = "the change of linear momentum of " + name +
                                   " equals the impulses on it: " + (s < 0 ? "-P = -(N e_n + F)" : "P = N e_n + F") +
                                   (pv ? " and the pivot impulse R" : "") +
                                   "; with friction the tangential components change too";
        for (int a = 0; a < dim; ++a)
            add(tidy_expand(dp[a]), tidy_expand(ex(s) * P[a] + R[a]), principle::linear_impulse, reason, i, a);
        if (b.particle)
            continue;
        const int first = dim == 2 ? 2 : 0;
        if (pv) {
            const vec3 dH =
                mul(b.inertia, d.angular_velocity_after[i] - b.angular_velocity) + cross(b.position - pv->point, dp);
            const vec3 moment = cross(p.contact().point - pv->point, ex(s) * P);
            for (int a = first; a < 3; ++a)
                add(tidy_expand(dH[a]), tidy_expand(moment[a]), principle::angular_momentum,
                    "about the pivot E, fixed in the inertial frame, the pivot impulse has no moment: the change of "
                    "angular momentum of " +
                        name + " about E is the moment (O - E) × P of the contact impulse, its friction part included",
                    i, a);
        } else {
            const vec3 r = b.position - p.contact().point;
            const vec3 Ha = mul(b.inertia, d.angular_velocity_after[i]) + cross(r, b.mass * d.velocity_after[i]);
            const vec3 Hb = mul(b.inertia, b.angular_velocity) + cross(r, b.mass * b.velocity);
            for (int a = first; a < 3; ++a)
                add(tidy_expand(Ha[a]), tidy_expand(Hb[a]), principle::angular_momentum,
                    "the whole contact impulse on " + name +
                        ", normal and friction part alike, acts at O, which is fixed in the inertial frame: it has "
                        "no moment about O, so the angular momentum of " +
                        name + " about O is conserved, with friction as without",
                    i, a);
        }
    }
}

// The equations of Coulomb's law with Newton's restitution.
friction_equations derive_friction(const derivation &d)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    friction_equations fe;
    fe.N = d.impulse_form ? d.normal_impulse : ex(fresh_impulse_symbol(d, "N", "N"));
    if (dim == 2) {
        fe.F = {fresh_impulse_symbol(d, "F", "F")};
        fe.tangents = {d.t_dir};
    } else {
        for (const std::string t : {"t", "b"}) {
            fe.F.push_back(fresh_impulse_symbol(d, "F_" + t, "F_{" + t + "}"));
            fe.slide_d.push_back(fresh_impulse_symbol(d, "d_" + t, "d_{" + t + "}"));
        }
        fe.tangents = {d.e_t, d.e_b};
    }
    int label = 0;
    friction_momentum(d, fe, label);
    for (principle why : {principle::pivot_fixed, principle::restitution})
        for (const equation &eq : d.equations)
            if (eq.why == why)
                fe.equations.push_back(
                    {std::to_string(++label), eq.lhs, eq.rhs, eq.why, eq.reason, eq.bodies, eq.component});
    // Coulomb's law: one equation per tangent, different in each regime.
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    const ex mu = p.contact().friction();
    for (std::size_t k = 0; k < fe.tangents.size(); ++k) {
        const std::string tag = std::to_string(label + 1 + static_cast<int>(k));
        fe.stick_law.push_back({tag,
                                tidy_expand(dot(d.vB_after - d.vA_after, fe.tangents[k])),
                                0,
                                principle::stick,
                                "the contact points leave together along the tangent",
                                {i1, i2},
                                -1});
        const ex rhs = dim == 2 ? ex(-mu * fe.N) : ex(-mu * fe.N * fe.slide_d[k]);
        fe.slide_law.push_back({tag + "'",
                                fe.F[k],
                                rhs,
                                principle::slide,
                                "the friction impulse at the edge of the cone, against the slip",
                                {i1, i2},
                                -1});
    }
    return fe;
}

} // namespace

law_traits traits(const coulomb &, const problem &p)
{
    law_traits t;
    t.tangential_impulse = true;
    t.single_candidate = false;
    t.process = follows_process(p.contact().law_of_restitution);
    if (!t.process)
        t.jacobian = jacobian_route::per_regime;
    else
        t.jacobian = p.dimension == 2 ? jacobian_route::per_phase_sequence : jacobian_route::not_offered;
    return t;
}

void add_law_equations(const coulomb &, derivation &d)
{
    d.friction = derive_friction(d);
}

impact_solution solve_law(const coulomb &, const derivation &d)
{
    if (follows_process(d.prob.contact().law_of_restitution))
        return solve_routh(d); // Poisson's or the energetic law: Routh's process (routh.hpp)
    refuse_wedging(d);
    return solve_friction(d);
}

} // namespace impactgen
