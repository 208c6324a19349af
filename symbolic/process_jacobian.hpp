// The Jacobian of the impact map under Routh's process (poisson, energetic with friction, one
// planar contact), per phase sequence. Inside one phase sequence the impact map is a closed form
// (routh.hpp), smooth where every condition that selects the sequence holds strictly; its
// derivatives by the inputs are exact, by the chain rule through the contact's steps (K_tt, K_tn,
// K_nn, u_t, u_n): d out/dx = (partial out/partial x) + sum_k (partial out/partial s_k) ds_k/dx.
// Where a condition is 0 the problem sits on the boundary between two sequences: the map is
// continuous there, but its derivative is in general one-sided (each neighbour's own).
#pragma once

#include "friction.hpp"

#include <string>
#include <vector>

namespace impactgen
{

struct sequence_jacobian {
    std::string sequence;                        ///< the candidate's name: "process: slide, stick"
    std::vector<process_condition> conditions;   ///< the conditions that select it (> 0 or >= 0)
    std::vector<std::vector<GiNaC::ex>> entries; ///< [output][input], in inputs, steps and step derivatives
};

struct process_jacobian {
    std::vector<GiNaC::symbol> wrt;           ///< the inputs (the problem's symbols, or those asked)
    std::vector<std::string> outputs;         ///< "normal_impulse", "tangential_impulse", "v'_x,rod", ...
    std::vector<step> steps;                  ///< the contact's steps (as the solution has them)
    std::vector<step> derivative_steps;       ///< d s_k / d x_j, named d<s_k>_d<x_j> (zeros left out)
    std::vector<sequence_jacobian> sequences; ///< one per phase sequence of the solution
};

/// The derivatives of a chain of steps by the inputs (forward mode, exact): d s_k / d x_j by the
/// chain rule through the earlier steps, each nonzero one that is not a number a step of its own
/// (named d<s_k>_d<x_j>), so that outputs differentiated with chain_derivative share them.
struct step_gradients {
    std::vector<step> derivative_steps;   ///< in order of evaluation
    std::vector<std::vector<ex>> of_step; ///< [step][input]: 0, a number, or a derivative step's symbol
};
step_gradients differentiate_steps(const std::vector<step> &steps, const std::vector<GiNaC::symbol> &wrt);

/// d v / d wrt[j] for a value v in inputs and the steps: its partial derivatives, plus through
/// each step the chain rule's term (tidied).
ex chain_derivative(const ex &v, const std::vector<step> &steps, const step_gradients &g,
                    const std::vector<GiNaC::symbol> &wrt, std::size_t j);

/// The Jacobian of each phase sequence of a solution whose candidates follow Routh's process.
/// `wrt` names inputs (empty: every symbol of the problem). Throws input_error naming --wrt for a
/// name that is not a symbol of the problem, or --jacobian when there is none.
process_jacobian process_jacobian_of(const derivation &d, const impact_solution &s,
                                     const std::vector<std::string> &wrt);

/// The inputs a Jacobian differentiates by: those named in `wrt` (each a symbol of the problem,
/// named once: else input_error naming --wrt), or every symbol of the problem (none: input_error
/// naming --jacobian).
std::vector<GiNaC::symbol> jacobian_inputs(const problem &p, const std::vector<std::string> &wrt);

/// True when the solution's candidates are the phase sequences of Routh's process.
bool solution_follows_process(const impact_solution &s);

} // namespace impactgen
