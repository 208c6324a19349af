// The numeric reference for impact with Coulomb friction
// (numeric/friction_solver.hpp) against the PHYSICS, on seeded random problems
// of five kinds: planar two free bodies, planar ball on a floor (infinite mass),
// planar pinned rod struck by a ball, 3-D two free bodies with full random SPD
// inertia tensors, 3-D sphere on a floor. Every answer is checked from the
// bodies' states alone, independently of the solver's contact frame and
// Delassus matrix:
//   restitution u'.n^ = -e u.n^, P_n >= 0, P_t perpendicular to n^;
//   cone |P_t| <= mu P_n; stick (u'_t = 0) or slide (P_t = -mu P_n u'_t/|u'_t|);
//   impulse-momentum of each body: m dv = +-P (+R), I dw = r x (+-P) (+ (E - C) x R)
//   about C; the pivot point at rest afterwards; infinite masses unchanged;
//   mu = 0: P_t = 0 exactly and the answer of solve_momentum_system.
// Also: the textbook ball on a floor (stick iff mu >= 2|u_t| / (7 (1+e) |u_n|)),
// planar and 3-D, and in 3-D the semismooth Newton method against the
// enumeration wherever the enumeration finds a single solution; and a 3-D body
// pinned at a point struck by an immovable one (W singular), where the law often
// has no solution and an ok answer must still keep restitution.
//
// Inputs: masses log-uniform in [1e-3, 1e3] (ratios up to 1e6), mu 10% exactly 0,
// 10% log-uniform in [1e-4, 1], otherwise uniform in [0, 2]; e 5% exactly 0, 5%
// exactly 1, otherwise uniform in [0, 1]; one sample in eight near grazing
// (u.n^ = -|u| 10^U(-12, -4)). Velocities are flipped when the bodies would not
// approach.
//
// Counts: 10,000 problems per kind (IMPACTGEN_FRICTION_SAMPLES overrides;
// IMPACTGEN_SAMPLES, set to 200 by the sanitizer pass, caps it;
// IMPACTGEN_DEEP=1 runs 100,000 per kind). IMPACTGEN_SEED overrides the seed.
// Each kind prints its figures (regimes, statuses, worst residuals).
//
// Residuals are relative, to the size of the terms they are computed from:
// contact velocities against V = max(|u|, |u'|, the velocity each impulse gives
// its body's contact point on its own), a body's dv against its speeds and
// (|P| + |R|)/m, its dw against its angular speeds and |I^-1| times the moments'
// sizes, impulses against |P| + |R|. Every check uses 1e-9, far above the
// measured worst (printed, about 1e-14) and far below any physical error.
#include "numeric/friction_solver.hpp"
#include "numeric/generalized_solver.hpp"
#include "numeric/momentum_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <random>
#include <string>

namespace nm = impactgen::numeric;
using vec3 = nm::vec<double>;
using mat3 = nm::mat<double>;
using prob = nm::problem<double>;

namespace {

long env_or(const char* name, long fallback)
{
    const char* v = std::getenv(name);
    return v && *v ? std::strtol(v, nullptr, 10) : fallback;
}
bool deep() { return env_or("IMPACTGEN_DEEP", 0) != 0; }
long samples()
{
    if (const char* v = std::getenv("IMPACTGEN_FRICTION_SAMPLES"); v && *v)
        return std::strtol(v, nullptr, 10);
    if (deep())
        return 100000;
    return std::min(10000L, env_or("IMPACTGEN_SAMPLES", 10000));
}
unsigned seed(unsigned salt) { return static_cast<unsigned>(env_or("IMPACTGEN_SEED", 20261201)) + 7919u * salt; }

const double tol = 1e-9;

class rnd {
public:
    explicit rnd(unsigned s) : g_(s) {}
    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(g_); }
    double log_uniform(double lo_exp, double hi_exp) { return std::pow(10.0, uniform(lo_exp, hi_exp)); }
    bool chance(double p) { return uniform(0, 1) < p; }
    double mass() { return log_uniform(-3, 3); }
    double restitution()
    {
        double k = uniform(0, 1);
        return k < 0.05 ? 0.0 : k < 0.10 ? 1.0 : uniform(0, 1);
    }
    double friction()
    {
        double k = uniform(0, 1);
        return k < 0.1 ? 0.0 : k < 0.2 ? log_uniform(-4, 0) : uniform(0, 2);
    }
    vec3 vector(int dim, double bound)
    {
        vec3 v = vec3::Zero();
        for (int c = 0; c < dim; ++c)
            v[c] = uniform(-bound, bound);
        return v;
    }
    vec3 direction(int dim)
    {
        for (;;) {
            vec3 v = vector(dim, 1);
            double l = v.norm();
            if (l > 0.1 && l <= 1)
                return v / l;
        }
    }
    mat3 spd(double m, double size)
    {
        mat3 A;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                A(r, c) = uniform(-1, 1);
        return m * size * size * (A * A.transpose() + 0.05 * mat3::Identity());
    }
    std::mt19937_64& engine() { return g_; }

private:
    std::mt19937_64 g_;
};

bool spins(const nm::body<double>& b) { return b.infinite_mass || !b.particle; }
vec3 point_velocity(const nm::body<double>& b, const vec3& v, const vec3& w, const vec3& q)
{
    return v + (spins(b) ? vec3(w.cross(q - b.position)) : vec3::Zero());
}
vec3 relative_before(const prob& p)
{
    const auto& A = p.bodies[p.body1];
    const auto& B = p.bodies[p.body2];
    return point_velocity(B, B.velocity, B.angular_velocity, p.point) - point_velocity(A, A.velocity, A.angular_velocity, p.point);
}

