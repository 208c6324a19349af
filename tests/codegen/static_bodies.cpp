// Static, kinematic and rotation-locked bodies in the engine convention (--inverse-mass
// --inverse-inertia): an inverse mass 0 and an inverse inertia 0 or singular are valid
// inputs, and one header serves a dynamic-static and a dynamic-dynamic pair. Seeded random
// impacts of generated/noncentral_3d_engine.hpp and generated/planar_engine.hpp against
//  - the Eigen solve of the momentum system (numeric/momentum_solver.hpp) with body 2 of
//    infinite mass (static or kinematic: its velocities given), or a particle (rotation
//    locked: no angular response), or both bodies free;
//  - the closed form of a body striking one of infinite mass (generated/massive_3d.hpp,
//    the masses and tensor of body 1 as their inverses' inverses).
// And the statuses that stay: both bodies static is singular, an inverse mass < 0
// invalid_mass, an inverse tensor with a negative principal minor invalid_inertia.
#include "massive_3d.hpp"
#include "noncentral_3d_engine.hpp"
#include "planar_engine.hpp"

#include "numeric/momentum_solver.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace gen = impactgen::generated;
namespace nm = impactgen::numeric;

namespace
{

using M3 = nm::mat<double>;
using V3 = nm::vec<double>;

struct rng {
    std::mt19937_64 g;
    explicit rng(unsigned seed) : g(seed) {}
    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(g); }
    double log_uniform(double a, double b) { return std::exp(uniform(std::log(a), std::log(b))); }
    V3 vector(double a) { return V3(uniform(-a, a), uniform(-a, a), uniform(-a, a)); }
    // m R diag(0.2..1) R^T: a positive definite inertia tensor
    M3 inertia(double m)
    {
        Eigen::Quaterniond q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
        q.normalize();
        const M3 r = q.toRotationMatrix();
        const V3 d(uniform(0.2, 1), uniform(0.2, 1), uniform(0.2, 1));
        return m * r * d.asDiagonal() * r.transpose();
    }
};

// A free body of the numeric reference.
nm::body<double> free_body(double m, const M3 &inertia, const V3 &r, const V3 &v, const V3 &w)
{
    nm::body<double> b;
    b.particle = false;
    b.mass = m;
    b.inertia = inertia;
    b.position = r;
    b.velocity = v;
    b.angular_velocity = w;
    return b;
}

// |a - b| <= tol (1 + |b|) for every component.
void expect_close(const std::vector<double> &a, const std::vector<double> &b, double tol, const std::string &what)
{
    ASSERT_EQ(a.size(), b.size()) << what;
    for (std::size_t i = 0; i < a.size(); ++i)
        EXPECT_LE(std::abs(a[i] - b[i]), tol * (1 + std::abs(b[i]))) << what << ", component " << i;
}

// Body 2's kind in the engine convention.
enum class kind { dynamic, rotation_locked, kinematic };

struct case3 {
    std::array<double, 33> in{};
    nm::problem<double> ref;
    M3 I1;
};

