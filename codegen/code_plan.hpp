// The code plan: what one header computes, whatever the contact's law. The steps every
// candidate shares, the candidates of the law (symbolic/friction.hpp's impact_solution)
// and the rule that selects among them:
//   none              one unconditioned candidate (a smooth contact): straight-line code,
//                     a branchless fast path and a vectorised batch loop;
//   first_that_holds  candidates in closed form with typed conditions (stick, the planar
//                     or isotropic slides): the first whose conditions hold, no branch;
//   sliding_angle     besides those, a 3-D slide whose direction is a root of a
//                     trigonometric polynomial found at run time (detail::trig2_roots);
//   process           the phase sequences of Routh's process (poisson, energetic with
//                     friction, symbolic/routh.hpp): the first whose conditions hold, no
//                     branch; the regime is its last phase (stick or slide).
//   system_sets       a system's candidates (symbolic/system.hpp: one per set of contact
//                     regimes, in the order solve_system tries them): each whose conditions
//                     hold within rounding is a solution; the first is the answer, another
//                     with different velocities makes it ambiguous, none is no_solution
//                     (first_that_holds stops at the first: it cannot tell these apart).
// A new contact law adds its candidates in symbolic/ and, when they need it, a selection
// rule here; the one writer (writer.hpp) emits any plan. No C++ text is made here.
// Private to the codegen library.
#pragma once

#include "codegen.hpp"

