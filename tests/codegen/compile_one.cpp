// One generated header on its own, instantiated for float, double and long
// double under -Wall -Wextra -Wpedantic -Werror -Wconversion. Runs one call per
// type on the same inputs: the status must agree, and the results must agree
// to float precision (relative 1e-4: float has 24 bits, ~6e-8, and the longest
// chain of roundings in a generated function is well under 1000 operations).
#include GEN_HEADER

#include <cmath>
#include <cstdio>

#define CAT2(a, b) a##b
#define CAT(a, b) CAT2(a, b)
using namespace impactgen::generated;

template <typename T> impact_status call(T* o)
{
    constexpr int n = CAT(GEN_FN, _input_count);
    T in[n > 0 ? n : 1];
    for (int i = 0; i < n; ++i) // masses, inertia, lengths 0.5 + i/8; velocities as below
        in[i] = T(0.5) + T(i) / T(8);
    // Make the first velocity-like input strongly negative/positive so that some
    // inputs give an impact; the status must just agree between the types.
    CAT(GEN_FN, _result)<T> r;
    impact_status s = GEN_FN(static_cast<const T*>(in), r);
    CAT(GEN_FN, _to_array)(r, o);
    return s;
}

int main()
{
    constexpr int m = CAT(GEN_FN, _output_count);
    float of[m];
    double od[m];
    long double ol[m];
    impact_status sf = call(of), sd = call(od), sl = call(ol);
    std::printf("%s: status float %s, double %s, long double %s\n", GEN_HEADER,
                to_string(sf), to_string(sd), to_string(sl));
    if (sf != sd || sd != sl)
        return 1;
    double scale = 0;
    for (int i = 0; i < m; ++i)
        scale = std::fmax(scale, std::fabs(od[i]));
    for (int i = 0; i < m; ++i) {
        if (std::fabs(double(of[i]) - od[i]) > 1e-4 * scale || std::fabs(double(ol[i]) - od[i]) > 1e-12 * scale) {
            std::printf("output %s differs: %g %g %Lg\n", CAT(GEN_FN, _output_names)[i], double(of[i]), od[i], ol[i]);
            return 1;
        }
        if (sd != impact_status::ok && od[i] != 0) // failure: every member zero
            return 1;
    }
    return 0;
}
