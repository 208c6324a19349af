// Generated headers with NAME_jacobian (one, or every header of the family folded into
// one translation unit: header_checks.hpp), each instantiated for float, double
// and long double under -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Werror, both
// overloads (positional and NAME_input). Runs: inputs that make an impact give ok in
// every type with the plain function's values and finite derivatives that agree across
// the types; e = 2 gives invalid_restitution, all-zero derivatives and the state unchanged.
#include "header_checks.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <tuple>
#include <utility>

using namespace impactgen::generated;

// Beyond the common members (header_checks.hpp): the input struct, NAME_jacobian (both
// overloads) with its result, and the columns of the Jacobian.
#define IMPACTGEN_FAMILY_TRAITS(fn)                                                                                                \
    template <typename T> using input = ::impactgen::generated::fn##_input<T>;                                                     \
    template <typename T> using jacobian_result = ::impactgen::generated::fn##_jacobian_result<T>;                                 \
    template <typename... A> static decltype(auto) jacobian(A&&... a)                                                              \
    {                                                                                                                              \
        return ::impactgen::generated::fn##_jacobian(std::forward<A>(a)...);                                                       \
    }                                                                                                                              \
    static constexpr int wrt_count = ::impactgen::generated::fn##_wrt_count;                                                       \
    static constexpr auto& wrt_names = ::impactgen::generated::fn##_wrt_names;

// Inputs by name (as compile_one.cpp): masses, inertia (diagonal) and e in their valid
// ranges, off-diagonal inertia small, the rest in [-1, 1].
bool positive_quantity(const std::string& n) { return n[0] == 'm' || n[0] == 'I' || n.rfind("inv_", 0) == 0; }
bool off_diagonal(const std::string& n)
{
    if (!positive_quantity(n) || n.size() < 3)
        return false;
    const char a = n[n.size() - 2], b = n[n.size() - 1];
    return n[n.size() - 3] == '_' && a != b && std::isalpha(static_cast<unsigned char>(a)) &&
           std::isalpha(static_cast<unsigned char>(b));
}

template <typename T, std::size_t... I> auto as_tuple(const T* x, std::index_sequence<I...>) { return std::make_tuple(x[I]...); }

template <typename H, typename T> struct call_result {
    impact_status status = impact_status::ok, by_struct = impact_status::ok, plain = impact_status::ok;
    T value[H::output_count], plain_value[H::output_count], d[H::output_count][H::wrt_count];
    bool struct_same = true;
};

template <typename H, typename T> call_result<H, T> call(const double* x)
{
    constexpr int n_in = H::input_count, n_out = H::output_count, n_wrt = H::wrt_count;
    T in[n_in];
    for (int i = 0; i < n_in; ++i)
        in[i] = static_cast<T>(x[i]);
    const auto args = as_tuple(static_cast<const T*>(in), std::make_index_sequence<n_in>{});
    call_result<H, T> r;
    typename H::template jacobian_result<T> j, js;
    for (auto& row : j.d)
        for (T& v : row)
            v = T(7);
    r.status = std::apply([&](auto... v) { return H::jacobian(v..., j); }, args);
    const typename H::template input<T> named = std::apply([](auto... v) { return typename H::template input<T>{v...}; }, args);
    r.by_struct = H::jacobian(named, js);
    H::to_array(j.value, r.value);
    T other[n_out];
    H::to_array(js.value, other);
    for (int i = 0; i < n_out; ++i) {
        r.struct_same = r.struct_same && (other[i] == r.value[i] || (other[i] != other[i] && r.value[i] != r.value[i]));
        for (int k = 0; k < n_wrt; ++k) {
            r.d[i][k] = j.d[i][k];
            r.struct_same = r.struct_same && js.d[i][k] == j.d[i][k];
        }
    }
    typename H::template result<T> p;
    r.plain = H::call(static_cast<const T*>(in), p);
    H::to_array(p, r.plain_value);
    return r;
}

