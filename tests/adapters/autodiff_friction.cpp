// The headers with friction instantiated with Eigen's AutoDiffScalar (forward mode): the
// planar, the isotropic 3-D and the general 3-D one (its sliding direction found at run
// time by the root finder). On seeded random impacts the derivatives of every output by
// every input equal central differences of the double function, where the regime is the
// same a step either side (the impact map is smooth inside a regime). A header with --jacobian
// (the planar one: the 3-D one's NAME_jacobian with 34 fixed-size derivatives takes minutes to
// compile; codegen_friction.friction_jacobian.* checks it in double and long double) instantiates
// NAME_jacobian with AutoDiffScalar as well, and its forward-mode derivatives of the values equal
// the exact derivatives NAME_jacobian computes in double.
#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "ball_floor_friction.hpp"
#include "noncentral_3d_friction.hpp"
#include "planar_friction.hpp"
#include "planar_friction_jac.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace ig = impactgen::generated;

namespace
{

// Inputs by name: e in [0.2, 0.8], mu in [0.1, 0.9], masses in [0.5, 2], inertia tensors
// diagonally dominant, the rest in [-1, 1].
std::vector<double> draw(std::mt19937_64 &g, const char *const *names, int n)
{
    std::uniform_real_distribution<double> U(0, 1);
    std::vector<double> x(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) {
        const std::string nm = names[j];
        double v = 2 * U(g) - 1;
        if (nm == "e")
            v = 0.2 + 0.6 * U(g);
        else if (nm == "mu")
            v = 0.1 + 0.8 * U(g);
        else if (nm[0] == 'm' && nm.find('_') == std::string::npos)
            v = 0.5 + 1.5 * U(g);
        else if (nm[0] == 'I') {
            const std::size_t k = nm.rfind('_');
            const bool diagonal = k == std::string::npos || (nm.size() == k + 3 && nm[k + 1] == nm[k + 2]);
            v = diagonal ? 2.5 + U(g) : 0.4 * (2 * U(g) - 1);
        }
        x[static_cast<std::size_t>(j)] = v;
    }
    return x;
}

// (fixed-size derivatives, as the other autodiff tests: a dynamic size leaves constants with
// no derivative vector to combine with)
template <int N, typename Result, typename Fn>
void derivatives_agree(const char *what, const char *const *names, int n_out, Fn call, int min_compared)
{
    using ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;
    const int n_in = N;
    std::mt19937_64 g(31);
    int compared = 0;
    for (int trial = 0; trial < 300 && compared < 60; ++trial) {
        const std::vector<double> x = draw(g, names, n_in);
        std::vector<ad> xa(static_cast<std::size_t>(n_in));
        for (int j = 0; j < n_in; ++j)
            xa[static_cast<std::size_t>(j)] = ad(x[static_cast<std::size_t>(j)], n_in, j);
        typename Result::template of<ad> ra{};
        typename Result::template of<double> r0{};
        if (call(xa.data(), ra) != 0 || call(x.data(), r0) != 0 || ra.regime != r0.regime)
            continue;
        std::vector<ad> oa(static_cast<std::size_t>(n_out));
        Result::to_array(ra, oa.data());
        std::vector<double> o0(static_cast<std::size_t>(n_out));
        Result::to_array(r0, o0.data());
        bool counted = false;
        for (int j = 0; j < n_in; ++j) {
            const double h = 1e-6 * (1 + std::fabs(x[static_cast<std::size_t>(j)]));
            std::vector<double> xp = x, xm = x;
            xp[static_cast<std::size_t>(j)] += h;
            xm[static_cast<std::size_t>(j)] -= h;
            typename Result::template of<double> rp{}, rm{};
            if (call(xp.data(), rp) != 0 || call(xm.data(), rm) != 0 || rp.regime != r0.regime ||
                rm.regime != r0.regime)
                continue; // a regime boundary within the step: no derivative to compare
            std::vector<double> op(static_cast<std::size_t>(n_out)), om(op);
            Result::to_array(rp, op.data());
            Result::to_array(rm, om.data());
            for (int k = 0; k < n_out; ++k) {
                const double fd = (op[static_cast<std::size_t>(k)] - om[static_cast<std::size_t>(k)]) / (2 * h);
                const double d = oa[static_cast<std::size_t>(k)].derivatives()[j];
                EXPECT_NEAR(d, fd, 1e-5 * (1 + std::fabs(fd)))
                    << what << " trial " << trial << " d output " << k << " / d " << names[j];
                EXPECT_EQ(oa[static_cast<std::size_t>(k)].value(), o0[static_cast<std::size_t>(k)]) << what;
            }
            counted = true;
        }
        compared += counted;
    }
    EXPECT_GE(compared, min_compared) << what << ": too few impacts compared";
}

#define RESULT(FN)                                                                                                     \
    struct FN##_r {                                                                                                    \
        template <typename T> using of = ig::FN##_result<T>;                                                           \
        template <typename T> static void to_array(const of<T> &r, T *a) { ig::FN##_to_array(r, a); }                  \
    }
RESULT(planar_friction);
RESULT(ball_floor_friction);
RESULT(noncentral_3d_friction);

#define AGREE(FN, MIN)                                                                                                 \
    derivatives_agree<ig::FN##_input_count, FN##_r>(                                                                   \
        #FN, ig::FN##_input_names, ig::FN##_output_count,                                                              \
        [](const auto *x, auto &r) { return static_cast<int>(ig::FN(x, r)); }, MIN)

