// Generated system headers (every header of the family folded into one translation unit:
// header_checks.hpp), each instantiated for float, double and long double under the strict
// warnings (check_compile.cmake): one impact per type on the same inputs (the file's numbers,
// or a seeded search among inputs with positive masses for one that is solved), status ok and
// the same candidate set for every type, results agreeing to float precision; the batch form
// gives the same as the array form; a NaN input is refused as non_finite_input.
#include "header_checks.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <utility>

using namespace impactgen::generated;

#define IMPACTGEN_FAMILY_TRAITS(fn)                                                                                    \
    template <typename... A> static void batch(A &&...a)                                                               \
    {                                                                                                                  \
        ::impactgen::generated::fn##_batch(std::forward<A>(a)...);                                                     \
    }

template <typename H, typename T> friction_status call(const double *x, T *o, int &set)
{
    constexpr int n_in = H::input_count;
    T in[n_in > 0 ? n_in : 1] = {};
    for (int i = 0; i < n_in; ++i)
        in[i] = static_cast<T>(x[i]);
    typename H::template result<T> r;
    const friction_status s = H::call(static_cast<const T *>(in), r);
    H::to_array(r, o);
    set = r.set;
    return s;
}

template <typename H> int check()
{
    constexpr int n_in = H::input_count;
    constexpr int n_out = H::output_count;
    std::mt19937_64 rng(4243);
    std::uniform_real_distribution<double> unit(-1, 1), positive(0.5, 2), coefficient(0, 1);
    double x[n_in > 0 ? n_in : 1] = {};
    double od[n_out];
    int sd = -1;
    bool found = false;
    for (int attempt = 0; attempt < 1000 && !found; ++attempt) {
        for (int i = 0; i < n_in; ++i) {
            const std::string name = H::input_names[i];
            x[i] = name[0] == 'e' || name.rfind("mu", 0) == 0 ? coefficient(rng)
                   : name[0] == 'm' || name[0] == 'I'         ? positive(rng)
                                                              : unit(rng);
        }
        found = call<H, double>(x, od, sd) == friction_status::ok;
    }
    if (!found) {
        std::printf("%s: no input found that is solved\n", H::header);
        return 1;
    }
    float of[n_out];
    long double ol[n_out];
    int sf = -1, sl = -1;
    if (call<H, float>(x, of, sf) != friction_status::ok || call<H, long double>(x, ol, sl) != friction_status::ok ||
        sf != sd || sl != sd) {
        std::printf("%s: float or long double disagree on the status or the set\n", H::header);
        return 1;
    }
    double scale = 1;
    for (int j = 0; j < n_out; ++j)
        scale = std::fmax(scale, std::fabs(od[j]));
    for (int j = 0; j < n_out; ++j)
        if (std::fabs(static_cast<double>(of[j]) - od[j]) > 1e-3 * scale ||
            std::fabs(static_cast<double>(ol[j]) - od[j]) > 1e-9 * scale) {
            std::printf("%s: output %s differs between the scalar types\n", H::header, H::output_names[j]);
            return 1;
        }
    // The batch form: two impacts, the same as the array form.
    double columns[n_in > 0 ? n_in : 1][2];
    const double *in[n_in > 0 ? n_in : 1];
    for (int i = 0; i < n_in; ++i) {
        columns[i][0] = columns[i][1] = x[i];
        in[i] = columns[i];
    }
    double outs[n_out][2];
    double *out[n_out];
    for (int j = 0; j < n_out; ++j)
        out[j] = outs[j];
    friction_status status[2];
    int sets[2];
    H::batch(2L, static_cast<const double *const *>(in), static_cast<double *const *>(out), status, sets);
    for (int k = 0; k < 2; ++k) {
        if (status[k] != friction_status::ok || sets[k] != sd)
            return std::printf("%s: the batch form disagrees\n", H::header), 1;
        for (int j = 0; j < n_out; ++j)
            if (outs[j][k] != od[j])
                return std::printf("%s: the batch form's %s disagrees\n", H::header, H::output_names[j]), 1;
    }
    if (n_in > 0) {
        x[0] = std::nan("");
        if (call<H, double>(x, od, sd) != friction_status::non_finite_input || sd != -1)
            return std::printf("%s: a NaN input is not refused\n", H::header), 1;
    }
    return 0;
}

IMPACTGEN_CHECK_MAIN
