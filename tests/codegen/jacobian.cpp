// The generated Jacobians (impactgen codegen ... --jacobian [--wrt ...]) against two
// independent references, on seeded random inputs, for every named class, the engine
// convention of noncentral-3d and planar, and problem files:
//  (a) central finite differences of the plain generated double function (the same
//      header's NAME, not NAME_jacobian), and the long double instantiation of
//      NAME_jacobian;
//  (b) exact differentiation of the closed form: impactgen::solve of the problem in
//      the tensor convention (not the plan's steps, not plan_jacobian's chain rule),
//      every step substituted so that each output is one expression in the inputs
//      (the engine convention through m = 1/inv_m and I = inv_I^{-1}), differentiated
//      by GiNaC's diff() once per class, and evaluated in exact rationals (CLN) at the
//      very doubles the generated function received;
//  (c) a --wrt subset gives the full Jacobian's columns; a failed call gives all-zero
//      derivatives and the state unchanged.
// Counts: IMPACTGEN_JACOBIAN_CASES samples per class for (a) (default 1000) and
// IMPACTGEN_JACOBIAN_EXACT_CASES for (b) (default 300); without them IMPACTGEN_SAMPLES
// caps (a) at IMPACTGEN_SAMPLES and (b) at a quarter of it (the full sanitizer pass, IMPACTGEN_SANITIZE_ALL=1, sets 200),
// and IMPACTGEN_DEEP=1 runs 10,000 of each (about 3 minutes on one core).
// IMPACTGEN_SEED overrides the seed.
//
// Inputs as in verify.cpp: masses log-uniform in [1e-3, 1e3] (ratios to 1e6), inertia
// tensors m size^2 R diag(0.2..1) R^T (condition number <= 5, size in [0.3, 1.3]),
// velocities and positions in [-1, 1], e in [0, 1] (3% exactly 0, 3% exactly 1).
// The exact check adds one sample in eight near grazing ((v_B - v_A).n between -1e-12
// and -1e-4); finite differences cannot step across u = 0 and skip those.
//
// How errors are measured. A derivative d(output i)/d(input j) is compared in units of
// F_i / s_j. V is the largest velocity component (linear or angular) before or after
// the impact. s_j is the scale of input j: V for a velocity, 1 for e and a position, the
// value for a mass, an inverse mass or a length, the largest diagonal entry of its tensor
// for an inertia or inverse inertia entry. F_i is the scale of output i: V for velocities
// and the approach velocity; P = |N| max(1, V/|u|) = (1+e) max(|u|, V)/k for impulses;
// P V for the energy lost.
// err_ij = |J_ij - ref_ij| s_j / F_i is then the error of the first-order change of
// output i when input j moves by its own scale, relative to the output's scale: the
// quantity a user of the Jacobian (a Newton step, a saltation matrix) sees.
#include <algorithm>
#include <tuple>
#include <utility>

#include "codegen/codegen.hpp"
#include "numeric/momentum_solver.hpp"
#include "symbolic/named_classes.hpp"

#include "jac_central_direct.hpp"
#include "jac_central_oblique.hpp"
#include "jac_hinged_rod.hpp"
#include "jac_massive_3d.hpp"
#include "jac_noncentral_3d.hpp"
#include "jac_noncentral_3d_engine.hpp"
#include "jac_noncentral_3d_wrt.hpp"
#include "jac_pinned_3d.hpp"
#include "jac_pinned_planar.hpp"
#include "jac_planar.hpp"
#include "jac_planar_engine.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <random>
#include <unordered_map>

using namespace GiNaC;
namespace codegen = impactgen::codegen;
namespace nm = impactgen::numeric;
using impactgen::body;
using impactgen::find_named_class;
using impactgen::load_problem_file;
using impactgen::named_class;
using impactgen::problem;
using impactgen::solution;
using impactgen::step_role;

namespace gen = impactgen::generated;