#include "symbolic/friction.hpp"
#include "symbolic/system.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace impactgen::codegen
{

enum class selection_rule { none, first_that_holds, sliding_angle, process, system_sets };

/// An output of the header: the smooth plan's (its value in inputs and steps), or, with a
/// tangential impulse, one of its world components (computed from the selected impulse).
struct code_output : output_value {
    bool tangential = false;
    int axis = 0;         ///< tangential: world axis
    std::size_t base = 0; ///< not tangential: index in plan::outputs
};

/// A system's candidate in the header: its set's name, the outputs' values, and its
/// conditions, each with the scale its rounding is measured against.
struct system_code_set {
    std::string name; ///< "{0 stick, 1 open}"
    std::vector<GiNaC::ex> values;
    struct condition {
        GiNaC::ex value;
        bool velocity = false;   ///< a velocity (scale: the contacts' speeds before), else an impulse
        std::size_t contact = 0; ///< the contact it is about
        std::string meaning;
        /// The value is 0 for every input (a slip that another contact's sticking fixes, a
        /// redundant contact's speed): it holds (>= 0) or fails (> 0) exactly as the exact
        /// decision has it, never by rounding.
        bool identically_zero = false;
        bool strict = false;
    };
    std::vector<condition> conditions;
    /// Perfectly rough contacts that stick: (normal impulse output, tangential outputs); with
    /// no normal impulse they carry no tangential one.
    std::vector<std::pair<std::size_t, std::vector<std::size_t>>> rough_sticks;
};

/// Sequential impacts (a system with "impacts": "sequential", frictionless contacts): the
/// chain's state and, per contact, its single-contact impact in that state.
struct system_sequence {
    std::vector<GiNaC::symbol> state; ///< per output: its value before a step (velocities; else unused)
    std::vector<GiNaC::ex> speeds;    ///< per contact: its normal speed u_k in the state (along n_k as given)
    /// Per contact k: contact k acting alone (system_step_candidates' acting candidate), the
    /// outputs in inputs and state (velocities after the step, this step's impulses) and the
    /// condition P_k >= 0; no values where contact k has none (it cannot take an impulse).
    std::vector<system_code_set> steps;
};

/// What a system's header computes besides its outputs' fields.
struct system_code {
    std::vector<system_code_set> sets;
    std::vector<GiNaC::ex> speeds;         ///< the contact rows' relative velocities before impact
    std::vector<GiNaC::ex> unit_mass;      ///< per contact 1 / W_nn: speed to impulse (an impulse's rounding scale)
    std::vector<std::size_t> velocities;   ///< outputs that are velocities (compared for ambiguity)
    std::vector<std::size_t> impulses;     ///< outputs that are contact impulses (the impulse scale)
    std::vector<std::size_t> all_impulses; ///< every impulse output (impulses_unique)
    std::vector<GiNaC::ex> unchanged;      ///< per output, the value of a failed call
    bool redundant_joints = false;         ///< the joints' impulses are never unique
    std::vector<GiNaC::ex> energy_before;  ///< kinetic energy before, and after in the selected velocities:
    GiNaC::ex energy_lost;                 ///< in inputs and the symbols sel (below)
    std::vector<GiNaC::symbol> sel;        ///< per output, the selected value
    std::vector<std::pair<GiNaC::ex, std::string>> checks; ///< value >= 0 or > 0 checks: (value, kind)
    bool sequential = false; ///< the chain of single-contact impacts (sequence), not the sets
    system_sequence sequence;
};

/// One candidate's Jacobian in the header: the steps its program binds after the shared ones
/// (candidates_jacobian::steps) and the derivatives of the rows.
struct candidate_jacobian {
    std::vector<step> steps;                     ///< its own steps and derivative steps, in order of evaluation
    std::vector<std::vector<GiNaC::ex>> entries; ///< [row][wrt]: d(row)/d(wrt), in inputs and steps
    std::size_t same_as = 0; ///< the first candidate with the same closed form: one program serves both
    /// The 3-D slide without a closed form (Coulomb friction): cos and sin of its sliding angle,
    /// which the program reads from the direction the function found (the derivatives through
    /// the implicit function theorem of its angle equation); else empty.
    std::vector<GiNaC::symbol> angle;
};

/// With --jacobian, a law with candidates: per candidate the exact derivatives of the header's
/// velocities (and impulses) by the inputs wrt, its closed form differentiated by the chain rule
/// through its steps. One type for Coulomb friction under Newton's law (rules first_that_holds and
/// sliding_angle: code_plan.cpp, symbolic/friction_jacobian.hpp), Routh's process (rule process:
/// process_plan.cpp, symbolic/process_jacobian.hpp) and a system's candidate sets (rule
/// system_sets: system_plan.cpp); the one writer (writer_jacobian.cpp) emits NAME_jacobian from it.
struct candidates_jacobian {
    bool on = false;
    std::vector<GiNaC::symbol> wrt;             ///< the inputs differentiated by, in order (the columns)
    std::vector<std::size_t> rows;              ///< indices in code_plan::outputs, in order (the rows)
    std::vector<step> steps;                    ///< bound first in every candidate's program (shared, derivatives)
    std::vector<candidate_jacobian> candidates; ///< per candidate (impact_solution::cases, system_code::sets)
    /// Routh's process: the scales of its conditions' rounding, which the function needs to tell
    /// whether another sequence holds within rounding (its out.boundary).
    struct rounding {
        GiNaC::ex speed;    ///< |u| before impact: the scale of a condition on velocities
        GiNaC::ex response; ///< (1 + mu) (K_tt + K_nn): of one on K (squared for mu^2 K_tt^2 - K_tn^2)
    };
    std::optional<rounding> process;
};

struct code_plan {
    selection_rule rule = selection_rule::none;
    /// The closed form of the problem without the law's own parameters (with friction: mu
    /// = 0): its inputs and their meanings, outputs, vector views and the state a failed
    /// call returns; rewritten for the engine input conventions.
    plan base;
    problem prob; ///< specialised, with its law
    std::vector<GiNaC::symbol> inputs;
    std::vector<std::string> input_meaning;
    std::vector<code_output> outputs;
    std::vector<std::size_t> base_index; ///< plan::outputs index -> index in outputs
    std::vector<std::size_t> tangential; ///< indices in outputs of the tangential impulse
    /// With a selection rule: the derivation (its tangent basis at run time when the normal
    /// is an input), the candidates, and the one the sliding-angle solve finds (or -1).
    derivation deriv;
    impact_solution candidates;
    int angle = -1;
    /// rule system_sets: the system's candidates.
    system_code system;
    /// --jacobian with a selection rule (the candidates' or the system's sets' Jacobians).
    candidates_jacobian jacobian;
};

/// A contact law's code plan: one overload per alternative of contact_law (the law's other
/// hooks: symbolic/contact_law.hpp). make_code_plan calls the overload of the contact's law
/// with the options' --set values folded in (a coefficient of friction set to 0 is the smooth
/// law); of the problem's own law when the options do not fit it, so that the plan reports the
/// error. frictionless: the smooth plan alone; coulomb: the candidates (stick and the slides,
/// or the phase sequences of Routh's process) and their selection rule.
code_plan law_code_plan(const frictionless &, const problem &p, const options &o);
code_plan law_code_plan(const coulomb &, const problem &p, const options &o);

/// Every symbol in e, added to out.
void collect_symbols(const GiNaC::ex &e, GiNaC::exset &out);

/// The outputs a candidates' Jacobian differentiates, in order: velocities, spins, the normal and
/// the tangential impulse (world axes); not pivot impulses, approach velocity, energy lost.
std::vector<std::size_t> candidate_rows(const code_plan &cp);

/// The value of output k (one of candidate_rows) for candidate c, its impulse applied.
GiNaC::ex candidate_output(const code_plan &cp, std::size_t k, const regime_case &c);

/// The candidates of Routh's process (process_plan.cpp): the phase sequences of the
/// derivation's contact, in the shared steps of its friction solution; the wedging
/// sequences left out (none holding is no_solution). Throws input_error when every
/// sequence wedges.
impact_solution process_candidates(const derivation &d);

/// --jacobian for rule process (process_plan.cpp): cp.jacobian from the candidates. Throws
/// option_error naming --wrt for a name that is not an input, --jacobian for a normal given as
/// inputs.
void process_jacobian_plan(code_plan &cp, const std::vector<std::string> &wrt);

/// The inputs a Jacobian differentiates by (jacobian.cpp): `wrt` by name among `inputs` (empty:
/// every input); throws option_error naming --wrt for a name that is not an input (listing them)
/// or is named twice, and naming --jacobian when there is none.
std::vector<GiNaC::symbol> jacobian_inputs(const std::vector<GiNaC::symbol> &inputs,
                                           const std::vector<std::string> &wrt);

/// The plan's inputs in order: --params as given, else the symbols in the order of the
/// problem's quantities, each with its meaning (plan.cpp).
void order_plan_inputs(plan &pl, const options &o);

/// The code plan of a system (system_plan.cpp): its candidates' values and conditions in the
/// inputs the options choose; for sequential impacts the chain's steps (system_sequence).
/// Throws input_error naming the key for sequential impacts with friction, and option_error
/// for the options a system does not take.
code_plan system_code_plan(const problem &p, const options &o);

/// The code plan of a problem under the options (the names of generate()).
code_plan make_code_plan(const problem &p, const options &o);

} // namespace impactgen::codegen