/// Flips all velocities when the bodies separate, then (one in eight) moves a
/// free body along n^ so that the approach is nearly grazing.
void make_approach(prob& p, rnd& r, bool grazing = true)
{
    const vec3 n = p.normal.normalized();
    if (relative_before(p).dot(n) > 0)
        for (auto& b : p.bodies) {
            b.velocity = -b.velocity;
            b.angular_velocity = -b.angular_velocity;
        }
    if (grazing && r.chance(0.125)) {
        const vec3 u = relative_before(p);
        const double target = -std::max(u.norm(), 1e-3) * r.log_uniform(-12, -4);
        for (std::size_t i : {p.body2, p.body1})
            if (!p.immovable(i) && !p.pivot_of(i)) {
                const double s = i == p.body1 ? -1 : 1;
                p.bodies[i].velocity += s * (target - u.dot(n)) * n;
                break;
            }
    }
}

nm::body<double> free_body(rnd& r, int dim, double particle_chance)
{
    nm::body<double> b;
    b.particle = r.chance(particle_chance);
    b.mass = r.mass();
    const double size = r.uniform(0.3, 1.3);
    if (!b.particle) {
        if (dim == 2)
            b.inertia(2, 2) = b.mass * size * size * r.uniform(0.05, 1);
        else
            b.inertia = r.spd(b.mass, size);
        b.angular_velocity = dim == 2 ? vec3(0, 0, r.uniform(-2, 2)) : r.vector(3, 2);
    }
    b.velocity = r.vector(dim, 1);
    return b;
}
nm::body<double> floor_body(rnd& r, int dim, const vec3& n)
{
    nm::body<double> f;
    f.infinite_mass = true;
    f.particle = r.chance(0.2); // a "particle" of infinite mass: its spin still counts
    f.mass = 0;
    if (r.chance(0.5)) { // a moving floor: tangential velocity and spin
        vec3 v = r.vector(dim, 1);
        f.velocity = v - v.dot(n) * n;
        f.angular_velocity = dim == 2 ? vec3(0, 0, r.uniform(-0.5, 0.5)) : vec3(r.vector(3, 0.5));
    }
    return f;
}
/// A ball (I = k m R^2, k = 2/5 or random) whose centre is R from O along +-n^.
nm::body<double> ball(rnd& r, int dim, const vec3& O, const vec3& away, bool allow_particle)
{
    nm::body<double> b;
    b.mass = r.mass();
    b.particle = allow_particle && r.chance(0.3);
    const double R = r.uniform(0.1, 1.5);
    b.position = b.particle ? O : vec3(O + R * away);
    if (!b.particle) {
        const double k = r.chance(0.5) ? 0.4 : r.uniform(0.1, 1);
        if (dim == 2)
            b.inertia(2, 2) = k * b.mass * R * R;
        else
            b.inertia = k * b.mass * R * R * mat3::Identity();
        b.angular_velocity = dim == 2 ? vec3(0, 0, r.uniform(-3, 3)) : r.vector(3, 3);
    }
    b.velocity = r.vector(dim, 1);
    return b;
}

enum class kind { planar_free, planar_ball_floor, planar_pinned_rod, spatial_free, spatial_sphere_floor };
const char* kind_name(kind k)
{
    switch (k) {
    case kind::planar_free: return "planar two free bodies";
    case kind::planar_ball_floor: return "planar ball on floor";
    case kind::planar_pinned_rod: return "planar pinned rod struck by a ball";
    case kind::spatial_free: return "3-D two free bodies (SPD inertia)";
    case kind::spatial_sphere_floor: return "3-D sphere on floor";
    }
    return "?";
}

prob random_problem(kind k, rnd& r)
{
    prob p;
    const bool planar = k == kind::planar_free || k == kind::planar_ball_floor || k == kind::planar_pinned_rod;
    const int dim = planar ? 2 : 3;
    p.dimension = dim;
    p.restitution = r.restitution();
    p.friction = r.friction();
    p.point = r.vector(dim, 1);
    const vec3 n = r.direction(dim);
    p.normal = n * r.uniform(0.5, 2); // any length
    switch (k) {
    case kind::planar_free:
    case kind::spatial_free: {
        for (int i = 0; i < 2; ++i) {
            nm::body<double> b = free_body(r, dim, planar ? 0.25 : 0.1);
            b.position = b.particle ? p.point : vec3(p.point + r.vector(dim, 1));
            p.bodies.push_back(b);
        }
        break;
    }
    case kind::planar_ball_floor:
    case kind::spatial_sphere_floor: {
        // floor below the ball; the order of the bodies is random (n^ points from body 1 into body 2).
        const bool floor_first = r.chance(0.5);
        nm::body<double> f = floor_body(r, dim, n);
        f.position = p.point - (floor_first ? 1 : -1) * r.uniform(0, 2) * n + r.vector(dim, 1);
        nm::body<double> b = ball(r, dim, p.point, floor_first ? n : vec3(-n), false);
        p.bodies = floor_first ? std::vector<nm::body<double>>{f, b} : std::vector<nm::body<double>>{b, f};
        break;
    }
    case kind::planar_pinned_rod: {
        const bool rod_first = r.chance(0.5);
        nm::body<double> rod;
        rod.particle = false;
        rod.mass = r.mass();
        const double L = r.uniform(0.5, 2);
        const vec3 along = r.direction(2);
        const vec3 E = p.point - r.uniform(0.05, 1) * L * along;
        rod.position = E + 0.5 * L * along;
        rod.inertia(2, 2) = rod.mass * L * L * (r.chance(0.5) ? 1.0 / 12 : r.uniform(0.02, 0.3));
        rod.angular_velocity = vec3(0, 0, r.uniform(-2, 2));
        rod.velocity = rod.angular_velocity.cross(rod.position - E); // consistent with the pivot
        nm::body<double> b = ball(r, 2, p.point, rod_first ? n : vec3(-n), true);
        p.bodies = rod_first ? std::vector<nm::body<double>>{rod, b} : std::vector<nm::body<double>>{b, rod};
        p.pivots.push_back({rod_first ? std::size_t(0) : std::size_t(1), E});
        break;
    }
    }
    if (r.chance(0.1)) { // a bystander: a third body, unchanged by the impact
        nm::body<double> b = free_body(r, dim, 0.5);
        b.position = r.vector(dim, 3);
        p.bodies.push_back(b);
    }
    make_approach(p, r);
    return p;
}

