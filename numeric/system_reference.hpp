// A numeric reference for systems (format version 3), written independently of the closed
// form (symbolic/system.cpp): doubles and Eigen, six velocity unknowns per body (the angular
// block of a particle is left out by a zero inverse inertia), and for each active set of the
// contacts the whole constrained impulse-momentum system -- joints, pivots and the acting
// contacts' rows together -- solved by a full-pivot LU, the law's inequalities checked to a
// tolerance. Smooth and perfectly rough contacts, and in 2-D Coulomb friction mu per contact
// (regimes open, stick inside the cone, slide either way with F = -s mu P t and the slip along s t).
#pragma once

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace impactgen::numeric::systems
{

using vec3 = Eigen::Vector3d;
using mat3 = Eigen::Matrix3d;
constexpr std::size_t fixed_frame = std::numeric_limits<std::size_t>::max();

struct sys_body {
    bool infinite_mass = false, particle = true;
    double mass = 1;
    mat3 inertia = mat3::Zero();
    vec3 position = vec3::Zero(), velocity = vec3::Zero(), angular_velocity = vec3::Zero();
};
/// A joint, or a pivot when body1 is fixed_frame.
struct sys_link {
    std::size_t body1 = fixed_frame, body2 = 0;
    vec3 point = vec3::Zero();
};
struct sys_contact {
    std::size_t body1 = 0, body2 = 1;
    vec3 point = vec3::Zero(), normal = vec3::UnitY();
    double restitution = 0;
    bool rough = false;
    double mu = 0; ///< Coulomb's coefficient (2-D only; 0: smooth unless rough)
};
struct sys_problem {
    int dimension = 2;
    std::vector<sys_body> bodies;
    std::vector<sys_link> links;
    std::vector<sys_contact> contacts;
};
struct sys_answer {
    int holding = 0;  ///< active sets for which the law holds (0: none)
    int singular = 0; ///< active sets whose system is singular (solved in the least-norm sense)
    std::vector<vec3> velocity, angular_velocity;
    std::vector<double> normal_impulse; ///< along the unit normal
};

namespace detail
{
// The row of the velocity of body b's point q along a (6 entries per body).
inline void add_point(const sys_problem &p, Eigen::RowVectorXd &row, double &constant, std::size_t b, const vec3 &q,
                      const vec3 &a, double s)
{
    if (b == fixed_frame)
        return;
    const sys_body &B = p.bodies[b];
    const vec3 r = q - B.position;
    if (B.infinite_mass) {
        constant += s * a.dot(B.velocity + B.angular_velocity.cross(r));
        return;
    }
    row.segment<3>(6 * static_cast<Eigen::Index>(b)) += s * a.transpose();
    if (!B.particle)
        row.segment<3>(6 * static_cast<Eigen::Index>(b) + 3) += s * r.cross(a).transpose();
}
} // namespace detail

namespace sys_answer_detail
{
// One set of regimes: the acting rows' velocity conditions (links always; a contact's normal row
// while it acts, its tangent rows while it sticks), the impulse directions (a sliding contact's
// normal impulse carries -s mu along t), solved, then the law's inequalities checked to `tol`.
inline void try_set(const sys_problem &p, const std::vector<Eigen::RowVectorXd> &rows,
                    const std::vector<double> &constants, const std::vector<int> &owner,
                    const std::vector<bool> &normal, const std::vector<double> &w0, const Eigen::VectorXd &v,
                    const Eigen::MatrixXd &Minv, const std::vector<int> &regime, double tol, sys_answer &best)
{
    const std::size_t R = rows.size(), nc = p.contacts.size();
    const Eigen::Index n = v.size();
    auto tangent_of = [&](std::size_t i) { // the first tangent row of contact i
        for (std::size_t r = 0; r < R; ++r)
            if (owner[r] == static_cast<int>(i) && !normal[r])
                return r;
        return R;
    };
    std::vector<std::size_t> act;
    for (std::size_t r = 0; r < R; ++r) {
        if (owner[r] < 0) {
            act.push_back(r);
            continue;
        }
        const int g = regime[static_cast<std::size_t>(owner[r])];
        if (g != 0 && (normal[r] || g == 1))
            act.push_back(r);
    }
    const Eigen::Index m = static_cast<Eigen::Index>(act.size());
    Eigen::MatrixXd A(m, n), B(m, n);
    Eigen::VectorXd rhs(m);
    for (Eigen::Index k = 0; k < m; ++k) {
        const std::size_t r = act[static_cast<std::size_t>(k)];
        A.row(k) = rows[r];
        B.row(k) = rows[r];
        const double e = owner[r] >= 0 ? p.contacts[static_cast<std::size_t>(owner[r])].restitution : 0;
        rhs(k) = (normal[r] ? -e * w0[r] : 0) - w0[r];
        if (owner[r] >= 0 && normal[r]) {
            const std::size_t i = static_cast<std::size_t>(owner[r]);
            const int g = regime[i];
            if (g >= 2)
                B.row(k) -= (g == 2 ? 1.0 : -1.0) * p.contacts[i].mu * rows[tangent_of(i)];
        }
    }
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m);
    if (m > 0) {
        const Eigen::MatrixXd H = A * Minv * B.transpose();
        Eigen::FullPivLU<Eigen::MatrixXd> lu(H);
        lu.setThreshold(1e-12);
        if (lu.isInvertible()) {
            lambda = lu.solve(rhs);
        } else { // redundant rows: the least-norm impulses, if the velocities can be met at all
            ++best.singular;
            lambda = H.completeOrthogonalDecomposition().solve(rhs);
            if ((H * lambda - rhs).norm() > 1e-9 * (1 + rhs.norm()))
                return;
        }
    }
    const Eigen::VectorXd v2 = v + Minv * B.transpose() * lambda;
    bool ok = true;
    std::vector<double> P(nc, 0.0), F(nc, 0.0);
    for (Eigen::Index k = 0; k < m; ++k) {
        const std::size_t r = act[static_cast<std::size_t>(k)];
        if (owner[r] < 0)
            continue;
        const std::size_t i = static_cast<std::size_t>(owner[r]);
        if (normal[r]) {
            P[i] = lambda(k);
            ok = ok && lambda(k) >= -tol;
        } else if (F[i] == 0.0) {
            F[i] = lambda(k);
        }
    }
    for (std::size_t i = 0; i < nc && ok; ++i) {
        const sys_contact &c = p.contacts[i];
        const int g = regime[i];
        if (g == 1 && !c.rough && c.mu > 0 && p.dimension == 2)
            ok = c.mu * P[i] - std::abs(F[i]) >= -tol; // inside the cone
        if (g >= 2) {
            const std::size_t t = tangent_of(i);
            const double slip = rows[t].dot(v2) + constants[t];
            ok = (g == 2 ? slip : -slip) >= -tol; // slides the way its friction opposes
        }
    }
    for (std::size_t r = 0; r < R && ok; ++r)
        if (normal[r] && regime[static_cast<std::size_t>(owner[r])] == 0) {
            const double e = p.contacts[static_cast<std::size_t>(owner[r])].restitution;
            ok = rows[r].dot(v2) + constants[r] + e * w0[r] >= -tol;
        }
    if (!ok || ++best.holding > 1)
        return;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        best.velocity.push_back(v2.segment<3>(6 * static_cast<Eigen::Index>(b)));
        best.angular_velocity.push_back(v2.segment<3>(6 * static_cast<Eigen::Index>(b) + 3));
    }
    best.normal_impulse = P;
}
} // namespace sys_answer_detail

