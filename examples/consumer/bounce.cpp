// A ball dropped on the ground, bouncing: an event-driven simulation whose
// impacts are resolved by the solver that impactgen generated at build time
// from ball-on-ground.json (see CMakeLists.txt: impactgen_generate).
//
// Checks the physics of every impact (Newton's law v'_n = -e v_n, smooth
// contact v'_t = v_t, impulse and energy loss of a ball on immovable ground)
// and of the flight: the k-th apex is e^(2k) times the drop height.
#include "bounce_solver.hpp"

#include <cmath>
#include <cstdio>

namespace {

int failures = 0;

// Relative tolerance 1e-12: each checked quantity is a handful of double
// operations away from the reference (< 10 ulps ~ 2e-15); 1e-12 leaves room
// and still catches any wrong coefficient.
bool near(double a, double b) { return std::fabs(a - b) <= 1e-12 * std::fmax(1.0, std::fmax(std::fabs(a), std::fabs(b))); }

void expect(bool ok, const char* what, double got, double want)
{
    if (!ok) {
        std::printf("FAIL: %s: got %.17g, want %.17g\n", what, got, want);
        ++failures;
    }
}

} // namespace

int main()
{
    const double g = 9.81;      // m/s^2
    const double m = 0.057;     // kg, the ball's mass in ball-on-ground.json
    const double e = 0.8;       // coefficient of restitution
    const double h0 = 1.0;      // m, drop height
    const double vx = 0.5;      // m/s, horizontal velocity (a smooth ground keeps it)

    double x = 0, y = h0, vy = 0, t = 0;
    std::printf("%6s %10s %12s %12s %8s %12s %12s\n", "bounce", "t [s]", "impact v_y", "rebound v_y", "ratio", "apex [m]",
                "e^(2k) h0");
    for (int k = 1; k <= 8; ++k) {
        // Fly until y = 0: y + vy s - g s^2 / 2 = 0.
        const double s = (vy + std::sqrt(vy * vy + 2 * g * y)) / g;
        t += s;
        x += vx * s;
        vy -= g * s;
        y = 0;

        consumer::ball_hits_ground_result<double> out;
        const consumer::impact_status status = consumer::ball_hits_ground(e, vx, vy, out);
        if (status != consumer::impact_status::ok) {
            std::printf("FAIL: impact %d: %s\n", k, consumer::to_string(status));
            return 1;
        }
        expect(near(out.v_y_ball, -e * vy), "rebound speed is e times the impact speed", out.v_y_ball, -e * vy);
        expect(out.v_x_ball == vx, "smooth ground: horizontal velocity unchanged", out.v_x_ball, vx);
        expect(near(out.normal_impulse, -(1 + e) * m * vy), "normal impulse -(1 + e) m v_y", out.normal_impulse,
               -(1 + e) * m * vy);
        expect(near(out.energy_lost, (1 - e * e) * m * vy * vy / 2), "energy lost (1 - e^2) m v_y^2 / 2",
               out.energy_lost, (1 - e * e) * m * vy * vy / 2);
        expect(out.energy_lost >= 0, "energy lost >= 0", out.energy_lost, 0);

        const double impact_vy = vy;
        vy = out.v_y_ball;
        const double apex = vy * vy / (2 * g);
        const double predicted = std::pow(e, 2 * k) * h0;
        std::printf("%6d %10.4f %12.6f %12.6f %8.4f %12.6f %12.6f\n", k, t, impact_vy, vy, -vy / impact_vy, apex,
                    predicted);
        expect(near(apex, predicted), "apex after k bounces is e^(2k) h0", apex, predicted);
    }
    std::printf("travelled %.4f m in %.4f s\n", x, t);

    // Degenerate inputs are reported as a status, never as numbers.
    consumer::ball_hits_ground_result<double> out;
    if (consumer::ball_hits_ground(e, vx, 1.0, out) != consumer::impact_status::not_approaching) {
        std::printf("FAIL: a ball moving up is not an impact\n");
        ++failures;
    }
    if (consumer::ball_hits_ground(1.5, vx, -1.0, out) != consumer::impact_status::invalid_restitution) {
        std::printf("FAIL: e = 1.5 is refused\n");
        ++failures;
    }
    // e = 1: elastic, no energy lost; the header is a template, float works too.
    // Tolerance 1e-5 relative: a few float operations of 6e-8 each (57/1000 and
    // 1000/57 are not exact in float), far below any wrong coefficient.
    consumer::ball_hits_ground_result<float> outf;
    const float kinetic = 0.5f * float(m) * 2.0f * 2.0f;
    if (consumer::ball_hits_ground(1.0f, 0.0f, -2.0f, outf) != consumer::impact_status::ok ||
        std::fabs(outf.v_y_ball - 2.0f) > 1e-5f * 2.0f || std::fabs(outf.energy_lost) > 1e-5f * kinetic) {
        std::printf("FAIL: elastic bounce in float: v_y' = %.9g, energy lost %g\n", outf.v_y_ball, outf.energy_lost);
        ++failures;
    }

    if (failures == 0)
        std::printf("ok: every bounce obeys v'_y = -e v_y\n");
    else
        std::printf("%d checks FAILED\n", failures);
    return failures == 0 ? 0 : 1;
}
