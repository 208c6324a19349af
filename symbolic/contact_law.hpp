// A contact law's part of the one-contact pipeline. Each alternative of contact_law
// (problem.hpp) defines the overloads below in one file of its own (law_frictionless.cpp,
// law_coulomb.cpp): the equations it adds to the derivation, its candidates, and the traits
// the printers, the figure and the code plan ask of it. The callers reach them through the
// *_of functions below, each a std::visit (contact_law.cpp), so a new alternative does not
// build until it declares every overload here and defines it in its file: no caller falls
// silently into another law's branch.
//
// Beside this file a law writes its chapter of the document (print/explain_law.hpp, one
// file print/explain_law_*.cpp) and its code plan (law_code_plan, codegen/code_plan.hpp).
#pragma once

#include "problem.hpp"

namespace impactgen
{

struct derivation;
struct impact_solution;

/// How the derivatives of the closed form are offered (formulas --jacobian).
enum class jacobian_route {
    closed_form,        ///< the one candidate's closed form differentiated (codegen::plan)
    per_regime,         ///< each regime's closed form (symbolic/friction_jacobian.hpp)
    per_phase_sequence, ///< each phase sequence of Routh's process (symbolic/process_jacobian.hpp)
    not_offered         ///< refused, with the reason, by the closed form's plan (codegen::make_plan)
};

/// What the pipeline asks of a contact's law.
struct law_traits {
    /// The law lets an impulse act in the tangent plane: the answer's tangential impulse and
    /// regime, the figure's friction arrow.
    bool tangential_impulse = false;
    /// One unconditioned candidate, the smooth closed form of solution.hpp (else several,
    /// each with the conditions that select it).
    bool single_candidate = true;
    /// The candidates are the phase sequences of Routh's process: the restitution law
    /// (poisson, energetic) is followed through the impact.
    bool process = false;
    jacobian_route jacobian = jacobian_route::closed_form;
};

// ---- what each law defines (one file each) ----

law_traits traits(const frictionless &, const problem &p);
law_traits traits(const coulomb &, const problem &p);

/// The equations the law adds to the derivation (derive() writes the smooth impact's).
void add_law_equations(const frictionless &, derivation &d);
void add_law_equations(const coulomb &, derivation &d);

/// Every candidate of the law in closed form (solve_impact).
impact_solution solve_law(const frictionless &, const derivation &d);
impact_solution solve_law(const coulomb &, const derivation &d);

// ---- the dispatch to the overloads of the (one) contact's law (contact_law.cpp) ----

law_traits law_traits_of(const problem &p);
void add_law_equations_of(derivation &d);
impact_solution solve_law_of(const derivation &d);

} // namespace impactgen
