// Restitution laws through the impact at the one contact of a system (format version 3: a
// `contacts` file with joints and pivots): the closed form (symbolic/system_process.hpp, the
// contact's 2x2 Delassus matrix with the joints eliminated, through Routh's process) against the
// numeric reference numeric/system_process.hpp (the response found from the whole constrained
// impulse-momentum system in doubles, the process integrated in small normal-impulse steps:
// nothing shared with the closed form), on random struck double pendulums and random pairs of
// rods joined by a pin falling on a rough floor, with exact rationals. Seeded: IMPACTGEN_SEED;
// IMPACTGEN_SAMPLES caps the counts.
#include "numeric/system_process.hpp"
#include "print/answer.hpp"
#include "print/explain.hpp"
#include "print/explain_system.hpp"
#include "print/formulas.hpp"
#include "symbolic/derivation.hpp"
#include "sampling.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/system.hpp"
#include "symbolic/system_process.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <random>
#include <string>

using namespace impactgen;
using num = GiNaC::numeric;
using json = nlohmann::json;
namespace ns = impactgen::numeric::systems;

namespace
{

double dbl(const GiNaC::ex &e)
{
    return GiNaC::ex_to<num>(GiNaC::evalf(e)).to_double();
}

std::string text(const num &x)
{
    std::ostringstream os;
    os << x;
    return os.str();
}

struct rational_rng {
    std::mt19937 g;
    num in(int lo, int hi, int den) // a rational in [lo, hi] with denominator den
    {
        return num(std::uniform_int_distribution<int>(lo * den, hi * den)(g), den);
    }
    num mass() // 2^k times a rational in [1, 2], k in -7..6: mass ratios up to about 1e4
    {
        return in(1, 2, 16) * num(2).power(std::uniform_int_distribution<int>(-7, 6)(g));
    }
};

// A planar body in the file's words and in the reference's.
struct body_spec {
    std::string name;
    bool infinite = false, particle = false;
    num m = 1, I = 0, px = 0, py = 0, vx = 0, vy = 0, w = 0;
};

json body_json(const body_spec &b)
{
    json j{{"name", b.name},
           {"mass", b.infinite ? std::string("inf") : text(b.m)},
           {"position", {text(b.px), text(b.py)}},
           {"velocity", {text(b.vx), text(b.vy)}}};
    if (!b.particle && !b.infinite) {
        j["inertia"] = text(b.I);
        j["angular_velocity"] = text(b.w);
    }
    return j;
}

ns::sys_body body_ref(const body_spec &b)
{
    ns::sys_body r;
    r.infinite_mass = b.infinite;
    r.particle = b.particle;
    r.mass = b.infinite ? 1 : b.m.to_double();
    r.inertia(2, 2) = b.I.to_double();
    r.position = ns::vec3(b.px.to_double(), b.py.to_double(), 0);
    r.velocity = ns::vec3(b.vx.to_double(), b.vy.to_double(), 0);
    r.angular_velocity = ns::vec3(0, 0, b.w.to_double());
    return r;
}

// A rod from (ax, ay) to (bx, by): centre, inertia m l^2 / 12, its centre's velocity from the
// velocity (vx, vy) of the end a and the spin w.
body_spec rod(const std::string &name, const num &m, const num &ax, const num &ay, const num &bx, const num &by,
              const num &vx, const num &vy, const num &w)
{
    body_spec r;
    r.name = name;
    r.m = m;
    r.I = m * ((bx - ax) * (bx - ax) + (by - ay) * (by - ay)) / 12;
    r.px = (ax + bx) / 2, r.py = (ay + by) / 2;
    r.w = w;
    r.vx = vx - w * (r.py - ay), r.vy = vy + w * (r.px - ax);
    return r;
}

struct case_spec {
    std::vector<body_spec> bodies;
    std::vector<std::pair<std::string, std::array<num, 2>>> pivots; // body, point
    std::vector<std::pair<std::array<std::string, 2>, std::array<num, 2>>> joints;
    std::array<std::string, 2> contact_bodies;
    std::array<num, 2> point, normal;
    num mu, e;
};

json file_of(const case_spec &c, const std::string &law)
{
    json j{{"dimension", 2}, {"restitution", text(c.e)}};
    for (const body_spec &b : c.bodies)
        j["bodies"].push_back(body_json(b));
    for (const auto &[b, q] : c.pivots)
        j["pivots"].push_back({{"body", b}, {"point", {text(q[0]), text(q[1])}}});
    for (const auto &[bs, q] : c.joints)
        j["joints"].push_back({{"bodies", {bs[0], bs[1]}}, {"point", {text(q[0]), text(q[1])}}});
    j["contacts"] = json::array({{{"bodies", {c.contact_bodies[0], c.contact_bodies[1]}},
                                  {"point", {text(c.point[0]), text(c.point[1])}},
                                  {"normal", {text(c.normal[0]), text(c.normal[1])}},
                                  {"friction", text(c.mu)},
                                  {"law", law}}});
    return j;
}

std::size_t index_of(const case_spec &c, const std::string &name)
{
    for (std::size_t k = 0; k < c.bodies.size(); ++k)
        if (c.bodies[k].name == name)
            return k;
    return ns::fixed_frame;
}

ns::sys_problem reference_of(const case_spec &c)
{
    ns::sys_problem p;
    for (const body_spec &b : c.bodies)
        p.bodies.push_back(body_ref(b));
    for (const auto &[b, q] : c.pivots)
        p.links.push_back({ns::fixed_frame, index_of(c, b), ns::vec3(q[0].to_double(), q[1].to_double(), 0)});
    for (const auto &[bs, q] : c.joints)
        p.links.push_back({index_of(c, bs[0]), index_of(c, bs[1]), ns::vec3(q[0].to_double(), q[1].to_double(), 0)});
    ns::sys_contact k;
    k.body1 = index_of(c, c.contact_bodies[0]);
    k.body2 = index_of(c, c.contact_bodies[1]);
    k.point = ns::vec3(c.point[0].to_double(), c.point[1].to_double(), 0);
    k.normal = ns::vec3(c.normal[0].to_double(), c.normal[1].to_double(), 0);
    k.restitution = c.e.to_double();
    p.contacts.push_back(k);
    return p;
}

// The relative normal velocity u . n of the contact (body 2 minus body 1), exactly.
num approach(const case_spec &c)
{
    num u[2] = {0, 0};
    for (int s = 0; s < 2; ++s) {
        const body_spec &b = c.bodies[index_of(c, c.contact_bodies[static_cast<std::size_t>(s)])];
        const num sg = s ? 1 : -1;
        u[0] += sg * (b.vx - b.w * (c.point[1] - b.py));
        u[1] += sg * (b.vy + b.w * (c.point[0] - b.px));
    }
    return u[0] * c.normal[0] + u[1] * c.normal[1];
}

// A double pendulum (two rods, pivot at the origin, pin between them) struck at the lower rod's
// end by a ball, at rest or swinging; the normal of any direction and length.
case_spec struck_double_pendulum(rational_rng &r)
{
    for (;;) {
        case_spec c;
        const num jx = r.in(-1, 1, 8), jy = r.in(-2, -1, 8), ex = jx + r.in(-1, 1, 8), ey = jy + r.in(-2, -1, 8);
        const num w1 = r.in(-2, 2, 4), w2 = r.in(-2, 2, 4);
        const body_spec upper = rod("upper", r.mass(), 0, 0, jx, jy, 0, 0, w1);
        const body_spec lower = rod("lower", r.mass(), jx, jy, ex, ey, -w1 * jy, w1 * jx, w2);
        body_spec ball;
        ball.name = "ball";
        ball.particle = true;
        ball.m = r.mass();
        c.normal = {r.in(-2, 2, 4), r.in(-2, 2, 4)};
        if (c.normal[0].is_zero() && c.normal[1].is_zero())
            continue;
        ball.px = ex - c.normal[0] / 8, ball.py = ey - c.normal[1] / 8;
        ball.vx = r.in(-2, 2, 8), ball.vy = r.in(-2, 2, 8);
        c.bodies = {upper, lower, ball};
        c.pivots = {{"upper", {0, 0}}};
        c.joints = {{{"upper", "lower"}, {jx, jy}}};
        c.contact_bodies = {"ball", "lower"};
        c.point = {ex, ey};
        c.mu = r.in(0, 2, 16);
        c.e = r.in(0, 1, 16);
        if (!c.mu.is_zero() && approach(c) < 0)
            return c;
    }
}

// Two free rods joined by a pin, falling on a rough floor (infinite mass at rest) with the free
// end of the first; the floor's normal tilted.
case_spec jointed_rods_on_floor(rational_rng &r)
{
    for (;;) {
        case_spec c;
        const num jx = r.in(-1, 1, 8), jy = r.in(1, 2, 8), fx = jx + r.in(-1, 1, 8), fy = jy + r.in(1, 2, 8);
        const num wa = r.in(-3, 3, 4), wb = r.in(-3, 3, 4), vx = r.in(-1, 1, 8), vy = r.in(-2, 0, 8);
        const body_spec a = rod("a", r.mass(), 0, 0, jx, jy, vx, vy, wa);
        const num vjx = vx - wa * jy, vjy = vy + wa * jx; // the pin's velocity
        const body_spec b = rod("b", r.mass(), jx, jy, fx, fy, vjx, vjy, wb);
        body_spec floor;
        floor.name = "floor";
        floor.infinite = true;
        floor.py = -1;
        c.bodies = {floor, a, b};
        c.joints = {{{"a", "b"}, {jx, jy}}};
        c.contact_bodies = {"floor", "a"};
        c.point = {0, 0};
        c.normal = {r.in(-1, 1, 4), 1};
        c.mu = r.in(0, 2, 16);
        c.e = r.in(0, 1, 16);
        if (!c.mu.is_zero() && approach(c) < 0)
            return c;
    }
}

// The closed form and the integration agree on one case; counts what was compared.
struct tally {
    int compared = 0, wedged = 0, reversed = 0, stuck = 0;
    double worst = 0;
};

void agree(const case_spec &c, const std::string &law, tally &t)
{
    const problem p = read_problem(file_of(c, law).dump(), "test");
    const ns::sys_process_answer ref = ns::integrate_system_process(
        reference_of(c), c.mu.to_double(),
        law == "poisson" ? impactgen::numeric::process_law::poisson : impactgen::numeric::process_law::energetic);
    system_answer a;
    try {
        a = solve_system(p);
    } catch (const input_error &err) { // the contact wedges: the integration does not end either
        EXPECT_NE(std::string(err.what()).find("wedges"), std::string::npos) << err.what();
        EXPECT_FALSE(ref.process.ok);
        ++t.wedged;
        return;
    }
    ASSERT_TRUE(ref.process.ok) << file_of(c, law).dump();
    ASSERT_FALSE(a.result.process.empty());
    // The integrator is exact within each linear step; its error is the rounding of thousands of
    // steps (~1e-12 relative) and its slip threshold (a slip below 1e-11 of the velocity scale
    // counts as stopped, which moves a phase boundary by up to ~1e-7 relative where the slip
    // decelerates slowly: tests/codegen/laws.cpp measured 8e-8). 1e-6 of the velocity scale
    // bounds both; a wrong phase sequence is off by O(mu) of it.
    double scale = 0;
    for (const body_spec &b : c.bodies)
        scale = std::max({scale, std::abs(b.vx.to_double()), std::abs(b.vy.to_double()), std::abs(b.w.to_double())});
    double err = 0;
    for (std::size_t k = 0; k < c.bodies.size(); ++k) {
        for (int d = 0; d < 2; ++d)
            err = std::max(err, std::abs(dbl(a.result.velocity[k][d]) - ref.velocity[k][d]));
        err = std::max(err, std::abs(dbl(a.result.angular_velocity[k][2]) - ref.angular_velocity[k][2]));
    }
    EXPECT_LE(err, 1e-6 * scale) << law << ": " << file_of(c, law).dump();
    t.worst = std::max(t.worst, err / scale);
    const double N = dbl(a.result.normal_impulse[0]);
    EXPECT_NEAR(N, ref.process.normal_impulse, 1e-6 * (std::abs(N) + 1e-300)) << file_of(c, law).dump();
    EXPECT_NEAR(dbl(a.result.process.back().normal_impulse_end), N, 1e-12 * N);
    if (law == "energetic") { // Stronge's law never creates energy: decided exactly
        EXPECT_NE(decide(a.energy_before - a.energy_after), decision::negative) << file_of(c, law).dump();
    }
    t.reversed += a.result.process.back().kind == phase_kind::reverse;
    t.stuck += a.result.process.back().kind == phase_kind::stick;
    ++t.compared;
}

void random_agreement(case_spec (*make)(rational_rng &), const std::string &law, unsigned salt)
{
    rational_rng r{std::mt19937(impactgen::testing::seed_from_env() + salt)};
    const int n = impactgen::testing::samples_from_env(1000);
    tally t;
    for (int i = 0; i < n; ++i)
        agree(make(r), law, t);
    EXPECT_GT(t.compared, n * 3 / 4);
    EXPECT_GT(t.reversed + t.stuck, 0) << "no sample left the first slide";
    std::printf("[ %s ] %d compared (%d reversed, %d stuck at the end), %d wedged; worst %.3g of the velocity scale\n",
                law.c_str(), t.compared, t.reversed, t.stuck, t.wedged, t.worst);
}

} // namespace

