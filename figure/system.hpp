// A figure of a planar system (problem format version 3): every body, joint, pivot and
// contact, drawn from the problem's own numbers into the same `drawing` that to_tikz(),
// to_svg() print (figure.hpp).
//
// A body of finite mass is drawn through the points where it is attached (its joints, pivot
// and contacts) and their reflections through its centre: a rod for a leg or a pendulum's
// link, a box for a body that touches at two corners, a disc for a particle (its radius the
// distance to its nearest contact point). A body of infinite mass is a hatched ground
// through its contact points. Each contact point O_i carries the normal impulse P_i on its
// second body and -P_i on its first (drawn along the normal, the sense in which it counts
// positive); each joint J_j its impulse on the second body and the reaction on the first
// (drawn along the answer when one is given, else along +x); each centre its velocity
// before impact.
#pragma once

#include "figure/figure.hpp"

#include <optional>
#include <string>
#include <vector>

namespace impactgen::figure
{

/// The drawing of a numeric planar system, or nothing (3-D or symbols: no figure).
/// `joint_impulses`: the answer's impulse of each joint on its second body, or null.
std::optional<drawing> draw_system(const impactgen::problem &p, const std::vector<vec3> *joint_impulses = nullptr);

/// One line of alternative text: "stance (rod), swing (rod), ground (ground); 1 joint; 2 contacts".
std::string describe_system(const impactgen::problem &p, const drawing &g);

} // namespace impactgen::figure
