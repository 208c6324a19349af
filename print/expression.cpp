#include "expression.hpp"

#include "canonical.hpp"
#include "symbolic/decide.hpp"

#include <cmath>
#include <cstdio>
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
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.15g", to_double(e));
    return buf;
}

ex tidy(const ex& e) { return impactgen::tidy(e); }

} // namespace impactgen::print
