// The figure of a planar system (system.hpp): bodies through their attachment points,
// grounds, joints, pivots, contacts with their impulses, velocities before impact.
#include "figure/system.hpp"

#include "figure/geometry.hpp"
#include "figure/values.hpp"
#include "names/escape.hpp"

#include <algorithm>
#include <cmath>

namespace impactgen::figure
{
using namespace detail;

namespace
{

struct frame {
    point origin;
    double scale = 1;
    point at(const problem &, const vec3 &v) const
    {
        return {(number(v[0], {}, 0) - origin.x) / scale, (number(v[1], {}, 0) - origin.y) / scale};
    }
};

point dir(const vec3 &v)
{
    return unit2({number(v[0], {}, 0), number(v[1], {}, 0)}, {1, 0});
}

// The world points the figure shows: centres of finite bodies, joints, pivots, contacts.
frame fit_frame(const problem &p)
{
    std::vector<point> pts;
    auto add = [&](const vec3 &v) { pts.push_back({number(v[0], {}, 0), number(v[1], {}, 0)}); };
    for (const body &b : p.bodies)
        if (!b.infinite_mass)
            add(b.position);
    for (const joint &j : p.joints)
        add(j.point);
    for (const pivot &k : p.pivots)
        add(k.point);
    for (const contact_spec &c : p.contacts)
        add(c.point);
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const point &q : pts) {
        x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
    }
    frame f;
    f.origin = {(x0 + x1) / 2, (y0 + y1) / 2};
    double r = 0;
    for (const point &q : pts)
        r = std::max(r, length(q - f.origin));
    f.scale = r > 1e-9 && std::isfinite(r) ? r : 1;
    return f;
}

void add_item(drawing &g, item::kind_t k, role what, int b, const std::string &key, std::vector<point> pts,
              bool closed = false, bool filled = false, bool thin = false, double radius = 0)
{
    item it = make_item(k, what, b, key, std::move(pts));
    it.closed = closed;
    it.filled = filled;
    it.thin = thin;
    it.radius = radius;
    g.items.push_back(it);
}

void add_math_label(drawing &g, point at, place side, role what, int b, const std::string &key, const std::string &text,
                    const std::string &sub)
{
    label l = make_label(at, side, what, b, key);
    l.text = text;
    l.sub = sub;
    l.tex = text + "_{" + sub + "}";
    g.labels.push_back(l);
}

// The convex hull of a few points (monotone chain), counter-clockwise.
std::vector<point> hull(std::vector<point> s)
{
    std::sort(s.begin(), s.end(), [](point a, point b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    if (s.size() < 3)
        return s;
    auto turn = [](point o, point a, point b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
    std::vector<point> h(2 * s.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        while (k >= 2 && turn(h[k - 2], h[k - 1], s[i]) <= 1e-12)
            --k;
        h[k++] = s[i];
    }
    for (std::size_t i = s.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && turn(h[k - 2], h[k - 1], s[i - 1]) <= 1e-12)
            --k;
        h[k++] = s[i - 1];
    }
    h.resize(k - 1);
    return h;
}

// A body of finite mass: the hull of its attachment points and their reflections through C;
// a thin rectangle when they lie on one line, a disc for a particle.
void draw_body(drawing &g, const problem &p, const frame &f, std::size_t b)
{
    const body &B = p.bodies[b];
    const point C = f.at(p, B.position);
    std::vector<point> s;
    for (const joint &j : p.joints)
        if (j.body1 == b || j.body2 == b)
            s.push_back(f.at(p, j.point));
    for (const pivot &k : p.pivots)
        if (k.body == b)
            s.push_back(f.at(p, k.point));
    double nearest = 1e300;
    for (const contact_spec &c : p.contacts)
        if (c.body1 == b || c.body2 == b) {
            s.push_back(f.at(p, c.point));
            nearest = std::min(nearest, length(s.back() - C));
        }
    const int bi = static_cast<int>(b);
    if (B.particle || s.empty()) {
        const double r = std::clamp(nearest < 1e300 ? nearest : 0.08, 0.04, 0.5);
        add_item(g, item::circle, role::body, bi, "body", {C}, false, true, false, r);
        g.bodies.push_back({display_name(B), shape::disc, false, B.at_rest(), p.pivot_of(b) != nullptr});
        return;
    }
    const std::size_t n = s.size();
    for (std::size_t k = 0; k < n; ++k)
        s.push_back(C + (-1.0) * (s[k] - C));
    std::vector<point> h = hull(s);
    shape form = shape::box;
    if (h.size() < 3) { // on one line: a rod of a small width
        point a = s[0], z = s[0];
        for (const point &q : s) {
            if (length(q - C) > length(a - C))
                a = q;
        }
        z = C + (-1.0) * (a - C);
        const point w = 0.025 * perp(unit2(a - z, {1, 0}));
        h = {a + w, z + w, z + (-1.0) * w, a + (-1.0) * w};
        form = shape::rod;
    }
    add_item(g, item::path, role::body, bi, "body", h, true, true);
    g.bodies.push_back({display_name(B), form, false, B.at_rest(), p.pivot_of(b) != nullptr});
}

// A body of infinite mass: a hatched ground through its contact points, on its own side.
void draw_ground(drawing &g, const problem &p, const frame &f, std::size_t b)
{
    const int bi = static_cast<int>(b);
    std::vector<point> pts;
    point n{0, 1};
    double side = -1;
    for (const contact_spec &c : p.contacts)
        if (c.body1 == b || c.body2 == b) {
            pts.push_back(f.at(p, c.point));
            n = dir(c.normal);
            side = c.body1 == b ? -1 : 1;
        }
    g.bodies.push_back({display_name(p.bodies[b]), shape::wall, true, p.bodies[b].at_rest(), false});
    if (pts.empty())
        return;
    const point t = perp(n);
    double lo = 1e300, hi = -1e300;
    for (const point &q : pts) {
        lo = std::min(lo, q.x * t.x + q.y * t.y);
        hi = std::max(hi, q.x * t.x + q.y * t.y);
    }
    const point base = pts[0] + (-(pts[0].x * t.x + pts[0].y * t.y)) * t;
    const point a = base + (lo - 0.25) * t, z = base + (hi + 0.25) * t;
    add_item(g, item::path, role::body, bi, "ground", {a, z});
    const int marks = 8;
    for (int k = 0; k <= marks; ++k) {
        const point q = a + (static_cast<double>(k) / marks) * (z - a);
        add_item(g, item::path, role::body, bi, "hatch", {q, q + (side * 0.07) * n + (-0.05) * t}, false, false, true);
    }
}

void draw_links(drawing &g, const problem &p, const frame &f, const std::vector<vec3> *joint_impulses)
{
    for (std::size_t j = 0; j < p.joints.size(); ++j) {
        const point J = f.at(p, p.joints[j].point);
        const std::string k = std::to_string(j);
        point d{1, 0};
        if (joint_impulses && j < joint_impulses->size())
            d = dir((*joint_impulses)[j]);
        add_item(g, item::arrow, role::pivot_impulse, static_cast<int>(p.joints[j].body2), "J" + k, {J, J + 0.22 * d});
        add_item(g, item::arrow, role::pivot_impulse, static_cast<int>(p.joints[j].body1), "J" + k,
                 {J, J + (-0.22) * d});
        add_item(g, item::circle, role::pivot, -1, "J" + k, {J}, false, false, false, 0.02);
        add_math_label(g, J + 0.22 * d, place::north_east, role::pivot_impulse, -1, "J" + k, "J", k);
    }
    for (std::size_t k = 0; k < p.pivots.size(); ++k) {
        const point E = f.at(p, p.pivots[k].point);
        add_item(g, item::circle, role::pivot, -1, "E" + std::to_string(k), {E}, false, false, false, 0.02);
        add_item(g, item::path, role::pivot, -1, "support", {E, E + point{-0.06, 0.1}, E + point{0.06, 0.1}}, true,
                 false);
        add_math_label(g, E, place::west, role::pivot, -1, "E" + std::to_string(k), "E", std::to_string(k));
    }
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const contact_spec &c = p.contacts[i];
        const point O = f.at(p, c.point), n = dir(c.normal);
        const std::string k = std::to_string(i);
        add_item(g, item::arrow, role::impulse, static_cast<int>(c.body2), "P" + k, {O, O + 0.3 * n});
        if (!p.bodies[c.body1].infinite_mass)
            add_item(g, item::arrow, role::impulse, static_cast<int>(c.body1), "P" + k, {O, O + (-0.3) * n});
        add_item(g, item::circle, role::contact, -1, "O" + k, {O});
        add_math_label(g, O + 0.3 * n, place::east, role::impulse, -1, "P" + k, "P", k);
        add_math_label(g, O, place::south_west, role::contact, -1, "O" + k, "O", k);
    }
}

void draw_centres(drawing &g, const problem &p, const frame &f)
{
    double vmax = 0;
    for (const body &B : p.bodies)
        if (!B.infinite_mass)
            vmax = std::max(vmax, length({number(B.velocity[0], {}, 0), number(B.velocity[1], {}, 0)}));
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const body &B = p.bodies[b];
        if (B.infinite_mass)
            continue;
        const int bi = static_cast<int>(b);
        const point C = f.at(p, B.position);
        const point v{number(B.velocity[0], {}, 0), number(B.velocity[1], {}, 0)};
        if (vmax > 0 && length(v) > 1e-12)
            add_item(g, item::arrow, role::velocity, bi, "v", {C, C + (0.3 / vmax) * v});
        add_item(g, item::circle, role::centre, bi, "C", {C});
        label l = make_label(C, place::west, role::body, bi, "body");
        l.is_name = true;
        l.name = B.name;
        g.labels.push_back(l);
    }
}

} // namespace

