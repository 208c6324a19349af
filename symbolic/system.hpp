// Systems (problem format version 3): bodies joined by joints and pivots, several contacts
// acting in one impact (simultaneously, or one at a time in sequence).
//
// The notes' constrained-collision method: each body's impulse-momentum with every joint,
// pivot and contact impulse acting on it. In generalized velocities v (per movable body: the
// centre's velocity, then the angular velocity unless it is a particle) with the block-diagonal
// mass matrix M, every constraint is a row a_r: the relative velocity of two material points
// along a direction, w_r = a_r v + c_r (c_r: the part of bodies of infinite mass). With lambda
// the row impulses,
//
//   M (v' - v) = A^T lambda,     w' = w + H lambda,     H = A M^-1 A^T.
//
// Joints and pivots are kept as bilateral rows (w'_J = 0, lambda_J free) and eliminated once
// by the Schur complement, which gives the Delassus matrix of the contacts:
//
//   W = H_CC - H_CJ H_JJ^-1 H_JC,   lambda_J = -H_JJ^-1 H_JC lambda_C,   u' = u + W lambda_C.
//
// (Kept as rows rather than eliminated by generalized coordinates: the rows are the world
// components the answer reports as joint and pivot impulses, they need no null-space basis
// -- which in closed form brings choices and square roots -- and the joint velocities before
// impact are zero, so eliminating them leaves q = u unchanged.)
//
// Each contact i has a normal row (along n_i as given, so no square root enters the law) and,
// with friction, tangent rows (2-D: t_i = (-n_y, n_x), as long as n_i; 3-D perfectly rough: two
// tangents). The law per contact, 0 <= P_i _|_ u'_i + e_i u_i >= 0 with Coulomb or no slip, is
// solved by one closed-form candidate per active set and regime: open (P_i = 0), smooth,
// stick (u'_t,i = 0), slide (2-D: P_t,i = -s mu_i P_i, s = +-1, with s u'_t,i >= 0: a slide with
// zero slip is the impulse on the cone's edge, which Coulomb's law allows). Each candidate's
// linear system is square; a singular one gives its basic solutions. The solutions of a set
// under the law's inequalities form a polyhedron; each of its vertices is a basic solution of
// some set, its active inequalities being open contacts (P_i = 0) or cone edges (slides with
// zero slip), so the law holds for some candidate whenever it holds at all. For a numeric
// problem every condition is decided exactly.
#pragma once

#include "problem.hpp"

#include <string>
#include <vector>

namespace impactgen
{

/// The regime of one contact in a candidate: the answer's contacts[i].regime.
enum class contact_regime { open, smooth, stick, slide };
const char *contact_regime_name(contact_regime r);

/// One inequality of a candidate, in the problem's values: value > 0 (strict) or >= 0.
struct system_condition {
    ex value;
    bool strict = false;
    std::string meaning;     ///< e.g. "P_0 >= 0 (contacts[0] pushes)" (formulas: the inequality and the key)
    std::string words;       ///< the same in a person's words, for documents: "contact 0 pushes"
    bool velocity = false;   ///< a velocity after impact (open, slide direction), else an impulse
    std::size_t contact = 0; ///< the contact it is about
};

/// One candidate of the law: a regime per contact, its closed form and its conditions.
struct system_candidate {
    std::vector<contact_regime> regimes;
    std::vector<int> slide_sign;                  ///< +1 / -1 for a 2-D slide along +t / -t, else 0
    std::vector<ex> normal_impulse;               ///< P_i >= 0 along the unit normal, on body 2
    std::vector<vec3> tangential_impulse;         ///< world axes, on body 2
    std::vector<ex> normal_velocity_after;        ///< u'_i = (v'_B - v'_A) . n_i / |n_i|
    std::vector<vec3> joint_impulses;             ///< on each joint's second body
    std::vector<vec3> pivot_impulses;             ///< on each pivot's body
    std::vector<vec3> velocity, angular_velocity; ///< per body, after impact
    std::vector<system_condition> conditions;
    std::vector<ex> impulses; ///< every row impulse (joints, pivots, contacts): uniqueness checks
    /// Contact 0's phases when it follows Routh's process (poisson, energetic with friction;
    /// system_process.hpp), P_n along the unit normal at each phase's end; else empty.
    std::vector<process_phase> process;
    /// "{0 stick, 1 open}": the set, for messages and formulas.
    std::string name() const;
};

/// The answer of a system for a numeric problem.
struct system_answer {
    system_candidate result;           ///< regimes, impulses (summed over steps when sequential), velocities
    bool impulses_unique = true;       ///< false: the velocities are unique, the impulses one valid choice
    bool sequential = false;           ///< "impacts": "sequential"
    std::vector<std::size_t> sequence; ///< the contacts in the order they acted (sequential)

    /// Sequential: per step, its impulses and the velocities after it (explain shows the chain).
    std::vector<system_candidate> steps;
    ex energy_before, energy_after;
    bool energy_gain = false; ///< kinetic energy gained with no moving body of infinite mass doing work
};

/// Every candidate of the simultaneous law in closed form (symbolic or numeric problem);
/// a singular set gives its basic solutions. Throws input_error for too
/// many candidate sets (more than 4096), or sequential impacts (no closed form: the chain
/// depends on the numbers).
std::vector<system_candidate> system_candidates(const problem &p);

/// One step of sequential impacts: the candidates with contact k alone acting (every other
/// contact open), in the order solve_system's chain tries them, for the problem's velocities
/// before that step (sequential or not: the chain's step is decided as a simultaneous law of
/// one contact). Throws input_error as system_candidates does (k out of range: std::out_of_range).
std::vector<system_candidate> system_step_candidates(const problem &p, std::size_t k);

/// A numeric problem's answer: the candidate that holds, decided exactly (simultaneous), or
/// the chain of single-contact impacts (sequential, at most 64 steps). Refuses, naming the
/// key, when no candidate holds, when two hold with different velocities (naming the sets),
/// or when the problem has symbols.
system_answer solve_system(const problem &p);

/// For a candidate of a numeric problem: decided exactly as solve_system decides, the index of
/// its first condition that fails, conditions.size() when a sticking contact with no normal
/// impulse would carry a tangential one, or -1 when the law holds for it.
long system_candidate_failure(const system_candidate &c);

/// The Delassus matrix of a system's contact rows (the joints and pivots eliminated) and the
/// rows' velocities before impact: u' = u + W lambda. Rows per contact: its normal (along n_i
/// as given), then its tangents; `rows` names them "n0", "t0", "b0".
struct system_delassus {
    std::vector<std::vector<ex>> W;
    std::vector<ex> u;
    std::vector<std::string> rows;
    bool redundant_joints = false; ///< dependent joint rows left out (the impulses are not unique)
};
system_delassus system_delassus_of(const problem &p);

/// The kinetic energy of the bodies of finite mass, for velocities per body.
ex system_kinetic_energy(const problem &p, const std::vector<vec3> &v, const std::vector<vec3> &w);

/// Throws input_error saying that `command` does not handle systems yet, when p is one.
void refuse_system_for(const problem &p, const std::string &command);

} // namespace impactgen
