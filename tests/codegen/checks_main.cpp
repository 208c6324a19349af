// The validity checks of generated headers, called with inputs that must fail
// them and inputs that must pass, for float, double and long double, under
// g++ and clang++ with strict warnings (tests/codegen/CMakeLists.txt):
//  - inertia: positive definiteness by leading principal minors (a tensor with a
//    positive determinant that is not positive definite is invalid_inertia), block
//    by block, also of the inverse tensor in the engine convention (--inverse-inertia);
//  - a diagonal tensor without I^3 intermediates: float computes I = 4e-15 and 1e13;
//  - the normal: zero, denormal and overflowing n.n are invalid_normal; with
//    --unit-normal the normal is not normalised, a normal of length 2 is
//    invalid_normal, a normal normalised in float passes in every type, and the
//    results agree with the plain header's.
// Every call goes through the fast path (the one flag), which defers to the checked
// path for the status, and through the batch form, which must agree bit for bit.
#include "checks_block.hpp"
#include "checks_block_engine.hpp"
#include "checks_diag.hpp"
#include "checks_diag_engine.hpp"
#include "checks_diag_unit.hpp"
#include "checks_full.hpp"
#include "checks_full_engine.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace impactgen::generated;

namespace {

int failures = 0;

void expect(bool ok, const std::string& what)
{
    if (!ok) {
        std::printf("FAILED: %s\n", what.c_str());
        ++failures;
    }
}

template <typename T> const char* type_name()
{
    return sizeof(T) == sizeof(float) ? "float" : sizeof(T) == sizeof(double) ? "double" : "long double";
}

using values = std::map<std::string, long double>;

template <typename T> bool same(T a, T b) { return a == b || (a != a && b != b); }

// One call by input names: the fast path (array form), then the batch form on the
// same inputs, which must give the same status and the same outputs.
template <typename T, int NI, int NO, typename Fast, typename Batch>
impact_status call(const char* what, const char* const* names, const values& v, std::vector<T>& out, Fast fast, Batch batch)
{
    T in[NI];
    for (int j = 0; j < NI; ++j) {
        auto it = v.find(names[j]);
        if (it == v.end()) {
            expect(false, std::string(what) + ": no value for input " + names[j]);
            return impact_status::ok;
        }
        in[j] = static_cast<T>(it->second);
    }
    out.assign(NO, T(0));
    const impact_status s = fast(in, out.data());
    // The batch form, one impact.
    T bin[NI], bout[NO];
    const T* ip[NI];
    T* op[NO];
    for (int j = 0; j < NI; ++j) {
        bin[j] = in[j];
        ip[j] = &bin[j];
    }
    for (int j = 0; j < NO; ++j)
        op[j] = &bout[j];
    impact_status bs = impact_status::ok;
    batch(1L, ip, op, &bs);
    expect(bs == s, std::string(what) + " (" + type_name<T>() + "): the batch form gives " + to_string(bs) + ", the function " +
                        to_string(s));
    for (int j = 0; j < NO; ++j)
        expect(same(bout[j], out[static_cast<std::size_t>(j)]),
               std::string(what) + " (" + type_name<T>() + "): batch output " + std::to_string(j) + " differs");
    return s;
}

} // namespace

