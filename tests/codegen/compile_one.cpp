// Generated headers (one, or every header of the family folded into one translation
// unit: header_checks.hpp), each instantiated for float, double and long double under
// -Wall -Wextra -Wpedantic -Werror -Wconversion. Runs one call per type on the same
// inputs, chosen so that they make an impact: the status must be ok for every type,
// and the results must agree to float precision (relative 1e-4: float has 24 bits,
// ~6e-8, and the longest chain of roundings in a generated function is well under
// 1000 operations).
#include "header_checks.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace impactgen::generated;

// No members beyond the common ones (header_checks.hpp).
#define IMPACTGEN_FAMILY_TRAITS(fn)

// Inputs by name: masses, inertia (diagonal) and e in their valid ranges,
// off-diagonal inertia small, the rest (positions, velocities, spins) in [-1, 1].
bool positive_quantity(const std::string& n)
{
    return n[0] == 'm' || n[0] == 'I' || n.rfind("inv_", 0) == 0;
}
bool off_diagonal(const std::string& n)
{
    if (!positive_quantity(n) || n.size() < 3)
        return false;
    const char a = n[n.size() - 2], b = n[n.size() - 1];
    return n[n.size() - 3] == '_' && a != b && std::isalpha(static_cast<unsigned char>(a)) &&
           std::isalpha(static_cast<unsigned char>(b));
}

template <typename H, typename T> impact_status call(const double* x, T* o)
{
    constexpr int n = H::input_count;
    T in[n > 0 ? n : 1];
    for (int i = 0; i < n; ++i)
        in[i] = static_cast<T>(x[i]);
    typename H::template result<T> r;
    impact_status s = H::call(static_cast<const T*>(in), r);
    H::to_array(r, o);
    return s;
}

// The header of traits H (header_checks.hpp): 0 if it passes.
template <typename H> int check()
{
    constexpr int n = H::input_count;
    constexpr int m = H::output_count;
    float of[m];
    double od[m];
    long double ol[m];
    // Seeded search for inputs that make an impact (status ok in double): the
    // comparison below is between real results, never between zeros.
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> unit(-1, 1), positive(0.5, 2), small(-0.1, 0.1), coefficient(0, 1);
    double x[n > 0 ? n : 1] = {};
    bool found = false;
    for (int attempt = 0; attempt < 100000 && !found; ++attempt) {
        for (int i = 0; i < n; ++i) {
            const std::string name = H::input_names[i];
            x[i] = name == "e" ? coefficient(rng) : off_diagonal(name) ? small(rng) : positive_quantity(name) ? positive(rng) : unit(rng);
        }
        found = call<H>(x, od) == impact_status::ok;
    }
    if (!found) {
        std::printf("%s: no input found for which the header computes an impact\n", H::header);
        return 1;
    }
    impact_status sf = call<H>(x, of), sd = call<H>(x, od), sl = call<H>(x, ol);
    std::printf("%s: status float %s, double %s, long double %s\n", H::header, to_string(sf), to_string(sd), to_string(sl));
    if (sf != impact_status::ok || sd != impact_status::ok || sl != impact_status::ok)
        return 1;
    double scale = 0;
    for (int i = 0; i < m; ++i)
        scale = std::fmax(scale, std::fabs(od[i]));
    for (int i = 0; i < m; ++i) {
        if (std::fabs(double(of[i]) - od[i]) > 1e-4 * scale || std::fabs(double(ol[i]) - od[i]) > 1e-12 * scale) {
            std::printf("output %s differs: %g %g %Lg\n", H::output_names[i], double(of[i]), od[i], ol[i]);
            return 1;
        }
    }
    return 0;
}

IMPACTGEN_CHECK_MAIN