/// Worst relative residuals over a run.
struct worst {
    std::map<std::string, double> v;
    std::map<std::string, std::string> where;
    std::string current; ///< the problem being checked
    void note(const std::string& what, double x)
    {
        double& w = v[what];
        if (!(x <= w) || !where.count(what)) {
            w = std::max(w, std::isfinite(x) ? x : 1e300);
            where[what] = current;
        }
    }
    double operator[](const std::string& what) const
    {
        auto it = v.find(what);
        return it == v.end() ? 0 : it->second;
    }
};

/// Checks a solved answer against the physics, from the bodies' states alone;
/// records the residuals in w. Returns false (with a failure) when a law is broken.
bool check_physics(const prob& p, const nm::friction_answer<double>& a, worst& w, const std::string& what, double limit)
{
    bool good = true;
    auto expect = [&](const char* law, double residual) {
        w.note(law, residual);
        if (!(residual <= limit)) {
            good = false;
            ADD_FAILURE() << what << ": " << law << " residual " << residual;
        }
    };
    const vec3 n = p.normal.normalized();
    const auto& A = p.bodies[p.body1];
    const auto& B = p.bodies[p.body2];
    const vec3 u = relative_before(p);
    const vec3 u1 = point_velocity(B, a.velocity[p.body2], a.angular_velocity[p.body2], p.point) -
                    point_velocity(A, a.velocity[p.body1], a.angular_velocity[p.body1], p.point);
    const vec3 P = a.normal_impulse * n + a.tangential_impulse;
    double Rn = 0;
    for (const auto& R : a.pivot_impulses)
        Rn = std::max(Rn, R.norm());
    const double Ps = std::max(P.norm() + Rn, 1e-300);
    const double mu = p.friction;
    // Velocity scale of the contact checks: the contact velocities, and the velocity
    // each impulse would give its body's contact point on its own (|P| + |R|)/m +
    // |I^-1| (|O - C| |P| + |E - C| |R|) |O - C|: when a pivot cancels most of a large
    // contact impulse on a light body, or W is ill-conditioned (a jam: |P| >> m |u|),
    // u' is a small difference of such terms and known to eps times them.
    double V = std::max(u.norm(), u1.norm());
    for (std::size_t i : {p.body1, p.body2}) {
        const auto& b = p.bodies[i];
        if (p.immovable(i))
            continue;
        const auto* pv = p.pivot_of(i);
        const double R = pv ? a.pivot_impulses[static_cast<std::size_t>(pv - p.pivots.data())].norm() : 0.0;
        const double arm = (p.point - b.position).norm(), parm = pv ? (pv->point - b.position).norm() : 0.0;
        double Vi = (P.norm() + R) / b.mass;
        if (!b.particle) {
            const double inv_I = p.dimension == 2 ? 1 / b.inertia(2, 2) : b.inertia.inverse().norm();
            Vi += inv_I * (arm * P.norm() + parm * R) * arm;
        }
        V = std::max(V, Vi);
    }
    expect("restitution", std::abs(u1.dot(n) + p.restitution * u.dot(n)) / V);
    expect("P_n >= 0", std::max(0.0, -a.normal_impulse) / Ps);
    expect("P_t . n = 0", std::abs(a.tangential_impulse.dot(n)) / Ps);
    expect("cone", std::max(0.0, a.tangential_impulse.norm() - mu * a.normal_impulse) / Ps);
    const vec3 u1t = u1 - u1.dot(n) * n;
    if (mu == 0) {
        if (a.tangential_impulse.norm() != 0 || a.regime != nm::friction_regime::smooth) {
            good = false;
            ADD_FAILURE() << what << ": mu = 0 but P_t = " << a.tangential_impulse.transpose() << " regime " << nm::friction_regime_name(a.regime);
        }
    } else if (a.regime == nm::friction_regime::stick) {
        expect("stick u'_t = 0", u1t.norm() / V);
    } else if (a.regime == nm::friction_regime::slide) {
        // |P_t| = mu P_n, and u'_t along d = -P_t/|P_t|. In velocity form: the
        // direction of a small u'_t is known only to eps V / |u'_t|.
        expect("slide |P_t| = mu P_n", std::abs(a.tangential_impulse.norm() - mu * a.normal_impulse) / Ps);
        if (a.tangential_impulse.norm() > 0) {
            const vec3 d = -a.tangential_impulse.normalized();
            expect("slide u'_t x d = 0", (u1t - u1t.dot(d) * d).norm() / V);
            expect("slide u'_t . d >= 0", std::max(0.0, -u1t.dot(d)) / V);
        }
    } else {
        good = false;
        ADD_FAILURE() << what << ": regime smooth with mu = " << mu;
    }
    // Each body: unchanged (bystander, infinite mass, pinned particle) or the impulse-momentum laws.
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const auto& b = p.bodies[i];
        const bool in_contact = i == p.body1 || i == p.body2;
        if (!in_contact || p.immovable(i)) {
            if (a.velocity[i] != b.velocity || a.angular_velocity[i] != b.angular_velocity) {
                good = false;
                ADD_FAILURE() << what << ": body " << i << " should be unchanged";
            }
            continue;
        }
        const double s = i == p.body1 ? -1 : 1;
        const auto* pv = p.pivot_of(i);
        const vec3 R = pv ? a.pivot_impulses[static_cast<std::size_t>(pv - p.pivots.data())] : vec3::Zero();
        const vec3 J = s * P + R;
        const vec3 dv = a.velocity[i] - b.velocity;
        const double vs = std::max({b.velocity.norm(), a.velocity[i].norm(), (P.norm() + R.norm()) / b.mass, V});
        expect("m dv = +-P + R", (dv - J / b.mass).norm() / vs);
        if (!b.particle) {
            const vec3 M = (p.point - b.position).cross(s * P) + (pv ? vec3((pv->point - b.position).cross(R)) : vec3::Zero());
            const vec3 dw = a.angular_velocity[i] - b.angular_velocity;
            vec3 expected;
            if (p.dimension == 2)
                expected = vec3(0, 0, M[2] / b.inertia(2, 2));
            else
                expected = b.inertia.ldlt().solve(M);
            const double arm = std::max((p.point - b.position).norm(), pv ? (pv->point - b.position).norm() : 0.0);
            const double inv_I = p.dimension == 2 ? 1 / b.inertia(2, 2) : b.inertia.inverse().norm();
            const double moments = inv_I * ((p.point - b.position).norm() * P.norm() + (pv ? (pv->point - b.position).norm() : 0.0) * R.norm());
            const double ws = std::max({b.angular_velocity.norm(), a.angular_velocity[i].norm(), moments, arm > 0 ? V / arm : 0.0});
            expect("I dw = r x (+-P) (+ (E-C) x R)", (dw - expected).norm() / std::max(ws, 1e-300));
        }
        if (pv) {
            const vec3 vE = point_velocity(b, a.velocity[i], a.angular_velocity[i], pv->point);
            const double es = std::max(V, a.angular_velocity[i].norm() * (pv->point - b.position).norm());
            expect("pivot at rest", vE.norm() / es);
        }
        if (p.dimension == 2 && (std::abs(a.velocity[i][2]) + std::abs(a.angular_velocity[i][0]) + std::abs(a.angular_velocity[i][1]) != 0)) {
            good = false;
            ADD_FAILURE() << what << ": planar state leaves the plane";
        }
    }
    return good;
}

