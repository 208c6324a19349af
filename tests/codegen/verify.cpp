// The compiled generated functions against two independent references, on
// seeded random inputs (IMPACTGEN_SEED, IMPACTGEN_SAMPLES override the seed and
// the count per case, default 20,000; IMPACTGEN_EXACT_SAMPLES the exact subset,
// default 2,000; IMPACTGEN_DEEP=1 makes the defaults 100,000 and 10,000):
//  - the closed form: impactgen::solve of the same (specialised) problem in the
//    tensor convention, its steps evaluated by CLN at the very inputs the double
//    function received: in exact rationals on the exact subset, in 40-digit CLN
//    floats on every other sample;
//  - the Eigen solve of the momentum system (numeric/momentum_solver.hpp).
// Inputs: masses log-uniform in [1e-3, 1e3] (mass ratios 1e-6 ... 1e6), inertia
// tensors m * R diag(0.2..1) R^T, velocities in [-1, 1], one sample in eight
// near-grazing ((v_B - v_A).n between -1e-12 and -1e-4).
#include <tuple>
#include <utility>
#include <algorithm>
#include "codegen/codegen.hpp"
#include "numeric/momentum_solver.hpp"
#include "symbolic/named_classes.hpp"

#include "central_direct.hpp"
#include "central_oblique.hpp"
#include "hinged_rod.hpp"
#include "massive_3d.hpp"
#include "noncentral_3d.hpp"
#include "noncentral_3d_engine.hpp"
#include "planar_engine.hpp"
#include "pinned_3d.hpp"
#include "pinned_planar.hpp"
#include "pinned_planar_set.hpp"
#include "planar.hpp"
#include "puck_block_34.hpp"
#include "puck_block_34_const.hpp"
#include "spinning_spheres.hpp"
#include "wall_oblique_3d.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <random>

using namespace GiNaC;
namespace codegen = impactgen::codegen;
namespace nm = impactgen::numeric;
using impactgen::body;
using impactgen::find_named_class;
using impactgen::load_problem_file;
using impactgen::named_class;
using impactgen::pivot;
using impactgen::problem;
using impactgen::solution;

namespace gen = impactgen::generated;

namespace {

long env_or(const char* name, long fallback)
{
    const char* v = std::getenv(name);
    return v && *v ? std::strtol(v, nullptr, 10) : fallback;
}

struct case_def {
    std::string source; ///< named class or file under examples/problems
    codegen::options opt;
    int n_in, n_out;
    const char* const* in_names;
    const char* const* out_names;
    std::function<int(const double*, double*)> fd;
    std::function<int(const long double*, long double*)> fld;
};

#define GEN_FUNCS(FN)                                                                                                 \
    gen::FN##_input_count, gen::FN##_output_count, gen::FN##_input_names, gen::FN##_output_names,                     \
        [](const double* in, double* o) {                                                                             \
            gen::FN##_result<double> r;                                                                               \
            int s = int(gen::FN(in, r));                                                                              \
            gen::FN##_to_array(r, o);                                                                                 \
            return s;                                                                                                 \
        },                                                                                                            \
        [](const long double* in, long double* o) {                                                                   \
            gen::FN##_result<long double> r;                                                                          \
            int s = int(gen::FN(in, r));                                                                              \
            gen::FN##_to_array(r, o);                                                                                 \
            return s;                                                                                                 \
        }

codegen::options opts(std::string params = "", std::string set = "", bool inv = false)
{
    codegen::options o;
    o.params_given = !params.empty();
    std::stringstream ps(params), ss(set);
    std::string item;
    while (std::getline(ps, item, ','))
        o.params.push_back(item);
    while (std::getline(ss, item, ',')) {
        auto eq = item.find('=');
        o.set.push_back({item.substr(0, eq), item.substr(eq + 1)});
    }
    o.inverse_inertia = o.inverse_mass = inv;
    return o;
}

problem load(const std::string& source)
{
    if (const named_class* c = find_named_class(source))
        return c->build();
    return load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/" + source);
}

numeric exact(double x)
{
    int e = 0;
    double m = std::frexp(x, &e); // x = m 2^e, |m| in [0.5, 1)
    long long mant = static_cast<long long>(std::ldexp(m, 53));
    return numeric(mant) * pow(numeric(2), numeric(e - 53));
}

// Evaluation of a GiNaC tree with the given symbol values (no substitution, no
// expression building): exact for numeric, rounded for double.
template <typename T> struct evaluator {
    std::map<ex, T, ex_is_less> values;
    bool exact_only = true; ///< numeric: refuse anything but rationals (false: CLN floats allowed)
    T operator()(const ex& e) const
    {
        if (is_a<numeric>(e)) {
            if constexpr (std::is_same_v<T, numeric>)
                return ex_to<numeric>(e);
            else {
                const numeric& x = ex_to<numeric>(e);
                return T(x.numer().to_double()) / T(x.denom().to_double());
            }
        }
        if (is_a<symbol>(e)) {
            auto it = values.find(e);
            if (it == values.end())
                throw std::runtime_error("no value for " + ex_to<symbol>(e).get_name());
            return it->second;
        }
        if (is_a<add>(e)) {
            T s = (*this)(e.op(0));
            for (std::size_t i = 1; i < e.nops(); ++i)
                s = s + (*this)(e.op(i));
            return s;
        }
        if (is_a<mul>(e)) {
            T s = (*this)(e.op(0));
            for (std::size_t i = 1; i < e.nops(); ++i)
                s = s * (*this)(e.op(i));
            return s;
        }
        if (is_a<power>(e)) {
            T b = (*this)(e.op(0));
            const numeric& x = ex_to<numeric>(e.op(1));
            if (x.is_integer()) {
                int k = x.to_int();
                T r = T(1);
                for (int i = 0; i < std::abs(k); ++i)
                    r = r * b;
                return k < 0 ? T(1) / r : r;
            }
            if constexpr (std::is_same_v<T, numeric>) {
                numeric r = GiNaC::pow(b, x);  // exact when b is a perfect square (all normals here)
                if (exact_only && !r.is_rational())
                    throw std::runtime_error("irrational power in the exact reference");
                return r;
            } else {
                return std::pow(b, T(x.to_double()));
            }
        }
        throw std::runtime_error("cannot evaluate");
    }
};

struct stats {
    double gen_exact = 0, eigen_exact = 0, gen_eigen = 0, ld_exact = 0, gen_ld = 0;
    long samples = 0, exact_samples = 0, grazing = 0;
};

// Normwise error of the post-impact state, relative to the velocities at the
// impact (before and after): v' = v + dv is formed at the scale of v, so a
// component that nearly vanishes after the impact (e ~ 0 against a heavy body)
// cannot be had to better than roundoff of |v| by any method.
double state_error(const std::vector<double>& a, const std::vector<double>& ref, const std::vector<double>& before)
{
    double scale = 0, err = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        scale = std::max({scale, std::fabs(ref[i]), std::fabs(before[i])});
        err = std::max(err, std::fabs(a[i] - ref[i]));
    }
    return scale > 0 ? err / scale : err;
}

