// Routh's process for one planar contact with Coulomb friction, in closed form: the impact
// followed as the normal impulse P_n grows, restitution measured by Poisson's law or by
// Stronge's energetic coefficient (restitution_law.hpp).
//
// In the contact frame (e_t, n) the relative velocity of the contact points is
//   u(P) = u_0 + K P,   K = [[K_tt, K_tn], [K_tn, K_nn]]  (the contact response, response.hpp)
// and in each phase it is linear in P_n, with dP_t = r dP_n:
//   slide, slip sign s:  r = -s mu,         du_t/dP_n = a = K_tn - s mu K_tt,  du_n/dP_n = b = K_nn - s mu K_tn
//   stick (u_t = 0):     r = -K_tn / K_tt,  a = 0,                            b = det K / K_tt
// The phases (at most two):
//   1. slide along s = sign(u_t0); starting without slip, stick when mu K_tt >= |K_tn|, else slide
//      along s = sign(K_tn);
//   2. the slip reaches zero at x_s = -u_t / a when s a < 0; then stick when mu K_tt + s K_tn >= 0
//      (the sticking ratio |K_tn|/K_tt inside the cone), else reverse (slide along -s, whose slip
//      only grows: s a < 0 and mu K_tt < -s K_tn give (-s) a' > 0, and b' = K_nn + s mu K_tn > 0
//      by K_tn^2 <= K_tt K_nn).
// Compression ends where u_n = 0 (x_c = -u_n / b in the phase where b > 0; a slide with b <= 0
// whose slip never stops wedges: no finite impulse ends the compression, refused under every
// law). Restitution ends at
//   poisson     P_n = (1 + e) P_c
//   energetic   W_r = -e^2 W_c, W = int u_n dP_n; in a phase from u_n = v >= 0 with W_r short of
//               the target by R: x = 2 R / (v + sqrt(v^2 + 2 b R))  (x = sqrt(2 R / b) from v = 0).
// Each transition is a comparison of two closed forms; numbers are decided exactly (decide.hpp),
// symbols fork the process into phase sequences, each with the conditions that select it.
#pragma once

#include "friction.hpp"
#include "response.hpp"

#include <array>
#include <string>
#include <vector>

namespace impactgen
{

/// The process's inputs: the contact response in (t, n), the velocities before impact along
/// e_t and n, mu, e and the law. Numbers (then every decision is exact) or expressions.
struct process_inputs {
    ex Ktt, Ktn, Knn; ///< K in the contact frame (e_t, n)
    ex ut, un;        ///< u_0 . e_t and u_0 . n (< 0: an impact)
    ex mu, e;
    restitution_law law = poisson_restitution{};
    /// For deciding: each input symbol == its value in the problem's own symbols (or numbers);
    /// empty when the inputs are the values themselves.
    GiNaC::lst values;
};

/// One phase sequence of the process: its phases, the impulses and velocities at its end, and
/// the conditions (value > 0, or >= 0 when not strict) under which it is the process.
struct process_sequence {
    std::vector<process_phase> phases;
    ex compression_impulse; ///< P_c: u_n = 0
    ex compression_work;    ///< W_c = int_0^P_c u_n dP_n (<= 0)
    ex normal_impulse;      ///< P_n at the end of restitution
    ex tangential_impulse;  ///< P_t along e_t at the end
    ex tangential_velocity; ///< u'_t
    ex normal_velocity;     ///< u'_n
    bool wedges = false;    ///< compression never ends (this branch is refused)
    std::vector<process_condition> conditions;
};

/// Every phase sequence of the process for inputs with symbols, or the one that holds for
/// numbers (no conditions). With compression_only the walk stops where compression ends (the
/// wedge check of Newton's law). Numbers: throws input_error (naming `where`) when the contact
/// wedges, when the tangential impulse is not determined (K_tt = 0 without slip) or when a
/// decision cannot be made exactly.
std::vector<process_sequence> routh_process(const process_inputs &in, const std::string &where,
                                            bool compression_only = false);

/// The candidates of a derivation whose contact has friction and follows poisson or energetic:
/// one regime_case per phase sequence (its `process` and `process_conditions`), each with the
/// bodies after impact through the response layer. 2-D only (the reader refuses 3-D).
impact_solution solve_routh(const derivation &d);

/// Newton's law with Coulomb friction (law_coulomb.cpp) in 2-D: refuses (input_error naming contact.friction) a numeric
/// problem whose contact wedges. Symbolic problems and 3-D pass.
void refuse_wedging(const derivation &d);

/// The contact's response and velocities in (e_t, n) as step symbols of `s` (2-D): the inputs of
/// the process with `values` set for deciding.
process_inputs process_inputs_of(const derivation &d, solution &s);

/// The two bodies of the contact with their inverse inertia (planar: the [2][2] entry), as
/// apply_impulse takes them.
std::array<contact_side, 2> process_sides(const problem &p);

/// A one-line refusal for the outputs that do not teach or generate the process yet: throws
/// input_error naming contact.law when the problem's contact has friction and a law other than
/// newton. `what` names the output ("explain", "codegen").
void require_newton_for_output(const problem &p, const std::string &what);

/// A candidate's solution from its impulse c.impulse (world, on body 2), the friction candidates'
/// and the process's alike: the bodies after impact, the pivots' impulses (planar: no z
/// component), the unknowns' values and the energies; with tidied, each velocity after and
/// the energy lost tidied.
void apply_impulse(const derivation &d, const std::array<contact_side, 2> &sides, regime_case &c, bool tidied);

} // namespace impactgen
