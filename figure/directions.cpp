// The directions of the figure's impulses and spins (see directions.hpp).
#include "figure/directions.hpp"

#include "symbolic/contact_law.hpp"
#include "symbolic/friction.hpp"

#include <cmath>
#include <exception>

namespace impactgen::figure::detail
{
using namespace GiNaC;

namespace
{

double to_double(const ex &e, const exmap &values)
{
    try {
        const ex v = (values.empty() ? e : e.subs(values)).evalf();
        if (is_a<numeric>(v) && ex_to<numeric>(v).is_real()) {
            const double r = ex_to<numeric>(v).to_double();
            if (std::isfinite(r))
                return r;
        }
    } catch (const std::exception &) {
        // not a number: 0 below
    }
    return 0;
}

vec unit(const vec &a)
{
    const double m = std::max({std::abs(a[0]), std::abs(a[1]), std::abs(a[2])});
    if (!(m > 0) || !std::isfinite(m))
        return {};
    const vec s{a[0] / m, a[1] / m, a[2] / m};
    const double l = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    return {s[0] / l, s[1] / l, s[2] / l};
}

vec values_of(const vec3 &v, const exmap &values, int dim)
{
    vec out{};
    for (int c = 0; c < dim; ++c)
        out[c] = to_double(v[c], values);
    return out;
}

/// The problem with the illustrative values put in (a numeric twin to solve).
problem with_values(problem p, const exmap &values)
{
    for_each_value(p, [&](ex &x) { x = x.subs(values); });
    return p;
}

/// The answer of a numeric problem: pivot impulses and the friction impulse on body 2, world.
bool answer_of(const derivation &d, std::vector<vec> &pivot, vec &friction)
{
    try {
        const regime_case c = select_candidate(d, solve_impact(d));
        const int dim = d.prob.dimension == 2 ? 2 : 3;
        // The values are written in the solution's steps: expanded to numbers first.
        auto numbers = [&](const vec3 &v) {
            vec3 x = v;
            for (ex &e : x)
                e = c.sol.expand_steps(e);
            return values_of(x, {}, dim);
        };
        pivot.clear();
        for (const vec3 &r : c.sol.pivot_impulses)
            pivot.push_back(numbers(r));
        friction = law_traits_of(d.prob).tangential_impulse ? numbers(c.tangential_impulse) : vec{};
        return true;
    } catch (const std::exception &) {
        return false; // no single regime, or a decision the numbers cannot make
    }
}

const char *axis_sign(int c)
{
    static const char *names[3] = {"+x", "+y", "+z"};
    return names[c];
}

/// The positive senses of the unknowns: R along the world axes of its components that the
/// answer at the illustrative values does not make zero, F along +e_t (+e_b in 3-D).
void positive_senses(const derivation &d, const exmap &values, const std::vector<vec> &at_values,
                     const vec &friction_at_values, bool solved, directions &out)
{
    const int dim = d.prob.dimension == 2 ? 2 : 3;
    for (std::size_t j = 0; j < d.prob.pivots.size(); ++j) {
        vec r{};
        std::string axes;
        for (int c = 0; c < dim; ++c)
            if (!solved || (j < at_values.size() && std::abs(at_values[j][c]) > 1e-9)) {
                r[c] = 1;
                axes += axes.empty() ? axis_sign(c) : std::string(" and ") + axis_sign(c);
            }
        out.pivot.push_back(unit(r));
        if (!axes.empty())
            out.positive.push_back((d.prob.pivots.size() == 1 ? std::string("the pivot impulse")
                                                              : "the impulse of pivot " + std::to_string(j + 1)) +
                                   " towards " + axes);
    }
    if (!law_traits_of(d.prob).tangential_impulse)
        return;
    const vec et = values_of(d.e_t, values, dim), eb = dim == 3 ? values_of(d.e_b, values, dim) : vec{};
    const double ft = et[0] * friction_at_values[0] + et[1] * friction_at_values[1] + et[2] * friction_at_values[2];
    const double fb = eb[0] * friction_at_values[0] + eb[1] * friction_at_values[1] + eb[2] * friction_at_values[2];
    const bool use_t = !solved || std::abs(ft) > 1e-9, use_b = dim == 3 && (!solved || std::abs(fb) > 1e-9);
    vec f{};
    for (int c = 0; c < 3; ++c)
        f[c] = (use_t ? et[c] : 0) + (use_b ? eb[c] : 0);
    out.friction = unit(f);
    if (use_t || use_b)
        out.positive.push_back(std::string("the friction impulse on body 2 along the positive tangent") +
                               (use_t && use_b ? "s" : ""));
}

} // namespace

directions directions_of(const derivation &d, const exmap &values)
{
    directions out;
    const problem &p = d.prob;
    const int dim = p.dimension == 2 ? 2 : 3;
    const bool symbolic = !values.empty();
    // Spins before impact: a number with its sign; a symbol in the positive sense.
    bool spin_symbol = false;
    for (const body &b : p.bodies) {
        vec w{};
        for (int c = 0; c < 3; ++c) {
            const ex &x = b.angular_velocity[c];
            if (x.is_zero() || b.particle || b.infinite_mass)
                continue;
            const bool has_symbol = !is_a<numeric>(x.evalf());
            spin_symbol = spin_symbol || has_symbol;
            w[c] = has_symbol ? 1 : to_double(x, {});
        }
        out.spin.push_back(dim == 2 ? vec{0, 0, w[2] > 0 ? 1.0 : (w[2] < 0 ? -1.0 : 0.0)} : unit(w));
    }
    if (spin_symbol)
        out.positive.push_back(dim == 2 ? "each spin counter-clockwise" : "each spin along its positive axes");
    if (!symbolic) {
        vec friction{};
        if (answer_of(d, out.pivot, friction)) {
            out.from_answer = true;
            for (vec &r : out.pivot)
                r = unit(r);
            out.friction = unit(friction);
            return out;
        }
        out.pivot.clear();
    }
    // Symbols (or a numeric problem without a single answer): the positive senses, with the
    // components the answer at the illustrative values leaves zero left out.
    std::vector<vec> at_values;
    vec friction_at_values{};
    bool solved = false;
    try {
        const derivation twin = derive(with_values(p, values));
        solved = answer_of(twin, at_values, friction_at_values);
    } catch (const std::exception &) {
        solved = false;
    }
    positive_senses(d, values, at_values, friction_at_values, solved, out);
    return out;
}

} // namespace impactgen::figure::detail
