#include "decide.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>

#include <sstream>

namespace impactgen
{
using namespace GiNaC;

namespace
{

constexpr double unbounded = std::numeric_limits<double>::infinity();
constexpr double log10_e = 0.43429448190325182765;

double log10_abs(const numeric &x)
{
    if (x.is_zero())
        return -unbounded;
    numeric a = abs(x);
    if (a.is_rational()) // numerator and denominator digits, no overflow of double
        return std::log10(a.numer().to_double() + 0.0) - std::log10(a.denom().to_double() + 0.0);
    return std::log10(a.to_double());
}

double bound(const ex &e, const exmap *values = nullptr)
{
    if (is_a<numeric>(e)) {
        const numeric &x = ex_to<numeric>(e);
        if (!x.is_real())
            return std::max(bound(x.real()), bound(x.imag())) + 0.5;
        if (x.is_rational() && (x.numer().int_length() > 4000 || x.denom().int_length() > 4000))
            return x.numer().int_length() > x.denom().int_length() ? unbounded : -unbounded;
        return log10_abs(x);
    }
    if (is_a<symbol>(e) && values) {
        auto it = values->find(e);
        if (it != values->end() && is_a<numeric>(it->second))
            return bound(it->second);
        return 0; // the reader's own symbols: magnitude 1, their exponents are limited apart
    }
    if (is_a<symbol>(e) || is_a<constant>(e))
        return 0.5; // symbols count as 1; Pi, Euler, Catalan < 10^0.5
    if (is_a<add>(e)) {
        double m = -unbounded;
        for (std::size_t k = 0; k < e.nops(); ++k)
            m = std::max(m, bound(e.op(k), values));
        return m + std::log10(static_cast<double>(e.nops()));
    }
    if (is_a<mul>(e)) {
        double m = 0;
        for (std::size_t k = 0; k < e.nops(); ++k) {
            double b = bound(e.op(k), values);
            if (b == unbounded)
                return unbounded;
            m += std::max(b, 0.0); // a small factor only shrinks the product
        }
        return m;
    }
    if (is_a<power>(e)) {
        double b = bound(e.op(0), values);
        if (b == -unbounded)
            return -unbounded; // 0^x: zero (or a division by zero, which GiNaC reports)
        const ex &x = e.op(1);
        if (is_a<numeric>(x) && ex_to<numeric>(x).is_real()) {
            double xv = std::abs(ex_to<numeric>(x).to_double());
            if (!std::isfinite(xv) || xv > 1e6)
                return (b == 0.5 || b == 0) && is_a<symbol>(e.op(0)) ? b : unbounded;
            // a negative exponent of a small base is large: bound by the magnitude of the log
            return std::abs(b) * xv + 1;
        }
        double xb = bound(x, values);
        if (xb > 6) // a huge exponent: only a base of magnitude 1 (1, or a reader's symbol) stays bounded
            return b == 0 ? 0 : unbounded;
        return std::abs(b) * std::pow(10.0, xb) + 1;
    }
    if (is_a<function>(e)) {
        const std::string name = ex_to<function>(e).get_name();
        double arg = e.nops() > 0 ? bound(e.op(0), values) : 0;
        if (name == "exp" || name == "sinh" || name == "cosh") {
            if (arg > 6)
                return unbounded;
            return std::pow(10.0, arg) * log10_e + 1;
        }
        if (name == "sin" || name == "cos" || name == "atan" || name == "tanh" || name == "asin" || name == "acos")
            return 0.5;
        if (name == "log")
            return std::log10(std::abs(arg) * 2.31 + 2) + 0.5;
        double m = 0; // abs, sqrt, tan and the rest: bounded by their arguments, checked by evaluation
        for (std::size_t k = 0; k < e.nops(); ++k)
            m = std::max(m, std::abs(bound(e.op(k), values)));
        return m + 1;
    }
    return unbounded;
}

decision sign_of(const numeric &x)
{
    if (!x.is_real())
        return decision::not_real;
    if (x.is_zero())
        return decision::zero;
    return x.is_positive() ? decision::positive : decision::negative;
}

// One evaluation at P digits: real and imaginary parts, or false when the
// value does not evaluate to a number (an unevaluated function, an overflow).
bool evaluate(const ex &e, long digits, numeric &re, numeric &im)
{
    try {
        digits_scope guard(digits);
        ex v = e.evalf();
        if (!is_a<numeric>(v))
            return false;
        const numeric &x = ex_to<numeric>(v);
        re = x.real();
        im = x.imag();
        return true;
    } catch (const std::exception &) {
        return false;
    }
}

// The sign of a part evaluated at two precisions, when both agree and stand clear of zero.
decision stable_sign(const numeric &coarse, const numeric &fine, long digits)
{
    const numeric clear = pow(numeric(10), numeric(-digits / 2));
    if (abs(coarse) <= clear || abs(fine) <= clear)
        return decision::undecided;
    if (coarse.is_positive() != fine.is_positive())
        return decision::undecided;
    if (abs(coarse - fine) > abs(fine) * pow(numeric(10), numeric(-digits / 4)))
        return decision::undecided;
    return fine.is_positive() ? decision::positive : decision::negative;
}

bool small(const numeric &x, long digits)
{
    return abs(x) <= pow(numeric(10), numeric(-digits / 2));
}

} // namespace

bool is_constant(const ex &e)
{
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it))
            return false;
    return true;
}