class verifier {
public:
    explicit verifier(const case_def& c) : c_(c)
    {
        codegen::options o = c.opt;
        o.name = "f";
        o.source = c.source;
        pl_ = codegen::make_plan(load(c.source), o);
        ref_ = impactgen::solve(pl_.deriv); // the tensor convention, independent of the engine rewrite
        // The header the test compiled and the plan must agree on the inputs.
        EXPECT_EQ(static_cast<int>(pl_.inputs.size()), c.n_in) << c.source;
        for (int i = 0; i < c.n_in && i < static_cast<int>(pl_.inputs.size()); ++i)
            EXPECT_EQ(pl_.inputs[static_cast<std::size_t>(i)].get_name(), c.in_names[i]);
        EXPECT_EQ(static_cast<int>(pl_.outputs.size()), c.n_out);
        classify();
    }

    stats run(long samples, long exact_samples, unsigned seed);

private:
    enum role_t { restitution, mass, inv_mass, inertia, inv_inertia, velocity, position, other };
    struct role {
        role_t kind;
        std::size_t body = 0;
        int r = 0, c = 0;
        symbol sym; ///< the problem symbol this input stands for (or whose inverse it is)
    };

    void classify()
    {
        const problem& q = pl_.prob;
        for (const symbol& in : pl_.inputs) {
            std::string nm = in.get_name();
            bool inverse = false;
            symbol s = in;
            if (nm.rfind("inv_", 0) == 0) {
                for (const symbol& p : q.parameters())
                    if (p.get_name() == nm.substr(4)) {
                        s = p;
                        inverse = true;
                    }
            }
            role r{other, 0, 0, 0, s};
            if (q.restitution.is_equal(s))
                r.kind = restitution;
            for (std::size_t b = 0; b < q.bodies.size(); ++b) {
                const body& bd = q.bodies[b];
                if (!bd.infinite_mass && bd.mass.is_equal(s))
                    r = {inverse ? inv_mass : mass, b, 0, 0, s};
                for (int i = 0; i < 3; ++i)
                    for (int j = i; j < 3; ++j)
                        if (bd.inertia[i][j].is_equal(s))
                            r = {inverse ? inv_inertia : inertia, b, i, j, s};
                for (int i = 0; i < 3; ++i) {
                    if (bd.velocity[i].is_equal(s) || bd.angular_velocity[i].is_equal(s))
                        r = {velocity, b, i, 0, s};
                    if (bd.position[i].is_equal(s))
                        r = {position, b, i, 0, s};
                }
            }
            roles_.push_back(r);
        }
    }

    // One random input vector; symbol values (exact) for the references.
    void sample(std::mt19937_64& rng, std::vector<double>& in)
    {
        std::uniform_real_distribution<double> U(0, 1);
        const problem& q = pl_.prob;
        std::vector<double> m(q.bodies.size(), 1);
        for (std::size_t b = 0; b < q.bodies.size(); ++b)
            if (!q.bodies[b].infinite_mass && is_a<numeric>(q.bodies[b].mass))
                m[b] = ex_to<numeric>(q.bodies[b].mass).to_double();
        for (const role& r : roles_)
            if (r.kind == mass || r.kind == inv_mass)
                m[r.body] = std::pow(10.0, -3 + 6 * U(rng));
        // Inertia tensors (double) per body: m * size^2 * R diag(l) R^T.
        std::vector<nm::mat<double>> I(q.bodies.size());
        for (std::size_t b = 0; b < q.bodies.size(); ++b) {
            Eigen::Quaterniond qr(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5);
            qr.normalize();
            bool full = false;
            for (const role& r : roles_)
                full = full || ((r.kind == inertia || r.kind == inv_inertia) && r.body == b && r.r != r.c);
            Eigen::Matrix3d R = full ? qr.toRotationMatrix() : Eigen::Matrix3d::Identity();
            Eigen::Vector3d l(0.2 + 0.8 * U(rng), 0.2 + 0.8 * U(rng), 0.2 + 0.8 * U(rng));
            double size = 0.3 + U(rng);
            I[b] = m[b] * size * size * R * l.asDiagonal() * R.transpose();
            I[b] = (0.5 * (I[b] + I[b].transpose())).eval();
        }
        std::vector<nm::mat<double>> K(q.bodies.size());
        for (std::size_t b = 0; b < q.bodies.size(); ++b) {
            K[b] = I[b].inverse();
            K[b] = (0.5 * (K[b] + K[b].transpose())).eval();
        }
        in.assign(roles_.size(), 0);
        for (std::size_t i = 0; i < roles_.size(); ++i) {
            const role& r = roles_[i];
            double x = 0;
            switch (r.kind) {
            case restitution: {
                double t = U(rng);
                x = t < 0.03 ? 0.0 : t > 0.97 ? 1.0 : U(rng);
                break;
            }
            case mass: x = m[r.body]; break;
            case inv_mass: x = 1 / m[r.body]; break;
            case inertia: x = q.dimension == 2 ? m[r.body] * (0.05 + U(rng)) : I[r.body](r.r, r.c); break;
            case inv_inertia: x = K[r.body](r.r, r.c); break;
            case velocity:
            case position: x = 2 * U(rng) - 1; break;
            case other: x = 0.2 + 1.8 * U(rng); break;
            }
            in[i] = x;
        }
    }