TEST(SystemProcessRandom, DoublePendulumPoisson)
{
    random_agreement(struck_double_pendulum, "poisson", 1);
}
TEST(SystemProcessRandom, DoublePendulumEnergetic)
{
    random_agreement(struck_double_pendulum, "energetic", 2);
}
TEST(SystemProcessRandom, JointedRodsOnFloorPoisson)
{
    random_agreement(jointed_rods_on_floor, "poisson", 3);
}
TEST(SystemProcessRandom, JointedRodsOnFloorEnergetic)
{
    random_agreement(jointed_rods_on_floor, "energetic", 4);
}

// Without a stop of the slip (one phase, a slide) Poisson's impulse ratio and Newton's ratio of
// velocities give the same answer: u_n is linear in P_n along one phase, so u'_n = -e u_n exactly
// when P_n = (1 + e) P_c. Decided exactly; the energetic law agrees there too (b x^2 / 2 work).
TEST(SystemProcess, OnePhasePoissonIsNewton)
{
    rational_rng r{std::mt19937(impactgen::testing::seed_from_env() + 5)};
    int one_phase = 0;
    for (int i = 0; i < 60; ++i) {
        const case_spec c = i % 2 ? struck_double_pendulum(r) : jointed_rods_on_floor(r);
        system_answer a[3];
        const char *laws[3] = {"poisson", "energetic", "newton"};
        try {
            for (int k = 0; k < 3; ++k)
                a[k] = solve_system(read_problem(file_of(c, laws[k]).dump(), "test"));
        } catch (const input_error &) {
            continue; // wedges
        }
        if (a[0].result.process.size() != 1 || a[0].result.process[0].kind != phase_kind::slide)
            continue;
        ++one_phase;
        for (int k = 1; k < 3; ++k)
            for (std::size_t b = 0; b < c.bodies.size(); ++b) {
                for (int d = 0; d < 2; ++d)
                    EXPECT_EQ(decide(a[0].result.velocity[b][d] - a[k].result.velocity[b][d]), decision::zero)
                        << laws[k] << ": " << file_of(c, "poisson").dump();
                EXPECT_EQ(decide(a[0].result.angular_velocity[b][2] - a[k].result.angular_velocity[b][2]),
                          decision::zero);
            }
    }
    EXPECT_GT(one_phase, 5);
}

