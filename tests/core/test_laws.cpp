// Restitution laws through the impact (format version 3, "law"): Routh's process in closed form
// (symbolic/routh.hpp) against the num integration in small impulse steps
// (num/process_integrator.hpp), the physics of the laws, and hand-derived exact cases.
// Seeded: IMPACTGEN_SEED; IMPACTGEN_SAMPLES caps the random counts (the sanitizer pass sets it).
#include "numeric/from_problem.hpp"
#include "numeric/process_integrator.hpp"
#include "print/answer.hpp"
#include "sampling.hpp"
#include "symbolic/contact_law.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/routh.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>
#include <variant>

using namespace impactgen;
using namespace GiNaC;
using json = nlohmann::json;
using num = GiNaC::numeric;

namespace
{

double dbl(const ex &e)
{
    const ex v = e.evalf();
    if (!is_a<num>(v)) {
        ADD_FAILURE() << "not a number: " << e;
        return 0;
    }
    return ex_to<num>(v).to_double();
}

restitution_law law_of(const std::string &name)
{
    return law_from_name(name, "test");
}

std::string read_text(const std::string &path)
{
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

problem with_law(const std::string &path, const std::string &law)
{
    json j = json::parse(read_text(path));
    j["contact"]["law"] = law;
    return read_problem(j.dump(), path);
}

regime_case answer_of(const problem &p)
{
    const derivation d = derive(p);
    return select_candidate(d, solve_impact(d));
}

// ---- the contact-level random process: K from random planar bodies, u, mu, e -------------

std::mt19937 &rng()
{
    static std::mt19937 g(impactgen::testing::seed_from_env());
    return g;
}

num uniform(int lo, int hi, int den) // a rational in [lo, hi] with denominator den
{
    std::uniform_int_distribution<int> d(lo * den, hi * den);
    return num(d(rng()), den);
}

// A mass of 10^k times a rational in [1, 10), k in -2..1: two bodies' mass ratio spans 1e-4..1e4.
num random_mass()
{
    std::uniform_int_distribution<int> k(-2, 1);
    return uniform(1, 10, 100) * num(10).power(k(rng()));
}

// One body's response at the contact in (t, n): free, particle, pinned or immovable.
void add_body_response(num K[3])
{
    std::uniform_int_distribution<int> kind(0, 9);
    const int k = kind(rng());
    const num m = random_mass();
    const num I = m * uniform(1, 40, 20) / 20; // radius of gyration^2 in [1/20, 2]
    const num rt = uniform(-2, 2, 50), rn = uniform(-2, 2, 50);
    const num gt = -rn, gn = rt; // z x r: the lever's turn
    if (k <= 5) {                // free body: 1/m + g g^T / I
        K[0] += 1 / m + gt * gt / I, K[1] += gt * gn / I, K[2] += 1 / m + gn * gn / I;
    } else if (k == 6) { // particle
        K[0] += 1 / m, K[2] += 1 / m;
    } else if (k <= 8) { // pinned at E: g g^T / I_E, I_E = I + m |d|^2
        const num dx = uniform(-1, 1, 20), dy = uniform(-1, 1, 20);
        const num IE = I + m * (dx * dx + dy * dy);
        K[0] += gt * gt / IE, K[1] += gt * gn / IE, K[2] += gn * gn / IE;
    } // else: infinite mass, no response
}

struct sample {
    num K[3]; // K_tt, K_tn, K_nn
    num ut, un, mu, e;
    bool near_boundary = false; // a transition within 1e-6 of another, or exactly on it
};

sample random_sample()
{
    sample s;
    do {
        s.K[0] = s.K[1] = s.K[2] = 0;
        add_body_response(s.K);
        add_body_response(s.K);
    } while (s.K[2].is_zero() || s.K[0].is_zero());
    s.un = -uniform(1, 30, 10);
    s.ut = uniform(-30, 30, 10);
    s.mu = uniform(0, 2, 100);
    s.e = uniform(0, 1, 100);
    std::uniform_int_distribution<int> pick(0, 19);
    const int k = pick(rng());
    const num delta = k % 3 == 0 ? num(0) : (k % 3 == 1 ? num(1, 1000000) : num(-1, 1000000));
    if (k == 0) {
        s.ut = 0;        // starting without slip
    } else if (k <= 3) { // mu at the sticking ratio |K_tn| / K_tt (and 1e-6 on either side)
        s.mu = abs(s.K[1]) / s.K[0] * (1 + delta);
        s.near_boundary = true;
    } else if (k <= 9) { // the slip stops where compression ends (k <= 6) or restitution ends (Poisson)
        const int sg = s.ut.is_negative() ? -1 : 1;
        const num a = s.K[1] - sg * s.mu * s.K[0], b = s.K[2] - sg * s.mu * s.K[1];
        if (sg * a < 0 && b > 0) {
            const num xc = -s.un / b;
            s.ut = -a * xc * (k <= 6 ? num(1) : 1 + s.e) * (1 + delta);
            s.near_boundary = true;
        }
    }
    if (pick(rng()) == 0)
        s.e = pick(rng()) < 10 ? 0 : 1;
    return s;
}

struct compared {
    int samples = 0, agreed = 0, refused = 0, phases_compared = 0;
    double worst_impulse = 0, worst_velocity = 0;
    double closed_seconds = 0, integration_seconds = 0; // measurements, printed (not asserted)
};

// The closed form for the sample, or false when refused (wedging, an undetermined impulse).
bool closed_form(const sample &s, const std::string &law, process_sequence &out)
{
    process_inputs in;
    in.Ktt = s.K[0], in.Ktn = s.K[1], in.Knn = s.K[2], in.ut = s.ut, in.un = s.un, in.mu = s.mu, in.e = s.e;
    in.law = law_of(law);
    try {
        const std::vector<process_sequence> q = routh_process(in, "sample");
        EXPECT_EQ(q.size(), 1u) << "a num process has one phase sequence";
        out = q.front();
        return true;
    } catch (const input_error &) {
        return false;
    }
}

// The phases with a length above `rel` of the whole.
std::vector<int> long_phases(const std::vector<int> &kinds, const std::vector<double> &ends, double rel)
{
    std::vector<int> r;
    double start = 0;
    for (std::size_t k = 0; k < kinds.size(); ++k) {
        if (ends[k] - start > rel * ends.back())
            r.push_back(kinds[k]);
        start = ends[k];
    }
    return r;
}

impactgen::numeric::process_law numeric_law(const std::string &law)
{
    return law == "poisson" ? impactgen::numeric::process_law::poisson : impactgen::numeric::process_law::energetic;
}

// Closed form (exact) against the integration (double, 400 steps of the frictionless
// compression impulse, events located by bisection). Tolerances: within a step the motion is
// linear, so the integration is exact but for rounding: about 1e-16 per step relative to the
// largest entry of K times |P| (mass ratios up to 1e4 make K's entries span 1e8 at most), over
// at most a few thousand steps: below 1e-9 of the scale; 1e-8 leaves a margin. Phase lists are
// compared where no transition lies within 1e-6 of another (there two orders are both right
// to within the tolerance, and the values agree either way: the process is continuous there).
void compare_with_integration(const std::string &law, int count, compared &c)
{
    for (int k = 0; k < count; ++k) {
        const sample s = random_sample();
        ++c.samples;
        process_sequence q;
        // long double: a process that sticks with det K = 0 after a compression ending a hair before
        // the slip stops restores its work at a tiny u_n over an impulse of 1e5 times the usual, and
        // u = c + W P then loses |W| |P| / |u_n| times the rounding (1e-6 of the answer in double).
        using real = long double;
        Eigen::Matrix<real, 2, 2> W;
        W << s.K[2].to_double(), s.K[1].to_double(), s.K[1].to_double(), s.K[0].to_double();
        const Eigen::Matrix<real, 2, 1> u0(s.un.to_double(), s.ut.to_double());
        const auto t0 = std::chrono::steady_clock::now();
        const auto r = impactgen::numeric::integrate_process<real>(W, u0, s.mu.to_double(), s.e.to_double(),
                                                                   numeric_law(law), 400);
        const auto t1 = std::chrono::steady_clock::now();
        const bool solved = closed_form(s, law, q);
        const auto t2 = std::chrono::steady_clock::now();
        c.integration_seconds += std::chrono::duration<double>(t1 - t0).count();
        c.closed_seconds += std::chrono::duration<double>(t2 - t1).count();
        if (!solved) {
            ++c.refused;
            // Refused only where K is singular (a pinned body against an immovable one): the
            // wedge needs det K = 0 (see routh.hpp).
            EXPECT_TRUE((s.K[0] * s.K[2] - s.K[1] * s.K[1]).is_zero()) << "refused with det K != 0";
            continue;
        }
        ASSERT_TRUE(r.ok) << law << " sample " << k << ": the integration did not end; K = (" << s.K[0] << ", "
                          << s.K[1] << ", " << s.K[2] << "), u = (" << s.ut << ", " << s.un << "), mu = " << s.mu
                          << ", e = " << s.e;
        const double Pn = dbl(q.normal_impulse), Pt = dbl(q.tangential_impulse);
        const double scale_P = std::abs(Pn) + std::abs(Pt);
        const double Kmax = std::max({std::abs(W(0, 0)), std::abs(W(0, 1)), std::abs(W(1, 1))});
        const double scale_u = u0.norm() + Kmax * scale_P;
        const double dP =
            std::max(std::abs(Pn - double(r.normal_impulse)), std::abs(Pt - double(r.tangential))) / scale_P;
        const double du = std::max(std::abs(dbl(q.normal_velocity) - double(r.velocity_after[0])),
                                   std::abs(dbl(q.tangential_velocity) - double(r.velocity_after[1]))) /
                          scale_u;
        c.worst_velocity = std::max(c.worst_velocity, du);
        // With det K = 0 (a pinned body against an immovable one) an impulse along K's null vector
        // moves nothing, so nothing damps its rounding: in a nearly wedging process (mu within 1e-6
        // of sqrt(K_nn / K_tt)) whose impulse is 1e5..1e12 times the usual, the inputs' rounding to
        // double shifts the impulse along that vector by up to 10% while the velocities still agree
        // to 1e-9. There only the velocities (K P, what the bodies feel) are compared.
        const bool singular = (s.K[0] * s.K[2] - s.K[1] * s.K[1]).is_zero();
        if (!singular)
            c.worst_impulse = std::max(c.worst_impulse, dP);
        const bool ok = (singular || dP < 1e-8) && du < 1e-8;
        c.agreed += ok;
        EXPECT_TRUE(ok) << law << " sample " << k << ": P (" << Pn << ", " << Pt << ") vs (" << r.normal_impulse << ", "
                        << r.tangential << "), K = (" << s.K[0] << ", " << s.K[1] << ", " << s.K[2] << "), u = ("
                        << s.ut << ", " << s.un << "), mu = " << s.mu << ", e = " << s.e;
        if (s.near_boundary)
            continue;
        std::vector<int> a, b;
        std::vector<double> ae, be;
        for (const real x : r.phase_ends)
            be.push_back(double(x));
        for (const process_phase &ph : q.phases) {
            a.push_back(static_cast<int>(ph.kind));
            ae.push_back(dbl(ph.normal_impulse_end));
        }
        for (auto kind : r.phases)
            b.push_back(static_cast<int>(kind));
        const auto la = long_phases(a, ae, 1e-6), lb = long_phases(b, be, 1e-6);
        if (la.size() != a.size() || lb.size() != b.size())
            continue; // a phase shorter than 1e-6 of the whole: too close to a boundary to compare
        ++c.phases_compared;
        EXPECT_EQ(a, b) << law << " sample " << k << ": the phases differ";
    }
}

// The default count, a tenth of it in the sanitized build (IMPACTGEN_LAWS_SANITIZED), capped by
// IMPACTGEN_SAMPLES.
int random_count(int fallback)
{
#if IMPACTGEN_LAWS_SANITIZED
    fallback = std::max(1, fallback / 10);
#endif
    return std::min(fallback, impactgen::testing::samples_from_env(fallback));
}

} // namespace

// ---- closed form against num integration -------------------------------------------

class ProcessRandom : public ::testing::TestWithParam<const char *>
{
};

TEST_P(ProcessRandom, ClosedFormAgreesWithIntegration)
{
    const std::string law = GetParam();
    compared c;
    compare_with_integration(law, random_count(20000), c);
    std::printf("%s: %d samples, %d agree, %d refused (K singular), %d phase lists compared; worst relative "
                "difference: impulse %.2e, velocity %.2e\n",
                law.c_str(), c.samples, c.agreed, c.refused, c.phases_compared, c.worst_impulse, c.worst_velocity);
    std::printf("%s: closed form in exact arithmetic %.1f us per sample, integration (long double, 400+ steps) "
                "%.1f us\n",
                law.c_str(), 1e6 * c.closed_seconds / c.samples, 1e6 * c.integration_seconds / c.samples);
    EXPECT_EQ(c.agreed + c.refused, c.samples);
    EXPECT_LT(c.refused, c.samples / 20) << "nearly every sample is solved";
    EXPECT_GT(c.phases_compared, c.samples / 2);
}

INSTANTIATE_TEST_SUITE_P(Laws, ProcessRandom, ::testing::Values("poisson", "energetic"),
                         [](const ::testing::TestParamInfo<const char *> &i) { return std::string(i.param); });

// The energetic law never creates energy: with u' = u + K P the change of kinetic energy is
// P.u + P.K P / 2 = int u.dP (u linear in P along each phase), the normal part (1 - e^2) W_c <= 0
// and the tangential part -mu |u_t| dP_n <= 0 or 0 (stick). Decided exactly.
TEST(ProcessRandom, EnergeticNeverCreatesEnergy)
{
    const int count = random_count(3000);
    int checked = 0;
    for (int k = 0; k < count; ++k) {
        const sample s = random_sample();
        process_sequence q;
        if (!closed_form(s, "energetic", q))
            continue;
        const ex Pn = q.normal_impulse, Pt = q.tangential_impulse;
        const ex dT = Pt * s.ut + Pn * s.un + (s.K[0] * Pt * Pt + 2 * s.K[1] * Pt * Pn + s.K[2] * Pn * Pn) / 2;
        const decision d = decide(tidy(dT));
        EXPECT_TRUE(d == decision::negative || d == decision::zero)
            << "sample " << k << ": energy change " << dT.evalf() << " (" << decision_text(d) << ")";
        ++checked;
    }
    EXPECT_GT(checked, count * 9 / 10);
}

// ---- hand-derived exact cases -----------------------------------------------------------

// examples/friction/rod-slips.json: a uniform rod (m = 1, I = 1/12) whose lower end O = (0, 0)
// strikes the floor (normal (0, 1), e_t = (1, 0)) with C = (0.3, 0.4), v = (1, -2), w = 0;
// mu = 1/5, e = 1/2. With r = O - C = (-3/10, -2/5), g = z x r = (2/5, -3/10):
//   K = 1/m + g g^T / I:  K_tt = 1 + 12 (4/25) = 73/25, K_tn = 12 (2/5)(-3/10) = -36/25,
//                         K_nn = 1 + 12 (9/100) = 52/25;   u = (1, -2).
// Slide (s = +1): a = K_tn - mu K_tt = -253/125 (the slip slows), b = K_nn - mu K_tn = 296/125.
//   The slip stops at x_s = 1 / (253/125) = 125/253 before u_n = 0 (x_c = 2 / (296/125) = 125/148);
//   there u_n = -2 + (296/125)(125/253) = -210/253.
// Stick? mu K_tt + s K_tn = 73/125 - 36/25 = -107/125 < 0: no, the slip reverses (s = -1):
//   b' = K_nn - mu K_tn... with s = -1: K_nn + s mu K_tn = 52/25 - 36/125 = 224/125.
//   Compression ends at P_c = 125/253 + (210/253) / (224/125) = 27125/28336.
// Poisson: N = (1 + e) P_c = 81375/56672 = 1.43589...
// Energetic: W_c = [-2 x_s + b x_s^2 / 2] + [-(210/253)^2 / (2 b')] = -44750/64009 - 5512500/28676032
//   = -25560500/28676032; restitution from u_n = 0 along b': b' x^2 / 2 = -e^2 W_c,
//   N = P_c + sqrt(-2 e^2 W_c / b') = 1.45596...
TEST(Laws, RodSlipsMatchesTheHandDerivation)
{
    const std::string path = IMPACTGEN_SOURCE_DIR "/examples/friction/rod-slips.json";
    const num Pc = num(125, 253) + num(210, 253) / num(224, 125);
    EXPECT_EQ(Pc, num(27125, 28336));
    const num Wc = num(-44750, 64009) - num(5512500, 28676032);
    EXPECT_EQ(Wc, num(-25560500, 28676032));
    const ex poisson = num(3, 2) * Pc;
    const ex energetic = Pc + sqrt(ex(-2 * num(1, 4) * Wc / num(224, 125))); // sqrt of an ex: exact
    const regime_case p = answer_of(with_law(path, "poisson"));
    const regime_case e = answer_of(with_law(path, "energetic"));
    EXPECT_EQ(decide(tidy(p.sol.expand_steps(p.sol.normal_impulse) - poisson)), decision::zero)
        << p.sol.normal_impulse << " vs " << poisson;
    EXPECT_EQ(decide(tidy(e.sol.expand_steps(e.sol.normal_impulse) - energetic)), decision::zero)
        << e.sol.normal_impulse << " vs " << energetic;
    EXPECT_NEAR(dbl(poisson), 1.43589, 1e-5);
    EXPECT_NEAR(dbl(energetic), 1.45596, 1e-5);
    for (const regime_case *c : {&p, &e}) {
        ASSERT_EQ(c->process.size(), 2u);
        EXPECT_EQ(c->process[0].kind, phase_kind::slide);
        EXPECT_EQ(c->process[1].kind, phase_kind::reverse);
        EXPECT_EQ(decide(tidy(c->process[0].normal_impulse_end - num(125, 253))), decision::zero);
        // the friction impulse: -mu x_s forward, then +mu (N - x_s) after the reversal
        EXPECT_EQ(decide(tidy(c->tangential_scalar - num(1, 5) * (c->sol.normal_impulse - 2 * num(125, 253)))),
                  decision::zero);
    }
    // Newton's answer (today's) is another: N = (1 + e) |u_n| / b = 375/224 (one slide).
    const regime_case n = answer_of(with_law(path, "newton"));
    EXPECT_EQ(n.sol.normal_impulse, ex(num(375, 224)));
}

// ---- the laws against each other ----------------------------------------------------------

// A smooth contact: the three laws are the same law (u_n linear in P_n along one phase, so
// P_n = (1 + e) P_c, u'_n = -e u_n and W_r = -e^2 W_c all hold at once), in 2-D and 3-D.
TEST(Laws, SmoothContactsAnswerTheSameUnderEveryLaw)
{
    int files = 0;
    for (const char *name : {"hinged-rod", "pinned-3d", "plate-struck-obliquely", "puck-block-34", "spinning-spheres",
                             "wall-oblique-3d"}) {
        const std::string path = std::string(IMPACTGEN_SOURCE_DIR "/examples/problems/") + name + ".json";
        const problem base = with_law(path, "newton");
        ASSERT_TRUE(std::holds_alternative<frictionless>(base.contact().law));
        // numbers: solve's answer; symbols: the closed form as formulas --format json writes it
        auto answer = [](const problem &p) {
            const derivation d = derive(p);
            const impact_solution s = solve_impact(d);
            return p.is_numeric() ? print::answer_json(d, select_candidate(d, s), false).dump()
                                  : print::answer_json(d, s.cases.front(), true).dump();
        };
        const std::string newton = answer(base);
        for (const char *law : {"poisson", "energetic"})
            EXPECT_EQ(answer(with_law(path, law)), newton) << name << " " << law;
        ++files;
    }
    EXPECT_EQ(files, 6);
}

// ---- full problems: bodies, pivots, immovable bodies -------------------------------------

std::string text_of(const num &x)
{
    std::ostringstream os;
    os << x;
    return os.str();
}

// A random planar problem in exact values: two bodies, each free, a particle, pinned (turning
// about a pivot at rest) or of infinite mass (at most one), a contact at O = (0, 0).
std::string random_planar_problem(std::mt19937 &g, const std::string &law)
{
    std::uniform_int_distribution<int> kind(0, 9);
    json bodies = json::array(), pivots = json::array();
    bool one_infinite = false;
    for (int i = 0; i < 2; ++i) {
        const int k = kind(g);
        json b = {{"name", i == 0 ? "A" : "B"}};
        const bool infinite = k == 9 && !one_infinite;
        one_infinite = one_infinite || infinite;
        const num m = random_mass();
        b["mass"] = infinite ? std::string("inf") : text_of(m);
        const num cx = uniform(-2, 2, 10), cy = (i == 0 ? -1 : 1) * uniform(1, 20, 10) / 10;
        b["position"] = {text_of(cx), text_of(cy)};
        b["velocity"] = {text_of(uniform(-3, 3, 10)), text_of(uniform(-3, 3, 10))};
        if (!infinite && (k <= 5 || k == 7 || k == 8))
            b["inertia"] = text_of(uniform(1, 40, 20) / 20 * m);
        if (!infinite && (k == 7 || k == 8)) { // pinned at E: the pivot at rest, the body turning about it
            const num ex_ = cx + uniform(-1, 1, 10), ey = cy + uniform(-1, 1, 10), w = uniform(-2, 2, 10);
            b["velocity"] = {text_of(-w * (cy - ey)), text_of(w * (cx - ex_))};
            b["angular_velocity"] = text_of(w);
            pivots.push_back({{"body", b["name"]}, {"point", {text_of(ex_), text_of(ey)}}});
        }
        bodies.push_back(b);
    }
    json p = {{"dimension", 2}, {"restitution", text_of(uniform(0, 1, 20))}, {"bodies", bodies}};
    p["contact"] = {{"bodies", {"A", "B"}},
                    {"point", {0, 0}},
                    {"normal", {text_of(uniform(-1, 1, 10)), 1}},
                    {"friction", text_of(uniform(0, 2, 20))},
                    {"law", law}};
    if (!pivots.empty())
        p["pivots"] = pivots;
    return p.dump();
}

// Closed form through the whole pipeline (derive, solve_impact) against the integration with
// the bodies' own Delassus matrix (friction_contact: generalized velocities and pivot rows,
// another road to K): every body's velocity and spin after impact. Tolerance 1e-8 of the
// velocity scale, as above. And Poisson against Newton where they must agree: a process of one
// phase (the slip keeps its direction, or it sticks from the start) has u_n linear in P_n, so
// (1 + e) P_c is Newton's impulse and the single phase's conditions are the conditions of
// Newton's candidate of that regime. Newton may hold several candidates (refused): skipped.
TEST(PipelineRandom, ClosedFormAgreesWithIntegrationAndWithNewtonOnOnePhase)
{
    std::mt19937 g(impactgen::testing::seed_from_env() + 7);
    const int count = random_count(300);
    int solved = 0, refused = 0, one_phase = 0, newton_equal = 0;
    for (int k = 0; k < count; ++k) {
        for (const char *law : {"poisson", "energetic"}) {
            const std::string text = random_planar_problem(g, law);
            problem p;
            regime_case c;
            derivation d;
            try {
                p = read_problem(text, "random.json");
                d = derive(p);
                c = select_candidate(d, solve_impact(d));
            } catch (const input_error &err) {
                ++refused;
                const std::string m = err.what();
                EXPECT_TRUE(m.find("not an impact") != std::string::npos || m.find("wedges") != std::string::npos ||
                            m.find("can move") != std::string::npos || m.find("not determined") != std::string::npos)
                    << m << "\n"
                    << text;
                continue;
            }
            ++solved;
            const auto q = impactgen::numeric::from_problem<double>(p);
            const auto a = impactgen::numeric::integrate_process<double>(q, numeric_law(law), 400);
            ASSERT_TRUE(a.process.ok) << text;
            double scale = 0, worst = 0;
            for (std::size_t i = 0; i < p.bodies.size(); ++i)
                scale = std::max(
                    {scale, q.bodies[i].velocity.norm(), a.velocity[i].norm(), std::abs(a.angular_velocity[i][2])});
            for (std::size_t i = 0; i < p.bodies.size(); ++i) {
                for (int ax = 0; ax < 2; ++ax)
                    worst = std::max(
                        worst, std::abs(dbl(c.sol.expand_steps(c.sol.after[i].velocity[ax])) - a.velocity[i][ax]));
                worst = std::max(worst, std::abs(dbl(c.sol.expand_steps(c.sol.after[i].angular_velocity[2])) -
                                                 a.angular_velocity[i][2]));
            }
            EXPECT_LT(worst, 1e-8 * scale) << law << "\n" << text;
            bool moving_wall = false; // a moving body of infinite mass may do work
            for (const body &b : p.bodies)
                moving_wall = moving_wall || (b.infinite_mass && !b.at_rest());
            if (law == std::string("energetic") && !moving_wall) {
                EXPECT_NE(decide(tidy(c.sol.expand_steps(c.sol.energy_lost))), decision::negative) << text;
            }
            if (law != std::string("poisson") || c.process.size() != 1)
                continue;
            ++one_phase;
            json j = json::parse(text);
            j["contact"]["law"] = "newton";
            try {
                const problem pn = read_problem(j.dump(), "random.json");
                const derivation dn = derive(pn);
                const regime_case n = select_candidate(dn, solve_impact(dn));
                for (std::size_t i = 0; i < p.bodies.size(); ++i)
                    for (int ax = 0; ax < 3; ++ax) {
                        EXPECT_EQ(
                            decide(tidy(c.sol.after[i].velocity[ax] - n.sol.expand_steps(n.sol.after[i].velocity[ax]))),
                            decision::zero)
                            << text;
                        EXPECT_EQ(decide(tidy(c.sol.after[i].angular_velocity[ax] -
                                              n.sol.expand_steps(n.sol.after[i].angular_velocity[ax]))),
                                  decision::zero)
                            << text;
                    }
                ++newton_equal;
            } catch (const input_error &) {
            }
        }
    }
    std::printf("%d solved, %d refused, %d Poisson processes of one phase, %d equal to Newton's answer\n", solved,
                refused, one_phase, newton_equal);
    EXPECT_GT(solved, count / 2); // about half the random pairs do not approach ("not an impact")
    EXPECT_GT(newton_equal, one_phase / 2);
}

// ---- the symbolic phase sequences select the numeric answer ------------------------------

// rod-rough-floor (symbols m, l, theta, v_t, v_n, w, mu, e): for numbers, exactly one of the
// printed phase sequences has every condition true, and it is the answer solve gives for the
// same numbers (decided exactly there; here the conditions are evaluated at 30 digits, samples
// within 1e-12 of a boundary skipped).
TEST(Laws, SymbolicSequencesSelectTheNumericAnswer)
{
    const problem p = find_named_class("rod-rough-floor")->build();
    const derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    ASSERT_GE(s.cases.size(), 6u);
    std::mt19937 g(impactgen::testing::seed_from_env() + 11);
    const ex angles[3] = {Pi / 6, Pi / 4, Pi / 3};
    int checked = 0;
    for (int k = 0; k < 40; ++k) {
        std::uniform_int_distribution<int> pick(0, 2);
        auto sym = [](const char *n) { return symbol_named(n); };
        const lst values{sym("m") == uniform(1, 5, 4),        sym("l") == uniform(1, 2, 4),
                         sym("theta") == angles[pick(g)],     sym("v_t") == uniform(-2, 2, 4),
                         sym("v_n") == -uniform(1, 3, 4),     sym("w") == uniform(-2, 2, 4),
                         sym("mu") == uniform(1, 40, 1) / 20, sym("e") == uniform(0, 1, 20)};
        regime_case numeric_answer;
        try {
            numeric_answer = answer_of(substitute(p, values));
        } catch (const input_error &) {
            continue; // not an impact for these values
        }
        int holding = 0;
        bool boundary = false;
        const regime_case *held = nullptr;
        // Values on a boundary of some sequence (a condition 0 within 1e-12, or one of its
        // denominators 0, e.g. u_t = 0: a start without slip, not among the printed sequences)
        // are skipped.
        try {
            for (const regime_case &c : s.cases) {
                bool all = true;
                for (const process_condition &pc : c.process_conditions) {
                    const double v = dbl(c.sol.expand_steps(pc.value).subs(values));
                    boundary = boundary || std::abs(v) < 1e-12;
                    all = all && (pc.strict ? v > 0 : v >= 0);
                }
                if (all) {
                    ++holding;
                    held = &c;
                }
            }
        } catch (const std::exception &) { // GiNaC: division by zero
            boundary = true;
        }
        if (boundary)
            continue;
        ASSERT_EQ(holding, 1) << "values " << values;
        ++checked;
        ASSERT_EQ(held->process.size(), numeric_answer.process.size()) << values;
        for (std::size_t i = 0; i < held->process.size(); ++i)
            EXPECT_EQ(held->process[i].kind, numeric_answer.process[i].kind) << values;
        EXPECT_NEAR(dbl(held->sol.expand_steps(held->sol.normal_impulse).subs(values)),
                    dbl(numeric_answer.sol.normal_impulse), 1e-12 * (1 + dbl(numeric_answer.sol.normal_impulse)))
            << values;
    }
    EXPECT_GT(checked, 20);
}

// ---- the command line -------------------------------------------------------------------

struct run_result {
    int code = 0;
    std::string out, err;
};

run_result run_cli(const std::string &args)
{
    const std::string err_path = "/tmp/impactgen_laws_err_" + std::to_string(::getpid());
    run_result r;
    FILE *f = ::popen((std::string(IMPACTGEN_CLI) + " " + args + " 2>" + err_path).c_str(), "r");
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
        r.out.append(buf, n);
    const int status = ::pclose(f);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.err = read_text(err_path);
    std::remove(err_path.c_str());
    return r;
}

std::string write_temp(const std::string &name, const std::string &text)
{
    const std::string path = "/tmp/impactgen_laws_" + std::to_string(::getpid()) + "_" + name + ".json";
    std::ofstream(path) << text;
    return path;
}

std::string with_law_text(const std::string &path, const std::string &law)
{
    json j = json::parse(read_text(path));
    j["contact"]["law"] = law;
    return j.dump();
}

void expect_one_line_refusal(const run_result &r, const std::string &part)
{
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
}

// explain teaches the process (tests/explain/explain_process_test.cpp) and codegen generates it
// (tests/codegen/laws.cpp); formulas --jacobian differentiates each phase sequence of a problem
// with symbols (test_laws_jacobian.cpp) and refuses a numeric one (no input), codegen --jacobian
// refuses friction.
TEST(LawsCli, ExplainAndCodegenAnswerPoissonAndEnergeticWithFriction)
{
    for (const char *law : {"poisson", "energetic"}) {
        const std::string path =
            write_temp(law, with_law_text(IMPACTGEN_SOURCE_DIR "/examples/friction/rod-slips.json", law));
        const run_result explained = run_cli("explain " + path);
        EXPECT_EQ(explained.code, 0) << explained.err;
        EXPECT_NE(explained.out.find("Routh's process"), std::string::npos);
        const run_result header = run_cli("codegen " + path); // codegen follows the process (tests/codegen/laws.cpp)
        EXPECT_EQ(header.code, 0) << header.err;
        EXPECT_NE(header.out.find("Routh's process"), std::string::npos);
        expect_one_line_refusal(run_cli("formulas --jacobian " + path), "--jacobian: the problem has no symbol");
        expect_one_line_refusal(run_cli("codegen --jacobian " + path), "--jacobian");
        const run_result solved = run_cli("solve --json " + path);
        EXPECT_EQ(solved.code, 0) << solved.err;
        std::remove(path.c_str());
    }
    const run_result jac = run_cli("formulas --jacobian --wrt mu,theta rod-rough-floor");
    EXPECT_EQ(jac.code, 0) << jac.err;
    EXPECT_NE(jac.out.find("per phase sequence"), std::string::npos);
    EXPECT_NE(jac.out.find("d normal_impulse / d theta"), std::string::npos);
    const run_result symbolic = run_cli("explain rod-rough-floor");
    EXPECT_EQ(symbolic.code, 0) << symbolic.err;
    EXPECT_NE(symbolic.out.find("Phase sequence 16"), std::string::npos);
}

// A smooth contact takes any law with the same answer everywhere: solve, formulas, explain and
// codegen print byte for byte what they print for newton (the same file path, so the banners match).
TEST(LawsCli, SmoothContactPrintsTheSameUnderEveryLaw)
{
    for (const char *file : {"/examples/problems/hinged-rod.json", "/examples/problems/wall-oblique-3d.json"}) {
        const std::string src = std::string(IMPACTGEN_SOURCE_DIR) + file;
        const std::string path = write_temp("smooth", with_law_text(src, "newton"));
        std::vector<std::string> newton;
        const std::vector<std::string> commands = {"solve --json ", "formulas ", "explain ", "codegen "};
        for (const std::string &cmd : commands)
            newton.push_back(run_cli(cmd + path).out);
        for (const char *law : {"poisson", "energetic"}) {
            write_temp("smooth", with_law_text(src, law));
            for (std::size_t k = 0; k < commands.size(); ++k) {
                const run_result r = run_cli(commands[k] + path);
                EXPECT_TRUE(!r.out.empty() || k == 0) << commands[k] << file << ": " << r.err; // solve needs numbers
                EXPECT_EQ(r.out, newton[k]) << commands[k] << file << " " << law;
            }
        }
        std::remove(path.c_str());
    }
}

TEST(LawsCli, AnswerKeysProcessRegimeAndEnergyGain)
{
    const run_result r = run_cli("solve --json " IMPACTGEN_SOURCE_DIR "/examples/laws/rod-slip-reverses.json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json a = json::parse(r.out);
    EXPECT_EQ(a.at("regime"), "reverse");
    ASSERT_EQ(a.at("process").size(), 2u);
    EXPECT_EQ(a["process"][0].at("phase"), "slide");
    EXPECT_EQ(a["process"][1].at("phase"), "reverse");
    EXPECT_NEAR(a["process"][0].at("normal_impulse_end").get<double>(), 125.0 / 253, 1e-15);
    EXPECT_EQ(a["process"][1].at("normal_impulse_end"), a.at("normal_impulse"));
    EXPECT_FALSE(a.contains("energy_gain"));
    // Newton on the spinning rod gains energy; the two laws followed through the impact do not.
    const std::string gains = IMPACTGEN_SOURCE_DIR "/examples/laws/rod-gains-energy.json";
    const json n = json::parse(run_cli("solve --json " + gains).out);
    EXPECT_EQ(n.value("energy_gain", false), true);
    EXPECT_LT(n["kinetic_energy"]["lost"].get<double>(), 0);
    EXPECT_FALSE(n.contains("process"));
    for (const char *law : {"poisson", "energetic"}) {
        const std::string path = write_temp(law, with_law_text(gains, law));
        const json l = json::parse(run_cli("solve --json " + path).out);
        EXPECT_FALSE(l.contains("energy_gain")) << law;
        EXPECT_GT(l["kinetic_energy"]["lost"].get<double>(), 0) << law;
        EXPECT_EQ(l.at("regime"), "stick") << law;
        std::remove(path.c_str());
    }
    // A Newton answer that loses energy carries no energy_gain.
    const json lost =
        json::parse(run_cli("solve --json " IMPACTGEN_SOURCE_DIR "/examples/friction/rod-slips.json").out);
    EXPECT_FALSE(lost.contains("energy_gain"));
}

// A rod pinned at E = (-1, 1) whose end O = (0, 0) is struck by a wall moving at (-1, 1): the
// end can only move along (1, 1), and with mu >= 1 the friction impulse P_n (-mu s, 1) turns the
// impulse along the rod (mu = 1) or sticks it with det K = 0: u_n never reaches 0, the impulse
// would grow without bound. Refused under every law, naming the key.
TEST(LawsCli, WedgingContactIsRefusedUnderEveryLaw)
{
    for (const char *mu : {"1", "1.5"})
        for (const char *law : {"newton", "poisson", "energetic"}) {
            const std::string text = std::string(R"({"dimension": 2, "restitution": 0.5, "bodies": [
              {"name": "wall", "mass": "inf", "position": [0, -1], "velocity": [-1, 1]},
              {"name": "rod", "mass": 1, "inertia": "1/6", "position": [-0.5, 0.5], "velocity": [0, 0]}],
              "pivots": [{"body": "rod", "point": [-1, 1]}],
              "contact": {"bodies": ["wall", "rod"], "point": [0, 0], "normal": [0, 1], "friction": )") +
                                     mu + R"(, "law": ")" + law + "\"}}";
            const std::string path = write_temp("wedge", text);
            const run_result r = run_cli("solve --json " + path);
            expect_one_line_refusal(r, "contact.friction: the contact wedges");
            std::remove(path.c_str());
        }
}

// ---- a contact law's hooks (symbolic/contact_law.hpp): what the pipeline asks of each law ------

TEST(ContactLaw, EachLawAnswersWhatThePipelineAsks)
{
    const std::string dir = IMPACTGEN_SOURCE_DIR "/examples/";
    // A smooth contact: one unconditioned candidate, no equation beside the smooth impact's,
    // under every restitution law.
    for (const char *law : {"newton", "poisson", "energetic"}) {
        const problem p = with_law(dir + "problems/hinged-rod.json", law);
        ASSERT_TRUE(std::holds_alternative<frictionless>(p.contact().law)) << law;
        const law_traits t = law_traits_of(p);
        EXPECT_FALSE(t.tangential_impulse) << law;
        EXPECT_TRUE(t.single_candidate) << law;
        EXPECT_FALSE(t.process) << law;
        EXPECT_EQ(t.jacobian, jacobian_route::closed_form) << law;
        const derivation d = derive(p);
        EXPECT_TRUE(d.friction.equations.empty()) << law;
        const impact_solution s = solve_impact(d);
        ASSERT_EQ(s.cases.size(), 1u) << law;
        EXPECT_EQ(s.cases.front().kind, regime::smooth) << law;
    }
    // Coulomb's law under Newton's restitution: stick and the slides, differentiated per regime.
    const problem rod = with_law(dir + "friction/rod-slips.json", "newton");
    ASSERT_TRUE(std::holds_alternative<coulomb>(rod.contact().law));
    law_traits t = law_traits_of(rod);
    EXPECT_TRUE(t.tangential_impulse);
    EXPECT_FALSE(t.single_candidate);
    EXPECT_FALSE(t.process);
    EXPECT_EQ(t.jacobian, jacobian_route::per_regime);
    const derivation d = derive(rod);
    EXPECT_FALSE(d.friction.stick_law.empty());
    EXPECT_FALSE(d.friction.slide_law.empty());
    EXPECT_GE(solve_impact(d).cases.size(), 2u);
    // Under Poisson's law in 2-D: the phase sequences of Routh's process.
    t = law_traits_of(with_law(dir + "friction/rod-slips.json", "poisson"));
    EXPECT_TRUE(t.process);
    EXPECT_EQ(t.jacobian, jacobian_route::per_phase_sequence);
    // In 3-D (which the reader refuses under a process law) no Jacobian is offered.
    problem box = with_law(dir + "friction/box-corner-3d.json", "newton");
    EXPECT_EQ(law_traits_of(box).jacobian, jacobian_route::per_regime);
    box.contact().law_of_restitution = poisson_restitution{};
    EXPECT_EQ(law_traits_of(box).jacobian, jacobian_route::not_offered);
}
