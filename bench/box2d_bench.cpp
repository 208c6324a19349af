// The same two-body planar impacts solved three ways, timed and compared with the exact
// answer:
//   box2d/<case>         Box2D 2.4 (Debian's libbox2d-dev): one b2World::Step of a world that
//                        holds the two bodies in contact, warm starting off (every step is a
//                        fresh impact), 8 velocity and 3 position iterations, restitution
//                        threshold 0 (Newton's law at every approach speed). The step also
//                        re-detects the contact (broad and narrow phase) and integrates the
//                        positions: that is what an engine pays per contact pair and step.
//   generated/<case>     the generated header generated/planar_friction.hpp on the same
//                        contact (point and normal read from Box2D's manifold), frame
//                        inputs precomputed, with_energy_lost = false.
//   eigen/<case>         the Eigen reference numeric/friction_solver.hpp (an enumeration of
//                        the law's regimes in double): the "exact" answer the errors are
//                        measured against (the generated header agrees with it to rounding;
//                        the set-up checks that before anything is timed).
// Cases (seeded, 256 contacts each):
//   disc-disc   two dynamic discs (radius 0.5, densities 0.5..2), approaching, spinning,
//               e in [0, 1], mu in [0, 1]: a central impact (the normal passes through both
//               centres), friction acting through the spins.
//   box-box     a dynamic box tilted 15..40 degrees falls with spin on one corner onto a
//               dynamic box lying flat (densities 0.5..2): a non-central impact, one
//               manifold point.
// (A two-point manifold, a box landing on two corners, is in box2d_manifold_bench.cpp.)
// Counters: ns_per_impact; for box2d/<case> also max_rel_error and mean_rel_error: the
// largest and mean |v'_box2d - v'_exact| / max(|v|, |v'|) over every body's velocity and
// spin (spin times the body's size) of the case's contacts. Box2D computes in float and
// solves the contact by sequential impulses; the exact answer is the law itself.
#include "planar_friction.hpp"

#include "numeric/friction_solver.hpp"

#include <benchmark/benchmark.h>
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace gen = impactgen::generated;
namespace nm = impactgen::numeric;

