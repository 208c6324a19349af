// The runtime files (codegen/runtime/*.hpp) compiled on their own and run, as the headers
// emit them: inside a namespace; impact_runtime.hpp after <limits> (every header includes
// it: smallest_normal, machine_epsilon), friction_runtime.hpp after <cmath>, <limits> and
// impact_runtime.hpp (it uses
// impact_status, IMPACTGEN_FUNC and the detail helpers). GEN_HEADER is the file under
// test; RUNTIME_IMPACT or RUNTIME_FRICTION says which. The templates are instantiated for
// float, double and long double, so that the strict warnings of check_compile.cmake see
// their bodies, and a few of their answers checked. RUNTIME_FRICTION_STATS: the friction
// file with its iteration counters (IMPACTGEN_TRIG2_STATS) compiled in.
#ifdef RUNTIME_FRICTION_STATS
#define RUNTIME_FRICTION
#define IMPACTGEN_TRIG2_STATS
#endif
#include <limits>
#ifdef RUNTIME_FRICTION
#include <cmath>
#endif

namespace runtime_check
{
#ifdef RUNTIME_FRICTION
#include "../../codegen/runtime/impact_runtime.hpp"
#endif
#include GEN_HEADER
} // namespace runtime_check

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace
{
using namespace runtime_check;

int failures = 0;

void expect(bool ok, const char *what)
{
    if (!ok) {
        std::printf("FAILED: %s\n", what);
        ++failures;
    }
}

template <typename T> void check_impact()
{
    const T inf = std::numeric_limits<T>::infinity();
    expect(detail::finite(T(1)) && !detail::finite(inf) && !detail::finite(inf - inf), "detail::finite");
    expect(detail::all_finite(T(1), T(2), T(3)) && !detail::all_finite(T(1), inf), "detail::all_finite");
    expect(detail::min_of(T(3), T(1), T(2)) == T(1), "detail::min_of");
    expect(detail::constant<T>(0.5L) == T(0.5), "detail::constant");
    expect(detail::constant<T>(IMPACTGEN_WIDE(0.25)) == T(0.25), "IMPACTGEN_WIDE");
    expect(detail::smallest_normal<T>() == std::numeric_limits<T>::min(), "detail::smallest_normal");
    expect(detail::machine_epsilon<T>() == std::numeric_limits<T>::epsilon(), "detail::machine_epsilon");
    T x = T(2);
    const view<T, 1, 1> v = {{&x}, {0.0L}};
    expect(*v.entry[0] == T(2) && v.rows == 1 && v.cols == 1, "view");
}

#ifdef RUNTIME_FRICTION
template <typename T> void check_friction()
{
    using std::abs;
    T t[3], b[3];
    detail::tangent_basis(T(0), T(0), T(2), t, b);
    expect(abs(t[0] * t[0] + t[1] * t[1] + t[2] * t[2] - T(1)) < T(1e-5) && abs(t[2]) < T(1e-5), "tangent_basis");
    expect(detail::boundary_tolerance<T>() > T(0) && detail::boundary_tolerance<T>() < T(1e-3), "boundary_tolerance");
    T rc[4], rs[4];
    // g = cos theta: roots (0, 1) and (0, -1).
    const int n = detail::trig2_roots(T(0), T(1), T(0), T(0), T(0), static_cast<const T *>(nullptr), rc, rs);
    expect(n == 2 && abs(rc[0]) < T(1e-5) && abs(rc[1]) < T(1e-5) && abs(rs[0] + rs[1]) < T(1e-5), "trig2_roots");
    // g = cos 2 theta: four roots.
    expect(detail::trig2_roots(T(0), T(0), T(0), T(1), T(0), static_cast<const T *>(nullptr), rc, rs) == 4,
           "trig2_roots, four roots");
    expect(detail::trig2_roots(T(0), T(0), T(0), T(0), T(0), static_cast<const T *>(nullptr), rc, rs) == -1,
           "trig2_roots, g = 0");
    const T nan = std::numeric_limits<T>::quiet_NaN();
    expect(detail::trig2_roots(nan, T(0), T(0), T(0), T(0), static_cast<const T *>(nullptr), rc, rs) == -2,
           "trig2_roots, NaN");
    T c = T(0), s = T(0);
    // m = 1, b = (2, 0): the direction (1, 0).
    expect(detail::slide_direction(T(1), T(0), T(0), T(1), T(2), T(0), c, s) && abs(c - T(1)) < T(1e-5) &&
               abs(s) < T(1e-5),
           "slide_direction");
}
#endif

} // namespace

int main()
{
    expect(std::strcmp(to_string(impact_status::singular), "singular effective mass") == 0, "to_string(impact_status)");
    check_impact<float>();
    check_impact<double>();
    check_impact<long double>();
#ifdef RUNTIME_FRICTION
    expect(std::strcmp(to_string(friction_status::ambiguous), "ambiguous") == 0, "to_string(friction_status)");
    expect(std::strcmp(to_string(impact_regime::slide), "slide") == 0, "to_string(impact_regime)");
    expect(detail::friction_status_of(impact_status::overflow) == friction_status::overflow, "friction_status_of");
    check_friction<float>();
    check_friction<double>();
    check_friction<long double>();
#endif
#ifdef IMPACTGEN_TRIG2_STATS
    expect(detail::trig2_stats::max_iterations() <= std::numeric_limits<long double>::digits + 16, "trig2_stats");
#endif
    std::printf("%s: %s\n", GEN_HEADER, failures == 0 ? "ok" : "failed");
    return failures == 0 ? 0 : 1;
}