struct tally {
    long count = 0, stick = 0, slide = 0, smooth = 0, ambiguous = 0, no_solution = 0, singular = 0, energy_gain = 0,
         grazing = 0, newton_failed = 0, newton_failed_alone = 0, newton_reduced = 0, gain_stick = 0, gain_slide = 0, gain_e0 = 0;
    double max_gain = 0;
    std::vector<std::string> examples;
};

void print(kind k, const tally& t, const worst& w)
{
    std::cout << "[friction] " << kind_name(k) << ": " << t.count << " problems; stick " << t.stick << ", slide " << t.slide
              << ", smooth " << t.smooth << "; ambiguous " << t.ambiguous << ", no_solution " << t.no_solution << ", singular "
              << t.singular << "; near grazing " << t.grazing << "; Newton not converged " << t.newton_failed << " (alone, where the enumeration found one: " << t.newton_failed_alone << ")"
              << "; Newton from the reduced root " << t.newton_reduced << "; energy gained (static surroundings) " << t.energy_gain << " (stick "
              << t.gain_stick << ", slide " << t.gain_slide << ", at e = 0 " << t.gain_e0 << "; max " << t.max_gain << " of T)\n";
    for (const auto& [law, r] : w.v)
        std::cout << "[friction]   worst " << law << ": " << r << " (" << w.where.at(law) << ")\n";
    for (const auto& e : t.examples)
        std::cout << "[friction]   " << e << "\n";
}

bool static_surroundings(const prob& p)
{
    for (const auto& b : p.bodies)
        if (b.infinite_mass && (b.velocity.norm() + b.angular_velocity.norm()) != 0)
            return false;
    return true;
}

/// Sign changes of phi(P_n) = W_n.(P_n, P_t(P_n)) - rhs_n (3-D; see count_solutions)
/// on 1000 log-spaced P_n over 26 decades around the impulse scale, plus the
/// midpoints between consecutive P_n of the given solutions (so that two roots
/// closer than a grid step, seen 2 times in 72 problems with several solutions,
/// are separated); -1 on failure.
long reduced_sign_changes(const prob& p, const std::vector<nm::friction_candidate<double>>& found = {})
{
    const nm::friction_contact<double> fc(p);
    if (!fc.ok)
        return -1;
    std::vector<double> grid, roots;
    for (int i = 0; i <= 1000; ++i)
        grid.push_back(fc.impulse_scale * std::pow(10.0, -16 + 26.0 * i / 1000));
    for (const auto& k : found)
        roots.push_back(k.normal_impulse);
    std::sort(roots.begin(), roots.end());
    for (std::size_t i = 1; i < roots.size(); ++i)
        grid.push_back((roots[i - 1] + roots[i]) / 2);
    std::sort(grid.begin(), grid.end());
    const double rhs = fc.normal_rhs();
    Eigen::Vector2d Pt;
    double previous = -rhs;
    long changes = 0;
    for (double Pn : grid) {
        if (!nm::detail::tangential_response(fc, Pn, Pt))
            return -1;
        const double f = fc.W(0, 0) * Pn + fc.W(0, 1) * Pt[0] + fc.W(0, 2) * Pt[1] - rhs;
        changes += (f < 0) != (previous < 0);
        previous = f;
    }
    return changes;
}

