// The generated headers with Coulomb friction (the writer codegen/writer.hpp) for the named
// friction classes (planar-friction, ball-floor-friction, noncentral-3d-friction),
// compiled into this test, against:
//  - select_regime (symbolic/friction.hpp) evaluated exactly by CLN at the very inputs
//    the double function received (exact rationals; the sliding angle of a 3-D slide at
//    50 digits): regime and every output, on 2,000 seeded samples per planar class and
//    400 for the 3-D class (each takes ~20 ms in CLN) (IMPACTGEN_FRICTION_EXACT
//    overrides; IMPACTGEN_DEEP=1: 20,000);
//  - the same closed form evaluated by CLN long floats (cln_closed_form.hpp: the class's
//    cases -- conditions, angle equation, outputs -- compiled once into a flat program and
//    run per sample on 256-bit floats with error bounds; the sliding angles of a 3-D slide
//    from a quartic in tan, by Aberth's method and Newton's at 256 bits, not the header's
//    root finder): regime and every output on 30,000 samples per class, the first 2,000 /
//    400 of them the samples above (IMPACTGEN_FRICTION_CLN overrides; IMPACTGEN_DEEP=1:
//    400,000; Release build, 100,000 samples: planar 2 s, ball-floor 1 s, 3-D 16 s, of
//    which 0.5 s and 4 s are the self-check below). A sample with a condition within 1e20 times its error
//    bound of 0 goes to select_regime instead (none with the default seed); the first 300
//    are decided by select_regime as well: the same regime, and outputs to 1e-30 and
//    within the error bounds the evaluation gives them (IMPACTGEN_FRICTION_CLN_SELF;
//    IMPACTGEN_DEEP=1: 2,000). Where the header finds none or two regimes but the closed
//    form exactly one, a slide with D = n.K(n - mu d) within 1e-7 of 0 must be the reason
//    (counted: about 30 in 100,000 samples of the 3-D class);
//  - the independent Eigen reference numeric/friction_solver.hpp (complementarity
//    problem, enumeration and semismooth Newton, no closed form): status, regime away
//    from the regime boundaries, every output, on 30,000 samples per class
//    (IMPACTGEN_FRICTION_SAMPLES overrides; IMPACTGEN_DEEP=1: 400,000);
//  - the law itself, from the header's outputs alone (restitution, cone, stick or
//    slide against the sliding velocity), on every sample it answers ok;
// and: continuity across the stick/slide boundary (mu = mu* (1 +- delta), mu* = |F|/N of
// the stick candidate), the regime on either side decided as select_regime decides it;
// mu = 0 is the smooth answer (the smooth headers generated/planar.hpp and
// noncentral_3d.hpp on the same inputs); float and long double against double;
// statuses and the unchanged state for bad inputs; the run-time root finder
// detail::trig2_roots against the whole-circle method in long double.
// IMPACTGEN_SAMPLES (200 in the full sanitizer pass, IMPACTGEN_SANITIZE_ALL=1) caps every count; IMPACTGEN_SEED moves
// the seed; FRICTION_DEBUG=1 prints the inputs and outputs of a disagreement. Five
// problem files (tests/codegen/friction: a 3-D sphere on the floor, a ball against a
// hinged rod, a box on a floor with a symbolic normal; and without a stick candidate, K
// singular: a rod pinned at its centre and a plate on a ball joint, each struck by a body
// of infinite mass) run the same tests on a quarter of the counts (without stick: no
// boundary to cross, the header never sticks; the law has no solution for much of the
// range of mu, so half of the samples that have one are compared).
//
// Inputs: masses log-uniform in [1e-3, 1e3] (ratios up to 1e6), inertia m s^2 (0.1..1)
// (planar) or m s^2 R diag(0.2..1) R^T (3-D, R a random rotation), s in [0.1, 1];
// positions, velocities and spins uniform in [-1, 1] (flipped when the contact points
// separate); e 5% 0, 5% 1, else uniform in [0, 1]; mu 10% log-uniform in [1e-4, 1], 10%
// near the stick/slide boundary (mu* 10^U(-9, -3) away from it, on either side), else
// uniform in [0, 2]; one sample in eight near grazing (u_n = -|u| 10^U(-12, -4)).
#define IMPACTGEN_TRIG2_STATS
#include "ball_floor_friction.hpp"
#include "noncentral_3d.hpp"
#include "noncentral_3d_friction.hpp"
#include "planar.hpp"
#include "pinned_plate_struck_3d.hpp"
#include "pinned_rod_struck.hpp"
#include "pinned_rod_struck_symbolic.hpp"
#include "planar_friction.hpp"
#include "rod_hinge_friction.hpp"
#include "sphere_floor_3d.hpp"
#include "tilted_box_friction.hpp"
#include "tilted_box_friction_unit.hpp"

#include "cln_closed_form.hpp"
#include "numeric/friction_solver.hpp"
#include "symbolic/derivation.hpp"
#include "symbolic/friction.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/problem.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace GiNaC;
namespace gen = impactgen::generated;
namespace nm = impactgen::numeric;
using impactgen::find_named_class;
using impactgen::friction_solution;
using impactgen::problem;
using impactgen::regime_case;

namespace {

long env_or(const char* name, long fallback)
{
    const char* v = std::getenv(name);
    return v && *v ? std::strtol(v, nullptr, 10) : fallback;
}
bool deep() { return env_or("IMPACTGEN_DEEP", 0) != 0; }
long count(const char* var, long normal, long in_deep)
{
    long n = env_or(var, deep() ? in_deep : normal);
    return std::min(n, env_or("IMPACTGEN_SAMPLES", n));
}
/// The problem files' tests run a quarter of the named classes' counts.
long count_for(const std::string& name, const char* var, long normal, long in_deep)
{
    const long n = count(var, normal, in_deep);
    return name.find(".json") != std::string::npos ? std::max(1L, n / 4) : n;
}
unsigned seed(unsigned salt) { return static_cast<unsigned>(env_or("IMPACTGEN_SEED", 20261207)) + 7919u * salt; }

// ---------------------------------------------------------------------------
// The classes

struct fclass {
    std::string name; ///< named class, or problem file under tests/codegen/friction
    int n_in, n_out;
    const char* const* in_names;
    const char* const* out_names;
    std::function<int(const double*, double*, int&)> fd;
    std::function<int(const long double*, long double*, int&)> fld;
    std::function<int(const float*, float*, int&)> ff;
};

#define FRICTION_FUNCS(FN)                                                                                            \
    gen::FN##_input_count, gen::FN##_output_count, gen::FN##_input_names, gen::FN##_output_names,                     \
        [](const double* in, double* o, int& regime) {                                                                \
            gen::FN##_result<double> r;                                                                               \
            int s = int(gen::FN(in, r));                                                                              \
            gen::FN##_to_array(r, o);                                                                                 \
            regime = int(r.regime);                                                                                   \
            return s;                                                                                                 \
        },                                                                                                            \
        [](const long double* in, long double* o, int& regime) {                                                      \
            gen::FN##_result<long double> r;                                                                          \
            int s = int(gen::FN(in, r));                                                                              \
            gen::FN##_to_array(r, o);                                                                                 \
            regime = int(r.regime);                                                                                   \
            return s;                                                                                                 \
        },                                                                                                            \
        [](const float* in, float* o, int& regime) {                                                                  \
            gen::FN##_result<float> r;                                                                                \
            int s = int(gen::FN(in, r));                                                                              \
            gen::FN##_to_array(r, o);                                                                                 \
            regime = int(r.regime);                                                                                   \
            return s;                                                                                                 \
        }

const std::vector<fclass>& classes()
{
    static const std::vector<fclass> all = {
        {"planar-friction", FRICTION_FUNCS(planar_friction)},
        {"ball-floor-friction", FRICTION_FUNCS(ball_floor_friction)},
        {"noncentral-3d-friction", FRICTION_FUNCS(noncentral_3d_friction)},
        // Problem files (tests/codegen/friction): a 3-D sphere on the floor (K isotropic: the
        // closed-form slide along u_t), a ball against a hinged rod with an oblique normal
        // (a pivot, its impulse an output), a box on a floor with a symbolic normal (sqrt).
        {"sphere-floor-3d.json", FRICTION_FUNCS(sphere_floor_3d)},
        {"rod-hinge-friction.json", FRICTION_FUNCS(rod_hinge_friction)},
        {"tilted-box-friction.json", FRICTION_FUNCS(tilted_box_friction)},
        // No stick candidate (the contact response K singular): a rod pinned at its centre and a
        // plate on a ball joint (full inertia tensor), each struck by a body of infinite mass.
        {"pinned-rod-struck-symbolic.json", FRICTION_FUNCS(pinned_rod_struck_symbolic)},
        {"pinned-plate-struck-3d.json", FRICTION_FUNCS(pinned_plate_struck_3d)},
    };
    return all;
}
bool is_case(const std::string& name) { return name.find(".json") != std::string::npos; }

const int ok = int(gen::friction_status::ok);
const int no_solution = int(gen::friction_status::no_solution);
const int ambiguous = int(gen::friction_status::ambiguous);
const int stick = int(gen::impact_regime::stick), slide = int(gen::impact_regime::slide), smooth = int(gen::impact_regime::smooth);

int index_of(const char* const* names, int n, const std::string& name)
{
    for (int i = 0; i < n; ++i)
        if (name == names[i])
            return i;
    return -1;
}

// ---------------------------------------------------------------------------
// Fast evaluation of the class's symbolic quantities in double (no GiNaC substitution).

double eval(const ex& e, const std::map<std::string, double>& v)
{
    if (is_a<numeric>(e))
        return ex_to<numeric>(e).to_double();
    if (is_a<symbol>(e))
        return v.at(ex_to<symbol>(e).get_name());
    if (is_a<add>(e)) {
        double s = 0;
        for (std::size_t i = 0; i < e.nops(); ++i)
            s += eval(e.op(i), v);
        return s;
    }
    if (is_a<mul>(e)) {
        double s = 1;
        for (std::size_t i = 0; i < e.nops(); ++i)
            s *= eval(e.op(i), v);
        return s;
    }
    if (is_a<power>(e))
        return std::pow(eval(e.op(0), v), eval(e.op(1), v));
    throw std::runtime_error("eval: unexpected expression");
}

nm::vec<double> evalv(const impactgen::vec3& x, const std::map<std::string, double>& v)
{
    return {eval(x[0], v), eval(x[1], v), eval(x[2], v)};
}

// A class with its symbolic problem, regimes (solved once) and the maps between the
// header's inputs and outputs and the problem.
struct class_model {
    const fclass* fc;
    problem prob;
    impactgen::derivation deriv;
    friction_solution fsol;
    bool has_stick = true;       // false: K singular, the slides are the only candidates
    std::vector<symbol> in_syms; // by header input
    struct out_ref {
        enum { velocity, angular, normal, tangential, approach, energy, pivot } kind;
        std::size_t body = 0;
        int axis = 0;
    };
    std::vector<out_ref> outs;

