// How restitution is measured at a contact (problem format version 3, "law"), independent of
// the friction law (contact_law): a second choice the contact carries.
//
//   newton      u'_n = -e u_n                      (velocities; the default, versions 1 and 2)
//   poisson     P_n = (1 + e) P_n,c                (impulses: P_n,c ends the compression)
//   energetic   W_r = -e^2 W_c                     (the normal impulse's work, W = int u_n dP_n:
//                                                   Stronge's coefficient; never creates energy)
//
// With friction, poisson and energetic follow the impact as the normal impulse grows (Routh's
// process, symbolic/routh.hpp); for a smooth contact the three give the same answer. A next law
// is one more alternative of restitution_law and one more case in routh.cpp's restitution end.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <variant>

namespace impactgen
{

struct newton_restitution {
};
struct poisson_restitution {
};
struct energetic_restitution {
};
using restitution_law = std::variant<newton_restitution, poisson_restitution, energetic_restitution>;

/// "newton", "poisson" or "energetic": the key's value in a problem file.
const char *law_name(const restitution_law &law);

/// The law named by a file's "law" value; throws input_error naming `where` for any other name.
restitution_law law_from_name(const std::string &name, const std::string &where);

/// One callable per law, for std::visit over a restitution_law: where the laws differ, each site
/// visits, so that a new alternative does not build until every site has its case (never an
/// if/else that would give it another law's).
template <class... F> struct law_cases : F... {
    using F::operator()...;
};
template <class... F> law_cases(F...) -> law_cases<F...>;

/// True for a law measured along the process (poisson, energetic), false for newton.
inline bool follows_process(const restitution_law &law)
{
    return !std::holds_alternative<newton_restitution>(law);
}

/// The phases of Routh's process (the answer's "process" key).
enum class phase_kind {
    slide,  ///< sliding in the direction of the initial slip (or, starting without slip, the one it takes)
    stick,  ///< no slip: the impulse ratio inside the cone
    reverse ///< sliding against the initial slip, after it stopped and could not stick
};
const char *phase_name(phase_kind k);

struct process_phase {
    phase_kind kind = phase_kind::slide;
    GiNaC::ex normal_impulse_end; ///< P_n at the end of the phase
};

/// What a condition of a phase sequence says (printers word it from this).
enum class process_test {
    initial_slip,      ///< s u_t > 0: the contact slips along s e_t before impact
    sticks_at_start,   ///< mu^2 K_tt^2 - K_tn^2 >= 0: starting without slip, the ratio is inside the cone
    slip_direction,    ///< s K_tn > 0: starting without slip (outside the cone), the slip it takes
    slip_slows,        ///< -s a > 0: the slip decelerates and reaches zero
    normal_slope,      ///< b > 0: the normal velocity grows in this phase (else the contact wedges)
    compression_first, ///< x_stop - x_c >= 0: the compression ends before the slip stops
    sticks,            ///< mu K_tt + s K_tn >= 0: the slip stopped and the ratio is inside the cone
    ends_first         ///< x_stop - x_f >= 0: restitution ends before the slip stops
};

/// value > 0 (strict) or value >= 0, in the process's quantities (K_tt, K_tn, K_nn, u_t, u_n, mu, e).
struct process_condition {
    GiNaC::ex value;
    bool strict = true;
    process_test kind = process_test::initial_slip;
    std::string meaning; ///< plain text, for logs and the formulas printout
};

} // namespace impactgen
