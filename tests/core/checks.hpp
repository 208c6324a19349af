// Shared assertions: the exact closed form against the derivation's equations,
// the physics, and the two Eigen reference solvers.
#pragma once

#include "numeric/from_problem.hpp"
#include "numeric/generalized_solver.hpp"
#include "numeric/momentum_solver.hpp"
#include "symbolic/solution.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace impactgen::testing {

/// The post-impact state of a numeric problem, exactly: every body's v', w', then N, then pivot impulses.
struct exact_state {
    std::vector<GiNaC::ex> values;
};

inline exact_state state_of(const solution& s, const GiNaC::ex& inputs)
{
    GiNaC::lst steps = s.step_values(inputs);
    auto ev = [&](const GiNaC::ex& e) { return e.subs(inputs).subs(steps); };
    exact_state st;
    for (const body_state& b : s.after)
        for (int c = 0; c < 3; ++c) {
            st.values.push_back(ev(b.velocity[c]));
            st.values.push_back(ev(b.angular_velocity[c]));
        }
    st.values.push_back(ev(s.normal_impulse));
    for (const vec3& R : s.pivot_impulses)
        for (int c = 0; c < 3; ++c)
            st.values.push_back(ev(R[c]));
    return st;
}

template <typename T> std::vector<T> state_of(const numeric::answer<T>& a)
{
    std::vector<T> v;
    for (std::size_t i = 0; i < a.velocity.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            v.push_back(a.velocity[i][c]);
            v.push_back(a.angular_velocity[i][c]);
        }
    v.push_back(a.normal_impulse);
    for (const auto& R : a.pivot_impulses)
        for (int c = 0; c < 3; ++c)
            v.push_back(R[c]);
    return v;
}

/// max |a - b| / max(1e-300, max |exact|): relative error of the whole state.
template <typename T> double state_error(const exact_state& exact, const std::vector<T>& approx)
{
    if (exact.values.size() != approx.size())
        return 1e300;
    double scale = 0, err = 0;
    for (std::size_t k = 0; k < approx.size(); ++k) {
        double x = GiNaC::ex_to<GiNaC::numeric>(exact.values[k].evalf()).to_double();
        scale = std::max(scale, std::abs(x));
        err = std::max(err, std::abs(x - static_cast<double>(approx[k])));
    }
    return err / std::max(scale, 1e-300);
}

inline bool is_zero_exact(const GiNaC::ex& e) { return e.normal().is_zero(); }

/// The laws an exact numeric solution must satisfy, checked exactly.
inline void expect_physics(const derivation& d, const solution& s, const GiNaC::ex& inputs, const std::string& what)
{
    using GiNaC::ex;
    const problem& p = d.prob;
    GiNaC::lst steps = s.step_values(inputs);
    auto ev = [&](const ex& e) { return e.subs(inputs).subs(steps).normal(); };
    auto evv = [&](const vec3& v) { return vec3{ev(v[0]), ev(v[1]), ev(v[2])}; };
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    vec3 n = evv(d.n_hat);
    auto contact_v = [&](std::size_t i, const vec3& v, const vec3& w) {
        body b = p.bodies[i];
        b.position = evv(b.position);
        return point_velocity(b, v, w, evv(p.contact().point));
    };
    const body& A = p.bodies[i1];
    const body& B = p.bodies[i2];
    vec3 vA = contact_v(i1, evv(A.velocity), evv(A.angular_velocity));
    vec3 vB = contact_v(i2, evv(B.velocity), evv(B.angular_velocity));
    vec3 vA1 = contact_v(i1, evv(s.after[i1].velocity), evv(s.after[i1].angular_velocity));
    vec3 vB1 = contact_v(i2, evv(s.after[i2].velocity), evv(s.after[i2].angular_velocity));
    ex e = ev(p.restitution);
    EXPECT_TRUE(is_zero_exact(dot(vB1 - vA1, n) + e * dot(vB - vA, n))) << what << ": restitution law";
    ex N = ev(s.normal_impulse);
    EXPECT_TRUE(GiNaC::ex_to<GiNaC::numeric>(N) >= 0) << what << ": normal impulse " << N << " < 0";

    // Momentum of each body: m dv = s N n + R (pivot), exactly, for every body of finite mass.
    for (std::size_t i : {i1, i2}) {
        const body& b = p.bodies[i];
        if (b.infinite_mass) {
            for (int c = 0; c < 3; ++c)
                EXPECT_TRUE(is_zero_exact(ev(s.after[i].velocity[c] - b.velocity[c]))) << what << ": infinite mass moved";
            continue;
        }
        ex sg = i == i1 ? -1 : 1;
        vec3 R = zero_vec();
        const pivot* pv = p.pivot_of(i);
        if (pv)
            R = evv(s.pivot_impulses[static_cast<std::size_t>(pv - p.pivots.data())]);
        vec3 dv = evv(s.after[i].velocity) - evv(b.velocity);
        for (int c = 0; c < 3; ++c)
            EXPECT_TRUE(is_zero_exact(ev(b.mass) * dv[c] - sg * N * n[c] - R[c])) << what << ": linear impulse of " << b.name;
        // Tangential components unchanged for a free body (no tangential impulse).
        if (!pv) {
            vec3 cr = cross(dv, n);
            for (int c = 0; c < 3; ++c)
                EXPECT_TRUE(is_zero_exact(cr[c])) << what << ": tangential velocity of " << b.name << " changed";
        }
        // Angular momentum about the pivot (or O) changes by the moment of the contact impulse only.
        if (!b.particle) {
            vec3 ref = pv ? evv(pv->point) : evv(p.contact().point);
            vec3 C = evv(b.position);
            mat3 J;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    J[r][c] = ev(b.inertia[r][c]);
            vec3 dw = evv(s.after[i].angular_velocity) - evv(b.angular_velocity);
            vec3 dH = mul(J, dw) + cross(C - ref, ev(b.mass) * dv);
            vec3 M = cross(evv(p.contact().point) - ref, (sg * N) * n);
            for (int c = 0; c < 3; ++c)
                EXPECT_TRUE(is_zero_exact(dH[c] - M[c])) << what << ": angular momentum of " << b.name;
        }
        if (pv) {
            body bb = b;
            bb.position = evv(b.position);
            vec3 vE = point_velocity(bb, evv(s.after[i].velocity), evv(s.after[i].angular_velocity), evv(pv->point));
            for (int c = 0; c < 3; ++c)
                EXPECT_TRUE(is_zero_exact(vE[c])) << what << ": pivot of " << b.name << " moves after impact";
        }
    }
    // Energy: the compact work formula equals T - T'; lost >= 0 unless a moving infinite mass does work.
    ex lost = ev(s.energy_lost);
    EXPECT_TRUE(is_zero_exact(lost - ev(s.energy_before) + ev(s.energy_after_direct))) << what << ": energy bookkeeping";
    bool moving_infinite = false;
    for (std::size_t i : {i1, i2})
        if (p.bodies[i].infinite_mass)
            for (int c = 0; c < 3; ++c)
                moving_infinite = moving_infinite || !ev(p.bodies[i].velocity[c]).is_zero() || !ev(p.bodies[i].angular_velocity[c]).is_zero();
    if (!moving_infinite) {
        EXPECT_TRUE(GiNaC::ex_to<GiNaC::numeric>(lost) >= 0) << what << ": energy gained " << -lost;
    }
    if (e == 1 && !moving_infinite) {
        EXPECT_TRUE(lost.is_zero()) << what << ": energy lost at e = 1: " << lost;
    }
}

} // namespace impactgen::testing