    explicit class_model(const fclass& c) : fc(&c)
    {
        prob = is_case(c.name) ? impactgen::load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/tests/codegen/friction/" + c.name)
                               : find_named_class(c.name)->build();
        deriv = impactgen::derive(prob);
        fsol = impactgen::solve_friction(deriv);
        has_stick = fsol.stick() != nullptr;
        std::map<std::string, symbol> by;
        for (const symbol& s : prob.parameters())
            by.emplace(s.get_name(), s);
        for (int i = 0; i < c.n_in; ++i)
            in_syms.push_back(by.at(c.in_names[i]));
        // Outputs by name, as the smooth headers name them.
        for (int k = 0; k < c.n_out; ++k) {
            const std::string n = c.out_names[k];
            out_ref r{};
            if (n == "normal_impulse")
                r.kind = out_ref::normal;
            else if (n.rfind("tangential_impulse_", 0) == 0) {
                r.kind = out_ref::tangential;
                r.axis = axis(n.substr(19));
            } else if (n == "approach_velocity")
                r.kind = out_ref::approach;
            else if (n == "energy_lost")
                r.kind = out_ref::energy;
            else if (n.rfind("R_", 0) == 0) {
                r.kind = out_ref::pivot;
                r.axis = axis(n.substr(2, 1));
                r.body = 0; // the problems here have one pivot
            } else {
                r.kind = n[0] == 'v' ? out_ref::velocity : out_ref::angular;
                r.axis = axis(n.substr(2, 1));
                const std::string label = n.substr(3);
                bool found = false;
                for (std::size_t b = 0; b < prob.bodies.size(); ++b) {
                    const std::string& L = prob.bodies[b].label;
                    if ((L.size() == 1 ? L : "_" + L) == label) {
                        r.body = b;
                        found = true;
                    }
                }
                if (!found)
                    throw std::runtime_error("output " + n + ": no body");
            }
            outs.push_back(r);
        }
    }
    int axis(const std::string& a) const
    {
        for (int k = 0; k < 3; ++k)
            if (prob.axes[static_cast<std::size_t>(k)] == a)
                return k;
        throw std::runtime_error("axis " + a);
    }
    std::map<std::string, double> values(const double* x) const
    {
        std::map<std::string, double> v;
        for (std::size_t i = 0; i < in_syms.size(); ++i)
            v[in_syms[i].get_name()] = x[i];
        return v;
    }
    nm::problem<double> numeric_problem(const double* x) const
    {
        const auto v = values(x);
        nm::problem<double> q;
        q.dimension = prob.dimension;
        q.restitution = eval(prob.restitution, v);
        for (const impactgen::body& b : prob.bodies) {
            nm::body<double> nb;
            nb.infinite_mass = b.infinite_mass;
            nb.particle = b.particle;
            nb.mass = b.infinite_mass ? 0.0 : eval(b.mass, v);
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    nb.inertia(r, c) = eval(b.inertia[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)], v);
            nb.position = evalv(b.position, v);
            nb.velocity = evalv(b.velocity, v);
            nb.angular_velocity = evalv(b.angular_velocity, v);
            q.bodies.push_back(nb);
        }
        q.body1 = prob.contact().body1;
        q.body2 = prob.contact().body2;
        q.point = evalv(prob.contact().point, v);
        q.normal = evalv(prob.contact().normal, v);
        q.friction = eval(prob.contact().friction(), v);
        for (const impactgen::pivot& pv : prob.pivots)
            q.pivots.push_back({pv.body, evalv(pv.point, v)});
        return q;
    }
};

const class_model& model(const std::string& name)
{
    static std::map<std::string, std::unique_ptr<class_model>> all;
    auto it = all.find(name);
    if (it == all.end())
        for (const fclass& c : classes())
            if (c.name == name)
                it = all.emplace(name, std::make_unique<class_model>(c)).first;
    return *it->second;
}

// ---------------------------------------------------------------------------
// Inputs

class sampler {
public:
    explicit sampler(unsigned s) : g_(s) {}
    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(g_); }
    double log_uniform(double lo, double hi) { return std::pow(10.0, uniform(lo, hi)); }
    bool chance(double p) { return uniform(0, 1) < p; }

    /// Inputs by name for the class; mu as drawn (the caller may move it to the boundary).
    std::vector<double> draw(const fclass& c)
    {
        std::vector<double> x(static_cast<std::size_t>(c.n_in), 0.0);
        std::map<std::string, double> mass;
        for (int i = 0; i < c.n_in; ++i) {
            const std::string n = c.in_names[i];
            if (n[0] == 'm' && n != "mu")
                mass[n.substr(1)] = x[static_cast<std::size_t>(i)] = log_uniform(-3, 3);
        }
        std::map<std::string, std::array<double, 6>> tensor; // body label -> tt tn tb nn nb bb
        for (int i = 0; i < c.n_in; ++i) {
            const std::string n = c.in_names[i];
            double& v = x[static_cast<std::size_t>(i)];
            if (n == "e") {
                const double k = uniform(0, 1);
                v = k < 0.05 ? 0.0 : k < 0.1 ? 1.0 : uniform(0, 1);
            } else if (n == "mu") {
                const double k = uniform(0, 1);
                v = k < 0.1 ? log_uniform(-4, 0) : uniform(0, 2);
            } else if (n[0] == 'm') {
            } else if (n == "R" || n == "l") {
                v = log_uniform(-2, 0);
            } else if (n[0] == 'I' && n.find('_') == std::string::npos) {
                // I1, I2 (planar) or a diagonal entry Ixx (the one body's mass)
                const double s = uniform(0.1, 1);
                v = (mass.count(n.substr(1)) ? mass.at(n.substr(1)) : mass.begin()->second) * s * s * uniform(0.1, 1);
            } else if (n[0] == 'I') {
                const std::string label = n.substr(1, n.find('_') - 1);
                if (!tensor.count(label))
                    tensor[label] = spd(mass.at(label));
                const std::string ax = n.substr(n.find('_') + 1);
                const char* order[6] = {"tt", "tn", "tb", "nn", "nb", "bb"};
                for (int k = 0; k < 6; ++k)
                    if (ax == order[k])
                        v = tensor[label][static_cast<std::size_t>(k)];
            } else {
                v = uniform(-1, 1);
            }
        }
        return x;
    }

