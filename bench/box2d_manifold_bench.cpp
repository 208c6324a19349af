// A two-point manifold: a box (2 x 0.5, density 0.5..2) landing flat on the static ground with
// both bottom corners approaching it (spin small enough), smooth (friction 0), e in [0, 1]:
//   box2d/two-corners      one b2World::Step of the two bodies (warm starting off, 8 velocity and
//                          3 position iterations, restitution threshold 0): Box2D's block solver of
//                          its two-point manifold;
//   reference/two-corners  the exact answer of impactgen's numeric reference for systems
//                          (numeric/system_reference.hpp: the active sets of the two contacts, the
//                          impulse-momentum system solved for each, the law checked), on the
//                          contact points and normal of Box2D's manifold.
// Counters: ns_per_impact; for box2d/two-corners also max_rel_error and mean_rel_error of the
// box's velocity and spin (times its half-diagonal) against the exact answer, relative to the
// largest of them before and after. 256 seeded landings.
#include "numeric/system_reference.hpp"

#include <benchmark/benchmark.h>
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

namespace
{

namespace sys = impactgen::numeric::systems;

struct landing {
    std::unique_ptr<b2World> world;
    b2Body *box = nullptr;
    b2Vec2 position, velocity;
    float spin = 0;
    sys::sys_problem problem;
    double exact[3] = {0, 0, 0}; // v_x, v_y, w of the box after impact
    double size = 0;
};

void reset(landing &c)
{
    c.box->SetTransform(c.position, 0);
    c.box->SetLinearVelocity(c.velocity);
    c.box->SetAngularVelocity(c.spin);
    c.box->SetAwake(true);
}

bool make_landing(landing &c, std::mt19937_64 &g)
{
    std::uniform_real_distribution<double> U(-1, 1), D(0.5, 2), E(0, 1);
    const double e = E(g), hx = 1.0, hy = 0.25;
    c.world = std::make_unique<b2World>(b2Vec2(0, 0));
    c.world->SetWarmStarting(false);
    b2BodyDef gd; // the ground: a static box whose top face is y = 0
    gd.position.Set(0, -0.5f);
    b2Body *ground = c.world->CreateBody(&gd);
    b2PolygonShape gs;
    gs.SetAsBox(5.0f, 0.5f);
    b2FixtureDef gf;
    gf.shape = &gs;
    gf.friction = 0;
    gf.restitution = static_cast<float>(e);
    gf.restitutionThreshold = 0;
    ground->CreateFixture(&gf);
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    c.position.Set(static_cast<float>(0.5 * U(g)), static_cast<float>(hy + 0.005)); // inside Box2D's skin
    bd.position = c.position;
    c.box = c.world->CreateBody(&bd);
    b2PolygonShape bs;
    bs.SetAsBox(static_cast<float>(hx), static_cast<float>(hy));
    b2FixtureDef bf;
    bf.shape = &bs;
    bf.density = static_cast<float>(D(g));
    bf.friction = 0;
    bf.restitution = static_cast<float>(e);
    bf.restitutionThreshold = 0;
    c.box->CreateFixture(&bf);
    // both corners approach: v_y -/+ w hx < 0
    const double vy = -(0.5 + 2 * E(g)), w = 0.9 * U(g) * std::fabs(vy) / hx;
    c.velocity.Set(static_cast<float>(2 * U(g)), static_cast<float>(vy));
    c.spin = static_cast<float>(w);
    c.size = std::hypot(hx, hy);
    reset(c);
    c.world->Step(0.0f, 8, 3); // detect the contact
    const b2Contact *k = c.world->GetContactList();
    if (!k || !k->IsTouching() || k->GetManifold()->pointCount != 2)
        return false;
    b2WorldManifold wm;
    k->GetWorldManifold(&wm);
    b2Vec2 n = wm.normal; // from fixture A's body into fixture B's body
    if (k->GetFixtureA()->GetBody() != ground)
        n = -n;
    sys::sys_problem &p = c.problem;
    p.dimension = 2;
    sys::sys_body gb, box;
    gb.infinite_mass = true;
    gb.position = sys::vec3(0, -0.5, 0);
    box.particle = false;
    box.mass = c.box->GetMass();
    box.inertia = sys::mat3::Zero();
    box.inertia(2, 2) = c.box->GetInertia(); // about the centre (the body's origin)
    box.position = sys::vec3(c.position.x, c.position.y, 0);
    box.velocity = sys::vec3(c.velocity.x, c.velocity.y, 0);
    box.angular_velocity = sys::vec3(0, 0, c.spin);
    p.bodies = {gb, box};
    const double l = std::hypot(static_cast<double>(n.x), static_cast<double>(n.y));
    for (int i = 0; i < 2; ++i) {
        sys::sys_contact sc;
        sc.body1 = 0;
        sc.body2 = 1;
        sc.point = sys::vec3(wm.points[i].x, wm.points[i].y, 0);
        sc.normal = sys::vec3(n.x / l, n.y / l, 0);
        sc.restitution = e;
        p.contacts.push_back(sc);
    }
    const sys::sys_answer a = sys::solve_reference(p);
    if (a.holding != 1)
        return false;
    c.exact[0] = a.velocity[1].x();
    c.exact[1] = a.velocity[1].y();
    c.exact[2] = a.angular_velocity[1].z();
    return true;
}

std::vector<landing> &landings()
{
    static std::vector<landing> set;
    if (!set.empty())
        return set;
    std::mt19937_64 g(20261129);
    for (int tries = 0; set.size() < 256 && tries < 100000; ++tries) {
        landing c;
        if (make_landing(c, g))
            set.push_back(std::move(c));
    }
    if (set.size() < 256) {
        std::fprintf(stderr, "box2d_manifold_bench: only %zu landings\n", set.size());
        std::exit(1);
    }
    return set;
}

double relative_error(const landing &c, const double *a)
{
    const double scale = std::max({std::hypot(static_cast<double>(c.velocity.x), static_cast<double>(c.velocity.y)),
                                   std::fabs(static_cast<double>(c.spin)) * c.size, std::hypot(c.exact[0], c.exact[1]),
                                   std::fabs(c.exact[2]) * c.size});
    const double err =
        std::max({std::fabs(a[0] - c.exact[0]), std::fabs(a[1] - c.exact[1]), std::fabs(a[2] - c.exact[2]) * c.size});
    return err / scale;
}

void box2d_two_corners(benchmark::State &st)
{
    std::vector<landing> &set = landings();
    double worst = 0, sum = 0;
    for (landing &c : set) {
        reset(c);
        c.world->Step(1.0f / 60.0f, 8, 3);
        const b2Vec2 v = c.box->GetLinearVelocity();
        const double got[3] = {v.x, v.y, c.box->GetAngularVelocity()};
        const double err = relative_error(c, got);
        worst = std::max(worst, err);
        sum += err;
    }
    std::size_t i = 0;
    for (auto _ : st) {
        landing &c = set[i++ % set.size()];
        reset(c);
        c.world->Step(1.0f / 60.0f, 8, 3);
        benchmark::DoNotOptimize(c.box->GetLinearVelocity());
    }
    st.counters["ns_per_impact"] = benchmark::Counter(static_cast<double>(st.iterations()),
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    st.counters["max_rel_error"] = worst;
    st.counters["mean_rel_error"] = sum / static_cast<double>(set.size());
}

void reference_two_corners(benchmark::State &st)
{
    const std::vector<landing> &set = landings();
    std::size_t i = 0;
    for (auto _ : st)
        benchmark::DoNotOptimize(sys::solve_reference(set[i++ % set.size()].problem));
    st.counters["ns_per_impact"] = benchmark::Counter(static_cast<double>(st.iterations()),
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

} // namespace

BENCHMARK(box2d_two_corners)->Name("box2d/two-corners");
BENCHMARK(reference_two_corners)->Name("reference/two-corners");
