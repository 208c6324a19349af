// A numeric reference for Routh's process at the one contact of a system (joints, pivots, any
// number of bodies; planar), independent of symbolic/system.cpp and symbolic/routh.hpp:
//   1. the contact's 2x2 response W in (n, t) (unit normal, t = (-n_y, n_x)) from the whole
//      constrained impulse-momentum system: for a unit impulse along n and along t at the
//      contact, the bilateral rows (joints, pivots: their relative velocity unchanged) solved
//      for their impulses by a least-squares solve of A_J M^-1 A_J^T (doubles, Eigen), the
//      contact's velocity change read off -- no Schur complement in closed form;
//   2. the process integrated in small normal-impulse steps (process_integrator.hpp);
//   3. the bodies after impact from the same constrained system with the impulse found.
#pragma once

#include "process_integrator.hpp"
#include "system_reference.hpp"

namespace impactgen::numeric::systems
{

struct sys_process_answer {
    process_result<double> process; ///< impulses along the unit n and t
    std::vector<vec3> velocity, angular_velocity;
    double energy_before = 0, energy_after = 0;
};

namespace detail
{
// The system's rows and its inverse mass matrix (6 unknowns per body), for one contact.
struct sys_rows {
    Eigen::MatrixXd Minv, AJ; ///< AJ: the bilateral rows
    Eigen::VectorXd v;        ///< generalized velocities before impact
    Eigen::RowVectorXd an, at;
    double cn = 0, ct = 0; ///< the contact rows' constants (bodies of infinite mass)
};

inline sys_rows rows_of(const sys_problem &p)
{
    const Eigen::Index n = 6 * static_cast<Eigen::Index>(p.bodies.size());
    sys_rows s;
    s.Minv = Eigen::MatrixXd::Zero(n, n);
    s.v.resize(n);
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const sys_body &B = p.bodies[b];
        const Eigen::Index o = 6 * static_cast<Eigen::Index>(b);
        s.v.segment<3>(o) = B.velocity;
        s.v.segment<3>(o + 3) = B.angular_velocity;
        if (B.infinite_mass)
            continue;
        s.Minv.block<3, 3>(o, o) = mat3::Identity() / B.mass;
        if (!B.particle)
            s.Minv(o + 5, o + 5) = 1 / B.inertia(2, 2);
    }
    s.AJ = Eigen::MatrixXd::Zero(2 * static_cast<Eigen::Index>(p.links.size()), n);
    for (std::size_t k = 0; k < p.links.size(); ++k)
        for (int d = 0; d < 2; ++d) {
            Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
            double unused = 0;
            add_point(p, r, unused, p.links[k].body2, p.links[k].point, vec3::Unit(d), 1);
            add_point(p, r, unused, p.links[k].body1, p.links[k].point, vec3::Unit(d), -1);
            s.AJ.row(2 * static_cast<Eigen::Index>(k) + d) = r;
        }
    const sys_contact &c = p.contacts.at(0);
    const vec3 nh = c.normal.normalized(), th(-nh.y(), nh.x(), 0);
    s.an = s.at = Eigen::RowVectorXd::Zero(n);
    add_point(p, s.an, s.cn, c.body2, c.point, nh, 1);
    add_point(p, s.an, s.cn, c.body1, c.point, nh, -1);
    add_point(p, s.at, s.ct, c.body2, c.point, th, 1);
    add_point(p, s.at, s.ct, c.body1, c.point, th, -1);
    return s;
}

// The change of the generalized velocities for the contact impulse Pn n + Pt t on body 2 (and
// its opposite on body 1), the bilateral rows keeping their relative velocities.
inline Eigen::VectorXd response(const sys_rows &s, double Pn, double Pt)
{
    const Eigen::VectorXd f = s.an.transpose() * Pn + s.at.transpose() * Pt;
    if (s.AJ.rows() == 0)
        return s.Minv * f;
    const Eigen::MatrixXd H = s.AJ * s.Minv * s.AJ.transpose();
    const Eigen::VectorXd lambda = H.completeOrthogonalDecomposition().solve(-s.AJ * s.Minv * f);
    return s.Minv * (f + s.AJ.transpose() * lambda);
}

inline double kinetic(const sys_problem &p, const Eigen::VectorXd &v)
{
    double T = 0;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const sys_body &B = p.bodies[b];
        if (B.infinite_mass)
            continue;
        const Eigen::Index o = 6 * static_cast<Eigen::Index>(b);
        T += B.mass * v.segment<3>(o).squaredNorm() / 2;
        if (!B.particle)
            T += B.inertia(2, 2) * v(o + 5) * v(o + 5) / 2;
    }
    return T;
}
} // namespace detail

/// The process at p's one contact (contacts[0]) with friction mu under `law`, its restitution
/// the contact's: process.ok false when the contact does not approach or wedges.
inline sys_process_answer integrate_system_process(const sys_problem &p, double mu, process_law law, int steps = 4000)
{
    sys_process_answer a;
    const detail::sys_rows s = detail::rows_of(p);
    const Eigen::VectorXd dn = detail::response(s, 1, 0), dt = detail::response(s, 0, 1);
    Eigen::Matrix2d W;
    W << s.an.dot(dn), s.an.dot(dt), s.at.dot(dn), s.at.dot(dt);
    const Eigen::Vector2d c(s.an.dot(s.v) + s.cn, s.at.dot(s.v) + s.ct);
    if (!(c(0) < 0))
        return a;
    a.process = integrate_process<double>(W, c, mu, p.contacts[0].restitution, law, steps);
    if (!a.process.ok)
        return a;
    const Eigen::VectorXd v2 = s.v + detail::response(s, a.process.normal_impulse, a.process.tangential);
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const Eigen::Index o = 6 * static_cast<Eigen::Index>(b);
        const bool moves = !p.bodies[b].infinite_mass;
        a.velocity.push_back(moves ? vec3(v2.segment<3>(o)) : p.bodies[b].velocity);
        a.angular_velocity.push_back(moves ? vec3(v2.segment<3>(o + 3)) : p.bodies[b].angular_velocity);
    }
    a.energy_before = detail::kinetic(p, s.v);
    a.energy_after = detail::kinetic(p, v2);
    return a;
}

} // namespace impactgen::numeric::systems