private:
    std::array<double, 6> spd(double m)
    {
        // m s^2 R diag(d) R^T with R from a random unit quaternion
        double q[4], l = 0;
        for (double& a : q) {
            a = uniform(-1, 1);
            l += a * a;
        }
        l = std::sqrt(l);
        for (double& a : q)
            a /= l;
        const double w = q[0], x = q[1], y = q[2], z = q[3];
        const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                                {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                                {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
        const double s = uniform(0.1, 1), d[3] = {uniform(0.2, 1), uniform(0.2, 1), uniform(0.2, 1)};
        double I[3][3];
        for (int r = 0; r < 3; ++r)
            for (int cc = 0; cc < 3; ++cc) {
                I[r][cc] = 0;
                for (int k = 0; k < 3; ++k)
                    I[r][cc] += R[r][k] * d[k] * R[cc][k];
                I[r][cc] *= m * s * s;
            }
        return {I[0][0], I[0][1], I[0][2], I[1][1], I[1][2], I[2][2]};
    }
    std::mt19937_64 g_;
};

struct run_result {
    int status = -1, regime = -1;
    std::vector<double> out;
};

run_result call(const fclass& c, const std::vector<double>& x)
{
    run_result r;
    r.out.assign(static_cast<std::size_t>(c.n_out), 0.0);
    r.status = c.fd(x.data(), r.out.data(), r.regime);
    return r;
}

/// Random inputs with approaching contact points (and one in eight near grazing).
std::vector<double> approaching(const fclass& c, sampler& s, bool grazing = true)
{
    for (;;) {
        std::vector<double> x = s.draw(c);
        run_result r = call(c, x);
        if (r.status == int(gen::friction_status::not_approaching)) {
            for (int i = 0; i < c.n_in; ++i) {
                const std::string n = c.in_names[i];
                if (n[0] == 'v' || n[0] == 'w')
                    x[static_cast<std::size_t>(i)] = -x[static_cast<std::size_t>(i)];
            }
            r = call(c, x);
        }
        if (r.status == int(gen::friction_status::not_approaching))
            continue;
        if (grazing && s.chance(0.125)) {
            // u_n moves one for one with body 2's normal velocity (the normal is (0, 1, 0)).
            const int un = index_of(c.out_names, c.n_out, "approach_velocity");
            int vn = index_of(c.in_names, c.n_in, "v_n2");
            if (vn < 0)
                vn = index_of(c.in_names, c.n_in, "v_n");
            if (vn < 0) // a problem file: its normal is not the n axis
                return x;
            const double u = r.out[static_cast<std::size_t>(un)];
            double size = 0;
            for (int i = 0; i < c.n_in; ++i)
                if (c.in_names[i][0] == 'v')
                    size = std::max(size, std::fabs(x[static_cast<std::size_t>(i)]));
            x[static_cast<std::size_t>(vn)] += -std::max(size, 1e-3) * s.log_uniform(-12, -4) - u;
        }
        return x;
    }
}

/// mu* = |F| / N of the stick candidate (the header's answer with mu large, when it sticks).
bool critical_mu(const fclass& c, std::vector<double> x, double& mu_star)
{
    const int mu = index_of(c.in_names, c.n_in, "mu");
    x[static_cast<std::size_t>(mu)] = 1e6;
    run_result r = call(c, x);
    if (r.status != ok || r.regime != stick)
        return false;
    const int N = index_of(c.out_names, c.n_out, "normal_impulse");
    double F2 = 0;
    for (int k = 0; k < c.n_out; ++k)
        if (std::string(c.out_names[k]).rfind("tangential_impulse_", 0) == 0)
            F2 += r.out[static_cast<std::size_t>(k)] * r.out[static_cast<std::size_t>(k)];
    mu_star = std::sqrt(F2) / r.out[static_cast<std::size_t>(N)];
    return mu_star > 0 && std::isfinite(mu_star);
}

// ---------------------------------------------------------------------------
// The law from the outputs alone: restitution, cone, stick or slide.

struct law_check {
    double worst = 0;
    std::string what;
};

double check_law(const class_model& m, const std::vector<double>& x, const run_result& r, double kappa, std::string& what)
{
    const fclass& c = *m.fc;
    const nm::problem<double> p = m.numeric_problem(x.data());
    std::vector<nm::vec<double>> v, w;
    for (const auto& b : p.bodies) {
        v.push_back(b.velocity);
        w.push_back(b.angular_velocity);
    }
    double N = 0;
    nm::vec<double> F = nm::vec<double>::Zero();
    for (int k = 0; k < c.n_out; ++k) {
        const auto& o = m.outs[static_cast<std::size_t>(k)];
        const double val = r.out[static_cast<std::size_t>(k)];
        switch (o.kind) {
        case class_model::out_ref::velocity: v[o.body][o.axis] = val; break;
        case class_model::out_ref::angular: w[o.body][o.axis] = val; break;
        case class_model::out_ref::normal: N = val; break;
        case class_model::out_ref::tangential: F[o.axis] = val; break;
        default: break;
        }
    }
    auto point = [&](std::size_t i, const nm::vec<double>& vi, const nm::vec<double>& wi) {
        const auto& b = p.bodies[i];
        return nm::vec<double>(vi + ((b.infinite_mass || !b.particle) ? nm::vec<double>(wi.cross(p.point - b.position))
                                                                      : nm::vec<double>::Zero()));
    };
    const nm::vec<double> n = p.normal.normalized();
    const nm::vec<double> u = point(p.body2, p.bodies[p.body2].velocity, p.bodies[p.body2].angular_velocity) -
                              point(p.body1, p.bodies[p.body1].velocity, p.bodies[p.body1].angular_velocity);
    const nm::vec<double> u1 = point(p.body2, v[p.body2], w[p.body2]) - point(p.body1, v[p.body1], w[p.body1]);
    // Scales: velocities V, impulse P; the velocity an impulse gives the contact points on its own.
    double V = std::max(u.norm(), u1.norm());
    for (std::size_t i : {p.body1, p.body2}) {
        V = std::max(V, (point(i, v[i], w[i]) - point(i, p.bodies[i].velocity, p.bodies[i].angular_velocity)).norm());
        V = std::max(V, v[i].norm());
    }
    const double P = std::hypot(N, F.norm());
    double worst = 0;
    auto note = [&](double x, const char* label) {
        if (x > worst) {
            worst = x;
            what = label;
        }
    };
    note(std::fabs(u1.dot(n) + p.restitution * u.dot(n)) / V, "restitution");
    note(std::fabs(F.dot(n)) / std::max(P, 1e-300), "P_t . n");
    note(std::max(0.0, F.norm() - p.friction * N) / std::max(P, 1e-300), "cone");
    const nm::vec<double> ut = u1 - u1.dot(n) * n;
    if (r.regime == stick)
        note(ut.norm() / V, "stick: u'_t");
    if (r.regime == slide) {
        // F = -mu N u'_t / |u'_t| (within the rounding of u'_t)
        note((F.norm() - p.friction * N) / std::max(P, 1e-300) * (F.norm() < p.friction * N ? -1.0 : 1.0), "slide: |F| = mu N");
        // F against the direction of u'_t, less what the rounding of u'_t (computed from the
        // output velocities: an error of a few eps times the largest of them, spins times
        // lever arms included) does to that direction when u'_t is small (near stick).
        double noise = 0;
        for (std::size_t i : {p.body1, p.body2}) {
            noise = std::max(noise, v[i].norm());
            if (!p.bodies[i].particle || p.bodies[i].infinite_mass)
                noise = std::max(noise, w[i].norm() * (p.point - p.bodies[i].position).norm());
        }
        // (An error of the sliding angle of eps kappa moves u'_t by about that times the
        // velocities the friction impulse makes, which near stick is all of u'_t's direction.)
        if (ut.norm() > 0)
            note(std::max(0.0, (F + p.friction * N * ut.normalized()).norm() / std::max(P, 1e-300) -
                                   1e3 * std::numeric_limits<double>::epsilon() * std::max(kappa, 1.0) * std::max(noise, V) / ut.norm()),
                 "slide: F against u'_t");
    }
    if (r.regime == smooth)
        note(F.norm() / std::max(P, 1e-300), "smooth: F = 0");
    return worst;
}

// How much the answer amplifies the rounding of its inputs: the stick candidate solves
// K P = -(u + e u_n n) (condition number of K in the contact frame); a slide divides by
// D = n.K(n - mu d), whose terms are |K_nn| + mu |K_nt| (D near 0: the strong coupling
// of normal and tangential motion that makes the law lose its solution).
double conditioning(const class_model& m, const std::vector<double>& x, const run_result& r)
{
    const nm::problem<double> p = m.numeric_problem(x.data());
    const nm::friction_contact<double> fc(p);
    const int k = 1 + fc.tangents;
    Eigen::MatrixXd W = fc.W.topLeftCorner(k, k);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(W);
    // (no stick candidate: K is singular, and no answer solves a system in it)
    double kappa = m.has_stick ? svd.singularValues()(0) / svd.singularValues()(k - 1) : 1.0;
    if (r.regime == slide) {
        const fclass& c = *m.fc;
        nm::vec<double> F = nm::vec<double>::Zero();
        for (int i = 0; i < c.n_out; ++i)
            if (m.outs[static_cast<std::size_t>(i)].kind == class_model::out_ref::tangential)
                F[m.outs[static_cast<std::size_t>(i)].axis] = r.out[static_cast<std::size_t>(i)];
        const nm::vec<double> d = -F.normalized();
        const double dt1 = d.dot(fc.t1), dt2 = d.dot(fc.t2);
        const double D = fc.W(0, 0) - fc.mu * (fc.W(0, 1) * dt1 + fc.W(0, 2) * dt2);
        const double terms = std::fabs(fc.W(0, 0)) + fc.mu * std::hypot(fc.W(0, 1), fc.W(0, 2));
        kappa = std::max(kappa, terms / std::fabs(D));
        if (fc.tangents == 2) {
            // The sliding angle is a root of g: rounding of g (relative to its size) moves it
            // by that over |g'| there.
            const double th = std::atan2(dt2, dt1), h = 1e-6;
            double gmax = 0;
            for (int k = 0; k < 64; ++k)
                gmax = std::max(gmax, std::fabs(nm::detail::slide_residual(fc, 2 * 3.141592653589793 * k / 64)));
            const double dg = (nm::detail::slide_residual(fc, th + h) - nm::detail::slide_residual(fc, th - h)) / (2 * h);
            kappa = std::max(kappa, gmax / std::fabs(dg));
        }
    }
    return kappa;
}

// A sliding direction (a root of g) whose normal response D = n.K(n - mu d) is within
// 1e-7 of 0 relative to its terms: the normal impulse -(1 + e) u_n / D of that slide is a
// ratio of two small numbers (near grazing), its conditions undecidable in double.
bool degenerate_slide(const class_model& m, const std::vector<double>& x)
{
    const nm::problem<double> p = m.numeric_problem(x.data());
    const nm::friction_contact<double> fc(p);
    if (fc.tangents != 2)
        return false;
    const int N = 3600;
    const double two_pi = 2 * 3.141592653589793;
    const double terms = std::fabs(fc.W(0, 0)) + fc.mu * std::hypot(fc.W(0, 1), fc.W(0, 2));
    double a = 0, ga = nm::detail::slide_residual(fc, a);
    for (int k = 1; k <= N; ++k) {
        const double b = two_pi * k / N, gb = nm::detail::slide_residual(fc, b);
        if ((ga < 0) != (gb < 0)) {
            double lo = a, hi = b, glo = ga;
            for (int it = 0; it < 60; ++it) {
                const double mid = (lo + hi) / 2, gm = nm::detail::slide_residual(fc, mid);
                if ((gm < 0) == (glo < 0)) {
                    lo = mid;
                    glo = gm;
                } else {
                    hi = mid;
                }
            }
            const double th = (lo + hi) / 2;
            const double D = fc.W(0, 0) - fc.mu * (fc.W(0, 1) * std::cos(th) + fc.W(0, 2) * std::sin(th));
            if (std::fabs(D) < 1e-7 * terms)
                return true;
        }
        a = b;
        ga = gb;
    }
    return false;
}

// The same for either sliding direction of a planar contact (D = K_nn -+ mu K_nt), and
// degenerate_slide in 3-D.
bool degenerate_slide_any(const class_model& m, const std::vector<double>& x)
{
    const nm::problem<double> p = m.numeric_problem(x.data());
    const nm::friction_contact<double> fc(p);
    if (fc.tangents == 2)
        return degenerate_slide(m, x);
    const double terms = std::fabs(fc.W(0, 0)) + fc.mu * std::fabs(fc.W(0, 1));
    return std::fabs(fc.W(0, 0) - fc.mu * fc.W(0, 1)) < 1e-7 * terms || std::fabs(fc.W(0, 0) + fc.mu * fc.W(0, 1)) < 1e-7 * terms;
}

// ---------------------------------------------------------------------------
// Exact: select_regime at the inputs, every value substituted.

ex exact_of(double x)
{
    int e = 0;
    const double m = std::frexp(x, &e);
    const long long mant = static_cast<long long>(std::ldexp(m, 53));
    return numeric(mant) * pow(numeric(2), numeric(e - 53));
}

friction_solution substituted(const friction_solution& f, const lst& values)
{
    friction_solution r = f;
    auto sv = [&](impactgen::vec3& v) {
        for (ex& x : v)
            x = x.subs(values);
    };
    for (regime_case& c : r.cases) {
        for (impactgen::step& st : c.sol.steps)
            st.value = st.value.subs(values);
        for (auto& b : c.sol.after) {
            sv(b.velocity);
            sv(b.angular_velocity);
        }
        c.sol.normal_impulse = c.sol.normal_impulse.subs(values);
        for (auto& R : c.sol.pivot_impulses)
            sv(R);
        c.sol.energy_before = c.sol.energy_before.subs(values);
        c.sol.energy_after = c.sol.energy_after.subs(values);
        c.sol.energy_after_direct = c.sol.energy_after_direct.subs(values);
        c.sol.energy_lost = c.sol.energy_lost.subs(values);
        lst uv;
        for (const ex& rel : c.sol.unknown_values)
            uv.append(rel.lhs() == rel.rhs().subs(values));
        c.sol.unknown_values = uv;
        sv(c.impulse);
        sv(c.tangential_impulse);
        sv(c.direction);
        c.tangential_scalar = c.tangential_scalar.subs(values);
        c.sliding_speed = c.sliding_speed.subs(values);
        for (auto& rc : c.conditions)
            rc.value = rc.value.subs(values);
        c.angle_equation = c.angle_equation.subs(values);
    }
    r.mu = r.mu.subs(values);
    return r;
}

struct exact_answer {
    enum { ok, none, several, undecided } kind = undecided;
    int regime = -1;
    std::vector<double> out;
    std::string message;
};

// An output of the class (as the header names it) in a case's steps and the inputs.
ex output_expression(const class_model::out_ref& o, const regime_case& c)
{
    switch (o.kind) {
    case class_model::out_ref::velocity: return c.sol.after[o.body].velocity[o.axis];
    case class_model::out_ref::angular: return c.sol.after[o.body].angular_velocity[o.axis];
    case class_model::out_ref::normal: return c.sol.normal_impulse;
    case class_model::out_ref::tangential: return c.tangential_impulse[o.axis];
    case class_model::out_ref::approach: return c.sol.find(impactgen::step_role::approach_velocity)->sym;
    case class_model::out_ref::energy: return c.sol.energy_lost;
    case class_model::out_ref::pivot: return c.sol.pivot_impulses[o.body][o.axis];
    }
    throw std::runtime_error("output_expression: unknown output");
}

exact_answer exact(const class_model& m, const std::vector<double>& x, std::vector<numeric>* precise = nullptr,
                   long precise_digits = 90)
{
    lst values;
    for (std::size_t i = 0; i < m.in_syms.size(); ++i)
        values.append(m.in_syms[i] == exact_of(x[i]));
    exact_answer a;
    const ex mu = m.prob.contact().friction().subs(values);
    try {
        impactgen::derivation d = m.deriv; // the problem numeric (select_regime decides numeric problems only)
        d.prob = impactgen::substitute(m.prob, values);
        const regime_case c = impactgen::select_regime(d, substituted(m.fsol, values));
        a.kind = exact_answer::ok;
        a.regime = mu.is_zero() ? smooth : c.kind == impactgen::regime::stick ? stick : slide;
        // (precise: the values at `precise_digits`, for the CLN evaluation's self-check)
        const long saved = Digits;
        if (precise)
            Digits = precise_digits;
        for (const auto& o : m.outs) {
            const ex v = c.sol.expand_steps(output_expression(o, c)).evalf();
            if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real()) {
                Digits = saved;
                throw std::runtime_error("exact: not a real number");
            }
            a.out.push_back(ex_to<numeric>(v).to_double());
            if (precise)
                precise->push_back(ex_to<numeric>(v));
        }
        Digits = saved;
    } catch (const impactgen::input_error& e) {
        a.message = e.what();
        a.kind = a.message.find("has no solution") != std::string::npos      ? exact_answer::none
                 : a.message.find("more than one solution") != std::string::npos ? exact_answer::several
                                                                                 : exact_answer::undecided;
    }
    return a;
}