// The answer of a `contacts` file: "process" and its last phase as "regime" in contacts[0], the
// phases' ends increasing to the normal impulse; a contact that reverses says "reverse".
TEST(SystemProcess, AnswerCarriesTheProcess)
{
    rational_rng r{std::mt19937(impactgen::testing::seed_from_env() + 6)};
    int reversed = 0;
    for (int i = 0; i < 400 && reversed < 3; ++i) {
        const case_spec c = struck_double_pendulum(r);
        const problem p = read_problem(file_of(c, "energetic").dump(), "test");
        system_answer a;
        try {
            a = solve_system(p);
        } catch (const input_error &) {
            continue;
        }
        const nlohmann::ordered_json j = print::system_answer_json(p, a);
        const auto &k = j["contacts"][0];
        ASSERT_TRUE(k.contains("process")) << j.dump();
        EXPECT_EQ(k["regime"], k["process"].back()["phase"]);
        double last = 0;
        for (const auto &ph : k["process"]) {
            EXPECT_GT(ph["normal_impulse_end"].get<double>(), last);
            last = ph["normal_impulse_end"].get<double>();
        }
        EXPECT_NEAR(last, k["normal_impulse"].get<double>(), 1e-12 * last);
        reversed += k["regime"] == "reverse";
    }
    EXPECT_EQ(reversed, 3);
}

