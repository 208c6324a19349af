// An independent formulation, to catch errors in the derivation itself:
// generalized velocities u = (v_C, w) per movable body, mass matrix
// M = diag(m 1, I_C), constraint Jacobians J (contact normal, pivots), and the
// KKT system
//     [ M  -J^T ] [ u'     ]   [ M u ]
//     [ J   0   ] [ lambda ] = [ c   ],   c = -e J_c u (contact), 0 (pivot)
// lambda = (N, R_1, ...). Solved with Eigen's FullPivLU.
#pragma once

#include "numeric_problem.hpp"

namespace impactgen::numeric
{

/// The KKT system of the generalized formulation, with its unknowns' layout and its assembly.
template <typename T> struct kkt_system {
    using M = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
    using V = Eigen::Matrix<T, Eigen::Dynamic, 1>;
    const problem<T> &p;
    const int dim;
    const int nw;
    const vec<T> &n;
    const std::size_t ids[2];
    std::vector<int> off;
    int ndof = 0;
    std::vector<int> pivot_row;
    int ncon = 1;
    M K;
    V rhs;
    V u;
    M J;
    V c;

    kkt_system(const problem<T> &p_, const vec<T> &n_)
        : p(p_), dim(p_.dimension), nw(dim == 2 ? 1 : 3), n(n_), ids{p_.body1, p_.body2}, off(p_.bodies.size(), -1),
          pivot_row(p_.pivots.size(), -1)
    {
        count_unknowns();
        K = M::Zero(ndof + ncon, ndof + ncon);
        rhs = V::Zero(ndof + ncon);
        u = V::Zero(ndof);
        J = M::Zero(ncon, ndof);
        c = V::Zero(ncon);
    }

    /// The degrees of freedom and the constraint rows.
    void count_unknowns()
    {
        // Degrees of freedom: bodies of finite mass in contact (a pinned particle
        // keeps its translational freedom; the pivot row then holds it).
        for (std::size_t i : ids) {
            if (p.bodies[i].infinite_mass)
                continue;
            off[i] = ndof;
            ndof += dim + (p.bodies[i].particle ? 0 : nw);
        }
        // Constraint rows: the contact, then each pivot of a body in contact (a
        // bystander's pivot takes no impulse).
        for (std::size_t k = 0; k < p.pivots.size(); ++k)
            if (off[p.pivots[k].body] >= 0) {
                pivot_row[k] = ncon;
                ncon += dim;
            }
    }

    // Jacobian row of the velocity of point q along a, for body i: v.a + (w x (q - C)).a
    void point_row(int r, std::size_t i, const vec<T> &q, const vec<T> &a, T s)
    {
        const auto &b = p.bodies[i];
        for (int k = 0; k < dim; ++k)
            J(r, off[i] + k) += s * a[k];
        if (!b.particle) {
            vec<T> g = (q - b.position).cross(a);
            for (int k = 0; k < nw; ++k)
                J(r, off[i] + dim + k) += s * g[dim == 2 ? 2 : k];
        }
    }

    /// The mass matrix M = diag(m 1, I_C) and the velocities u before impact.
    void mass_block()
    {
        for (std::size_t i : ids) {
            const auto &b = p.bodies[i];
            if (off[i] < 0)
                continue;
            for (int k = 0; k < dim; ++k) {
                K(off[i] + k, off[i] + k) = b.mass;
                u[off[i] + k] = b.velocity[k];
            }
            if (!b.particle) {
                if (dim == 2) {
                    K(off[i] + 2, off[i] + 2) = b.inertia(2, 2);
                    u[off[i] + 2] = b.angular_velocity[2];
                } else {
                    K.block(off[i] + 3, off[i] + 3, 3, 3) = b.inertia;
                    u.segment(off[i] + 3, 3) = b.angular_velocity;
                }
            }
        }
    }

    /// The constraint rows J and their right-hand sides c: the contact, then the pivots.
    void constraint_rows()
    {
        // Contact row: (v_B - v_A).n; a body without DOFs contributes a known velocity.
        T known = 0;
        for (std::size_t i : ids) {
            const auto &b = p.bodies[i];
            const T s = i == p.body1 ? T(-1) : T(1);
            vec<T> q = p.point - b.position;
            if (off[i] >= 0) {
                point_row(0, i, p.point, n, s);
            } else {
                known += s * (b.velocity + b.angular_velocity.cross(q)).dot(n);
            }
        }
        T approach = (J.row(0) * u)(0) + known;
        c[0] = -p.restitution * approach - known;
        for (std::size_t k = 0; k < p.pivots.size(); ++k) {
            const auto &pv = p.pivots[k];
            if (pivot_row[k] < 0)
                continue;
            for (int a = 0; a < dim; ++a) {
                int r = pivot_row[k] + a;
                point_row(r, pv.body, pv.point, vec<T>::Unit(a), 1);
                c[r] = 0;
            }
        }
    }

    /// The KKT matrix and right-hand side from M, J, u and c.
    void close()
    {
        K.topRightCorner(ndof, ncon) = -J.transpose();
        K.bottomLeftCorner(ncon, ndof) = J;
        rhs.head(ndof) = K.topLeftCorner(ndof, ndof) * u;
        rhs.tail(ncon) = c;
    }

    /// The velocities after impact and the impulses, read from the solution x.
    void read_answer(answer<T> &out, const V &x) const
    {
        out.ok = true;
        for (std::size_t i = 0; i < p.bodies.size(); ++i) {
            vec<T> v = p.bodies[i].velocity, w = p.bodies[i].angular_velocity;
            if (off[i] >= 0) {
                for (int k = 0; k < dim; ++k)
                    v[k] = x[off[i] + k];
                if (!p.bodies[i].particle) {
                    if (dim == 2)
                        w[2] = x[off[i] + 2];
                    else
                        w = x.segment(off[i] + 3, 3);
                }
            }
            out.velocity.push_back(v);
            out.angular_velocity.push_back(w);
        }
        out.normal_impulse = x[ndof];
        for (std::size_t k = 0; k < p.pivots.size(); ++k) {
            vec<T> R = vec<T>::Zero();
            for (int a = 0; a < dim && pivot_row[k] >= 0; ++a)
                R[a] = x[ndof + pivot_row[k] + a];
            out.pivot_impulses.push_back(R);
        }
    }
};

template <typename T> answer<T> solve_generalized(const problem<T> &p)
{
    using M = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
    using V = Eigen::Matrix<T, Eigen::Dynamic, 1>;
    const vec<T> n = p.normal / p.normal.norm();
    kkt_system<T> S(p, n);
    S.mass_block();
    S.constraint_rows();
    S.close();

    answer<T> out;
    Eigen::FullPivLU<M> lu(S.K);
    if (!lu.isInvertible())
        return out;
    V x = lu.solve(S.rhs);
    if (!x.allFinite())
        return out;
    S.read_answer(out, x);
    return out;
}

} // namespace impactgen::numeric
