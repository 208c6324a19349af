// Each body's response to an impulse applied at a point, written once: the smooth closed
// form, the friction candidates and the generated code all build on it.
//
//   free body      v' = v + P / m,   w' = w + I_C^{-1} (r x P),   r = Q - C
//   pinned at E    w' = w + I_E^{-1} (rho x P),  v' = v + (w' - w) x (C - E),  rho = Q - E,
//                  I_E = I_C + m (|d|^2 1 - d d^T), d = C - E   (planar: I_C + m |d|^2)
//                  the pivot's impulse R = m (v' - v) - P
//   a particle has no rotational term; a body of infinite mass or a pinned particle
//   does not move.
//
// The inverse inertia is the caller's to keep (as named steps, or inline): the functions
// below take it as given.
#pragma once

#include "problem.hpp"

namespace impactgen
{

struct body_response {
    std::size_t index = 0;
    bool movable = false;      ///< the impulse moves the body (not of infinite mass, not a pinned particle)
    bool pinned = false;       ///< the body turns about a fixed pivot E
    bool particle = true;      ///< no rotational inertia
    ex mass = 0;               ///< m (movable bodies)
    vec3 lever = zero_vec();   ///< r = Q - C (free) or rho = Q - E (pinned), Q the point of the impulse
    vec3 arm = zero_vec();     ///< d = C - E of a pinned body, else zero
    mat3 inertia = zero_mat(); ///< about C (free: as given) or about E (pinned: parallel-axis theorem)
};

/// One body of a contact: its response, the sign of the contact impulse it receives (body 1
/// -P, body 2 +P) and its inverse inertia about C (free) or E (pinned) as the caller keeps it
/// (planar: [2][2] only).
struct contact_side {
    body_response r;
    int sign = 1;
    mat3 inv = zero_mat();
};

/// The inertia of a body about the point E: I_C + m (|d|^2 1 - d d^T), d = C - E, each entry
/// tidied (planar problems read the [2][2] entry, I_C + m |d|^2).
mat3 inertia_about(const body &b, const vec3 &E);

/// The response of body `index` of p to an impulse at the point Q.
body_response response_of(const problem &p, std::size_t index, const vec3 &Q);

/// The change of angular velocity for the impulse P at the point: inv (lever x P), with inv
/// the inverse of the response's inertia (zero for a particle or an immovable body).
vec3 spin_change(const body_response &r, const mat3 &inv, const vec3 &P);

/// The change of the centre of mass's velocity for the impulse P, given the change of
/// angular velocity dw (spin_change): P / m for a free body, dw x d for a pinned one.
vec3 centre_velocity_change(const body_response &r, const vec3 &P, const vec3 &dw);

/// The change of the velocity of the point Q for the impulse P at Q (K_i P, the body's part
/// of the contact response): P / m + (inv (r x P)) x r for a free body, (inv (rho x P)) x rho
/// for a pinned one.
vec3 point_velocity_change(const body_response &r, const mat3 &inv, const vec3 &P);

/// The impulse the pivot of a pinned body exerts on it while P acts at Q: m dv - P.
vec3 pivot_impulse(const body_response &r, const vec3 &P, const vec3 &dv);

} // namespace impactgen
