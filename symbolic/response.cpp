#include "response.hpp"

#include "decide.hpp"

namespace impactgen
{
using namespace GiNaC;

mat3 inertia_about(const body &b, const vec3 &E)
{
    const vec3 d = b.position - E;
    const ex dd = dot(d, d);
    mat3 J;
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c)
            J[a][c] = tidy(b.inertia[a][c] + b.mass * ((a == c ? dd : ex(0)) - d[a] * d[c]));
    return J;
}

body_response response_of(const problem &p, std::size_t index, const vec3 &Q)
{
    const body &b = p.bodies[index];
    body_response r;
    r.index = index;
    r.movable = !p.immovable(index);
    if (!r.movable)
        return r;
    const pivot *pv = p.pivot_of(index);
    r.pinned = pv != nullptr;
    r.particle = b.particle;
    r.mass = b.mass;
    r.lever = r.pinned ? Q - pv->point : Q - b.position;
    if (r.pinned) {
        r.arm = b.position - pv->point;
        r.inertia = inertia_about(b, pv->point);
    } else {
        r.inertia = b.inertia;
    }
    return r;
}

vec3 spin_change(const body_response &r, const mat3 &inv, const vec3 &P)
{
    if (!r.movable || r.particle)
        return zero_vec();
    return mul(inv, cross(r.lever, P));
}

vec3 centre_velocity_change(const body_response &r, const vec3 &P, const vec3 &dw)
{
    if (!r.movable)
        return zero_vec();
    return r.pinned ? cross(dw, r.arm) : (1 / r.mass) * P;
}

vec3 point_velocity_change(const body_response &r, const mat3 &inv, const vec3 &P)
{
    if (!r.movable)
        return zero_vec();
    vec3 v = r.pinned ? zero_vec() : (1 / r.mass) * P;
    if (!r.particle)
        v = v + cross(spin_change(r, inv, P), r.lever);
    return v;
}

vec3 pivot_impulse(const body_response &r, const vec3 &P, const vec3 &dv)
{
    return r.mass * dv - P;
}

} // namespace impactgen