void run_kind(kind k)
{
    rnd r(seed(static_cast<unsigned>(k)));
    const long N = samples();
    tally t;
    worst w, agree;
    long failures = 0;
    for (long s = 0; s < N && failures < 20; ++s) {
        prob p = random_problem(k, r);
        const std::string what = std::string(kind_name(k)) + " #" + std::to_string(s);
        w.current = agree.current = "#" + std::to_string(s);
        const vec3 u = relative_before(p);
        if (std::abs(u.dot(p.normal.normalized())) < 1e-4 * u.norm())
            ++t.grazing;
        const auto a = nm::solve_friction(p);
        ++t.count;
        if (a.status == nm::friction_status::singular) {
            ++t.singular;
            ++failures;
            ADD_FAILURE() << what << ": singular";
            continue;
        }
        if (p.dimension == 3 && p.friction > 0 && !a.newton_converged)
            ++t.newton_failed;
        if (a.newton_reduced)
            ++t.newton_reduced;
        if (a.status == nm::friction_status::no_solution) {
            ++t.no_solution;
            if (t.examples.size() < 6)
                t.examples.push_back(what + ": no solution (mu " + std::to_string(p.friction) + ")");
            continue;
        }
        if (a.status == nm::friction_status::ambiguous) {
            ++t.ambiguous;
            // Every solution found satisfies the law: the bodies' states after each
            // candidate impulse (friction_contact::apply) checked like an answer; in 3-D
            // the reduced problem has as many roots.
            if (p.dimension == 3) {
                EXPECT_EQ(reduced_sign_changes(p, a.candidates), static_cast<long>(a.candidates.size())) << what;
            }
            const nm::friction_contact<double> fc(p);
            for (std::size_t c = 0; c < a.candidates.size(); ++c) {
                nm::friction_answer<double> alt = a;
                const auto& k = a.candidates[c];
                alt.regime = k.regime;
                alt.normal_impulse = k.normal_impulse;
                alt.tangential_impulse = k.tangential_impulse;
                fc.apply(k.normal_impulse * p.normal.normalized() + k.tangential_impulse, alt.velocity, alt.angular_velocity, alt.pivot_impulses);
                check_physics(p, alt, w, what + " candidate " + std::to_string(c), tol);
            }
            if (t.examples.size() < 6) {
                std::string names;
                for (const auto& c : a.candidates)
                    names += std::string(" ") + nm::friction_regime_name(c.regime) + " P_n=" + std::to_string(c.normal_impulse);
                t.examples.push_back(what + ": ambiguous (mu " + std::to_string(p.friction) + "):" + names);
            }
        }
        (a.regime == nm::friction_regime::stick ? t.stick : a.regime == nm::friction_regime::slide ? t.slide : t.smooth)++;
        if (!check_physics(p, a, w, what, tol))
            ++failures;
        if (static_surroundings(p)) {
            const double T0 = nm::kinetic_energy(p), T1 = nm::kinetic_energy(p, a.velocity, a.angular_velocity);
            if (T1 > T0 * (1 + 1e-12)) {
                ++t.energy_gain;
                ++(a.regime == nm::friction_regime::stick ? t.gain_stick : t.gain_slide);
                if (p.restitution == 0)
                    ++t.gain_e0;
                t.max_gain = std::max(t.max_gain, (T1 - T0) / T0);
            }
        }
        // mu = 0: the smooth answers of the existing solvers. solve_generalized (KKT) to
        // tol; solve_momentum_system (system momentum, angular momentum about O) to 1e-7:
        // its own physics residual reaches ~1e-9 at mass ratios ~1e5 in 3-D (measured).
        if (p.friction == 0) {
            const auto g = nm::solve_generalized(p);
            const auto m = nm::solve_momentum_system(p);
            EXPECT_TRUE(g.ok && m.ok) << what;
            // P_n against the impulse scale m_r |u| (m_r: reduced translational mass of the
            // movable bodies): solve_momentum_system takes N from one body's change of
            // momentum, exact only to eps m |v| (a heavy body's tiny dv).
            double inv = 0;
            for (std::size_t i : {p.body1, p.body2})
                if (!p.immovable(i))
                    inv += 1 / p.bodies[i].mass;
            auto compare = [&](const nm::answer<double>& o, const std::string& name, double limit) {
                if (!o.ok)
                    return;
                const double scale = std::max(std::abs(o.normal_impulse), u.norm() / inv);
                const double err = std::abs(o.normal_impulse - a.normal_impulse) / scale;
                double vs = 0, ve = 0;
                for (std::size_t i = 0; i < p.bodies.size(); ++i) {
                    vs = std::max({vs, o.velocity[i].norm(), o.angular_velocity[i].norm()});
                    ve = std::max({ve, (o.velocity[i] - a.velocity[i]).norm(), (o.angular_velocity[i] - a.angular_velocity[i]).norm()});
                }
                w.note("mu = 0 vs " + name + ": P_n", err);
                w.note("mu = 0 vs " + name + ": v, w", ve / vs);
                EXPECT_LE(err, limit) << what << " vs " << name;
                EXPECT_LE(ve, limit * vs) << what << " vs " << name;
            };
            compare(g, "solve_generalized", tol);
            compare(m, "solve_momentum_system", 1e-7);
        }
        // 3-D: Newton alone against the enumeration alone where the enumeration finds one solution.
        if (p.dimension == 3 && p.friction > 0) {
            nm::friction_options<double> en, nw;
            en.method = nm::friction_method::enumeration;
            nw.method = nm::friction_method::newton;
            const auto ae = nm::solve_friction(p, en), an = nm::solve_friction(p, nw);
            if (ae.status == nm::friction_status::ok) {
                check_physics(p, ae, agree, what + " (enumeration)", tol);
                EXPECT_EQ(an.status, nm::friction_status::ok) << what << ": Newton failed where the enumeration found one solution";
                if (an.status != nm::friction_status::ok)
                    ++t.newton_failed_alone;
                if (an.status == nm::friction_status::ok) {
                    const vec3 Pe = ae.normal_impulse * p.normal.normalized() + ae.tangential_impulse;
                    const vec3 Pn = an.normal_impulse * p.normal.normalized() + an.tangential_impulse;
                    const double d = (Pe - Pn).norm() / std::max(Pe.norm(), 1e-300);
                    agree.note("Newton vs enumeration |dP|/|P|", d);
                    EXPECT_LE(d, 1e-7) << what << ": Newton and the enumeration disagree";
                    EXPECT_EQ(an.regime, ae.regime) << what;
                }
            }
        }
    }
    print(k, t, w);
    for (const auto& [law, r] : agree.v)
        std::cout << "[friction]   " << kind_name(k) << " enumeration alone, worst " << law << ": " << r << "\n";
    EXPECT_EQ(t.singular, 0);
    EXPECT_EQ(failures, 0);
}

} // namespace

