// An independent numeric reference for impact with Coulomb friction: Newton's
// restitution along the normal and Coulomb's law at impulse level, solved as
// the complementarity problem it is. Nothing here uses a closed form.
//
// The law. Bodies 1 and 2 touch at O with normal n (body 1 -> body 2, any
// non-zero length; n^ = n/|n|). The contact impulse on body 2 is
// P = P_n n^ + P_t (P_t perpendicular to n^), on body 1 it is -P. u = v_B - v_A
// is the relative velocity of the contact points before the impact, u' after,
// u'_t the part of u' perpendicular to n^:
//   restitution   u'.n^ = -e u.n^,  P_n >= 0;
//   cone          |P_t| <= mu P_n;
//   stick         u'_t = 0,   or
//   slide         u'_t != 0 and P_t = -mu P_n u'_t/|u'_t|.
// mu = 0 is a smooth contact (P_t = 0, regime smooth).
//
// The body dynamics are assembled numerically (friction_contact): generalized
// velocities q = (v_C, w) of each movable body in contact, the block-diagonal
// mass matrix M = diag(m 1, I_C), the pivot constraints J_p q' = 0 (the pivot
// point is at rest after the impact) with the pivot impulses R as multipliers:
//     M (q' - q) = f(P) + J_p^T R,   J_p q' = 0,
// solved through the Schur complement S = J_p M^-1 J_p^T. f(P) is the
// generalized impulse of +P at O on body 2 and -P on body 1. Applying unit
// impulses along the contact frame (n^, t1[, t2]) gives the Delassus matrix
// W = du'/dP column by column, so that in frame coordinates
//     u'(P) = c + W P,   c = u'(P = 0)
// (c = u unless a pivot point was moving before the impact).
//
// The law is then solved in the contact frame:
//  * planar (one tangent): regime enumeration -- stick (a 2x2 solve) and
//    sliding with u'_t along +t and along -t (the normal equation with
//    P_t = -/+ mu P_n gives P_n); each candidate is checked against every
//    condition of the law;
//  * 3-D: a semismooth Newton method on the Alart-Curnier function with the
//    restitution as an equation (detail::alart_curnier), damped by backtracking
//    on |F|^2, from up to 7 starting points (normal impulse alone, the stick
//    impulse, slides along -u'_t and +-t1, +-t2), max_iterations each. When all
//    of them fail -- seen about once in 1000 random two-body problems, near
//    grazing with a large mu, where a slide needs a finite P_n for a vanishing
//    approach and |F| has a spurious local minimum at P = 0 -- the start is the
//    root of the reduced problem (detail::reduced_root: for fixed P_n the
//    tangential law is a strictly convex minimization over the disc, unique;
//    phi(P_n) = W_n.P - rhs_n is then bracketed and bisected);
//    and an enumeration: the stick candidate (a 3x3 solve) and the sliding
//    candidates, found by scanning the sliding direction d(theta) = cos(theta) t1
//    + sin(theta) t2 for the zeros of g(theta) = D(theta) (u'_t(theta) x d(theta)),
//    where P_n(theta) = rhs_n / D(theta) solves the normal equation with
//    P_t = -mu P_n d. D g is a trigonometric polynomial of degree 2 (at most four
//    zeros on the circle) without the poles of u'_t(theta); its sign changes over
//    scan_samples equal steps are bracketed, bisected to machine precision and
//    polished by Newton's method on (theta, P_n) (detail::polish_slide). Zeros of
//    even multiplicity (a tangency of g to 0, a degenerate case) and two zeros
//    within one step are not seen by the scan.
// A singular stick system (W's leading block: the contact point cannot move in
// some direction, e.g. a pinned body on an infinite mass) has no stick
// candidate: sticking is then impossible or indeterminate. No compliance along
// the normal (W_nn = 0) is status singular.
//
// Tolerances (friction_options): all relative to the problem's own scales.
// V = max(|u|, |c|) is the velocity scale and w = max |W_ij| the compliance
// scale; P0 = V / w is the impulse scale of the contact. A candidate x (frame
// coordinates of P) is accepted when, with Vx = max(V, w |x|) (the size of the
// terms of c + W x, hence of their rounding) and Px = tol |x| + floor P0:
//   |u'_n + e u_n| <= tol Vx,  P_n >= -Px,  |P_t| <= mu P_n + Px,
//   stick: |u'_t| <= tol Vx;
//   slide: u'_t.d >= -tol Vx, |u'_t - (u'_t.d) d| <= tol Vx, |P_t + mu P_n d| <= Px;
// tol = friction_options::tolerance (default sqrt(machine epsilon), 1.5e-8 in
// double), floor = impulse_floor (default 1000 eps, 2.2e-13). The impulse
// conditions are relative to the impulse itself: near grazing every candidate's
// impulse is tiny against P0, and a slide with P_n = -1e-9 P0 must still be
// rejected. A candidate must also be resolved (detail::resolved):
//   eps w |x| <= tol V,  i.e. |x| <= (tol / eps) P0 (6.7e7 P0 in double).
// Beyond it the rounding of W itself (eps w per entry) moves u' = c + W x by more
// than the tolerance on the velocity scale, and tol Vx > (tol^2 / eps) V (= V in
// double) no longer tells restitution from its failure. A singular W (a body
// pinned at a point struck by an infinite mass: the contact point can only move
// perpendicular to the lever from the pivot) has spurious roots there: its
// smallest singular value is a rounding (below eps w) instead of 0, and an impulse of
// ~P0 / eps along its null direction (inside the cone when mu exceeds the lever's
// slope) cancels any residual. Without this condition Newton's method converged
// there (|F| <= newton_tolerance w |x| is then 1e4 to 1e5 V) on about 2% of the
// random problems of tests/codegen/friction/pinned-plate-struck-3d.json, with a
// normal impulse ~1e17 P0 and u' breaking restitution by up to 50 V where the law
// has no solution; an unresolved Newton point is a failed start. Two candidates
// x, y are one solution when |x - y| <= merge max(|x|, |y|) + floor P0 (a stick
// impulse on the cone's edge is also a slide with u'_t = 0).
#pragma once