// Output scales: velocities (and the approach velocity) against the largest velocity in
// or out, impulses against |P|, the energy against the kinetic energy involved.
std::vector<double> scales(const class_model& m, const std::vector<double>& x, const std::vector<double>& out)
{
    const fclass& c = *m.fc;
    double V = 0, P = 0;
    for (int i = 0; i < c.n_in; ++i)
        if (c.in_names[i][0] == 'v' || c.in_names[i][0] == 'w')
            V = std::max(V, std::fabs(x[static_cast<std::size_t>(i)]));
    std::vector<double> s(out.size());
    double W = 0; // spins, which can be large for light or small bodies
    for (std::size_t k = 0; k < out.size(); ++k) {
        const auto& o = m.outs[k];
        if (o.kind == class_model::out_ref::velocity)
            V = std::max(V, std::fabs(out[k]));
        if (o.kind == class_model::out_ref::angular)
            W = std::max(W, std::fabs(out[k]));
        if (o.kind == class_model::out_ref::normal || o.kind == class_model::out_ref::tangential)
            P = std::hypot(P, out[k]);
    }
    const nm::problem<double> p = m.numeric_problem(x.data());
    // The impulse that changes the contact points' velocity by V: the rounding of the
    // relative velocity (eps V) becomes eps V / |K| in an impulse (near grazing N itself is
    // tiny), so impulses are compared against that too.
    const nm::friction_contact<double> fc(p);
    P = std::max(P, V / fc.compliance_scale);
    double T = 0;
    for (const auto& b : p.bodies)
        if (!b.infinite_mass)
            T += b.mass * b.velocity.squaredNorm() / 2 + (b.particle ? 0.0 : b.angular_velocity.dot(b.inertia * b.angular_velocity) / 2);
    for (std::size_t k = 0; k < out.size(); ++k) {
        switch (m.outs[k].kind) {
        case class_model::out_ref::velocity:
        case class_model::out_ref::approach: s[k] = V; break;
        case class_model::out_ref::angular: s[k] = std::max(W, V); break;
        case class_model::out_ref::normal:
        case class_model::out_ref::tangential:
        case class_model::out_ref::pivot: s[k] = P; break;
        case class_model::out_ref::energy: s[k] = std::max({T, std::fabs(out[k]), P * V}); break;
        }
        s[k] = std::max(s[k], 1e-300);
    }
    return s;
}

double worst_difference(const class_model& m, const std::vector<double>& x, const std::vector<double>& a,
                        const std::vector<double>& b, std::string& which)
{
    const std::vector<double> s = scales(m, x, b);
    double worst = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        const double d = std::fabs(a[k] - b[k]) / s[k];
        if (!(d <= worst)) {
            worst = d;
            which = m.fc->out_names[k];
        }
    }
    return worst;
}

// Tolerances (relative to the scales above): a closed form evaluated in double, about
// 100 operations deep, with K's condition number up to ~1e6 for the drawn mass ratios
// and lever arms, has relative errors of a few 1e-11 at worst; the sliding angle of a
// 3-D slide is refined to the rounding of the angle equation, whose coefficients carry
// the same errors.
const double exact_tol = 1e-8;
const double reference_tol = 1e-6; // the reference's own tolerance is sqrt(eps) ~ 1.5e-8 on the law, its impulses follow
const double law_tol = 1e-8;
const double eps = std::numeric_limits<double>::epsilon();

// The class's closed form compiled for CLN long floats (cln_closed_form.hpp), once.
cln_closed_form::evaluator& cln_evaluator(const class_model& m)
{
    static std::map<std::string, std::unique_ptr<cln_closed_form::evaluator>> all;
    auto it = all.find(m.fc->name);
    if (it == all.end()) {
        auto outputs = [&m](const regime_case& c) {
            std::vector<ex> r;
            for (const auto& o : m.outs)
                r.push_back(output_expression(o, c));
            return r;
        };
        // 60 decimal digits: 256-bit long floats (IMPACTGEN_FRICTION_CLN_DIGITS overrides: fewer
        // digits send more samples to select_regime)
        const long digits = env_or("IMPACTGEN_FRICTION_CLN_DIGITS", 60);
        it = all.emplace(m.fc->name, std::make_unique<cln_closed_form::evaluator>(m.fsol, m.in_syms, outputs, digits)).first;
    }
    return *it->second;
}

} // namespace

// ---------------------------------------------------------------------------

// What the comparisons of the header with the closed form (exact, or in CLN long floats)
// count over the samples the closed form answers with one regime and the header with ok.
struct closed_form_tally {
    long compared = 0, regime_checked = 0, ill_conditioned = 0;
    std::map<int, long> regimes;
    double worst = 0;
    std::string worst_what;
};

// One such sample: unless too ill-conditioned to compare (eps kappa > 1e-6), the same
// regime but within 1e-10 of the stick/slide boundary mu* (where both answers are the same
// impulse to within the rounding, checked next), and every output within 1e3 eps kappa
// (exact_tol at least) of the closed form's. `what` names the sample in messages.
void compare_with_closed_form(const class_model& m, const std::vector<double>& x, const run_result& r, const exact_answer& a,
                              const std::string& what, closed_form_tally& t)
{
    const fclass& c = *m.fc;
    const double kappa = conditioning(m, x, r);
    if (eps * kappa > 1e-6) {
        ++t.ill_conditioned;
        return;
    }
    ++t.regimes[a.regime];
    if (r.regime != a.regime) {
        const double mu = x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "mu"))];
        double mu_star = 0;
        ASSERT_TRUE(critical_mu(c, x, mu_star)) << what;
        EXPECT_LT(std::fabs(mu / mu_star - 1), 1e-10) << what << ": regime " << r.regime << ", closed form " << a.regime;
    } else {
        ++t.regime_checked;
    }
    std::string which;
    const double d = worst_difference(m, x, r.out, a.out, which);
    if (d > t.worst) {
        t.worst = d;
        t.worst_what = which;
    }
    EXPECT_LE(d, std::max(exact_tol, 1e3 * eps * kappa)) << what << ": " << which;
    if (d > 1e-9 && std::getenv("FRICTION_DEBUG"))
        std::cout << what << ": difference " << d << " (" << which << "), header regime " << r.regime << ", closed form "
                  << a.regime << ", conditioning " << kappa << "\n";
    ++t.compared;
}

class friction_class : public ::testing::TestWithParam<std::string> {};

TEST_P(friction_class, agrees_with_select_regime_exactly)
{
    const class_model& m = model(GetParam());
    const fclass& c = *m.fc;
    const bool three_d = m.prob.dimension == 3;
    const long n = count_for(c.name, "IMPACTGEN_FRICTION_EXACT", three_d ? 400 : 2000, 20000);
    sampler s(seed(1 + static_cast<unsigned>(c.n_in)));
    const int mu_i = index_of(c.in_names, c.n_in, "mu");
    long none = 0, several = 0, undecided = 0, status_agree = 0;
    closed_form_tally t;
    for (long i = 0; i < n; ++i) {
        std::vector<double> x = approaching(c, s);
        if (i % 10 == 1) { // near the stick/slide boundary
            double mu_star;
            if (critical_mu(c, x, mu_star))
                x[static_cast<std::size_t>(mu_i)] = mu_star * (1 + (s.chance(0.5) ? 1 : -1) * s.log_uniform(-9, -3));
        }
        const run_result r = call(c, x);
        const exact_answer a = exact(m, x);
        if (a.kind == exact_answer::none || a.kind == exact_answer::several) {
            (a.kind == exact_answer::none ? none : several)++;
            status_agree += r.status == (a.kind == exact_answer::none ? no_solution : ambiguous);
            continue;
        }
        if (a.kind == exact_answer::undecided) {
            if (undecided++ == 0)
                std::cout << c.name << ": select_regime: " << a.message << "\n";
            continue;
        }
        ASSERT_EQ(r.status, ok) << c.name << " sample " << i << ": exact regime " << a.regime;
        compare_with_closed_form(m, x, r, a, c.name + " sample " + std::to_string(i), t);
    }
    std::cout << c.name << " vs select_regime (exact): " << t.compared << " compared (" << t.regime_checked << " regimes equal; stick "
              << t.regimes[stick] << ", slide " << t.regimes[slide] << ", smooth " << t.regimes[smooth] << "), worst relative difference "
              << t.worst << " (" << t.worst_what << "); exact none " << none << ", several " << several << " (header agrees on "
              << status_agree << "), too close to call " << undecided << "; ill-conditioned (eps kappa > 1e-6) " << t.ill_conditioned << "\n";
    // Without a stick candidate the law has no solution for much of the range of mu (the rod
    // pinned at its centre: for mu > 1/2): half of the samples that have one are compared,
    // and the header says no_solution or ambiguous where select_regime does.
    if (!m.has_stick) {
        EXPECT_EQ(status_agree, none + several) << c.name;
        EXPECT_GT(t.compared, (n - none - several) / 2);
        EXPECT_GT(t.compared, n / 10);
        return;
    }
    EXPECT_GT(t.compared, n / 2);
}

