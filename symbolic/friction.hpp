// Impact with Coulomb friction (problem format version 2, contact.set_friction(mu).
//
// The contact impulse on body 2 is P = P_n n + P_t (P_t normal to n); on body 1 it is -P).
// Each body's impulse-momentum equations are linear in P, so the relative velocity
// of the contact points after impact is
//
//   u' = u + K P,        K = K_1 + K_2   (the contact response, symmetric)
//   K_i P = P / m_i + (I_i^{-1} (r_i x P)) x r_i       free body, r_i = O - C_i
//   K_i P = (I_{E,i}^{-1} (rho_i x P)) x rho_i         pinned at E, rho_i = O - E
//   K_i = 0                                           infinite mass, pinned particle
//
// (a particle drops the rotational term). With u_n = u.n < 0 the approach velocity,
// Newton's law u'.n = -e u_n and Coulomb's law give three kinds of solution:
//
//   stick   u'_t = 0:        P = -K^{-1} (u + e u_n n)       holds when |P_t| <= mu P_n
//   slide   along a unit d (tangent): P = P_n (n - mu d),
//           D = n.K(n - mu d),  P_n = -(1 + e) u_n / D,  u' = u + P_n K (n - mu d)
//           holds when D > 0 and u'_t = lambda d with lambda > 0
//   planar: d = +e_t or -e_t (two closed forms);
//   3-D, K isotropic on the tangent plane and K n parallel to n (spheres, particles,
//   central impacts of spheres): d = u_t / |u_t| (closed form);
//   3-D otherwise: d = cos(theta) e_t + sin(theta) e_b with theta a root of
//           g(theta) = n . (h x d),  h = D u + a K (n - mu d),  a = -(1 + e) u_n,
//           a trigonometric polynomial of degree 2 (at most four roots).
//
// Exactly one kind must hold; a problem for which none or several hold is refused
// naming them. mu = 0 is the smooth impact of solution.hpp, unchanged.
#pragma once

#include "decide.hpp"
#include "solution.hpp"

#include <string>
#include <vector>

