// The equations of a smooth impact in contact-frame components (t, n, b) when the
// contact normal is not a world axis, the way the notes write them: the smooth-contact
// equation of a body whose normal is (3/5, 4/5) reads v′_t = v_t, not
// 4 v′_x/5 - 3 v′_y/5 = 4 v_x/5 - 3 v_y/5.
//
// The derivation stays in world components (its unknowns are what the answer
// reports); this is a view for teaching. Every world velocity (and, in 3-D, angular
// velocity and pivot impulse) that is an unknown, or an input given as one plain
// symbol per component, is written through its contact-frame components,
//   v_x = e_t,x v_t + e_n,x v_n + e_b,x v_b,
// exact because e_t, e_n, e_b are orthonormal (exactly: e_n = n/|n|, e_t the
// normalised projection of a world axis, e_b = e_t × e_n); and each vector equation
// (angular momentum, impulse-momentum, a fixed pivot) is projected on e_t, e_n, e_b
// in place of x, y, z. In plane motion e_b is the world's z (e_t × e_n = +z), so
// spins stay ω_z.
#pragma once

#include "symbolic/derivation.hpp"

#include <string>
#include <vector>

namespace impactgen::print
{

/// A contact-frame component that the view names: v′_t,puck = e_t · v′_puck.
struct frame_component {
    GiNaC::symbol sym;
    GiNaC::ex world;     ///< the same in world components (a combination of world symbols or inputs)
    std::string meaning; ///< what it is: "velocity of the centre of mass of puck after impact"
    std::string axis;    ///< the axis of the component: "t" (the contact frame), "x" (world), or "" (none)
};

/// An unknown of the derivation as a component: its words from its kind and owner, and its
/// world axis (a normal impulse keeps its own words and has no axis).
frame_component unknown_component(const problem &p, const unknown &u);

/// One equation of the derivation as the view prints it.
struct framed_equation {
    const equation *source = nullptr; ///< label, principle and bodies
    GiNaC::ex lhs, rhs;
    std::string axis; ///< "t", "n", "b" (projected), a world axis name, or "" (a scalar equation)
};

struct contact_frame_view {
    bool active = false;                   ///< false: the equations print in world components as derived
    int count = 0;                         ///< 2 (e_t, e_n) or 3 (e_t, e_n, e_b)
    vec3 e[3];                             ///< unit e_t, e_n, e_b
    GiNaC::exmap to_frame;                 ///< world symbol -> its contact-frame combination
    std::vector<frame_component> unknowns; ///< the derivation's unknowns as the view names them, in its order
    std::vector<frame_component> inputs;   ///< the inputs before impact it renamed
    /// In 3-D, the entries of a body's inertia tensor about C in the contact frame,
    /// e_t·I e_n, ..., that the projected angular momentum equations use.
    std::vector<frame_component> inertia;
    std::vector<framed_equation> equations;

    /// x with the world symbols written through their contact-frame components (tidy).
    GiNaC::ex apply(const GiNaC::ex &x) const;
    /// values (a list of symbol == number) with the renamed inputs' and the inertia entries' values appended.
    GiNaC::lst with_inputs(const GiNaC::ex &values) const;
};

/// The view of d, active when the normal is a fixed (symbol-free) direction other
/// than a world axis and the named world axes are x, y, z (a named class with axes
/// t, n, b is already in the contact frame), and when it does not make the
/// equations longer (a normal with unlike radicals may not simplify); inactive
/// otherwise, with `equations` then the derivation's own.
contact_frame_view contact_frame_view_of(const derivation &d);
/// The inactive view: the derivation's unknowns and equations in world components.
contact_frame_view world_components_view(const derivation &d);

} // namespace impactgen::print