// The closed form evaluated by CLN long floats (cln_closed_form.hpp): the samples of
// agrees_with_select_regime_exactly first (the same seed), then as many more as the count
// asks. Every condition of every case is decided from its 77-digit value and error bound,
// the sliding angles of a 3-D slide without closed form from the quartic in tan((phi -
// phi0)/2); the regime that holds and every output are compared with the header as the
// exact test compares them. A sample with a decision too close for that is decided by
// select_regime (exact) instead, and counted. The first samples are decided both ways:
// the same kind, regime and outputs to 1e-30 (and within the error bounds the evaluation
// gives them), a check of the fast path itself.
TEST_P(friction_class, agrees_with_the_closed_form_in_cln)
{
    const class_model& m = model(GetParam());
    const fclass& c = *m.fc;
    const long n = count_for(c.name, "IMPACTGEN_FRICTION_CLN", 30000, 400000);
    const long n_self = std::min(n, count_for(c.name, "IMPACTGEN_FRICTION_CLN_SELF", 300, 2000));
    sampler s(seed(1 + static_cast<unsigned>(c.n_in))); // agrees_with_select_regime_exactly's samples
    const int mu_i = index_of(c.in_names, c.n_in, "mu");
    const auto start = std::chrono::steady_clock::now();
    cln_closed_form::evaluator& ev = cln_evaluator(m);
    const double compile_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    long none = 0, several = 0, status_agree = 0, too_close = 0, undecided = 0, self_checked = 0, self_undecided = 0,
         degenerate = 0, status_differs = 0;
    closed_form_tally t;
    std::map<std::string, long> close_why;
    double worst_self = 0, worst_bound = 0;
    auto inputs_text = [&](const std::vector<double>& x) {
        std::ostringstream t;
        t.precision(17);
        for (int k = 0; k < c.n_in; ++k)
            t << (k ? ", " : "") << c.in_names[k] << " = " << x[static_cast<std::size_t>(k)];
        return t.str();
    };
    for (long i = 0; i < n; ++i) {
        std::vector<double> x = approaching(c, s);
        if (i % 10 == 1) { // near the stick/slide boundary
            double mu_star;
            if (critical_mu(c, x, mu_star))
                x[static_cast<std::size_t>(mu_i)] = mu_star * (1 + (s.chance(0.5) ? 1 : -1) * s.log_uniform(-9, -3));
        }
        const run_result r = call(c, x);
        const cln_closed_form::answer f = ev.solve(x.data());
        exact_answer a; // the closed form's answer: from the CLN evaluation, or select_regime when it is too close
        if (f.kind == cln_closed_form::answer::undecided) {
            ++too_close;
            ++close_why[f.why];
            a = exact(m, x);
        } else {
            a.kind = f.kind == cln_closed_form::answer::ok     ? exact_answer::ok
                     : f.kind == cln_closed_form::answer::none ? exact_answer::none
                                                               : exact_answer::several;
            a.regime = x[static_cast<std::size_t>(mu_i)] == 0 ? smooth : f.regime == impactgen::regime::stick ? stick : slide;
            a.out = f.out;
            if (i < n_self) {
                // Self-check: select_regime on the same inputs, its outputs at 90 digits.
                std::vector<numeric> precise;
                const exact_answer e = exact(m, x, &precise);
                if (e.kind == exact_answer::undecided) {
                    ++self_undecided;
                } else {
                    ++self_checked;
                    ASSERT_EQ(int(a.kind), int(e.kind)) << c.name << " sample " << i << ": " << inputs_text(x);
                    if (a.kind == exact_answer::ok) {
                        ASSERT_EQ(a.regime, e.regime) << c.name << " sample " << i << ": " << inputs_text(x);
                        const std::vector<double> sc = scales(m, x, e.out);
                        // a 3-D slide without closed form: select_regime's sliding angle is a 50-digit root
                        const bool angle = m.fsol.cases[f.case_index].needs_angle;
                        // 1e-30 at 256 bits (fewer bits: 1e15 roundings)
                        const double self_tol = std::max(1e-30, 1e15 * ev.code().unit());
                        for (std::size_t k = 0; k < e.out.size(); ++k) {
                            const cln::cl_R exact_k = cln::the<cln::cl_R>(precise[k].to_cl_N());
                            const double diff = cln::double_approx(cln::abs(f.values[k] - exact_k));
                            worst_self = std::max(worst_self, diff / sc[k]);
                            EXPECT_LE(diff, self_tol * sc[k]) << c.name << " sample " << i << ": " << c.out_names[k] << ": " << inputs_text(x);
                            if (!angle) {
                                // (select_regime's values at 90 digits: within 1e-85 of the scale)
                                worst_bound = std::max(worst_bound, diff / (f.errors[k] + 1e-85 * sc[k]));
                                EXPECT_LE(diff, f.errors[k] + 1e-85 * sc[k])
                                    << c.name << " sample " << i << ": " << c.out_names[k] << ": the error bound " << f.errors[k];
                            }
                        }
                    }
                }
            }
        }
        if (a.kind == exact_answer::none || a.kind == exact_answer::several) {
            (a.kind == exact_answer::none ? none : several)++;
            const int want = a.kind == exact_answer::none ? no_solution : ambiguous;
            status_agree += r.status == want;
            // otherwise only beside a slide with D ~ 0 (below)
            if (r.status != want && !degenerate_slide_any(m, x)) {
                ++status_differs;
                ADD_FAILURE() << c.name << " sample " << i << ": header " << gen::to_string(gen::friction_status(r.status))
                              << ", closed form " << (a.kind == exact_answer::none ? "none" : "several") << ": " << inputs_text(x);
            }
            continue;
        }
        if (a.kind == exact_answer::undecided) {
            if (undecided++ == 0)
                std::cout << c.name << ": select_regime: " << a.message << "\n";
            continue;
        }
        if (r.status != ok && std::getenv("FRICTION_DEBUG")) {
            const exact_answer e = exact(m, x);
            const nm::friction_answer<double> ref = nm::solve_friction(m.numeric_problem(x.data()));
            std::cout << c.name << " sample " << i << ": header " << gen::to_string(gen::friction_status(r.status))
                      << "; CLN " << (f.kind == cln_closed_form::answer::ok ? "ok" : "too close") << " (real roots of g "
                      << f.real_roots << "); select_regime "
                      << (e.kind == exact_answer::ok ? "ok regime " + std::to_string(e.regime) : e.message) << "; reference "
                      << nm::friction_status_name(ref.status) << " (" << ref.candidates.size() << " candidates)\n"
                      << ev.describe(x.data());
        }
        if (r.status != ok && degenerate_slide_any(m, x)) {
            // a slide with D = n.K(n - mu d) within 1e-7 of 0 relative to its terms (its N a
            // ratio of two small numbers next to grazing): whether it holds is not decided in
            // double, so the header may find none or two (as the Eigen test counts it; the
            // exact test, on fewer samples, meets none)
            ++degenerate;
            continue;
        }
        ASSERT_EQ(r.status, ok) << c.name << " sample " << i << ": closed form regime " << a.regime << ": " << inputs_text(x);
        compare_with_closed_form(m, x, r, a, c.name + " sample " + std::to_string(i) + " (" + inputs_text(x) + ")", t);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << c.name << " vs the closed form in CLN long floats (" << ev.code().bits() << " bits, " << ev.code().size()
              << " nodes): " << n << " samples, " << t.compared << " compared (" << t.regime_checked << " regimes equal; stick "
              << t.regimes[stick] << ", slide " << t.regimes[slide] << ", smooth " << t.regimes[smooth] << "), worst relative difference "
              << t.worst << " (" << t.worst_what << "); none " << none << ", several " << several << " (header agrees on "
              << status_agree << ", differs apart from D ~ 0 on " << status_differs << "); too close for the long floats " << too_close << " (decided by select_regime; too close "
              << "for it too " << undecided << "); ill-conditioned (eps kappa > 1e-6) " << t.ill_conditioned << ", header not ok beside a "
              << "slide with D within 1e-7 of 0 " << degenerate << "; self-check against "
              << "select_regime on " << self_checked << " (undecided there " << self_undecided << "), worst relative difference "
              << worst_self << ", worst difference / error bound " << worst_bound << "; " << seconds << " s (compiling "
              << compile_seconds << " s)\n";
    for (const auto& [why, k] : close_why)
        std::cout << "  too close: " << why << ": " << k << "\n";
    // (no stick candidate: the law has no solution for much of the range of mu)
    EXPECT_GT(t.compared, (m.has_stick ? n : n - none - several) / 2);
    EXPECT_LE(too_close, n / 100 + 5); // the fast path decides almost every sample
}

// The header's outputs as the Eigen reference gives them, in the header's order.
std::vector<double> reference_outputs(const class_model& m, const nm::problem<double>& p,
                                      const nm::friction_answer<double>& ref)
{
    const nm::vec<double> n_hat = p.normal.normalized();
    std::vector<double> expect(m.outs.size());
    for (std::size_t k = 0; k < m.outs.size(); ++k) {
        const auto& o = m.outs[k];
        switch (o.kind) {
        case class_model::out_ref::velocity: expect[k] = ref.velocity[o.body][o.axis]; break;
        case class_model::out_ref::angular: expect[k] = ref.angular_velocity[o.body][o.axis]; break;
        case class_model::out_ref::normal: expect[k] = ref.normal_impulse; break;
        case class_model::out_ref::tangential: expect[k] = ref.tangential_impulse[o.axis]; break;
        case class_model::out_ref::approach: expect[k] = ref.relative_velocity_before.dot(n_hat); break;
        case class_model::out_ref::energy:
            expect[k] = nm::kinetic_energy(p) - nm::kinetic_energy(p, ref.velocity, ref.angular_velocity);
            break;
        case class_model::out_ref::pivot: expect[k] = ref.pivot_impulses[o.body][o.axis]; break;
        }
    }
    return expect;
}

TEST_P(friction_class, agrees_with_the_eigen_reference)
{
    const class_model& m = model(GetParam());
    const fclass& c = *m.fc;
    const long n = count_for(c.name, "IMPACTGEN_FRICTION_SAMPLES", 30000, 400000);
    sampler s(seed(2 + static_cast<unsigned>(c.n_in)));
    const int mu_i = index_of(c.in_names, c.n_in, "mu");
    long compared = 0, regime_checked = 0, ref_other = 0, status_same = 0, our_other = 0, law_checked = 0, ill_conditioned = 0;
    std::map<std::string, long> mismatches;
    double worst = 0, worst_law = 0;
    std::string worst_what, worst_law_what;
    for (long i = 0; i < n; ++i) {
        std::vector<double> x = approaching(c, s);
        if (i % 10 == 1) {
            double mu_star;
            if (critical_mu(c, x, mu_star))
                x[static_cast<std::size_t>(mu_i)] = mu_star * (1 + (s.chance(0.5) ? 1 : -1) * s.log_uniform(-9, -3));
        }
        const run_result r = call(c, x);
        // Conditioning: eps kappa is the relative error the rounding of the inputs alone
        // causes; beyond 1e-6 (D of a slide within 1e-10 of 0: the strong coupling that
        // makes the law lose or multiply its solutions) a double answer is not worth checking.
        const double kappa = r.status == ok ? conditioning(m, x, r) : 0;
        if (eps * kappa > 1e-6) {
            ++ill_conditioned;
            continue;
        }
        if (r.status == ok) {
            std::string what;
            const double l = check_law(m, x, r, kappa, what);
            if (l > worst_law) {
                worst_law = l;
                worst_law_what = what;
            }
            EXPECT_LE(l, std::max(law_tol, 1e3 * eps * kappa)) << c.name << " sample " << i << ": " << what << ", conditioning " << kappa;
            if (l > law_tol && std::getenv("FRICTION_DEBUG")) {
                std::cout << "conditioning " << kappa << "\n";
                for (int k = 0; k < c.n_in; ++k)
                    std::cout << c.in_names[k] << " = " << x[static_cast<std::size_t>(k)] << "\n";
                for (int k = 0; k < c.n_out; ++k)
                    std::cout << c.out_names[k] << ": " << r.out[static_cast<std::size_t>(k)] << "\n";
                std::cout << "regime " << r.regime << "\n";
            }
            ++law_checked;
        } else {
            ++our_other;
        }
        const nm::problem<double> p = m.numeric_problem(x.data());
        const nm::friction_answer<double> ref = nm::solve_friction(p);
        if (ref.status != nm::friction_status::ok) {
            if (std::getenv("FRICTION_DEBUG"))
                std::cout << c.name << " sample " << i << ": reference " << nm::friction_status_name(ref.status) << " ("
                          << ref.candidates.size() << " candidates), header " << gen::to_string(gen::friction_status(r.status))
                          << " regime " << r.regime << ", mu " << p.friction << "\n";
            ++ref_other;
            status_same += (ref.status == nm::friction_status::no_solution && r.status == no_solution) ||
                           (ref.status == nm::friction_status::ambiguous && r.status == ambiguous);
            continue;
        }
        // Away from the regime boundaries the reference's regime is clear: stick strictly
        // inside the cone, slide with u'_t clearly non-zero; then the header must agree.
        const double mu = p.friction;
        const double V = std::max(ref.relative_velocity_before.norm(), 1e-300);
        const double Pt = ref.tangential_impulse.norm(), Pn = ref.normal_impulse;
        const nm::vec<double> n_hat = p.normal.normalized();
        const nm::vec<double> ut = ref.relative_velocity_after - ref.relative_velocity_after.dot(n_hat) * n_hat;
        const bool clear = mu == 0 || (ref.regime == nm::friction_regime::stick && Pt < (1 - 1e-6) * mu * Pn) ||
                           (ref.regime == nm::friction_regime::slide && ut.norm() > 1e-6 * V);
        if (!clear) {
            // Not compared, but an answer all the same: where the header and select_regime
            // (exactly) find no solution, the reference finds none either.
            if (r.status == no_solution && !degenerate_slide(m, x) && exact(m, x).kind == exact_answer::none)
                ++mismatches["reference ok on a regime boundary, header no solution, select_regime none"];
            continue;
        }
        if (r.status != ok) {
            if (std::getenv("FRICTION_DEBUG")) {
                const exact_answer a = exact(m, x);
                std::cout << c.name << " sample " << i << ": reference ok (regime " << int(ref.regime) << "), header "
                          << gen::to_string(gen::friction_status(r.status)) << "; exact: "
                          << (a.kind == exact_answer::ok ? "ok regime " + std::to_string(a.regime) : a.message) << "\n";
                std::cout.precision(17);
                for (int k = 0; k < c.n_in; ++k)
                    std::cout << x[static_cast<std::size_t>(k)] << (k + 1 < c.n_in ? ", " : "\n");
                std::cout.precision(6);
            }
            ++mismatches["reference ok, header " + std::string(gen::to_string(gen::friction_status(r.status))) +
                         (degenerate_slide(m, x) ? " (a slide with D within 1e-7 of 0)" : "")];
            continue;
        }
        const int ref_regime = ref.regime == nm::friction_regime::stick ? stick : ref.regime == nm::friction_regime::slide ? slide : smooth;
        EXPECT_EQ(r.regime, ref_regime) << c.name << " sample " << i;
        ++regime_checked;
        const std::vector<double> expect = reference_outputs(m, p, ref);
        std::string which;
        const double d = worst_difference(m, x, r.out, expect, which);
        if (d > worst) {
            worst = d;
            worst_what = which;
        }
        EXPECT_LE(d, std::max(reference_tol, 1e3 * eps * kappa)) << c.name << " sample " << i << ": " << which;
        if (d > reference_tol && std::getenv("FRICTION_DEBUG")) {
            for (int k = 0; k < c.n_in; ++k)
                std::cout << c.in_names[k] << " = " << x[static_cast<std::size_t>(k)] << "\n";
            for (int k = 0; k < c.n_out; ++k)
                std::cout << c.out_names[k] << ": " << r.out[static_cast<std::size_t>(k)] << " ref " << expect[static_cast<std::size_t>(k)] << "\n";
            std::cout << "regime " << r.regime << " ref " << int(ref.regime) << " candidates " << ref.candidates.size() << "\n";
        }
        ++compared;
    }
    std::cout << c.name << " vs numeric/friction_solver.hpp: " << n << " samples, " << compared << " compared (regime checked "
              << regime_checked << "), worst relative difference " << worst << " (" << worst_what << "); the law from the header's "
              << "outputs on " << law_checked << " answers, worst residual " << worst_law << " (" << worst_law_what << "); reference "
              << "not ok on " << ref_other << " (header the same status on " << status_same << "), header not ok on " << our_other
              << "; ill-conditioned (eps kappa > 1e-6), not compared: " << ill_conditioned << "\n";
    for (const auto& [what, k] : mismatches)
        std::cout << "  " << what << ": " << k << "\n";
    // Where the reference finds exactly one clear solution the header finds it too, but
    // for the 3-D cases the reference's scan or tolerances decide otherwise (a handful).
    // A slide with D ~ 0 next to grazing (N = -(1 + e) u_n / D of two small numbers) can
    // hold or not within rounding: those are counted apart; any other disagreement is a
    // failure (the body pinned at a point and struck by an immovable one included: where
    // the law has no solution the reference must not answer ok).
    long total_mismatch = 0;
    for (const auto& [what, k] : mismatches)
        if (what.find("D within") == std::string::npos)
            total_mismatch += k;
    EXPECT_EQ(total_mismatch, 0) << c.name;
    // (no stick candidate: the law has no solution for much of the range of mu; see above)
    EXPECT_GT(compared, (m.has_stick ? n : n - ref_other) / 2);
}

// A normal given as inputs takes every direction: the world axes and their negatives (a box
// on a z-up floor: the formula basis e_t = (z - n_z n)/|...| divided by 0 there and the
// header returned overflow), directions within 1e-300 of an axis, lengths other than 1, and
// random directions; the unit-normal header the same with unit normals. Each answer is
// checked against the law from the header's own outputs and against the Eigen reference.
TEST(friction_normals, every_direction_of_a_normal_given_as_inputs)
{
    const class_model& m = model("tilted-box-friction.json");
    const fclass& c = *m.fc;
    const int nx = index_of(c.in_names, c.n_in, "nx"), ny = index_of(c.in_names, c.n_in, "ny"),
              nz = index_of(c.in_names, c.n_in, "nz");
    ASSERT_GE(nx, 0);
    ASSERT_GE(ny, 0);
    ASSERT_GE(nz, 0);
    std::vector<std::array<double, 3>> directions;
    for (int a = 0; a < 3; ++a)
        for (double sgn : {1.0, -1.0}) {
            std::array<double, 3> n{0, 0, 0};
            n[static_cast<std::size_t>(a)] = sgn;
            directions.push_back(n);
            for (double tiny : {1e-300, -1e-300, 1e-12}) {
                std::array<double, 3> t = n;
                t[static_cast<std::size_t>((a + 1) % 3)] = tiny;
                directions.push_back(t);
            }
            std::array<double, 3> longer = n;
            longer[static_cast<std::size_t>(a)] *= 2.5;
            directions.push_back(longer);
            std::array<double, 3> shorter = n;
            shorter[static_cast<std::size_t>(a)] *= 1e-3;
            directions.push_back(shorter);
        }
    sampler s(seed(77));
    for (int k = 0; k < 40; ++k)
        directions.push_back({s.uniform(-1, 1), s.uniform(-1, 1), s.uniform(-1, 1)});
    long compared = 0;
    for (std::size_t k = 0; k < directions.size(); ++k) {
        for (int trial = 0; trial < 20; ++trial) {
            std::vector<double> x = s.draw(c);
            for (int a = 0; a < 3; ++a)
                x[static_cast<std::size_t>((a == 0 ? nx : a == 1 ? ny : nz))] = directions[k][static_cast<std::size_t>(a)];
            run_result r = call(c, x);
            if (r.status == int(gen::friction_status::not_approaching)) {
                for (int i = 0; i < c.n_in; ++i)
                    if (c.in_names[i][0] == 'v' || c.in_names[i][0] == 'w')
                        x[static_cast<std::size_t>(i)] = -x[static_cast<std::size_t>(i)];
                r = call(c, x);
            }
            if (r.status == int(gen::friction_status::not_approaching))
                continue;
            const std::string where = "n = (" + std::to_string(directions[k][0]) + ", " + std::to_string(directions[k][1]) +
                                      ", " + std::to_string(directions[k][2]) + ") trial " + std::to_string(trial);
            // no_solution and ambiguous are answers of the law (strong coupling of the normal and
            // tangential motion: a random box can have them); overflow, singular or
            // invalid_normal are not.
            if (r.status == no_solution || r.status == ambiguous)
                continue;
            ASSERT_EQ(r.status, ok) << where << ": " << gen::to_string(gen::friction_status(r.status));
            const double kappa = conditioning(m, x, r);
            std::string what;
            EXPECT_LE(check_law(m, x, r, kappa, what), std::max(law_tol, 1e3 * eps * kappa)) << where << ": " << what;
            const nm::problem<double> p = m.numeric_problem(x.data());
            const nm::friction_answer<double> ref = nm::solve_friction(p);
            if (ref.status != nm::friction_status::ok || eps * kappa > 1e-6)
                continue;
            const std::vector<double> expect = reference_outputs(m, p, ref);
            std::string which;
            EXPECT_LE(worst_difference(m, x, r.out, expect, which), std::max(reference_tol, 1e3 * eps * kappa)) << where << ": " << which;
            ++compared;
            break;
        }
    }
    // Every direction found an approaching sample within 20 draws, and nearly every one a
    // well-conditioned reference answer to compare with.
    EXPECT_GE(compared, static_cast<long>(directions.size()) * 9 / 10);
    // The unit-normal header: the unit axes (and their negatives) as given, no normalisation.
    for (int a = 0; a < 3; ++a)
        for (double sgn : {1.0, -1.0}) {
            double in[gen::tilted_box_friction_unit_input_count];
            for (int i = 0; i < gen::tilted_box_friction_unit_input_count; ++i) {
                const std::string name = gen::tilted_box_friction_unit_input_names[i];
                in[i] = name == "e" ? 0.5 : name == "mu" ? 0.6 : name == "m" ? 2 : name[0] == 'I' ? 0.3 : 0.1 * (i % 5) - 0.2;
                if (name == std::string("n") + "xyz"[a])
                    in[i] = sgn;
                else if (name.size() == 2 && name[0] == 'n')
                    in[i] = 0;
                if (name == std::string("v") + "xyz"[a])
                    in[i] = -sgn; // approaching: body 2 moves against n
                if (name == std::string("") + "xyz"[a])
                    in[i] = sgn * 0.4; // the centre of mass on body 2's side of the contact
            }
            gen::tilted_box_friction_unit_result<double> r;
            EXPECT_EQ(gen::tilted_box_friction_unit(in, r), gen::friction_status::ok) << "unit normal along axis " << a << " sign " << sgn;
            EXPECT_GT(r.normal_impulse, 0.0);
        }
}

TEST_P(friction_class, continuous_across_the_stick_slide_boundary)
{
    const class_model& m = model(GetParam());
    const fclass& c = *m.fc;
    const long n = count_for(c.name, "IMPACTGEN_FRICTION_BOUNDARY", m.prob.dimension == 3 ? 150 : 300, 3000);
    sampler s(seed(3 + static_cast<unsigned>(c.n_in)));
    const int mu_i = index_of(c.in_names, c.n_in, "mu");
    long checked = 0, exact_checked = 0;
    double worst_jump = 0;
    if (!m.has_stick) {
        // No stick candidate (K singular): no boundary to cross, and the header never sticks.
        for (long i = 0; i < n; ++i) {
            std::vector<double> x = approaching(c, s, false);
            for (double mu : {1e-3, 0.1, 0.4, 1.0, 1e6}) {
                x[static_cast<std::size_t>(mu_i)] = mu;
                const run_result r = call(c, x);
                EXPECT_TRUE(r.status != ok || r.regime == slide) << c.name << " sample " << i << " mu " << mu;
                checked += r.status == ok;
            }
        }
        std::cout << c.name << ": no stick candidate; " << checked << " answers ok, each a slide\n";
        EXPECT_GT(checked, n / 4);
        return;
    }
    for (long i = 0; i < n; ++i) {
        std::vector<double> x = approaching(c, s, false);
        double mu_star;
        if (!critical_mu(c, x, mu_star) || mu_star > 1e3)
            continue;
        double lipschitz = -1; // the difference at the wider pair before
        for (double delta : {1e-3, 1e-6, 1e-9}) {
            std::vector<double> above = x, below = x;
            above[static_cast<std::size_t>(mu_i)] = mu_star * (1 + delta);
            below[static_cast<std::size_t>(mu_i)] = mu_star * (1 - delta);
            const run_result ra = call(c, above), rb = call(c, below);
            if (ra.status != ok || rb.status != ok)
                break; // another solution beside (ambiguous): no boundary to cross
            // Above mu* the stick candidate is inside the cone: the contact sticks; below it
            // slides, as decided exactly (select_regime, at the narrowest pair) ...
            EXPECT_EQ(ra.regime, stick) << c.name << " sample " << i << " delta " << delta;
            EXPECT_EQ(rb.regime, slide) << c.name << " sample " << i << " delta " << delta;
            if (delta == 1e-9) {
                const exact_answer eb = exact(m, below);
                if (eb.kind == exact_answer::ok) {
                    EXPECT_EQ(rb.regime, eb.regime) << c.name << " sample " << i;
                    ++exact_checked;
                }
            }
            // ... and the state is continuous: the difference of the two answers shrinks with
            // delta (by 1000 from one pair to the next when the answer is Lipschitz there; a
            // jump would not shrink at all): at least tenfold, to the rounding of the outputs.
            std::string which;
            const double jump = worst_difference(m, x, ra.out, rb.out, which);
            if (lipschitz >= 0)
                EXPECT_LE(jump, 0.1 * lipschitz + 1e-12) << c.name << " sample " << i << " delta " << delta << ": " << which;
            lipschitz = jump;
            worst_jump = std::max(worst_jump, jump / delta);
            ++checked;
        }
    }
    std::cout << c.name << ": " << checked << " pairs mu* (1 +- delta), delta 1e-3, 1e-6, 1e-9 (" << exact_checked
              << " of the narrowest decided by select_regime too): largest (change / scale) / delta " << worst_jump << "\n";
    EXPECT_GT(checked, n / 4);
}

TEST_P(friction_class, float_and_long_double_agree_with_double)
{
    const class_model& m = model(GetParam());
    const fclass& c = *m.fc;
    const long n = count_for(c.name, "IMPACTGEN_FRICTION_TYPES", 3000, 30000);
    sampler s(seed(4 + static_cast<unsigned>(c.n_in)));
    double worst_ld = 0, worst_f = 0;
    long compared_f = 0;
    for (long i = 0; i < n; ++i) {
        std::vector<double> x = approaching(c, s, false);
        const run_result r = call(c, x);
        if (r.status != ok)
            continue;
        std::vector<long double> xl(x.begin(), x.end()), ol(r.out.size());
        int rl = -1;
        ASSERT_EQ(c.fld(xl.data(), ol.data(), rl), ok) << c.name << " sample " << i;
        std::vector<double> old(ol.begin(), ol.end());
        std::string which;
        // long double differs from double by double's rounding (and, within it of a regime
        // boundary, by the regime: then both are the same impulse to that rounding).
        const double d = worst_difference(m, x, old, r.out, which);
        worst_ld = std::max(worst_ld, d);
        EXPECT_LE(d, exact_tol) << c.name << " sample " << i << ": " << which;
        // float on moderate problems (masses within 1e-1..1e1: float has 24 bits).
        bool moderate = true;
        for (int k = 0; k < c.n_in; ++k)
            if (c.in_names[k][0] == 'm' || c.in_names[k][0] == 'I')
                moderate = moderate && std::fabs(x[static_cast<std::size_t>(k)]) > 1e-2 && std::fabs(x[static_cast<std::size_t>(k)]) < 1e2;
        if (!moderate || rl != r.regime)
            continue;
        std::vector<float> xf(x.begin(), x.end()), of(r.out.size());
        int rf = -1;
        if (c.ff(xf.data(), of.data(), rf) != ok || rf != r.regime)
            continue; // a regime boundary within float's rounding
        std::vector<double> od(of.begin(), of.end());
        const double df = worst_difference(m, x, od, r.out, which);
        worst_f = std::max(worst_f, df);
        ++compared_f;
    }
    std::cout << c.name << ": long double vs double worst " << worst_ld << "; float vs double worst " << worst_f << " on " << compared_f
              << " moderate samples\n";
    // float: inputs rounded to 24 bits move the result by up to cond(K) 6e-8.
    EXPECT_LE(worst_f, 1e-2);
}

std::string param_name(const ::testing::TestParamInfo<std::string>& i)
{
    std::string n = i.param.substr(0, i.param.find(".json"));
    std::replace(n.begin(), n.end(), '-', '_');
    return n;
}
INSTANTIATE_TEST_SUITE_P(named, friction_class,
                         ::testing::Values("planar-friction", "ball-floor-friction", "noncentral-3d-friction"), param_name);
INSTANTIATE_TEST_SUITE_P(files, friction_class,
                         ::testing::Values("sphere-floor-3d.json", "rod-hinge-friction.json", "tilted-box-friction.json"), param_name);
INSTANTIATE_TEST_SUITE_P(pinned, friction_class,
                         ::testing::Values("pinned-rod-struck-symbolic.json", "pinned-plate-struck-3d.json"), param_name);

// No stick candidate: the rod pinned at its centre, struck at (1, 1/2) by a wall of infinite
// mass moving at (-1, 0) (e = 1/2, mu = 3/10) slides, with N = 5/4, the pivot's impulse
// (5/4, 3/8) and the rod's spin 3 (impactgen solve's answer); the header with e, mu and the
// wall's velocity as inputs the same there, and both agree with select_regime and the Eigen reference.
TEST(friction_pinned, a_pinned_rod_struck_by_an_immovable_wall_slides)
{
    gen::pinned_rod_struck_result<double> r;
    ASSERT_EQ(gen::pinned_rod_struck(r), gen::friction_status::ok);
    EXPECT_EQ(r.regime, gen::impact_regime::slide);
    EXPECT_DOUBLE_EQ(r.normal_impulse, 1.25);
    EXPECT_DOUBLE_EQ(r.R_x_rod, 1.25);
    EXPECT_DOUBLE_EQ(r.R_y_rod, 0.375);
    EXPECT_DOUBLE_EQ(r.w_z_rod, 3.0);
    EXPECT_DOUBLE_EQ(r.tangential_impulse_x, 0.0);
    EXPECT_DOUBLE_EQ(r.tangential_impulse_y, 0.375);
    EXPECT_DOUBLE_EQ(r.energy_lost, -0.375);
    double fixed[gen::pinned_rod_struck_output_count];
    gen::pinned_rod_struck_to_array(r, fixed);

    const class_model& m = model("pinned-rod-struck-symbolic.json");
    const fclass& c = *m.fc;
    ASSERT_FALSE(m.has_stick);
    ASSERT_EQ(c.n_out, gen::pinned_rod_struck_output_count);
    std::vector<double> x(static_cast<std::size_t>(c.n_in));
    x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "e"))] = 0.5;
    x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "mu"))] = 0.3;
    x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "vw"))] = -1;
    const run_result rs = call(c, x);
    ASSERT_EQ(rs.status, ok);
    EXPECT_EQ(rs.regime, slide);
    for (int k = 0; k < c.n_out; ++k)
        EXPECT_DOUBLE_EQ(rs.out[static_cast<std::size_t>(k)], fixed[k]) << c.out_names[k];
    const exact_answer a = exact(m, x);
    ASSERT_EQ(a.kind, exact_answer::ok) << a.message;
    EXPECT_EQ(a.regime, slide);
    std::string which;
    EXPECT_LE(worst_difference(m, x, rs.out, a.out, which), 1e-15) << which;
    const nm::friction_answer<double> ref = nm::solve_friction(m.numeric_problem(x.data()));
    ASSERT_EQ(ref.status, nm::friction_status::ok);
    EXPECT_EQ(ref.regime, nm::friction_regime::slide);
    EXPECT_NEAR(ref.normal_impulse, 1.25, 1e-12);
    EXPECT_NEAR(ref.angular_velocity[1][2], 3.0, 1e-12);
    EXPECT_NEAR(ref.pivot_impulses[0][0], 1.25, 1e-12);
    EXPECT_NEAR(ref.pivot_impulses[0][1], 0.375, 1e-12);
    // mu = 0: the smooth impact, N = -(1 + e) u_n / K_nn = 1/2; mu = 5: no regime holds.
    x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "mu"))] = 0;
    const run_result r0 = call(c, x);
    ASSERT_EQ(r0.status, ok);
    EXPECT_EQ(r0.regime, smooth);
    EXPECT_DOUBLE_EQ(r0.out[static_cast<std::size_t>(index_of(c.out_names, c.n_out, "normal_impulse"))], 0.5);
    x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "mu"))] = 5;
    EXPECT_EQ(call(c, x).status, no_solution);
    EXPECT_EQ(exact(m, x).kind, exact_answer::none);
}

