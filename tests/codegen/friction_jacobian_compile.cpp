// The headers with friction generated with --jacobian (folded into one translation unit by
// tests/codegen/CMakeLists.txt: IMPACTGEN_CHECKED_HEADERS(X) lists them), NAME_jacobian
// instantiated for float and double under the strict warnings of
// strict_flags.cmake, with each compiler: on one impact per header (every input 1/2, 1/3 or
// 1/4) each type returns a status, and jac is zero unless it is ok or ambiguous.
#include <cstdio>

using namespace impactgen::generated;

namespace
{

template <typename T, int n_in, int n_jac, typename R, typename F> int run(F jacobian, const char *path)
{
    T in[n_in];
    for (int i = 0; i < n_in; ++i)
        in[i] = T(1) / T(2 + i % 3);
    R out{};
    T jac[n_jac];
    const friction_status s = jacobian(static_cast<const T *>(in), out, jac);
    if (s == friction_status::ok || s == friction_status::ambiguous)
        return 0;
    for (int k = 0; k < n_jac; ++k)
        if (jac[k] != T(0)) {
            std::printf("%s: status %s with a nonzero jac\n", path, to_string(s));
            return 1;
        }
    return 0;
}

#define IMPACTGEN_RUN_TYPE(fn, path, T)                                                                                \
    run<T, fn##_input_count, fn##_jacobian_row_count * fn##_wrt_count, fn##_result<T>>(                                \
        [](const T *x, fn##_result<T> &o, T *j) { return fn##_jacobian(x, o, j); }, path)
#define IMPACTGEN_RUN(fn, path) failures += IMPACTGEN_RUN_TYPE(fn, path, float) + IMPACTGEN_RUN_TYPE(fn, path, double);

} // namespace

int main()
{
    int failures = 0;
    IMPACTGEN_CHECKED_HEADERS(IMPACTGEN_RUN)
    std::printf("friction Jacobian headers: %d failures\n", failures);
    return failures == 0 ? 0 : 1;
}
