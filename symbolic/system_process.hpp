// Routh's process for the one frictional contact of a system (problem format version 3): a
// `contacts` file with one contact under "poisson" or "energetic", with joints and pivots.
//
// The joints and pivots are eliminated as for every system (system.hpp): the contact's rows, its
// normal n (as given, of length L) and its tangent t = (-n_y, n_x) (of the same length), see
// u' = u + W lambda with W the 2x2 Delassus matrix. In the process (routh.hpp) the unit frame
// only scales: K = W / L^2, u = q / L, P = L lambda, so the process run on (W, q) gives the
// row impulses lambda directly (Coulomb's cone |lambda_t| <= mu lambda_n, Poisson's ratio of
// normal impulses and the normal work int q_n d lambda_n = int u_n dP_n are the same in either
// frame), with no square root of L^2.
#pragma once

#include "system.hpp"

namespace impactgen
{

/// True for a system whose one contact has friction (not "inf") and a law measured through the
/// impact (poisson, energetic): its candidates are the phase sequences of Routh's process.
bool system_follows_process(const problem &p);

/// The phase sequences of the process as system candidates (contact 0's `process`, its regime
/// the last phase's: stick, or slide for a slide or a reversal; the conditions that select each),
/// plus the open candidate (the contact does not approach). A numeric problem gets the one that
/// holds, decided exactly; input_error (naming contacts[0].friction) when the contact wedges.
std::vector<system_candidate> system_process_candidates(const problem &p);

/// (system.cpp) The candidate whose contact-row impulses are lambda (rows ordered as
/// system_delassus_of names them), with contact 0's regime and slide sign: every joint and
/// pivot impulse, the bodies after impact and the contacts' normal velocities after.
system_candidate system_candidate_of_impulses(const problem &p, const std::vector<ex> &lambda, contact_regime regime,
                                              int slide_sign);

} // namespace impactgen
