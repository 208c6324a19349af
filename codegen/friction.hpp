// Code generation for impacts with Coulomb friction (symbolic/friction.hpp): one
// dependency-free C++17 header per problem whose function computes the frictional
// impact and selects the regime by the derived inequalities.
//
//   problem --(--set, --params)--> derive --> solve_friction (closed forms of every regime)
//           --> canonical trees --> straight-line programs with CSE --> C++ (emit_cpp),
//
// the same pipeline as the smooth headers (codegen.hpp), in stages: the shared steps,
// the validity checks, every closed-form candidate and its conditions (one program);
// the sliding directions of a 3-D slide without closed form (the roots of a
// trigonometric polynomial of degree 2 whose coefficients are derived here, found at
// run time by detail::trig2_roots) and that slide at each of them (a second program);
// the frictionless impact for mu = 0 (a third); and the post-impact state for the
// impulse of the regime that holds (a fourth). The header's preamble shares the smooth
// headers' (impact_status, view, detail helpers: one copy per namespace) and adds
// friction_status, impact_regime and the root finder under a guard of its own: the files
// codegen/runtime/impact_runtime.hpp and friction_runtime.hpp, emitted verbatim.
#pragma once

#include "codegen.hpp"

namespace impactgen::codegen
{

/// True when the problem, with the options' --set values folded in, has Coulomb friction
/// (a coefficient that is not identically 0): `impactgen codegen` then calls
/// generate_friction, else generate. A problem the options do not fit (an unknown
/// symbol, say) counts as having friction when it has a coefficient at all, so that
/// generate_friction reports the error.
bool has_friction(const problem &p, const options &o);

/// The header for a problem with friction. Options as for generate(): name, ns, source,
/// version, params (mu may be named: a numeric coefficient of friction is then lifted
/// to the parameter mu), set, unit_normal. The engine conventions (--inverse-mass,
/// --inverse-inertia) and Jacobians are not offered for friction: option_error.
header generate_friction(const problem &p, const options &o);

} // namespace impactgen::codegen
