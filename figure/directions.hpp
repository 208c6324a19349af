// Which way the figure draws the impulses and spins (figure.cpp's helper, not installed API).
//
// A numeric problem: every impulse along the answer -- the pivot impulse R as the answer's R,
// the friction impulse F on body 2 as the answer's tangential impulse (none when it is 0) --
// and each spin before impact with its own sense. A problem with symbols: each unknown impulse
// in the sense in which its components count positive (R along +x where R_x is not identically
// zero; F along +e_t), and a spin given by a symbol counter-clockwise (positive); the caption
// says so (figure::caption). Whether a component is identically zero is read from the answer
// at the figure's illustrative values.
#pragma once

#include "symbolic/derivation.hpp"

#include <array>
#include <string>
#include <vector>

namespace impactgen::figure::detail
{

using vec = std::array<double, 3>;

struct directions {
    bool from_answer = false;          ///< numeric: the answer's directions; else the positive senses
    std::vector<vec> pivot;            ///< per pivot: R on its body, world axes, unit, or zero (none)
    vec friction{};                    ///< the friction impulse on body 2, world axes, unit, or zero (none)
    std::vector<vec> spin;             ///< per body: the angular velocity before impact, unit, or zero
    std::vector<std::string> positive; ///< the senses assumed (symbols), in words: "the pivot impulse towards +x"
};

/// The directions for the derivation; `values` are the figure's illustrative values of the
/// problem's symbols (empty for a numeric problem). Never throws: what cannot be solved is
/// drawn in the positive sense of its unknowns.
directions directions_of(const derivation &d, const GiNaC::exmap &values);

} // namespace impactgen::figure::detail