namespace {

long env_or(const char* name, long fallback)
{
    const char* v = std::getenv(name);
    return v && *v ? std::strtol(v, nullptr, 10) : fallback;
}

bool deep() { return env_or("IMPACTGEN_DEEP", 0) != 0; }

// Samples per class: finite differences (a) and exact (b).
long fd_cases()
{
    if (deep())
        return env_or("IMPACTGEN_JACOBIAN_CASES", 10000);
    return env_or("IMPACTGEN_JACOBIAN_CASES", std::min(1000L, env_or("IMPACTGEN_SAMPLES", 1000)));
}
long exact_cases()
{
    if (deep())
        return env_or("IMPACTGEN_JACOBIAN_EXACT_CASES", env_or("IMPACTGEN_JACOBIAN_CASES", 10000));
    return env_or("IMPACTGEN_JACOBIAN_EXACT_CASES", std::min(300L, std::max(1L, env_or("IMPACTGEN_SAMPLES", 1200) / 4)));
}

template <typename T, std::size_t... I> auto as_tuple(const T* x, std::index_sequence<I...>) { return std::make_tuple(x[I]...); }

// A generated function through arrays: status, outputs (n_out) and derivatives
// (n_out x n_wrt, row-major). The derivatives are set to garbage before the call.
template <typename T> using jac_fn = std::function<int(const T*, T*, T*)>;
template <typename T> using val_fn = std::function<int(const T*, T*)>;

struct jac_case {
    std::string source; ///< named class or file under examples/problems
    codegen::options opt;
    int n_in, n_out, n_wrt;
    const char* const* in_names;
    const char* const* out_names;
    const char* const* wrt_names;
    val_fn<double> f;
    val_fn<long double> fld;
    jac_fn<double> jd;
    jac_fn<long double> jld;
    jac_fn<double> jd_struct; ///< the overload taking NAME_input<double>
};

#define JAC_CALL(FN, T, STRUCT)                                                                                       \
    [](const T* in, T* v, T* d) {                                                                                     \
        gen::FN##_jacobian_result<T> r;                                                                               \
        for (auto& row : r.d)                                                                                         \
            for (T& x : row)                                                                                          \
                x = static_cast<T>(12345);                                                                    \
        const auto args = as_tuple(in, std::make_index_sequence<gen::FN##_input_count>{});                           \
        int s;                                                                                                        \
        if (STRUCT)                                                                                                   \
            s = int(gen::FN##_jacobian(                                                                               \
                std::apply([](auto... x) { return gen::FN##_input<T>{x...}; }, args), r));                            \
        else                                                                                                          \
            s = std::apply([&](auto... x) { return int(gen::FN##_jacobian(x..., r)); }, args);                        \
        gen::FN##_to_array(r.value, v);                                                                               \
        for (int i = 0; i < gen::FN##_output_count; ++i)                                                              \
            for (int j = 0; j < gen::FN##_wrt_count; ++j)                                                             \
                d[i * gen::FN##_wrt_count + j] = r.d[i][j];                                                           \
        return s;                                                                                                     \
    }

#define JAC_FUNCS(FN)                                                                                                 \
    gen::FN##_input_count, gen::FN##_output_count, gen::FN##_wrt_count, gen::FN##_input_names,                        \
        gen::FN##_output_names, gen::FN##_wrt_names,                                                                  \
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
        },                                                                                                            \
        JAC_CALL(FN, double, false), JAC_CALL(FN, long double, false), JAC_CALL(FN, double, true)

codegen::options opts(std::string params = "", bool inv = false, std::string wrt = "")
{
    codegen::options o;
    o.params_given = !params.empty();
    std::stringstream ps(params), ws(wrt);
    std::string item;
    while (std::getline(ps, item, ','))
        o.params.push_back(item);
    while (std::getline(ws, item, ','))
        o.wrt.push_back(item);
    o.inverse_inertia = o.inverse_mass = inv;
    o.jacobian = true;
    return o;
}

problem load(const std::string& source)
{
    if (const named_class* c = find_named_class(source))
        return c->build();
    return load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/" + source);
}

// A double or long double exactly as a rational (the mantissa 32 bits at a time:
// exact for x87's 64 bits and for a 113-bit quad long double alike).
numeric exact(long double x)
{
    if (x == 0)
        return 0;
    int e = 0;
    long double m = std::frexp(std::fabs(x), &e); // |x| = m 2^e, m in [0.5, 1)
    numeric r = 0;
    int shift = 0;
    while (m != 0) {
        m = std::ldexp(m, 32);
        const long double hi = std::floor(m);
        r = r * numeric(4294967296UL) + numeric(static_cast<unsigned long>(hi));
        m -= hi;
        shift += 32;
    }
    r = r * pow(numeric(2), numeric(e - shift));
    return x < 0 ? -r : r;
}

// Expressions in the inputs compiled once into a straight-line list of nodes
// (shared subexpressions once: the substituted closed form is a DAG), then
// evaluated per sample: exactly in CLN rationals, or in double.
class tape {
public:
    explicit tape(const std::vector<symbol>& inputs) : inputs_(inputs) {}

    int node_of(const ex& e)
    {
        auto it = memo_.find(e);
        if (it != memo_.end())
            return it->second;
        node n;
        if (is_a<numeric>(e)) {
            n.kind = node::num;
            n.c = ex_to<numeric>(e);
            if (!n.c.is_rational())
                throw std::runtime_error("an irrational constant in the exact reference");
        } else if (is_a<symbol>(e)) {
            n.kind = node::sym;
            for (std::size_t i = 0; i < inputs_.size(); ++i)
                if (e.is_equal(inputs_[i]))
                    n.input = static_cast<int>(i);
            if (n.input < 0)
                throw std::runtime_error("no input " + ex_to<symbol>(e).get_name());
        } else if (is_a<add>(e) || is_a<mul>(e)) {
            n.kind = is_a<add>(e) ? node::sum : node::product;
            for (std::size_t i = 0; i < e.nops(); ++i)
                n.args.push_back(node_of(e.op(i)));
        } else if (is_a<power>(e)) {
            n.kind = node::pow;
            n.args.push_back(node_of(e.op(0)));
            if (!is_a<numeric>(e.op(1)) || !ex_to<numeric>(e.op(1)).is_rational())
                throw std::runtime_error("a power with a symbolic exponent");
            n.c = ex_to<numeric>(e.op(1));
        } else {
            throw std::runtime_error("cannot evaluate a function in the exact reference");
        }
        n.cd = n.kind == node::num || n.kind == node::pow ? n.c.to_double() : 0.0;
        nodes_.push_back(n);
        const int id = static_cast<int>(nodes_.size()) - 1;
        memo_.emplace(e, id);
        return id;
    }

    std::size_t size() const { return nodes_.size(); }

    void eval(const std::vector<numeric>& in, std::vector<numeric>& v) const
    {
        v.resize(nodes_.size());
        for (std::size_t k = 0; k < nodes_.size(); ++k) {
            const node& n = nodes_[k];
            switch (n.kind) {
            case node::num: v[k] = n.c; break;
            case node::sym: v[k] = in[static_cast<std::size_t>(n.input)]; break;
            case node::sum: {
                numeric s = v[static_cast<std::size_t>(n.args[0])];
                for (std::size_t i = 1; i < n.args.size(); ++i)
                    s = s + v[static_cast<std::size_t>(n.args[i])];
                v[k] = s;
                break;
            }
            case node::product: {
                numeric s = v[static_cast<std::size_t>(n.args[0])];
                for (std::size_t i = 1; i < n.args.size(); ++i)
                    s = s * v[static_cast<std::size_t>(n.args[i])];
                v[k] = s;
                break;
            }
            case node::pow: {
                const numeric& b = v[static_cast<std::size_t>(n.args[0])];
                numeric r = n.c.is_integer() ? b.power(n.c) : GiNaC::pow(b, n.c);
                if (!r.is_rational()) // a square root of a non-square (no normal here needs one)
                    throw std::runtime_error("an irrational power in the exact reference");
                v[k] = r;
                break;
            }
            }
        }
    }

    void eval(const std::vector<double>& in, std::vector<double>& v) const
    {
        v.resize(nodes_.size());
        for (std::size_t k = 0; k < nodes_.size(); ++k) {
            const node& n = nodes_[k];
            switch (n.kind) {
            case node::num: v[k] = n.cd; break;
            case node::sym: v[k] = in[static_cast<std::size_t>(n.input)]; break;
            case node::sum:
            case node::product: {
                double s = v[static_cast<std::size_t>(n.args[0])];
                for (std::size_t i = 1; i < n.args.size(); ++i)
                    s = n.kind == node::sum ? s + v[static_cast<std::size_t>(n.args[i])] : s * v[static_cast<std::size_t>(n.args[i])];
                v[k] = s;
                break;
            }
            case node::pow: v[k] = std::pow(v[static_cast<std::size_t>(n.args[0])], n.cd); break;
            }
        }
    }

private:
    struct node {
        enum kind_t { num, sym, sum, product, pow } kind = num;
        numeric c;
        double cd = 0;
        int input = -1;
        std::vector<int> args;
    };
    std::vector<symbol> inputs_;
    std::vector<node> nodes_;
    std::unordered_map<ex, int, std::hash<ex>, ex_is_equal> memo_;
};

// The reference: each output of the plan as one expression in the inputs, from
// impactgen::solve of the problem in the tensor convention, and its derivatives by
// GiNaC's diff(), compiled into one tape.
struct exact_reference {
    std::vector<int> value;             ///< tape node of output i
    std::vector<std::vector<int>> d;    ///< tape node of d(output i)/d(wrt j)
    tape t;
    double seconds = 0;
    std::size_t nodes = 0;

    explicit exact_reference(const codegen::plan& pl) : t(pl.inputs)
    {
        auto t0 = std::chrono::steady_clock::now();
        const solution ref = impactgen::solve(pl.deriv);
        const problem& q = pl.prob;
        // The engine convention: the problem's masses and inertia through the inputs.
        exmap sub;
        for (const auto& [old, inv] : pl.inverse_of)
            sub[old] = 1 / ex(inv);
        for (const auto& [b, K] : pl.inverse_tensor) {
            matrix Km(3, 3);
            for (unsigned r = 0; r < 3; ++r)
                for (unsigned c = 0; c < 3; ++c)
                    Km(r, c) = K[r][c];
            const matrix I = Km.inverse();
            for (unsigned r = 0; r < 3; ++r)
                for (unsigned c = 0; c < 3; ++c)
                    if (is_a<symbol>(q.bodies[b].inertia[r][c]))
                        sub[q.bodies[b].inertia[r][c]] = I(r, c);
        }
        // Every step in the inputs (one pass each: the earlier steps are already in inputs).
        for (const impactgen::step& st : ref.steps)
            sub[st.sym] = st.value.subs(sub, subs_options::no_pattern);
        const impactgen::step* u_step = ref.find(step_role::approach_velocity);
        for (std::size_t i = 0; i < pl.outputs.size(); ++i) {
            const codegen::output_value& ov = pl.outputs[i];
            ex e;
            switch (ov.kind) {
            case codegen::output_value::velocity: e = ref.after[ov.index].velocity[static_cast<std::size_t>(ov.component)]; break;
            case codegen::output_value::angular_velocity:
                e = ref.after[ov.index].angular_velocity[static_cast<std::size_t>(ov.component)];
                break;
            case codegen::output_value::normal_impulse: e = ref.normal_impulse; break;
            case codegen::output_value::pivot_impulse: e = ref.pivot_impulses[ov.index][static_cast<std::size_t>(ov.component)]; break;
            case codegen::output_value::approach_velocity: e = u_step ? ex(u_step->sym) : ex(0); break;
            case codegen::output_value::energy_lost: e = ref.energy_lost; break;
            }
            e = e.subs(sub, subs_options::no_pattern);
            value.push_back(t.node_of(e));
            std::vector<int> row;
            for (const symbol& x : pl.jac.wrt)
                row.push_back(t.node_of(e.diff(x)));
            d.push_back(row);
        }
        nodes = t.size();
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
};

struct stats {
    long fd_samples = 0, exact_samples = 0, grazing = 0;
    double fd = 0, ld = 0, exact_d = 0, exact_ld = 0, value_exact = 0, struct_diff = 0, values_vs_plain = 0;
};

class checker {
public:
    explicit checker(const jac_case& c) : c_(c)
    {
        codegen::options o = c.opt;
        o.name = "f";
        o.source = c.source;
        pl_ = codegen::make_plan(load(c.source), o);
        // The header the test compiled and the plan agree on inputs, outputs and wrt.
        EXPECT_EQ(static_cast<int>(pl_.inputs.size()), c.n_in) << c.source;
        for (int i = 0; i < c.n_in && i < static_cast<int>(pl_.inputs.size()); ++i)
            EXPECT_EQ(pl_.inputs[static_cast<std::size_t>(i)].get_name(), c.in_names[i]);
        EXPECT_EQ(static_cast<int>(pl_.outputs.size()), c.n_out);
        EXPECT_EQ(static_cast<int>(pl_.jac.wrt.size()), c.n_wrt);
        for (int j = 0; j < c.n_wrt && j < static_cast<int>(pl_.jac.wrt.size()); ++j) {
            EXPECT_EQ(pl_.jac.wrt[static_cast<std::size_t>(j)].get_name(), c.wrt_names[j]);
            for (std::size_t i = 0; i < pl_.inputs.size(); ++i)
                if (pl_.inputs[i].is_equal(pl_.jac.wrt[static_cast<std::size_t>(j)]))
                    wrt_index_.push_back(i);
        }
        EXPECT_EQ(static_cast<int>(wrt_index_.size()), c.n_wrt);
        EXPECT_EQ(c.wrt_names[c.n_wrt], nullptr);
        classify();
        for (std::size_t i = 0; i < pl_.outputs.size(); ++i) {
            if (pl_.outputs[i].kind == codegen::output_value::approach_velocity)
                iu_ = i;
            if (pl_.outputs[i].kind == codegen::output_value::normal_impulse)
                iN_ = i;
        }
        // The state before the impact, in the inputs (for the scales).
        before_ = tape(pl_.inputs);
        lst inverses;
        for (const auto& [old, inv] : pl_.inverse_of)
            inverses.append(old == 1 / inv);
        for (const ex& u : pl_.unchanged)
            before_nodes_.push_back(before_.node_of(u.subs(inverses)));
    }

    // The scales at `in` (see the top of the file): F_i of each output (out: the
    // outputs there) and s_j of each input differentiated by.
    void scales(const std::vector<double>& in, const std::vector<double>& out, std::vector<double>& F, std::vector<double>& sj) const
    {
        std::vector<double> v, before;
        before_.eval(in, v);
        for (int id : before_nodes_)
            before.push_back(v[static_cast<std::size_t>(id)]);
        double V = 0;
        F = output_scales(out, before, V);
        sj.resize(wrt_index_.size());
        for (std::size_t j = 0; j < wrt_index_.size(); ++j)
            sj[j] = input_scale(in, wrt_index_[j], V);
    }

    const codegen::plan& plan() const { return pl_; }
    std::size_t wrt_input(std::size_t j) const { return wrt_index_[j]; }

    stats run(long fd_samples, long exact_samples, unsigned seed, double& reference_seconds, std::size_t& reference_nodes);

    // One sample of valid inputs that make an impact (ok in double and long double).
    // grazing: u moved to -1e-4 ... -1e-12 (when a velocity input moves u).
    bool draw(std::mt19937_64& rng, std::vector<double>& in, bool want_grazing)
    {
        std::vector<long double> ld;
        for (int attempt = 0; attempt < 200; ++attempt) {
            sample(rng, in);
            int status = call_ld(in, ld);
            if (status == int(gen::impact_status::not_approaching)) {
                for (std::size_t i = 0; i < roles_.size(); ++i)
                    if (roles_[i].kind == velocity)
                        in[i] = -in[i];
                status = call_ld(in, ld);
            }
            if (status != int(gen::impact_status::ok))
                continue;
            if (!want_grazing)
                return false;
            // u is affine in each velocity input: move the one with the largest
            // coefficient so that u becomes -10^(-4 ... -12).
            const long double u0 = ld[iu_];
            std::size_t best = roles_.size();
            long double best_a = 0;
            for (std::size_t i = 0; i < roles_.size(); ++i) {
                if (roles_[i].kind != velocity)
                    continue;
                std::vector<double> x = in;
                x[i] += 1;
                std::vector<long double> o;
                call_ld(x, o);
                const long double a = o[iu_] - u0;
                if (std::fabs(a) > std::fabs(best_a)) {
                    best_a = a;
                    best = i;
                }
            }
            if (best == roles_.size())
                return false;
            std::uniform_real_distribution<double> U(0, 1);
            const long double target = -std::pow(10.0L, -4 - 8 * (long double)U(rng));
            std::vector<double> x = in;
            x[best] = double(x[best] + (target - u0) / best_a);
            if (call_ld(x, ld) != int(gen::impact_status::ok))
                continue;
            in = x;
            return true;
        }
        throw std::runtime_error(c_.source + ": no impact among 200 random draws");
    }

    // The scale s_j of input i (see the top of the file); V: the state's velocity scale.
    double input_scale(const std::vector<double>& in, std::size_t i, double V) const
    {
        const role& r = roles_[i];
        switch (r.kind) {
        case mass:
        case inv_mass:
        case other: return std::fabs(in[i]);
        case inertia:
        case inv_inertia: {
            double s = 0;
            for (std::size_t k = 0; k < roles_.size(); ++k)
                if (roles_[k].kind == r.kind && roles_[k].body == r.body && roles_[k].r == roles_[k].c)
                    s = std::max(s, std::fabs(in[k]));
            return s > 0 ? s : std::fabs(in[i]);
        }
        case velocity: return V;
        case restitution:
        case position: return 1.0;
        }
        return 1.0;
    }

    // The scale F_i of each output (see the top of the file), from the outputs and the state before.
    std::vector<double> output_scales(const std::vector<double>& out, const std::vector<double>& before, double& V) const
    {
        V = 0;
        for (std::size_t i = 0; i < pl_.outputs.size(); ++i) {
            const auto k = pl_.outputs[i].kind;
            if (k == codegen::output_value::velocity || k == codegen::output_value::angular_velocity)
                V = std::max({V, std::fabs(out[i]), std::fabs(before[i])});
        }
        const double u = std::fabs(out[iu_]);
        V = std::max(V, u);
        const double P = std::fabs(out[iN_]) * std::max(1.0, V / u);
        std::vector<double> F(pl_.outputs.size());
        for (std::size_t i = 0; i < F.size(); ++i) {
            switch (pl_.outputs[i].kind) {
            case codegen::output_value::velocity:
            case codegen::output_value::angular_velocity:
            case codegen::output_value::approach_velocity: F[i] = V; break;
            case codegen::output_value::normal_impulse:
            case codegen::output_value::pivot_impulse: F[i] = P; break;
            case codegen::output_value::energy_lost: F[i] = P * V; break;
            }
        }
        return F;
    }

    bool is_restitution(std::size_t i) const { return roles_[i].kind == restitution; }
    bool is_mass(std::size_t i) const { return roles_[i].kind == mass || roles_[i].kind == inv_mass; }
    bool is_velocity(std::size_t i) const { return roles_[i].kind == velocity; }

private:
    enum role_t { restitution, mass, inv_mass, inertia, inv_inertia, velocity, position, other };
    struct role {
        role_t kind;
        std::size_t body = 0;
        int r = 0, c = 0;
    };

    // The role of each input (as in verify.cpp): what it is in the problem.
    void classify()
    {
        const problem& q = pl_.prob;
        for (const symbol& in : pl_.inputs) {
            role r{other, 0, 0, 0};
            ex s = in;
            bool inverse = false;
            for (const auto& [old, inv] : pl_.inverse_of)
                if (inv.is_equal(in)) {
                    s = old;
                    inverse = true;
                }
            if (q.restitution.is_equal(s))
                r.kind = restitution;
            for (std::size_t b = 0; b < q.bodies.size(); ++b) {
                const body& bd = q.bodies[b];
                if (!bd.infinite_mass && bd.mass.is_equal(s))
                    r = {inverse ? inv_mass : mass, b, 0, 0};
                for (int i = 0; i < 3; ++i)
                    for (int j = i; j < 3; ++j) {
                        if (bd.inertia[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)].is_equal(s))
                            r = {inverse ? inv_inertia : inertia, b, i, j};
                        auto it = pl_.inverse_tensor.find(b);
                        if (it != pl_.inverse_tensor.end() &&
                            it->second[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)].is_equal(in))
                            r = {inv_inertia, b, i, j};
                    }
                for (std::size_t i = 0; i < 3; ++i) {
                    if (bd.velocity[i].is_equal(s) || bd.angular_velocity[i].is_equal(s))
                        r = {velocity, b, static_cast<int>(i), 0};
                    if (bd.position[i].is_equal(s))
                        r = {position, b, static_cast<int>(i), 0};
                }
            }
            roles_.push_back(r);
        }
    }

    // One random input vector (verify.cpp's distribution).
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
        std::vector<nm::mat<double>> I(q.bodies.size()), K(q.bodies.size());
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
            case inv_inertia: x = q.dimension == 2 ? 1 / (m[r.body] * (0.05 + U(rng))) : K[r.body](r.r, r.c); break;
            case velocity:
            case position: x = 2 * U(rng) - 1; break;
            case other: x = 0.2 + 1.8 * U(rng); break;
            }
            in[i] = x;
        }
    }

    int call_ld(const std::vector<double>& in, std::vector<long double>& out) const
    {
        std::vector<long double> x(in.begin(), in.end());
        out.assign(static_cast<std::size_t>(c_.n_out), 0);
        return c_.fld(x.data(), out.data());
    }

    const jac_case& c_;
    codegen::plan pl_;
    std::vector<role> roles_;
    std::vector<std::size_t> wrt_index_;
    tape before_{std::vector<symbol>()};
    std::vector<int> before_nodes_;
    std::size_t iu_ = 0, iN_ = 0;
};

// Tolerances, in units of F_i / s_j (see the top of the file).
//
// (a) Central differences D = (f(x + h) - f(x - h)) / (2h), h = c s_j, c = 2^-20 (9.5e-7):
//   truncation h^2/6 |f'''|, in these units c^2/6 |s_j^3 f'''| / F_i = 1.5e-13 C3 with C3
//   the relative third derivative along the input's own scale. The map is affine in the
//   velocities (the energy lost quadratic: central differences are exact there); in masses,
//   inertia, lengths and positions it is rational, and C3 is bounded by the conditioning
//   of the inputs: k = 1/m + (r x n).I^{-1}(r x n) changes by a factor up to ~7 per unit
//   of r (I/m >= 0.3^2 0.2 = 0.018, |r| <= 1.8), 6 7^3 = 2e3, and the mass ratios add a
//   few more; measured over 20,000 draws with c = 2^-17 (where truncation dominates):
//   C3 <= 9e3. Allowing C3 up to 1e5: <= 1.5e-8.
//   rounding: f is computed to within 1e-14 F (verify.cpp asserts that against the exact
//   closed form), so a difference is off by <= 2e-14 F / (2 c s_j): <= 1.1e-8 in these units.
//   Their sum, 2.6e-8, with a margin of 4: 1e-7 (the deep run measures <= 1.5e-9). A wrong
//   derivative (a missing chain-rule term, a wrong sign, a swapped column) is off by O(1).
const double fd_tolerance = 1e-7;
// (a') double against long double of the same generated code, and (b) double against the
//   exact derivative: each entry is a chain-rule sum of products of the values' steps and
//   earlier derivative steps (the 3-D classes: ~30 value operations and up to ~10 products
//   per derivative step on top), each product a few roundings (eps = 1.1e-16) of terms
//   bounded by a few F_i / s_j for these inputs (the conditioning above; k >= 1/m, the
//   1/k^2 of d N / d m cancels against 1/m^2 when the masses differ by 1e6). So the error
//   is C eps F_i / s_j with C of at most a few hundred: 1e-13 = 900 eps (the deep run
//   measures <= 1e-14). Near grazing (|u| down to 1e-12 V) P uses max(|u|, V), the scale
//   the products are formed at.
const double rounding_tolerance = 1e-13;
// long double against the exact derivative: the same C with long double's eps
// (2^-64 = 5.4e-20): 900 eps = 5e-17, 1e-16 (the difference to the exact value is
// computed exactly; the deep run measures <= 4e-18).
const double ld_tolerance = 1e-16;

stats checker::run(long fd_samples, long exact_samples, unsigned seed, double& reference_seconds, std::size_t& reference_nodes)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0, 1);
    stats st;
    const std::size_t no = static_cast<std::size_t>(c_.n_out), nw = static_cast<std::size_t>(c_.n_wrt);
    std::vector<double> in, out(no), val(no), d(no * nw), val2(no), d2(no * nw), fp(no), fm(no);
    std::vector<long double> lval(no), ld(no * nw);

    exact_reference ref(pl_);
    reference_seconds = ref.seconds;
    reference_nodes = ref.nodes;
    std::vector<numeric> xin, xv;

    // The generated Jacobian at `in`, the plain function's values, the scales; the
    // checks every sample gets (the values are the plain function's, the struct
    // overload gives the same numbers).
    std::vector<double> F, sj(nw);
    auto evaluate = [&](long s) {
        const int status = c_.jd(in.data(), val.data(), d.data());
        EXPECT_EQ(status, int(gen::impact_status::ok)) << c_.source << " sample " << s;
        const int ps = c_.f(in.data(), out.data());
        EXPECT_EQ(ps, status) << c_.source << " sample " << s;
        if (status != 0 || ps != 0)
            return false;
        scales(in, out, F, sj);
        // The values of NAME_jacobian are those of NAME (the same program; contraction
        // of a*b+c into an fma may differ between the two functions: a few roundings).
        for (std::size_t i = 0; i < no; ++i) {
            const double e = std::fabs(val[i] - out[i]) / F[i];
            st.values_vs_plain = std::max(st.values_vs_plain, e);
            EXPECT_LE(e, 1e-14) << c_.source << " sample " << s << " output " << c_.out_names[i];
        }
        c_.jd_struct(in.data(), val2.data(), d2.data());
        double diff = 0;
        for (std::size_t k = 0; k < no * nw; ++k)
            diff = std::max(diff, std::fabs(d2[k] - d[k]));
        for (std::size_t i = 0; i < no; ++i)
            diff = std::max(diff, std::fabs(val2[i] - val[i]));
        st.struct_diff = std::max(st.struct_diff, diff);
        EXPECT_EQ(diff, 0.0) << c_.source << " sample " << s << ": the struct overload differs";
        std::vector<long double> lin(in.begin(), in.end());
        EXPECT_EQ(c_.jld(lin.data(), lval.data(), ld.data()), 0) << c_.source << " sample " << s << " (long double)";
        return true;
    };
    auto enough = [&] { return ::testing::Test::HasFailure() && st.fd_samples + st.exact_samples > 20; };

    // (a) Central differences of the plain double function, and long double against double.
    const double c = std::ldexp(1.0, -20);
    for (long s = 0; s < fd_samples && !enough(); ++s) {
        for (;;) {
            draw(rng, in, false);
            // Differences would step across u = 0 near grazing: keep |u| >= 1e-3 V.
            c_.f(in.data(), out.data());
            double V = 0;
            for (std::size_t i = 0; i < no; ++i)
                if (pl_.outputs[i].kind == codegen::output_value::velocity ||
                    pl_.outputs[i].kind == codegen::output_value::angular_velocity)
                    V = std::max(V, std::fabs(out[i]));
            if (std::fabs(out[iu_]) >= 1e-3 * V)
                break;
        }
        if (!evaluate(s))
            continue;
        ++st.fd_samples;
        for (std::size_t j = 0; j < nw; ++j) {
            const std::size_t k = wrt_index_[j];
            const double h = c * sj[j];
            std::vector<double> xp = in, xm = in;
            // e stays in [0, 1]: at its ends one-sided second-order differences
            // (-3 f(x) + 4 f(x + h) - f(x + 2h)) / 2h (h < 0 backwards), the same O(h^2).
            const bool forward = is_restitution(k) && in[k] - h < 0, backward = is_restitution(k) && in[k] + h > 1;
            const bool one_sided = forward || backward;
            if (one_sided) {
                xp[k] = in[k] + (forward ? h : -h);
                xm[k] = in[k] + (forward ? 2 * h : -2 * h);
            } else {
                xp[k] = in[k] + h;
                xm[k] = in[k] - h;
            }
            const int sp = c_.f(xp.data(), fp.data()), sm = c_.f(xm.data(), fm.data());
            EXPECT_TRUE(sp == 0 && sm == 0) << c_.source << " sample " << s << ": a step in " << c_.wrt_names[j]
                                            << " leaves the valid inputs";
            if (sp != 0 || sm != 0)
                continue;
            for (std::size_t i = 0; i < no; ++i) {
                const double D = one_sided ? (-3 * out[i] + 4 * fp[i] - fm[i]) / (2 * (xp[k] - in[k]))
                                           : (fp[i] - fm[i]) / (xp[k] - xm[k]); // the steps as represented
                const double e = std::fabs(d[i * nw + j] - D) * sj[j] / F[i];
                st.fd = std::max(st.fd, e);
                EXPECT_LE(e, fd_tolerance) << c_.source << " sample " << s << " d " << c_.out_names[i] << " / d "
                                           << c_.wrt_names[j] << ": generated " << d[i * nw + j] << ", differences " << D;
            }
        }
        for (std::size_t i = 0; i < no; ++i)
            for (std::size_t j = 0; j < nw; ++j) {
                const double e = double(std::fabs((long double)d[i * nw + j] - ld[i * nw + j])) * sj[j] / F[i];
                st.ld = std::max(st.ld, e);
                EXPECT_LE(e, rounding_tolerance) << c_.source << " sample " << s << " d " << c_.out_names[i] << " / d "
                                                 << c_.wrt_names[j] << ": double " << d[i * nw + j] << ", long double "
                                                 << double(ld[i * nw + j]);
            }
    }

    // (b) The exact derivative at the same (exactly converted) inputs; one sample in
    // eight near grazing.
    for (long s = 0; s < exact_samples && !enough(); ++s) {
        const bool grazing = draw(rng, in, U(rng) < 0.125);
        if (!evaluate(s))
            continue;
        ++st.exact_samples;
        st.grazing += grazing;
        xin.clear();
        for (double x : in)
            xin.push_back(exact(x));
        ref.t.eval(xin, xv);
        for (std::size_t i = 0; i < no; ++i) {
            const numeric& xval = xv[static_cast<std::size_t>(ref.value[i])];
            const double ev = abs(exact(val[i]) - xval).to_double() / F[i];
            st.value_exact = std::max(st.value_exact, ev);
            EXPECT_LE(ev, 1e-14) << c_.source << " sample " << s << " value " << c_.out_names[i];
            for (std::size_t j = 0; j < nw; ++j) {
                const numeric& xd = xv[static_cast<std::size_t>(ref.d[i][j])];
                const double unit = sj[j] / F[i];
                const double e = abs(exact(d[i * nw + j]) - xd).to_double() * unit;
                const double el = abs(exact(ld[i * nw + j]) - xd).to_double() * unit;
                st.exact_d = std::max(st.exact_d, e);
                st.exact_ld = std::max(st.exact_ld, el);
                EXPECT_LE(e, rounding_tolerance) << c_.source << " sample " << s << (grazing ? " (grazing)" : "") << " d "
                                                 << c_.out_names[i] << " / d " << c_.wrt_names[j] << ": generated "
                                                 << d[i * nw + j] << ", exact " << xd.to_double();
                EXPECT_LE(el, ld_tolerance) << c_.source << " sample " << s << (grazing ? " (grazing)" : "") << " long double d "
                                            << c_.out_names[i] << " / d " << c_.wrt_names[j] << ": " << double(ld[i * nw + j])
                                            << ", exact " << xd.to_double();
            }
        }
    }
    return st;
}

void check(const jac_case& c)
{
    GiNaC::Digits = 40;
    const long fd = fd_cases(), ex_n = exact_cases();
    const unsigned seed = static_cast<unsigned>(env_or("IMPACTGEN_SEED", 20240611));
    auto t0 = std::chrono::steady_clock::now();
    checker k(c);
    double ref_seconds = 0;
    std::size_t ref_nodes = 0;
    stats st = k.run(fd, ex_n, seed, ref_seconds, ref_nodes);
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[jacobian] %-36s %2d x %2d | finite differences on %ld samples: max err %.2e, long double vs double %.2e"
                " | exact (CLN) on %ld samples (%ld grazing): double %.2e, long double %.2e, values %.2e"
                " | reference %zu nodes in %.2f s | seed %u, %.1f s\n",
                (c.source + (c.opt.inverse_inertia ? " (inverse I, 1/m)" : "") + (c.opt.wrt.empty() ? "" : " (--wrt)")).c_str(),
                c.n_out, c.n_wrt, st.fd_samples, st.fd, st.ld, st.exact_samples, st.grazing, st.exact_d, st.exact_ld,
                st.value_exact, ref_nodes, ref_seconds, seed, secs);
}


jac_case central_direct() { return {"central-direct", opts(), JAC_FUNCS(jac_central_direct)}; }
jac_case central_oblique() { return {"central-oblique", opts(), JAC_FUNCS(jac_central_oblique)}; }
jac_case noncentral_3d() { return {"noncentral-3d", opts(), JAC_FUNCS(jac_noncentral_3d)}; }
jac_case noncentral_3d_engine() { return {"noncentral-3d", opts("", true), JAC_FUNCS(jac_noncentral_3d_engine)}; }
jac_case noncentral_3d_wrt() { return {"noncentral-3d", opts("", false, "w_t1,v_n1,e,I1_tn,m2,r_b2"), JAC_FUNCS(jac_noncentral_3d_wrt)}; }
jac_case massive_3d() { return {"massive-3d", opts(), JAC_FUNCS(jac_massive_3d)}; }
jac_case planar() { return {"planar", opts(), JAC_FUNCS(jac_planar)}; }
jac_case planar_engine() { return {"planar", opts("", true), JAC_FUNCS(jac_planar_engine)}; }
jac_case pinned_planar() { return {"pinned-planar", opts(), JAC_FUNCS(jac_pinned_planar)}; }
jac_case hinged_rod() { return {"hinged-rod.json", opts("v_x_ball,m_ball,e,m_rod,I_rod,r_y_rod"), JAC_FUNCS(jac_hinged_rod)}; }
jac_case pinned_3d() { return {"pinned-3d.json", opts(), JAC_FUNCS(jac_pinned_3d)}; }

} // namespace

TEST(CodegenJacobian, CentralDirect) { check(central_direct()); }
TEST(CodegenJacobian, CentralOblique) { check(central_oblique()); }
TEST(CodegenJacobian, Noncentral3d) { check(noncentral_3d()); }
TEST(CodegenJacobian, Noncentral3dEngineConvention) { check(noncentral_3d_engine()); }
TEST(CodegenJacobian, Noncentral3dWrtSubset) { check(noncentral_3d_wrt()); }
TEST(CodegenJacobian, Massive3d) { check(massive_3d()); }
TEST(CodegenJacobian, Planar) { check(planar()); }
TEST(CodegenJacobian, PlanarEngineConvention) { check(planar_engine()); }
TEST(CodegenJacobian, PinnedPlanar) { check(pinned_planar()); }
TEST(CodegenJacobian, HingedRod) { check(hinged_rod()); }
TEST(CodegenJacobian, Pinned3d) { check(pinned_3d()); }

// --wrt w_t1,v_n1,e,I1_tn,m2,r_b2: the columns are the full Jacobian's columns of those
// inputs, in the order given, and the values are the same.
TEST(CodegenJacobianWrt, SubsetIsTheFullJacobiansColumns)
{
    const std::vector<std::string> wanted = {"w_t1", "v_n1", "e", "I1_tn", "m2", "r_b2"};
    ASSERT_EQ(gen::jac_noncentral_3d_wrt_wrt_count, static_cast<int>(wanted.size()));
    std::vector<int> column;
    for (std::size_t j = 0; j < wanted.size(); ++j) {
        EXPECT_EQ(std::string(gen::jac_noncentral_3d_wrt_wrt_names[j]), wanted[j]);
        for (int k = 0; k < gen::jac_noncentral_3d_wrt_count; ++k)
            if (wanted[j] == gen::jac_noncentral_3d_wrt_names[k])
                column.push_back(k);
    }
    EXPECT_EQ(gen::jac_noncentral_3d_wrt_wrt_names[wanted.size()], nullptr);
    ASSERT_EQ(column.size(), wanted.size());
    // The full header differentiates by every input, in input order.
    ASSERT_EQ(gen::jac_noncentral_3d_wrt_count, gen::jac_noncentral_3d_input_count);
    for (int k = 0; k < gen::jac_noncentral_3d_wrt_count; ++k)
        EXPECT_STREQ(gen::jac_noncentral_3d_wrt_names[k], gen::jac_noncentral_3d_input_names[k]);

    const jac_case full = noncentral_3d(), sub = noncentral_3d_wrt();
    checker k(full);
    std::mt19937_64 rng(static_cast<unsigned>(env_or("IMPACTGEN_SEED", 20240611)));
    const std::size_t no = static_cast<std::size_t>(full.n_out), nf = static_cast<std::size_t>(full.n_wrt), ns = wanted.size();
    std::vector<double> in, vf(no), df(no * nf), vs(no), ds(no * ns), F, sj;
    double worst = 0;
    long identical = 0, n = 0;
    for (long s = 0; s < 1000; ++s, ++n) {
        k.draw(rng, in, false);
        ASSERT_EQ(full.jd(in.data(), vf.data(), df.data()), 0);
        ASSERT_EQ(sub.jd(in.data(), vs.data(), ds.data()), 0);
        k.scales(in, vf, F, sj);
        bool same = true;
        for (std::size_t i = 0; i < no; ++i) {
            EXPECT_EQ(vs[i], vf[i]) << "sample " << s << " value " << full.out_names[i];
            for (std::size_t j = 0; j < ns; ++j) {
                const std::size_t jf = static_cast<std::size_t>(column[j]);
                const double a = ds[i * ns + j], b = df[i * nf + jf];
                same = same && a == b;
                // The same chain rule; with fewer columns the shared subexpressions (CSE)
                // and so the order of some sums differ. Each is within rounding_tolerance
                // of the exact derivative (the tests above): twice that apart at most.
                const double e = std::fabs(a - b) * sj[jf] / F[i];
                worst = std::max(worst, e);
                EXPECT_LE(e, 2 * rounding_tolerance) << "sample " << s << " d " << full.out_names[i] << " / d " << wanted[j]
                                                     << ": subset " << a << ", full " << b;
            }
        }
        identical += same;
    }
    std::printf("[jacobian] --wrt subset of noncentral-3d: %ld samples, %ld bit-identical to the full Jacobian's columns, max diff %.2e"
                " (units of F_i / s_j)\n",
                n, identical, worst);
}

// On a status other than ok: every derivative zero and out.value what the plain
// function returns (the state unchanged), for every header and every kind of failure;
// and the one failure the plain function does not have: finite values whose
// derivatives are not (1/m^2 overflows where 1/m does not) give overflow.
TEST(CodegenJacobianStatus, FailureGivesZeroDerivativesAndTheStateUnchanged)
{
    using gen::impact_status;
    const double nan = std::nan("");
    auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
    long overflows = 0;
    for (const jac_case& c : {central_direct(), central_oblique(), noncentral_3d(), noncentral_3d_engine(), noncentral_3d_wrt(),
                              massive_3d(), planar(), planar_engine(), pinned_planar(), hinged_rod(), pinned_3d()}) {
        checker k(c);
        std::mt19937_64 rng(7);
        const std::size_t no = static_cast<std::size_t>(c.n_out), nw = static_cast<std::size_t>(c.n_wrt);
        std::vector<double> in, out(no), val(no), d(no * nw), unchanged(no);
        std::size_t ie = in.size(), im = in.size();
        for (int s = 0; s < 20; ++s) {
            k.draw(rng, in, false);
            ie = im = in.size();
            for (std::size_t i = 0; i < in.size(); ++i) {
                if (k.is_restitution(i))
                    ie = i;
                if (k.is_mass(i) && im == in.size())
                    im = i;
            }
            ASSERT_LT(ie, in.size()) << c.source << ": e is an input of every header here";
            // The state unchanged, from the plain function (e = 2 is refused).
            std::vector<double> x = in;
            x[ie] = 2;
            ASSERT_EQ(c.f(x.data(), unchanged.data()), int(impact_status::invalid_restitution));
            std::vector<std::pair<std::string, std::vector<double>>> bad;
            bad.push_back({"e = 2", x});
            x = in;
            x[ie] = nan;
            bad.push_back({"e = NaN", x});
            x = in;
            x.back() = HUGE_VAL;
            bad.push_back({"last input infinite", x});
            x = in;
            for (std::size_t i = 0; i < x.size(); ++i)
                if (k.is_velocity(i))
                    x[i] = -x[i];
            bad.push_back({"velocities reversed", x});
            if (im < in.size()) {
                x = in;
                x[im] = -x[im];
                bad.push_back({"a negative mass", x});
            }
            for (const auto& [what, y] : bad) {
                const int sp = c.f(y.data(), out.data());
                const int sj = c.jd(y.data(), val.data(), d.data());
                EXPECT_NE(sj, int(impact_status::ok)) << c.source << ": " << what;
                EXPECT_EQ(sj, sp) << c.source << ": " << what;
                for (std::size_t i = 0; i < no; ++i)
                    EXPECT_TRUE(same(val[i], out[i])) << c.source << ": " << what << ", output " << c.out_names[i];
                for (std::size_t i = 0; i < no * nw; ++i)
                    EXPECT_EQ(d[i], 0.0) << c.source << ": " << what << ", entry " << i;
            }
            // A tiny mass: the values are finite; 1/m^2 in the derivatives may not be.
            if (im < in.size()) {
                x = in;
                x[im] = k.plan().inverse_of.empty() ? 1e-200 : 1e200;
                const int sp = c.f(x.data(), out.data());
                const int sj = c.jd(x.data(), val.data(), d.data());
                if (sp == int(impact_status::ok) && sj != int(impact_status::ok)) {
                    ++overflows;
                    EXPECT_EQ(sj, int(impact_status::overflow)) << c.source;
                    std::vector<double> y = x;
                    y[ie] = 2;
                    ASSERT_EQ(c.f(y.data(), unchanged.data()), int(impact_status::invalid_restitution));
                    for (std::size_t i = 0; i < no; ++i)
                        EXPECT_TRUE(same(val[i], unchanged[i])) << c.source << ": derivatives overflow, output " << c.out_names[i];
                    for (std::size_t i = 0; i < no * nw; ++i)
                        EXPECT_EQ(d[i], 0.0) << c.source << ": derivatives overflow, entry " << i;
                } else if (sj == int(impact_status::ok)) {
                    for (std::size_t i = 0; i < no * nw; ++i)
                        EXPECT_TRUE(std::isfinite(d[i])) << c.source << ": ok with a non-finite derivative";
                }
            }
        }
    }
    EXPECT_GT(overflows, 0) << "no case where the values are finite and the derivatives overflow";
    // planar, m1 = 1e-200: k = 1e200, N ~ 1e-200, v' finite; d w_1 / d m1 = -1/m1^2 overflows.
    gen::jac_planar_jacobian_result<double> r;
    EXPECT_EQ(gen::jac_planar_jacobian(0.5, 1e-200, 1.0, 0.1, 0.2, 0.0, 1.0, 0.0, 1.0, 1.0, 0.3, -0.2, 0.0, -1.0, 0.0, r),
              impact_status::overflow);
    EXPECT_EQ(r.value.v_n1, 1.0);
    EXPECT_EQ(r.value.v_n2, -1.0);
    EXPECT_EQ(r.value.normal_impulse, 0.0);
    EXPECT_EQ(r.value.energy_lost, 0.0);
    EXPECT_EQ(r.d[1][1], 0.0);
}