namespace {

constexpr int kContacts = 256;
constexpr float kStep = 1.0f / 60.0f;

// One contact pair: its Box2D world and the state before impact.
struct pair_case {
    std::unique_ptr<b2World> world;
    b2Body* body[2] = {nullptr, nullptr};
    b2Vec2 position[2];
    float angle[2] = {0, 0};
    b2Vec2 velocity[2];
    float spin[2] = {0, 0};
    double mass[2] = {0, 0}, inertia[2] = {0, 0}, size[2] = {0, 0};
    double e = 0, mu = 0;
    b2Vec2 point, normal; // from Box2D's manifold; normal from body 0 into body 1
    double nx = 0, ny = 0; // the normal made unit in double (Box2D's float normal is unit to 6e-8)
    std::vector<double> exact;  // v_x, v_y, w of body 0 then body 1 (Eigen reference)
    double inputs[16] = {};     // planar_friction's inputs in the contact frame
};

void reset(pair_case& c)
{
    for (int i = 0; i < 2; ++i) {
        c.body[i]->SetTransform(c.position[i], c.angle[i]);
        c.body[i]->SetLinearVelocity(c.velocity[i]);
        c.body[i]->SetAngularVelocity(c.spin[i]);
        c.body[i]->SetAwake(true);
    }
}

b2Body* add_body(b2World& w, const b2Shape& shape, b2Vec2 p, float angle, float density, double e, double mu)
{
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position = p;
    bd.angle = angle;
    b2Body* b = w.CreateBody(&bd);
    b2FixtureDef fd;
    fd.shape = &shape;
    fd.density = density;
    fd.friction = static_cast<float>(mu); // mixed as sqrt(mu mu) = mu
    fd.restitution = static_cast<float>(e); // mixed as max(e, e) = e
    fd.restitutionThreshold = 0.0f;
    b->CreateFixture(&fd);
    return b;
}

// The contact's point and normal as Box2D's narrow phase finds them (a step of length 0
// detects contacts without solving them).
bool read_manifold(pair_case& c)
{
    c.world->Step(0.0f, 8, 3);
    for (b2Contact* k = c.world->GetContactList(); k; k = k->GetNext()) {
        if (!k->IsTouching() || k->GetManifold()->pointCount != 1)
            continue;
        b2WorldManifold wm;
        k->GetWorldManifold(&wm);
        c.point = wm.points[0];
        c.normal = wm.normal; // from fixture A's body into fixture B's body
        if (k->GetFixtureA()->GetBody() != c.body[0])
            c.normal = -c.normal;
        const double l = std::hypot(static_cast<double>(c.normal.x), static_cast<double>(c.normal.y));
        c.nx = c.normal.x / l;
        c.ny = c.normal.y / l;
        return true;
    }
    return false;
}

// The contact as the Eigen reference takes it.
nm::problem<double> reference_problem(const pair_case& c)
{
    nm::problem<double> p;
    p.dimension = 2;
    p.restitution = c.e;
    p.friction = c.mu;
    for (int i = 0; i < 2; ++i) {
        nm::body<double> b;
        b.particle = false;
        b.mass = c.mass[i];
        b.inertia(2, 2) = c.inertia[i];
        b.position = {c.position[i].x, c.position[i].y, 0};
        b.velocity = {c.velocity[i].x, c.velocity[i].y, 0};
        b.angular_velocity = {0, 0, c.spin[i]};
        p.bodies.push_back(b);
    }
    p.point = {c.point.x, c.point.y, 0};
    p.normal = {c.nx, c.ny, 0};
    return p;
}

// The Eigen reference's answer and planar_friction's inputs for the contact as read.
bool exact_answer(pair_case& c)
{
    const nm::problem<double> p = reference_problem(c);
    const nm::friction_answer<double> a = nm::solve_friction(p);
    if (a.status != nm::friction_status::ok)
        return false;
    c.exact.clear();
    for (int i = 0; i < 2; ++i) {
        c.exact.push_back(a.velocity[i][0]);
        c.exact.push_back(a.velocity[i][1]);
        c.exact.push_back(a.angular_velocity[i][2]);
    }
    // The header's frame: n, t = (n_y, -n_x) (t x n = z); positions C - O.
    const double nx = c.nx, ny = c.ny, tx = ny, ty = -nx;
    double* in = c.inputs;
    in[0] = c.e;
    in[1] = c.mu;
    for (int i = 0; i < 2; ++i) {
        const double rx = c.position[i].x - c.point.x, ry = c.position[i].y - c.point.y;
        double* b = in + 2 + 7 * i;
        b[0] = c.mass[i];
        b[1] = c.inertia[i];
        b[2] = rx * tx + ry * ty;
        b[3] = rx * nx + ry * ny;
        b[4] = c.velocity[i].x * tx + c.velocity[i].y * ty;
        b[5] = c.velocity[i].x * nx + c.velocity[i].y * ny;
        b[6] = c.spin[i];
    }
    return true;
}

gen::friction_status generated_answer(const pair_case& c, gen::planar_friction_result<double>& r)
{
    const double* x = c.inputs;
    return gen::planar_friction<double, false>(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8], x[9], x[10],
                                               x[11], x[12], x[13], x[14], x[15], r);
}

// The generated answer in world axes (v_x, v_y, w per body).
std::vector<double> generated_world(const pair_case& c)
{
    gen::planar_friction_result<double> r;
    if (generated_answer(c, r) != gen::friction_status::ok)
        return {};
    const double nx = c.nx, ny = c.ny, tx = ny, ty = -nx;
    return {r.v_t1 * tx + r.v_n1 * nx, r.v_t1 * ty + r.v_n1 * ny, r.w_b1,
            r.v_t2 * tx + r.v_n2 * nx, r.v_t2 * ty + r.v_n2 * ny, r.w_b2};
}

// |a - b| / scale over every component, velocities and spins times the body's size.
double relative_error(const pair_case& c, const std::vector<double>& a, const std::vector<double>& b)
{
    double scale = 0, err = 0;
    for (int i = 0; i < 2; ++i) {
        scale = std::max({scale, static_cast<double>(std::hypot(c.velocity[i].x, c.velocity[i].y)), std::fabs(c.spin[i]) * c.size[i]});
        scale = std::max({scale, std::hypot(b[3 * i], b[3 * i + 1]), std::fabs(b[3 * i + 2]) * c.size[i]});
        for (int k = 0; k < 3; ++k)
            err = std::max(err, std::fabs(a[3 * i + k] - b[3 * i + k]) * (k == 2 ? c.size[i] : 1.0));
    }
    return err / scale;
}