    // The problem's symbol values for the inputs: exact (CLN rationals) or double.
    template <typename V> void symbol_values(const std::vector<double>& in, std::map<ex, V, ex_is_less>& values) const
    {
        values.clear();
        std::map<std::size_t, bool> inverse_tensor;
        for (std::size_t i = 0; i < roles_.size(); ++i) {
            const role& r = roles_[i];
            V x;
            if constexpr (std::is_same_v<V, numeric>)
                x = exact(in[i]);
            else
                x = in[i];
            if (r.kind == inv_mass)
                values[r.sym] = V(1) / x;
            else if (r.kind == inv_inertia)
                inverse_tensor[r.body] = true;
            else
                values[r.sym] = x;
        }
        for (auto& [b, yes] : inverse_tensor) {
            (void)yes;
            std::vector<std::size_t> idx;
            for (std::size_t i = 0; i < roles_.size(); ++i)
                if (roles_[i].kind == inv_inertia && roles_[i].body == b)
                    idx.push_back(i);
            if (idx.size() == 1) { // planar: the inverse of a scalar moment of inertia
                if constexpr (std::is_same_v<V, numeric>)
                    values[roles_[idx[0]].sym] = numeric(1) / exact(in[idx[0]]);
                else
                    values[roles_[idx[0]].sym] = V(1) / in[idx[0]];
                continue;
            }
            if constexpr (std::is_same_v<V, numeric>) {
                matrix Km(3, 3);
                for (std::size_t i : idx) {
                    Km(static_cast<unsigned>(roles_[i].r), static_cast<unsigned>(roles_[i].c)) = exact(in[i]);
                    Km(static_cast<unsigned>(roles_[i].c), static_cast<unsigned>(roles_[i].r)) = exact(in[i]);
                }
                matrix Ie = Km.inverse();
                for (std::size_t i : idx)
                    values[roles_[i].sym] = ex_to<numeric>(Ie(static_cast<unsigned>(roles_[i].r), static_cast<unsigned>(roles_[i].c)));
            } else {
                Eigen::Matrix3d Km;
                for (std::size_t i : idx)
                    Km(roles_[i].r, roles_[i].c) = Km(roles_[i].c, roles_[i].r) = in[i];
                Eigen::Matrix3d Ie = Km.inverse();
                for (std::size_t i : idx)
                    values[roles_[i].sym] = Ie(roles_[i].r, roles_[i].c);
            }
        }
    }

    int call_ld(const std::vector<double>& in, std::vector<long double>& out) const
    {
        std::vector<long double> x(in.begin(), in.end());
        out.assign(static_cast<std::size_t>(c_.n_out), 0);
        return c_.fld(x.data(), out.data());
    }

    std::size_t approach_index() const
    {
        for (std::size_t i = 0; i < pl_.outputs.size(); ++i)
            if (pl_.outputs[i].kind == codegen::output_value::approach_velocity)
                return i;
        return 0;
    }

    const case_def& c_;
    codegen::plan pl_;
    solution ref_;
    std::vector<role> roles_;
};

