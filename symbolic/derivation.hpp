// The equations of one impact, written the way the lecture notes write them:
// every equation carries the principle it comes from and the bodies involved.
//
// Free bodies (no pivots) -- the notes' unconstrained impact:
//   smooth contact        (v'_i - v_i) . e_t = 0, (v'_i - v_i) . e_b = 0      (each movable body)
//   system momentum       sum_i m_i v'_i . n = sum_i m_i v_i . n          (both bodies of finite mass)
//   angular momentum at O I_i w'_i + r_{C_i O} x m_i v'_i = I_i w_i + r_{C_i O} x m_i v_i
//   restitution           (v'_B - v'_A) . n = -e (v_B - v_A) . n,  v_A = v_C1 + w_1 x r_{A C1}
// With a pivot -- the notes' constrained collision: impulse-momentum for each
// body with the normal impulse N and the pivot impulses R as further unknowns:
//   linear impulse        m_i (v'_i - v_i) = s_i N n + R_i               (s_1 = -1, s_2 = +1)
//   angular impulse       about the pivot E (or about O for a free body)
//   pivot fixed           v'_i + w'_i x r_{E C_i} = 0
//   restitution           as above
#pragma once

#include "problem.hpp"
#include "system.hpp"

#include <string>
#include <vector>

namespace impactgen
{

enum class principle {
    smooth_contact,   ///< no tangential impulse: tangential COM velocity unchanged
    system_momentum,  ///< the contact impulse is internal to the pair of bodies
    angular_momentum, ///< about O (or the pivot), where the impulsive moment vanishes
    linear_impulse,   ///< impulse-momentum of one body with the unknown impulses
    pivot_fixed,      ///< the pivot point does not move
    restitution,      ///< Newton's law on the contact points' normal velocities
    stick,            ///< Coulomb's law, sticking: no tangential relative velocity after impact
    slide             ///< Coulomb's law, sliding: the friction impulse at the cone's edge, against the slip
};
const char *principle_name(principle p);

struct equation {
    std::string label; ///< "1", "2", ... in the order derived
    ex lhs, rhs;
    principle why;
    std::string reason;              ///< one sentence: why this equation holds (the same for every component)
    std::vector<std::size_t> bodies; ///< indices into problem::bodies
    int component = -1;              ///< world axis of a vector equation's component, -1 for a scalar equation
};

enum class unknown_kind { velocity, angular_velocity, normal_impulse, pivot_impulse };

struct unknown {
    GiNaC::symbol sym;
    unknown_kind kind;
    std::size_t owner = 0; ///< body index, or pivot index for pivot impulses
    int component = 0;     ///< world axis 0..2
    std::string meaning;
};

/// Why a principle gives no usable equation, or a body takes no part.
enum class remark_kind {
    momentum_infinite_mass,  ///< system momentum along n: m (v'_n - v_n) is infinity times zero
    infinite_mass_unchanged, ///< an infinite mass keeps its velocities (no angular momentum equation)
    particle_no_rotation,    ///< a particle has no angular velocity unknowns
    pinned_particle,         ///< a particle pinned at a fixed point cannot move
    uninvolved               ///< a body not in the contact
};

struct remark {
    remark_kind kind;
    std::size_t body; ///< the body it is about
    std::string text; ///< one sentence in ASCII (for logs and tests)
};

/// With Coulomb friction: the contact impulse P = N e_n + sum_k F_k t_k on body 2 (-P on body
/// 1) with its unknowns, and the equations the law implies: impulse-momentum of each body with
/// the whole impulse P (and the pivot impulse), angular momentum about the pivot or about O,
/// the pivots' fixedness, restitution; then Coulomb's law, one equation per tangent, in each of
/// its two forms (stick: the tangential relative velocity after impact is 0; slide: F = -mu N d).
struct friction_equations {
    ex N;                                       ///< the normal impulse (the unknown in impulse form, else a symbol)
    std::vector<ex> F;                          ///< the friction impulse along each tangent (symbols)
    std::vector<vec3> tangents;                 ///< planar: t_dir; 3-D: e_t, e_b
    std::vector<ex> slide_d;                    ///< 3-D: the sliding direction's components along e_t, e_b (symbols)
    std::vector<equation> equations;            ///< numbered 1, 2, ...: impulse-momentum, pivots, restitution
    std::vector<equation> stick_law, slide_law; ///< per tangent: (k) and (k') after the last of `equations`
    /// P in world components, in N and F.
    vec3 impulse(int dimension, const vec3 &n_hat) const;
};

struct derivation {
    problem prob;
    bool impulse_form = false; ///< true when a pivot makes the impulses unknowns
    std::vector<unknown> unknowns;
    std::vector<equation> equations;
    std::vector<remark> remarks; ///< principles that give no usable equation, and why
    /// With Coulomb's law (law_coulomb.cpp): the equations of its law (`equations` above are
    /// those of the smooth impact, which the friction solution reduces to for mu = 0).
    friction_equations friction;