inline sys_answer solve_reference(const sys_problem &p, double tol = 1e-9)
{
    const Eigen::Index n = 6 * static_cast<Eigen::Index>(p.bodies.size());
    Eigen::MatrixXd Minv = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd v(n);
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const sys_body &B = p.bodies[b];
        const Eigen::Index o = 6 * static_cast<Eigen::Index>(b);
        v.segment<3>(o) = B.velocity;
        v.segment<3>(o + 3) = B.angular_velocity;
        if (B.infinite_mass)
            continue;
        Minv.block<3, 3>(o, o) = mat3::Identity() / B.mass;
        if (!B.particle)
            Minv.block<3, 3>(o + 3, o + 3) =
                p.dimension == 2 ? mat3(vec3(0, 0, 1 / B.inertia(2, 2)).asDiagonal()) : mat3(B.inertia.inverse());
    }
    // Rows: links (always), then per contact its normal and tangents.
    std::vector<Eigen::RowVectorXd> rows;
    std::vector<double> constants;
    std::vector<int> owner; // -1 link, else contact index
    std::vector<bool> normal;
    auto add_row = [&](std::size_t b1, std::size_t b2, const vec3 &q, const vec3 &a, int who, bool is_normal) {
        Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
        double c = 0;
        detail::add_point(p, r, c, b2, q, a, 1);
        detail::add_point(p, r, c, b1, q, a, -1);
        rows.push_back(r);
        constants.push_back(c);
        owner.push_back(who);
        normal.push_back(is_normal);
    };
    for (const sys_link &l : p.links)
        for (int k = 0; k < p.dimension; ++k)
            add_row(l.body1, l.body2, l.point, vec3::Unit(k), -1, false);
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const sys_contact &c = p.contacts[i];
        const vec3 nh = c.normal.normalized();
        add_row(c.body1, c.body2, c.point, nh, static_cast<int>(i), true);
        if (!c.rough && !(p.dimension == 2 && c.mu > 0))
            continue;
        if (p.dimension == 2) {
            add_row(c.body1, c.body2, c.point, vec3(-nh.y(), nh.x(), 0), static_cast<int>(i), false);
        } else {
            vec3 t1 = nh.unitOrthogonal();
            add_row(c.body1, c.body2, c.point, t1, static_cast<int>(i), false);
            add_row(c.body1, c.body2, c.point, nh.cross(t1), static_cast<int>(i), false);
        }
    }
    const std::size_t R = rows.size(), nc = p.contacts.size();
    std::vector<double> w0(R);
    for (std::size_t r = 0; r < R; ++r)
        w0[r] = rows[r].dot(v) + constants[r];
    sys_answer best;
    // Regimes per contact: 0 open, 1 acts (smooth; rough or Coulomb: sticks), 2 / 3 slides along +t / -t.
    std::vector<int> regimes_of(nc, 2);
    for (std::size_t i = 0; i < nc; ++i)
        if (p.dimension == 2 && !p.contacts[i].rough && p.contacts[i].mu > 0)
            regimes_of[i] = 4;
    std::vector<int> regime(nc, 0);
    for (bool more = true; more;) {
        sys_answer_detail::try_set(p, rows, constants, owner, normal, w0, v, Minv, regime, tol, best);
        more = false;
        for (std::size_t i = 0; i < nc && !more; ++i) {
            if (++regime[i] < regimes_of[i])
                more = true;
            else
                regime[i] = 0;
        }
    }
    return best;
}

} // namespace impactgen::numeric::systems
