// Three-component vectors and 3x3 matrices of GiNaC expressions. Planar
// problems use the same types with z = 0 for points and velocities and only
// the z component for angular quantities.
#pragma once

#include <ginac/ginac.h>

#include <array>

namespace impactgen
{

using GiNaC::ex;
using vec3 = std::array<ex, 3>;
using mat3 = std::array<std::array<ex, 3>, 3>;

inline vec3 zero_vec()
{
    return {ex(0), ex(0), ex(0)};
}
inline mat3 zero_mat()
{
    return {zero_vec(), zero_vec(), zero_vec()};
}

inline vec3 operator+(const vec3 &a, const vec3 &b)
{
    return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline vec3 operator-(const vec3 &a, const vec3 &b)
{
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline vec3 operator*(const ex &s, const vec3 &a)
{
    return {s * a[0], s * a[1], s * a[2]};
}
inline ex dot(const vec3 &a, const vec3 &b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline vec3 cross(const vec3 &a, const vec3 &b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline vec3 mul(const mat3 &m, const vec3 &v)
{
    vec3 r;
    for (int i = 0; i < 3; ++i)
        r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    return r;
}
inline ex det(const mat3 &m)
{
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}
/// The adjugate (transposed cofactor matrix): m * adj(m) = det(m) * 1.
inline mat3 adjugate(const mat3 &m)
{
    mat3 a;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            a[i][j] = m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
        }
    return a;
}
inline vec3 subs(const vec3 &v, const GiNaC::ex &what)
{
    return {v[0].subs(what), v[1].subs(what), v[2].subs(what)};
}

} // namespace impactgen