    vec3 n_hat;                       ///< unit normal n / |n| (n itself when normal_assumed_unit)
    ex normal_length;                 ///< |n| (1 when normal_assumed_unit)
    bool normal_assumed_unit = false; ///< derived with the normal taken as a unit vector (derive_options::unit_normal)
    vec3 t_dir, b_dir;                ///< tangent directions (b_dir zero in 2-D); not unit in general
    /// The unit tangents, e_t = t_dir/|t_dir| and e_b = e_t × n_hat (zero in 2-D), with their
    /// roots as root_of writes them: the frame friction, explain's contact-frame view and its
    /// tables use.
    vec3 e_t, e_b;
    bool frame_is_world = false; ///< e_t, e_n, e_b are world axes (up to sign)
    /// derive_options::runtime_tangent_basis took effect: e_t and e_b are these symbols
    /// (e_t's three components, then e_b's), computed at run time from the normal by the
    /// generated code, not formulas in it (t_dir and b_dir stay the formulas).
    std::vector<GiNaC::symbol> tangent_basis_symbols;

    /// Velocity, angular velocity after impact: unknown symbols, or the
    /// values before for bodies the impact does not change.
    std::vector<vec3> velocity_after, angular_velocity_after;
    std::vector<vec3> pivot_impulse; ///< in unknown symbols (impulse form only)
    ex normal_impulse;               ///< the unknown N (impulse form only), else 0
    vec3 vA, vB, vA_after, vB_after; ///< contact point velocities

    /// A system (problem::is_system, format version 3; system_derivation.cpp): `equations` are
    /// each body's impulse-momentum with every joint, pivot and contact impulse acting on it
    /// (angular momentum about the centre, or about the fixed pivot), then the joints' and the
    /// pivots' velocity conditions; system_unknowns lists the unknowns (velocities after, then
    /// the impulses); system_laws[i] is contact i's law in its acting form (restitution, then
    /// no slip along each tangent for stick), system_tangents[i] its unit tangents.
    bool system = false;
    std::vector<std::pair<GiNaC::symbol, std::string>> system_unknowns;
    std::vector<std::vector<equation>> system_laws;
    std::vector<std::vector<vec3>> system_tangents;
    std::vector<GiNaC::symbol> system_normal_impulse;               ///< P_i, along the unit normal
    std::vector<std::vector<GiNaC::symbol>> system_tangent_impulse; ///< F_ik, along system_tangents[i][k]

    std::size_t count_equations() const { return equations.size(); }
    std::size_t count_unknowns() const { return unknowns.size(); }
    /// All the unknown symbols, in order.
    GiNaC::lst unknown_symbols() const;
};

struct derive_options {
    /// The contact normal is a unit vector as given (the engine convention): n_hat = n,
    /// never divided by |n|. Only the caller can know it (a symbolic normal's inputs are
    /// then promised to have length 1); a constant normal of another length is the
    /// caller's to refuse (codegen's --unit-normal does).
    bool unit_normal = false;
    /// 3-D, a normal with symbols and no zero entry: e_t and e_b become symbols
    /// (derivation::tangent_basis_symbols) for generated code that computes them at run
    /// time. The formulas e_t = t_dir/|t_dir| divide by zero where the normal lies along
    /// the world axis t_dir is made from (n = (0, 0, 1) for a symbolic normal): no single
    /// formula serves every direction.
    bool runtime_tangent_basis = false;
};

derivation derive(const problem &p, const derive_options &options = {});

/// The equations of a system (derive() calls it for problem::is_system).
void derive_system(derivation &d);
/// symbol == value for every unknown of a system's derivation at the candidate's values: the
/// derived equations' residuals are then zero (tests).
GiNaC::lst system_unknown_values(const derivation &d, const system_candidate &c);

/// A body label as a subscript after another one: "1" stays "1", a longer label gets a comma
/// (",ball"); the TeX form sets a long label as text.
std::string label_subscript(const std::string &label);
std::string label_subscript_tex(const std::string &label);

/// Names a symbol of a body's quantity for printing: base, axis, body label,
/// e.g. ("v", "t", "1", true) -> v'_t1.
std::string quantity_name(const std::string &base, const std::string &axis, const std::string &body_label, bool after);
std::string quantity_tex(const std::string &base_tex, const std::string &axis, const std::string &body_label,
                         bool after);

} // namespace impactgen