double log10_magnitude_bound(const ex &e, const exmap &values)
{
    return bound(e, &values);
}

decision decide(const ex &e)
{
    if (is_a<numeric>(e))
        return sign_of(ex_to<numeric>(e));
    if (!is_constant(e))
        return decision::symbolic;
    if (bound(e) > 400)
        return decision::out_of_range;
    // A product's sign from its factors' (sqrt(2)·10^-100 stands within 10^-20 of 0 at 40
    // digits, which the evaluation below cannot tell from a cancelled 0); its magnitude
    // still checked against double's range.
    if (is_a<GiNaC::mul>(e)) {
        bool negative = false, settled = true;
        for (std::size_t k = 0; k < e.nops() && settled; ++k) {
            const decision f = decide(e.op(k));
            if (f == decision::zero)
                return decision::zero;
            if (f == decision::negative)
                negative = !negative;
            else if (f != decision::positive)
                settled = false;
        }
        numeric re, im;
        if (settled && evaluate(e, 40, re, im) && im.is_zero() && !re.is_zero()) {
            if (std::abs(log10_abs(re)) > 308.25)
                return decision::out_of_range;
            return negative ? decision::negative : decision::positive;
        }
    }
    ex x = tidy_expand(e); // exact only where expansion is cheap; evaluation decides the rest
    if (is_a<numeric>(x))
        return sign_of(ex_to<numeric>(x));
    // Roots of integers merged: sqrt(2) sqrt(8) - 4 is 0, which no evaluation can show.
    if (const ex merged = merge_roots(x).expand(); is_a<numeric>(merged))
        return sign_of(ex_to<numeric>(merged));
    numeric re0, im0;
    long p0 = 40;
    if (!evaluate(x, p0, re0, im0))
        return decision::undecided;
    for (long p = 80; p <= 320; p *= 2) {
        numeric re1, im1;
        if (!evaluate(x, p, re1, im1))
            return decision::undecided;
        if (!(small(im0, p0) && small(im1, p))) {
            if (stable_sign(im0, im1, p0) != decision::undecided)
                return decision::not_real;
        } else {
            decision s = stable_sign(re0, re1, p0);
            if (s != decision::undecided) {
                if (std::abs(log10_abs(re1)) > 308.25)
                    return decision::out_of_range;
                // the imaginary part: exactly zero in the float evaluation, or below any doubt
                if (im1.is_zero() || small(im1, p))
                    return s;
            }
        }
        re0 = re1;
        im0 = im1;
        p0 = p;
    }
    return decision::undecided;
}

