// formulas --jacobian with Coulomb friction under Newton's law (symbolic/friction_jacobian.hpp):
// per regime, the exact derivatives of the impact map (chain rule through the regime's steps; the
// 3-D slide without a closed form through the implicit function theorem of its angle equation)
// against central differences of the same regime's closed form, at seeded random rational points
// where that regime holds strictly and alone. The closed form is evaluated with CLN at 40 digits
// (the sliding angle by Newton's method from the root at the point, to 40 digits), so the step
// h = 1e-12 leaves a truncation error h^2 |f'''| ~ 1e-24 and a rounding error 1e-40 / h = 1e-28:
// a derivative agrees to 1e-9 relative unless it is wrong (a wrong term is O(1) of it).
#include "sampling.hpp"
#include "symbolic/friction_jacobian.hpp"
#include "symbolic/named_classes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace impactgen;
using namespace GiNaC;

namespace
{

numeric num(const ex &e, const exmap &at)
{
    const ex v = e.subs(at).evalf();
    if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
        throw std::runtime_error("not a real number");
    return ex_to<numeric>(v);
}

// The values of the steps, in order, added to `at`.
void evaluate(const std::vector<impactgen::step> &steps, std::size_t from, exmap &at)
{
    for (std::size_t k = from; k < steps.size(); ++k)
        at[steps[k].sym] = num(steps[k].value, at);
}

// A random rational input by the symbol's name: e in (0, 1], mu in [1/16, 2], masses in [1/2, 4],
// the diagonal of an inertia tensor in [1, 2] and its other entries in [-1/4, 1/4] (positive
// definite), a radius in [1/4, 2], everything else (positions, velocities) in [-2, 2].
numeric draw(const std::string &name, std::mt19937 &g)
{
    auto R = [&](int lo, int hi, int den) { return numeric(std::uniform_int_distribution<int>(lo, hi)(g), den); };
    if (name == "e")
        return R(1, 16, 16);
    if (name == "mu")
        return R(1, 32, 16);
    if (name[0] == 'm')
        return R(4, 32, 8);
    if (name[0] == 'I') {
        const std::string tail = name.size() >= 2 ? name.substr(name.size() - 2) : "";
        const bool off = name.size() > 3 && tail[0] != tail[1];
        return off ? R(-4, 4, 16) : R(16, 32, 16);
    }
    if (name == "R")
        return R(2, 16, 8);
    return R(-16, 16, 8);
}

// The regime's steps at the sliding angle t, added to a copy of `at` (inputs and shared steps).
exmap at_angle(const regime_case &c, std::size_t shared, const exmap &at, const numeric &t)
{
    exmap m = at;
    m[c.dir_c] = cos(t);
    m[c.dir_s] = sin(t);
    evaluate(c.sol.steps, shared, m);
    return m;
}

numeric g_at(const regime_case &c, std::size_t shared, const exmap &at, const numeric &t)
{
    return num(c.angle_equation, at_angle(c, shared, at, t));
}

// A root of the angle equation near t, to 40 digits: Newton's method in theta, the slope by a
// central difference of step 1e-15 (its error ~1e-30 relative only slows the last step).
numeric refine(const regime_case &c, std::size_t shared, const exmap &at, numeric t)
{
    const numeric dt("1e-15");
    for (int it = 0; it < 40; ++it) {
        const numeric slope = (g_at(c, shared, at, t + dt) - g_at(c, shared, at, t - dt)) / (2 * dt);
        const numeric step = g_at(c, shared, at, t) / slope;
        t -= step;
        if (abs(step) < numeric("1e-36"))
            break;
    }
    return t;
}

// The simple roots of the angle equation at the point: a sign change on one of 360 arcs.
std::vector<numeric> angle_roots(const regime_case &c, std::size_t shared, const exmap &at)
{
    std::vector<numeric> roots;
    const int arcs = 360;
    const numeric two_pi = ex_to<numeric>((2 * Pi).evalf());
    numeric prev = g_at(c, shared, at, 0);
    for (int i = 1; i <= arcs; ++i) {
        const numeric t1 = two_pi * i / arcs, v1 = g_at(c, shared, at, t1);
        if ((prev < 0) != (v1 < 0))
            roots.push_back(refine(c, shared, at, t1 - two_pi / (2 * arcs)));
        prev = v1;
    }
    return roots;
}

bool holds_strictly(const regime_case &c, const exmap &at)
{
    for (const regime_condition &k : c.conditions)
        if (!(num(k.value, at) > 0))
            return false;
    return true;
}

// The regime's steps at the point, added to `at` (inputs and shared steps); for the slide without
// a closed form at the root near `theta`, or, when theta < 0, the one root whose conditions hold
// (theta set to it). False when the regime does not hold there (or holds at several roots).
bool regime_at(const regime_case &c, std::size_t shared, exmap &at, numeric &theta)
{
    if (!c.needs_angle) {
        evaluate(c.sol.steps, shared, at);
        return holds_strictly(c, at);
    }
    const std::vector<numeric> roots =
        theta < 0 ? angle_roots(c, shared, at) : std::vector<numeric>{refine(c, shared, at, theta)};
    int holding = 0;
    exmap found;
    for (const numeric &t : roots) {
        const exmap m = at_angle(c, shared, at, t);
        if (holds_strictly(c, m)) {
            ++holding;
            found = m;
            theta = t < 0 ? t + ex_to<numeric>((2 * Pi).evalf()) : t;
        }
    }
    if (holding != 1)
        return false;
    at = found;
    return true;
}

// `regimes` of the candidates (every one when 0) must each get per_regime points; every point
// checks every entry of its regime's Jacobian.
void check_problem(const problem &p, unsigned salt, int per_regime, std::size_t regimes = 0)
{
    impactgen::testing::digits_40 precision;
    const derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    const friction_jacobian j = friction_jacobian_of(d, s, {});
    ASSERT_EQ(j.regimes.size(), s.cases.size());
    const std::size_t shared = s.shared.steps.size();
    const impactgen::step *un = s.shared.find(step_role::approach_velocity);
    ASSERT_NE(un, nullptr);
    std::mt19937 g(impactgen::testing::seed_from_env() + salt);
    std::vector<int> seen(s.cases.size(), 0);
    const numeric h("1e-12");
    int entries = 0;
    const int want = impactgen::testing::samples_from_env(per_regime);
    const std::size_t needed = regimes ? regimes : s.cases.size();
    auto enough = [&] {
        std::size_t full = 0;
        for (int n : seen)
            full += n >= want;
        return full >= needed;
    };
    for (int draw_no = 0; draw_no < 4000 && !enough(); ++draw_no) {
        exmap x;
        for (const symbol &w : j.wrt)
            x[w] = draw(w.get_name(), g);
        exmap base = x;
        int regime = -1, holding = 0;
        std::vector<numeric> angles(s.cases.size(), -1);
        std::vector<exmap> states(s.cases.size());
        try {
            evaluate(s.shared.steps, 0, base);
            if (!(num(un->sym, base) < 0))
                continue;
            for (std::size_t k = 0; k < s.cases.size(); ++k) {
                states[k] = base;
                if (regime_at(s.cases[k], shared, states[k], angles[k])) {
                    ++holding;
                    regime = static_cast<int>(k);
                }
            }
        } catch (const std::exception &) {
            continue; // a division by zero: a degenerate draw
        }
        if (holding != 1 || seen[static_cast<std::size_t>(regime)] >= want)
            continue;
        const std::size_t k = static_cast<std::size_t>(regime);
        const regime_case &c = s.cases[k];
        const regime_jacobian &r = j.regimes[k];
        ++seen[k];
        exmap at = states[k];
        evaluate(j.derivative_steps, 0, at);
        evaluate(r.derivative_steps, 0, at);
        const auto outs = friction_outputs(p, c);
        for (std::size_t w = 0; w < j.wrt.size(); ++w) {
            exmap plus = x, minus = x;
            plus[j.wrt[w]] = x[j.wrt[w]] + h;
            minus[j.wrt[w]] = x[j.wrt[w]] - h;
            numeric tp = angles[k], tm = angles[k];
            evaluate(s.shared.steps, 0, plus);
            evaluate(s.shared.steps, 0, minus);
            ASSERT_TRUE(regime_at(c, shared, plus, tp) && regime_at(c, shared, minus, tm))
                << c.name << ": the regime does not hold next to the point";
            for (std::size_t o = 0; o < outs.size(); ++o) {
                const numeric fd = (num(outs[o].second, plus) - num(outs[o].second, minus)) / (2 * h);
                const numeric exact = num(r.entries[o][w], at);
                EXPECT_LE(abs(exact - fd).to_double(), 1e-9 * (1 + abs(fd).to_double()))
                    << p.source << " " << c.name << ": d " << j.outputs[o] << " / d " << j.wrt[w] << " = " << exact
                    << ", central difference " << fd;
                ++entries;
            }
        }
    }
    EXPECT_TRUE(enough()) << p.source << ": too few points in its regimes";
    std::printf("[ %s ] %d derivatives compared in %zu regimes\n", p.source.c_str(), entries, s.cases.size());
}

problem named(const std::string &name)
{
    for (const named_class &c : friction_classes())
        if (c.name == name)
            return c.build();
    throw std::runtime_error("no class " + name);
}

} // namespace

TEST(FrictionJacobian, PlanarFrictionAgainstCentralDifferences)
{
    check_problem(named("planar-friction"), 21, 4);
}
TEST(FrictionJacobian, BallFloorFrictionAgainstCentralDifferences)
{
    check_problem(named("ball-floor-friction"), 22, 4);
}
TEST(FrictionJacobian, IsotropicSlide3dAgainstCentralDifferences)
{
    check_problem(load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/tests/codegen/friction/sphere-floor-3d.json"),
                  23, 3);
}
TEST(FrictionJacobian, Noncentral3dThroughTheAngleEquationAgainstCentralDifferences)
{
    check_problem(named("noncentral-3d-friction"), 24, 2);
}
TEST(FrictionJacobian, NoStickCandidateAgainstCentralDifferences)
{
    check_problem(load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) +
                                    "/tests/codegen/friction/pinned-rod-struck-symbolic.json"),
                  25, 3, 1); // (the struck rod slides one way only: the other slide never holds)
}