// noncentral_3d_engine's inputs (e, inv_m1, inv_I1 (6), r1, v1, w1, inv_m2, inv_I2 (6), r2,
// v2, w2) and the reference problem (contact point O, normal e_n).
case3 draw3(rng &g, kind k2)
{
    case3 c;
    const double e = g.uniform(0, 1), m1 = g.log_uniform(1e-2, 1e2), m2 = g.log_uniform(1e-2, 1e2);
    const M3 I1 = g.inertia(m1), I2 = g.inertia(m2);
    const M3 J1 = I1.inverse(), J2 = I2.inverse();
    const V3 r1 = g.vector(1) - V3(0, 1.5, 0), r2 = g.vector(1) + V3(0, 1.5, 0);
    V3 v1 = g.vector(1), v2 = g.vector(1);
    const V3 w1 = g.vector(1);
    // (a particle of the reference has no spin that moves its contact point)
    const V3 w2 = k2 == kind::rotation_locked ? V3::Zero() : g.vector(1);
    v1.y() = g.uniform(0.1, 2); // approaching: body 1 moves up into body 2 more than body 2's points do
    v2.y() = -g.uniform(0.1, 2);
    std::size_t at = 0;
    auto put_tensor = [&](const M3 &J) {
        for (int r = 0; r < 3; ++r)
            for (int col = r; col < 3; ++col)
                c.in[at++] = J(r, col);
    };
    auto put = [&](const V3 &x) {
        for (int i = 0; i < 3; ++i)
            c.in[at++] = x[i];
    };
    c.in[at++] = e;
    c.in[at++] = 1 / m1;
    put_tensor(J1);
    put(r1), put(v1), put(w1);
    c.in[at++] = k2 == kind::kinematic ? 0.0 : 1 / m2;
    put_tensor(k2 == kind::dynamic ? J2 : M3::Zero());
    put(r2), put(v2), put(w2);
    c.ref.dimension = 3;
    c.ref.restitution = e;
    c.ref.normal = V3::UnitY();
    nm::body<double> b2 = free_body(m2, I2, r2, v2, w2);
    if (k2 == kind::kinematic)
        b2.infinite_mass = true;
    if (k2 == kind::rotation_locked) {
        b2.particle = true; // no angular response; its spin moves its contact point, unchanged
        b2.inertia = M3::Zero();
    }
    c.ref.bodies = {free_body(m1, I1, r1, v1, w1), b2};
    c.I1 = I1;
    return c;
}

// The reference answer in the header's output order (velocities of both bodies, N).
std::vector<double> reference3(const nm::problem<double> &p, const V3 &w2_before)
{
    const nm::answer<double> a = nm::solve_momentum_system(p);
    EXPECT_TRUE(a.ok);
    std::vector<double> r;
    for (int b = 0; b < 2; ++b) {
        for (int i = 0; i < 3; ++i)
            r.push_back(a.velocity[b][i]);
        for (int i = 0; i < 3; ++i)
            r.push_back(b == 1 && p.bodies[1].particle ? w2_before[i] : a.angular_velocity[b][i]);
    }
    r.push_back(a.normal_impulse);
    return r;
}

std::vector<double> header3(const case3 &c, gen::impact_status &status)
{
    gen::noncentral_3d_engine_result<double> out{};
    status = gen::noncentral_3d_engine<double>(c.in.data(), out);
    double a[15];
    gen::noncentral_3d_engine_to_array(out, a);
    return std::vector<double>(a, a + 13); // velocities and N (not u, energy)
}

void agree3(kind k2, const char *what, unsigned seed)
{
    rng g(seed);
    int compared = 0;
    for (int s = 0; s < 2000; ++s) {
        const case3 c = draw3(g, k2);
        gen::impact_status st;
        const std::vector<double> h = header3(c, st);
        const V3 w2(c.in[30], c.in[31], c.in[32]);
        if (nm::solve_momentum_system(c.ref).normal_impulse <= 0)
            continue; // not approaching at the contact point: the header says so (tested below)
        ASSERT_EQ(st, gen::impact_status::ok) << what << ", sample " << s;
        ++compared;
        expect_close(h, reference3(c.ref, w2), 1e-9, std::string(what) + ", sample " + std::to_string(s));
        if (k2 == kind::kinematic)
            for (int i = 0; i < 6; ++i) // an infinite mass keeps its velocities exactly
                EXPECT_EQ(h[6 + static_cast<std::size_t>(i)], c.in[27 + static_cast<std::size_t>(i)]) << what;
        // The energy lost is the energy dissipated, (1 - e^2) u^2 / (2 k) = -(1 - e) u N / 2,
        // also against a moving (kinematic) body.
        gen::noncentral_3d_engine_result<double> r{};
        gen::noncentral_3d_engine<double>(c.in.data(), r);
        const double dissipated = -(1 - c.in[0]) * r.approach_velocity * r.normal_impulse / 2;
        EXPECT_LE(std::abs(r.energy_lost - dissipated), 1e-9 * (1 + std::abs(dissipated))) << what << ", sample " << s;
    }
    EXPECT_GT(compared, 1000) << what;
}

