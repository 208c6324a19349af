// Converts a numeric symbolic::problem (every value a number) into floating point.
#pragma once

#include "numeric_problem.hpp"
#include "symbolic/problem.hpp"

#include <stdexcept>

namespace impactgen::numeric
{

template <typename T> T to_float(const GiNaC::ex &e)
{
    GiNaC::ex v = GiNaC::is_a<GiNaC::numeric>(e) ? e : e.evalf();
    if (!GiNaC::is_a<GiNaC::numeric>(v))
        throw std::invalid_argument("value is not a number");
    const GiNaC::numeric &x = GiNaC::ex_to<GiNaC::numeric>(v);
    if (x.is_rational()) // exact rationals: numerator and denominator separately
        return static_cast<T>(x.numer().to_double()) / static_cast<T>(x.denom().to_double());
    return static_cast<T>(x.to_double());
}

template <typename T> vec<T> to_float(const impactgen::vec3 &v)
{
    return vec<T>(to_float<T>(v[0]), to_float<T>(v[1]), to_float<T>(v[2]));
}

template <typename T> problem<T> from_problem(const impactgen::problem &p)
{
    problem<T> q;
    q.dimension = p.dimension;
    q.restitution = to_float<T>(p.restitution);
    for (const impactgen::body &b : p.bodies) {
        body<T> nb;
        nb.infinite_mass = b.infinite_mass;
        nb.particle = b.particle;
        nb.mass = b.infinite_mass ? T(0) : to_float<T>(b.mass);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                nb.inertia(r, c) = to_float<T>(b.inertia[r][c]);
        nb.position = to_float<T>(b.position);
        nb.velocity = to_float<T>(b.velocity);
        nb.angular_velocity = to_float<T>(b.angular_velocity);
        q.bodies.push_back(nb);
    }
    q.body1 = p.contact().body1;
    q.body2 = p.contact().body2;
    q.point = to_float<T>(p.contact().point);
    q.normal = to_float<T>(p.contact().normal);
    q.friction = to_float<T>(p.contact().friction());
    for (const impactgen::pivot &pv : p.pivots)
        q.pivots.push_back({pv.body, to_float<T>(pv.point)});
    return q;
}

} // namespace impactgen::numeric