std::vector<double> box2d_answer(pair_case& c)
{
    reset(c);
    c.world->Step(kStep, 8, 3);
    std::vector<double> v;
    for (int i = 0; i < 2; ++i) {
        const b2Vec2 u = c.body[i]->GetLinearVelocity();
        v.push_back(u.x);
        v.push_back(u.y);
        v.push_back(c.body[i]->GetAngularVelocity());
    }
    return v;
}

// Bodies approach at the contact: flip both velocities and spins otherwise.
bool approaching(const pair_case& c)
{
    double u = 0;
    for (int i = 0; i < 2; ++i) {
        const double rx = c.point.x - c.position[i].x, ry = c.point.y - c.position[i].y;
        const double vx = c.velocity[i].x - c.spin[i] * ry, vy = c.velocity[i].y + c.spin[i] * rx;
        u += (i == 0 ? -1 : 1) * (vx * c.nx + vy * c.ny);
    }
    return u < -1e-3;
}

bool make_case(pair_case& c, const std::string& kind, std::mt19937_64& g)
{
    std::uniform_real_distribution<double> U(-1, 1), D(0.5, 2), E(0, 1), T(15, 40);
    c.world = std::make_unique<b2World>(b2Vec2(0, 0));
    c.world->SetWarmStarting(false);
    c.e = E(g);
    c.mu = E(g);
    float density[2] = {static_cast<float>(D(g)), static_cast<float>(D(g))};
    if (kind == "disc-disc") {
        b2CircleShape s;
        s.m_radius = 0.5f;
        const double a = 3.14159265358979 * U(g);
        c.position[0] = b2Vec2(0, 0);
        c.position[1] = b2Vec2(static_cast<float>(0.999 * std::cos(a)), static_cast<float>(0.999 * std::sin(a)));
        for (int i = 0; i < 2; ++i) {
            c.body[i] = add_body(*c.world, s, c.position[i], 0, density[i], c.e, c.mu);
            c.size[i] = 0.5;
        }
    } else {
        b2PolygonShape flat, tilted;
        flat.SetAsBox(1.0f, 0.25f);
        tilted.SetAsBox(0.4f, 0.2f);
        const double th = T(g) * 3.14159265358979 / 180 * (U(g) < 0 ? -1 : 1);
        // the tilted box's lowest corner 0.005 above the flat box's top face (inside Box2D's skin)
        const double hx = 0.4, hy = 0.2;
        const double low = -std::fabs(hx * std::sin(th)) - hy * std::cos(th);
        c.position[0] = b2Vec2(0, 0);
        c.position[1] = b2Vec2(static_cast<float>(0.3 * U(g)), static_cast<float>(0.25 - low + 0.005));
        c.angle[1] = static_cast<float>(th);
        c.body[0] = add_body(*c.world, flat, c.position[0], 0, density[0], c.e, c.mu);
        c.body[1] = add_body(*c.world, tilted, c.position[1], c.angle[1], density[1], c.e, c.mu);
        c.size[0] = std::hypot(1.0, 0.25);
        c.size[1] = std::hypot(hx, hy);
    }
    for (int i = 0; i < 2; ++i) {
        c.mass[i] = c.body[i]->GetMass();
        c.inertia[i] = c.body[i]->GetInertia() - c.mass[i] * b2Dot(c.body[i]->GetLocalCenter(), c.body[i]->GetLocalCenter());
        c.position[i] = c.body[i]->GetWorldCenter();
        c.velocity[i] = b2Vec2(static_cast<float>(2 * U(g)), static_cast<float>(2 * U(g)));
        c.spin[i] = static_cast<float>(2 * U(g));
    }
    // bodies placed by their centre; Box2D keeps the origin = centre for these shapes
    if (!read_manifold(c))
        return false;
    if (!approaching(c))
        for (int i = 0; i < 2; ++i) {
            c.velocity[i] = -c.velocity[i];
            c.spin[i] = -c.spin[i];
        }
    if (!approaching(c))
        return false;
    reset(c);
    return exact_answer(c);
}

