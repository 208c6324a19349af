#include "named_systems.hpp"

namespace impactgen
{
using namespace GiNaC;

namespace
{

// A symbol of the class, with the default LaTeX form of its name (w1 is w_1): symbols are shared
// by name across the process, so a class must not depend on being the first to create one (w
// is the other classes' omega, and is written so here too).
ex S(const std::string &name)
{
    return symbol_named(name);
}

body ground(const ex &below)
{
    body g;
    g.name = g.label = "ground";
    g.infinite_mass = true;
    g.mass = 0;
    g.position = {0, below, 0}; // any point below the surface: an infinite mass at rest
    return g;
}

body rigid(const std::string &name, const ex &mass, const ex &inertia, const vec3 &centre)
{
    body b;
    b.name = b.label = name;
    b.mass = mass;
    b.particle = false;
    b.inertia[2][2] = inertia;
    b.position = centre;
    return b;
}

contact_spec contact(std::size_t b1, std::size_t b2, const vec3 &point, const vec3 &normal)
{
    contact_spec c;
    c.body1 = b1;
    c.body2 = b2;
    c.point = point;
    c.normal = normal;
    return c;
}

problem system_base(const std::string &name, const std::string &title, const std::string &description)
{
    problem p;
    p.source = name;
    p.illustrated = true;
    p.title = title;
    p.description = description;
    p.dimension = 2;
    p.contacts.clear();
    return p;
}

// Heel strike of a compass-gait walker: two legs (mass m, inertia I_C about the centre, the
// centre at mid-length) joined at the hip H = (a, h); the stance foot rests at the origin, the
// swing foot strikes at (2a, 0). Before impact the stance leg turns about its foot with w1 and
// the swing leg about the hip with w2 (the joint holds and the stance foot rests, by
// construction). Plastic (e = 0), perfectly rough feet.
problem compass_gait()
{
    problem p = system_base("compass-gait", "Heel strike of a compass-gait walker",
                            "Two legs joined at the hip; the swing foot strikes the ground while the stance "
                            "foot rests on it; plastic, no slip.");
    const ex m = S("m"), I = S("I_C"), a = S("a"), h = S("h"), w1 = S("w1"), w2 = S("w2");
    p.restitution = 0;
    body stance = rigid("stance", m, I, {a / 2, h / 2, 0});
    stance.velocity = {-w1 * h / 2, w1 * a / 2, 0};
    stance.angular_velocity[2] = w1;
    body swing = rigid("swing", m, I, {3 * a / 2, h / 2, 0});
    swing.velocity = {-w1 * h + w2 * h / 2, w1 * a + w2 * a / 2, 0};
    swing.angular_velocity[2] = w2;
    p.bodies = {ground(0), stance, swing};
    p.joints = {joint{1, 2, {a, h, 0}}};
    p.contacts = {contact(0, 2, {2 * a, 0, 0}, {0, 1, 0}), contact(0, 1, {0, 0, 0}, {0, 1, 0})};
    for (contact_spec &c : p.contacts)
        c.rough = true;
    return p;
}

// Three equal balls (mass m, radius R) on a line: the first moves at v towards the other two,
// which touch and rest. Simultaneous impacts (the sequential model is the same problem with
// the contacts acting one at a time: explain teaches both).
problem three_balls()
{
    problem p = system_base("three-balls", "Three equal balls in a line",
                            "A ball strikes two touching balls at rest: both contacts at once, or one after the "
                            "other.");
    const ex m = S("m"), R = S("R"), v = S("v");
    p.restitution = S("e");
    std::vector<body> balls;
    for (int k = 0; k < 3; ++k) {
        body b;
        b.name = b.label = std::to_string(k + 1);
        b.numbered = true;
        b.mass = m;
        b.position = {2 * k * R, 0, 0};
        balls.push_back(b);
    }
    balls[0].velocity = {v, 0, 0};
    p.bodies = balls;
    p.contacts = {contact(0, 1, {R, 0, 0}, {1, 0, 0}), contact(1, 2, {3 * R, 0, 0}, {1, 0, 0})};
    p.illustrate(p.restitution, 0.8);
    return p;
}

// Two equal uniform rods (mass m, length l, inertia m l^2/12) hang from a pivot at the origin,
// joined by a pin at (0, -l); a ball (mass M, radius R) moving at v strikes the lower end
// (0, -2l) horizontally.
problem double_pendulum_struck()
{
    problem p = system_base("double-pendulum-struck", "A ball strikes a hanging double pendulum",
                            "Two equal rods hang from a pivot, joined by a pin; a ball strikes the lower end "
                            "horizontally.");
    const ex m = S("m"), l = S("l"), M = S("M"), R = S("R"), v = S("v");
    p.restitution = S("e");
    body upper = rigid("upper", m, m * l * l / 12, {0, -l / 2, 0});
    body lower = rigid("lower", m, m * l * l / 12, {0, -3 * l / 2, 0});
    body ball;
    ball.name = ball.label = "ball";
    ball.mass = M;
    ball.position = {-R, -2 * l, 0};
    ball.velocity = {v, 0, 0};
    p.bodies = {upper, lower, ball};
    p.pivots = {pivot{0, zero_vec()}};
    p.joints = {joint{0, 1, {0, -l, 0}}};
    p.contacts = {contact(2, 1, {0, -2 * l, 0}, {1, 0, 0})};
    p.illustrate(p.restitution, 0.8);
    p.illustrate(l, 1.5);
    return p;
}

// A planar box (2a wide, 2b high, mass m, inertia m (a^2 + b^2)/3) lands on its two bottom
// corners: turning with w > 0, its left corner (-a, 0) strikes while its right corner (a, 0)
// rests (v_y = -a w). Coulomb friction mu at both corners, restitution e.
problem two_corner_landing()
{
    problem p = system_base("two-corner-landing", "A box landing on two corners",
                            "A box falls and turns: its left corner strikes the ground while the right corner "
                            "rests on it; Coulomb friction at both corners.");
    const ex m = S("m"), a = S("a"), b = S("b"), vx = S("v_x"), w = symbol_named("w", "\\omega"), mu = S("mu");
    p.restitution = S("e");
    body box = rigid("box", m, m * (a * a + b * b) / 3, {0, b, 0});
    box.velocity = {vx, -a * w, 0};
    box.angular_velocity[2] = w;
    p.bodies = {ground(-b), box};
    p.contacts = {contact(0, 1, {-a, 0, 0}, {0, 1, 0}), contact(0, 1, {a, 0, 0}, {0, 1, 0})};
    for (contact_spec &c : p.contacts)
        c.set_friction(mu);
    p.illustrate(p.restitution, 0.8);
    p.illustrate(mu, 0.3);
    return p;
}

struct system_class_entry {
    named_class cls;
    std::vector<std::pair<std::string, std::string>> example;
};

const std::vector<system_class_entry> &entries()
{
    static const std::vector<system_class_entry> all = {
        {{"compass-gait",
          "heel strike of a two-legged walker: the swing foot strikes, the stance foot may lift off (plastic, "
          "no slip)",
          compass_gait},
         {{"m", "5"}, {"I_C", "97/240"}, {"a", "2/5"}, {"h", "9/10"}, {"w1", "-6/5"}, {"w2", "2/5"}}},
        {{"three-balls", "a ball strikes two touching equal balls: simultaneous and sequential impacts", three_balls},
         {{"m", "1"}, {"R", "1"}, {"v", "1"}, {"e", "1"}}},
        {{"double-pendulum-struck", "two rods joined by a pin hang from a pivot; a ball strikes the lower end",
          double_pendulum_struck},
         {{"m", "1"}, {"l", "1"}, {"M", "1"}, {"R", "1/10"}, {"v", "1"}, {"e", "1/2"}}},
        {{"two-corner-landing", "a planar box lands with one corner striking and the other resting, friction mu",
          two_corner_landing},
         {{"m", "2"}, {"a", "1"}, {"b", "1/2"}, {"v_x", "3/10"}, {"w", "1"}, {"e", "1/5"}, {"mu", "1/2"}}},
    };
    return all;
}

} // namespace

const std::vector<named_class> &system_classes()
{
    static const std::vector<named_class> all = [] {
        std::vector<named_class> out;
        for (const system_class_entry &e : entries())
            out.push_back(e.cls);
        return out;
    }();
    return all;
}

std::vector<std::pair<std::string, std::string>> system_class_example(const std::string &name)
{
    for (const system_class_entry &e : entries())
        if (e.cls.name == name)
            return e.example;
    return {};
}

lst system_class_example_values(const std::string &name)
{
    lst out;
    for (const system_class_entry &e : entries()) {
        if (e.cls.name != name)
            continue;
        const std::vector<symbol> params = e.cls.build().parameters(); // the class's own symbols
        for (const auto &kv : e.example)
            for (const symbol &s : params)
                if (s.get_name() == kv.first)
                    out.append(s == parse_value(kv.second, true, kv.first));
    }
    return out;
}

} // namespace impactgen
