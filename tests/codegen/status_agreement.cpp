// Status values that agree: the same input gives the same status in every header that can
// take it. Masses and moments of inertia over the whole range of double (1e-308 ... 1e308,
// the masses of 1e308 included), and invalid values (0, < 0, NaN, infinite, e out
// of [0, 1], separating velocities): the smooth planar header, the planar friction header
// with mu = 0 (the same impact) and with mu = 0.3 (the same validity and the same
// overflow), the engine convention where its inverses are finite; the same in 3-D. The
// entry points of the 3-D engine header (inputs as values, in an array, by name) against its
// checked path on every input and pair of tensor entries set to a value that breaks a check.
#include "noncentral_3d.hpp"
#include "noncentral_3d_engine.hpp"
#include "noncentral_3d_friction.hpp"
#include "planar.hpp"
#include "planar_engine.hpp"
#include "planar_friction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace gen = impactgen::generated;

namespace
{

const std::vector<double> scales = {1e-308, 1e-300, 1e-200, 1e-100, 1e-10, 1, 1e10, 1e100, 1e200, 1e300, 1e308};

struct planar_in {
    double e = 0.5, m1 = 1, I1 = 1, m2 = 2, I2 = 3, v_n1 = 1, v_n2 = -1;
};

int smooth(const planar_in &x)
{
    gen::planar_result<double> r{};
    return int(
        gen::planar(x.e, x.m1, x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, x.m2, x.I2, -0.3, 0.4, -0.5, x.v_n2, 0.125, r));
}

int friction(const planar_in &x, double mu)
{
    gen::planar_friction_result<double> r{};
    return int(gen::planar_friction(x.e, mu, x.m1, x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, x.m2, x.I2, -0.3, 0.4, -0.5,
                                    x.v_n2, 0.125, r));
}

int engine(const planar_in &x)
{
    gen::planar_engine_result<double> r{};
    return int(gen::planar_engine(x.e, 1 / x.m1, 1 / x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, 1 / x.m2, 1 / x.I2, -0.3, 0.4,
                                  -0.5, x.v_n2, 0.125, r));
}

bool finite_inverses(const planar_in &x)
{
    for (double v : {x.m1, x.I1, x.m2, x.I2})
        if (!std::isfinite(v) || !std::isfinite(1 / v) || 1 / v == 0)
            return false;
    return true;
}

void expect_agree(const planar_in &x, const std::string &what)
{
    const int s = smooth(x), f0 = friction(x, 0), f = friction(x, 0.3);
    EXPECT_EQ(s, f0) << what << ": planar and planar_friction with mu = 0";
    // With friction the impact is another one: it may have no regime (or two) where the
    // smooth one is ok; every other status is the smooth header's.
    const bool regime_status = f == int(gen::friction_status::no_solution) || f == int(gen::friction_status::ambiguous);
    if (!(s == 0 && regime_status))
        EXPECT_EQ(s, f) << what << ": planar and planar_friction with mu = 0.3";
    if (finite_inverses(x))
        EXPECT_EQ(s, engine(x)) << what << ": planar and planar_engine";
}

TEST(CodegenStatusAgreement, PlanarOverTheWholeRange)
{
    for (double m : scales)
        for (double I : scales)
            for (double m2 : {1.0, 2.0}) {
                planar_in x;
                x.m1 = m, x.I1 = I, x.m2 = m2 * m, x.I2 = 3 * I;
                if (!std::isfinite(x.m2) || !std::isfinite(x.I2))
                    continue;
                expect_agree(x, "m " + std::to_string(m) + ", I " + std::to_string(I));
            }
    // The example: masses (and moments of inertia) of 1e308, where the friction header
    // said singular: the impact in both (k is denormal, the impulse about 1.4e308). Compared
    // without the energy lost: the smooth header computes it as -(u N + k N^2 / 2), whose N^2
    // overflows here (overflow), the friction header as the work of the impulse (finite).
    planar_in x;
    x.m1 = x.m2 = x.I1 = x.I2 = 1e308;
    gen::planar_result<double> a{};
    gen::planar_friction_result<double> b{};
    const auto s = gen::planar<double, false>(x.e, x.m1, x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, x.m2, x.I2, -0.3, 0.4,
                                              -0.5, x.v_n2, 0.125, a);
    const auto f = gen::planar_friction<double, false>(x.e, 0.3, x.m1, x.I1, 0.1, -0.2, 0.25, x.v_n1, 0.0, x.m2, x.I2,
                                                       -0.3, 0.4, -0.5, x.v_n2, 0.125, b);
    EXPECT_EQ(int(s), int(gen::impact_status::ok));
    EXPECT_EQ(int(f), int(gen::friction_status::ok));
    EXPECT_GT(a.normal_impulse, 1e307);
}

TEST(CodegenStatusAgreement, PlanarInvalidInputs)
{
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    for (double bad : {0.0, -1.0, nan, inf}) {
        planar_in x;
        x.m1 = bad;
        expect_agree(x, "m1 = " + std::to_string(bad));
        x = planar_in{};
        x.I2 = bad;
        expect_agree(x, "I2 = " + std::to_string(bad));
    }
    for (double e : {-0.1, 1.5, nan}) {
        planar_in x;
        x.e = e;
        expect_agree(x, "e = " + std::to_string(e));
    }
    planar_in x;
    x.v_n1 = -1, x.v_n2 = 1; // separating
    expect_agree(x, "separating");
    x.v_n1 = x.v_n2 = 0; // resting
    expect_agree(x, "resting");
}

TEST(CodegenStatusAgreement, ThreeDimensionalOverTheWholeRange)
{
    for (double m : scales)
        for (double I : scales) {
            if (!std::isfinite(3 * I) || !std::isfinite(2 * m))
                continue;
            gen::noncentral_3d_result<double> a{};
            gen::noncentral_3d_friction_result<double> b{};
            const double z = 0;
            const int s = int(gen::noncentral_3d<double>(0.5, m, I, z, z, I, z, I, 0.1, -0.2, 0.05, 0.25, 1.0, z, 0.1,
                                                         z, 0.2, 2 * m, 2 * I, z, z, 3 * I, z, 2 * I, -0.3, 0.4, 0.1,
                                                         -0.5, -1.0, z, 0.125, z, z, a));
            const int f = int(gen::noncentral_3d_friction<double>(
                0.5, 0.0, m, I, z, z, I, z, I, 0.1, -0.2, 0.05, 0.25, 1.0, z, 0.1, z, 0.2, 2 * m, 2 * I, z, z, 3 * I, z,
                2 * I, -0.3, 0.4, 0.1, -0.5, -1.0, z, 0.125, z, z, b));
            EXPECT_EQ(s, f) << "m " << m << ", I " << I;
        }
}

// The entry points of one engine header on the same inputs: the fast path called with the
// inputs as values, in an array and by name (the last two with a slow path of their own that
// reads the inputs again), and the checked path. Same status and the same result bit for bit.
template <typename T, typename Result, typename Input, std::size_t... I, typename Value, typename Array, typename Named,
          typename Checked>
void forms_agree(const T* x, std::index_sequence<I...>, Value value, Array array, Named named, Checked checked,
                 int (&count)[16], const std::string& what)
{
    Result a{}, b{}, c{}, d{};
    const Input in{x[I]...};
    const int sa = int(value(x[I]..., a)), sb = int(array(x, b)), sc = int(named(in, c)), sd = int(checked(x[I]..., d));
    ++count[sd & 15];
    EXPECT_EQ(sa, sd) << what << ": the value form and the checked path";
    EXPECT_EQ(sb, sd) << what << ": the array form and the checked path";
    EXPECT_EQ(sc, sd) << what << ": the struct form and the checked path";
    EXPECT_EQ(std::memcmp(&a, &d, sizeof a), 0) << what << ": the value form's result";
    EXPECT_EQ(std::memcmp(&b, &d, sizeof b), 0) << what << ": the array form's result";
    EXPECT_EQ(std::memcmp(&c, &d, sizeof c), 0) << what << ": the struct form's result";
}

// Every entry of the inverse inertia tensors (and every other input) set to a value that
// breaks a check or sits on its edge, one entry and every pair of tensor entries: a
// non-finite diagonal entry that only a minor sees, a minor that overflows, a determinant
// that cancels. The fast path's finiteness sum leaves out the values that another value in
// it implies (a diagonal entry its minors are made of, the minor its determinant is made
// of): the statuses must stay those of the checked path.
template <typename T> void noncentral_engine_forms_agree()
{
    constexpr int n = gen::noncentral_3d_engine_input_count;
    const T inf = std::numeric_limits<T>::infinity(), nan = std::numeric_limits<T>::quiet_NaN();
    const T big = std::sqrt(std::numeric_limits<T>::max()) * T(2), tiny = std::numeric_limits<T>::denorm_min();
    const std::vector<T> special = {nan, inf, -inf, T(-1), T(-0.0), T(0), tiny, T(1e-3), big, -big, std::numeric_limits<T>::max()};
    // a valid impact: I^-1 positive definite, the contact points approaching
    const T base[n] = {T(0.5), T(1),    T(2),    T(0.3), T(-0.2), T(1.5),  T(0.1), T(1.2),  T(0.1),  T(-0.2), T(0.05),
                       T(0.25), T(1),   T(0),    T(0.1), T(0),    T(0.2),  T(0.5), T(0.8),  T(-0.1), T(0.2),  T(0.9),
                       T(0.3),  T(1.1), T(-0.3), T(0.4), T(0.1),  T(-0.5), T(-1),  T(0),    T(0.125), T(0),   T(0)};
    using R = gen::noncentral_3d_engine_result<T>;
    using In = gen::noncentral_3d_engine_input<T>;
    int count[16] = {};
    auto run = [&](const T* x, const std::string& what) {
        forms_agree<T, R, In>(
            x, std::make_index_sequence<n>{}, [](auto&&... v) { return gen::noncentral_3d_engine<T>(v...); },
            [](const T* p, R& r) { return gen::noncentral_3d_engine<T>(p, r); },
            [](const In& p, R& r) { return gen::noncentral_3d_engine<T>(p, r); },
            [](auto&&... v) { return gen::detail::noncentral_3d_engine_checked<T, true>(v...); }, count, what);
    };
    run(base, "the valid impact");
    const int tensor[12] = {2, 3, 4, 5, 6, 7, 18, 19, 20, 21, 22, 23};
    T x[n];
    for (int j = 0; j < n; ++j)
        for (T v : special) {
            std::copy(base, base + n, x);
            x[j] = v;
            run(x, "input " + std::to_string(j) + " = " + std::to_string(double(v)));
        }
    for (int j : tensor)
        for (int k : tensor)
            for (T v : special)
                for (T w : special) {
                    if (k <= j)
                        continue;
                    std::copy(base, base + n, x);
                    x[j] = v;
                    x[k] = w;
                    run(x, "inputs " + std::to_string(j) + ", " + std::to_string(k) + " = " + std::to_string(double(v)) +
                               ", " + std::to_string(double(w)));
                }
    // each way of failing is reached (a check left out of the fast path would show as ok)
    for (gen::impact_status s : {gen::impact_status::ok, gen::impact_status::non_finite_input,
                                 gen::impact_status::invalid_inertia, gen::impact_status::invalid_restitution,
                                 gen::impact_status::invalid_mass, gen::impact_status::not_approaching})
        EXPECT_GT(count[int(s)], 0) << gen::to_string(s);
}

TEST(CodegenStatusAgreement, EngineFormsAgreeOnBrokenTensors)
{
    noncentral_engine_forms_agree<double>();
    noncentral_engine_forms_agree<float>();
}

} // namespace
