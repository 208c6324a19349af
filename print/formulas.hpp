// The closed form of a solution as text or LaTeX: the named intermediate
// quantities in order, then every unknown written through them.
#pragma once

#include "symbolic/friction.hpp"
#include "symbolic/friction_jacobian.hpp"
#include "symbolic/process_jacobian.hpp"
#include "symbolic/system_jacobian.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace impactgen::print
{

std::string formulas_text(const derivation &d, const solution &s);
std::string formulas_latex(const derivation &d, const solution &s);

/// With friction: the shared steps, then each regime's closed form and the
/// inequalities that select it, and the threshold mu* = |P_t| / P_n of sticking.
std::string formulas_text(const derivation &d, const friction_solution &f);
std::string formulas_latex(const derivation &d, const friction_solution &f);
/// {"regimes": [{"regime", "case", "steps", "answer", "conditions"}], "stick_threshold"}:
/// expressions in GiNaC's syntax, in the steps (which read back in order).
nlohmann::ordered_json formulas_json(const derivation &d, const friction_solution &f);

/// False when the stick impulse is a number (every value but mu given) and pulls (N <= 0): no mu sticks,
/// and no threshold is printed.
bool stick_can_hold(const derivation &d, const friction_solution &f);

/// The threshold of sticking: stick holds iff mu >= mu* = |P_t| / P_n, where P is the
/// stick impulse (which does not depend on mu). In the stick case's steps; for a planar
/// problem |P_t| is written as an absolute value.
GiNaC::ex stick_threshold(const derivation &d, const friction_solution &f);

/// A system (format version 3): every candidate of the law (a regime per contact) with its
/// closed form and the conditions under which it is the answer.
std::string system_formulas_text(const problem &p, bool latex);
/// {"candidates": [{"set", "regimes", "answer", "conditions"}]}: expressions in GiNaC's syntax.
nlohmann::ordered_json system_formulas_json(const problem &p);
/// formulas --jacobian of a system: after the candidates, each set's Jacobian of the velocities
/// after impact by the inputs (symbolic/system_jacobian.hpp), in the candidates' notation.
std::string system_jacobian_text(const problem &p, const system_jacobian &j, bool latex);
/// {"wrt": [..], "sets": [{"set", "conditions", "matrix": {output: {input: d}}}]}
nlohmann::ordered_json system_jacobian_json(const problem &p, const system_jacobian &j);

/// formulas --jacobian under Routh's process: each phase sequence's conditions and its
/// derivatives (symbolic/process_jacobian.hpp); with latex, every line a LaTeX comment.
std::string process_jacobian_text(const process_jacobian &j, bool latex);
/// {"wrt", "steps", "sequences": [{"sequence", "conditions", "matrix": {output: {input: d}}}], "boundary"}
nlohmann::ordered_json process_jacobian_json(const process_jacobian &j);
/// formulas --jacobian with Coulomb friction under Newton's law: each regime's conditions and
/// derivatives (symbolic/friction_jacobian.hpp), the 3-D slide without a closed form through its angle.
std::string friction_jacobian_text(const friction_jacobian &j, bool latex);
/// {"wrt", "steps", "regimes": [{"regime", "conditions", "through_angle", "steps", "matrix"}], "boundary"}
nlohmann::ordered_json friction_jacobian_json(const friction_jacobian &j);

} // namespace impactgen::print
