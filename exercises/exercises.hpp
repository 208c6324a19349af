// Exercise sheets (issue 25): N variants of one impact with numbers a person can work by
// hand, each with its figure, short answers, full worked solution, problem and answer files,
// and a Moodle quiz.
//
// A variant keeps the problem's geometry and kind (bodies, contact, pivots, the sign of every
// velocity and spin, which are zero) and draws new simple values: masses, speeds and spins of
// one significant digit near the problem's own (a named class is first given the figure's
// illustrative values), inertias scaled with their masses, e from {0, 1/4, 1/2, 3/4, 1}, mu
// from {1/10, 1/5, 1/4, 1/3, 1/2, 3/4, 1}. Then the answer is chosen first: the approach
// speed is back-generated so that the normal impulse N is a simple number (N is linear in
// the velocity of approach within a regime). A variant is kept only when every answer is a
// short fraction, its regime is the one asked for, and it stays so when mu is made a third
// larger or smaller (not near a regime boundary). The generator is seeded (a 64-bit xorshift
// of its own, no library distribution), and the search is bounded by a count of draws, never by
// the clock, so the same seed gives the same sheet byte for byte however fast or loaded the machine.
#pragma once

#include "symbolic/friction.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace impactgen::exercises
{

struct options {
    int count = 10;         ///< 1 .. 99 variants
    std::uint64_t seed = 1; ///< the same seed, the same sheet
    std::string regime;     ///< "" (any), "smooth", "stick" or "slide"
    int attempts = 400;     ///< most draws per exercise
    /// Work units for the draws of the whole sheet past the 8 every exercise gets; a draw costs
    /// draw_units(problem) (its usual time here, in ms). 0: sheet_units, about 5 s of searching here.
    int units = 0;
    /// Safety net only: a search still running after this many seconds is refused with an
    /// input_error (never cut to a sheet that depends on the machine's speed). 0: none.
    double seconds = 120;
    std::function<void()> before_draw; ///< called before every draw (tests slow the search with it)
};

/// The default work units of a sheet's search (options::units 0).
constexpr int sheet_units = 6000;
/// What one draw of a variant of `p` costs in work units: about its time in ms on the machine that
/// sized them (a system 1, one contact 3, with friction 6, in 3-D with friction 100).
int draw_units(const problem &p);

/// One asked quantity of an exercise: a scalar of the answer.
struct quantity {
    std::string pointer; ///< JSON pointer into the answer object ("/bodies/ball/velocity/0")
    std::string words;   ///< "velocity of ball after impact, x component"
    std::string unit;    ///< "m/s", "rad/s", "N s", "J" or "" (no units)
    GiNaC::ex exact;     ///< the exact value (a rational)
};

struct exercise {
    problem prob;                  ///< numeric, titled "Exercise NN: ..."
    std::string regime;            ///< "smooth", "stick" or "slide"
    std::vector<quantity> asked;   ///< what the sheet asks for, in order
    nlohmann::ordered_json answer; ///< the answer object, as solve --json writes it
};

struct sheet {
    std::string title;  ///< the problem's title (or a person's name for it)
    bool units = false; ///< SI units printed
    std::vector<exercise> exercises;
    /// Exercises whose search ran out of its draws (options::attempts or options::units) before
    /// short answers: each is the best of its draws (long answers as decimals), the same everywhere.
    int short_of_draws = 0;
};

/// The sheet of `base` (a named class or a problem file). Throws input_error with one line
/// naming the option when it cannot be made (count out of range, a regime the problem cannot
/// have, no variant found within the attempts).
sheet make_sheet(const problem &base, const options &opt);

/// Every file of the sheet, by its path relative to the output folder: sheet.tex,
/// sheet.html, quiz.xml, problems/NN.json, answers/NN.json, solutions/NN.tex and .html.
std::map<std::string, std::string> sheet_files(const sheet &s);

/// A numeric problem in the problem format (version 3 keys that it uses only), exact:
/// an integer or a decimal that is exact as a JSON number, other values as strings ("1/3").
nlohmann::ordered_json problem_json(const problem &p);

/// The asked quantities of a solved variant (exact values of its answer).
std::vector<quantity> asked_quantities(const derivation &d, const regime_case &c);

} // namespace impactgen::exercises
