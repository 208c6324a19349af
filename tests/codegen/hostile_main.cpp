// A generated header from a problem with hostile names (tests/codegen/hostile/),
// compiled under strict warnings by g++ and clang++ in C++17 and C++20, and run:
// the names may be anything, the physics must not change. In particular a user
// symbol named u (the approach velocity's name in the closed form) is a plain
// input: with u < 0 the bodies separate and the header must say so.
#include GEN_HEADER

#include <cstdio>

using namespace impactgen::generated;

namespace {

int failures = 0;

void expect(bool ok, const char* what)
{
    if (!ok) {
        std::printf("FAILED: %s\n", what);
        ++failures;
    }
}

#ifdef HOSTILE_SYMBOLS
// Inputs in order: e, class (m1), l, u (v_x1), NULL (m2), errno (I2), k, N (v_x2), i (w2).
template <typename T> void symbols_named_like_steps_case()
{
    symbols_named_like_steps_result<T> r{};
    impact_status s = symbols_named_like_steps<T>(T(0.5), T(1), T(1), T(1), T(2), T(0.5), T(0.5), T(0), T(0), r);
    expect(s == impact_status::ok, "u = 1 approaches: ok");
    expect(r.normal_impulse > T(0), "u = 1: positive normal impulse");
    expect(r.approach_velocity < T(0), "u = 1: approach velocity < 0");
    s = symbols_named_like_steps<T>(T(0.5), T(1), T(1), T(-1), T(2), T(0.5), T(0.5), T(0), T(0), r);
    expect(s == impact_status::not_approaching, "u = -1 separates: not_approaching");
    const char* const* names = symbols_named_like_steps_input_names;
    int n = 0;
    while (names[n])
        ++n;
    expect(n == symbols_named_like_steps_input_count, "input names listed");
}
#endif

#ifdef HOSTILE_NUMERIC
template <typename T> void numeric_case()
{
    x_9_numeric_3d_result<T> r{};
    impact_status s = x_9_numeric_3d<T>(r);
    expect(s == impact_status::ok, "fully numeric 3-D problem: ok");
    expect(r.normal_impulse > T(0), "fully numeric 3-D problem: positive normal impulse");
}
#endif

#ifdef HOSTILE_EXTREME
// Masses 1e-300 and 1e300, fully numeric: folded constants beyond float's range
// must never give ok with NaN (they gave inf/inf before).
template <typename T> void extreme_case()
{
    extreme_scales_result<T> r{};
    impact_status s = extreme_scales<T>(r);
    T values[extreme_scales_output_count];
    extreme_scales_to_array(r, values);
    bool finite = true;
    for (T v : values)
        finite = finite && v - v == T(0);
    expect(s != impact_status::ok || finite, "ok means every output is finite");
}
#endif

#ifdef HOSTILE_CMATH
// Symbols named like <cmath> macros, and Pi, cos(1) as constants; M_PI = 3 (mass), M_E = 1 (speed).
template <typename T> void cmath_case()
{
    cmath_names_result<T> r{};
    impact_status s = cmath_names<T>(T(3), T(1), T(0.5), r);
    expect(s == impact_status::ok, "cmath names: ok");
    expect(r.normal_impulse > T(0), "cmath names: positive normal impulse");
}
#endif

} // namespace

int main()
{
#ifdef HOSTILE_SYMBOLS
    symbols_named_like_steps_case<float>();
    symbols_named_like_steps_case<double>();
    symbols_named_like_steps_case<long double>();
#endif
#ifdef HOSTILE_NUMERIC
    numeric_case<float>();
    numeric_case<double>();
    numeric_case<long double>();
#endif
#ifdef HOSTILE_EXTREME
    extreme_case<float>();
    extreme_case<double>();
    extreme_case<long double>();
    {
        extreme_scales_result<double> r{};
        expect(extreme_scales<double>(r) == impact_status::ok, "extreme scales in double: ok");
    }
#endif
#ifdef HOSTILE_CMATH
    cmath_case<float>();
    cmath_case<double>();
    cmath_case<long double>();
#endif
    std::printf("%s: %d failure(s)\n", GEN_HEADER, failures);
    return failures == 0 ? 0 : 1;
}
