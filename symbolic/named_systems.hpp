// The named system classes (problem format version 3): bodies joined by joints, several
// contacts in one impact. Each is a symbolic problem whose symbols keep the closed form short
// and free of trigonometric functions (positions and lever arms are symbols), with a worked
// example: numbers for every symbol, which documents use for the figure and the verdict.
#pragma once

#include "named_classes.hpp"

#include <string>
#include <utility>
#include <vector>

namespace impactgen
{

/// The named system classes, in the order `impactgen list` prints them.
const std::vector<named_class> &system_classes();

/// The worked example of a named system class: every symbol with an exact value, in the
/// class's order ("m=5", ...), or an empty list when `name` is not a system class.
std::vector<std::pair<std::string, std::string>> system_class_example(const std::string &name);

/// The symbol = value list of system_class_example(name), parsed exactly.
GiNaC::lst system_class_example_values(const std::string &name);

} // namespace impactgen
