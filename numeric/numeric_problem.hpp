// A problem in floating point, for the Eigen reference solvers and the
// benchmarks. Same conventions as symbolic/problem.hpp: planar problems use
// z = 0 for points and velocities and only z for angular quantities.
#pragma once

#include <Eigen/Dense>

#include <vector>

namespace impactgen::numeric
{

template <typename T> using vec = Eigen::Matrix<T, 3, 1>;
template <typename T> using mat = Eigen::Matrix<T, 3, 3>;

template <typename T> struct body {
    bool infinite_mass = false;
    bool particle = true;
    T mass = 1;
    mat<T> inertia = mat<T>::Zero();
    vec<T> position = vec<T>::Zero(), velocity = vec<T>::Zero(), angular_velocity = vec<T>::Zero();
};

template <typename T> struct pivot {
    std::size_t body = 0;
    vec<T> point = vec<T>::Zero();
};

template <typename T> struct problem {
    int dimension = 3;
    T restitution = 0;
    std::vector<body<T>> bodies;
    std::size_t body1 = 0, body2 = 1;
    vec<T> point = vec<T>::Zero();
    vec<T> normal = vec<T>::UnitY();
    T friction = 0; ///< Coulomb's mu at the contact (0: smooth)
    std::vector<pivot<T>> pivots;

    const pivot<T> *pivot_of(std::size_t b) const
    {
        for (const auto &p : pivots)
            if (p.body == b)
                return &p;
        return nullptr;
    }
    bool immovable(std::size_t b) const { return bodies[b].infinite_mass || (bodies[b].particle && pivot_of(b)); }
};

template <typename T> struct answer {
    bool ok = false; ///< false when the system is singular
    std::vector<vec<T>> velocity, angular_velocity;
    T normal_impulse = 0;
    std::vector<vec<T>> pivot_impulses;
};

} // namespace impactgen::numeric