// The header of traits H (header_checks.hpp): 0 if it passes.
template <typename H> int check()
{
    constexpr int n_in = H::input_count, n_out = H::output_count, n_wrt = H::wrt_count;
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> unit(-1, 1), positive(0.5, 2), small(-0.1, 0.1), coefficient(0, 1);
    double x[n_in] = {};
    bool found = false;
    for (int attempt = 0; attempt < 100000 && !found; ++attempt) {
        for (int i = 0; i < n_in; ++i) {
            const std::string name = H::input_names[i];
            x[i] = name == "e" ? coefficient(rng) : off_diagonal(name) ? small(rng) : positive_quantity(name) ? positive(rng) : unit(rng);
        }
        found = call<H, double>(x).status == impact_status::ok;
    }
    if (!found) {
        std::printf("%s: no input found for which the header computes an impact\n", H::header);
        return 1;
    }
    const call_result<H, float> f = call<H, float>(x);
    const call_result<H, double> d = call<H, double>(x);
    const call_result<H, long double> l = call<H, long double>(x);
    std::printf("%s: jacobian status float %s, double %s, long double %s\n", H::header, to_string(f.status), to_string(d.status),
                to_string(l.status));
    if (f.status != impact_status::ok || d.status != impact_status::ok || l.status != impact_status::ok)
        return 1;
    if (f.by_struct != f.status || d.by_struct != d.status || l.by_struct != l.status || !f.struct_same || !d.struct_same ||
        !l.struct_same) {
        std::printf("the overload taking the input struct differs\n");
        return 1;
    }
    double vscale = 0, dscale = 0;
    for (int i = 0; i < n_out; ++i) {
        vscale = std::fmax(vscale, std::fabs(d.value[i]));
        for (int k = 0; k < n_wrt; ++k)
            dscale = std::fmax(dscale, std::fabs(d.d[i][k]));
    }
    for (int i = 0; i < n_out; ++i) {
        if (std::fabs(d.value[i] - d.plain_value[i]) > 1e-14 * vscale) {
            std::printf("output %s: jacobian's value %g, plain function %g\n", H::output_names[i], d.value[i], d.plain_value[i]);
            return 1;
        }
        for (int k = 0; k < n_wrt; ++k) {
            // float: 24 bits and a chain of a few hundred operations at most (1e-3 of the
            // largest entry); long double: within 1e-12 of double.
            const double df = double(f.d[i][k]), dd = d.d[i][k], dl = double(l.d[i][k]);
            if (!std::isfinite(dd) || std::fabs(df - dd) > 1e-3 * dscale || std::fabs(dl - dd) > 1e-12 * dscale) {
                std::printf("d %s / d %s: float %g, double %g, long double %g\n", H::output_names[i],
                            H::wrt_names[k], df, dd, dl);
                return 1;
            }
        }
    }
    // A failure: e = 2 (e is an input of every header tested here).
    for (int i = 0; i < n_in; ++i)
        if (std::string(H::input_names[i]) == "e")
            x[i] = 2;
    const call_result<H, double> bad = call<H, double>(x);
    if (bad.status != impact_status::invalid_restitution || bad.plain != bad.status) {
        std::printf("e = 2: status %s (plain function %s)\n", to_string(bad.status), to_string(bad.plain));
        return 1;
    }
    for (int i = 0; i < n_out; ++i) {
        if (bad.value[i] != bad.plain_value[i]) {
            std::printf("e = 2: output %s is not the state unchanged\n", H::output_names[i]);
            return 1;
        }
        for (int k = 0; k < n_wrt; ++k)
            if (bad.d[i][k] != 0) {
                std::printf("e = 2: d %s / d %s = %g, not 0\n", H::output_names[i], H::wrt_names[k],
                            double(bad.d[i][k]));
                return 1;
            }
    }
    return 0;
}

IMPACTGEN_CHECK_MAIN
