// The Jacobian of a system's impact map (format version 3, simultaneous impacts): for every
// candidate set of the law (system.hpp's system_candidates), the derivatives of the velocities
// after impact by the problem's symbols, each set's closed form differentiated exactly. Inside
// a set (its conditions strict) the map is that set's rational function and smooth; on a
// boundary between sets it is continuous where the velocities agree, with one-sided derivatives.
// These are the derivatives the generated NAME_jacobian computes for the selected set.
#pragma once

#include "system.hpp"

#include <string>
#include <vector>

namespace impactgen
{

/// A velocity after impact of one body of finite mass: its centre's component, or its spin's.
struct system_velocity_output {
    std::size_t body = 0;
    bool angular = false;
    int component = 0; ///< 0, 1, 2 for x, y, z (a planar spin: 2)
};

struct system_set_jacobian {
    system_candidate candidate;
    std::vector<std::vector<GiNaC::ex>> entries; ///< [output][input]: d(output)/d(input)
};

struct system_jacobian {
    std::vector<GiNaC::symbol> wrt;              ///< the inputs, in the order given (default: every symbol)
    std::vector<system_velocity_output> outputs; ///< per body of finite mass: v'_x, v'_y (, v'_z), then its spin
    std::vector<system_set_jacobian> sets;
};

/// Every candidate set's Jacobian. `wrt` names the inputs (empty: every symbol of the problem);
/// a name that is not a symbol of the problem, or one named twice, is refused naming --wrt.
/// Refuses a numeric problem (nothing to differentiate by) and sequential impacts.
system_jacobian system_jacobian_of(const problem &p, const std::vector<std::string> &wrt);

} // namespace impactgen
