// Deciding constant expressions exactly, or refusing to guess.
//
// A value of the problem format may be a plain rational (exact: its sign is
// read off) or a constant expression such as sqrt(2)/2, Pi/4 or
// sin(1)^2 + cos(1)^2 - 1. Before such a value is used as a mass, a normal or
// an approach velocity, its sign -- and whether it is real at all -- must be
// known. decide() tells, in this order:
//
//   1. symbols in it                  -> symbolic (the caller assumes validity)
//   2. a GiNaC numeric                -> exact sign, or not_real
//   3. expand() gives a numeric       -> exact sign (sqrt(2)^2 - 2 is 0)
//   4. a magnitude bound (no evaluation) says it is beyond double range
//                                     -> out_of_range
//   5. evaluation with CLN floats at 40, 80, 160 and 320 digits: a sign is
//      accepted when two successive precisions agree to many digits and the
//      value stands clear of zero by far more than the precision's error
//      (|x| > 10^(-P/2)), and likewise for the imaginary part; otherwise
//                                     -> undecided
//
// Exact zero is only ever reported from steps 2-3: a value that evaluates to
// 1e-300 at every precision (sin(1)^2 + cos(1)^2 - 1) is undecided, and the
// caller refuses it with a message naming the key. Nothing undecided is used.
#pragma once

#include <ginac/ginac.h>

#include <functional>
#include <string>
#include <vector>

namespace impactgen
{

enum class decision {
    negative,
    zero,
    positive,
    symbolic,     ///< contains symbols: nothing is decided
    not_real,     ///< decided to have a non-zero imaginary part
    out_of_range, ///< magnitude beyond the range of double (or too large to evaluate safely)
    undecided     ///< constant, but neither its sign nor its realness could be decided
};

/// The decision for e (see above). Never throws for an expression GiNaC holds.
decision decide(const GiNaC::ex &e);

/// True when e contains no symbol.
bool is_constant(const GiNaC::ex &e);

/// log10 of an upper bound of |e| computed without evaluating e (symbols count
/// as 1, or as the numbers `values` gives them: the reader's placeholders);
/// +infinity when no finite bound is known, -infinity for zero. Guards evaluation against
/// numbers that would take minutes or silently lose every digit (exp(exp(1000))).
double log10_magnitude_bound(const GiNaC::ex &e, const GiNaC::exmap &values = {});

/// Checks every constant part of e that is not a plain number (for a symbolic
/// e, each maximal symbol-free subexpression such as (-1)^(1/3) in x*(-1)^(1/3)):
/// it must be real and within double range. Returns "" when it is, else why not
/// ("not real", "cannot be decided", ...).
std::string constant_parts_problem(const GiNaC::ex &e);

/// The nodes of e, up to limit (limit when there are as many or more), counted so that
/// GiNaC's run-to-run term order cannot change the count: a factor -1 and a product that
/// only negates a term count nothing, so a - b and b - a, -(a - b) c and (b - a) c -- the
/// forms normal() and factor() return in different runs -- are the same size. Every choice
/// between forms by size (tidy() below, the documents' "short enough to print") uses it,
/// so that the choice is the same in every run.
int expression_size(const GiNaC::ex &e, int limit);

/// e put over a common denominator (normal()) when that is cheap: a constant,
/// or a small expression without powers of sums beyond the square. Otherwise e
/// as it is: normal() of a symbolic expression can expand (a + b + ...)^12 into
/// 10^5 terms or spend minutes in multivariate gcd.
GiNaC::ex tidy(const GiNaC::ex &e);
/// e.expand() under the same rule as tidy(): only when it is cheap.
GiNaC::ex tidy_expand(const GiNaC::ex &e);

/// sqrt(q) and 1/sqrt(q) as the notes write them: for a rational q > 0, a rational times
/// the root of a square-free integer (sqrt(21/20) -> sqrt(105)/10, 1/sqrt(8/9) ->
/// 3 sqrt(2)/4); any other q as GiNaC writes it.
GiNaC::ex root_of(const GiNaC::ex &q);
GiNaC::ex inverse_root_of(const GiNaC::ex &q);
/// e with the square roots of integers in each product merged into one, its square
/// taken out: sqrt(105) sqrt(2730) -> 105 sqrt(26) (GiNaC keeps unlike roots apart).
/// Cheap: one pass over e; other powers are left alone.
/// GiNaC's global precision (Digits) set for a scope and restored however it ends.
class digits_scope
{
public:
    explicit digits_scope(long digits) : saved_(GiNaC::Digits) { GiNaC::Digits = digits; }
    ~digits_scope() { GiNaC::Digits = saved_; }
    digits_scope(const digits_scope &) = delete;
    digits_scope &operator=(const digits_scope &) = delete;

private:
    long saved_;
};

/// A non-zero real number as "m" "e" "k" with `significant` digits of mantissa
/// (-1e-400, 4.148e-800), at any magnitude, from the number itself (exact or a float
/// of enough digits), never through a double that would flush it to 0.
std::string scientific_text(const GiNaC::numeric &x, int significant);

GiNaC::ex merge_roots(const GiNaC::ex &e);
/// A constant made of rationals and square roots of integers as a textbook writes it: the
/// roots in each product merged, and the denominator rationalised (one root at a time, times
/// its conjugate: 1/(1 + sqrt(2)) -> sqrt(2) - 1) when that prints no longer. The same value.
/// Anything else (symbols, other functions, more than 4 roots in a denominator) unchanged.
GiNaC::ex surd_form(const GiNaC::ex &x);

/// Whether e (with symbols) is identically zero: exact evaluation at random
/// positive rational points (fixed seed); a non-zero value proves it is not,
/// and a rational function that vanishes at six random points drawn from 10^6
/// values per symbol is zero but with probability below (degree/10^6)^6
/// (Schwartz-Zippel). A constant e is decided by decide(). Never expands e.
bool identically_zero(const GiNaC::ex &e);

/// The random-point test itself: value_at(point) for random positive rational
/// values of the symbols (point: symbol == value); true when every evaluation
/// that could be decided was zero (at least one).
bool vanishes_at_random_points(const std::vector<GiNaC::symbol> &symbols,
                               const std::function<GiNaC::ex(const GiNaC::lst &)> &value_at);

/// Text for a refusal: "is negative", "is not real", "cannot be decided exactly", ...
const char *decision_text(decision d);

} // namespace impactgen
