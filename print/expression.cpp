#include "expression.hpp"

#include "canonical.hpp"
#include "symbolic/decide.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace impactgen::print {
using namespace GiNaC;

std::string parser_syntax(const ex& e) { return canonical_parser(e); }

namespace {
// GiNaC's Digits for one evaluation, restored however it ends.
struct digits_scope {
    long saved;
    explicit digits_scope(long d) : saved(Digits) { Digits = d; }
    ~digits_scope() { Digits = saved; }
};

// The value of a constant to double precision: exact for a rational; otherwise evaluated at
// 40, 80, ... digits until two evaluations agree to 1e-18 relative, as a difference of near
// values (10^8 - sqrt(10^16 + 1) = -5e-9) cancels the leading digits of a short evaluation.
ex evaluated(const ex& e)
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
        } catch (const std::exception&) {
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
    throw std::invalid_argument("no decimal: its exact form cancels beyond 1280 digits");
}
} // namespace

ex evaluated_constant(const ex& e) { return evaluated(e); }

double to_double(const ex& e)
{
    ex v = evaluated(e);
    if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
        throw std::invalid_argument("not a real number: " + parser_syntax(e));
    const numeric& x = ex_to<numeric>(v);
    double d = x.to_double();
    if (d == 0 && !x.is_zero()) // CLN flushes values below DBL_MIN to 0: scale into range, then back (a subnormal)
        d = std::ldexp((x * numeric(2).power(600)).to_double(), -600);
    if (!std::isfinite(d))
        throw std::invalid_argument("not a finite number: " + parser_syntax(e));
    return d == 0 ? 0.0 : d; // no "-0"
}

std::string decimal(const ex& e)
{
    char buf[96];
    const double d = to_double(e);
    if (std::fabs(d) < std::numeric_limits<double>::min()) {
        // Below the normal range of double (a subnormal, or 0 for a value that is not): the
        // mantissa and the exponent apart, from the exact value's float, never "0" for x != 0.
        const ex v = evaluated(e);
        if (is_a<numeric>(v) && !ex_to<numeric>(v).is_zero()) {
            const numeric x = ex_to<numeric>(v);
            long k = std::lround(std::floor(ex_to<numeric>(log(abs(x)) / log(numeric(10))).to_double()));
            double m = ex_to<numeric>(x / numeric(10).power(k)).to_double();
            if (std::fabs(m) >= 10 - 5e-15) { // rounded up to 10
                m /= 10;
                ++k;
            }
            std::snprintf(buf, sizeof buf, "%.15ge%ld", m, k);
            return buf;
        }
    }
    std::snprintf(buf, sizeof buf, "%.15g", d);
    return buf;
}

ex tidy(const ex& e) { return impactgen::tidy(e); }

} // namespace impactgen::print
