// The impact classes of the lecture notes as ready-made problems, with
// symbols named as the notes name them (contact frame e_t, e_n, e_b = world x, y, z).
#pragma once

#include "problem.hpp"

#include <string>
#include <vector>

namespace impactgen
{

struct named_class {
    std::string name;
    std::string description;
    problem (*build)();
};

/// All named classes, in the order of the notes.
const std::vector<named_class> &named_classes();
/// Past the notes: the classes with Coulomb friction (format version 2).
const std::vector<named_class> &friction_classes();
/// Past the notes: the classes whose restitution law is followed through the impact (version 3,
/// "law"; symbolic/routh.hpp).
const std::vector<named_class> &law_classes();
/// The class of that name (smooth or with friction), or nullptr.
const named_class *find_named_class(const std::string &name);

} // namespace impactgen