// mu = 0: the smooth impact, as the smooth headers compute it.
TEST(friction_smooth, mu_zero_is_the_smooth_answer)
{
    const long n = count("IMPACTGEN_FRICTION_SMOOTH", 20000, 200000);
    sampler s(seed(5));
    double worst[3] = {0, 0, 0};
    for (const std::string name : {"planar-friction", "noncentral-3d-friction", "ball-floor-friction"}) {
        const class_model& m = model(name);
        const fclass& c = *m.fc;
        const int mu_i = index_of(c.in_names, c.n_in, "mu");
        const std::size_t which = name == "planar-friction" ? 0 : name == "noncentral-3d-friction" ? 1 : 2;
        for (long i = 0; i < n; ++i) {
            std::vector<double> x = approaching(c, s);
            x[static_cast<std::size_t>(mu_i)] = 0;
            const run_result r = call(c, x);
            ASSERT_EQ(r.status, ok) << name;
            EXPECT_EQ(r.regime, smooth);
            // the smooth inputs: the same without mu
            std::vector<double> xs;
            for (int k = 0; k < c.n_in; ++k)
                if (k != mu_i)
                    xs.push_back(x[static_cast<std::size_t>(k)]);
            std::map<std::string, double> smooth_out;
            if (which == 0) {
                gen::planar_result<double> sr;
                ASSERT_EQ(gen::planar(xs.data(), sr), gen::impact_status::ok);
                double a[gen::planar_output_count];
                gen::planar_to_array(sr, a);
                for (int k = 0; k < gen::planar_output_count; ++k)
                    smooth_out[gen::planar_output_names[k]] = a[k];
            } else if (which == 1) {
                gen::noncentral_3d_result<double> sr;
                ASSERT_EQ(gen::noncentral_3d(xs.data(), sr), gen::impact_status::ok);
                double a[gen::noncentral_3d_output_count];
                gen::noncentral_3d_to_array(sr, a);
                for (int k = 0; k < gen::noncentral_3d_output_count; ++k)
                    smooth_out[gen::noncentral_3d_output_names[k]] = a[k];
            } else {
                // the ball on the floor: N = -(1 + e) m v_n, no tangential impulse, v_t and w unchanged
                const double e = x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "e"))];
                const double mass = x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "m"))];
                const double vn = x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "v_n"))];
                smooth_out["normal_impulse"] = -(1 + e) * mass * vn;
                smooth_out["v_n_ball"] = -e * vn;
                smooth_out["v_t_ball"] = x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "v_t"))];
                smooth_out["w_b_ball"] = x[static_cast<std::size_t>(index_of(c.in_names, c.n_in, "w"))];
            }
            std::vector<double> expect(r.out.size(), 0.0);
            for (int k = 0; k < c.n_out; ++k) {
                const std::string on = c.out_names[k];
                if (smooth_out.count(on))
                    expect[static_cast<std::size_t>(k)] = smooth_out[on];
                else if (on.rfind("tangential_impulse_", 0) == 0 || which == 2)
                    expect[static_cast<std::size_t>(k)] = on.rfind("tangential_impulse_", 0) == 0 ? 0.0 : r.out[static_cast<std::size_t>(k)];
                else
                    FAIL() << name << ": no smooth output " << on;
                if (on.rfind("tangential_impulse_", 0) == 0)
                    EXPECT_EQ(r.out[static_cast<std::size_t>(k)], 0.0) << name;
            }
            std::string w;
            worst[which] = std::max(worst[which], worst_difference(m, x, r.out, expect, w));
            EXPECT_LE(worst[which], 1e-12) << name << " sample " << i << ": " << w;
        }
    }
    std::cout << "mu = 0 against the smooth answer: planar " << worst[0] << ", noncentral-3d " << worst[1] << ", ball-floor "
              << worst[2] << " (worst relative difference)\n";
}

