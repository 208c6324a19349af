// A tumbling box bouncing to rest on a floor: a small rigid-body loop of the
// kind an engine runs, with the solver impactgen generated at build time from
// box-floor.json in the engine convention (see CMakeLists.txt):
//
//   impactgen_generate(box_floor_solver PROBLEM box-floor.json NAME box_floor
//                      INVERSE_MASS INVERSE_INERTIA UNIT_NORMAL
//                      JACOBIAN WRT vx vy vz wx wy wz e)
//
// It uses the named-input struct, the Eigen adapter (impactgen/eigen.hpp), the
// failure semantics (the state is written back whatever the status: a failed
// call leaves it unchanged), and the Jacobian of the impact map, checked
// against central differences and against Eigen's forward-mode autodiff of the
// same generated function. Built for float, double and long double.
//
// Checks: every impact obeys Newton's law at the contact point (v'_n = -e v_n),
// the impulse is >= 0, energy never grows, and the box comes to rest.
#include "box_floor_solver.hpp"

#include <impactgen/eigen.hpp>

#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include <cmath>
#include <cstdio>
#include <limits>

namespace ig = impactgen::generated;

namespace {

int failures = 0;

void expect(bool ok, const char* type, const char* what, double got, double want)
{
    if (!ok) {
        std::printf("FAIL [%s]: %s: got %.17g, want %.17g\n", type, what, got, want);
        ++failures;
    }
}

template <typename T> struct box {
    using vec = Eigen::Matrix<T, 3, 1>;
    using mat = Eigen::Matrix<T, 3, 3>;
    vec x{T(0), T(0), T(1)};           // centre of mass, m
    Eigen::Quaternion<T> q{Eigen::AngleAxis<T>(T(0.3), vec(T(1), T(2), T(0.5)).normalized())};
    vec v{T(0.4), T(-0.2), T(0)};      // m/s
    vec w{T(1.5), T(-2), T(3)};        // rad/s
    T inv_mass = T(1) / T(2);          // 2 kg
    vec half{T(0.2), T(0.15), T(0.1)}; // half extents, m
    mat inv_inertia_body() const
    {
        const T m = T(1) / inv_mass;
        vec d;
        d << m * (half.y() * half.y() + half.z() * half.z()) / T(3), m * (half.x() * half.x() + half.z() * half.z()) / T(3),
            m * (half.x() * half.x() + half.y() * half.y()) / T(3);
        return d.cwiseInverse().asDiagonal();
    }
    mat inv_inertia_world() const
    {
        const mat r = q.toRotationMatrix();
        return r * inv_inertia_body() * r.transpose();
    }
    T kinetic_energy() const
    {
        const mat r = q.toRotationMatrix();
        const mat inertia = r * inv_inertia_body().inverse() * r.transpose();
        return v.squaredNorm() / (T(2) * inv_mass) + w.dot(inertia * w) / T(2);
    }
};

// The inputs of one impact, by name and through the Eigen adapter.
template <typename T>
ig::box_floor_input<T> impact_input(const box<T>& b, const Eigen::Matrix<T, 3, 1>& corner, T e)
{
    ig::box_floor_input<T> in{};
    in.e = e;
    in.inv_m = b.inv_mass;
    bool agrees = impactgen::eigen::assign(in.inv_I_box(), b.inv_inertia_world());
    agrees = impactgen::eigen::assign(in.r_box(), b.x) && agrees;
    agrees = impactgen::eigen::assign(in.v_box(), b.v) && agrees;
    agrees = impactgen::eigen::assign(in.w_box(), b.w) && agrees;
    agrees = impactgen::eigen::assign(in.O(), corner) && agrees;
    agrees = impactgen::eigen::assign(in.n(), Eigen::Matrix<T, 3, 1>(T(0), T(0), T(1))) && agrees;
    expect(agrees, "setup", "the adapter agrees with the header's fixed entries", 0, 0);
    return in;
}

template <typename T> int simulate(const char* type)
{
    using vec = Eigen::Matrix<T, 3, 1>;
    const T g = T(9.81), e = T(0.5), dt = T(1) / T(2000);
    const double eps = static_cast<double>(std::numeric_limits<T>::epsilon());
    box<T> b;
    const T start = b.kinetic_energy() + g * b.x.z() / b.inv_mass;
    int impacts = 0;
    for (int step = 0; step < 20000; ++step) {
        // Flight: semi-implicit Euler, orientation by the angular velocity (world frame).
        b.v.z() -= g * dt;
        b.x += b.v * dt;
        const T angle = b.w.norm() * dt;
        if (angle > T(0))
            b.q = Eigen::Quaternion<T>(Eigen::AngleAxis<T>(angle, b.w.normalized())) * b.q;
        b.q.normalize();
        // The lowest corner below the floor and approaching: one impact there.
        const Eigen::Matrix<T, 3, 3> r = b.q.toRotationMatrix();
        vec corner = b.x;
        T lowest = std::numeric_limits<T>::max();
        for (int k = 0; k < 8; ++k) {
            const vec c = b.x + r * vec((k & 1 ? 1 : -1) * b.half.x(), (k & 2 ? 1 : -1) * b.half.y(), (k & 4 ? 1 : -1) * b.half.z());
            if (c.z() < lowest) {
                lowest = c.z();
                corner = c;
            }
        }
        if (lowest > T(0))
            continue;
        b.x.z() -= lowest; // resolve the penetration
        corner.z() = T(0);
        const ig::box_floor_input<T> in = impact_input(b, corner, e);
        const T before = b.kinetic_energy();
        ig::box_floor_result<T> out;
        const ig::impact_status s = ig::box_floor(in, out);
        const T vn_before = (b.v + b.w.cross(corner - b.x)).z();
        // Written back unconditionally: a failed call (not approaching: a resting
        // contact) leaves the state unchanged.
        b.v = impactgen::eigen::to_eigen(out.v_box());
        b.w = impactgen::eigen::to_eigen(out.w_box());
        if (s != ig::impact_status::ok) {
            expect(out.normal_impulse == T(0), type, "no impulse on failure", static_cast<double>(out.normal_impulse), 0);
            continue;
        }
        ++impacts;
        const T vn_after = (b.v + b.w.cross(corner - b.x)).z();
        // Tolerances: the post-impact state is a few dozen operations on values of order 1-10
        // from the inputs (error ~ 100 eps of the scale); 1e3 eps leaves room, and a wrong
        // coefficient (e, a lever arm, an inertia entry) is off by O(1) of the scale.
        const double scale = std::fabs(static_cast<double>(vn_before)) + 1;
        expect(std::fabs(static_cast<double>(vn_after + e * vn_before)) <= 1e3 * eps * scale, type, "Newton's law at the corner",
               static_cast<double>(vn_after), static_cast<double>(-e * vn_before));
        expect(out.normal_impulse >= T(0), type, "impulse >= 0", static_cast<double>(out.normal_impulse), 0);
        // The impact loses kinetic energy (e < 1), exactly as much as the solver says.
        const T after = b.kinetic_energy();
        const double tol = 1e3 * eps * (static_cast<double>(before) + 1);
        expect(static_cast<double>(after) <= static_cast<double>(before) + tol, type, "kinetic energy does not grow",
               static_cast<double>(after), static_cast<double>(before));
        expect(std::fabs(static_cast<double>(before - after - out.energy_lost)) <= tol, type, "energy lost as reported",
               static_cast<double>(out.energy_lost), static_cast<double>(before - after));
    }
    const T end = b.kinetic_energy() + g * b.x.z() / b.inv_mass;
    std::printf("[%s] %d impacts; energy %.4g J at the start, %.4g J at the end\n", type, impacts, static_cast<double>(start),
                static_cast<double>(end));
    expect(impacts > 10, type, "the box bounces", impacts, 10);
    expect(static_cast<double>(end) < static_cast<double>(start) / 2, type, "energy is lost", static_cast<double>(end),
           static_cast<double>(start));
    return 0;
}

// The Jacobian at one impact: against central differences of the double
// function, and against forward-mode autodiff of the same generated function.
void check_jacobian()
{
    using vec = Eigen::Vector3d;
    box<double> b;
    b.v = vec(0.4, -0.2, -2.0);
    const vec corner = b.x + b.q.toRotationMatrix() * vec(-0.2, -0.15, -0.1);
    const ig::box_floor_input<double> in = impact_input(b, corner, 0.5);
    ig::box_floor_jacobian_result<double> jac;
    if (ig::box_floor_jacobian(in, jac) != ig::impact_status::ok) {
        expect(false, "jacobian", "status ok", 0, 0);
        return;
    }
    // The inputs differentiated by, as members of the input struct.
    double ig::box_floor_input<double>::*const wrt[] = {&ig::box_floor_input<double>::vx, &ig::box_floor_input<double>::vy,
                                                        &ig::box_floor_input<double>::vz, &ig::box_floor_input<double>::wx,
                                                        &ig::box_floor_input<double>::wy, &ig::box_floor_input<double>::wz,
                                                        &ig::box_floor_input<double>::e};
    static_assert(sizeof wrt / sizeof wrt[0] == ig::box_floor_wrt_count, "one member per Jacobian column");
    double worst_fd = 0, worst_ad = 0;
    for (int j = 0; j < ig::box_floor_wrt_count; ++j) {
        // Central differences: error O(h^2 f''') + O(eps f / h); h = 1e-5 gives ~1e-10.
        const double h = 1e-5;
        ig::box_floor_input<double> a = in, c = in;
        a.*wrt[j] += h;
        c.*wrt[j] -= h;
        ig::box_floor_result<double> ra, rc;
        ig::box_floor(a, ra);
        ig::box_floor(c, rc);
        double va[ig::box_floor_output_count], vc[ig::box_floor_output_count];
        ig::box_floor_to_array(ra, va);
        ig::box_floor_to_array(rc, vc);
        for (int i = 0; i < ig::box_floor_output_count; ++i)
            worst_fd = std::fmax(worst_fd, std::fabs((va[i] - vc[i]) / (2 * h) - jac.d[i][j]));
    }
    // Forward-mode autodiff: the same template with T = AutoDiffScalar, seeded by the wrt inputs.
    using ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, ig::box_floor_wrt_count, 1>>;
    ig::box_floor_input<ad> ain;
    double ig::box_floor_input<double>::*const all[] = {
        &ig::box_floor_input<double>::e,   &ig::box_floor_input<double>::inv_m, &ig::box_floor_input<double>::inv_Ixx,
        &ig::box_floor_input<double>::inv_Ixy, &ig::box_floor_input<double>::inv_Ixz, &ig::box_floor_input<double>::inv_Iyy,
        &ig::box_floor_input<double>::inv_Iyz, &ig::box_floor_input<double>::inv_Izz, &ig::box_floor_input<double>::x,
        &ig::box_floor_input<double>::y,   &ig::box_floor_input<double>::z,     &ig::box_floor_input<double>::vx,
        &ig::box_floor_input<double>::vy,  &ig::box_floor_input<double>::vz,    &ig::box_floor_input<double>::wx,
        &ig::box_floor_input<double>::wy,  &ig::box_floor_input<double>::wz,    &ig::box_floor_input<double>::px,
        &ig::box_floor_input<double>::py,  &ig::box_floor_input<double>::pz,    &ig::box_floor_input<double>::nx,
        &ig::box_floor_input<double>::ny,  &ig::box_floor_input<double>::nz};
    ad ig::box_floor_input<ad>::*const all_ad[] = {
        &ig::box_floor_input<ad>::e,   &ig::box_floor_input<ad>::inv_m, &ig::box_floor_input<ad>::inv_Ixx,
        &ig::box_floor_input<ad>::inv_Ixy, &ig::box_floor_input<ad>::inv_Ixz, &ig::box_floor_input<ad>::inv_Iyy,
        &ig::box_floor_input<ad>::inv_Iyz, &ig::box_floor_input<ad>::inv_Izz, &ig::box_floor_input<ad>::x,
        &ig::box_floor_input<ad>::y,   &ig::box_floor_input<ad>::z,     &ig::box_floor_input<ad>::vx,
        &ig::box_floor_input<ad>::vy,  &ig::box_floor_input<ad>::vz,    &ig::box_floor_input<ad>::wx,
        &ig::box_floor_input<ad>::wy,  &ig::box_floor_input<ad>::wz,    &ig::box_floor_input<ad>::px,
        &ig::box_floor_input<ad>::py,  &ig::box_floor_input<ad>::pz,    &ig::box_floor_input<ad>::nx,
        &ig::box_floor_input<ad>::ny,  &ig::box_floor_input<ad>::nz};
    static_assert(sizeof all / sizeof all[0] == ig::box_floor_input_count, "every input");
    for (int k = 0; k < ig::box_floor_input_count; ++k) {
        ain.*all_ad[k] = ad(in.*all[k]);
        (ain.*all_ad[k]).derivatives().setZero();
        for (int j = 0; j < ig::box_floor_wrt_count; ++j)
            if (all[k] == wrt[j])
                (ain.*all_ad[k]).derivatives()(j) = 1;
    }
    ig::box_floor_result<ad> aout;
    if (ig::box_floor(ain, aout) != ig::impact_status::ok) {
        expect(false, "autodiff", "status ok", 0, 0);
        return;
    }
    ad values[ig::box_floor_output_count];
    ig::box_floor_to_array(aout, values);
    for (int i = 0; i < ig::box_floor_output_count; ++i)
        for (int j = 0; j < ig::box_floor_wrt_count; ++j)
            worst_ad = std::fmax(worst_ad, std::fabs(values[i].derivatives()(j) - jac.d[i][j]));
    std::printf("[jacobian] max |J - central differences| = %.2e, max |J - autodiff| = %.2e\n", worst_fd, worst_ad);
    // Central differences (see above) are ~1e-10 off (measured 1.1e-10): 1e-7 catches any wrong
    // term. Autodiff and the Jacobian are two double evaluations of the same derivative: a few
    // hundred roundings apart (measured 8.9e-16); 1e-12 leaves room.
    expect(worst_fd < 1e-7, "jacobian", "central differences", worst_fd, 0);
    expect(worst_ad < 1e-12, "jacobian", "autodiff", worst_ad, 0);
}

} // namespace

int main()
{
    simulate<float>("float");
    simulate<double>("double");
    simulate<long double>("long double");
    check_jacobian();
    if (failures)
        std::printf("%d failure(s)\n", failures);
    return failures ? 1 : 0;
}