TEST(FrictionReference, PlanarTwoFreeBodies) { run_kind(kind::planar_free); }
TEST(FrictionReference, PlanarBallOnFloor) { run_kind(kind::planar_ball_floor); }
TEST(FrictionReference, PlanarPinnedRodStruckByBall) { run_kind(kind::planar_pinned_rod); }
TEST(FrictionReference, SpatialTwoFreeBodies) { run_kind(kind::spatial_free); }
TEST(FrictionReference, SpatialSphereOnFloor) { run_kind(kind::spatial_sphere_floor); }

// 3-D: the number of distinct solutions (automatic method: Newton and the
// enumeration merged) against a different characterization of the law: for fixed
// P_n the tangential law is a strictly convex minimization over the disc
// |P_t| <= mu P_n with a unique P_t(P_n) (detail::tangential_response), so the
// solutions are the roots of phi(P_n) = W_n.(P_n, P_t(P_n)) - rhs_n, counted here
// as sign changes on 1000 log-spaced P_n over 26 decades around the impulse scale
// (and the midpoints between the solutions found: a finer grid where needed).
// One problem in 20 of each 3-D kind (this is the slow test: ~1 ms a problem).
void count_solutions(kind k)
{
    rnd r(seed(200 + static_cast<unsigned>(k)));
    const long N = std::max(1L, samples() / 20);
    long checked = 0, several = 0, mismatches = 0;
    for (long s = 0; s < N; ++s) {
        prob p = random_problem(k, r);
        if (p.friction == 0)
            continue;
        const auto a = nm::solve_friction(p);
        const long changes = reduced_sign_changes(p, a.candidates);
        ++checked;
        several += a.candidates.size() > 1;
        if (static_cast<long>(a.candidates.size()) != changes) {
            ++mismatches;
            ADD_FAILURE() << kind_name(k) << " #" << s << ": " << a.candidates.size() << " solutions found, phi changes sign " << changes << " times";
        }
    }
    std::cout << "[friction] " << kind_name(k) << ": solution counts against the reduced problem on " << checked << " problems (" << several
              << " with several solutions): " << mismatches << " mismatches\n";
}

TEST(FrictionReference, SpatialTwoFreeBodiesSolutionCount) { count_solutions(kind::spatial_free); }
TEST(FrictionReference, SpatialSphereOnFloorSolutionCount) { count_solutions(kind::spatial_sphere_floor); }

// The textbook case: a ball (I = 2/5 m R^2) strikes a resting floor with
// tangential contact velocity u_t and normal velocity u_n < 0. With
// P_n = m (1+e) |u_n| and du_t = 7/2 P_t/m, it sticks (leaves rolling: the
// contact point at rest, v' = -w' x (O - C)) iff mu >= 2|u_t| / (7 (1+e) |u_n|),
// with P_t = -2/7 m u_t; else it slides with P_t = -mu P_n u_t/|u_t|.
void textbook(int dim, nm::friction_method method)
{
    rnd r(seed(100 + static_cast<unsigned>(dim) * 10 + static_cast<unsigned>(method)));
    const long N = samples();
    long sticks = 0, slides = 0, near_threshold = 0, failures = 0;
    double worst_err = 0, rolling_err = 0;
    for (long s = 0; s < N && failures < 20; ++s) {
        prob p;
        p.dimension = dim;
        p.restitution = r.restitution();
        p.point = r.vector(dim, 1);
        const vec3 n = r.direction(dim);
        p.normal = n * r.uniform(0.5, 2);
        nm::body<double> f;
        f.infinite_mass = true;
        f.mass = 0;
        f.position = p.point - n;
        nm::body<double> b;
        b.particle = false;
        b.mass = r.mass();
        const double R = r.uniform(0.1, 2);
        b.position = p.point + R * n;
        b.inertia = dim == 2 ? mat3(vec3(0, 0, 0.4 * b.mass * R * R).asDiagonal()) : mat3(0.4 * b.mass * R * R * mat3::Identity());
        b.velocity = r.vector(dim, 1);
        b.angular_velocity = dim == 2 ? vec3(0, 0, r.uniform(-3, 3)) : r.vector(3, 3);
        p.bodies = {f, b};
        make_approach(p, r, false); // near grazing mu* = 2|u_t|/(7(1+e)|u_n|) is huge: the random kinds cover it
        const vec3 u = relative_before(p);
        const double un = u.dot(n);
        const vec3 ut = u - un * n;
        if (!(un < 0) || ut.norm() == 0)
            continue;
        const double mu_star = 2 * ut.norm() / (7 * (1 + p.restitution) * std::abs(un));
        p.friction = mu_star * r.log_uniform(-1, 1);
        const double Pn = b.mass * (1 + p.restitution) * std::abs(un);
        nm::friction_options<double> opt;
        opt.method = method;
        const auto a = nm::solve_friction(p, opt);
        const std::string what = "textbook " + std::to_string(dim) + "-D #" + std::to_string(s);
        if (a.status != nm::friction_status::ok) {
            ++failures;
            ADD_FAILURE() << what << ": status " << nm::friction_status_name(a.status);
            continue;
        }
        if (std::abs(p.friction / mu_star - 1) < 1e-9) {
            ++near_threshold; // both regimes coincide there
            continue;
        }
        const bool stick = p.friction >= mu_star;
        const vec3 Pt = stick ? vec3(-2.0 / 7 * b.mass * ut) : vec3(-p.friction * Pn * ut.normalized());
        // Relative to the contact's impulse scale m |u|: u.n^ itself is only known to eps |u|.
        const double err = std::max(std::abs(a.normal_impulse - Pn), (a.tangential_impulse - Pt).norm()) / (b.mass * u.norm());
        worst_err = std::max(worst_err, err);
        (stick ? sticks : slides)++;
        bool good = err <= tol && a.regime == (stick ? nm::friction_regime::stick : nm::friction_regime::slide);
        if (stick) { // leaves rolling: the ball's contact point has no tangential velocity
            const vec3 vO = a.velocity[1] + a.angular_velocity[1].cross(p.point - b.position);
            rolling_err = std::max(rolling_err, (vO - vO.dot(n) * n).norm() / u.norm());
            good = good && (vO - vO.dot(n) * n).norm() <= tol * u.norm();
        }
        if (!good) {
            ++failures;
            ADD_FAILURE() << what << ": expected " << (stick ? "stick" : "slide") << ", got " << nm::friction_regime_name(a.regime)
                          << ", impulse error " << err << " (mu / mu* = " << p.friction / mu_star << "; u = " << u.transpose()
                          << ", n = " << n.transpose() << ", P_n = " << a.normal_impulse << " (expected " << Pn << "), P_t = "
                          << a.tangential_impulse.transpose() << " (expected " << Pt.transpose() << "))";
        }
    }
    std::cout << "[friction] textbook ball on floor " << dim << "-D (" << (method == nm::friction_method::newton ? "Newton" : "enumeration")
              << "): " << sticks << " stick, " << slides << " slide, " << near_threshold << " at the threshold; worst impulse error " << worst_err
              << " of m |u|, worst |u'_t| / |u| when sticking " << rolling_err << "\n";
    EXPECT_EQ(failures, 0);
    EXPECT_GT(sticks, 0);
    EXPECT_GT(slides, 0);
}