// Statuses for inputs that make no impact, and the state unchanged.
TEST(friction_statuses, bad_inputs)
{
    for (const fclass& c : classes()) {
        if (is_case(c.name))
            continue; // (the named classes' input names below)
        sampler s(seed(6));
        const class_model& m = model(c.name);
        std::vector<double> x = approaching(c, s, false);
        auto expect_status = [&](std::vector<double> y, gen::friction_status want, const std::string& what) {
            run_result r = call(c, y);
            EXPECT_EQ(r.status, int(want)) << c.name << ": " << what << ": " << gen::to_string(gen::friction_status(r.status));
            if (r.status == ok)
                return;
            EXPECT_EQ(r.regime, smooth) << c.name << ": " << what;
            // unchanged: velocities as given, everything else 0
            for (int k = 0; k < c.n_out; ++k) {
                const auto& o = m.outs[static_cast<std::size_t>(k)];
                if (o.kind == class_model::out_ref::velocity || o.kind == class_model::out_ref::angular) {
                    const std::string src = (o.kind == class_model::out_ref::velocity ? "v_" : "w_") + m.prob.axes[o.axis] +
                                            std::string(c.out_names[k]).substr(3);
                    int at = index_of(c.in_names, c.n_in, src);
                    if (at < 0) // the ball: v_t, v_n, w
                        at = index_of(c.in_names, c.n_in, std::string(o.kind == class_model::out_ref::velocity ? "v_" : "w") +
                                                              (o.kind == class_model::out_ref::velocity ? m.prob.axes[o.axis] : ""));
                    ASSERT_GE(at, 0) << src;
                    if (std::isfinite(y[static_cast<std::size_t>(at)]))
                        EXPECT_EQ(r.out[static_cast<std::size_t>(k)], y[static_cast<std::size_t>(at)]) << c.name << ": " << what;
                } else {
                    EXPECT_EQ(r.out[static_cast<std::size_t>(k)], 0.0) << c.name << ": " << what << ": " << c.out_names[k];
                }
            }
        };
        auto with = [&](const std::string& name, double v) {
            std::vector<double> y = x;
            const int i = index_of(c.in_names, c.n_in, name);
            EXPECT_GE(i, 0) << name;
            y[static_cast<std::size_t>(i)] = v;
            return y;
        };
        ASSERT_EQ(call(c, x).status, ok) << c.name;
        const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
        expect_status(with("mu", -0.1), gen::friction_status::invalid_friction, "mu < 0");
        expect_status(with("mu", inf), gen::friction_status::non_finite_input, "mu infinite");
        expect_status(with("mu", nan), gen::friction_status::non_finite_input, "mu NaN");
        expect_status(with("e", 1.5), gen::friction_status::invalid_restitution, "e > 1");
        expect_status(with("e", -0.5), gen::friction_status::invalid_restitution, "e < 0");
        const std::string mass = index_of(c.in_names, c.n_in, "m1") >= 0 ? "m1" : "m";
        expect_status(with(mass, 0), gen::friction_status::invalid_mass, "m = 0");
        expect_status(with(mass, -1), gen::friction_status::invalid_mass, "m < 0");
        if (index_of(c.in_names, c.n_in, "I1") >= 0)
            expect_status(with("I1", -1), gen::friction_status::invalid_inertia, "I < 0");
        if (index_of(c.in_names, c.n_in, "I1_tt") >= 0) {
            expect_status(with("I1_tt", -1), gen::friction_status::invalid_inertia, "I_tt < 0");
            expect_status(with("I1_tn", 1e3), gen::friction_status::invalid_inertia, "indefinite tensor");
        }
        if (index_of(c.in_names, c.n_in, "R") >= 0)
            expect_status(with("R", 0), gen::friction_status::invalid_inertia, "R = 0");
        // separating: every velocity reversed
        std::vector<double> y = x;
        for (int i = 0; i < c.n_in; ++i)
            if (c.in_names[i][0] == 'v' || c.in_names[i][0] == 'w')
                y[static_cast<std::size_t>(i)] = -y[static_cast<std::size_t>(i)];
        expect_status(y, gen::friction_status::not_approaching, "separating");
        const std::string vel = index_of(c.in_names, c.n_in, "v_t1") >= 0 ? "v_t1" : "v_t";
        expect_status(with(vel, nan), gen::friction_status::non_finite_input, "a NaN velocity");
        // approaching at 1e200: impulses of 1e200 and more, the energy lost (P.u) overflows
        const std::string vn = index_of(c.in_names, c.n_in, "v_n2") >= 0 ? "v_n2" : "v_n";
        expect_status(with(vn, -1e200), gen::friction_status::overflow, "approaching at 1e200");
    }
}

