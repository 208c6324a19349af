#include "expression.hpp"

#include "canonical.hpp"
#include "symbolic/decide.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace impactgen::print
{
using namespace GiNaC;

std::string parser_syntax(const ex &e)
{
    return canonical_parser(e);
}

namespace
{
ex evaluated(const ex &e)
{
    if (is_a<numeric>(e))
        return e.evalf();
    ex last;
    bool have = false;
    for (long digits = 40; digits <= 1280; digits *= 2) {
        digits_scope scope(digits);
        ex v;
        try {
            v = e.evalf();
        } catch (const std::exception &) {
            continue; // a part that cancels to a float 0 and divides (1/(sqrt(10^100 + 1) - 10^50)): more digits
        }
        if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
            return v;
        const numeric a = ex_to<numeric>(v);
        // Two non-zero evaluations that agree; a float 0 is no evidence (10^50 - sqrt(10^100 + 1)
        // is 0.0 at 40 and 80 digits), only decide() says a value is 0.
        if (have && !a.is_zero() && abs(a - ex_to<numeric>(last)) <= abs(a) * numeric(1, 10).power(18))
            return v;
        last = v;
        have = true;
    }
    if (decide(e) == decision::zero)
        return numeric(0);
    throw no_decimal();
}
} // namespace

ex evaluated_constant(const ex &e)
{
    return evaluated(e);
}

double to_double(const ex &e)
{
    ex v = evaluated(e);
    if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
        throw std::invalid_argument("not a real number: " + parser_syntax(e));
    const numeric &x = ex_to<numeric>(v);
    double d = x.to_double();
    if (d == 0 && !x.is_zero()) // CLN flushes values below DBL_MIN to 0: scale into range, then back (a subnormal)
        d = std::ldexp((x * numeric(2).power(600)).to_double(), -600);
    if (!std::isfinite(d))
        throw std::invalid_argument("not a finite number: " + parser_syntax(e));
    return d == 0 ? 0.0 : d; // no "-0"
}

std::string decimal(const ex &e)
{
    const ex v = evaluated(e);
    const double d = to_double(v);
    // Below the normal range of double (a subnormal, or 0 for a value that is not): the
    // mantissa and the exponent from the evaluated value itself, never "0" for x != 0.
    if (std::fabs(d) < std::numeric_limits<double>::min() && is_a<numeric>(v) && !ex_to<numeric>(v).is_zero())
        return scientific_text(ex_to<numeric>(v), 15);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.15g", d);
    return buf;
}

ex tidy(const ex &e)
{
    return impactgen::tidy(e);
}

namespace
{
ex expanded_factor(const ex &f)
{
    if (is_a<power>(f))
        return pow(f.op(0).expand(), f.op(1));
    return is_a<add>(f) ? f.expand() : f;
}
} // namespace

ex factored(const ex &e)
{
    const ex f = factor(e);
    if (!is_a<mul>(f))
        return expanded_factor(f);
    ex out = 1;
    for (std::size_t k = 0; k < f.nops(); ++k)
        out *= expanded_factor(f.op(k));
    return out;
}

} // namespace impactgen::print
