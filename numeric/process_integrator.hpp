// A numeric reference for Routh's process (planar, one contact with Coulomb friction):
// the impact followed in small steps of the normal impulse, with Eigen, independent of the
// closed form of symbolic/routh.hpp. Nothing here solves a phase in closed form.
//
// The contact frame (n, t): u(P) = c + W P for the impulse P = (P_n, P_t) on body 2 (W the
// Delassus matrix; friction_contact assembles it from the bodies). The integrator marches
// P_n from 0 in steps h, each step taking the tangential impulse Coulomb's law asks for:
//   slip u_t != 0:        dP_t = -mu sign(u_t) dP_n                       (slide)
//   no slip, |r| <= mu:   dP_t = r dP_n, r = -W_tn / W_tt (u_t stays 0)    (stick)
//   no slip, |r| > mu:    slide in the direction the slip then takes
// and recomputes u = c + W P after each step. Within a step the motion is linear, so the
// step is cut at the first event it contains (the slip reaching 0, u_n reaching 0, the end of
// restitution), located by bisection on the step's fraction.
// Compression ends at u_n = 0 (P_c, W_c = int u_n dP_n); restitution ends at
//   poisson     P_n = (1 + e) P_c
//   energetic   int_{P_c} u_n dP_n = -e^2 W_c
// newton is not followed (ok = false).
#pragma once

#include "friction_solver.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <string>
#include <vector>