TEST(CodegenStaticBodies, DynamicDynamicAgreesWithEigen)
{
    agree3(kind::dynamic, "dynamic-dynamic", 11);
}
TEST(CodegenStaticBodies, KinematicBodyAgreesWithEigen)
{
    agree3(kind::kinematic, "dynamic-kinematic", 12);
}
TEST(CodegenStaticBodies, RotationLockedBodyAgreesWithEigen)
{
    agree3(kind::rotation_locked, "dynamic-rotation-locked", 13);
}

// Body 2 static (inverse mass 0, inverse tensor 0, at rest or moving) against the closed
// form of massive_3d: the same outputs for body 1, the same impulse, approach velocity and
// energy lost.
TEST(CodegenStaticBodies, StaticBodyAgreesWithTheClosedFormOfAnInfiniteMass)
{
    rng g(14);
    int compared = 0;
    for (int s = 0; s < 2000; ++s) {
        case3 c = draw3(g, kind::kinematic);
        for (std::size_t i = 27; i < 33; ++i)
            c.in[i] = 0; // at rest: the energy lost is then body 1's loss of kinetic energy
        gen::noncentral_3d_engine_result<double> a{};
        const gen::impact_status sa = gen::noncentral_3d_engine<double>(c.in.data(), a);
        // massive_3d: e, m1, I1 (6), r1, v1, w1, r2, v2, w2
        std::array<double, 26> in{};
        std::size_t at = 0;
        in[at++] = c.in[0];
        in[at++] = 1 / c.in[1];
        for (int r = 0; r < 3; ++r)
            for (int col = r; col < 3; ++col)
                in[at++] = c.I1(r, col);
        for (std::size_t i = 8; i < 17; ++i)
            in[at++] = c.in[i];
        for (std::size_t i = 24; i < 33; ++i)
            in[at++] = c.in[i];
        gen::massive_3d_result<double> b{};
        const gen::impact_status sb = gen::massive_3d<double>(in.data(), b);
        ASSERT_EQ(sa, sb) << "sample " << s;
        if (sa != gen::impact_status::ok)
            continue;
        ++compared;
        expect_close(
            {a.v_t1, a.v_n1, a.v_b1, a.w_t1, a.w_n1, a.w_b1, a.normal_impulse, a.approach_velocity, a.energy_lost},
            {b.v_t1, b.v_n1, b.v_b1, b.w_t1, b.w_n1, b.w_b1, b.normal_impulse, b.approach_velocity, b.energy_lost},
            1e-9, "static body 2, sample " + std::to_string(s));
    }
    EXPECT_GT(compared, 1000);
}

// The planar engine header: body 2 static (inverse mass and moment 0) against Eigen with an
// infinite mass; a dynamic pair against Eigen with both free.
TEST(CodegenStaticBodies, PlanarStaticAndDynamicAgreeWithEigen)
{
    rng g(15);
    for (int s = 0; s < 2000; ++s) {
        const bool fixed = s % 2 == 0;
        const double e = g.uniform(0, 1), m1 = g.log_uniform(1e-2, 1e2), m2 = g.log_uniform(1e-2, 1e2);
        const double I1 = m1 * g.uniform(0.2, 1), I2 = m2 * g.uniform(0.2, 1);
        const V3 r1(g.uniform(-1, 1), -g.uniform(0.5, 1.5), 0), r2(g.uniform(-1, 1), g.uniform(0.5, 1.5), 0);
        const V3 v1(g.uniform(-1, 1), g.uniform(0.5, 2), 0), v2(g.uniform(-1, 1), -g.uniform(0, 0.4), 0);
        const double w1 = g.uniform(-0.1, 0.1), w2 = g.uniform(-0.1, 0.1);
        // e, inv_m1, inv_I1, r_t1, r_n1, v_t1, v_n1, w_b1, inv_m2, inv_I2, r_t2, r_n2, v_t2, v_n2, w_b2
        const double in[15] = {
            e,      1 / m1, 1 / I1, r1.x(), r1.y(), v1.x(), v1.y(), w1, fixed ? 0.0 : 1 / m2, fixed ? 0.0 : 1 / I2,
            r2.x(), r2.y(), v2.x(), v2.y(), w2};
        nm::problem<double> p;
        p.dimension = 2;
        p.restitution = e;
        p.normal = V3::UnitY();
        M3 J1 = M3::Zero(), J2 = M3::Zero();
        J1(2, 2) = I1;
        J2(2, 2) = I2;
        p.bodies = {free_body(m1, J1, r1, v1, V3(0, 0, w1)), free_body(m2, J2, r2, v2, V3(0, 0, w2))};
        p.bodies[1].infinite_mass = fixed;
        const nm::answer<double> ref = nm::solve_momentum_system(p);
        gen::planar_engine_result<double> out{};
        const gen::impact_status st = gen::planar_engine<double>(in, out);
        if (ref.normal_impulse <= 0) {
            EXPECT_EQ(st, gen::impact_status::not_approaching) << "sample " << s;
            continue;
        }
        ASSERT_EQ(st, gen::impact_status::ok) << "sample " << s;
        expect_close({out.v_t1, out.v_n1, out.w_b1, out.v_t2, out.v_n2, out.w_b2, out.normal_impulse},
                     {ref.velocity[0].x(), ref.velocity[0].y(), ref.angular_velocity[0].z(), ref.velocity[1].x(),
                      ref.velocity[1].y(), ref.angular_velocity[1].z(), ref.normal_impulse},
                     1e-9, std::string(fixed ? "planar static" : "planar dynamic") + ", sample " + std::to_string(s));
    }
}