std::string constant_parts_problem(const ex &e)
{
    if (is_a<numeric>(e)) {
        const numeric &x = ex_to<numeric>(e);
        if (!x.is_real())
            return "it is not real";
        if (bound(e) <= 308.25)
            return "";
        return abs(x) < 1 ? "it is below the range of double (its magnitude is under 1e-308; write 0 for zero)"
                          : "it is out of the range of double (non-finite number)";
    }
    if (is_a<symbol>(e) || is_a<constant>(e))
        return "";
    if (is_constant(e)) {
        switch (decide(e)) {
        case decision::not_real:
            return "it is not real";
        case decision::out_of_range:
            return "it is beyond the range of double: its magnitude, or a part's, is above about 1e308 or below 1e-308";
        case decision::undecided:
            return "its value cannot be decided exactly (write it as a plain number or a simpler expression)";
        default:
            return "";
        }
    }
    for (std::size_t k = 0; k < e.nops(); ++k) {
        std::string why = constant_parts_problem(e.op(k));
        if (!why.empty())
            return why;
    }
    return "";
}

namespace
{

bool is_sign(const ex &f)
{
    return is_a<numeric>(f) && abs(ex_to<numeric>(f)).is_equal(1);
}

// Counts the nodes of e against budget (see expression_size); with tame, fails on a power
// of a sum with |exponent| > 2 as well.
bool within(const ex &e, int &budget, bool tame)
{
    if (is_a<mul>(e)) {
        std::size_t factors = 0;
        for (std::size_t k = 0; k < e.nops(); ++k)
            if (!is_sign(e.op(k)))
                ++factors;
        if (factors > 1 && --budget < 0)
            return false;
        for (std::size_t k = 0; k < e.nops(); ++k)
            if (!is_sign(e.op(k)) && !within(e.op(k), budget, tame))
                return false;
        return true;
    }
    if (--budget < 0)
        return false;
    if (tame && is_a<power>(e) && is_a<add>(e.op(0)) && is_a<numeric>(e.op(1)) && abs(ex_to<numeric>(e.op(1))) > 2)
        return false;
    for (std::size_t k = 0; k < e.nops(); ++k)
        if (!within(e.op(k), budget, tame))
            return false;
    return true;
}

// Small (expression_size) and without powers of sums beyond the square.
bool small_and_tame(const ex &e, int &budget)
{
    return within(e, budget, true);
}

} // namespace

int expression_size(const ex &e, int limit)
{
    int budget = limit;
    return within(e, budget, false) ? limit - budget : limit;
}

namespace
{

// The distinct irrational atoms of a constant (Pi, exp(1), 2^(1/2)): normal() treats
// each as a variable, and its gcds grow fast with their number.
std::size_t irrational_atoms(const ex &e)
{
    exset atoms;
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<constant>(*it) || is_a<function>(*it) ||
            (is_a<power>(*it) && is_a<numeric>(it->op(1)) && !ex_to<numeric>(it->op(1)).is_integer()))
            atoms.insert(*it);
    return atoms.size();
}

} // namespace

namespace
{

// op(e) when it is cheap: a small expression without powers of sums beyond the
// square, a constant within range (and, for normal(), with few irrationals).
ex bounded(const ex &e, int symbolic_budget, bool normalise)
{
    const bool constant_value = is_constant(e);
    int budget = constant_value ? 300 : symbolic_budget; // nodes
    if (normalise && constant_value && irrational_atoms(e) > 2)
        return e;
    if (!small_and_tame(e, budget) || (constant_value && bound(e) > 400))
        return e;
    try {
        return normalise ? e.normal() : e.expand();
    } catch (const std::exception &) {
        return e;
    }
}

} // namespace

ex tidy(const ex &e)
{
    return bounded(e, 80, true);
}

ex tidy_expand(const ex &e)
{
    return bounded(e, 200, false);
}

