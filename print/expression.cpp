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

double to_double(const ex& e)
{
    ex v = e.evalf();
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
        const ex v = e.evalf();
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