TEST(FrictionReference, TextbookBallOnFloorPlanar) { textbook(2, nm::friction_method::automatic); }
TEST(FrictionReference, TextbookBallOnFloorSpatialNewton) { textbook(3, nm::friction_method::newton); }
TEST(FrictionReference, TextbookBallOnFloorSpatialEnumeration) { textbook(3, nm::friction_method::enumeration); }

// Degenerate inputs: both bodies immovable, a zero normal, two pivots on one
// planar body, mu < 0, separating bodies; a particle sliding on a floor; long
// double and float instantiate and agree.
TEST(FrictionReference, DegenerateInputsAndScalarTypes)
{
    prob p;
    p.dimension = 2;
    p.restitution = 0.5;
    p.friction = 0.3;
    p.normal = vec3(0, 1, 0);
    nm::body<double> f;
    f.infinite_mass = true;
    nm::body<double> b;
    b.mass = 1;
    b.velocity = vec3(1, -1, 0);
    p.bodies = {f, f};
    EXPECT_EQ(nm::solve_friction(p).status, nm::friction_status::singular);
    p.bodies = {f, b};
    EXPECT_EQ(nm::solve_friction(p).status, nm::friction_status::ok);
    p.normal = vec3::Zero();
    EXPECT_EQ(nm::solve_friction(p).status, nm::friction_status::singular);
    p.normal = vec3(0, 1, 0);
    p.friction = -0.1;
    EXPECT_EQ(nm::solve_friction(p).status, nm::friction_status::no_solution);
    p.friction = 0.3;
    p.bodies[1].velocity = vec3(1, 1, 0); // separating: P_n < 0
    EXPECT_EQ(nm::solve_friction(p).status, nm::friction_status::no_solution);
    nm::body<double> rod;
    rod.particle = false;
    rod.mass = 1;
    rod.inertia(2, 2) = 0.1;
    rod.velocity = vec3(0, -1, 0);
    p.bodies = {f, rod};
    p.point = vec3(0, 0, 0);
    p.pivots = {{1, vec3(-1, 0.5, 0)}, {1, vec3(1, 0.5, 0)}};
    EXPECT_EQ(nm::solve_friction(p).status, nm::friction_status::singular);
    // A particle sliding on a floor: P_n = m (1+e)|u_n|, P_t = -mu P_n.
    p.pivots.clear();
    p.bodies = {f, b};
    p.bodies[1].velocity = vec3(2, -1, 0);
    const auto a = nm::solve_friction(p);
    ASSERT_EQ(a.status, nm::friction_status::ok);
    EXPECT_EQ(a.regime, nm::friction_regime::slide);
    EXPECT_NEAR(a.normal_impulse, 1.5, 1e-14);
    EXPECT_NEAR(a.tangential_impulse.x(), -0.45, 1e-14);
    EXPECT_NEAR(a.velocity[1].x(), 2 - 0.45, 1e-14);
    EXPECT_NEAR(a.velocity[1].y(), 0.5, 1e-14);
    // long double instantiates and agrees.
    nm::problem<long double> q;
    q.dimension = 3;
    q.restitution = 0.5L;
    q.friction = 0.3L;
    q.normal = nm::vec<long double>(0, 1, 0);
    nm::body<long double> fl, bl;
    fl.infinite_mass = true;
    bl.mass = 1;
    bl.velocity = nm::vec<long double>(2, -1, 1);
    q.bodies = {fl, bl};
    const auto al = nm::solve_friction(q);
    ASSERT_EQ(al.status, nm::friction_status::ok);
    EXPECT_NEAR(static_cast<double>(al.normal_impulse), 1.5, 1e-15);
    EXPECT_NEAR(static_cast<double>(al.tangential_impulse.norm()), 0.45, 1e-15);
    // float, a rigid sphere: both 3-D methods.
    nm::problem<float> qf;
    qf.dimension = 3;
    qf.restitution = 0.5f;
    qf.friction = 0.3f;
    qf.normal = nm::vec<float>(0, 2, 0);
    nm::body<float> ff, bf;
    ff.infinite_mass = true;
    bf.particle = false;
    bf.mass = 1;
    bf.inertia = 0.4f * nm::mat<float>::Identity();
    bf.position = nm::vec<float>(0, 1, 0);
    bf.velocity = nm::vec<float>(2, -1, 1);
    qf.bodies = {ff, bf};
    for (auto method : {nm::friction_method::newton, nm::friction_method::enumeration}) {
        nm::friction_options<float> of;
        of.method = method;
        const auto af = nm::solve_friction(qf, of);
        ASSERT_EQ(af.status, nm::friction_status::ok);
        EXPECT_EQ(af.regime, nm::friction_regime::slide);
        EXPECT_NEAR(af.normal_impulse, 1.5f, 1e-5f);
        EXPECT_NEAR(af.tangential_impulse.norm(), 0.45f, 1e-5f);
    }
}

