// The closed-form solution of a derivation, kept structured: named
// intermediate quantities (lever arms, effective inverse masses, approach
// velocity, the normal impulse) followed by every unknown written through them.
//
//   w_i = 1/m_i + (r_i x n)^T I_i^{-1} (r_i x n)   free body, r_i = O - C_i
//   w_i = (rho_i x n)^T I_{E,i}^{-1} (rho_i x n)    pinned at E, rho_i = O - E,
//         I_E = I_C + m (|d|^2 1 - d d^T), d = C - E
//   w_i = 0                                        infinite mass, pinned particle
//   u   = (v_B - v_A) . n        (< 0: the contact points approach)
//   N   = -(1 + e) u / (w_1 + w_2)
//   v'_i = v_i + s_i N n / m_i,  w'_i = w_i + s_i N I^{-1} (r_i x n),  s_1 = -1, s_2 = +1
#pragma once

#include "derivation.hpp"

#include <set>
#include <string>
#include <vector>

namespace impactgen
{

/// What a step of the closed form is. Code generation, the explanation and the
/// checks find steps by role (and body, component), never by the printed name:
/// a user's symbol named u is a symbol, not the approach velocity.
enum class step_role {
    lever_arm,              ///< (r x n) of a body about C (free) or E (pinned), one component
    pivot_inertia,          ///< a body's inertia about its pivot E (planar scalar, or a tensor entry)
    inertia_determinant,    ///< det of a body's inertia tensor (3-D; none for a diagonal tensor)
    angular_response,       ///< g = I^{-1} (r x n) of a body, one component
    effective_inverse_mass, ///< w_i of a body at the contact point along n
    approach_velocity,      ///< u = (v_B - v_A) . n before impact
    contact_inverse_mass,   ///< k = w_1 + w_2
    normal_impulse,         ///< N = -(1 + e) u / k
    energy_lost,            ///< T - T' of the bodies of finite mass
    // Friction (symbolic/friction.hpp): world axes in row/column.
    inverse_inertia,      ///< an entry of a body's inverse inertia tensor (about C, or E when pinned)
    contact_response,     ///< an entry of K = K_1 + K_2: change of u per unit impulse on body 2
    relative_velocity,    ///< a component of u = v_B - v_A before impact
    response_determinant, ///< det K (stick)
    impulse_component,    ///< a component of the contact impulse P on body 2
    tangential_impulse,   ///< P_t along e_t (planar), or a world component of P_t
    slide_denominator,    ///< D = n.K(n - mu d): normal response while sliding along d
    slide_direction,      ///< a world component of the sliding direction d
    separation_velocity   ///< a component of u' after impact (tangential: sliding speed)
};

inline constexpr std::size_t no_body = static_cast<std::size_t>(-1);

struct step {
    GiNaC::symbol sym;
    ex value; ///< in inputs and earlier steps
    std::string meaning;
    step_role role = step_role::lever_arm;
    std::size_t body = no_body; ///< the body the step belongs to, or no_body
    int row = -1, column = -1;  ///< world axis of a vector component (row), tensor entry (row, column)
};

struct body_state {
    vec3 velocity, angular_velocity;
};

struct solution {
    std::vector<step> steps;
    std::vector<body_state> after;               ///< every body, in steps and inputs
    ex normal_impulse;                           ///< integral of N dt along the unit normal, >= 0
    std::vector<vec3> pivot_impulses;            ///< on each pivot's body, world axes
    ex energy_before, energy_after, energy_lost; ///< lost is a step: the work of the contact impulse
    ex energy_after_direct;                      ///< sum of 1/2 m v'.v' + 1/2 w'.I w', for checks
    GiNaC::lst unknown_values;                   ///< unknown == value (in steps), for every unknown of the derivation

    /// The step of that role (and body, and component when given), or nullptr
    /// when the value was too simple to name (then it appears inline).
    const step *find(step_role role, std::size_t body = no_body, int row = -1, int column = -1) const;
    step *find(step_role role, std::size_t body = no_body, int row = -1, int column = -1);

    /// e with every step symbol replaced by its definition, recursively.
    ex expand_steps(const ex &e) const;
    /// The value of every step for the given inputs (numbers stay exact).
    GiNaC::lst step_values(const ex &input_values) const;
};

solution solve(const derivation &d);

/// Names the steps of a solution: a step's name never equals a problem symbol's or an
/// earlier step's (a trailing _ is added); values too simple to name stay inline.
class step_builder
{
public:
    step_builder(solution &s, const problem &p);
    /// A named step, or the value itself when it is too simple to name (unless force).
    ex add(step_role role, std::size_t body, int row, int column, const std::string &name, const std::string &tex,
           const ex &value, const std::string &meaning, bool force = false);

private:
    solution &s_;
    std::set<std::string> taken_;
};

/// Each equation with the solution substituted, normalised: all zero when the
/// closed form is right. Substitutes input values first when given; with input
/// values the residuals are normalised only where cheap (tidy). A problem without
/// symbols but with irrational numbers gets 60-digit float residuals (a correct
/// closed form leaves them below 1e-40 relative to the values).
std::vector<ex> residuals(const derivation &d, const solution &s, const ex &input_values = GiNaC::lst{});

/// Whether a value written in the solution's steps and any symbols is zero.
/// Without symbols: decided exactly (decide.hpp), refused with input_error
/// (starting with `what`) when it cannot be. With symbols: evaluated exactly
/// at random positive rational points (fixed seed): one non-zero value proves
/// it is not identically zero; a rational function that vanishes at six random
/// points drawn from 10^6 values per symbol is zero but with probability below
/// (degree/10^6)^6 (Schwartz-Zippel). Never expands or normalises the closed
/// form, whose size grows fast in 3-D.
bool vanishes_identically(const solution &s, const ex &value, const std::string &what);

/// unknown == value for every unknown of the derivation, read from the solution's bodies after
/// impact, normal impulse and pivot impulses.
GiNaC::lst unknown_values(const derivation &d, const solution &s);

/// The solution's energy_before and energy_after_direct, from the bodies before and after.
void set_energies(const problem &p, solution &s);

/// Kinetic energy of the bodies of finite mass (1/2 m v.v + 1/2 w.I w).
ex kinetic_energy(const problem &p, const std::vector<vec3> &v, const std::vector<vec3> &w);

} // namespace impactgen