// What stays refused: both bodies immovable (no impulse can change anything: singular), a
// negative inverse mass, an inverse tensor that is not positive semidefinite.
TEST(CodegenStaticBodies, WhatStaysRefused)
{
    rng g(16);
    case3 c = draw3(g, kind::kinematic);
    gen::noncentral_3d_engine_result<double> out{};
    c.in[1] = 0;
    for (std::size_t i = 2; i < 8; ++i)
        c.in[i] = 0;
    EXPECT_EQ(gen::noncentral_3d_engine<double>(c.in.data(), out), gen::impact_status::singular);
    c = draw3(g, kind::dynamic);
    c.in[17] = -1e-3;
    EXPECT_EQ(gen::noncentral_3d_engine<double>(c.in.data(), out), gen::impact_status::invalid_mass);
    c = draw3(g, kind::dynamic);
    c.in[18] = -1e-3; // inv_I2_tt < 0
    EXPECT_EQ(gen::noncentral_3d_engine<double>(c.in.data(), out), gen::impact_status::invalid_inertia);
    c = draw3(g, kind::dynamic);
    // inv_I2 = [[1, 2, 0], [2, 1, 0], [0, 0, 1]]: diagonal >= 0, the minor tt nn - tn^2 = -3
    const double bad[6] = {1, 2, 0, 1, 0, 1};
    for (std::size_t i = 0; i < 6; ++i)
        c.in[18 + i] = bad[i];
    EXPECT_EQ(gen::noncentral_3d_engine<double>(c.in.data(), out), gen::impact_status::invalid_inertia);
    // A rotation locked about one axis only (a singular inverse tensor diag(a, 0, b)) is valid.
    c = draw3(g, kind::dynamic);
    const double locked[6] = {0.5, 0, 0, 0, 0, 0.25};
    for (std::size_t i = 0; i < 6; ++i)
        c.in[18 + i] = locked[i];
    const gen::impact_status st = gen::noncentral_3d_engine<double>(c.in.data(), out);
    EXPECT_TRUE(st == gen::impact_status::ok || st == gen::impact_status::not_approaching);
    // The planar header: inverse moment of inertia < 0 refused, 0 accepted.
    const double p_ok[15] = {0.5, 1, 1, 0, -1, 0, 1, 0, 1, 0, 0, 1, 0, 0, 0};
    gen::planar_engine_result<double> pr{};
    EXPECT_EQ(gen::planar_engine<double>(p_ok, pr), gen::impact_status::ok);
    double p_bad[15];
    std::copy(p_ok, p_ok + 15, p_bad);
    p_bad[9] = -1;
    EXPECT_EQ(gen::planar_engine<double>(p_bad, pr), gen::impact_status::invalid_inertia);
}

} // namespace
