// Eigen solve of the same linear system the derivation writes
// (symbolic/derivation.hpp): the same unknowns in the same order and the same
// equations -- smooth contact, system momentum along n, angular momentum about
// O for free bodies; impulse-momentum with N and pivot impulses R as unknowns
// when a pivot is present; Newton's restitution. Assembled directly in T.
#pragma once

#include "numeric_problem.hpp"

#include <cmath>

namespace impactgen::numeric
{

template <typename T> struct system_layout {
    // Column of the first velocity / angular velocity unknown of each body, or -1.
    std::vector<int> v_col, w_col;
    int n_col = -1;
    std::vector<int> r_col;
    int size = 0;
};

template <typename T> inline vec<T> unit(const vec<T> &n)
{
    return n / n.norm();
}

/// Tangent directions of the derivation's contact frame (not necessarily unit).
template <typename T> void tangents(const problem<T> &p, const vec<T> &n, vec<T> &t, vec<T> &b)
{
    if (p.dimension == 2) {
        t = vec<T>(n.y(), -n.x(), 0);
        b.setZero();
        return;
    }
    int zeros = 0, axis = 0;
    for (int i = 0; i < 3; ++i)
        if (n[i] == 0)
            ++zeros;
        else
            axis = i;
    vec<T> a = vec<T>::Zero();
    if (zeros == 2) {
        a[(axis + 2) % 3] = 1;
        t = a;
    } else {
        int pick = -1;
        for (int i = 0; i < 3 && pick < 0; ++i)
            if (n[i] == 0)
                pick = i;
        if (pick < 0)
            n.cwiseAbs().minCoeff(&pick);
        a[pick] = 1;
        t = a - a.dot(n) * n;
    }
    b = t.cross(n);
}

/// Columns of the unknowns: each movable body's velocity (and angular velocity), then N and
/// the pivot impulses when a pivot is present.
template <typename T> system_layout<T> layout_of(const problem<T> &p)
{
    const int dim = p.dimension;
    const std::size_t ids[2] = {p.body1, p.body2};
    const bool impulse_form = !p.pivots.empty();
    system_layout<T> L;
    L.v_col.assign(p.bodies.size(), -1);
    L.w_col.assign(p.bodies.size(), -1);
    for (std::size_t i : ids) {
        if (p.immovable(i))
            continue;
        L.v_col[i] = L.size;
        L.size += dim;
        if (!p.bodies[i].particle) {
            L.w_col[i] = L.size;
            L.size += dim == 2 ? 1 : 3;
        }
    }
    if (impulse_form) {
        L.n_col = L.size++;
        for (std::size_t k = 0; k < p.pivots.size(); ++k) {
            bool in_contact = p.pivots[k].body == p.body1 || p.pivots[k].body == p.body2;
            L.r_col.push_back(in_contact ? L.size : -1); // a bystander's pivot takes no impulse
            if (in_contact)
                L.size += dim;
        }
    }
    return L;
}

/// The linear system A x = rhs being filled row by row, with its coefficient helpers.
template <typename T> struct momentum_rows {
    using M = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
    using V = Eigen::Matrix<T, Eigen::Dynamic, 1>;
    const problem<T> &p;
    const system_layout<T> &L;
    const vec<T> &n;
    const int dim;
    const std::size_t ids[2];
    const int first_ang;
    const int last_lin;
    M A;
    V rhs;
    int row = 0;

    momentum_rows(const problem<T> &p_, const system_layout<T> &L_, const vec<T> &n_)
        : p(p_), L(L_), n(n_), dim(p_.dimension), ids{p_.body1, p_.body2}, first_ang(dim == 2 ? 2 : 0), last_lin(dim),
          A(M::Zero(L_.size, L_.size)), rhs(V::Zero(L_.size))
    {
    }

    // Angular columns: world component c maps to column offset (planar: only z).
    int wcol(std::size_t i, int c) const { return dim == 2 ? (c == 2 ? L.w_col[i] : -1) : L.w_col[i] + c; }
    void put(int r, int c, T v)
    {
        if (c >= 0)
            A(r, c) += v;
    }
    // Coefficients of v'_i . a and of (w'_i x q) . a in row r.
    void velocity_dot(int r, std::size_t i, const vec<T> &a, T scale)
    {
        for (int c = 0; c < dim; ++c)
            put(r, L.v_col[i] + c, scale * a[c]);
    }
    void angular_dot(int r, std::size_t i, const vec<T> &q, const vec<T> &a, T scale)
    {
        vec<T> coef = q.cross(a); // (w x q).a = w.(q x a)
        for (int c = 0; c < 3; ++c)
            put(r, wcol(i, c), scale * coef[c]);
    }

    /// Rows without a pivot: smooth contact along the tangents, system momentum along n, angular
    /// momentum about O.
    void smooth_rows()
    {
        vec<T> t, b;
        tangents<T>(p, n, t, b);
        for (std::size_t i : ids) {
            if (p.immovable(i))
                continue;
            velocity_dot(row, i, t, 1);
            rhs[row++] = p.bodies[i].velocity.dot(t);
            if (dim == 3) {
                velocity_dot(row, i, b, 1);
                rhs[row++] = p.bodies[i].velocity.dot(b);
            }
        }
        if (!p.bodies[p.body1].infinite_mass && !p.bodies[p.body2].infinite_mass) {
            for (std::size_t i : ids) {
                velocity_dot(row, i, n, p.bodies[i].mass);
                rhs[row] += p.bodies[i].mass * p.bodies[i].velocity.dot(n);
            }
            ++row;
        }
        for (std::size_t i : ids) {
            const auto &bd = p.bodies[i];
            if (p.immovable(i) || bd.particle)
                continue;
            vec<T> r = bd.position - p.point;
            vec<T> H = bd.inertia * bd.angular_velocity + r.cross(bd.mass * bd.velocity);
            for (int c = first_ang; c < 3; ++c) {
                for (int k = 0; k < 3; ++k)
                    put(row, wcol(i, k), bd.inertia(c, k));
                // (r x m v')_c = m * (e_c . (r x v')) = m * v' . (e_c x r)
                vec<T> ec = vec<T>::Unit(c);
                velocity_dot(row, i, ec.cross(r), bd.mass);
                rhs[row++] = H[c];
            }
        }
    }

    /// Rows with a pivot: impulse-momentum with N and the pivot impulses R, and each pivot fixed.
    void impulse_rows()
    {
        for (std::size_t i : ids) {
            const auto &bd = p.bodies[i];
            if (bd.infinite_mass)
                continue;
            const T s = i == p.body1 ? T(-1) : T(1);
            const pivot<T> *pv = p.pivot_of(i);
            int rk = pv ? L.r_col[static_cast<std::size_t>(pv - p.pivots.data())] : -1;
            bool movable = !p.immovable(i);
            for (int c = 0; c < last_lin; ++c) {
                if (movable)
                    put(row, L.v_col[i] + c, bd.mass);
                rhs[row] = movable ? bd.mass * bd.velocity[c] : T(0);
                put(row, L.n_col, -s * n[c]);
                if (rk >= 0)
                    put(row, rk + c, -1);
                ++row;
            }
            if (!bd.particle) {
                vec<T> ref = pv ? pv->point : p.point;
                vec<T> r = bd.position - ref;
                vec<T> H = bd.inertia * bd.angular_velocity + r.cross(bd.mass * bd.velocity);
                vec<T> arm = p.point - ref; // moment of s N n about ref: arm x (s N n)
                vec<T> mom = arm.cross(n);
                for (int c = first_ang; c < 3; ++c) {
                    for (int k = 0; k < 3; ++k)
                        put(row, wcol(i, k), bd.inertia(c, k));
                    vec<T> ec = vec<T>::Unit(c);
                    velocity_dot(row, i, ec.cross(r), bd.mass);
                    put(row, L.n_col, pv ? -s * mom[c] : T(0));
                    rhs[row++] = H[c];
                }
                if (pv) {
                    vec<T> q = pv->point - bd.position;
                    for (int c = 0; c < last_lin; ++c) {
                        put(row, L.v_col[i] + c, 1);
                        angular_dot(row, i, q, vec<T>::Unit(c), 1);
                        rhs[row++] = 0;
                    }
                }
            }
        }
    }

    /// Restitution: (v'_B - v'_A).n = -e (v_B - v_A).n; known parts to the right.
    void restitution_row()
    {
        T known_before = 0, known_after = 0;
        for (std::size_t i : ids) {
            const auto &bd = p.bodies[i];
            const T s = i == p.body1 ? T(-1) : T(1);
            vec<T> q = p.point - bd.position;
            // A particle is a point: its spin does not move its contact point.
            const vec<T> spin =
                bd.particle && !bd.infinite_mass ? vec<T>::Zero() : vec<T>(bd.angular_velocity.cross(q));
            known_before += s * (bd.velocity + spin).dot(n);
            if (p.immovable(i)) {
                known_after += s * (bd.velocity + spin).dot(n);
                continue;
            }
            velocity_dot(row, i, n, s);
            if (!bd.particle)
                angular_dot(row, i, q, n, s);
        }
        rhs[row++] = -p.restitution * known_before - known_after;
    }

    /// The velocities after impact and the impulses, read from the solution x.
    void read_answer(answer<T> &out, const V &x, bool impulse_form) const
    {
        out.ok = true;
        for (std::size_t i = 0; i < p.bodies.size(); ++i) {
            vec<T> v = p.bodies[i].velocity, w = p.bodies[i].angular_velocity;
            if (L.v_col[i] >= 0)
                for (int c = 0; c < dim; ++c)
                    v[c] = x[L.v_col[i] + c];
            if (L.w_col[i] >= 0)
                for (int c = first_ang; c < 3; ++c)
                    w[c] = x[wcol(i, c)];
            out.velocity.push_back(v);
            out.angular_velocity.push_back(w);
        }
        if (impulse_form) {
            out.normal_impulse = x[L.n_col];
            for (int rk : L.r_col) {
                vec<T> R = vec<T>::Zero();
                for (int c = 0; c < dim && rk >= 0; ++c)
                    R[c] = x[rk + c];
                out.pivot_impulses.push_back(R);
            }
        } else {
            // N from the change of momentum of a body of finite mass along n.
            std::size_t i = p.bodies[p.body2].infinite_mass ? p.body1 : p.body2;
            const T s = i == p.body1 ? T(-1) : T(1);
            out.normal_impulse = s * p.bodies[i].mass * (out.velocity[i] - p.bodies[i].velocity).dot(n);
        }
    }
};

template <typename T> answer<T> solve_momentum_system(const problem<T> &p)
{
    using M = typename momentum_rows<T>::M;
    using V = typename momentum_rows<T>::V;
    const bool impulse_form = !p.pivots.empty();
    const vec<T> n = unit<T>(p.normal);
    const system_layout<T> L = layout_of<T>(p);
    momentum_rows<T> S(p, L, n);
    if (!impulse_form)
        S.smooth_rows();
    else
        S.impulse_rows();
    S.restitution_row();
    answer<T> out;
    if (S.row != L.size)
        return out;
    Eigen::PartialPivLU<M> lu(S.A);
    V x = lu.solve(S.rhs);
    if (!x.allFinite())
        return out;
    S.read_answer(out, x, impulse_form);
    return out;
}

} // namespace impactgen::numeric
