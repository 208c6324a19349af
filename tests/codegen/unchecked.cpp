// The validate-once fast path: NAME_unchecked skips the per-call validation of the inputs
// (restitution, friction, masses, inertia and its positive-definiteness minors, the normal,
// finiteness) and keeps the checks of the state. On valid inputs (seeded random, by the
// inputs' names) it returns what NAME returns where that is ok, not_approaching or singular,
// and where NAME returns ok the same outputs bit for bit (and the same regime), for the
// smooth headers and those with friction, in float and double.
#include "ball_floor_friction.hpp"
#include "central_direct.hpp"
#include "massive_3d.hpp"
#include "noncentral_3d.hpp"
#include "noncentral_3d_engine.hpp"
#include "noncentral_3d_friction.hpp"
#include "pinned_planar.hpp"
#include "planar.hpp"
#include "planar_engine.hpp"
#include "planar_friction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace gen = impactgen::generated;

namespace
{

template <typename T, std::size_t... I> auto tuple_of(const T *x, std::index_sequence<I...>)
{
    return std::make_tuple(x[I]...);
}

// An inertia entry: "I1", "inv_I1" (planar) or "I1_tn", "inv_I2_bb" (3-D); diagonal when its
// two axis letters agree.
bool inertia_name(const std::string &nm, bool &diagonal)
{
    const std::string s = nm.rfind("inv_", 0) == 0 ? nm.substr(4) : nm;
    if (s.empty() || s[0] != 'I')
        return false;
    const std::size_t k = s.rfind('_');
    diagonal = k == std::string::npos || (s.size() == k + 3 && s[k + 1] == s[k + 2]);
    return true;
}

bool mass_name(const std::string &nm)
{
    const std::string s = nm.rfind("inv_", 0) == 0 ? nm.substr(4) : nm;
    return s.size() >= 2 && s[0] == 'm' && s.find('_') == std::string::npos;
}

// Valid inputs by name: e in [0, 1], mu in [0, 1.2], masses log-uniform in [1e-2, 1e2],
// inertia tensors diagonally dominant (positive definite, their inverses too), the rest in
// [-1, 1].
template <typename T> std::vector<T> draw(std::mt19937_64 &g, const char *const *names, int n)
{
    std::uniform_real_distribution<double> U(0, 1);
    std::vector<T> x(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) {
        const std::string nm = names[j];
        bool diagonal = false;
        double v = 2 * U(g) - 1;
        if (nm == "e")
            v = U(g);
        else if (nm == "mu")
            v = 1.2 * U(g);
        else if (mass_name(nm))
            v = std::exp(std::log(1e-2) + U(g) * std::log(1e4));
        else if (inertia_name(nm, diagonal))
            v = diagonal ? 2.5 + U(g) : 0.5 * (2 * U(g) - 1);
        x[static_cast<std::size_t>(j)] = static_cast<T>(v);
    }
    return x;
}

template <typename T> bool same_bits(const std::vector<T> &a, const std::vector<T> &b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// Draws valid inputs, calls both functions through `call(x, unchecked, outputs, regime)`,
// and compares; at least min_ok of the draws must be impacts.
template <typename T, typename Status, typename Call>
void agree(const char *what, const char *const *names, int n_in, Call call, int min_ok)
{
    std::mt19937_64 g(2024);
    int ok = 0, state = 0;
    for (int i = 0; i < 4000; ++i) {
        const std::vector<T> x = draw<T>(g, names, n_in);
        std::vector<T> a, b;
        int ra = -1, rb = -1;
        const Status sa = call(x, false, a, ra), sb = call(x, true, b, rb);
        if (sa == Status::ok) {
            ++ok;
            ASSERT_EQ(int(sb), int(Status::ok)) << what << " draw " << i;
            EXPECT_TRUE(same_bits(a, b)) << what << " draw " << i << ": outputs differ";
            EXPECT_EQ(ra, rb) << what << " draw " << i << ": regimes differ";
        } else if (sa == Status::not_approaching || sa == Status::singular) {
            ++state;
            EXPECT_EQ(int(sb), int(sa)) << what << " draw " << i;
        }
    }
    EXPECT_GE(ok, min_ok) << what << ": too few impacts among the draws (" << state << " of the state)";
}

// Both functions of header FN for scalar T (STATUS its status enum, REGIME the result's
// regime as an int, or 0).
#define BOTH(FN, T, MIN_OK, STATUS, REGIME)                                                                            \
    agree<T, gen::STATUS>(                                                                                             \
        #FN " " #T, gen::FN##_input_names, gen::FN##_input_count,                                                      \
        [](const std::vector<T> &x, bool unchecked, std::vector<T> &o, int &regime) {                                  \
            gen::FN##_result<T> r{};                                                                                   \
            const auto args = tuple_of(x.data(), std::make_index_sequence<gen::FN##_input_count>{});                   \
            const gen::STATUS s = unchecked                                                                            \
                                      ? std::apply([&](auto... v) { return gen::FN##_unchecked<T>(v..., r); }, args)   \
                                      : std::apply([&](auto... v) { return gen::FN<T>(v..., r); }, args);              \
            o.assign(static_cast<std::size_t>(gen::FN##_output_count), T(0));                                          \
            gen::FN##_to_array(r, o.data());                                                                           \
            regime = REGIME;                                                                                           \
            return s;                                                                                                  \
        },                                                                                                             \
        MIN_OK)
#define SMOOTH(FN, T, MIN_OK) BOTH(FN, T, MIN_OK, impact_status, 0)
#define FRICTION(FN, T, MIN_OK) BOTH(FN, T, MIN_OK, friction_status, static_cast<int>(r.regime))

TEST(CodegenUnchecked, SmoothHeadersBitIdentical)
{
    SMOOTH(central_direct, double, 1000);
    SMOOTH(planar, double, 1000);
    SMOOTH(planar, float, 1000);
    SMOOTH(planar_engine, double, 1000);
    SMOOTH(pinned_planar, double, 1000);
    SMOOTH(noncentral_3d, double, 1000);
    SMOOTH(noncentral_3d, float, 1000);
    SMOOTH(noncentral_3d_engine, double, 1000);
    SMOOTH(massive_3d, double, 1000);
}

TEST(CodegenUnchecked, FrictionHeadersBitIdentical)
{
    FRICTION(planar_friction, double, 1000);
    FRICTION(planar_friction, float, 1000);
    FRICTION(ball_floor_friction, double, 500);
    FRICTION(noncentral_3d_friction, double, 1000);
}

// The contract's other side: the unchecked function does not validate (a negative mass is
// computed with, not refused), where the checked one refuses.
TEST(CodegenUnchecked, SkipsTheValidation)
{
    gen::planar_result<double> a{}, b{};
    const double m1 = -10; // k = 1/m1 + ... stays > 0
    EXPECT_EQ(gen::planar(0.5, m1, 0.5, 0.1, -0.2, 0.25, 1.0, 0.0, 2.0, 0.7, -0.3, 0.4, -0.5, -1.0, 0.125, a),
              gen::impact_status::invalid_mass);
    EXPECT_EQ(gen::planar_unchecked(0.5, m1, 0.5, 0.1, -0.2, 0.25, 1.0, 0.0, 2.0, 0.7, -0.3, 0.4, -0.5, -1.0, 0.125, b),
              gen::impact_status::ok);
    EXPECT_NE(b.normal_impulse, 0.0);
}

} // namespace