std::vector<pair_case>& cases(const std::string& kind)
{
    static std::vector<pair_case> disc, box;
    std::vector<pair_case>& set = kind == "disc-disc" ? disc : box;
    if (!set.empty())
        return set;
    std::mt19937_64 g(kind == "disc-disc" ? 20261127 : 20261128);
    for (int tries = 0; static_cast<int>(set.size()) < kContacts && tries < 100 * kContacts; ++tries) {
        pair_case c;
        if (!make_case(c, kind, g))
            continue;
        // the header agrees with the reference before anything is timed (to 1e-6: both decide
        // the regime with a tolerance of about sqrt(eps), so near a stick/slide boundary they may
        // take the two sides of it, whose answers differ by about that tolerance)
        const std::vector<double> gw = generated_world(c);
        if (gw.empty() || relative_error(c, gw, c.exact) > 1e-6) {
            std::fprintf(stderr, "box2d_bench: generated and Eigen answers differ on a %s case\n", kind.c_str());
            for (std::size_t k = 0; k < gw.size() && k < c.exact.size(); ++k)
                std::fprintf(stderr, "  %zu: %.17g %.17g\n", k, gw[k], c.exact[k]);
            std::exit(1);
        }
        set.push_back(std::move(c));
    }
    if (static_cast<int>(set.size()) < kContacts) {
        std::fprintf(stderr, "box2d_bench: only %zu %s cases\n", set.size(), kind.c_str());
        std::exit(1);
    }
    return set;
}

void box2d(benchmark::State& st, const std::string& kind)
{
    std::vector<pair_case>& set = cases(kind);
    double worst = 0, sum = 0;
    for (pair_case& c : set) {
        const double err = relative_error(c, box2d_answer(c), c.exact);
        worst = std::max(worst, err);
        sum += err;
    }
    std::size_t i = 0;
    for (auto _ : st) {
        pair_case& c = set[i++ % set.size()];
        reset(c);
        c.world->Step(kStep, 8, 3);
        benchmark::DoNotOptimize(c.body[1]->GetLinearVelocity());
    }
    st.counters["ns_per_impact"] = benchmark::Counter(static_cast<double>(st.iterations()),
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    st.counters["max_rel_error"] = worst;
    st.counters["mean_rel_error"] = sum / static_cast<double>(set.size());
}

void generated(benchmark::State& st, const std::string& kind)
{
    const std::vector<pair_case>& set = cases(kind);
    gen::planar_friction_result<double> r;
    std::size_t i = 0;
    for (auto _ : st) {
        benchmark::DoNotOptimize(generated_answer(set[i++ % set.size()], r));
        benchmark::DoNotOptimize(r);
    }
    st.counters["ns_per_impact"] = benchmark::Counter(static_cast<double>(st.iterations()),
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void eigen(benchmark::State& st, const std::string& kind)
{
    const std::vector<pair_case>& set = cases(kind);
    std::vector<nm::problem<double>> problems;
    for (const pair_case& c : set)
        problems.push_back(reference_problem(c));
    std::size_t i = 0;
    for (auto _ : st)
        benchmark::DoNotOptimize(nm::solve_friction(problems[i++ % problems.size()]));
    st.counters["ns_per_impact"] = benchmark::Counter(static_cast<double>(st.iterations()),
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

} // namespace

BENCHMARK_CAPTURE(box2d, disc - disc, std::string("disc-disc"))->Name("box2d/disc-disc");
BENCHMARK_CAPTURE(generated, disc - disc, std::string("disc-disc"))->Name("generated/disc-disc");
BENCHMARK_CAPTURE(eigen, disc - disc, std::string("disc-disc"))->Name("eigen/disc-disc");
BENCHMARK_CAPTURE(box2d, box - box, std::string("box-box"))->Name("box2d/box-box");
BENCHMARK_CAPTURE(generated, box - box, std::string("box-box"))->Name("generated/box-box");
BENCHMARK_CAPTURE(eigen, box - box, std::string("box-box"))->Name("eigen/box-box");

BENCHMARK_MAIN();