#include "friction_contact.hpp"
#include "numeric_problem.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace impactgen::numeric
{

namespace detail
{

template <typename T> using fv3 = Eigen::Matrix<T, 3, 1>;
template <typename T> using fm3 = Eigen::Matrix<T, 3, 3>;

/// The tangential part (components 1, 2) of a frame vector.
template <typename T> Eigen::Matrix<T, 2, 1> tangential(const fv3<T> &a)
{
    return Eigen::Matrix<T, 2, 1>(a[1], a[2]);
}

/// Whether the law can be checked at frame impulse x (header comment): the rounding
/// of W x, eps w |x|, within the tolerance on the velocity scale, tol V. Beyond it
/// u' = c + W x is not known to the tolerance; a singular W has spurious roots there
/// (its null direction, scaled by ~1 / eps, against a rounding-sized singular value).
template <typename T> bool resolved(const friction_contact<T> &fc, const fv3<T> &x, const friction_options<T> &opt)
{
    return std::numeric_limits<T>::epsilon() * fc.compliance_scale * x.norm() <= opt.tolerance * fc.velocity_scale;
}

/// Checks frame impulse x against the law (header comment); d: the sliding direction (frame, tangential) for a slide.
template <typename T>
bool satisfies_law(const friction_contact<T> &fc, const fv3<T> &x, friction_regime regime,
                   const Eigen::Matrix<T, 2, 1> &d, const friction_options<T> &opt)
{
    using std::abs;
    if (!x.allFinite() || !resolved(fc, x, opt))
        return false;
    const T tol = opt.tolerance;
    const fv3<T> up = fc.velocity_after(x);
    const T Vx = std::max(fc.velocity_scale, fc.compliance_scale * x.norm());
    const T Pt = tol * x.norm() + opt.impulse_floor * fc.impulse_scale; // impulse tolerance
    if (!(abs(up[0] + fc.e * fc.u[0]) <= tol * Vx) || !(x[0] >= -Pt))
        return false;
    const auto ut = tangential<T>(up);
    const auto pt = tangential<T>(x);
    if (regime == friction_regime::smooth)
        return pt.norm() == 0;
    if (!(pt.norm() <= fc.mu * std::max(x[0], T(0)) + Pt))
        return false;
    if (regime == friction_regime::stick)
        return ut.norm() <= tol * Vx;
    const T along = ut.dot(d);
    return along >= -tol * Vx && (ut - along * d).norm() <= tol * Vx && (pt + fc.mu * x[0] * d).norm() <= Pt;
}

template <typename T>
friction_candidate<T> make_candidate(const friction_contact<T> &fc, const fv3<T> &x, friction_regime regime,
                                     const Eigen::Matrix<T, 2, 1> &d)
{
    friction_candidate<T> k;
    k.regime = regime;
    k.normal_impulse = x[0];
    k.tangential_impulse = x[1] * fc.t1 + x[2] * fc.t2;
    if (regime == friction_regime::slide)
        k.sliding_direction = d[0] * fc.t1 + d[1] * fc.t2;
    k.relative_velocity_after = fc.world(fc.velocity_after(x));
    return k;
}

template <typename T> fv3<T> frame_impulse(const friction_contact<T> &fc, const friction_candidate<T> &k)
{
    return fv3<T>(k.normal_impulse, k.tangential_impulse.dot(fc.t1), k.tangential_impulse.dot(fc.t2));
}

/// Adds k to list unless a candidate with the same impulse is already there.
template <typename T>
void add_distinct(const friction_contact<T> &fc, std::vector<friction_candidate<T>> &list,
                  const friction_candidate<T> &k, T merge, T floor)
{
    const fv3<T> x = frame_impulse(fc, k);
    for (const auto &o : list) {
        const fv3<T> y = frame_impulse(fc, o);
        if ((x - y).norm() <= merge * std::max(x.norm(), y.norm()) + floor * fc.impulse_scale)
            return;
    }
    list.push_back(k);
}

/// The stick candidate: u'_t = 0 and the restitution, a (1 + tangents)-square solve.
template <typename T> bool stick_impulse(const friction_contact<T> &fc, fv3<T> &x)
{
    const int k = 1 + fc.tangents;
    using MX = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
    using VX = Eigen::Matrix<T, Eigen::Dynamic, 1>;
    MX A = fc.W.topLeftCorner(k, k);
    VX b(k);
    b[0] = fc.normal_rhs();
    for (int i = 1; i < k; ++i)
        b[i] = -fc.c[i];
    Eigen::FullPivLU<MX> lu(A);
    if (!lu.isInvertible())
        return false;
    VX s = lu.solve(b);
    x.setZero();
    x.head(k) = s;
    return x.allFinite();
}

/// The slide candidate along the frame-tangential unit direction d: P_t = -mu P_n d
/// and the normal equation; false when that equation is degenerate.
template <typename T> bool slide_impulse(const friction_contact<T> &fc, const Eigen::Matrix<T, 2, 1> &d, fv3<T> &x)
{
    const T D = fc.W(0, 0) - fc.mu * (fc.W(0, 1) * d[0] + fc.W(0, 2) * d[1]);
    if (D == 0)
        return false;
    const T Pn = fc.normal_rhs() / D;
    x = fv3<T>(Pn, -fc.mu * Pn * d[0], -fc.mu * Pn * d[1]);
    return x.allFinite();
}

/// D(theta) (u'_t(theta) x d(theta)), the scan function of the 3-D enumeration.
template <typename T> T slide_residual(const friction_contact<T> &fc, T theta)
{
    using std::cos;
    using std::sin;
    const T dx = cos(theta), dy = sin(theta);
    const T D = fc.W(0, 0) - fc.mu * (fc.W(0, 1) * dx + fc.W(0, 2) * dy);
    const T rn = fc.normal_rhs();
    // u'_t D = c_t D + (W_tn - mu W_tt d) rn
    const T hx = fc.c[1] * D + (fc.W(1, 0) - fc.mu * (fc.W(1, 1) * dx + fc.W(1, 2) * dy)) * rn;
    const T hy = fc.c[2] * D + (fc.W(2, 0) - fc.mu * (fc.W(2, 1) * dx + fc.W(2, 2) * dy)) * rn;
    return hx * dy - hy * dx;
}

/// Polishes a sliding root (theta, P_n) by Newton's method on the two equations of
/// the slide regime without the division by D: F1 = W_n.x - rhs_n and
/// F2 = u'_t x d, x = (P_n, -mu P_n d(theta)); steps are taken while |F| decreases.
/// (Near grazing with a large mu, D is a small difference and P_n = rhs_n / D loses
/// digits that this recovers.)
template <typename T> fv3<T> polish_slide(const friction_contact<T> &fc, T theta, T Pn, int steps = 8)
{
    using std::cos;
    using std::sin;
    using D2 = Eigen::Matrix<T, 2, 1>;
    using M2 = Eigen::Matrix<T, 2, 2>;
    const T mu = fc.mu, rhs = fc.normal_rhs();
    const D2 wnt(fc.W(0, 1), fc.W(0, 2)), wtn(fc.W(1, 0), fc.W(2, 0));
    const M2 Wtt = fc.W.template bottomRightCorner<2, 2>();
    const D2 ct(fc.c[1], fc.c[2]);
    auto cross = [](const D2 &p, const D2 &q) { return p[0] * q[1] - p[1] * q[0]; };
    auto residual = [&](T th, T pn, M2 *J) {
        const D2 d(cos(th), sin(th)), dd(-sin(th), cos(th));
        const D2 ut = ct + wtn * pn - mu * pn * (Wtt * d);
        D2 F(fc.W(0, 0) * pn - mu * pn * wnt.dot(d) - rhs, cross(ut, d));
        if (J) {
            const D2 dut_dpn = wtn - mu * (Wtt * d), dut_dth = -mu * pn * (Wtt * dd);
            (*J)(0, 0) = -mu * pn * wnt.dot(dd);
            (*J)(0, 1) = fc.W(0, 0) - mu * wnt.dot(d);
            (*J)(1, 0) = cross(dut_dth, d) + cross(ut, dd);
            (*J)(1, 1) = cross(dut_dpn, d);
        }
        return F;
    };
    M2 J;
    D2 F = residual(theta, Pn, &J);
    for (int k = 0; k < steps; ++k) {
        const D2 step = J.fullPivLu().solve(-F);
        if (!step.allFinite())
            break;
        M2 Jn;
        const D2 Fn = residual(theta + step[0], Pn + step[1], &Jn);
        if (!(Fn.norm() < F.norm()))
            break;
        theta += step[0];
        Pn += step[1];
        F = Fn;
        J = Jn;
    }
    return fv3<T>(Pn, -mu * Pn * cos(theta), -mu * Pn * sin(theta));
}

/// Every distinct solution of the law found by the enumeration (mu > 0).
template <typename T>
std::vector<friction_candidate<T>> enumerate(const friction_contact<T> &fc, const friction_options<T> &opt)
{
    using D2 = Eigen::Matrix<T, 2, 1>;
    std::vector<friction_candidate<T>> out;
    fv3<T> x;
    if (stick_impulse(fc, x) && satisfies_law(fc, x, friction_regime::stick, D2(D2::Zero()), opt))
        add_distinct(fc, out, make_candidate(fc, x, friction_regime::stick, D2(D2::Zero())), opt.merge,
                     opt.impulse_floor);
    auto try_slide = [&](const D2 &d) {
        fv3<T> y;
        if (slide_impulse(fc, d, y) && satisfies_law(fc, y, friction_regime::slide, d, opt))
            add_distinct(fc, out, make_candidate(fc, y, friction_regime::slide, d), opt.merge, opt.impulse_floor);
    };
    if (fc.tangents == 1) {
        try_slide(D2(1, 0));
        try_slide(D2(-1, 0));
        return out;
    }
    const T two_pi = T(2) * T(3.14159265358979323846264338327950288L);
    const int N = std::max(opt.scan_samples, 8);
    const T step = two_pi / T(N);
    T a = 0, ga = slide_residual(fc, a);
    for (int k = 1; k <= N; ++k) {
        const T b = step * T(k);
        const T gb = slide_residual(fc, b);
        if (ga == 0)
            try_slide(D2(std::cos(a), std::sin(a)));
        else if ((ga < 0) != (gb < 0) && gb != 0) {
            T lo = a, hi = b, glo = ga;
            for (int it = 0; it < 200 && hi - lo > std::numeric_limits<T>::epsilon() * two_pi; ++it) {
                const T mid = (lo + hi) / 2;
                if (mid <= lo || mid >= hi)
                    break;
                const T gm = slide_residual(fc, mid);
                if (gm == 0) {
                    lo = hi = mid;
                    break;
                }
                if ((gm < 0) == (glo < 0)) {
                    lo = mid;
                    glo = gm;
                } else
                    hi = mid;
            }
            const T th = (lo + hi) / 2;
            fv3<T> y;
            if (slide_impulse(fc, D2(std::cos(th), std::sin(th)), y)) {
                y = polish_slide(fc, th, y[0]);
                const D2 d = -tangential<T>(y) / (fc.mu * y[0]);
                if (y[0] != 0 && satisfies_law(fc, y, friction_regime::slide, d, opt))
                    add_distinct(fc, out, make_candidate(fc, y, friction_regime::slide, d), opt.merge,
                                 opt.impulse_floor);
                else
                    try_slide(D2(std::cos(th), std::sin(th)));
            }
        }
        a = b;
        ga = gb;
    }
    return out;
}

/// The Alart-Curnier function with the restitution as an equation, in velocity units:
///   F_n = u'_n + e u_n,
///   F_t = (P_t - proj_{|.| <= mu max(P_n, 0)}(P_t - rho u'_t)) / rho,
/// and an element of its generalized Jacobian.
template <typename T> fv3<T> alart_curnier(const friction_contact<T> &fc, const fv3<T> &x, T rho, fm3<T> *J)
{
    using M2 = Eigen::Matrix<T, 2, 2>;
    using D2 = Eigen::Matrix<T, 2, 1>;
    const fv3<T> up = fc.velocity_after(x);
    fv3<T> F;
    F[0] = up[0] + fc.e * fc.u[0];
    const D2 pt = tangential<T>(x), ut = tangential<T>(up);
    const D2 z = pt - rho * ut;
    const T r = fc.mu * std::max(x[0], T(0));
    const T nz = z.norm();
    const M2 Wtt = fc.W.template bottomRightCorner<2, 2>();
    const D2 wtn(fc.W(1, 0), fc.W(2, 0));
    if (J)
        J->row(0) = fc.W.row(0);
    if (nz <= r) { // inside the disc: F_t = u'_t
        F.template tail<2>() = ut;
        if (J)
            J->template bottomRows<2>() = fc.W.template bottomRows<2>();
    } else {
        const D2 zh = nz > 0 ? D2(z / nz) : D2::Zero();
        F.template tail<2>() = (pt - r * zh) / rho;
        if (J) {
            const M2 Pz = M2::Identity() - zh * zh.transpose();
            const T s = nz > 0 ? r / nz : T(0);
            const M2 Jtt = (M2::Identity() - s * Pz * (M2::Identity() - rho * Wtt)) / rho;
            const D2 Jtn = ((x[0] > 0 ? -fc.mu : T(0)) * zh + s * rho * (Pz * wtn)) / rho;
            J->template block<2, 1>(1, 0) = Jtn;
            J->template block<2, 2>(1, 1) = Jtt;
        }
    }
    return F;
}

/// Damped semismooth Newton from x (Armijo backtracking on |F|^2). Converged when
/// |F| <= newton_tolerance * max(V, w |x|) and the step has stopped contracting
/// (|dx| <= 8 eps |x|, or no smaller than half the previous step: the rounding floor),
/// at a resolved point (resolved: with W singular the iteration can run off along its
/// null direction to |x| ~ P0 / eps, where that test passes for any u').
template <typename T>
bool newton_from(const friction_contact<T> &fc, const friction_options<T> &opt, fv3<T> &x, int &iterations)
{
    const T eps = std::numeric_limits<T>::epsilon();
    const T rho = T(1) / fc.compliance_scale; // the Alart-Curnier parameter: 1 / max |W_ij|
    fm3<T> J;
    fv3<T> F = alart_curnier(fc, x, rho, &J);
    T previous = std::numeric_limits<T>::infinity();
    for (int it = 0; it < opt.max_iterations; ++it) {
        const bool small =
            F.norm() <= opt.newton_tolerance * std::max(fc.velocity_scale, fc.compliance_scale * x.norm());
        Eigen::FullPivLU<fm3<T>> lu(J);
        const fv3<T> dx = lu.solve(-F);
        if (!dx.allFinite())
            return false;
        const T step = dx.norm();
        if (small && (step <= 8 * eps * x.norm() || step >= previous / 2))
            return resolved(fc, x, opt);
        previous = step;
        ++iterations;
        const T phi = F.squaredNorm();
        T alpha = 1;
        fv3<T> xn;
        bool accepted = false;
        for (int ls = 0; ls < 40 && !accepted; ++ls) {
            xn = x + alpha * dx;
            accepted = alart_curnier(fc, xn, rho, static_cast<fm3<T> *>(nullptr)).squaredNorm() <=
                       (T(1) - T(1e-4) * alpha) * phi;
            if (!accepted)
                alpha /= 2;
        }
        if (!accepted)
            return small && resolved(fc, x, opt); // no descent left: at the rounding floor, or stuck
        x = xn;
        F = alart_curnier(fc, x, rho, &J);
    }
    return F.norm() <= opt.newton_tolerance * std::max(fc.velocity_scale, fc.compliance_scale * x.norm()) &&
           resolved(fc, x, opt);
}

/// Classifies a converged point (stick when |u'_t| <= tol Vx) and checks it against the law.
template <typename T>
bool accept_point(const friction_contact<T> &fc, const friction_options<T> &opt, const fv3<T> &x,
                  friction_candidate<T> &out)
{
    using D2 = Eigen::Matrix<T, 2, 1>;
    const D2 ut = tangential<T>(fc.velocity_after(x));
    const T Vx = std::max(fc.velocity_scale, fc.compliance_scale * x.norm());
    const bool stick = ut.norm() <= opt.tolerance * Vx;
    const D2 d = stick ? D2::Zero() : D2(ut / ut.norm());
    const friction_regime reg = stick ? friction_regime::stick : friction_regime::slide;
    if (!satisfies_law(fc, x, reg, d, opt))
        return false;
    out = make_candidate(fc, x, reg, d);
    out.from_newton = true;
    return true;
}

/// P_t(P_n) for a fixed P_n >= 0. The tangential law at fixed P_n (stick inside
/// the disc |P_t| <= mu P_n, or slide on its edge against u'_t) is the optimality
/// condition of the strictly convex problem: minimize P_t.W_tt P_t / 2 + b.P_t,
/// b = c_t + W_tn P_n, over the disc (maximal dissipation). Its unique minimizer is
/// -W_tt^-1 b when inside, else -(W_tt + lambda 1)^-1 b with lambda > 0 such that
/// |P_t| = mu P_n (found by bisection; |P_t(lambda)| decreases). False when W_tt
/// is not positive definite.
template <typename T> bool tangential_response(const friction_contact<T> &fc, T Pn, Eigen::Matrix<T, 2, 1> &Pt)
{
    using std::sqrt;
    using M2 = Eigen::Matrix<T, 2, 2>;
    using D2 = Eigen::Matrix<T, 2, 1>;
    const M2 A = fc.W.template bottomRightCorner<2, 2>();
    const D2 b(fc.c[1] + fc.W(1, 0) * Pn, fc.c[2] + fc.W(2, 0) * Pn);
    Eigen::SelfAdjointEigenSolver<M2> es(A);
    const D2 a = es.eigenvalues(); // ascending
    if (!(a[0] > std::numeric_limits<T>::epsilon() * a[1]))
        return false;
    const D2 beta = es.eigenvectors().transpose() * b;
    auto at = [&](T lambda) {
        return D2(-(es.eigenvectors() * D2(beta[0] / (a[0] + lambda), beta[1] / (a[1] + lambda))));
    };
    const T r = fc.mu * std::max(Pn, T(0));
    Pt = at(0);
    if (Pt.norm() <= r)
        return true;
    if (!(r > 0)) {
        Pt.setZero();
        return true;
    }
    T lo = 0, hi = b.norm() / r; // |P_t(hi)| < |b| / hi = r
    for (int it = 0; it < 400; ++it) {
        const T mid = (lo + hi) / 2;
        if (mid <= lo || mid >= hi)
            break;
        (at(mid).norm() > r ? lo : hi) = mid;
    }
    Pt = at((lo + hi) / 2);
    Pt *= r / Pt.norm(); // on the edge exactly
    return Pt.allFinite();
}

/// The reduced problem: every solution of the law is a root P_n >= 0 of
///     phi(P_n) = W_nn P_n + W_nt.P_t(P_n) - rhs_n
/// (tangential_response). phi(0) = -rhs_n < 0 for an approach; P_n grows
/// geometrically from 1e-3 rhs_n / w by factors of 2 (at most 160 steps) to the
/// first sign change, which bisection narrows. x: the root with its P_t.
template <typename T> bool reduced_root(const friction_contact<T> &fc, fv3<T> &x)
{
    using D2 = Eigen::Matrix<T, 2, 1>;
    const T rhs = fc.normal_rhs();
    if (!(rhs > 0))
        return false;
    D2 Pt;
    auto phi = [&](T Pn, bool &ok) {
        ok = tangential_response(fc, Pn, Pt);
        return fc.W(0, 0) * Pn + fc.W(0, 1) * Pt[0] + fc.W(0, 2) * Pt[1] - rhs;
    };
    bool ok = true;
    T lo = 0, hi = T(1e-3) * rhs / fc.compliance_scale;
    bool found = false;
    for (int k = 0; k < 160 && !found; ++k) {
        const T f = phi(hi, ok);
        if (!ok)
            return false;
        if (f >= 0)
            found = true;
        else {
            lo = hi;
            hi *= 2;
        }
    }
    if (!found)
        return false;
    for (int it = 0; it < 400; ++it) {
        const T mid = (lo + hi) / 2;
        if (mid <= lo || mid >= hi)
            break;
        (phi(mid, ok) < 0 ? lo : hi) = mid;
    }
    const T Pn = (lo + hi) / 2;
    phi(Pn, ok);
    x = fv3<T>(Pn, Pt[0], Pt[1]);
    return ok && x.allFinite();
}

/// The Newton method from its starting points (normal impulse alone, the stick
/// impulse, slides along -u'_t at the normal impulse and along +-t1, +-t2);
/// the first converged point that satisfies the law. When every start fails
/// (seen near grazing with a large mu, where a slide needs a finite P_n for a
/// vanishing approach and |F| has a spurious local minimum at P = 0), the root
/// of the reduced problem (reduced_root) is the last start; reduced is then true.
template <typename T>
bool newton(const friction_contact<T> &fc, const friction_options<T> &opt, friction_candidate<T> &out, int &iterations,
            bool &reduced)
{
    using D2 = Eigen::Matrix<T, 2, 1>;
    reduced = false;
    std::vector<fv3<T>> starts;
    if (fc.W(0, 0) != 0)
        starts.push_back(fv3<T>(fc.normal_rhs() / fc.W(0, 0), 0, 0));
    fv3<T> y;
    if (stick_impulse(fc, y))
        starts.push_back(y);
    std::vector<D2> dirs;
    if (!starts.empty()) {
        const D2 ut = tangential<T>(fc.velocity_after(starts.front()));
        if (ut.norm() > 0)
            dirs.push_back(ut / ut.norm());
    }
    dirs.push_back(D2(1, 0));
    dirs.push_back(D2(-1, 0));
    dirs.push_back(D2(0, 1));
    dirs.push_back(D2(0, -1));
    for (const D2 &d : dirs)
        if (slide_impulse(fc, d, y))
            starts.push_back(y);
    for (fv3<T> x : starts)
        if (newton_from(fc, opt, x, iterations) && accept_point(fc, opt, x, out))
            return true;
    if (!reduced_root(fc, y))
        return false;
    reduced = true;
    fv3<T> x = y;
    if (newton_from(fc, opt, x, iterations) && accept_point(fc, opt, x, out))
        return true;
    return accept_point(fc, opt, y, out); // the bisected root unpolished
}

} // namespace detail

/// Solves the impact with Coulomb friction (header comment). status ok: exactly
/// one solution was found; ambiguous: several (the state is the first, or
/// Newton's in 3-D); no_solution / singular: the state is the state before.
template <typename T> friction_answer<T> solve_friction(const problem<T> &p, const friction_options<T> &opt = {})
{
    using D2 = Eigen::Matrix<T, 2, 1>;
    friction_answer<T> out;
    for (const auto &b : p.bodies) {
        out.velocity.push_back(b.velocity);
        out.angular_velocity.push_back(b.angular_velocity);
    }
    out.pivot_impulses.assign(p.pivots.size(), vec<T>::Zero());
    const friction_contact<T> fc(p);
    if (!fc.ok || !(fc.W(0, 0) > 0))
        return out;
    out.relative_velocity_before = fc.u_world;
    if (!(fc.mu >= 0) || !std::isfinite(fc.mu)) {
        out.status = friction_status::no_solution;
        return out;
    }
    const friction_candidate<T> *chosen = nullptr;
    friction_candidate<T> newton_answer;
    if (fc.mu == 0) {
        detail::fv3<T> x(fc.normal_rhs() / fc.W(0, 0), 0, 0);
        if (detail::satisfies_law(fc, x, friction_regime::smooth, D2(D2::Zero()), opt))
            out.candidates.push_back(detail::make_candidate(fc, x, friction_regime::smooth, D2(D2::Zero())));
    } else if (fc.tangents == 1 || opt.method == friction_method::enumeration) {
        out.candidates = detail::enumerate(fc, opt);
    } else {
        out.newton_converged = detail::newton(fc, opt, newton_answer, out.iterations, out.newton_reduced);
        if (out.newton_converged)
            out.candidates.push_back(newton_answer);
        if (opt.method == friction_method::automatic)
            for (const auto &k : detail::enumerate(fc, opt))
                detail::add_distinct(fc, out.candidates, k, opt.merge, opt.impulse_floor);
        if (out.newton_converged)
            chosen = &out.candidates.front();
    }
    if (out.candidates.empty()) {
        out.status = friction_status::no_solution;
        return out;
    }
    if (!chosen)
        chosen = &out.candidates.front();
    out.status = out.candidates.size() == 1 ? friction_status::ok : friction_status::ambiguous;
    out.regime = chosen->regime;
    out.normal_impulse = chosen->normal_impulse;
    out.tangential_impulse = chosen->tangential_impulse;
    out.relative_velocity_after = chosen->relative_velocity_after;
    fc.apply(chosen->normal_impulse * fc.n + chosen->tangential_impulse, out.velocity, out.angular_velocity,
             out.pivot_impulses);
    return out;
}

/// Kinetic energy of the bodies of finite mass: sum of m v.v / 2 + w.I w / 2
/// (particles: translation only; planar: I_zz w_z^2 / 2 since w = (0, 0, w_z)).
template <typename T>
T kinetic_energy(const problem<T> &p, const std::vector<vec<T>> &velocity, const std::vector<vec<T>> &angular_velocity)
{
    T E = 0;
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const auto &b = p.bodies[i];
        if (b.infinite_mass)
            continue;
        E += b.mass * velocity[i].squaredNorm() / 2;
        if (!b.particle)
            E += angular_velocity[i].dot(b.inertia * angular_velocity[i]) / 2;
    }
    return E;
}
/// Kinetic energy before the impact.
template <typename T> T kinetic_energy(const problem<T> &p)
{
    std::vector<vec<T>> v, w;
    for (const auto &b : p.bodies) {
        v.push_back(b.velocity);
        w.push_back(b.angular_velocity);
    }
    return kinetic_energy(p, v, w);
}

#if defined(IMPACTGEN_NUMERIC_PREBUILT)
// The project's own tests and benchmarks link impactgen_numeric_prebuilt
// (numeric/prebuilt/), which compiles the solver once per scalar type: here it is only
// declared (instantiating it costs ~15 s of compile time per type and translation unit).
#define IMPACTGEN_NUMERIC_FRICTION_INSTANCES(T)                                                                        \
    extern template friction_answer<T> solve_friction<T>(const problem<T> &, const friction_options<T> &);             \
    extern template T kinetic_energy<T>(const problem<T> &, const std::vector<vec<T>> &, const std::vector<vec<T>> &); \
    extern template T kinetic_energy<T>(const problem<T> &);
IMPACTGEN_NUMERIC_FRICTION_INSTANCES(float)
IMPACTGEN_NUMERIC_FRICTION_INSTANCES(double)
IMPACTGEN_NUMERIC_FRICTION_INSTANCES(long double)
#undef IMPACTGEN_NUMERIC_FRICTION_INSTANCES
#endif

} // namespace impactgen::numeric