namespace impactgen
{

enum class regime { smooth, stick, slide };
/// "smooth", "stick" or "slide": the answer's regime key.
const char *regime_name(regime r);

/// value > 0 (strict) or value >= 0, in the case's steps and the inputs.
/// What a regime's inequality says (printers word it from this, never from `meaning`).
enum class condition_kind {
    cone_below,        ///< mu N - F >= 0: planar stick, inside the cone
    cone_above,        ///< mu N + F >= 0: planar stick, inside the cone
    pushes,            ///< N >= 0: the contact pushes
    cone,              ///< mu^2 N^2 - |F|^2 >= 0: 3-D stick, inside the cone
    slide_denominator, ///< D_s > 0
    slides             ///< lambda > 0: the contact slides along d after impact
};

struct regime_condition {
    ex value;
    bool strict = true;
    std::string meaning; ///< plain text, e.g. "mu P_n - P_t >= 0 (inside the cone)"
    condition_kind kind = condition_kind::pushes;
};

/// One candidate solution of the law: a regime with its closed form (in steps)
/// and the inequalities under which it is the answer.
struct regime_case {
    regime kind = regime::stick;
    int sign = 0;            ///< planar slide: +1 when u'_t points along +e_t, -1 along -e_t
    std::string name;        ///< "stick", "slide along +e_t", "slide along u_t", "slide"
    bool has_angle = false;  ///< a 3-D slide whose angle was found (numeric problems)
    double angle = 0;        ///< then: the sliding angle from e_t towards e_b, radians
    solution sol;            ///< steps (the shared ones first), bodies after, P_n, pivot impulses, energies
    vec3 impulse;            ///< P in world axes, on body 2
    vec3 tangential_impulse; ///< P_t = P - P_n n, world axes, on body 2
    ex tangential_scalar;    ///< planar: P_t . e_t; 3-D: 0
    vec3 direction;          ///< slide: the unit sliding direction d (world); stick: zero
    ex sliding_speed;        ///< slide: lambda = u'_t . d; stick: 0
    std::vector<regime_condition> conditions;
    /// 3-D slide without a closed form: d = c e_t + s e_b with these two symbols
    /// (cos and sin of the sliding angle), and the equation g(c, s) = 0 they solve.
    bool needs_angle = false;
    GiNaC::symbol dir_c{"c_d"}, dir_s{"s_d"};
    ex angle_equation; ///< g, in steps and dir_c, dir_s
    /// Poisson's or the energetic law with friction (symbolic/routh.hpp): the phases of the process
    /// in order (empty for newton), and the conditions that select this phase sequence (empty for a
    /// numeric problem, whose one sequence was decided exactly).
    std::vector<process_phase> process;
    std::vector<process_condition> process_conditions;
};

/// The one solution type of an impact, whatever the contact's law: the steps every
/// candidate shares, then the candidates, each with its own steps, impulse and the typed
/// conditions that select it. A smooth contact has one candidate (regime::smooth, no
/// conditions: the closed form of solution.hpp); Coulomb friction has stick (unless the
/// contact response K is singular: then `no_stick` says why) and the slides.
struct impact_solution {
    ex mu;                          ///< the coefficient of friction (0 for a smooth contact)
    solution shared;                ///< the steps every candidate starts with (K, u, u_n, ...)
    std::string no_stick;           ///< why there is no stick candidate (K singular), or empty
    vec3 n_hat, e_t, e_b;           ///< the unit contact frame (e_b zero in 2-D)
    bool isotropic = false;         ///< 3-D: K isotropic on the tangent plane and uncoupled from n
    std::vector<regime_case> cases; ///< the candidates: stick first (when there is one), then the slides
    /// The contact's restitution law. With friction and poisson or energetic, `cases` are the phase
    /// sequences of Routh's process (symbolic/routh.hpp): one for a numeric problem, decided exactly.
    restitution_law law = newton_restitution{};

    /// The stick candidate, or nullptr (a smooth contact, or K singular).
    const regime_case *stick() const;
};
/// The name the friction printers and writers still use for it.
using friction_solution = impact_solution;

/// Every candidate of the contact's law in closed form: one for a smooth contact, stick and
/// slides with Coulomb friction (solve_friction).
impact_solution solve_impact(const derivation &d);

/// A numeric problem's answer: the smooth candidate as it is (its printer substitutes), or
/// the one candidate of the law that holds (select_regime).
regime_case select_candidate(const derivation &d, const impact_solution &s);

/// The closed forms of every regime. The derivation must have been made for a problem
/// with friction (mu may be symbolic). When the contact response K is singular (a pinned
/// body struck by an immovable one: the contact point can only move along a line), there
/// is no stick candidate (no_stick says why) and the slides are the candidates.
friction_solution solve_friction(const derivation &d);

/// A numeric problem's answer: the one regime that holds, its values substituted
/// (exact where the closed form is; for a 3-D slide without one, the sliding angle at
/// 50 significant digits). Decided exactly or refused: input_error naming the regimes
/// when none holds, several hold, or the decision is too close to call.
regime_case select_regime(const derivation &d, const friction_solution &f);

/// Every regime that holds for a numeric problem (select_regime's candidates; a 3-D slide
/// without closed form gives one case per sliding angle that holds). Throws input_error
/// when a condition cannot be decided or the problem has symbols.
std::vector<regime_case> holding_regimes(const derivation &d, const friction_solution &f);

/// The sign of a constant condition: decide() (decide.hpp), and where its magnitude bound leaves
/// double's range (a term of 10^-400 from a tiny mu) CLN floats at 60 and 120 digits that agree
/// to 30 digits; else the undecided decision.
decision decide_condition(const ex &value);

/// The conditions of the case, as values (inputs substituted), for tests.
std::vector<ex> condition_values(const regime_case &c, const ex &input_values = GiNaC::lst{});

} // namespace impactgen
