// formulas --jacobian under Routh's process (symbolic/process_jacobian.hpp): per phase sequence,
// the exact derivatives of the impact map (chain rule through the contact's steps) against central
// finite differences of the same sequence's closed form, at random rational points of the rod of
// tests/codegen/laws/rod-rough-floor-*.json (inputs e, mu, m, I1, x, y, v_t, v_n, w), Poisson and
// energetic. The closed form is evaluated with 40 digits, so a step h = 1e-12 leaves a truncation
// error h^2 |f'''| ~ 1e-24 and a rounding error 1e-40 / h = 1e-28: the derivative agrees to 1e-9
// relative unless it is wrong (a wrong term is O(1) of it).
#include "sampling.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/process_jacobian.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace impactgen;
using namespace GiNaC;

namespace
{

// value(e) at the point: derivative steps, then steps, then the inputs.
numeric at(const ex &e, const lst &dsteps, const lst &steps, const lst &point)
{
    const ex v = e.subs(dsteps).subs(steps).subs(point).evalf();
    if (!is_a<numeric>(v)) {
        ADD_FAILURE() << "not a number: " << v;
        return 0;
    }
    return ex_to<numeric>(v);
}

// The sequence whose conditions hold strictly at the point, or -1.
int holding(const process_jacobian &j, const lst &steps, const lst &point)
{
    for (std::size_t k = 0; k < j.sequences.size(); ++k) {
        bool all = true;
        try { // a condition of another sequence may divide by zero here (a slope of 0)
            for (const process_condition &c : j.sequences[k].conditions)
                all = all && at(c.value, lst{}, steps, point) > 0;
        } catch (const std::exception &) {
            all = false;
        }
        if (all)
            return static_cast<int>(k);
    }
    return -1;
}

void jacobian_against_differences(const std::string &law, unsigned salt)
{
    impactgen::testing::digits_40 precision;
    const problem p =
        load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/tests/codegen/laws/rod-rough-floor-" + law + ".json");
    const derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    ASSERT_TRUE(solution_follows_process(s));
    const process_jacobian j = process_jacobian_of(d, s, {});
    ASSERT_EQ(j.sequences.size(), s.cases.size());
    lst steps, dsteps;
    for (const impactgen::step &st : j.steps)
        steps.append(st.sym == st.value);
    for (const impactgen::step &st : j.derivative_steps)
        dsteps.append(st.sym == st.value);
    std::mt19937 g(impactgen::testing::seed_from_env() + salt);
    auto R = [&](int lo, int hi, int den) {
        return numeric(std::uniform_int_distribution<int>(lo * den, hi * den)(g), den);
    };
    std::vector<int> seen(j.sequences.size(), 0);
    int points = 0, entries = 0;
    const numeric h("1e-12");
    for (int i = 0; i < 400 && points < impactgen::testing::samples_from_env(24); ++i) {
        // (e > 0: at e = 0 the energetic law's sqrt(e^2 ...) is |e ...|, not differentiable)
        std::map<std::string, numeric> x{{"e", R(1, 16, 1) / 16}, {"mu", R(1, 32, 1) / 16}, {"m", R(1, 4, 4)},
                                         {"I1", R(1, 4, 48)},     {"x", R(-1, 1, 8)},       {"y", R(0, 1, 8)},
                                         {"v_t", R(-2, 2, 8)},    {"v_n", R(-2, 0, 8)},     {"w", R(-4, 4, 4)}};
        auto point_of = [&](const symbol &moved, const numeric &by) {
            lst l;
            for (const symbol &w : j.wrt)
                l.append(w == x.at(w.get_name()) + (w.is_equal(moved) ? by : numeric(0)));
            return l;
        };
        const symbol none("none");
        const lst point = point_of(none, 0);
        const int k = holding(j, steps, point);
        if (k < 0 || x.at("y").is_zero() || !(x.at("v_n") - x.at("w") * x.at("x") < 0))
            continue; // not approaching (u_n = v_n - w x), wedging, or on a boundary
        ++points;
        ++seen[static_cast<std::size_t>(k)];
        const sequence_jacobian &q = j.sequences[static_cast<std::size_t>(k)];
        const regime_case &c = s.cases[static_cast<std::size_t>(k)];
        const ex outs[2] = {c.sol.normal_impulse, c.tangential_scalar};
        const ex spin = c.sol.after[1].angular_velocity[2];
        for (std::size_t w = 0; w < j.wrt.size(); ++w) {
            const lst plus = point_of(j.wrt[w], h), minus = point_of(j.wrt[w], -h);
            if (holding(j, steps, plus) != k || holding(j, steps, minus) != k)
                continue;
            for (int o = 0; o < 3; ++o) {
                const ex f = o < 2 ? outs[o] : spin;
                const std::size_t row = o < 2 ? static_cast<std::size_t>(o) : j.outputs.size() - 1; // w'_z,rod last
                numeric fd, exact;
                try {
                    fd = (at(f, lst{}, steps, plus) - at(f, lst{}, steps, minus)) / (2 * h);
                } catch (const std::exception &err) {
                    ADD_FAILURE() << "fd " << err.what() << " " << q.sequence << " " << point;
                    continue;
                }
                try {
                    exact = at(q.entries[row][w], dsteps, steps, point);
                } catch (const std::exception &err) {
                    ADD_FAILURE() << "exact " << err.what() << " " << q.sequence << " d " << j.outputs[row] << "/d "
                                  << j.wrt[w] << " " << point;
                    continue;
                }
                EXPECT_LE(abs(exact - fd).to_double(), 1e-9 * (1 + abs(fd).to_double()))
                    << law << " " << q.sequence << " d " << j.outputs[row] << "/d " << j.wrt[w];
                ++entries;
            }
        }
    }
    EXPECT_GE(points, impactgen::testing::samples_from_env(24));
    int sequences = 0;
    for (int n : seen)
        sequences += n > 0;
    EXPECT_GE(sequences, 2) << "the points fell in one sequence only";
    std::printf("[ %s ] %d points in %d sequences, %d derivatives compared\n", law.c_str(), points, sequences, entries);
}

} // namespace

TEST(ProcessJacobian, PoissonAgainstCentralDifferences)
{
    jacobian_against_differences("poisson", 11);
}
TEST(ProcessJacobian, EnergeticAgainstCentralDifferences)
{
    jacobian_against_differences("energetic", 12);
}
