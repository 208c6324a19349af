// Hooks the user may define before including a generated header:
//   IMPACTGEN_HOST_DEVICE  where functions run: by default __host__ __device__
//                   under a CUDA or HIP compiler (nvcc, hipcc, clang -x cuda), so
//                   that the header is callable from kernels as it is; nothing
//                   for any other compiler
//   IMPACTGEN_FUNC  what every function is declared with (default
//                   IMPACTGEN_HOST_DEVICE inline)
//   IMPACTGEN_MEMBER  what the structs' member functions are declared with
//                   (default IMPACTGEN_HOST_DEVICE)
//   IMPACTGEN_RESTRICT  the no-alias qualifier of the batch form's arrays
//                   (default __restrict with GCC, clang, MSVC)
//   IMPACTGEN_HOT, IMPACTGEN_COLD  attributes of the fast path and of the slow
//                   path that classifies failures
//   IMPACTGEN_ALLOW_FAST_MATH  compile under -ffast-math or -ffinite-math-only
//                   anyway (its NaN and infinity checks may then pass a NaN
//                   input as ok)
// Device code (CUDA, HIP): with IMPACTGEN_HOST_DEVICE __host__ __device__ (the
// default there), every function of the header compiles for the device:
// its device pass (__CUDA_ARCH__, __HIP_DEVICE_COMPILE__) calls no host-only
// function (std::numeric_limits' functions, compiler builtins) and has no long
// double (a number the header writes in long double is a double there: the
// device has no wider type; view::fixed is double there too).
#ifndef IMPACTGEN_HOST_DEVICE
#if defined(__CUDACC__) || defined(__HIPCC__)
#define IMPACTGEN_HOST_DEVICE __host__ __device__
#else
#define IMPACTGEN_HOST_DEVICE
#endif
#endif
#ifndef IMPACTGEN_FUNC
#define IMPACTGEN_FUNC IMPACTGEN_HOST_DEVICE inline
#endif
#ifndef IMPACTGEN_MEMBER
#define IMPACTGEN_MEMBER IMPACTGEN_HOST_DEVICE
#endif
#ifndef IMPACTGEN_RESTRICT
#if defined(__GNUC__) || defined(_MSC_VER)
#define IMPACTGEN_RESTRICT __restrict
#else
#define IMPACTGEN_RESTRICT
#endif
#endif
#ifndef IMPACTGEN_COLD
#if defined(__GNUC__)
#define IMPACTGEN_COLD __attribute__((noinline, cold))
#else
#define IMPACTGEN_COLD
#endif
#endif
#ifndef IMPACTGEN_HOT
#if defined(__GNUC__)
#define IMPACTGEN_HOT __attribute__((always_inline))
#else
#define IMPACTGEN_HOT
#endif
#endif
#if (defined(__FAST_MATH__) || (defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__)) && !defined(IMPACTGEN_ALLOW_FAST_MATH)
#error "impactgen: -ffast-math and -ffinite-math-only remove the NaN and infinity checks of this header (a NaN input would return ok); compile it without them (or with -fno-finite-math-only), or define IMPACTGEN_ALLOW_FAST_MATH"
#endif

#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
#define IMPACTGEN_WIDE(x) x
#else
#define IMPACTGEN_WIDE(x) x##L
#endif

/// The widest floating type of the pass: long double, or double in device code.
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
using wide_number = double;
#else
using wide_number = long double;
#endif

/// Why a call computed no post-impact state. On any status but ok the result
/// holds the state unchanged: the velocities as before the impact, every
/// impulse, the approach velocity and the energy lost zero (so an engine that
/// writes the result back unconditionally keeps its bodies' velocities).
enum class impact_status : int {
    ok = 0,
    non_finite_input,    ///< an input is infinite or NaN
    invalid_mass,        ///< a mass <= 0 (an inverse mass < 0) or not finite
    invalid_inertia,     ///< an inertia not positive definite (an inverse one not semidefinite) or not finite
    invalid_restitution, ///< e outside [0, 1]
    not_approaching,     ///< the contact points separate or rest: (v_B - v_A).n >= 0
    invalid_normal,      ///< the normal is zero, denormal or not finite (or, declared unit, not of length 1)
    singular,            ///< the effective inverse mass k = w_1 + w_2 is not positive and finite
    overflow             ///< finite inputs whose result overflows
};

