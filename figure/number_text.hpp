// Numbers as text for the figure's printers: fixed decimals, the same bytes
// in every locale and on every run.
#pragma once

#include <string>

namespace impactgen::figure::detail
{

/// v with three decimals, like "%.3f" in the C locale; a value that is not
/// finite prints as 0.000 and the magnitude is clamped to 1e9.
std::string decimal(double v);

} // namespace impactgen::figure::detail
