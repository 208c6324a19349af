// Internal to figure/: small 3-vector and 2-point arithmetic in doubles (figure.cpp,
// values.cpp), and the items and labels of a drawing started (figure.cpp, system.cpp).
#pragma once

#include "figure/figure.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace impactgen::figure::detail
{

struct v3 {
    double x = 0, y = 0, z = 0;
};
inline v3 operator+(v3 a, v3 b)
{
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline v3 operator-(v3 a, v3 b)
{
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline v3 operator*(double s, v3 a)
{
    return {s * a.x, s * a.y, s * a.z};
}
inline double dot(v3 a, v3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline v3 cross(v3 a, v3 b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double max_abs(v3 a)
{
    return std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)});
}

/// |a| without overflow or underflow in the squares.
inline double norm(v3 a)
{
    const double m = max_abs(a);
    if (!(m > 0) || !std::isfinite(m))
        return 0;
    const v3 s = (1 / m) * a;
    return m * std::sqrt(dot(s, s));
}

/// a / |a|, or the fallback when a is (numerically) zero.
inline v3 unit(v3 a, v3 fallback)
{
    const double l = norm(a);
    if (!(l > 0) || !std::isfinite(l))
        return fallback;
    const v3 u = (1 / l) * a;
    return std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z) ? u : fallback;
}

inline point operator+(point a, point b)
{
    return {a.x + b.x, a.y + b.y};
}
inline point operator-(point a, point b)
{
    return {a.x - b.x, a.y - b.y};
}
inline point operator*(double s, point a)
{
    return {s * a.x, s * a.y};
}
inline double length(point a)
{
    return std::hypot(a.x, a.y);
}
inline point unit2(point a, point fallback)
{
    const double l = length(a);
    return l > 1e-12 && std::isfinite(l) ? point{a.x / l, a.y / l} : fallback;
}
inline point perp(point a)
{
    return {-a.y, a.x};
}

/// A finite value or 0: nothing that is not finite reaches a printer.
inline double finite(double v)
{
    return std::isfinite(v) ? v : 0.0;
}

/// An item: its kind, role, body, key and points; the caller sets the rest.
inline item make_item(item::kind_t k, role what, int body, const std::string &key, std::vector<point> points)
{
    item it;
    it.kind = k;
    it.what = what;
    it.body = body;
    it.key = key;
    it.points = std::move(points);
    return it;
}

/// A label: where it sits, its role, body and key; the caller sets its text or name.
inline label make_label(point at, place side, role what, int body, const std::string &key)
{
    label l;
    l.at = at;
    l.side = side;
    l.what = what;
    l.body = body;
    l.key = key;
    return l;
}

} // namespace impactgen::figure::detail
