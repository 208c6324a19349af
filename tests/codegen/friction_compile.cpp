// Generated headers with friction (one, or every header of the family folded into one
// translation unit: header_checks.hpp), each instantiated for float, double and
// long double under -Wall -Wextra -Wpedantic -Werror -Wconversion -Wshadow (and
// -Wdouble-promotion): one impact per type on the same inputs (a seeded search for
// inputs that make an impact that sticks or slides clearly), statuses ok and the same
// regime for every type, results agreeing to float precision; the struct and array
// forms and the batch form give the same; a bad input is refused.
#include "header_checks.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace impactgen::generated;

// Beyond the common members (header_checks.hpp): the input struct and the batch form.
#define IMPACTGEN_FAMILY_TRAITS(fn)                                                                                                \
    template <typename T> using input = ::impactgen::generated::fn##_input<T>;                                                     \
    template <typename... A> static void batch(A&&... a)                                                                           \
    {                                                                                                                              \
        ::impactgen::generated::fn##_batch(std::forward<A>(a)...);                                                                 \
    }

bool positive_quantity(const std::string& n) { return n[0] == 'm' || n[0] == 'I' || n == "R"; }
bool off_diagonal(const std::string& n)
{
    if (n[0] != 'I' || n.size() < 3)
        return false;
    const char a = n[n.size() - 2], b = n[n.size() - 1];
    return n[n.size() - 3] == '_' && a != b;
}

template <typename H, typename T> friction_status call(const double* x, T* o, impact_regime& regime)
{
    constexpr int n_in = H::input_count;
    T in[n_in > 0 ? n_in : 1];
    for (int i = 0; i < n_in; ++i)
        in[i] = static_cast<T>(x[i]);
    typename H::template result<T> r;
    const friction_status s = H::call(static_cast<const T*>(in), r);
    H::to_array(r, o);
    regime = r.regime;
    return s;
}

// The header of traits H (header_checks.hpp): 0 if it passes.
template <typename H> int check()
{
    constexpr int n_in = H::input_count;
    constexpr int n_out = H::output_count;
    std::mt19937_64 rng(4242);
    std::uniform_real_distribution<double> unit(-1, 1), positive(0.5, 2), small(-0.05, 0.05), coefficient(0, 1);
    double x[n_in > 0 ? n_in : 1] = {};
    double od[n_out];
    impact_regime rd = impact_regime::smooth;
    bool found = false;
    for (int attempt = 0; attempt < 100000 && !found; ++attempt) {
        for (int i = 0; i < n_in; ++i) {
            const std::string name = H::input_names[i];
            x[i] = name == "e" ? coefficient(rng) : name == "mu" ? 0.1 + coefficient(rng) : off_diagonal(name) ? small(rng)
                   : positive_quantity(name) ? positive(rng) : unit(rng);
        }
        found = call<H>(x, od, rd) == friction_status::ok;
        // clear of the stick/slide boundary: the same regime with mu 1% either side
        for (int i = 0; i < n_in && found; ++i)
            if (std::string(H::input_names[i]) == "mu")
                for (double f : {0.99, 1.01}) {
                    double y[n_in > 0 ? n_in : 1], oy[n_out];
                    for (int k = 0; k < n_in; ++k)
                        y[k] = x[k];
                    y[i] *= f;
                    impact_regime ry;
                    found = found && call<H>(y, oy, ry) == friction_status::ok && ry == rd;
                }
    }
    if (!found) {
        std::printf("%s: no input found for which the header computes an impact\n", H::header);
        return 1;
    }
    float of[n_out];
    long double ol[n_out];
    impact_regime rf, rl;
    const friction_status sf = call<H>(x, of, rf), sd = call<H>(x, od, rd), sl = call<H>(x, ol, rl);
    std::printf("%s: status float %s, double %s, long double %s; regime %s\n", H::header, to_string(sf), to_string(sd), to_string(sl),
                to_string(rd));
    if (sf != friction_status::ok || sd != friction_status::ok || sl != friction_status::ok || rf != rd || rl != rd)
        return 1;
    double scale = 0;
    for (int i = 0; i < n_out; ++i)
        scale = std::fmax(scale, std::fabs(od[i]));
    for (int i = 0; i < n_out; ++i)
        if (std::fabs(double(of[i]) - od[i]) > 1e-3 * scale || std::fabs(double(ol[i]) - od[i]) > 1e-12 * scale) {
            std::printf("output %s differs: %g %g %Lg\n", H::output_names[i], double(of[i]), od[i], ol[i]);
            return 1;
        }
    // The struct form and the batch form.
    typename H::template input<double> by_name{};
    double* fields = reinterpret_cast<double*>(&by_name);
    for (int i = 0; i < n_in; ++i)
        fields[i] = x[i];
    typename H::template result<double> r;
    if (H::call(by_name, r) != friction_status::ok || r.regime != rd)
        return 1;
    double col_in[n_in > 0 ? n_in : 1][2], col_out[n_out][2];
    const double* in_ptr[n_in > 0 ? n_in : 1];
    double* out_ptr[n_out];
    for (int i = 0; i < n_in; ++i) {
        col_in[i][0] = col_in[i][1] = x[i];
        in_ptr[i] = col_in[i];
    }
    for (int j = 0; j < n_out; ++j)
        out_ptr[j] = col_out[j];
    friction_status st[2];
    impact_regime rg[2];
    H::batch(2L, in_ptr, out_ptr, st, rg);
    for (int j = 0; j < n_out; ++j)
        if (col_out[j][1] != od[j] || st[1] != friction_status::ok || rg[1] != rd) {
            std::printf("batch output %s differs\n", H::output_names[j]);
            return 1;
        }
    // mu < 0 is refused, and the state is left unchanged.
    for (int i = 0; i < n_in; ++i)
        if (std::string(H::input_names[i]) == "mu") {
            x[i] = -1;
            if (call<H>(x, od, rd) != friction_status::invalid_friction || rd != impact_regime::smooth)
                return 1;
        }
    return 0;
}

IMPACTGEN_CHECK_MAIN