// The function (array form) writing its outputs into an array, and the batch form.
#define CALL(FN, T, WHAT, V, OUT)                                                                                     \
    call<T, FN##_input_count, FN##_output_count>(                                                                     \
        WHAT, FN##_input_names, V, OUT,                                                                               \
        [](const T* in, T* o) {                                                                                       \
            FN##_result<T> r;                                                                                         \
            impact_status st = FN(in, r);                                                                             \
            FN##_to_array(r, o);                                                                                      \
            return st;                                                                                                \
        },                                                                                                            \
        [](long count, const T* const* in, T* const* o, impact_status* st) { FN##_batch(count, in, o, st); })

namespace {

// |a - b| within tol of the larger of the state's scales.
template <typename T> bool close(const std::vector<T>& a, const std::vector<T>& b, long double tol, long double scale_floor = 1)
{
    long double scale = scale_floor, err = 0;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
        scale = std::fmax(scale, std::fabs(static_cast<long double>(a[i])));
        scale = std::fmax(scale, std::fabs(static_cast<long double>(b[i])));
        err = std::fmax(err, std::fabs(static_cast<long double>(a[i]) - static_cast<long double>(b[i])));
    }
    return a.size() == b.size() && err <= tol * scale;
}

template <typename T> bool all_finite(const std::vector<T>& a)
{
    for (T x : a)
        if (!(x - x == T(0)))
            return false;
    return true;
}

// The box's state before impact: approaching the wall (or ball) along n.
values box_state(long double nx, long double ny, long double nz)
{
    return {{"e", 0.5L}, {"m", 2.0L}, {"vx", 2 * nx + 0.1L}, {"vy", 2 * ny - 0.2L}, {"vz", 2 * nz},
            {"wx", 0.3L}, {"wy", -0.1L}, {"wz", 0.2L}, {"nx", nx}, {"ny", ny}, {"nz", nz}};
}

// A full tensor (and its inverse, in long double) into the values by name.
void set_tensor(values& v, const long double I[3][3], const char* prefix = "I")
{
    const char* ax = "xyz";
    for (int r = 0; r < 3; ++r)
        for (int c = r; c < 3; ++c)
            v[std::string(prefix) + ax[r] + ax[c]] = I[r][c];
}

void inverse(const long double I[3][3], long double K[3][3])
{
    long double adj[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            adj[i][j] = I[r0][c0] * I[r1][c1] - I[r0][c1] * I[r1][c0];
        }
    const long double det = I[0][0] * adj[0][0] + I[0][1] * adj[1][0] + I[0][2] * adj[2][0];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            K[i][j] = adj[i][j] / det;
}

template <typename T> long double tolerance()
{
    return 1000 * static_cast<long double>(std::numeric_limits<T>::epsilon());
}

template <typename T> void inertia_checks()
{
    std::vector<T> a, b;
    // The tensor: Ixx = Iyy = -1, Izz = 1 has determinant 1 > 0.
    const long double bad_diag[3][3] = {{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}};
    // Ixx > 0 and determinant 1 + 1/100 > 0, but the minor Ixx Iyy - Ixy^2 < 0.
    const long double bad_minor[3][3] = {{1, 0.1L, 0}, {0.1L, -1, 0}, {0, 0, -1}};
    const long double good[3][3] = {{2, 0.3L, -0.2L}, {0.3L, 1.5L, 0.1L}, {-0.2L, 0.1L, 1}};
    for (const auto* I : {bad_diag, bad_minor}) {
        values v = box_state(1, 2, 2);
        set_tensor(v, I);
        expect(CALL(checks_full, T, "full tensor, not positive definite", v, a) == impact_status::invalid_inertia,
               std::string("full tensor not positive definite (determinant > 0): invalid_inertia, ") + type_name<T>());
        values k = box_state(1, 2, 2);
        set_tensor(k, I, "inv_I");
        expect(CALL(checks_full_engine, T, "inverse tensor, not positive definite", k, a) == impact_status::invalid_inertia,
               std::string("inverse tensor not positive definite (determinant > 0): invalid_inertia, ") + type_name<T>());
    }
    {
        values v = box_state(1, 2, 2);
        v["Ixx"] = v["Iyy"] = -1;
        v["Izz"] = 1;
        expect(CALL(checks_diag, T, "diagonal -1, -1, 1", v, a) == impact_status::invalid_inertia,
               std::string("diagonal tensor -1, -1, 1: invalid_inertia, ") + type_name<T>());
        v["inv_Ixx"] = v["inv_Iyy"] = -1;
        v["inv_Izz"] = 1;
        expect(CALL(checks_diag_engine, T, "inverse diagonal -1, -1, 1", v, a) == impact_status::invalid_inertia,
               std::string("inverse diagonal tensor -1, -1, 1: invalid_inertia, ") + type_name<T>());
    }
    {
        // Positive definite: ok, and the engine convention (I^{-1} as inputs) agrees.
        values v = box_state(1, 2, 2), k = v;
        long double K[3][3];
        inverse(good, K);
        set_tensor(v, good);
        set_tensor(k, K, "inv_I");
        const impact_status sa = CALL(checks_full, T, "full tensor, positive definite", v, a);
        const impact_status sb = CALL(checks_full_engine, T, "inverse tensor, positive definite", k, b);
        expect(sa == impact_status::ok && sb == impact_status::ok,
               std::string("positive definite tensor: ok in both conventions, ") + type_name<T>() + ": " + to_string(sa) + ", " +
                   to_string(sb));
        expect(close(a, b, tolerance<T>()), std::string("positive definite tensor: the engine convention agrees, ") + type_name<T>());
    }
    {
        // Blocks: xy coupled, z apart. A block whose minor is negative; then a valid one
        // in both conventions.
        values v = box_state(1, 2, 2), k = v;
        v["Ixx"] = 1, v["Ixy"] = 2, v["Iyy"] = 1, v["Izz"] = 1;
        k["inv_Ixx"] = 1, k["inv_Ixy"] = 2, k["inv_Iyy"] = 1, k["inv_Izz"] = 1;
        expect(CALL(checks_block, T, "block, minor < 0", v, a) == impact_status::invalid_inertia,
               std::string("block tensor with a negative minor: invalid_inertia, ") + type_name<T>());
        expect(CALL(checks_block_engine, T, "inverse block, minor < 0", k, a) == impact_status::invalid_inertia,
               std::string("inverse block tensor with a negative minor: invalid_inertia, ") + type_name<T>());
        const long double I[3][3] = {{2, 0.5L, 0}, {0.5L, 1, 0}, {0, 0, 0.7L}};
        long double Ki[3][3];
        inverse(I, Ki);
        set_tensor(v, I);
        set_tensor(k, Ki, "inv_I");
        const impact_status sa = CALL(checks_block, T, "block, positive definite", v, a);
        const impact_status sb = CALL(checks_block_engine, T, "inverse block, positive definite", k, b);
        expect(sa == impact_status::ok && sb == impact_status::ok,
               std::string("block tensor positive definite: ok in both conventions, ") + type_name<T>());
        expect(close(a, b, tolerance<T>()), std::string("block tensor: the engine convention agrees, ") + type_name<T>());
    }
}

// A diagonal tensor is inverted entry by entry: no I^3, so float holds the scales an
// engine uses (a speck of 4e-15, a ship of 1e13).
template <typename T> void diagonal_scales()
{
    for (long double I : {4e-15L, 1e13L, 1.0L}) {
        std::vector<T> a, b;
        std::vector<long double> ref;
        values v = box_state(1, 2, 2);
        v["Ixx"] = I, v["Iyy"] = 2 * I, v["Izz"] = 3 * I;
        v["inv_Ixx"] = 1 / I, v["inv_Iyy"] = 1 / (2 * I), v["inv_Izz"] = 1 / (3 * I);
        const std::string what = std::string("diagonal inertia ") + std::to_string(static_cast<double>(I)) + " in " + type_name<T>();
        const impact_status s = CALL(checks_diag, T, what.c_str(), v, a);
        expect(s == impact_status::ok, what + ": ok, got " + to_string(s));
        expect(all_finite(a), what + ": finite results");
        const impact_status sl = CALL(checks_diag, long double, what.c_str(), v, ref);
        expect(sl == impact_status::ok, what + ": ok in long double");
        expect(close(a, std::vector<T>(ref.begin(), ref.end()), 1e-4L), what + ": agrees with long double to float precision");
        const impact_status se = CALL(checks_diag_engine, T, what.c_str(), v, b);
        expect(se == impact_status::ok && all_finite(b), what + ": ok and finite in the engine convention");
        expect(close(a, b, 1e-4L), what + ": the engine convention agrees");
    }
}

template <typename T> void normal_checks()
{
    std::vector<T> a, b;
    const long double tiny = static_cast<long double>(std::numeric_limits<T>::min());
    const long double denorm = static_cast<long double>(std::numeric_limits<T>::denorm_min());
    const long double huge = static_cast<long double>(std::numeric_limits<T>::max());
    auto diag = [](values v) {
        v["Ixx"] = 1, v["Iyy"] = 2, v["Izz"] = 3;
        return v;
    };
    struct bad_normal {
        const char* what;
        long double x;
    };
    for (const bad_normal& c : {bad_normal{"zero normal", 0}, bad_normal{"denormal normal", 4 * denorm},
                                bad_normal{"normal whose n.n is denormal", std::sqrt(tiny) / 4},
                                bad_normal{"normal whose n.n overflows", std::sqrt(huge) * 2}}) {
        values v = diag(box_state(c.x, 0, 0));
        v["vx"] = 1; // approaching along x whatever the length
        const impact_status s = CALL(checks_diag, T, c.what, v, a);
        expect(s == impact_status::invalid_normal, std::string(c.what) + " (" + type_name<T>() + "): invalid_normal, got " + to_string(s));
        const impact_status su = CALL(checks_diag_unit, T, c.what, v, a);
        expect(su == impact_status::invalid_normal,
               std::string(c.what) + " (" + type_name<T>() + ", --unit-normal): invalid_normal, got " + to_string(su));
    }
    // --unit-normal: a normal of length 2 is refused; the plain header takes it.
    {
        values v = diag(box_state(2.0L / 3 * 2, 2.0L / 3 * 1, 2.0L / 3 * -2));
        expect(CALL(checks_diag_unit, T, "normal of length 2", v, a) == impact_status::invalid_normal,
               std::string("--unit-normal, a normal of length 2: invalid_normal, ") + type_name<T>());
        expect(CALL(checks_diag, T, "normal of length 2, plain header", v, a) == impact_status::ok,
               std::string("plain header, a normal of length 2: ok, ") + type_name<T>());
    }
    // Unit normals: the same results as the plain header, which normalises again.
    std::mt19937_64 rng(20240611);
    std::normal_distribution<double> g(0, 1);
    int compared = 0;
    for (int k = 0; k < 200; ++k) {
        long double n[3] = {static_cast<long double>(g(rng)), static_cast<long double>(g(rng)), static_cast<long double>(g(rng))};
        const long double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (long double& x : n)
            x /= len;
        values v = diag(box_state(n[0], n[1], n[2]));
        const impact_status sp = CALL(checks_diag, T, "unit normal, plain header", v, a);
        const impact_status su = CALL(checks_diag_unit, T, "unit normal, --unit-normal", v, b);
        expect(sp == su, std::string("unit normal: the same status with and without --unit-normal, ") + type_name<T>() + ": " +
                             to_string(sp) + ", " + to_string(su));
        if (sp == impact_status::ok && su == impact_status::ok) {
            ++compared;
            expect(close(a, b, tolerance<T>()), std::string("unit normal: the same results with and without --unit-normal, ") +
                                                    type_name<T>() + ", normal " + std::to_string(k));
        }
        // Normalised in float, as an engine storing float normals would: accepted in every type.
        float f[3] = {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])};
        const float flen = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        for (float& x : f)
            x /= flen;
        values vf = diag(box_state(static_cast<long double>(f[0]), static_cast<long double>(f[1]), static_cast<long double>(f[2])));
        const impact_status sf = CALL(checks_diag_unit, T, "normal normalised in float, --unit-normal", vf, b);
        expect(sf == impact_status::ok || sf == impact_status::not_approaching,
               std::string("a normal normalised in float passes the unit check in ") + type_name<T>() + ": " + to_string(sf));
    }
    expect(compared > 150, std::string("unit normals: enough impacts compared, ") + type_name<T>());
}

} // namespace

int main()
{
    inertia_checks<float>();
    inertia_checks<double>();
    inertia_checks<long double>();
    diagonal_scales<float>();
    diagonal_scales<double>();
    diagonal_scales<long double>();
    normal_checks<float>();
    normal_checks<double>();
    normal_checks<long double>();
    std::printf("generated-header checks: %d failure(s)\n", failures);
    return failures == 0 ? 0 : 1;
}