// Still refused, each in one line naming the key: several contacts with such a law, 3-D.
TEST(SystemProcess, RefusedBeyondOneContactIn2D)
{
    rational_rng r{std::mt19937(7)};
    json two = file_of(struck_double_pendulum(r), "poisson");
    two["contacts"].push_back(two["contacts"][0]);
    try {
        (void)read_problem(two.dump(), "test");
        ADD_FAILURE() << "two contacts under poisson with friction were read";
    } catch (const input_error &e) {
        EXPECT_NE(std::string(e.what()).find("contacts[0].law"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("one contact"), std::string::npos) << e.what();
    }
    json inf = file_of(struck_double_pendulum(r), "energetic");
    inf["contacts"][0]["friction"] = "inf";
    EXPECT_THROW((void)read_problem(inf.dump(), "test"), input_error);
}

// With symbols, formulas gives the phase sequences as candidates with their conditions; explain
// teaches the process of the system: a section per phase sequence the library's process has.
TEST(SystemProcess, FormulasListSequencesExplainTeachesThem)
{
    rational_rng r{std::mt19937(8)};
    json j = file_of(struck_double_pendulum(r), "energetic");
    j["restitution"] = "e";
    j["contacts"][0]["friction"] = "mu";
    const problem p = read_problem(j.dump(), "test");
    const std::string f = print::system_formulas_text(p, false);
    EXPECT_NE(f.find("Routh's process"), std::string::npos) << f;
    EXPECT_NE(f.find("then reverse"), std::string::npos) << f;
    EXPECT_NE(f.find("then stick"), std::string::npos) << f;
    const print::document doc = print::explain_system(derive(p));
    std::size_t sequences = 0, delassus = 0;
    for (const print::section &s : doc.sections) {
        sequences += s.title.find("Phase sequence ") != std::string::npos ? 1 : 0;
        delassus += s.title.find("The Delassus matrix") != std::string::npos ? 1 : 0;
    }
    std::size_t process = 0;
    for (const system_candidate &c : system_process_candidates(p))
        process += c.process.empty() ? 0 : 1;
    EXPECT_EQ(delassus, 1u);
    EXPECT_GT(process, 1u);
    EXPECT_EQ(sequences, process);
}