stats verifier::run(long samples, long exact_samples, unsigned seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0, 1);
    stats st;
    const problem& q = pl_.prob;
    const std::size_t ia = approach_index();
    std::vector<double> in;
    std::vector<long double> ld;
    const int ok = int(gen::impact_status::ok), not_approaching = int(gen::impact_status::not_approaching);
    for (long s = 0; s < samples; ++s) {
        // Draw until the inputs are an impact (flip the velocities first).
        bool grazing = false;
        for (int attempt = 0;; ++attempt) {
            if (attempt > 200)
                throw std::runtime_error(c_.source + ": no impact among 200 random draws");
            sample(rng, in);
            int status = call_ld(in, ld);
            if (status == not_approaching) {
                for (std::size_t i = 0; i < roles_.size(); ++i)
                    if (roles_[i].kind == velocity)
                        in[i] = -in[i];
                status = call_ld(in, ld);
            }
            if (status != ok)
                continue;
            grazing = U(rng) < 0.125;
            if (grazing) {
                // u is affine in each velocity input: move the one with the largest
                // coefficient so that u becomes -10^(-4 ... -12).
                long double u0 = ld[ia];
                std::size_t best = roles_.size();
                long double best_a = 0;
                for (std::size_t i = 0; i < roles_.size(); ++i) {
                    if (roles_[i].kind != velocity)
                        continue;
                    std::vector<double> x = in;
                    x[i] += 1;
                    std::vector<long double> o;
                    call_ld(x, o);
                    long double a = o[ia] - u0;
                    if (std::fabs(a) > std::fabs(best_a)) {
                        best_a = a;
                        best = i;
                    }
                }
                if (best == roles_.size())
                    grazing = false;
                else {
                    long double target = -std::pow(10.0L, -4 - 8 * (long double)U(rng));
                    in[best] = double(in[best] + (target - u0) / best_a);
                    if (call_ld(in, ld) != ok)
                        continue;
                }
            }
            break;
        }
        st.grazing += grazing;
        ++st.samples;

        std::vector<double> out(static_cast<std::size_t>(c_.n_out));
        int status = c_.fd(in.data(), out.data());
        EXPECT_EQ(status, ok) << c_.source << " sample " << s;
        if (status != ok)
            continue;

        // Eigen: the numeric problem at the (rounded) symbol values.
        evaluator<double> ed;
        symbol_values(in, ed.values);
        nm::problem<double> np;
        np.dimension = q.dimension;
        np.restitution = ed(q.restitution);
        for (const body& b : q.bodies) {
            nm::body<double> nb;
            nb.infinite_mass = b.infinite_mass;
            nb.particle = b.particle;
            nb.mass = b.infinite_mass ? 0.0 : ed(b.mass);
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    nb.inertia(r, c) = ed(b.inertia[r][c]);
            for (int c = 0; c < 3; ++c) {
                nb.position[c] = ed(b.position[c]);
                nb.velocity[c] = ed(b.velocity[c]);
                nb.angular_velocity[c] = ed(b.angular_velocity[c]);
            }
            np.bodies.push_back(nb);
        }
        np.body1 = q.contact().body1;
        np.body2 = q.contact().body2;
        for (int c = 0; c < 3; ++c) {
            np.point[c] = ed(q.contact().point[c]);
            np.normal[c] = ed(q.contact().normal[c]);
        }
        for (const pivot& pv : q.pivots) {
            nm::pivot<double> npv;
            npv.body = pv.body;
            for (int c = 0; c < 3; ++c)
                npv.point[c] = ed(pv.point[c]);
            np.pivots.push_back(npv);
        }
        nm::answer<double> ea = nm::solve_momentum_system(np);
        EXPECT_TRUE(ea.ok);

        std::vector<double> g_state, e_state, x_state, ld_state, before;
        // The reference: the closed form of impactgen::solve evaluated by CLN, in
        // exact rationals on the first exact_samples samples and in 40-digit CLN
        // floats on the others (rationals cost 0.2-2 ms per 3-D sample; 40 digits
        // leave an error below 1e-35, far under the 1e-16 being measured).
        const bool do_exact = s < exact_samples;
        evaluator<numeric> ex_eval;
        symbol_values(in, ex_eval.values);
        if (!do_exact) {
            ex_eval.exact_only = false;
            for (auto& kv : ex_eval.values)
                kv.second = ex_to<numeric>(ex(kv.second).evalf());
        }
        for (const impactgen::step& stp : ref_.steps)
            ex_eval.values[stp.sym] = ex_eval(stp.value);
        for (std::size_t i = 0; i < pl_.outputs.size(); ++i) {
            const auto& ov = pl_.outputs[i];
            if (ov.kind != codegen::output_value::velocity && ov.kind != codegen::output_value::angular_velocity)
                continue;
            bool lin = ov.kind == codegen::output_value::velocity;
            g_state.push_back(out[i]);
            before.push_back(ed(lin ? q.bodies[ov.index].velocity[ov.component] : q.bodies[ov.index].angular_velocity[ov.component]));
            ld_state.push_back(double(ld[i]));
            e_state.push_back(lin ? ea.velocity[ov.index][ov.component] : ea.angular_velocity[ov.index][ov.component]);
            const ex& rv = lin ? ref_.after[ov.index].velocity[ov.component] : ref_.after[ov.index].angular_velocity[ov.component];
            x_state.push_back(ex_eval(rv).to_double());
        }
        double ge = state_error(g_state, e_state, before);
        st.gen_eigen = std::max(st.gen_eigen, ge);
        // Every sample: against the same generated function in long double (64-bit
        // mantissa, 2^11 times finer than double), whose agreement with the exact
        // form is itself asserted on the exact subset below.
        double gl = state_error(g_state, ld_state, before);
        st.gen_ld = std::max(st.gen_ld, gl);
        EXPECT_LE(gl, 1e-14) << c_.source << " sample " << s;
        {
            st.exact_samples += do_exact ? 1 : 0;
            double gx = state_error(g_state, x_state, before), exx = state_error(e_state, x_state, before), lx = state_error(ld_state, x_state, before);
            st.gen_exact = std::max(st.gen_exact, gx);
            st.eigen_exact = std::max(st.eigen_exact, exx);
            st.ld_exact = std::max(st.ld_exact, lx);
            // 1e-14 = 45 units of roundoff of double: every output is v + s N g with
            // N = -(1+e) u / k; u, k and g are short sums of products of O(1)-scaled
            // inputs (inertia condition number <= 5 by construction), each a few
            // roundings relative to the state's scale, so the whole chain stays
            // within a few tens of ulps of the largest state component.
            EXPECT_LE(gx, 1e-14) << c_.source << " sample " << s;
            // The exact value is rounded to double for the comparison (<= 2^-53 = 1.1e-16
            // relative per component); long double itself adds < 1e-17.
            EXPECT_LE(lx, 3e-16) << c_.source << " sample " << s;
        }
        // Agreement with Eigen: the unscaled PartialPivLU solve loses up to
        // log10(mass ratio) + a few digits (measured-facts: 4.5e-8 at ratios of 1e6);
        // 1e-5 leaves room for the extremes of 100,000 draws.
        EXPECT_LE(ge, 1e-5) << c_.source << " sample " << s;
    }
    return st;
}

void verify(const case_def& c)
{
    // 20,000 samples per case by default (the whole suite stays within the CI's time
    // budget on two cores); IMPACTGEN_DEEP=1 draws 100,000.
    const bool deep = env_or("IMPACTGEN_DEEP", 0) != 0;
    const long samples = env_or("IMPACTGEN_SAMPLES", deep ? 100000 : 20000);
    // Exact CLN rationals cost 0.2-2 ms per sample for the 3-D classes: by
    // default the first 2,000 per case (10,000 deep); 40-digit CLN floats cover the rest.
    const long exact = env_or("IMPACTGEN_EXACT_SAMPLES", deep ? 10000 : 2000);
    GiNaC::Digits = 40;
    const unsigned seed = static_cast<unsigned>(env_or("IMPACTGEN_SEED", 20240611));
    auto t0 = std::chrono::steady_clock::now();
    verifier v(c);
    // A problem without inputs has one answer: one sample suffices.
    stats st = v.run(c.n_in == 0 ? 1 : samples, exact, seed);
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[codegen] %-28s %7ld samples (%ld grazing), exact CLN on %ld, 40-digit CLN on the rest | max rel. error of the post-impact state"
                " vs that reference: generated double %.2e, long double %.2e, Eigen %.2e | all samples: generated double vs"
                " long double %.2e, generated vs Eigen %.2e"
                " (seed %u, %.1f s)\n",
                (c.source + (c.opt.inverse_inertia ? " (inverse I, 1/m)" : "")).c_str(), st.samples, st.grazing,
                st.exact_samples, st.gen_exact, st.ld_exact, st.eigen_exact, st.gen_ld, st.gen_eigen, seed, secs);
}

} // namespace