// A body pinned at a point, struck by an immovable one (singular W): the plate of
// tests/codegen/friction/pinned-plate-struck-3d.json on a ball joint at the origin,
// struck at O = (0.5, 1, 0.25) by a ram of infinite mass moving at (0, vr, 0). The
// contact point can only move perpendicular to the lever l = O - E, so W has rank 2
// (its smallest singular value a rounding, ~1e-18, instead of 0), and for mu above the
// lever's slope (|l_t| / l_n = 0.56) an impulse along the lever is inside the cone.
// At e = 0.76, mu = 1, vr = -1 the law has no solution (impactgen solve: none of the
// slides holds); the reference answered ok, stick, with P_n = 1.4e17 along the lever
// and u' = (3, 2, -4) against u'_n = 0.76: Newton's method had run off along the null
// direction, where its convergence test (|F| <= 1000 eps w |x|) and the law's
// tolerance (tol w |x|) pass for any u'. A sweep of e, mu and vr: every ok answer keeps
// restitution to 1e-9 of the approach velocity, with a normal impulse of the contact's
// scale (about 2% of these answered ok with P_n ~ 1e17 and broke restitution).
prob pinned_plate_struck(double e, double mu, double vr)
{
    prob p;
    p.dimension = 3;
    p.restitution = e;
    p.friction = mu;
    nm::body<double> ram;
    ram.infinite_mass = true;
    ram.mass = 0;
    ram.position = vec3(1, 2, 0);
    ram.velocity = vec3(0, vr, 0);
    nm::body<double> plate;
    plate.particle = false;
    plate.mass = 2;
    plate.inertia << 1, 0.1, 0, 0.1, 2, 0.2, 0, 0.2, 1.5;
    plate.position = vec3(0.3, -0.5, 0.2);
    p.bodies = {ram, plate};
    p.body1 = 1; // the contact's bodies: plate, then ram (the normal points from the plate into the ram)
    p.body2 = 0;
    p.point = vec3(0.5, 1, 0.25);
    p.normal = vec3(0, 1, 0);
    p.pivots = {{1, vec3(0, 0, 0)}};
    return p;
}

TEST(FrictionReference, SpatialPinnedPlateStruckByImmovableSingularW)
{
    const prob p = pinned_plate_struck(0.76, 1, -1);
    const nm::friction_contact<double> fc(p);
    ASSERT_TRUE(fc.ok);
    const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::Matrix3d>(fc.W).singularValues();
    EXPECT_LT(sv[2], 1e-14 * sv[0]); // W singular
    for (auto method : {nm::friction_method::automatic, nm::friction_method::newton, nm::friction_method::enumeration}) {
        nm::friction_options<double> opt;
        opt.method = method;
        const auto a = nm::solve_friction(p, opt);
        EXPECT_EQ(a.status, nm::friction_status::no_solution)
            << "method " << int(method) << ": " << nm::friction_regime_name(a.regime) << ", P_n " << a.normal_impulse;
    }
    long ok = 0, none = 0;
    double worst = 0;
    for (double vr : {-1.0, -0.75, -0.5})
        for (int ie = 0; ie <= 100; ++ie)
            for (int im = 1; im <= 20; ++im) {
                const prob q = pinned_plate_struck(ie / 100.0, im / 10.0, vr);
                const auto a = nm::solve_friction(q);
                if (a.status != nm::friction_status::ok) {
                    none += a.status == nm::friction_status::no_solution;
                    continue;
                }
                ++ok;
                const vec3 u = relative_before(q), u1 = a.relative_velocity_after;
                const double residual = std::abs(u1.y() + q.restitution * u.y()) / u.norm();
                worst = std::max(worst, residual);
                EXPECT_LE(residual, tol) << "e " << q.restitution << ", mu " << q.friction << ", vr " << vr << ": "
                                         << nm::friction_regime_name(a.regime) << ", P_n " << a.normal_impulse;
                EXPECT_LE(a.normal_impulse, 100 * q.bodies[1].mass * u.norm()) << "e " << q.restitution << ", mu " << q.friction;
            }
    std::cout << "[friction] pinned plate struck by an immovable ram (W singular): " << ok << " ok, " << none
              << " no solution; worst restitution residual " << worst << " of |u|\n";
    EXPECT_GT(ok, 0);
    EXPECT_GT(none, 0);
}