namespace
{
// For a rational q > 0 with numerator and denominator under 10^12: sqrt(a/b) = s sqrt(f) / b
// with a b = s^2 f, f square-free (trial division by squares up to 10^6).
bool square_free_root(const ex &q, numeric &outside, numeric &inside, numeric &below)
{
    if (!is_a<numeric>(q) || !ex_to<numeric>(q).is_rational() || !ex_to<numeric>(q).is_positive())
        return false;
    const numeric r = ex_to<numeric>(q);
    const numeric limit(1000000000000LL);
    if (r.numer() > limit || r.denom() > limit)
        return false;
    inside = r.numer() * r.denom();
    outside = 1;
    for (numeric f = 2; f * f <= inside; f += 1)
        while (mod(inside, f * f).is_zero()) {
            inside = inside / (f * f);
            outside *= f;
        }
    below = r.denom();
    return true;
}
} // namespace

ex root_of(const ex &q)
{
    numeric outside, inside, below;
    if (!square_free_root(q, outside, inside, below))
        return sqrt(q);
    return outside * sqrt(ex(inside)) / below; // sqrt(a/b) = sqrt(a b)/b
}

std::string scientific_text(const numeric &x, int significant)
{
    const numeric ax = abs(x);
    long k = std::lround(std::floor(ex_to<numeric>((log(ex(ax)) / log(ex(numeric(10)))).evalf()).to_double()));
    double m = ex_to<numeric>((ax / numeric(10).power(k)).evalf()).to_double();
    if (m >= 10 - 5 * std::pow(10.0, -significant)) { // the mantissa rounds up to 10
        m /= 10;
        ++k;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%.*ge%ld", x.is_negative() ? "-" : "", significant, m, k);
    return buf;
}

ex merge_roots(const ex &e)
{
    struct merger : map_function {
        ex operator()(const ex &x) override
        {
            const ex y = x.map(*this);
            // a root on its own, its square taken out: sqrt(8) -> 2 sqrt(2)
            if (is_a<power>(y) && is_a<numeric>(y.op(0)) && ex_to<numeric>(y.op(0)).is_pos_integer() &&
                y.op(1).is_equal(numeric(1, 2)) && ex_to<numeric>(y.op(0)) < numeric(1000000))
                return root_of(y.op(0));
            if (!is_a<GiNaC::mul>(y))
                return y;
            numeric radicand = 1;
            int roots = 0;
            exvector rest;
            for (std::size_t k = 0; k < y.nops(); ++k) {
                const ex &f = y.op(k);
                if (is_a<power>(f) && is_a<numeric>(f.op(0)) && ex_to<numeric>(f.op(0)).is_pos_integer() &&
                    f.op(1).is_equal(numeric(1, 2)) && ex_to<numeric>(f.op(0)) < numeric(1000000)) {
                    radicand *= ex_to<numeric>(f.op(0));
                    ++roots;
                } else {
                    rest.push_back(f);
                }
            }
            if (roots < 2)
                return y;
            return GiNaC::mul(rest) * root_of(radicand);
        }
    } m;
    try {
        return m(e);
    } catch (const std::exception &) {
        return e;
    }
}

namespace
{
// sqrt(k) of a positive integer k (below the bound merge_roots takes).
bool is_integer_root(const ex &f)
{
    return is_a<power>(f) && is_a<numeric>(f.op(0)) && ex_to<numeric>(f.op(0)).is_pos_integer() &&
           f.op(1).is_equal(numeric(1, 2)) && ex_to<numeric>(f.op(0)) < numeric(1000000);
}

// Only rationals, + - * /, integer powers and square roots of positive integers.
bool is_surd_constant(const ex &e)
{
    if (is_a<numeric>(e))
        return ex_to<numeric>(e).is_rational();
    if (is_a<power>(e))
        return is_integer_root(e) ||
               (is_a<numeric>(e.op(1)) && ex_to<numeric>(e.op(1)).is_integer() && is_surd_constant(e.op(0)));
    if (is_a<GiNaC::add>(e) || is_a<GiNaC::mul>(e)) {
        for (std::size_t k = 0; k < e.nops(); ++k)
            if (!is_surd_constant(e.op(k)))
                return false;
        return true;
    }
    return false;
}

ex merged_expanded(const ex &e)
{
    return merge_roots(merge_roots(e.expand()).expand()).expand();
}
} // namespace

ex surd_form(const ex &x)
{
    if (!is_surd_constant(x))
        return x;
    try {
        const ex nd = merge_roots(x).normal().numer_denom();
        ex n = nd.op(0), d = merged_expanded(nd.op(1));
        // numerator and denominator each a sum of distinct roots
        const ex expanded = merged_expanded(n) / d;
        // One root of the denominator at a time: d = A + B sqrt(k) times A - B sqrt(k) is
        // A^2 - B^2 k, free of sqrt(k) (after merging, no term holds two roots).
        for (int step = 0; step < 4; ++step) {
            ex root;
            for (const_preorder_iterator it = d.preorder_begin(); it != d.preorder_end(); ++it)
                if (is_integer_root(*it)) {
                    root = *it;
                    break;
                }
            if (root.is_zero())
                break;
            const symbol t;
            const ex dt = d.subs(root == t);
            if (dt.degree(t) > 1 || dt.ldegree(t) < 0)
                return x;
            const ex A = dt.coeff(t, 0), B = dt.coeff(t, 1);
            n = merged_expanded(n * (A - B * root));
            d = merged_expanded(A * A - B * B * root.op(0));
        }
        // The merged form as it was, or the rationalised one when it has no more digits (its
        // integers grow with each conjugate: 1936 sqrt(3)(sqrt(3) + 2 sqrt(6))/(15 (179507 +
        // 8316 sqrt(2))) stays, 1/(1 + sqrt(2)) becomes sqrt(2) - 1).
        auto digits = [](const ex &e) {
            std::ostringstream os;
            os << e;
            const std::string t = os.str();
            return std::count_if(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
        };
        const ex merged = merge_roots(x);
        const ex best = digits(expanded) < digits(merged) ? expanded : merged;
        if (!is_a<numeric>(d) || d.is_zero())
            return best;
        const ex rationalised = (merged_expanded(n) / d).expand();
        return digits(rationalised) <= digits(best) ? rationalised : best;
    } catch (const std::exception &) {
        return x;
    }
}

ex inverse_root_of(const ex &q)
{
    numeric outside, inside, below;
    if (!square_free_root(q, outside, inside, below))
        return 1 / sqrt(q);
    // 1/sqrt(a/b) = sqrt(a b)/a, and a = (outside^2 inside)/b
    return outside * sqrt(ex(inside)) * below / (outside * outside * inside);
}

bool vanishes_at_random_points(const std::vector<symbol> &symbols, const std::function<ex(const lst &)> &value_at)
{
    std::mt19937_64 rng(20261123);
    std::uniform_int_distribution<long> num(1, 1000000);
    int zeros = 0;
    for (int attempt = 0; attempt < 24 && zeros < 6; ++attempt) {
        lst point;
        for (const symbol &x : symbols)
            point.append(x == numeric(num(rng), 1000));
        try {
            decision d = decide(value_at(point));
            if (d == decision::positive || d == decision::negative || d == decision::not_real)
                return false;
            if (d == decision::zero || d == decision::undecided) // undecided counts against: refuse rather than guess
                ++zeros;
        } catch (const std::exception &) {
            continue; // a pole at this point: try another
        }
    }
    return zeros > 0;
}

bool identically_zero(const ex &e)
{
    if (is_constant(e))
        return decide(e) == decision::zero;
    exset free;
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it))
            free.insert(*it);
    std::vector<symbol> symbols;
    for (const ex &x : free)
        symbols.push_back(ex_to<symbol>(x));
    return vanishes_at_random_points(symbols, [&](const lst &point) { return e.subs(point); });
}

const char *decision_text(decision d)
{
    switch (d) {
    case decision::negative:
        return "is negative";
    case decision::zero:
        return "is zero";
    case decision::positive:
        return "is positive";
    case decision::symbolic:
        return "is symbolic";
    case decision::not_real:
        return "is not real";
    case decision::out_of_range:
        return "is beyond the range of double (its magnitude, or a part's, is above about 1e308 or below 1e-308)";
    case decision::undecided:
        return "cannot be decided exactly (its sign or whether it is zero is beyond what can be proven; write it as a "
               "plain number or a simpler expression)";
    }
    return "?";
}

} // namespace impactgen