TEST(CodegenVerify, CentralDirect) { verify({"central-direct", opts(), GEN_FUNCS(central_direct)}); }
TEST(CodegenVerify, CentralOblique) { verify({"central-oblique", opts(), GEN_FUNCS(central_oblique)}); }
TEST(CodegenVerify, Noncentral3d) { verify({"noncentral-3d", opts(), GEN_FUNCS(noncentral_3d)}); }
TEST(CodegenVerify, Noncentral3dEngineConvention) { verify({"noncentral-3d", opts("", "", true), GEN_FUNCS(noncentral_3d_engine)}); }
TEST(CodegenVerify, Massive3d) { verify({"massive-3d", opts(), GEN_FUNCS(massive_3d)}); }
TEST(CodegenVerify, Planar) { verify({"planar", opts(), GEN_FUNCS(planar)}); }
TEST(CodegenVerify, PlanarEngineConvention) { verify({"planar", opts("", "", true), GEN_FUNCS(planar_engine)}); }
TEST(CodegenVerify, PinnedPlanar) { verify({"pinned-planar", opts(), GEN_FUNCS(pinned_planar)}); }
TEST(CodegenVerify, PinnedPlanarSpecialised) { verify({"pinned-planar", opts("m1,m2,v1", "e=0.9,l=1/2"), GEN_FUNCS(pinned_planar_set)}); }
TEST(CodegenVerify, WallOblique3d) { verify({"wall-oblique-3d.json", opts(), GEN_FUNCS(wall_oblique_3d)}); }
TEST(CodegenVerify, Pinned3d) { verify({"pinned-3d.json", opts(), GEN_FUNCS(pinned_3d)}); }
TEST(CodegenVerify, PuckBlock34) { verify({"puck-block-34.json", opts("v_x_puck,v_y_puck,w_z_puck,m_puck"), GEN_FUNCS(puck_block_34)}); }
TEST(CodegenVerify, PuckBlock34Constant) { verify({"puck-block-34.json", opts(), GEN_FUNCS(puck_block_34_const)}); }
TEST(CodegenVerify, SpinningSpheres) { verify({"spinning-spheres.json", opts(), GEN_FUNCS(spinning_spheres)}); }
TEST(CodegenVerify, HingedRod) { verify({"hinged-rod.json", opts("v_x_ball,m_ball,e"), GEN_FUNCS(hinged_rod)}); }

// Bad inputs get a status and the state unchanged: velocities as given (a NaN
// input stays NaN where it was), impulse, approach velocity and energy lost zero.
TEST(CodegenStatus, BadInputs)
{
    using gen::impact_status;
    auto call = [](double e, double m1, double m2, double vn1, double vn2, double w = 0) {
        gen::planar_result<double> r;
        r.v_n1 = r.w_b1 = r.normal_impulse = r.approach_velocity = r.energy_lost = 12345.0; // not left as they were
        impact_status s = gen::planar(e, m1, 0.5, 0.1, -0.2, 0.25, vn1, w, m2, 0.7, -0.3, 0.4, -0.5, vn2, 0.125, r);
        auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
        if (s != impact_status::ok) {
            EXPECT_TRUE(same(r.v_t1, 0.25));
            EXPECT_TRUE(same(r.v_n1, vn1));
            EXPECT_TRUE(same(r.w_b1, w));
            EXPECT_TRUE(same(r.v_t2, -0.5));
            EXPECT_TRUE(same(r.v_n2, vn2));
            EXPECT_TRUE(same(r.w_b2, 0.125));
            EXPECT_EQ(r.normal_impulse, 0.0);
            EXPECT_EQ(r.approach_velocity, 0.0);
            EXPECT_EQ(r.energy_lost, 0.0);
        } else {
            for (double x : {r.v_t1, r.v_n1, r.w_b1, r.v_t2, r.v_n2, r.w_b2, r.normal_impulse, r.energy_lost})
                EXPECT_FALSE(std::isnan(x));
        }
        return s;
    };
    const double nan = std::nan(""), inf = HUGE_VAL;
    EXPECT_EQ(call(0.5, 1, 2, 1, -1), impact_status::ok);
    EXPECT_EQ(call(0.5, -1, 2, 1, -1), impact_status::invalid_mass);
    EXPECT_EQ(call(0.5, 1, 0, 1, -1), impact_status::invalid_mass);
    EXPECT_EQ(call(0.5, 1, 2, -1, 1), impact_status::not_approaching);      // separating
    EXPECT_EQ(call(0.5, 1, 2, 0, 0), impact_status::not_approaching);       // resting
    EXPECT_EQ(call(0.5, 1, 2, nan, -1), impact_status::non_finite_input);
    EXPECT_EQ(call(nan, 1, 2, 1, -1), impact_status::non_finite_input);
    EXPECT_EQ(call(0.5, nan, 2, 1, -1), impact_status::non_finite_input);   // not "invalid mass"
    EXPECT_EQ(call(0.5, 1, 2, 1, -1, inf), impact_status::non_finite_input);
    EXPECT_EQ(call(1.5, 1, 2, 1, -1), impact_status::invalid_restitution);
    EXPECT_EQ(call(0.5, 1, 2, 1e300, -1e300), impact_status::overflow); // the kinetic energy overflows

    // Engine convention: a tiny k = w_1 + w_2 overflows N; the inverse inertia
    // tensors must be positive definite (their leading principal minors).
    gen::noncentral_3d_engine_result<double> r;
    double in[gen::noncentral_3d_engine_input_count] = {};
    in[0] = 0.5;      // e
    in[1] = 1e-320;   // inv_m1 (denormal, > 0)
    in[17] = 1e-320;  // inv_m2
    for (int j : {2, 5, 7, 18, 21, 23}) // inv_I1_tt, _nn, _bb, inv_I2_tt, _nn, _bb: identity (no lever arm: k = 2e-320)
        in[j] = 1;
    in[12] = -1;      // v_n1
    in[28] = -2;      // v_n2: u = v_n2 - v_n1 = -1 < 0, an impact
    EXPECT_STREQ(gen::noncentral_3d_engine_input_names[2], "inv_I1_tt");
    EXPECT_STREQ(gen::noncentral_3d_engine_input_names[7], "inv_I1_bb");
    EXPECT_STREQ(gen::noncentral_3d_engine_input_names[23], "inv_I2_bb");
    EXPECT_EQ(gen::noncentral_3d_engine(static_cast<const double*>(in), r), impact_status::overflow)
        << "k = 2e-320: N = -(1+e) u / k overflows";
    // A negative inverse inertia entry (it could make k negative) is no inverse inertia.
    in[1] = in[17] = 1;
    in[2] = -10; // inv_I1_tt
    in[10] = 1;  // r_b1, a lever arm about t
    EXPECT_EQ(gen::noncentral_3d_engine(static_cast<const double*>(in), r), impact_status::invalid_inertia);
    in[2] = 1;
    EXPECT_EQ(gen::noncentral_3d_engine(static_cast<const double*>(in), r), impact_status::ok);
    in[3] = 2; // inv_I1_tn: the minor tt nn - tn^2 = -3 < 0, the determinant -3 too
    EXPECT_EQ(gen::noncentral_3d_engine(static_cast<const double*>(in), r), impact_status::invalid_inertia);
}

