// Step 1 of draw(): numbers. Every symbol left in the problem gets an illustrative value and
// every expression is evaluated to a double, with a fallback wherever evaluation fails or is
// not finite (see figure.hpp, draw()).
#include "figure/values.hpp"

#include "figure/geometry.hpp"

#include <cmath>
#include <exception>

namespace impactgen::figure::detail
{
using namespace GiNaC;

/// The value of e with the illustrative values substituted, as a double; the
/// fallback when it does not evaluate to a finite real number.
double number(const ex &e, const exmap &values, double fallback)
{
    try {
        const ex v = (values.empty() ? e : e.subs(values)).evalf();
        if (is_a<numeric>(v)) {
            const numeric &x = ex_to<numeric>(v);
            if (x.is_real()) {
                const double r = x.to_double();
                if (std::isfinite(r))
                    return r;
            }
        }
    } catch (const std::exception &) {
        // a pole, an overflow in CLN: the fallback below
    }
    return fallback;
}

/// The symbols an expression contains (ordered, so the walk is deterministic).
std::vector<symbol> symbols_in(const ex &e)
{
    exset found;
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it))
            found.insert(*it);
    std::vector<symbol> out;
    for (const ex &s : found)
        out.push_back(ex_to<symbol>(s));
    return out;
}

/// Gives the symbols still open in e values: when e is linear in exactly one
/// open symbol with numeric coefficients, the value that makes e equal to
/// target; otherwise every open symbol of e takes the fallback.
void settle(exmap &known, const ex &e, double target, double fallback)
{
    ex r = e;
    try {
        if (!known.empty())
            r = e.subs(known);
    } catch (const std::exception &) {
        r = e;
    }
    const std::vector<symbol> open = symbols_in(r);
    if (open.empty())
        return;
    if (open.size() == 1) {
        try {
            const symbol &s = open[0];
            const ex x = r.expand();
            if (x.is_polynomial(s) && x.degree(s) == 1) {
                const ex a = x.coeff(s, 1).evalf(), b = x.coeff(s, 0).evalf();
                if (is_a<numeric>(a) && is_a<numeric>(b) && ex_to<numeric>(a).is_real() &&
                    ex_to<numeric>(b).is_real()) {
                    const double av = ex_to<numeric>(a).to_double(), bv = ex_to<numeric>(b).to_double();
                    const double v = (target - bv) / av;
                    if (av != 0 && std::isfinite(v) && std::abs(v) < 1e12) {
                        known[s] = numeric(v);
                        return;
                    }
                }
            }
        } catch (const std::exception &) {
            // not solvable: the fallback below
        }
    }
    for (const symbol &s : open)
        if (known.find(s) == known.end())
            known[s] = numeric(fallback);
}

/// A named class's symbol: the value the class gave it where it put it in a quantity
/// (problem::illustrative: bodies on their own side of the tangent plane, centres off the line of
/// impact for the non-central classes, velocities that approach), else by the quantity it is in
/// (a spin 0, an inertia entry 1 on the diagonal and 0 off it), anything else 1. Never by its name.
ex class_value(const problem &p, const symbol &s)
{
    const auto it = p.illustrative.find(s);
    if (it != p.illustrative.end())
        return it->second;
    for (const body &b : p.bodies)
        for (std::size_t r = 0; r < 3; ++r) {
            if (b.angular_velocity[r].is_equal(s))
                return numeric(0.0);
            for (std::size_t c = 0; c < 3; ++c)
                if (b.inertia[r][c].is_equal(s))
                    return numeric(r == c ? 1.0 : 0.0);
        }
    return numeric(1.0);
}

exmap illustrative_values(const problem &p)
{
    exmap known;
    const std::vector<symbol> all = p.parameters();
    if (all.empty())
        return known;
    if (p.illustrated) {
        for (const symbol &s : all)
            known[s] = class_value(p, s);
        return known;
    }
    const bool planar = p.dimension == 2;
    const int dim = planar ? 2 : 3;
    // Scalars first: masses, inertias, e, mu.
    for (const body &b : p.bodies) {
        if (!b.infinite_mass)
            settle(known, b.mass, 1, 1);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                settle(known, b.inertia[r][c], r == c ? (planar ? 0.2 : 1.0) : 0.0, r == c ? 1.0 : 0.0);
    }
    settle(known, p.restitution, 0.5, 0.5);
    settle(known, p.contact().friction(), 0.3, 0.3);
    // The normal (a symbolic component 1), the contact point (0).
    for (int c = 0; c < dim; ++c)
        settle(known, p.contact().normal[c], 1, 1);
    for (int c = 0; c < dim; ++c)
        settle(known, p.contact().point[c], 0, 0);
    const v3 n = unit({number(p.contact().normal[0], known, 0), number(p.contact().normal[1], known, 1),
                       planar ? 0 : number(p.contact().normal[2], known, 0)},
                      {0, 1, 0});
    const v3 t = planar ? v3{n.y, -n.x, 0} : unit(cross(std::abs(n.z) < 0.9 ? v3{0, 0, 1} : v3{1, 0, 0}, n), {1, 0, 0});
    const v3 o{number(p.contact().point[0], known, 0), number(p.contact().point[1], known, 0),
               planar ? 0 : number(p.contact().point[2], known, 0)};
    auto side = [&](std::size_t i) { return i == p.contact().body1 ? -1.0 : 1.0; };
    // Centres: 0.8 from O on the body's side, a rigid body's off the line of impact.
    std::vector<v3> centre(p.bodies.size());
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body &b = p.bodies[i];
        const double off = (b.particle || b.infinite_mass) ? 0.0 : 0.3 * side(i);
        const v3 target = o + (0.8 * side(i)) * n + off * t;
        const double tc[3] = {target.x, target.y, target.z};
        for (int c = 0; c < dim; ++c)
            settle(known, b.position[c], tc[c], tc[c]);
        centre[i] = {number(b.position[0], known, 0), number(b.position[1], known, 0),
                     planar ? 0 : number(b.position[2], known, 0)};
    }
    // A pivot beyond the centre, so that E, C and O are in line (a rod).
    for (const pivot &pv : p.pivots) {
        if (pv.body >= p.bodies.size())
            continue;
        const v3 c = centre[pv.body];
        const v3 target = c + (c - o);
        const double tc[3] = {target.x, target.y, target.z};
        for (int k = 0; k < dim; ++k)
            settle(known, pv.point[k], tc[k], tc[k]);
    }
    // Velocities that approach along the normal, spins 0.
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body &b = p.bodies[i];
        const v3 target = b.infinite_mass ? v3{} : (-0.8 * side(i)) * n + (0.3 * side(i)) * t;
        const double tc[3] = {target.x, target.y, target.z};
        for (int c = 0; c < dim; ++c)
            settle(known, b.velocity[c], tc[c], tc[c]);
        for (int c = 0; c < 3; ++c)
            settle(known, b.angular_velocity[c], 0, 0);
    }
    // Anything else (there should be nothing): 1.
    for (const symbol &s : all)
        if (known.find(s) == known.end())
            known[s] = numeric(1);
    return known;
}

} // namespace impactgen::figure::detail
