// The Jacobian of the impact map with Coulomb friction under Newton's law (friction.hpp), per
// regime candidate: stick, the planar slides along +e_t and -e_t, the isotropic 3-D slide along
// u_t, and the 3-D slide whose direction d = cos(theta) e_t + sin(theta) e_b is a root of the
// angle equation g(theta) = 0 (no closed form).
//
// Inside a regime (every condition strict) the map is that candidate's closed form and smooth;
// its derivatives by the inputs are exact, by the chain rule through the candidate's steps:
//   d out/dx = (partial out/partial x) + sum_k (partial out/partial s_k) ds_k/dx.
// The 3-D slide without a closed form is differentiated through the implicit function theorem
// of its angle equation: theta(x) is defined by g(x, theta) = 0 and, at a simple root
// (dg/dtheta != 0),
//   dtheta/dx = -(dg/dx) / (dg/dtheta),   d out/dx = (d out/dx)|_theta + (d out/dtheta) dtheta/dx,
// with d/dtheta acting on c = cos(theta), s = sin(theta) as dc = -s, ds = c. The entries are
// then written in the steps, the candidate's c and s (the root found for the numbers) and the
// derivative steps. At a double root (dg/dtheta = 0) the direction is not differentiable.
// Where a condition of the regime is 0 the problem sits on the boundary between two regimes:
// the map is continuous there (stick and slide give one impulse), its derivative one-sided.
#pragma once

#include "friction.hpp"

#include <functional>
#include <string>
#include <vector>

namespace impactgen
{

struct regime_jacobian {
    std::string name;                                  ///< the candidate's name: "stick", "slide along +e_t", ...
    impactgen::regime kind = impactgen::regime::stick; ///< stick or slide
    int sign = 0;                                      ///< planar slide: +1 along +e_t, -1 along -e_t
    std::vector<regime_condition> conditions;          ///< the conditions that select it
    /// d s_k / d x_j of the candidate's own steps (named d<s_k>_d<x_j>); for the slide without a
    /// closed form also d s_k / d theta (d<s_k>_dtheta), dg/dtheta and dtheta/dx_j.
    std::vector<step> derivative_steps;
    bool through_angle = false;                  ///< differentiated through the angle equation
    GiNaC::symbol dir_c{"c_d"}, dir_s{"s_d"};    ///< then: cos and sin of the sliding angle
    ex angle_slope;                              ///< then: dg/dtheta (its step symbol); != 0 at a simple root
    std::vector<std::vector<GiNaC::ex>> entries; ///< [output][input]
};

struct friction_jacobian {
    std::vector<GiNaC::symbol> wrt;     ///< the inputs (the problem's symbols, or those asked)
    std::vector<std::string> outputs;   ///< "normal_impulse", "tangential_impulse[_x]", "v'_x,body", ...
    std::vector<step> steps;            ///< the shared steps (K, u, u_n), as the solution has them
    std::vector<step> derivative_steps; ///< d s_k / d x_j of the shared steps (zeros left out)
    std::vector<regime_jacobian> regimes;
};

/// The Jacobian of each regime candidate of a solution with Coulomb friction under Newton's law
/// (solve_friction). `wrt` names inputs (empty: every symbol of the problem). Throws input_error
/// naming --wrt for a name that is not a symbol of the problem or one named twice, or --jacobian
/// when the problem has no symbol.
friction_jacobian friction_jacobian_of(const derivation &d, const impact_solution &s,
                                       const std::vector<std::string> &wrt);

/// The outputs a Jacobian differentiates: (name, value in the candidate's steps and inputs).
using candidate_outputs = std::function<std::vector<std::pair<std::string, GiNaC::ex>>(const regime_case &)>;

/// The same for the inputs `wrt` (symbols of the problem) and the outputs `outputs_of` gives each
/// candidate (the same names, in the same order, for every candidate): what codegen compiles.
friction_jacobian friction_jacobian_of(const impact_solution &s, const std::vector<GiNaC::symbol> &wrt,
                                       const candidate_outputs &outputs_of);

/// The outputs of a candidate, in the order of friction_jacobian::outputs: the normal impulse,
/// the tangential impulse (planar: along e_t; 3-D: world components), then each body of finite
/// mass's velocity after impact (world components) and, unless it is a particle, its spin.
std::vector<std::pair<std::string, GiNaC::ex>> friction_outputs(const problem &p, const regime_case &c);

} // namespace impactgen