// The fast path (one flag), the checked path (a status per check) and the batch
// form agree on status and outputs, for valid inputs, bad inputs, and inputs whose
// shared reciprocal products leave the normal range (the fast path then defers).
template <typename Result, typename Fast, typename Checked, typename Batch, typename ToArray>
void batch_agrees(const char* what, int n_in, int n_out, const char* const* names, Fast fast, Checked checked, Batch batch,
                  ToArray to_array, int min_ok)
{
    using gen::impact_status;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0, 1);
    const long n = 512;
    std::vector<std::vector<double>> in(static_cast<std::size_t>(n_in), std::vector<double>(n)),
        out(static_cast<std::size_t>(n_out), std::vector<double>(n));
    const double bad[] = {std::nan(""), HUGE_VAL, -1, 0, 1e-160, 1e200, 2};
    // The diagonal entries of 3-D (inverse) inertia tensors: most often dominant (the
    // tensor positive definite, so that the 3-D headers compute impacts too).
    auto tensor_diagonal = [&](int j) {
        const std::string nm = names[j];
        const std::size_t k = nm.rfind('_');
        return (nm.rfind("I", 0) == 0 || nm.rfind("inv_I", 0) == 0) && k != std::string::npos && nm.size() == k + 3 &&
               nm[k + 1] == nm[k + 2];
    };
    for (long i = 0; i < n; ++i)
        for (int j = 0; j < n_in; ++j) {
            double x = j == 0 ? U(rng) : 0.2 + U(rng); // e in [0, 1]; masses, inertia, positions > 0
            if (j > 0 && U(rng) < 0.3)
                x = 2 * U(rng) - 1;
            if (tensor_diagonal(j) && U(rng) < 0.9)
                x = 3.2 + U(rng); // > the sum of two off-diagonal entries in [-1, 1.2]
            if (U(rng) < 0.03)
                x = bad[static_cast<std::size_t>(U(rng) * 7) % 7];
            in[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] = x;
        }
    std::vector<const double*> ip;
    std::vector<double*> op;
    for (auto& a : in)
        ip.push_back(a.data());
    for (auto& a : out)
        op.push_back(a.data());
    std::vector<impact_status> st(static_cast<std::size_t>(n));
    batch(n, ip.data(), op.data(), st.data());
    int ok = 0;
    for (long i = 0; i < n; ++i) {
        std::vector<double> x(static_cast<std::size_t>(n_in)), a(static_cast<std::size_t>(n_out)), b(a);
        for (int j = 0; j < n_in; ++j)
            x[static_cast<std::size_t>(j)] = in[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)];
        Result ra, rb;
        impact_status sa = fast(x.data(), ra), sb = checked(x.data(), rb);
        to_array(ra, a.data());
        to_array(rb, b.data());
        ASSERT_EQ(sa, sb) << what << " impact " << i;
        ASSERT_EQ(st[static_cast<std::size_t>(i)], sa) << what << " impact " << i;
        ok += sa == impact_status::ok;
        for (int j = 0; j < n_out; ++j) {
            const double c = out[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)], av = a[static_cast<std::size_t>(j)],
                         bv = b[static_cast<std::size_t>(j)];
            if (sa != impact_status::ok) {
                // The state unchanged, bit for bit in all three forms (a NaN input stays NaN).
                auto same = [](double p, double q) { return p == q || (std::isnan(p) && std::isnan(q)); };
                EXPECT_TRUE(same(c, av) && same(av, bv)) << what << " impact " << i << " output " << j;
                continue;
            }
            EXPECT_FALSE(std::isnan(c) || std::isnan(av));
            const double tol = 1e-12 * std::max({1.0, std::fabs(av), std::fabs(bv)});
            EXPECT_LE(std::fabs(av - bv), tol) << what << " impact " << i << " output " << j;
            EXPECT_LE(std::fabs(c - av), tol) << what << " impact " << i << " output " << j;
        }
    }
    EXPECT_GE(ok, min_ok) << what << ": too few impacts to compare";
}

