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

#include <string>
#include <vector>

namespace impactgen {

struct step {
    GiNaC::symbol sym;
    ex value;            ///< in inputs and earlier steps
    std::string meaning;
};

struct body_state {
    vec3 velocity, angular_velocity;
};

struct solution {
    std::vector<step> steps;
    std::vector<body_state> after;       ///< every body, in steps and inputs
    ex normal_impulse;                   ///< integral of N dt along the unit normal, >= 0
    std::vector<vec3> pivot_impulses;    ///< on each pivot's body, world axes
    ex energy_before, energy_after, energy_lost; ///< lost is a step: the work of the contact impulse
    ex energy_after_direct;              ///< sum of 1/2 m v'.v' + 1/2 w'.I w', for checks
    GiNaC::lst unknown_values;           ///< unknown == value (in steps), for every unknown of the derivation

    /// e with every step symbol replaced by its definition, recursively.
    ex expand_steps(const ex& e) const;
    /// The value of every step for the given inputs (numbers stay exact).
    GiNaC::lst step_values(const ex& input_values) const;
};

solution solve(const derivation& d);

/// Each equation with the solution substituted, normalised: all zero when the
/// closed form is right. Substitutes input values first when given.
std::vector<ex> residuals(const derivation& d, const solution& s, const ex& input_values = GiNaC::lst{});

/// Kinetic energy of the bodies of finite mass (1/2 m v.v + 1/2 w.I w).
ex kinetic_energy(const problem& p, const std::vector<vec3>& v, const std::vector<vec3>& w);

} // namespace impactgen
