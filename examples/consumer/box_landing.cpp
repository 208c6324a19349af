// A sequential-impulse solver (the loop of Box2D or Bullet) with impactgen's exact contact
// rows: a box landing on two corners. box_corner.hpp is generated from box-corner.json with
// `impactgen codegen --rows` (one corner of the box on the ground, the corner an input); its
// box_corner_rows gives each contact's Jacobian rows, effective masses along the normal and the
// tangent, and the velocity bias of restitution, and the solver loop below is the engine's own.
//
//   box_landing                 checks one contact: one iteration is the closed form box_corner
//   box_landing vx vy w N1 N2   also the two-corner landing of examples/systems/
//                               two-corner-landing.json, against impactgen's exact answer given
//                               on the command line (velocities after impact, normal impulses)
#include "box_corner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace
{

using rows = impactgen::generated::box_corner_rows_result<double>;
using row = impactgen::generated::box_corner_row<double>;

struct box {
    double m, J, x, y, vx, vy, w; // mass, moment of inertia, centre, velocity, spin
};

struct contact {
    rows r;
    double normal_impulse = 0, tangent_impulse = 0; // accumulated (warm start 0)
};

// The relative velocity along a row for the box's current velocity (the ground is at rest:
// body 1 of the rows).
double velocity_along(const row &rw, const box &b)
{
    return rw.dir[0] * b.vx + rw.dir[1] * b.vy + rw.ang2[0] * b.w;
}

void apply(const rows &r, const row &rw, double impulse, box &b)
{
    b.vx += r.inv_m2 * impulse * rw.dir[0];
    b.vy += r.inv_m2 * impulse * rw.dir[1];
    b.w += r.inv_I2[0] * impulse * rw.ang2[0];
}

// Sequential impulses: normal (clamped >= 0, towards the bias of restitution), then friction
// (clamped to the cone of the accumulated normal impulse), contact after contact, until the
// impulses settle. Returns the iterations taken.
int solve(contact *c, int n, double mu, box &b, int max_iterations)
{
    for (int it = 1; it <= max_iterations; ++it) {
        double change = 0;
        for (int k = 0; k < n; ++k) {
            rows &r = c[k].r;
            const double dn = r.normal.effective_mass * (r.bias - velocity_along(r.normal, b));
            const double acc = std::max(0.0, c[k].normal_impulse + dn);
            apply(r, r.normal, acc - c[k].normal_impulse, b);
            change = std::max(change, std::fabs(acc - c[k].normal_impulse));
            c[k].normal_impulse = acc;
            const double dt = -r.tangent[0].effective_mass * velocity_along(r.tangent[0], b);
            const double limit = mu * c[k].normal_impulse;
            const double acct = std::clamp(c[k].tangent_impulse + dt, -limit, limit);
            apply(r, r.tangent[0], acct - c[k].tangent_impulse, b);
            change = std::max(change, std::fabs(acct - c[k].tangent_impulse));
            c[k].tangent_impulse = acct;
        }
        if (change <= 1e-15)
            return it;
    }
    return max_iterations;
}

bool near(double a, double b, double tol, const char *what)
{
    if (std::fabs(a - b) <= tol * std::max(1.0, std::fabs(b)))
        return true;
    std::printf("%s: %.17g, expected %.17g\n", what, a, b);
    return false;
}

} // namespace

int main(int argc, char **argv)
{
    namespace g = impactgen::generated;
    bool ok = true;
    // One contact: a box (2 x 1) strikes the ground with its left corner. Without friction one
    // normal step is the closed form; with friction the loop converges to it.
    const box b0{2, 2.0 * (4 + 1) / 12, 0, 0.5, 0.3, -1, 1};
    for (double mu : {0.0, 0.5}) {
        g::box_corner_result<double> exact{};
        if (g::box_corner(0.2, mu, b0.m, b0.J, b0.x, b0.y, b0.vx, b0.vy, b0.w, -1.0, 0.0, exact) !=
            g::friction_status::ok)
            return std::puts("box_corner: not ok"), 1;
        contact c;
        if (g::box_corner_rows(0.2, mu, b0.m, b0.J, b0.x, b0.y, b0.vx, b0.vy, b0.w, -1.0, 0.0, c.r) !=
            g::impact_status::ok)
            return std::puts("box_corner_rows: not ok"), 1;
        box b = b0;
        const int iterations = solve(&c, 1, mu, b, mu == 0 ? 1 : 100);
        const double tol = mu == 0 ? 1e-15 : 1e-13;
        ok = near(c.normal_impulse, exact.normal_impulse, tol, "one contact: normal impulse") && ok;
        ok =
            near(c.tangent_impulse * c.r.tangent[0].dir[0], exact.tangential_impulse_x, tol, "one contact: friction") &&
            ok;
        ok = near(b.vx, exact.v_x_box, tol, "one contact: vx") && ok;
        ok = near(b.vy, exact.v_y_box, tol, "one contact: vy") && ok;
        ok = near(b.w, exact.w_z_box, tol, "one contact: w") && ok;
        std::printf("one contact, mu = %g: %d iteration(s), N = %.17g (closed form %.17g)\n", mu, iterations,
                    c.normal_impulse, exact.normal_impulse);
    }
    if (argc == 6) {
        // Two contacts: the left corner strikes while the right one rests (e = 0.2, mu = 0.5).
        box b = b0;
        contact c[2];
        const double corner[2] = {-1, 1};
        for (int k = 0; k < 2; ++k)
            if (g::box_corner_rows(0.2, 0.5, b.m, b.J, b.x, b.y, b.vx, b.vy, b.w, corner[k], 0.0, c[k].r) !=
                g::impact_status::ok)
                return std::puts("box_corner_rows: not ok"), 1;
        const int iterations = solve(c, 2, 0.5, b, 10000);
        const double tol = 1e-12;
        ok = near(b.vx, std::atof(argv[1]), tol, "two contacts: vx") && ok;
        ok = near(b.vy, std::atof(argv[2]), tol, "two contacts: vy") && ok;
        ok = near(b.w, std::atof(argv[3]), tol, "two contacts: w") && ok;
        ok = near(c[0].normal_impulse, std::atof(argv[4]), tol, "two contacts: N1") && ok;
        ok = near(c[1].normal_impulse, std::atof(argv[5]), tol, "two contacts: N2") && ok;
        std::printf("two contacts: %d iterations, v = (%.17g, %.17g), w = %.17g, N = (%.17g, %.17g)\n", iterations,
                    b.vx, b.vy, b.w, c[0].normal_impulse, c[1].normal_impulse);
    }
    return ok ? 0 : 1;
}