#define BATCH_AGREES(FN, MIN_OK)                                                                                      \
    batch_agrees<gen::FN##_result<double>>(                                                                           \
        #FN, gen::FN##_input_count, gen::FN##_output_count, gen::FN##_input_names,                                    \
        [](const double* x, gen::FN##_result<double>& r) { return gen::FN(x, r); },                                   \
        [](const double* x, gen::FN##_result<double>& r) {                                                            \
            return std::apply([&](auto... v) { return gen::detail::FN##_checked(v..., r); }, to_tuple<gen::FN##_input_count>(x)); \
        },                                                                                                            \
        [](long n, const double* const* in, double* const* out, gen::impact_status* s) { gen::FN##_batch(n, in, out, s); }, \
        [](const gen::FN##_result<double>& r, double* a) { gen::FN##_to_array(r, a); }, MIN_OK)

/// The first N entries of x as a tuple (the positional form's arguments).
template <typename T, std::size_t... I> auto to_tuple_impl(const T* x, std::index_sequence<I...>)
{
    return std::make_tuple(x[I]...);
}
template <std::size_t N, typename T> auto to_tuple(const T* x) { return to_tuple_impl(x, std::make_index_sequence<N>{}); }

// The fast path (every check folded into a few tests, some checks replaced by values
// that imply them, such as 1/I_E for the centroidal inertia of pinned-planar) and the
// checked path (each check as written, naming the one that fails) over the whole range
// of each scalar type: every input log-uniform in magnitude between the smallest
// denormal and the largest finite value, of either sign, one in four set so that a
// product of two inputs lands near the underflow threshold. Same status, and the same
// outputs bit for bit (both compute them with the same expressions), on every draw.
template <typename T, typename Result, typename Fast, typename Checked, typename ToArray>
void whole_range_agrees(const char* what, int n_in, int n_out, Fast fast, Checked checked, ToArray to_array, long n)
{
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<long double> U(0, 1);
    const long double lo = std::log10(static_cast<long double>(std::numeric_limits<T>::denorm_min()));
    const long double hi = std::log10(static_cast<long double>(std::numeric_limits<T>::max()));
    auto magnitude = [&] { return static_cast<T>(std::pow(10.0L, lo + (hi - lo) * U(rng))); };
    std::vector<T> x(static_cast<std::size_t>(n_in)), a(static_cast<std::size_t>(n_out)), b(a);
    long ok = 0, statuses[16] = {};
    for (long i = 0; i < n; ++i) {
        for (int j = 0; j < n_in; ++j) {
            T v = j == 0 ? static_cast<T>(U(rng)) : magnitude(); // e in [0, 1]
            if (j > 0 && U(rng) < 0.2)
                v = -v;
            x[static_cast<std::size_t>(j)] = v;
        }
        if (n_in > 2 && U(rng) < 0.25) { // x_j^2 x_k about the smallest denormal
            const std::size_t j = 1 + static_cast<std::size_t>(U(rng) * (n_in - 1)) % static_cast<std::size_t>(n_in - 1);
            const std::size_t k = 1 + static_cast<std::size_t>(U(rng) * (n_in - 1)) % static_cast<std::size_t>(n_in - 1);
            x[k] = std::fabs(x[k]);
            x[j] = static_cast<T>(std::sqrt(static_cast<long double>(std::numeric_limits<T>::denorm_min()) * (1 + 100 * U(rng)) /
                                            static_cast<long double>(x[k])));
        }
        Result ra{}, rb{};
        const gen::impact_status sa = fast(x.data(), ra), sb = checked(x.data(), rb);
        ASSERT_EQ(int(sa), int(sb)) << what << " draw " << i;
        ++statuses[int(sa) & 15];
        if (sa != gen::impact_status::ok)
            continue;
        ++ok;
        to_array(ra, a.data());
        to_array(rb, b.data());
        for (int j = 0; j < n_out; ++j)
            ASSERT_TRUE(a[static_cast<std::size_t>(j)] == b[static_cast<std::size_t>(j)]) << what << " draw " << i << " output " << j;
    }
    std::printf("[whole range] %-22s %-12s %ld draws: %ld ok, %ld not approaching, %ld singular, %ld overflow\n", what,
                sizeof(T) == 4 ? "float" : sizeof(T) == 8 ? "double" : "long double", n, ok,
                statuses[int(gen::impact_status::not_approaching)], statuses[int(gen::impact_status::singular)],
                statuses[int(gen::impact_status::overflow)]);
    EXPECT_GE(ok, n / 100) << what << ": too few impacts among the draws";
}

#define WHOLE_RANGE_AGREES(FN, T, N)                                                                                  \
    whole_range_agrees<T, gen::FN##_result<T>>(                                                                       \
        #FN, gen::FN##_input_count, gen::FN##_output_count,                                                           \
        [](const T* x, gen::FN##_result<T>& r) { return gen::FN(x, r); },                                             \
        [](const T* x, gen::FN##_result<T>& r) {                                                                      \
            return std::apply([&](auto... v) { return gen::detail::FN##_checked(v..., r); }, to_tuple<gen::FN##_input_count>(x)); \
        },                                                                                                            \
        [](const gen::FN##_result<T>& r, T* a) { gen::FN##_to_array(r, a); }, N)

TEST(CodegenBatch, FastAndCheckedAgreeOverTheWholeRange)
{
    WHOLE_RANGE_AGREES(pinned_planar, float, 200000);
    WHOLE_RANGE_AGREES(pinned_planar, double, 200000);
    WHOLE_RANGE_AGREES(pinned_planar, long double, 100000);
    WHOLE_RANGE_AGREES(central_direct, float, 100000);
    WHOLE_RANGE_AGREES(central_direct, double, 100000);
    WHOLE_RANGE_AGREES(central_oblique, double, 100000);
    WHOLE_RANGE_AGREES(planar, float, 100000);
    WHOLE_RANGE_AGREES(planar, double, 100000);
    WHOLE_RANGE_AGREES(planar_engine, double, 100000);
}

TEST(CodegenBatch, FastCheckedAndBatchAgree)
{
    // (random 3-D tensors are seldom positive definite: few valid impacts there)
    BATCH_AGREES(planar, 50);
    BATCH_AGREES(planar_engine, 50);
    BATCH_AGREES(central_direct, 50);
    BATCH_AGREES(pinned_planar, 50);
    BATCH_AGREES(noncentral_3d, 1);
    BATCH_AGREES(noncentral_3d_engine, 1);
    BATCH_AGREES(massive_3d, 1);

    // m1 I1 = 1e-320 is not a normal number: the fast path defers to the checked one.
    gen::planar_result<double> a, b;
    EXPECT_EQ(gen::planar(0.5, 1e-160, 1e-160, 0.1, 0.2, 0.0, 1.0, 0.0, 1.0, 1.0, 0.3, -0.2, 0.0, -1.0, 0.0, a), gen::impact_status::ok);
    EXPECT_EQ(gen::detail::planar_checked(0.5, 1e-160, 1e-160, 0.1, 0.2, 0.0, 1.0, 0.0, 1.0, 1.0, 0.3, -0.2, 0.0, -1.0, 0.0, b),
              gen::impact_status::ok);
    EXPECT_EQ(a.v_n2, b.v_n2);
    EXPECT_EQ(a.normal_impulse, b.normal_impulse);

    // with_energy_lost = false: the same state, energy_lost 0 (and not checked for overflow).
    gen::planar_result<double> c;
    EXPECT_EQ((gen::planar<double, false>(0.5, 1.0, 0.5, 0.1, 0.2, 0.0, 1.0, 0.0, 2.0, 1.0, 0.3, -0.2, 0.0, -1.0, 0.0, c)),
              gen::impact_status::ok);
    EXPECT_EQ(gen::planar(0.5, 1.0, 0.5, 0.1, 0.2, 0.0, 1.0, 0.0, 2.0, 1.0, 0.3, -0.2, 0.0, -1.0, 0.0, a), gen::impact_status::ok);
    EXPECT_EQ(c.v_n1, a.v_n1);
    EXPECT_EQ(c.w_b2, a.w_b2);
    EXPECT_EQ(c.normal_impulse, a.normal_impulse);
    EXPECT_GT(a.energy_lost, 0.0);
    EXPECT_EQ(c.energy_lost, 0.0);
    EXPECT_EQ((gen::planar<double, false>(0.5, 1.0, 0.5, 0.1, 0.2, 0.0, 1e300, 0.0, 2.0, 1.0, 0.3, -0.2, 0.0, -1e300, 0.0, c)),
              gen::impact_status::ok); // the kinetic energy would overflow; the state does not
    {
        // The batch form without energy_lost: out[8] may be null; the rest as with it.
        double x[15][3] = {{0.5, 0.5, 2}, {1, -1, 1}, {0.5, 0.5, 0.5}, {0.1, 0.1, 0.1}, {0.2, 0.2, 0.2}, {0, 0, 0}, {1, 1, 1},
                           {0, 0, 0},     {2, 2, 2},  {1, 1, 1},       {0.3, 0.3, 0.3}, {-0.2, -0.2, -0.2}, {0, 0, 0}, {-1, -1, -1}, {0, 0, 0}};
        const double* in[15];
        for (int j = 0; j < 15; ++j)
            in[j] = x[j];
        double y[9][3] = {}, z[9][3] = {};
        double* oy[9];
        double* oz[9];
        for (int j = 0; j < 9; ++j) {
            oy[j] = y[j];
            oz[j] = z[j];
        }
        oz[8] = nullptr;
        gen::impact_status sy[3], sz[3];
        gen::planar_batch(3, in, oy, sy);
        gen::planar_batch<double, false>(3, in, oz, sz);
        EXPECT_EQ(sy[0], gen::impact_status::ok);
        EXPECT_EQ(sy[1], gen::impact_status::invalid_mass);
        EXPECT_EQ(sy[2], gen::impact_status::invalid_restitution);
        for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(sy[i], sz[i]);
            for (int j = 0; j < 8; ++j)
                EXPECT_EQ(y[j][i], z[j][i]);
        }
    }
    EXPECT_EQ(gen::planar(0.5, 1.0, 0.5, 0.1, 0.2, 0.0, 1e300, 0.0, 2.0, 1.0, 0.3, -0.2, 0.0, -1e300, 0.0, c), gen::impact_status::overflow);

    // k = 1/m1 + r_t1^2/I1 overflows (r_t1 = 1e150, I1 = 1e-10): singular in every form, with
    // and without energy_lost (without it, energy_lost used to be what proved k finite).
    {
        double x[15] = {0.5, 1, 1e-10, 1e150, 0, 0, 1, 0, 1, 1, 0, 0, 0, -1, 0};
        gen::planar_result<double> r;
        EXPECT_EQ((gen::planar<double, false>(static_cast<const double*>(x), r)), gen::impact_status::singular);
        EXPECT_EQ((gen::planar<double, true>(static_cast<const double*>(x), r)), gen::impact_status::singular);
        EXPECT_EQ(r.normal_impulse, 0.0);
        const double* in[15];
        double cols[15][1];
        for (int j = 0; j < 15; ++j) {
            cols[j][0] = x[j];
            in[j] = cols[j];
        }
        double oc[9][1];
        double* out[9];
        for (int j = 0; j < 9; ++j)
            out[j] = oc[j];
        gen::impact_status st[1];
        gen::planar_batch<double, false>(1, in, out, st);
        EXPECT_EQ(st[0], gen::impact_status::singular);
        gen::planar_batch<double, true>(1, in, out, st);
        EXPECT_EQ(st[0], gen::impact_status::singular);
    }
}

// The checked-in header for noncentral-3d is what the library generates now, and
// the same straight-line program comes out when the problem is built again
// (hash-consing does not depend on GiNaC's term order within one process either).
TEST(CodegenDeterminism, SameTextTwiceInOneProcess)
{
    codegen::options o;
    o.name = "noncentral_3d";
    o.source = "noncentral-3d";
    o.version = "x";
    std::string a = codegen::generate(load("noncentral-3d"), o).text;
    std::string b = codegen::generate(load("noncentral-3d"), o).text;
    EXPECT_EQ(a, b);
}
