// impactgen/eigen.hpp: an optional, thin Eigen adapter for generated impact
// solvers. Include it (after or before any generated header) only where Eigen is
// wanted; generated headers themselves never include Eigen.
//
// Every generated input struct and result struct offers views of the members
// that form vectors and matrices (in.v1(), in.inv_I1(), out.w2(), ...). With
// them:
//
//   box_input<double> in{};
//   impactgen::eigen::assign(in.v1(), body.velocity);          // Eigen::Vector3d
//   impactgen::eigen::assign(in.inv_I1(), body.inv_inertia);   // Eigen::Matrix3d
//   ...
//   body.velocity = impactgen::eigen::to_eigen(out.v1());
//
// assign() returns false when the matrix disagrees with an entry the header
// fixed as a constant (say a zero off-diagonal inertia entry, or a normal
// component folded in with --set): the problem the header solves is then not
// the one the caller has. A symmetric tensor's two entries (r, c) and (c, r)
// share one member: it takes their mean. Entries the header ties to one input
// otherwise (a velocity ["a", "a", 0]) must agree, or assign() returns false.
#pragma once

#include <Eigen/Core>

#include <type_traits>
#include <utility>

#ifndef IMPACTGEN_FUNC
#define IMPACTGEN_FUNC inline
#endif

namespace impactgen::eigen
{

/// The scalar type of a view (without const).
template <typename View>
using scalar_of =
    std::remove_const_t<std::remove_pointer_t<std::decay_t<decltype(std::declval<const View &>().entry[0])>>>;

namespace detail
{
/// A fixed entry (long double) in the scalar type: directly for the floating-point
/// types, through double for others (autodiff scalars are built on double).
template <typename T> IMPACTGEN_FUNC T fixed_value(long double x)
{
    if constexpr (std::is_floating_point<T>::value)
        return static_cast<T>(x);
    else
        return T(static_cast<double>(x));
}
} // namespace detail

/// Writes m into the members the view points to; false when m disagrees with an
/// entry the header fixed (that entry is then not written: it has no member).
template <typename View, typename Derived>
IMPACTGEN_FUNC bool assign(const View &v, const Eigen::MatrixBase<Derived> &m)
{
    using T = scalar_of<View>;
    static_assert(Derived::RowsAtCompileTime == View::rows && Derived::ColsAtCompileTime == View::cols,
                  "impactgen::eigen::assign: the Eigen object's size differs from the view's");
    bool agrees = true;
    for (int r = 0; r < View::rows; ++r)
        for (int c = 0; c < View::cols; ++c) {
            const int k = r * View::cols + c;
            const T x = T(m(r, c));
            T *p = v.entry[k];
            if (p == nullptr) {
                agrees = agrees && x == detail::fixed_value<T>(v.fixed[k]);
                continue;
            }
            int first = k; // the first entry that points to this member
            for (int j = k - 1; j >= 0; --j)
                if (v.entry[j] == p)
                    first = j;
            if (first == k) {
                *p = x;
            } else if (first == c * View::cols + r) {
                *p = (*p + x) / T(2); // a symmetric tensor's transposed entry: their mean
            } else {
                agrees = agrees && *p == x; // the header ties these entries to one input
            }
        }
    return agrees;
}

/// The members the view points to (and the fixed entries) as an Eigen matrix.
template <typename View> IMPACTGEN_FUNC Eigen::Matrix<scalar_of<View>, View::rows, View::cols> to_eigen(const View &v)
{
    using T = scalar_of<View>;
    Eigen::Matrix<T, View::rows, View::cols> m;
    for (int r = 0; r < View::rows; ++r)
        for (int c = 0; c < View::cols; ++c) {
            const int k = r * View::cols + c;
            m(r, c) = v.entry[k] != nullptr ? T(*v.entry[k]) : detail::fixed_value<T>(v.fixed[k]);
        }
    return m;
}

} // namespace impactgen::eigen