std::optional<drawing> draw_system(const problem &p, const std::vector<vec3> *joint_impulses)
{
    if (p.dimension != 2 || !p.is_numeric())
        return std::nullopt;
    drawing g;
    g.dimension = 2;
    const frame f = fit_frame(p);
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        if (p.bodies[b].infinite_mass)
            draw_ground(g, p, f, b);
        else
            draw_body(g, p, f, b);
    }
    draw_links(g, p, f, joint_impulses);
    draw_centres(g, p, f);
    g.impulses_from_answer = joint_impulses != nullptr;
    if (!joint_impulses && !p.joints.empty())
        g.positive.push_back("the joint impulses along +x");
    g.alt = describe_system(p, g);
    return g;
}

std::string describe_system(const problem &p, const drawing &g)
{
    std::string s;
    for (const body_summary &b : g.bodies)
        s += (s.empty() ? "" : ", ") + names::display_text(b.name, 64) + " (" + shape_name(b.form) + ")";
    auto count = [](std::size_t n, const char *one, const char *many) {
        return std::to_string(n) + " " + (n == 1 ? one : many);
    };
    s += ";";
    if (!p.joints.empty())
        s += " " + count(p.joints.size(), "joint", "joints") + ",";
    if (!p.pivots.empty())
        s += " " + count(p.pivots.size(), "pivot", "pivots") + ",";
    return s + " " + count(p.contacts.size(), "contact", "contacts") + " with " +
           (p.contacts.size() == 1 ? "its normal impulse" : "their normal impulses");
}

} // namespace impactgen::figure