namespace impactgen::numeric
{

enum class process_law { poisson, energetic };
enum class process_phase_kind { slide, stick, reverse };

template <typename T> struct process_result {
    bool ok = false;      ///< false: the compression did not end within max_steps (the contact wedges)
    T normal_impulse = 0; ///< P_n at the end
    T tangential = 0;     ///< P_t along the frame's t at the end
    T compression_impulse = 0, compression_work = 0, restitution_work = 0;
    Eigen::Matrix<T, 2, 1> velocity_after = Eigen::Matrix<T, 2, 1>::Zero(); ///< (u'_n, u'_t)
    std::vector<process_phase_kind> phases;
    std::vector<T> phase_ends; ///< P_n at each phase's end
};

/// The process for the contact response W = [[W_nn, W_nt], [W_tn, W_tt]] and the velocity
/// c = (u_n, u_t) before impact (u_n < 0), marching P_n in `steps` steps of the frictionless
/// compression impulse -u_n / W_nn, growing (see below), at most 20 times that many.
template <typename T>
process_result<T> integrate_process(const Eigen::Matrix<T, 2, 2> &W, const Eigen::Matrix<T, 2, 1> &c, T mu, T e,
                                    process_law law, int steps = 4000)
{
    using V2 = Eigen::Matrix<T, 2, 1>;
    process_result<T> r;
    const T V = c.norm(), Wmax = W.cwiseAbs().maxCoeff();
    // The step starts at h0 and grows by 1% after each step without an event (back to h0 after
    // one): within a step the motion is linear, so its size does not change the accuracy, and a
    // nearly wedging contact (u_n growing at 1e-6 of the usual rate) still ends its compression
    // in a few thousand steps.
    const T h0 = -c[0] / W(0, 0) / T(steps);
    T h = h0;
    V2 P = V2::Zero();
    T work = 0, target = 0;
    bool compressed = false;
    int first_sign = 0;
    auto u_at = [&](const V2 &x) -> V2 { return c + W * x; };
    auto record = [&](process_phase_kind k) {
        if (r.phases.empty() || r.phases.back() != k) {
            if (!r.phases.empty())
                r.phase_ends.push_back(P[0]);
            r.phases.push_back(k);
        }
    };
    for (long k = 0; k < 20L * steps; ++k) {
        const V2 u = u_at(P);
        // A slip below the rounding of u = c + W P (with a margin) is no slip.
        const T vtol = T(1e-11) * (V + Wmax * P.cwiseAbs().sum());
        if (!compressed && k > 0 && u[0] >= -vtol) { // u_n is 0 within rounding (a slip stopped there)
            compressed = true;
            r.compression_impulse = P[0];
            r.compression_work = work;
            target = -e * e * work;
            work = 0;
            if (e == 0 || (law == process_law::poisson && P[0] >= (1 + e) * r.compression_impulse)) {
                r.ok = true;
                r.normal_impulse = P[0];
                r.tangential = P[1];
                r.velocity_after = u;
                r.phase_ends.push_back(P[0]);
                if (r.phases.empty())
                    r.phases.push_back(process_phase_kind::slide);
                return r;
            }
        }
        // The mode for this step: dP = (1, rate) per unit of P_n.
        T rate = 0;
        process_phase_kind kind = process_phase_kind::stick;
        int s = 0;
        if (std::abs(u[1]) > vtol) {
            s = u[1] > 0 ? 1 : -1;
        } else if (std::abs(W(1, 0)) <= mu * W(1, 1)) {
            rate = -W(1, 0) / W(1, 1);
        } else {
            s = W(1, 0) > 0 ? 1 : -1; // the slip grows along sign(W_tn)
        }
        if (s != 0) {
            rate = -T(s) * mu;
            if (first_sign == 0)
                first_sign = s;
            kind = s == first_sign ? process_phase_kind::slide : process_phase_kind::reverse;
        }
        record(kind);
        const V2 dP(T(1), rate);
        // The fraction f in (0, 1] of the step at the first event, by bisection on a predicate
        // that is false at 0 and (when the event is in the step) true at 1.
        auto first_event = [&](auto &&happened) {
            if (!happened(T(1)))
                return T(2);
            T lo = 0, hi = 1;
            for (int i = 0; i < 80; ++i) {
                const T mid = (lo + hi) / 2;
                (happened(mid) ? hi : lo) = mid;
            }
            return hi;
        };
        auto work_to = [&](T f) { // int u_n dP_n over the fraction f (u_n linear: trapezoid)
            return (u[0] + u_at(P + f * h * dP)[0]) / 2 * f * h;
        };
        T f = 1;
        int event = 0; // 1: slip stops, 2: compression ends, 3: restitution ends
        if (s != 0 && std::abs(u[1]) > vtol) {
            const T g = first_event([&](T x) { return T(s) * u_at(P + x * h * dP)[1] <= 0; });
            if (g <= f) {
                f = g;
                event = 1;
            }
        }
        if (!compressed) {
            const T g = first_event([&](T x) { return u_at(P + x * h * dP)[0] >= 0; });
            if (g <= f) {
                f = g;
                event = 2;
            }
        } else if (law == process_law::poisson) {
            const T g = first_event([&](T x) { return P[0] + x * h >= (1 + e) * r.compression_impulse; });
            if (g <= f) {
                f = g;
                event = 3;
            }
        } else {
            const T g = first_event([&](T x) { return work + work_to(x) >= target; });
            if (g <= f) {
                f = g;
                event = 3;
            }
        }
        work += work_to(f);
        P += f * h * dP;
        h = event == 0 ? h * T(1.01) : h0;
        if (s == 0) // stick: P_t that holds u_t at 0 exactly, so that rounding does not accumulate
            P[1] = -(c[1] + W(1, 0) * P[0]) / W(1, 1);
        if (event == 1) { // snap the slip to 0: the next step decides stick or reverse
            // (the bisection leaves |u_t| below 2^-80 of the step's change)
        } else if (event == 2) {
            compressed = true;
            r.compression_impulse = P[0];
            r.compression_work = work;
            target = -e * e * work;
            work = 0;
            if (e == 0) // nothing to restore
                event = 3;
        }
        if (event == 3 || (compressed && law == process_law::energetic && target <= 0)) {
            r.ok = true;
            r.normal_impulse = P[0];
            r.tangential = P[1];
            r.restitution_work = work;
            r.velocity_after = u_at(P);
            r.phase_ends.push_back(P[0]);
            return r;
        }
    }
    return r; // the compression or the restitution never ended
}

/// The process for a planar problem's contact (friction_contact assembles W and c; the frame
/// is its n and t1), with the bodies after impact and their kinetic energies.
template <typename T> struct process_answer {
    process_result<T> process;
    vec<T> impulse = vec<T>::Zero(); ///< P on body 2, world axes
    std::vector<vec<T>> velocity, angular_velocity, pivot_impulses;
    T energy_before = 0, energy_after = 0;
};

template <typename T> process_answer<T> integrate_process(const problem<T> &p, process_law law, int steps = 4000)
{
    process_answer<T> a;
    friction_contact<T> fc(p);
    if (!fc.ok)
        return a;
    Eigen::Matrix<T, 2, 2> W;
    W << fc.W(0, 0), fc.W(0, 1), fc.W(1, 0), fc.W(1, 1);
    const Eigen::Matrix<T, 2, 1> c(fc.c[0], fc.c[1]);
    a.process = integrate_process<T>(W, c, fc.mu, fc.e, law, steps);
    if (!a.process.ok)
        return a;
    a.impulse = a.process.normal_impulse * fc.n + a.process.tangential * fc.t1;
    fc.apply(a.impulse, a.velocity, a.angular_velocity, a.pivot_impulses);
    a.energy_before = kinetic_energy(p);
    a.energy_after = kinetic_energy(p, a.velocity, a.angular_velocity);
    return a;
}

} // namespace impactgen::numeric
