#include "named_classes.hpp"
#include "named_systems.hpp"

#include "expr/roles.hpp"

namespace impactgen
{
using namespace GiNaC;

namespace
{

ex S(const std::string &name, const std::string &tex = "")
{
    return symbol_named(name, tex);
}

// An angular velocity of the notes (w_b1, w_t2): ω in every document.
ex spin(const std::string &name, const std::string &tex)
{
    return expr::set_role(symbol_named(name, tex), expr::symbol_role::angular_velocity);
}

// Body "1" or "2" with the notes' symbols: m1, v_t1, v_n1, v_b1, w_t1, ..., position r_t1 ... of C1 relative to O.
body free_body(const std::string &k, int dim, bool rigid, bool full_inertia)
{
    body b;
    b.name = b.label = k;
    b.numbered = true;
    b.mass = S("m" + k);
    const char *ax[3] = {"t", "n", "b"};
    for (int c = 0; c < dim; ++c) {
        b.position[c] = S(std::string("r_") + ax[c] + k, std::string("r_{") + ax[c] + k + "}");
        b.velocity[c] = S(std::string("v_") + ax[c] + k, std::string("v_{") + ax[c] + k + "}");
    }
    b.particle = !rigid;
    if (!rigid)
        return b;
    if (dim == 2) {
        b.inertia[2][2] = S("I" + k, "I_{" + k + "}");
        b.angular_velocity[2] = spin("w_b" + k, "\\omega_{b" + k + "}");
        return b;
    }
    for (int c = 0; c < 3; ++c)
        b.angular_velocity[c] = spin(std::string("w_") + ax[c] + k, std::string("\\omega_{") + ax[c] + k + "}");
    for (int r = 0; r < 3; ++r)
        for (int c = r; c < 3; ++c) {
            if (!full_inertia && r != c)
                continue;
            std::string nm = "I" + k + "_" + ax[r] + ax[c];
            ex s = S(nm, "I^{" + k + "}_{" + std::string(ax[r]) + ax[c] + "}");
            b.inertia[r][c] = s;
            b.inertia[c][r] = s;
        }
    return b;
}

// The figure of a free body of the notes (free_body), by body (1, 2) and quantity: on its own side
// of the tangent plane, its centre off the line of impact, its velocity approaching the other's.
void illustrate_free_body(problem &p, std::size_t i)
{
    static const double mass[2] = {1, 1.5}, planar_inertia = 0.25;
    static const double position[2][3] = {{-0.5, -0.9, 0.3}, {0.6, 1.0, -0.25}};
    static const double velocity[2][3] = {{0.5, 1.0, 0.3}, {-0.4, -0.6, -0.2}};
    const body &b = p.bodies[i];
    p.illustrate(b.mass, mass[i]);
    for (int c = 0; c < p.dimension; ++c) {
        p.illustrate(b.position[c], position[i][c]);
        p.illustrate(b.velocity[c], velocity[i][c]);
    }
    if (p.dimension == 2)
        p.illustrate(b.inertia[2][2], planar_inertia);
}

// Two free bodies of the notes, illustrated.
void free_bodies(problem &p, const body &b1, const body &b2)
{
    p.bodies = {b1, b2};
    illustrate_free_body(p, 0);
    illustrate_free_body(p, 1);
}

problem base(const std::string &name, int dim)
{
    problem p;
    p.source = name;
    p.illustrated = true;
    p.dimension = dim;
    p.restitution = S("e");
    p.illustrate(p.restitution, 0.8);
    p.axes = {"t", "n", "b"};
    p.contact().body1 = 0;
    p.contact().body2 = 1;
    p.contact().normal = {0, 1, 0};
    return p;
}

problem central_direct()
{
    problem p = base("central-direct", 2);
    body b1 = free_body("1", 2, false, false), b2 = free_body("2", 2, false, false);
    // Centres on the line of impact (the n axis), velocities along it.
    b1.position = {0, -S("R1", "R_{1}"), 0};
    b2.position = {0, S("R2", "R_{2}"), 0};
    b1.velocity[0] = 0;
    b2.velocity[0] = 0;
    free_bodies(p, b1, b2);
    p.illustrate(S("R1"), 1);
    p.illustrate(S("R2"), 0.8);
    return p;
}

problem central_oblique()
{
    problem p = base("central-oblique", 3);
    body b1 = free_body("1", 3, false, false), b2 = free_body("2", 3, false, false);
    b1.position = {0, -S("R1", "R_{1}"), 0};
    b2.position = {0, S("R2", "R_{2}"), 0};
    free_bodies(p, b1, b2);
    p.illustrate(S("R1"), 1);
    p.illustrate(S("R2"), 0.8);
    return p;
}

problem noncentral_3d()
{
    problem p = base("noncentral-3d", 3);
    free_bodies(p, free_body("1", 3, true, true), free_body("2", 3, true, true));
    return p;
}

problem massive_3d()
{
    problem p = base("massive-3d", 3);
    body b2 = free_body("2", 3, true, true);
    b2.infinite_mass = true;
    b2.mass = 0;
    b2.particle = true; // an infinite mass needs no inertia: its motion is given
    b2.inertia = zero_mat();
    free_bodies(p, free_body("1", 3, true, true), b2);
    return p;
}

problem planar()
{
    problem p = base("planar", 2);
    free_bodies(p, free_body("1", 2, true, false), free_body("2", 2, true, false));
    return p;
}

// The notes' worked example: a ball (particle, m1, speed v1) strikes the lower
// end B of a uniform rod AB (m2, length l) hanging at rest from a hinge at A.
// Here e_n = x (horizontal, the ball's motion), the rod along -y, A at the origin.
problem pinned_planar()
{
    problem p;
    p.source = "pinned-planar";
    p.illustrated = true;
    p.dimension = 2;
    p.restitution = S("e");
    p.illustrate(p.restitution, 0.8);
    p.axes = {"x", "y", "z"};
    ex l = S("l"), m1 = S("m1"), m2 = S("m2");
    body ball;
    ball.name = ball.label = "1";
    ball.numbered = true;
    ball.mass = m1;
    ball.position = {0, -l, 0};
    ball.velocity = {S("v1", "v_{1}"), 0, 0};
    body rod;
    rod.name = rod.label = "2";
    rod.numbered = true;
    rod.mass = m2;
    rod.particle = false;
    rod.inertia[2][2] = m2 * l * l / 12;
    rod.position = {0, -l / 2, 0};
    p.bodies = {ball, rod};
    p.contact().body1 = 0;
    p.contact().body2 = 1;
    p.contact().point = {0, -l, 0};
    p.contact().normal = {1, 0, 0};
    p.pivots = {pivot{1, zero_vec()}};
    p.illustrate(m1, 1);
    p.illustrate(m2, 1.5);
    p.illustrate(l, 1.5);
    p.illustrate(ball.velocity[0], 1);
    return p;
}

// Past the notes: Coulomb friction at the contact (format version 2), coefficient mu.
problem with_friction(problem p, const std::string &name)
{
    p.source = name;
    p.contact().set_friction(S("mu", "\\mu"));
    p.illustrate(p.contact().friction(), 0.3);
    return p;
}

problem planar_friction()
{
    return with_friction(planar(), "planar-friction");
}

problem noncentral_3d_friction()
{
    return with_friction(noncentral_3d(), "noncentral-3d-friction");
}

// The classic: a ball (radius R, mass m, I = 2 m R^2 / 5, spin w) strikes the
// immovable floor obliquely (v_n < 0) and leaves rolling when mu is large enough.
problem ball_floor_friction()
{
    problem p = base("ball-floor-friction", 2);
    const ex m = S("m"), R = S("R");
    body floor;
    floor.name = floor.label = "floor";
    floor.infinite_mass = true;
    floor.mass = 0;
    floor.position = {0, -R, 0}; // any point below the surface: an infinite mass at rest
    body ball;
    ball.name = ball.label = "ball";
    ball.mass = m;
    ball.particle = false;
    ball.inertia[2][2] = 2 * m * R * R / 5;
    ball.position = {0, R, 0};
    ball.velocity = {S("v_t", "v_{t}"), S("v_n", "v_{n}"), 0};
    ball.angular_velocity[2] = S("w", "\\omega");
    p.bodies = {floor, ball};
    // a ball of unit mass and radius that approaches the floor and slides along it
    p.illustrate(m, 1);
    p.illustrate(R, 1);
    p.illustrate(ball.velocity[0], 1.0);
    p.illustrate(ball.velocity[1], -1.2);
    return with_friction(p, "ball-floor-friction");
}

// The classic of slip reversal (Stronge, Impact Mechanics, ch. 5): a slender rod (mass m, length
// l, I = m l^2 / 12) at the angle theta to a rough floor strikes it with its lower end O; restitution
// by Stronge's energetic coefficient, followed through the impact.
problem rod_rough_floor()
{
    problem p = base("rod-rough-floor", 2);
    const ex m = S("m"), l = S("l"), th = S("theta", "\\theta");
    body floor;
    floor.name = floor.label = "floor";
    floor.infinite_mass = true;
    floor.mass = 0;
    floor.position = {0, -l, 0};
    body rod;
    rod.name = rod.label = "rod";
    rod.mass = m;
    rod.particle = false;
    rod.inertia[2][2] = m * l * l / 12;
    rod.position = {l * cos(th) / 2, l * sin(th) / 2, 0};
    rod.velocity = {S("v_t", "v_{t}"), S("v_n", "v_{n}"), 0};
    rod.angular_velocity[2] = S("w", "\\omega");
    p.bodies = {floor, rod};
    p.illustrate(m, 1);
    p.illustrate(l, 1.5);
    p.illustrate(rod.velocity[0], 1.0);
    p.illustrate(rod.velocity[1], -1.2);
    p = with_friction(p, "rod-rough-floor");
    p.contact().law_of_restitution = energetic_restitution{};
    return p;
}

} // namespace

const std::vector<named_class> &law_classes()
{
    static const std::vector<named_class> all = {
        {"rod-rough-floor",
         "a slender rod falls on a rough floor at an angle; its end slips, sticks or reverses (energetic law, "
         "Routh's process)",
         rod_rough_floor},
    };
    return all;
}

const std::vector<named_class> &friction_classes()
{
    static const std::vector<named_class> all = {
        {"planar-friction", "planar impact of two free rigid bodies with Coulomb friction mu", planar_friction},
        {"ball-floor-friction",
         "a spinning ball strikes the floor obliquely with friction: it sticks (leaves rolling) or slides",
         ball_floor_friction},
        {"noncentral-3d-friction", "two free rigid bodies in 3-D with full inertia tensors and Coulomb friction mu",
         noncentral_3d_friction},
    };
    return all;
}

const std::vector<named_class> &named_classes()
{
    static const std::vector<named_class> all = {
        {"central-direct", "two particles, centres and velocities on the line of impact", central_direct},
        {"central-oblique", "two spheres, centres on the line of impact, oblique 3-D velocities", central_oblique},
        {"noncentral-3d", "two free rigid bodies in 3-D with full inertia tensors", noncentral_3d},
        {"massive-3d", "a free rigid body strikes a moving body of infinite mass", massive_3d},
        {"planar", "smooth planar impact of two free rigid bodies (e_b a principal axis)", planar},
        {"pinned-planar", "a ball strikes the end of a rod hinged at a fixed point (unknown pivot impulse)",
         pinned_planar},
    };
    return all;
}

const named_class *find_named_class(const std::string &name)
{
    for (const named_class &c : named_classes())
        if (c.name == name)
            return &c;
    for (const named_class &c : friction_classes())
        if (c.name == name)
            return &c;
    for (const named_class &c : law_classes())
        if (c.name == name)
            return &c;
    for (const named_class &c : system_classes())
        if (c.name == name)
            return &c;
    return nullptr;
}

} // namespace impactgen