IMPACTGEN_FUNC constexpr const char* to_string(impact_status s) noexcept
{
    switch (s) {
    case impact_status::ok: return "ok";
    case impact_status::non_finite_input: return "non-finite input";
    case impact_status::invalid_mass: return "invalid mass";
    case impact_status::invalid_inertia: return "invalid inertia";
    case impact_status::invalid_restitution: return "invalid restitution";
    case impact_status::not_approaching: return "not approaching";
    case impact_status::invalid_normal: return "invalid normal";
    case impact_status::singular: return "singular effective mass";
    case impact_status::overflow: return "overflow";
    }
    return "?";
}

/// Members of an input or result struct that form a vector (Cols = 1) or a
/// matrix, row-major, for adapters such as impactgen/eigen.hpp: entry[k] points
/// to the member, or is null where the header fixed the value (then fixed[k]).
/// A symmetric tensor's entries (r, c) and (c, r) point to the same member.
template <typename S, int Rows, int Cols> struct view {
    static constexpr int rows = Rows, cols = Cols;
    S* entry[Rows * Cols];
    wide_number fixed[Rows * Cols];
};

/// Floating-point operations of one call of a generated function.
struct op_count {
    int add, mul, div, sqrt;
};

namespace detail {
template <typename T> IMPACTGEN_FUNC constexpr bool finite(T x) noexcept { return x - x == T(0); }
template <typename T, typename... U> IMPACTGEN_FUNC constexpr bool all_finite(T x, U... y) noexcept
{
    return (finite(x) && ... && finite(y));
}
/// A number of the header (a wide_number literal) in the scalar type: directly for
/// float, double and long double; through double for other types (autodiff
/// scalars such as Eigen's AutoDiffScalar or ceres::Jet are built on double), so
/// that no implicit long double conversion is left for -Wconversion to flag.
template <typename T> struct constant_of {
    IMPACTGEN_MEMBER static T from(wide_number x) noexcept { return T(static_cast<double>(x)); }
};
template <> struct constant_of<float> {
    IMPACTGEN_MEMBER static constexpr float from(wide_number x) noexcept { return static_cast<float>(x); }
};
template <> struct constant_of<double> {
    IMPACTGEN_MEMBER static constexpr double from(wide_number x) noexcept { return static_cast<double>(x); }
};
#if !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
template <> struct constant_of<long double> {
    IMPACTGEN_MEMBER static constexpr long double from(long double x) noexcept { return x; }
};
#endif
template <typename T> IMPACTGEN_FUNC T constant(wide_number x) noexcept { return constant_of<T>::from(x); }
/// The smallest positive normal number and the machine epsilon of T: std::numeric_limits'
/// on the host; in device code (where those functions are host-only) float's or double's.
template <typename T> IMPACTGEN_FUNC constexpr T smallest_normal() noexcept
{
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
    if constexpr (sizeof(T) == sizeof(float))
        return T(1.17549435082228750797e-38f);
    else
        return T(2.22507385850720138309e-308);
#else
    return std::numeric_limits<T>::min();
#endif
}
template <typename T> IMPACTGEN_FUNC constexpr T machine_epsilon() noexcept
{
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
    if constexpr (sizeof(T) == sizeof(float))
        return T(1.1920928955078125e-07f);
    else
        return T(2.220446049250313080847e-16);
#else
    return std::numeric_limits<T>::epsilon();
#endif
}
template <typename T> IMPACTGEN_FUNC constexpr T min_of(T x) noexcept { return x; }
/// The smallest argument (a NaN argument may be dropped: callers test finiteness apart).
template <typename T, typename... U> IMPACTGEN_FUNC constexpr T min_of(T x, T y, U... z) noexcept
{
    return min_of(y < x ? y : x, z...);
}
} // namespace detail