// The run-time root finder against the whole-circle method in long double.
TEST(friction_trig2, roots_of_degree_two_trigonometric_polynomials)
{
    namespace d = gen::detail;
    const long n = count("IMPACTGEN_FRICTION_TRIG", 200000, 2000000);
    std::mt19937_64 g(seed(7));
    std::uniform_real_distribution<double> U(-1, 1);
    long mismatched = 0, roots = 0;
    double worst = 0;
    d::trig2_stats::polished() = d::trig2_stats::split() = d::trig2_stats::circle() = 0;
    d::trig2_stats::iterations() = d::trig2_stats::max_iterations() = 0;
    long fast_circle = 0;
    for (long i = 0; i < n; ++i) {
        double a[5];
        for (double& x : a)
            x = U(g);
        switch (i % 6) {
        case 1: a[0] *= 3; break;                                   // fewer roots
        case 2: a[3] *= 1e-3, a[4] *= 1e-3; break;                  // nearly degree 1
        case 3: a[1] *= 1e-3, a[2] *= 1e-3; break;                  // nearly cos 2t, sin 2t only
        case 4: for (double& x : a) x *= std::pow(10.0, 300 * U(g)); break; // any scale
        case 5: { // a double root at a random angle: g = (cos(t - t0) - 1) (A + B cos t ...) is degree 2 only for A const
            const double t0 = 3.14159 * U(g), k = U(g);
            // g = k (1 - cos(t - t0)) + tiny: touches 0 at t0
            a[0] = k;
            a[1] = -k * std::cos(t0);
            a[2] = -k * std::sin(t0);
            a[3] = a[4] = 0;
            break;
        }
        default: break;
        }
        double rc[4], rs[4];
        const long before = d::trig2_stats::circle();
        const int nf = d::trig2_roots(a[0], a[1], a[2], a[3], a[4], static_cast<const double*>(nullptr), rc, rs);
        fast_circle += d::trig2_stats::circle() - before;
        // reference: the whole-circle method in long double
        long double al[5], gl[16];
        const long double mx = std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2]), std::fabs(a[3]), std::fabs(a[4])});
        for (int k = 0; k < 5; ++k)
            al[k] = a[k] / mx;
        for (int k = 0; k < 16; ++k) {
            long double c1, s1, c2, s2;
            d::unit_pi8(k, c1, s1);
            d::unit_pi8(2 * k, c2, s2);
            gl[k] = al[0] + al[1] * c1 + al[2] * s1 + al[3] * c2 + al[4] * s2;
        }
        const long saved[5] = {d::trig2_stats::polished(), d::trig2_stats::split(), d::trig2_stats::circle(),
                               d::trig2_stats::iterations(), d::trig2_stats::max_iterations()};
        long double lc[4], ls[4];
        const int nl = d::trig2_roots_circle(al[0], al[1], al[2], al[3], al[4], gl, lc, ls);
        d::trig2_stats::polished() = saved[0];
        d::trig2_stats::split() = saved[1];
        d::trig2_stats::circle() = saved[2];
        d::trig2_stats::iterations() = saved[3];
        d::trig2_stats::max_iterations() = saved[4];
        if (i % 6 == 5)
            continue; // a double root: found once, twice or not at all by either, as rounding has it
        if (nf != nl) {
            ++mismatched;
            continue;
        }
        roots += nf;
        for (int k = 0; k < nf; ++k) {
            EXPECT_NEAR(rc[k] * rc[k] + rs[k] * rs[k], 1.0, 1e-15);
            // the nearest root of the reference (the angle between them)
            double dtheta = 10, th = 0;
            for (int j = 0; j < nl; ++j) {
                const double dj = std::fabs(std::atan2(double(rs[k] * lc[j] - rc[k] * ls[j]), double(rc[k] * lc[j] + rs[k] * ls[j])));
                if (dj < dtheta) {
                    dtheta = dj;
                    th = double(std::atan2(ls[j], lc[j]));
                }
            }
            // the angle error times |g'| at the root, relative to the size of g: the rounding of g
            const double m = std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2]), std::fabs(a[3]), std::fabs(a[4])});
            const double dg = (a[2] * std::cos(th) - a[1] * std::sin(th) + 2 * (a[4] * std::cos(2 * th) - a[3] * std::sin(2 * th))) / m;
            worst = std::max(worst, dtheta * std::fabs(dg));
        }
    }
    std::cout << "trig2_roots: " << n << " polynomials, " << roots << " roots; counts differing from the long double method on "
              << mismatched << "; worst |angle error| |g'|/max|coefficient| " << worst << "; arcs subdivided "
              << d::trig2_stats::split() << ", calls sent to the whole-circle method " << fast_circle << ", roots polished "
              << d::trig2_stats::polished() << " (" << d::trig2_stats::iterations() << " iterations, at most "
              << d::trig2_stats::max_iterations() << ")\n";
    EXPECT_LE(mismatched, n / 100000);
    EXPECT_LE(worst, 1e-14);
    // special cases
    double rc[4], rs[4];
    EXPECT_EQ(d::trig2_roots(0.0, 0.0, 0.0, 0.0, 0.0, static_cast<const double*>(nullptr), rc, rs), -1);
    EXPECT_EQ(d::trig2_roots(std::nan(""), 0.0, 0.0, 0.0, 0.0, static_cast<const double*>(nullptr), rc, rs), -2);
    EXPECT_EQ(d::trig2_roots(1.0, 0.5, 0.0, 0.0, 0.0, static_cast<const double*>(nullptr), rc, rs), 0); // 1 + cos/2 > 0
    ASSERT_EQ(d::trig2_roots(0.0, 1.0, 0.0, 0.0, 0.0, static_cast<const double*>(nullptr), rc, rs), 2); // cos: zeros at pi/2, 3pi/2 (exact samples)
    EXPECT_NEAR(std::fabs(rs[0]), 1.0, 1e-15);
    ASSERT_EQ(d::trig2_roots(0.0, 0.0, 0.0, 0.0, 1.0, static_cast<const double*>(nullptr), rc, rs), 4); // sin 2t: 0, pi/2, pi, 3pi/2
}
