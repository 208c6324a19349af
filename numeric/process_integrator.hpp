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
#include <utility>
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

namespace detail
{

/// The fraction f in (0, 1] of a step at its first event, by bisection on a predicate that is
/// false at 0 and (when the event is in the step) true at 1; 2 when the step has none.
template <typename T, typename Happened> T first_event(Happened &&happened)
{
    if (!happened(T(1)))
        return T(2);
    T lo = 0, hi = 1;
    for (int i = 0; i < 80; ++i) {
        const T mid = (lo + hi) / 2;
        (happened(mid) ? hi : lo) = mid;
    }
    return hi;
}

/// The march of process_integrator.hpp: its state, a step's mode and its first event.
template <typename T> class process_march
{
    using V2 = Eigen::Matrix<T, 2, 1>;

public:
    process_march(const Eigen::Matrix<T, 2, 2> &W, const V2 &c, T mu, T e, process_law law, int steps)
        : W_(W), c_(c), mu_(mu), e_(e), law_(law), steps_(steps), V_(c.norm()), Wmax_(W.cwiseAbs().maxCoeff()),
          // The step starts at h0 and grows by 1% after each step without an event (back to h0
          // after one): within a step the motion is linear, so its size does not change the
          // accuracy, and a nearly wedging contact (u_n growing at 1e-6 of the usual rate)
          // still ends its compression in a few thousand steps.
          h0_(-c[0] / W(0, 0) / T(steps)), h_(h0_)
    {
    }

    process_result<T> run()
    {
        for (long k = 0; k < 20L * steps_; ++k) {
            const V2 u = u_at(P_);
            // A slip below the rounding of u = c + W P (with a margin) is no slip.
            const T vtol = T(1e-11) * (V_ + Wmax_ * P_.cwiseAbs().sum());
            if (!compressed_ && k > 0 && u[0] >= -vtol) { // u_n is 0 within rounding (a slip stopped there)
                end_compression();
                if (e_ == 0 || (law_ == process_law::poisson && P_[0] >= (1 + e_) * r_.compression_impulse)) {
                    finish(u);
                    if (r_.phases.empty())
                        r_.phases.push_back(process_phase_kind::slide);
                    return r_;
                }
            }
            // The mode for this step: dP = (1, rate) per unit of P_n.
            int s = 0;
            const V2 dP(T(1), rate(u, vtol, s));
            const auto [f, event] = step_event(u, dP, s, vtol);
            work_ += work_to(u, dP, f);
            P_ += f * h_ * dP;
            h_ = event == 0 ? h_ * T(1.01) : h0_;
            if (s == 0) // stick: P_t that holds u_t at 0 exactly, so that rounding does not accumulate
                P_[1] = -(c_[1] + W_(1, 0) * P_[0]) / W_(1, 1);
            // event 1 (the slip stopped): the bisection leaves |u_t| below 2^-80 of the step's
            // change; the next step decides stick or reverse.
            bool restored = event == 3;
            if (event == 2) {
                end_compression();
                restored = e_ == 0; // nothing to restore
            }
            if (restored || (compressed_ && law_ == process_law::energetic && target_ <= 0)) {
                r_.restitution_work = work_;
                finish(u_at(P_));
                return r_;
            }
        }
        return r_; // the compression or the restitution never ended
    }

private:
    V2 u_at(const V2 &x) const { return c_ + W_ * x; }

    void record(process_phase_kind k)
    {
        if (r_.phases.empty() || r_.phases.back() != k) {
            if (!r_.phases.empty())
                r_.phase_ends.push_back(P_[0]);
            r_.phases.push_back(k);
        }
    }

    void end_compression()
    {
        compressed_ = true;
        r_.compression_impulse = P_[0];
        r_.compression_work = work_;
        target_ = -e_ * e_ * work_;
        work_ = 0;
    }

    void finish(const V2 &u_after)
    {
        r_.ok = true;
        r_.normal_impulse = P_[0];
        r_.tangential = P_[1];
        r_.velocity_after = u_after;
        r_.phase_ends.push_back(P_[0]);
    }

    // dP_t per unit of P_n in the mode Coulomb's law asks for at u (recorded as a phase); s the
    // slip's sign, 0 for stick.
    T rate(const V2 &u, T vtol, int &s)
    {
        T r = 0;
        process_phase_kind kind = process_phase_kind::stick;
        if (std::abs(u[1]) > vtol) {
            s = u[1] > 0 ? 1 : -1;
        } else if (std::abs(W_(1, 0)) <= mu_ * W_(1, 1)) {
            r = -W_(1, 0) / W_(1, 1);
        } else {
            s = W_(1, 0) > 0 ? 1 : -1; // the slip grows along sign(W_tn)
        }
        if (s != 0) {
            r = -T(s) * mu_;
            if (first_sign_ == 0)
                first_sign_ = s;
            kind = s == first_sign_ ? process_phase_kind::slide : process_phase_kind::reverse;
        }
        record(kind);
        return r;
    }

    // int u_n dP_n over the fraction f of the step (u_n linear: trapezoid).
    T work_to(const V2 &u, const V2 &dP, T f) const { return (u[0] + u_at(P_ + f * h_ * dP)[0]) / 2 * f * h_; }

    // The fraction of the step at its first event and the event: 0 none, 1 the slip stops,
    // 2 the compression ends, 3 the restitution ends.
    std::pair<T, int> step_event(const V2 &u, const V2 &dP, int s, T vtol) const
    {
        T f = 1;
        int event = 0;
        auto take = [&](T g, int which) {
            if (g <= f) {
                f = g;
                event = which;
            }
        };
        if (s != 0 && std::abs(u[1]) > vtol)
            take(first_event<T>([&](T x) { return T(s) * u_at(P_ + x * h_ * dP)[1] <= 0; }), 1);
        if (!compressed_)
            take(first_event<T>([&](T x) { return u_at(P_ + x * h_ * dP)[0] >= 0; }), 2);
        else if (law_ == process_law::poisson)
            take(first_event<T>([&](T x) { return P_[0] + x * h_ >= (1 + e_) * r_.compression_impulse; }), 3);
        else
            take(first_event<T>([&](T x) { return work_ + work_to(u, dP, x) >= target_; }), 3);
        return {f, event};
    }

    const Eigen::Matrix<T, 2, 2> W_;
    const V2 c_;
    const T mu_, e_;
    const process_law law_;
    const int steps_;
    const T V_, Wmax_, h0_;
    T h_;
    V2 P_ = V2::Zero();
    T work_ = 0, target_ = 0;
    bool compressed_ = false;
    int first_sign_ = 0;
    process_result<T> r_;
};

} // namespace detail

/// The process for the contact response W = [[W_nn, W_nt], [W_tn, W_tt]] and the velocity
/// c = (u_n, u_t) before impact (u_n < 0), marching P_n in `steps` steps of the frictionless
/// compression impulse -u_n / W_nn, growing (see below), at most 20 times that many.
template <typename T>
process_result<T> integrate_process(const Eigen::Matrix<T, 2, 2> &W, const Eigen::Matrix<T, 2, 1> &c, T mu, T e,
                                    process_law law, int steps = 4000)
{
    return detail::process_march<T>(W, c, mu, e, law, steps).run();
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