// NAME_jacobian<AutoDiffScalar>: its values' derivatives against NAME_jacobian<double>'s jac
// (two roads to one derivative: forward mode through the selection and the root finder, and
// the closed form differentiated symbolically), to 1e-9 relative.
template <int N, int Rows, int Cols, typename Result, typename Fn>
void jacobian_agrees(const char *what, const char *const *names, const char *const *out_names, int n_out,
                     const char *const *row_names, const char *const *wrt_names, Fn call)
{
    using ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;
    std::mt19937_64 g(37);
    int compared = 0;
    for (int trial = 0; trial < 300 && compared < 30; ++trial) {
        const std::vector<double> x = draw(g, names, N);
        std::vector<ad> xa(static_cast<std::size_t>(N));
        for (int j = 0; j < N; ++j)
            xa[static_cast<std::size_t>(j)] = ad(x[static_cast<std::size_t>(j)], N, j);
        typename Result::template of<ad> ra{};
        typename Result::template of<double> r0{};
        std::vector<ad> ja(static_cast<std::size_t>(Rows * Cols));
        std::vector<double> j0(static_cast<std::size_t>(Rows * Cols));
        if (call(xa.data(), ra, ja.data()) != 0 || call(x.data(), r0, j0.data()) != 0)
            continue;
        std::vector<ad> oa(static_cast<std::size_t>(n_out));
        Result::to_array(ra, oa.data());
        for (int i = 0; i < Rows; ++i) {
            int k = 0;
            while (k < n_out && std::string(out_names[k]) != row_names[i])
                ++k;
            ASSERT_LT(k, n_out) << what << ": row " << row_names[i] << " is not an output";
            for (int w = 0; w < Cols; ++w) {
                int j = 0;
                while (j < N && std::string(names[j]) != wrt_names[w])
                    ++j;
                ASSERT_LT(j, N) << what << ": " << wrt_names[w] << " is not an input";
                const double exact = j0[static_cast<std::size_t>(i * Cols + w)],
                             forward = oa[static_cast<std::size_t>(k)].derivatives()[j];
                EXPECT_NEAR(forward, exact, 1e-9 * (1 + std::fabs(exact)))
                    << what << " trial " << trial << " d " << row_names[i] << " / d " << names[j];
            }
        }
        ++compared;
    }
    EXPECT_GE(compared, 30) << what << ": too few impacts compared";
}

RESULT(planar_friction_jac);

#define JACOBIAN_AGREE(FN)                                                                                             \
    jacobian_agrees<ig::FN##_input_count, ig::FN##_jacobian_row_count, ig::FN##_wrt_count, FN##_r>(                    \
        #FN, ig::FN##_input_names, ig::FN##_output_names, ig::FN##_output_count, ig::FN##_jacobian_row_names,          \
        ig::FN##_wrt_names,                                                                                            \
        [](const auto *x, auto &r, auto *jac) { return static_cast<int>(ig::FN##_jacobian(x, r, jac)); })

} // namespace

TEST(AutodiffFriction, JacobianHeadersInstantiateAndMatchForwardMode)
{
    static_assert(ig::planar_friction_jac_wrt_count == 8, "--wrt of tests/adapters/CMakeLists.txt");
    JACOBIAN_AGREE(planar_friction_jac);
}

TEST(AutodiffFriction, AutoDiffScalarMatchesCentralDifferences)
{
    AGREE(planar_friction, 20);
    AGREE(ball_floor_friction, 20);
    AGREE(noncentral_3d_friction, 20);
}
