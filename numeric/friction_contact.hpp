// The contact of numeric/friction_solver.hpp: the law's regimes, statuses and options, its
// answer, and friction_contact, which assembles the body dynamics numerically: generalized
// velocities q = (v_C, w) of each movable body in contact, the block-diagonal mass matrix
// M = diag(m 1, I_C), the pivot constraints J_p q' = 0 with the pivot impulses as multipliers
// (through the Schur complement), and the Delassus matrix W = du'/dP in the contact frame
// (n^, t1[, t2]), u'(P) = c + W P. See friction_solver.hpp for the law and how it is solved.
#pragma once

#include "numeric_problem.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace impactgen::numeric
{

enum class friction_regime { smooth, stick, slide };
enum class friction_status {
    ok,       ///< exactly one solution of the law
    singular, ///< the body equations or the contact are degenerate (no compliance at the contact, two pivots on a body,
              ///< ...)
    no_solution, ///< no impulse satisfies the law (or a separating contact: P_n < 0), or mu < 0
    ambiguous    ///< more than one distinct impulse satisfies the law; friction_answer::candidates lists them
};
enum class friction_method {
    automatic,  ///< planar: enumeration; 3-D: Newton, and the enumeration for uniqueness
    newton,     ///< 3-D: semismooth Newton only (planar: the enumeration, there is no Newton)
    enumeration ///< regime enumeration only (3-D: stick + scan of the sliding direction)
};

inline const char *friction_regime_name(friction_regime r)
{
    switch (r) {
    case friction_regime::smooth:
        return "smooth";
    case friction_regime::stick:
        return "stick";
    case friction_regime::slide:
        return "slide";
    }
    return "?";
}
inline const char *friction_status_name(friction_status s)
{
    switch (s) {
    case friction_status::ok:
        return "ok";
    case friction_status::singular:
        return "singular";
    case friction_status::no_solution:
        return "no_solution";
    case friction_status::ambiguous:
        return "ambiguous";
    }
    return "?";
}

template <typename T> struct friction_options {
    /// Acceptance tolerance of the law, relative to the scales above.
    T tolerance = std::sqrt(std::numeric_limits<T>::epsilon());
    /// Impulse conditions (P_n >= 0, the cone, the sliding impulse) hold to
    /// tolerance |x| + impulse_floor P0: the floor covers the rounding of impulses
    /// that are tiny against the contact's scale (near grazing, P ~ |u.n| / w).
    T impulse_floor = T(1000) * std::numeric_limits<T>::epsilon();
    /// Candidates x, y are the same solution when |x - y| <= merge max(|x|, |y|) + impulse_floor P0.
    T merge = T(100) * std::sqrt(std::numeric_limits<T>::epsilon());
    /// Newton stops when |F| <= newton_tolerance * max(V, w |x|) (F in velocity units).
    T newton_tolerance = T(1000) * std::numeric_limits<T>::epsilon();
    /// Newton iteration cap per starting point (at most 7 starting points, and the reduced root).
    int max_iterations = 50;
    /// Samples of the sliding direction angle over [0, 2 pi) in the 3-D enumeration.
    int scan_samples = 720;
    friction_method method = friction_method::automatic;
};

/// One solution of the law (world axes; the impulse acts on body 2).
template <typename T> struct friction_candidate {
    friction_regime regime = friction_regime::stick;
    T normal_impulse = 0;
    vec<T> tangential_impulse = vec<T>::Zero();
    vec<T> sliding_direction = vec<T>::Zero();       ///< unit u'_t / |u'_t| when sliding, else 0
    vec<T> relative_velocity_after = vec<T>::Zero(); ///< u' = v'_B - v'_A at O
    bool from_newton = false;                        ///< found by the Newton method (3-D), not by the enumeration
};

template <typename T> struct friction_answer {
    friction_status status = friction_status::singular;
    friction_regime regime = friction_regime::smooth;
    std::vector<vec<T>> velocity,
        angular_velocity; ///< every body, after the impact (unchanged when singular / no solution)
    T normal_impulse = 0; ///< P_n, on body 2
    vec<T> tangential_impulse = vec<T>::Zero();       ///< P_t, world axes, on body 2
    std::vector<vec<T>> pivot_impulses;               ///< per pivot, world axes, on its body
    vec<T> relative_velocity_before = vec<T>::Zero(); ///< u
    vec<T> relative_velocity_after = vec<T>::Zero();  ///< u'
    int iterations = 0;                               ///< Newton iterations, all starts together (0: no Newton)
    bool newton_converged = false;                    ///< 3-D, automatic or newton method
    bool newton_reduced = false; ///< every Newton start failed: the reduced problem's root was the start
    /// The distinct solutions found (planar: by the enumeration; 3-D automatic: the
    /// enumeration's and Newton's, merged). The answer's state is candidates[0] in
    /// the planar case and Newton's in 3-D when it converged.
    std::vector<friction_candidate<T>> candidates;
};

/// The contact problem in the contact frame: u'(x) = c + W x for the frame
/// coordinates x = (P_n, P_t1[, P_t2]) of the impulse on body 2.
template <typename T> class friction_contact
{
public:
    using V3 = Eigen::Matrix<T, 3, 1>;
    using M3 = Eigen::Matrix<T, 3, 3>;
    using MX = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
    using VX = Eigen::Matrix<T, Eigen::Dynamic, 1>;

    explicit friction_contact(const problem<T> &p) : p_(p) { assemble(); }

    bool ok = false;  ///< false: singular body equations or no compliance at the contact
    int tangents = 1; ///< 1 (planar) or 2
    vec<T> n = vec<T>::Zero(), t1 = vec<T>::Zero(),
           t2 = vec<T>::Zero(); ///< the frame: n^, t1, t2 = n^ x t1 (t2 = 0 in the plane)
    M3 W = M3::Zero();          ///< Delassus matrix in the frame (unused rows/columns 0 in the plane)
    V3 c = V3::Zero();          ///< u' at P = 0, frame coordinates
    V3 u = V3::Zero();          ///< u before the impact, frame coordinates
    vec<T> u_world = vec<T>::Zero();
    T e = 0, mu = 0;
    T velocity_scale = 0;   ///< V
    T compliance_scale = 0; ///< w
    T impulse_scale = 0;    ///< P0 = V / w

    vec<T> world(const V3 &x) const { return x[0] * n + x[1] * t1 + x[2] * t2; }
    V3 frame(const vec<T> &a) const { return V3(a.dot(n), a.dot(t1), tangents == 2 ? a.dot(t2) : T(0)); }
    V3 velocity_after(const V3 &x) const { return c + W * x; }
    T normal_rhs() const { return -e * u[0] - c[0]; } ///< W_n. x must equal this

    /// Every body's state after the impulse P (world, on body 2) and the pivot impulses.
    void apply(const vec<T> &P, std::vector<vec<T>> &v, std::vector<vec<T>> &w, std::vector<vec<T>> &R) const
    {
        v.clear();
        w.clear();
        R.assign(p_.pivots.size(), vec<T>::Zero());
        VX q1, r;
        respond(force(P), true, q1, r);
        for (std::size_t i = 0; i < p_.bodies.size(); ++i) {
            vec<T> vi = p_.bodies[i].velocity, wi = p_.bodies[i].angular_velocity;
            if (off_[i] >= 0) {
                vi = lin(q1, i);
                if (!p_.bodies[i].particle)
                    wi = ang(q1, i);
            }
            v.push_back(vi);
            w.push_back(wi);
        }
        for (std::size_t k = 0; k < p_.pivots.size(); ++k) {
            const std::size_t b = p_.pivots[k].body;
            if (row_[k] >= 0)
                for (int a = 0; a < dim_; ++a)
                    R[k][a] = r[row_[k] + a];
            else if (!p_.bodies[b].infinite_mass && p_.bodies[b].particle && (b == p_.body1 || b == p_.body2))
                R[k] = -(b == p_.body1 ? T(-1) : T(1)) * P; // a pinned particle: the pivot takes the whole impulse
            // A bystander's pivot takes none; the pivot of an infinite mass is not determined (reported 0).
        }
    }

private:
    problem<T> p_;
    int dim_ = 3, nw_ = 3, ndof_ = 0, ncon_ = 0;
    std::vector<int> off_, row_;
    MX Minv_, Jp_;
    Eigen::FullPivLU<MX> S_;
    VX q_;

    vec<T> lin(const VX &x, std::size_t i) const
    {
        vec<T> a = vec<T>::Zero();
        for (int k = 0; k < dim_; ++k)
            a[k] = x[off_[i] + k];
        return a;
    }
    vec<T> ang(const VX &x, std::size_t i) const
    {
        vec<T> a = vec<T>::Zero();
        if (dim_ == 2)
            a[2] = x[off_[i] + 2];
        else
            for (int k = 0; k < 3; ++k)    // element-wise: g++ 12 reports a false -Warray-bounds on
                a[k] = x[off_[i] + 3 + k]; // packet copies between a dynamic segment and vec<float>
        return a;
    }
    T sign(std::size_t i) const { return i == p_.body1 ? T(-1) : T(1); }

    /// Generalized impulse of P at O on body 2 and -P on body 1.
    VX force(const vec<T> &P) const
    {
        VX f = VX::Zero(ndof_);
        for (std::size_t i : {p_.body1, p_.body2}) {
            if (off_[i] < 0)
                continue;
            const vec<T> Pi = sign(i) * P;
            for (int k = 0; k < dim_; ++k)
                f[off_[i] + k] += Pi[k];
            if (!p_.bodies[i].particle) {
                const vec<T> m = (p_.point - p_.bodies[i].position).cross(Pi);
                if (dim_ == 2)
                    f[off_[i] + 2] += m[2];
                else
                    for (int k = 0; k < 3; ++k)
                        f[off_[i] + 3 + k] += m[k];
            }
        }
        return f;
    }
    /// q' (with_initial: q + dq, else dq alone) and the pivot impulses for generalized
    /// impulse f: q' = base + M^-1 J_p^T R, R = -S^-1 J_p base, base = (q +) M^-1 f.
    /// Two steps of iterative refinement on J_p q' = 0: a light pinned body struck by
    /// a heavy one has |M^-1 f| ~ (mass ratio) V, which the pivot cancels.
    void respond(const VX &f, bool with_initial, VX &q1, VX &r) const
    {
        VX base = Minv_ * f;
        if (with_initial)
            base += q_;
        r = VX::Zero(ncon_);
        q1 = base;
        for (int pass = 0; pass < 3 && ncon_ > 0; ++pass) {
            const VX dr = -S_.solve(Jp_ * q1);
            r += dr;
            q1 += Minv_ * (Jp_.transpose() * dr);
        }
    }
    /// v_B - v_A at O from generalized velocities x (with_known: the immovable bodies' own velocities count).
    vec<T> contact_velocity(const VX &x, bool with_known) const
    {
        vec<T> out = vec<T>::Zero();
        for (std::size_t i : {p_.body1, p_.body2}) {
            const auto &b = p_.bodies[i];
            const vec<T> arm = p_.point - b.position;
            vec<T> vi = vec<T>::Zero();
            if (off_[i] >= 0) {
                vi = lin(x, i);
                if (!b.particle)
                    vi += ang(x, i).cross(arm);
            } else if (with_known) {
                vi = b.velocity;
                if (b.infinite_mass) // an infinite mass's spin moves its contact point even when it is a "particle"
                    vi += b.angular_velocity.cross(arm);
            }
            out += sign(i) * vi;
        }
        return out;
    }
    vec<T> point_velocity_before(std::size_t i) const
    {
        const auto &b = p_.bodies[i];
        const bool spin = b.infinite_mass || !b.particle;
        return b.velocity + (spin ? vec<T>(b.angular_velocity.cross(p_.point - b.position)) : vec<T>::Zero());
    }

    /// The contact frame: the unit normal n and the tangents t1, t2 (false when the normal is zero).
    bool contact_frame()
    {
        vec<T> nn = p_.normal;
        if (dim_ == 2)
            nn[2] = 0;
        const T len = nn.norm();
        if (!(len > 0) || !std::isfinite(len))
            return false;
        n = nn / len;
        if (dim_ == 2) {
            t1 = vec<T>(n.y(), -n.x(), 0);
            t2.setZero();
        } else {
            int axis = 0;
            n.cwiseAbs().minCoeff(&axis);
            vec<T> a = vec<T>::Unit(axis);
            t1 = (a - a.dot(n) * n).normalized();
            t2 = n.cross(t1);
        }
        return true;
    }

    /// Degrees of freedom and the block-diagonal inverse mass matrix (false when a mass is not positive).
    bool inverse_mass(std::size_t nb)
    {
        off_.assign(nb, -1);
        for (std::size_t i : {p_.body1, p_.body2}) {
            if (p_.immovable(i))
                continue;
            off_[i] = ndof_;
            ndof_ += dim_ + (p_.bodies[i].particle ? 0 : nw_);
        }
        Minv_ = MX::Zero(ndof_, ndof_);
        q_ = VX::Zero(ndof_);
        for (std::size_t i : {p_.body1, p_.body2}) {
            if (off_[i] < 0)
                continue;
            const auto &b = p_.bodies[i];
            if (!(b.mass > 0))
                return false;
            for (int k = 0; k < dim_; ++k) {
                Minv_(off_[i] + k, off_[i] + k) = T(1) / b.mass;
                q_[off_[i] + k] = b.velocity[k];
            }
            if (b.particle)
                continue;
            if (dim_ == 2) {
                if (!(b.inertia(2, 2) > 0))
                    return false;
                Minv_(off_[i] + 2, off_[i] + 2) = T(1) / b.inertia(2, 2);
                q_[off_[i] + 2] = b.angular_velocity[2];
            } else {
                Eigen::LDLT<M3> ldlt(b.inertia);
                if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.vectorD().minCoeff() > 0))
                    return false;
                const M3 Iinv = ldlt.solve(M3::Identity());
                for (int r = 0; r < 3; ++r) {
                    for (int k = 0; k < 3; ++k)
                        Minv_(off_[i] + 3 + r, off_[i] + 3 + k) = Iinv(r, k);
                    q_[off_[i] + 3 + r] = b.angular_velocity[r];
                }
            }
        }
        return true;
    }

    /// The pivot constraint rows Jp and their Schur complement (false when it is singular).
    bool pivot_rows(std::size_t nb)
    {
        // Pivot constraints of the movable bodies in contact: v + w x (E - C) = 0 after the impact.
        row_.assign(p_.pivots.size(), -1);
        for (std::size_t k = 0; k < p_.pivots.size(); ++k) {
            const std::size_t pb = p_.pivots[k].body;
            if (pb < nb && off_[pb] >= 0) {
                row_[k] = ncon_;
                ncon_ += dim_;
            }
        }
        Jp_ = MX::Zero(ncon_, ndof_);
        for (std::size_t k = 0; k < p_.pivots.size(); ++k) {
            if (row_[k] < 0)
                continue;
            const std::size_t i = p_.pivots[k].body;
            const vec<T> arm = p_.pivots[k].point - p_.bodies[i].position;
            for (int a = 0; a < dim_; ++a) {
                Jp_(row_[k] + a, off_[i] + a) = 1;
                const vec<T> g = arm.cross(vec<T>::Unit(a)); // (w x arm).e_a = w.(arm x e_a)
                if (dim_ == 2)
                    Jp_(row_[k] + a, off_[i] + 2) = g[2];
                else
                    for (int c3 = 0; c3 < 3; ++c3)
                        Jp_(row_[k] + a, off_[i] + 3 + c3) = g[c3];
            }
        }
        if (ncon_ > 0) {
            S_.compute(Jp_ * Minv_ * Jp_.transpose());
            if (!S_.isInvertible())
                return false;
        }
        return true;
    }

    /// The contact velocities before and at P = 0, the Delassus matrix W and the scales.
    bool contact_response()
    {
        // The contact velocities: before, at P = 0, and the Delassus matrix column by column.
        u_world = point_velocity_before(p_.body2) - point_velocity_before(p_.body1);
        u = frame(u_world);
        VX q1, r;
        respond(VX::Zero(ndof_), true, q1, r);
        c = frame(contact_velocity(q1, true));
        const vec<T> axes[3] = {n, t1, t2};
        for (int k = 0; k <= tangents; ++k) {
            respond(force(axes[k]), false, q1, r);
            W.col(k) = frame(contact_velocity(q1, false));
        }
        velocity_scale = std::max(u.norm(), c.norm());
        if (!(velocity_scale > 0))
            velocity_scale = std::numeric_limits<T>::min();
        compliance_scale = W.cwiseAbs().maxCoeff();
        if (!(compliance_scale > 0) || !W.allFinite() || !c.allFinite() || !u.allFinite())
            return false;
        impulse_scale = velocity_scale / compliance_scale;
        return true;
    }

    void assemble()
    {
        dim_ = p_.dimension == 2 ? 2 : 3;
        nw_ = dim_ == 2 ? 1 : 3;
        tangents = dim_ == 2 ? 1 : 2;
        e = p_.restitution;
        mu = p_.friction;
        const std::size_t nb = p_.bodies.size();
        if (p_.body1 >= nb || p_.body2 >= nb || p_.body1 == p_.body2)
            return;
        if (!contact_frame() || !inverse_mass(nb) || !pivot_rows(nb) || !contact_response())
            return;
        ok = true;
    }
};

} // namespace impactgen::numeric
