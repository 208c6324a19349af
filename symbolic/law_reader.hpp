// The reader's part for "law" (restitution_law.hpp): the key in `contact` and in `contacts[]`
// entries, and the refusals the format lists for it. Called by problem.cpp's reader.
#pragma once

#include "problem.hpp"

namespace impactgen
{

/// Reads the contact object's optional "law" into c.law_of_restitution (newton when absent).
/// Refuses an unknown name, a law that is not a string, and "poisson"/"energetic" with
/// "friction": "inf" (a perfectly rough contact never slips: there is no process to follow).
void read_law_of_restitution(const json_value &contact_object, const std::string &where, contact_spec &c);

/// Refuses "poisson"/"energetic" with friction on an entry of a `contacts` list of more than one
/// contact (the process of several contacts at once has no closed form). A smooth entry takes any law.
void refuse_process_laws_in_systems(const json_value &contacts_list);

/// The checks that need the whole problem: "poisson"/"energetic" with friction in 3-D (the slip
/// direction turns continuously along the process: no closed form) and with several contacts.
void check_law_of_restitution(const problem &p);

} // namespace impactgen
