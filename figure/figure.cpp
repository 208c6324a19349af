// draw(): the figure of an impact in figure coordinates (see figure.hpp).
//
// The work is in three steps. (1) Numbers: every symbol left in the problem
// gets an illustrative value and every expression is evaluated to a double,
// with a fallback wherever evaluation fails or is not finite. (2) Scale: the
// world points are divided by their largest coordinate (so differences of
// numbers near the limits of double cannot overflow), moved so that O is the
// origin and divided by the largest distance of a centre or pivot from O.
// (3) Shapes: each body is drawn by what the problem says about it (a
// particle, a sphere, a pinned rod or plate, a free rod, a box, a wall), then
// the decorations of fixed length -- frame, lever arms, impulses, velocities.
#include "figure/figure.hpp"
#include "figure/directions.hpp"
#include "figure/geometry.hpp"
#include "figure/number_text.hpp"
#include "figure/values.hpp"

#include "names/escape.hpp"
#include "symbolic/named_classes.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <sstream>

namespace impactgen::figure
{
using namespace GiNaC;

const char *role_name(role r)
{
    switch (r) {
    case role::body:
        return "body";
    case role::centre:
        return "centre";
    case role::contact:
        return "contact";
    case role::frame_axis:
        return "frame axis";
    case role::lever_arm:
        return "lever arm";
    case role::impulse:
        return "impulse";
    case role::pivot_impulse:
        return "pivot impulse";
    case role::velocity:
        return "velocity";
    case role::pivot:
        return "pivot";
    case role::spin:
        return "spin";
    }
    return "?";
}

const char *shape_name(shape s)
{
    switch (s) {
    case shape::disc:
        return "disc";
    case shape::rod:
        return "rod";
    case shape::plate:
        return "plate";
    case shape::box:
        return "box";
    case shape::wall:
        return "wall";
    case shape::marker:
        return "point";
    }
    return "?";
}

namespace
{
using namespace detail;

// ---------------------------------------------------------------------------
// Steps 2 and 3: the drawing.

constexpr double frame_length = 0.3;    // e_t, e_n, e_b
constexpr double impulse_length = 0.45; // N on each body
constexpr double impulse_gap = 0.07;    // the impulses run beside e_n, on the -e_t side
constexpr double pivot_length = 0.36;   // R
constexpr double velocity_max = 0.5, velocity_min = 0.15;
constexpr double small_radius = 0.12; // a particle at O, an off-normal particle
constexpr double min_radius = 0.05;   // no disc is drawn smaller
constexpr double rod_half_width = 0.035;
constexpr double label_gap = 0.045;
constexpr double cabinet = 0.35355339059327373; // 1/2 cos 45 deg = 1/2 sin 45 deg

class builder
{
public:
    explicit builder(const derivation &d) : d_(d), p_(d.prob) {}
    drawing build();

private:
    const derivation &d_;
    const problem &p_;
    drawing g_;
    exmap values_;
    detail::directions dirs_; // which way the impulses and spins point
    bool planar_ = true;
    v3 n_, t_, b_;                 // the contact frame, unit, world axes
    std::vector<v3> c_;            // centres, figure coordinates (3-D)
    std::vector<v3> e_;            // pivots, figure coordinates (3-D)
    std::vector<point> centre_at_; // where each centre is drawn
    std::vector<bool> has_centre_;
    std::vector<bool> centre_at_o_;  // the problem's C is O (no lever arm)
    std::vector<std::string> index_; // "1", "2", ...
    long double world_unit_ = 1;     // the world length of one figure unit

    point proj(v3 a) const
    {
        if (planar_)
            return {finite(a.x), finite(a.y)};
        return {finite(a.x - cabinet * a.z), finite(a.y - cabinet * a.z)};
    }
    v3 value(const vec3 &v, double fallback = 0) const
    {
        return {number(v[0], values_, fallback), number(v[1], values_, fallback),
                planar_ ? 0 : number(v[2], values_, fallback)};
    }
    double side(std::size_t i) const;

    void add_path(role r, int body, const std::string &key, std::vector<point> pts, bool closed, bool filled,
                  bool dashed = false, bool thin = false)
    {
        item it = make_item(item::path, r, body, key, std::move(pts));
        it.closed = closed;
        it.filled = filled;
        it.dashed = dashed;
        it.thin = thin;
        g_.items.push_back(std::move(it));
    }
    void add_circle(role r, int body, const std::string &key, point c, double radius, bool filled)
    {
        item it = make_item(item::circle, r, body, key, {c});
        it.radius = radius;
        it.filled = filled;
        g_.items.push_back(std::move(it));
    }
    /// An arrow, unless it is too short to see; returns whether it was drawn.
    bool add_arrow(role r, int body, const std::string &key, point from, point to)
    {
        if (!(length(to - from) > 0.02))
            return false;
        g_.items.push_back(make_item(item::arrow, r, body, key, {from, to}));
        return true;
    }
    void add_math(role r, int body, const std::string &key, point at, point direction, const std::string &tex,
                  const std::string &text, const std::string &sub);
    void add_name(int body, point at, place side);

    void body_shape(std::size_t i);
    void pinned_shape(std::size_t i, const pivot *pv, v3 c);
    bool free_rod_shape(std::size_t i, v3 c, double r);
    void wall(std::size_t i);
    void box(std::size_t i, v3 c);
    void rod(std::size_t i, point a, point b);
    void pivots();
    void decorations();
    void lever_arms(std::size_t nb, point o, point t2);
    void frame_axes(point o, point t2);
    void velocity_arrows(std::size_t nb, point o, point t2);
    void contact_impulse(point t2, point n2);
    void friction_impulse(point t2);
    void spins();
    v3 dir(const detail::vec &a) const { return {a[0], a[1], planar_ ? 0 : a[2]}; }
    void centre_marks(std::size_t nb, point o, point t2, point n2);
};

double builder::side(std::size_t i) const
{
    if (i == p_.contact().body1)
        return -1;
    if (i == p_.contact().body2)
        return 1;
    return dot(c_[i], n_) < 0 ? -1 : 1;
}

/// The compass place of a direction in the figure.
place place_of(point dir)
{
    const double l = length(dir);
    if (!(l > 1e-9))
        return place::centre;
    const double a = std::atan2(dir.y, dir.x); // -pi .. pi
    const double pi = 3.14159265358979323846;
    int sector = static_cast<int>(std::lround(a / (pi / 4))); // -4 .. 4
    sector = (sector + 8) % 8;
    static const place by_sector[8] = {place::east, place::north_east, place::north, place::north_west,
                                       place::west, place::south_west, place::south, place::south_east};
    return by_sector[sector];
}

void builder::add_math(role r, int body, const std::string &key, point at, point direction, const std::string &tex,
                       const std::string &text, const std::string &sub)
{
    const point u = unit2(direction, {0, 0});
    label l = make_label(at + label_gap * u, place_of(u), r, body, key);
    l.tex = tex;
    l.text = text;
    l.sub = sub;
    g_.labels.push_back(std::move(l));
}

void builder::add_name(int body, point at, place side)
{
    label l = make_label(at, side, role::body, body, "name" + index_[static_cast<std::size_t>(body)]);
    l.is_name = true;
    l.name = g_.bodies[static_cast<std::size_t>(body)].name;
    g_.labels.push_back(std::move(l));
}

drawing builder::build()
{
    planar_ = p_.dimension == 2;
    g_.dimension = planar_ ? 2 : 3;
    g_.body1 = p_.contact().body1;
    g_.body2 = p_.contact().body2;
    values_ = illustrative_values(p_);
    g_.schematic = !values_.empty();
    dirs_ = detail::directions_of(d_, values_);
    g_.impulses_from_answer = dirs_.from_answer;
    g_.positive = dirs_.positive;

    // The contact frame, orthonormal whatever the derivation's vectors evaluate to.
    n_ = unit(value(d_.n_hat), {0, 1, 0});
    if (planar_)
        n_.z = 0, n_ = unit(n_, {0, 1, 0});
    const v3 t_guess =
        planar_ ? v3{n_.y, -n_.x, 0} : unit(cross(std::abs(n_.z) < 0.9 ? v3{0, 0, 1} : v3{1, 0, 0}, n_), {1, 0, 0});
    v3 t = value(d_.t_dir);
    if (planar_)
        t.z = 0;
    t = t - dot(t, n_) * n_;
    t_ = unit(t, t_guess);
    b_ = planar_ ? v3{} : unit(cross(t_, n_), {0, 0, 1});
    g_.n_hat = unit2(proj(n_), {0, 1});
    g_.t_hat = unit2(proj(t_), {1, 0});
    g_.b_hat = planar_ ? point{} : proj(b_);

    // Scale: world points divided by their largest coordinate, O moved to the
    // origin, then divided by the largest distance of a centre or pivot.
    const std::size_t nb = p_.bodies.size();
    const v3 o_world = value(p_.contact().point);
    std::vector<v3> c_world(nb), e_world(p_.pivots.size());
    double big = max_abs(o_world);
    for (std::size_t i = 0; i < nb; ++i) {
        c_world[i] = value(p_.bodies[i].position);
        big = std::max(big, max_abs(c_world[i]));
    }
    for (std::size_t j = 0; j < p_.pivots.size(); ++j) {
        e_world[j] = value(p_.pivots[j].point);
        big = std::max(big, max_abs(e_world[j]));
    }
    if (!(big > 0) || !std::isfinite(big))
        big = 1;
    const v3 o = (1 / big) * o_world;
    double reach = 0;
    for (std::size_t i = 0; i < nb; ++i)
        if (!p_.bodies[i].infinite_mass)
            reach = std::max(reach, norm((1 / big) * c_world[i] - o));
    for (const v3 &e : e_world)
        reach = std::max(reach, norm((1 / big) * e - o));
    if (!(reach > 1e-250) || !std::isfinite(reach))
        reach = 1;
    auto to_figure = [&](v3 w) {
        const v3 f = (1 / reach) * ((1 / big) * w - o);
        return v3{finite(f.x), finite(f.y), finite(f.z)};
    };
    c_.resize(nb);
    for (std::size_t i = 0; i < nb; ++i)
        c_[i] = to_figure(c_world[i]);
    for (const v3 &e : e_world)
        e_.push_back(to_figure(e));
    world_unit_ = static_cast<long double>(big) * reach;

    // Names and indices: body 1 and body 2 of the contact, then the others.
    index_.assign(nb, "");
    int next = 3;
    for (std::size_t i = 0; i < nb; ++i)
        index_[i] = i == g_.body1 ? "1" : i == g_.body2 ? "2" : std::to_string(next++);
    for (std::size_t i = 0; i < nb; ++i) {
        body_summary s;
        s.name = display_name(p_.bodies[i]);
        s.infinite_mass = p_.bodies[i].infinite_mass;
        s.at_rest = p_.bodies[i].at_rest();
        s.pinned = p_.pivot_of(i) != nullptr;
        g_.bodies.push_back(s);
    }

    centre_at_.assign(nb, point{});
    has_centre_.assign(nb, false);
    centre_at_o_.assign(nb, false);
    for (std::size_t i = 0; i < nb; ++i)
        body_shape(i);
    pivots();
    decorations();
    return g_;
}

// ---------------------------------------------------------------------------
// The bodies.

// A pinned body: a rod through E, C and O when they are in line, else a plate.
void builder::pinned_shape(std::size_t i, const pivot *pv, v3 c)
{
    const body &b = p_.bodies[i];
    const int bi = static_cast<int>(i);
    body_summary &summary = g_.bodies[i];
    // A pinned body: a rod through E, C and O when they are in line, else a
    // plate (the parallelogram E, O, 2C - E, 2C - O, whose centroid is C).
    const v3 e = e_[static_cast<std::size_t>(pv - p_.pivots.data())];
    const v3 ec = c - e, eo = v3{} - e;
    const double lc = norm(ec), lo = norm(eo);
    const bool in_line = lc < 1e-9 || lo < 1e-9 || norm(cross((1 / lc) * ec, (1 / lo) * eo)) < 1e-6;
    centre_at_[i] = proj(c);
    has_centre_[i] = true;
    if (in_line) {
        const v3 u = unit(lo > 1e-9 ? eo : ec, n_);
        const double t_o = dot(eo, u), t_c2 = 2 * dot(ec, u);
        const double lo_end = std::min({0.0, t_o, t_c2}), hi_end = std::max({0.0, t_o, t_c2, 0.2});
        summary.form = shape::rod;
        rod(i, proj(e + lo_end * u), proj(e + hi_end * u));
    } else {
        summary.form = shape::plate;
        const v3 c2 = 2.0 * c;
        add_path(role::body, bi, "body", {proj(e), proj(v3{}), proj(c2 - e), proj(c2)}, true, true);
        if (!b.numbered) {
            const double low = std::min({proj(e).y, 0.0, proj(c2 - e).y, proj(c2).y});
            add_name(bi, {proj(c).x, low - label_gap}, place::south);
        }
    }
}

// A free rod with its end at O, when the planar moment about C is a uniform rod's (true: drawn).
bool builder::free_rod_shape(std::size_t i, v3 c, double r)
{
    const body &b = p_.bodies[i];
    body_summary &summary = g_.bodies[i];
    const double m = number(b.mass, values_, 0), inertia = number(b.inertia[2][2], values_, 0);
    const long double length_world = static_cast<long double>(r) * world_unit_;
    const long double rod_moment = static_cast<long double>(m) * length_world * length_world / 3;
    if (m > 0 && inertia > 0 && rod_moment > 0 &&
        std::abs(static_cast<long double>(inertia) - rod_moment) <= 1e-9L * rod_moment) {
        summary.form = shape::rod;
        centre_at_[i] = proj(c);
        has_centre_[i] = true;
        rod(i, proj(v3{}), proj(2.0 * c));
        return true;
    }
    return false;
}

void builder::body_shape(std::size_t i)
{
    const body &b = p_.bodies[i];
    const int bi = static_cast<int>(i);
    body_summary &summary = g_.bodies[i];
    if (b.infinite_mass) {
        summary.form = shape::wall;
        wall(i);
        return;
    }
    const v3 c = c_[i];
    const double r = norm(c);
    const double s = side(i);
    const bool on_normal = r > 1e-9 && norm(cross((1 / r) * c, n_)) < 1e-6;
    centre_at_o_[i] = r <= 1e-9;
    auto disc = [&](v3 centre, double radius) {
        summary.form = shape::disc;
        const point at = proj(centre);
        add_circle(role::body, bi, "body", at, std::max(radius, min_radius), true);
        centre_at_[i] = at;
        has_centre_[i] = true;
        if (!b.numbered) {
            // The name under the disc, or over it when O is below (a ball on the floor).
            const point out = unit2(at, proj((s * 1.0) * n_));
            const point dir = out.y > 0.5 ? point{0, 1} : point{0, -1};
            add_name(bi, at + (std::max(radius, min_radius) + label_gap) * dir, place_of(dir));
        }
    };
    const pivot *pv = p_.pivot_of(i);
    if (b.particle) {
        if (on_normal)
            disc(c, r);
        else if (r <= 1e-9)
            disc((s * small_radius) * n_, small_radius); // a particle at O: a small ball touching O
        else
            disc(c, small_radius);
        return;
    }
    if (pv) {
        pinned_shape(i, pv, c);
        return;
    }
    if (on_normal) {
        disc(c, r);
        return;
    }
    if (r <= 1e-9) {
        disc((s * small_radius) * n_, small_radius);
        return;
    }
    // A free rod with its end at O: the planar moment about C is that of a
    // uniform rod of length 2|CO|, I = m (2|CO|)^2 / 12.
    if (planar_ && free_rod_shape(i, c, r))
        return;
    centre_at_[i] = proj(c);
    has_centre_[i] = true;
    if (s * dot(c, n_) > 1e-6 * r) {
        summary.form = shape::box;
        box(i, c);
        return;
    }
    // A body whose centre is not on its own side of the tangent plane: a marker.
    summary.form = shape::marker;
    const point at = proj(c);
    const double h = 0.06;
    add_path(role::body, bi, "body", {at + point{-h, -h}, at + point{h, -h}, at + point{h, h}, at + point{-h, h}}, true,
             true);
    if (!b.numbered)
        add_name(bi, at - point{0, h + label_gap}, place::south);
}

void builder::rod(std::size_t i, point a, point b)
{
    const int bi = static_cast<int>(i);
    const point u = unit2(b - a, {0, -1});
    const point w = rod_half_width * perp(u);
    const point a2 = a - rod_half_width * u, b2 = b + rod_half_width * u;
    add_path(role::body, bi, "body", {a2 - w, b2 - w, b2 + w, a2 + w}, true, true);
    if (!p_.bodies[i].numbered) {
        // The name beside the rod, four fifths of the way from the end at O,
        // on the body's own side of the tangent plane (clear of the impulses).
        const bool b_far = length(b) >= length(a);
        const point near_end = b_far ? a : b, far_end = b_far ? b : a;
        const point along = near_end + 0.8 * (far_end - near_end);
        const point n2 = proj(n_);
        point out = perp(u);
        if (out.x * n2.x + out.y * n2.y < 0 ? side(i) > 0 : side(i) < 0)
            out = -1.0 * out;
        add_name(bi, along + (rod_half_width + label_gap) * out, place_of(out));
    }
}

void builder::box(std::size_t i, v3 c)
{
    const int bi = static_cast<int>(i);
    // Half extents along e_t, e_n, e_b: one face in the tangent plane through O,
    // wide enough that O lies on it.
    const double ct = dot(c, t_), cn = dot(c, n_), cb = dot(c, b_);
    const double hn = std::abs(cn);
    const double ht = std::max({1.3 * std::abs(ct), 0.6 * hn, 0.2});
    const double hb = std::max({1.3 * std::abs(cb), 0.6 * hn, 0.2});
    if (planar_) {
        const v3 a = ht * t_, h = hn * n_;
        add_path(role::body, bi, "body", {proj(c - a - h), proj(c + a - h), proj(c + a + h), proj(c - a + h)}, true,
                 true);
    } else {
        // The faces a viewer of the cabinet projection sees: outward normal
        // towards the direction (k, k, 1) that projects to a point.
        const v3 view{cabinet, cabinet, 1};
        const v3 axis[3] = {ht * t_, hn * n_, hb * b_};
        for (int f = 0; f < 3; ++f)
            for (double sgn : {-1.0, 1.0}) {
                const v3 out = sgn * axis[f];
                if (dot(out, view) <= 1e-12)
                    continue;
                const v3 u = axis[(f + 1) % 3], w = axis[(f + 2) % 3];
                const v3 centre = c + out;
                add_path(role::body, bi, "body",
                         {proj(centre - u - w), proj(centre + u - w), proj(centre + u + w), proj(centre - u + w)}, true,
                         true);
            }
    }
    if (!p_.bodies[i].numbered) {
        double low = 1e9, x = proj(c).x;
        for (const item &it : g_.items)
            if (it.body == bi && it.what == role::body)
                for (const point &q : it.points)
                    low = std::min(low, q.y);
        add_name(bi, {x, low - label_gap}, place::south);
    }
}

void builder::wall(std::size_t i)
{
    const int bi = static_cast<int>(i);
    const double s = side(i);
    const double w = 0.55, hatch = 0.09;
    const v3 into = (s * hatch) * n_ - (0.6 * hatch) * t_;
    std::vector<point> strokes;
    if (planar_) {
        add_path(role::body, bi, "body", {proj(-w * t_), proj(w * t_)}, false, false);
        for (int k = 0; k <= 10; ++k) {
            const v3 base = (-w + 2 * w * k / 10.0) * t_;
            add_path(role::body, bi, "hatch", {proj(base), proj(base + into)}, false, false, false, true);
        }
    } else {
        const v3 a = w * t_, bb = w * b_;
        // Unfilled: the body that touches it stays visible through it.
        add_path(role::body, bi, "body", {proj(-1.0 * a - bb), proj(a - bb), proj(a + bb), proj(bb - a)}, true, false);
        // Hatching under the edge nearer the viewer.
        const v3 front = dot(b_, v3{cabinet, cabinet, 1}) >= 0 ? bb : -1.0 * bb;
        for (int k = 0; k <= 10; ++k) {
            const v3 base = front + (-w + 2 * w * k / 10.0) * t_;
            add_path(role::body, bi, "hatch", {proj(base), proj(base + into)}, false, false, false, true);
        }
    }
    if (!p_.bodies[i].numbered) {
        const point end = proj(w * t_ + (s * (hatch + 0.05)) * n_);
        add_name(bi, end, place_of(proj(t_)));
    }
}

// ---------------------------------------------------------------------------
// Pivots and decorations.

void builder::pivots()
{
    for (std::size_t j = 0; j < p_.pivots.size(); ++j) {
        const pivot &pv = p_.pivots[j];
        if (pv.body >= p_.bodies.size())
            continue;
        const std::string k = p_.pivots.size() == 1 ? "" : std::to_string(j + 1);
        const point e = proj(e_[j]);
        const point away = unit2(e - proj(c_[pv.body]), {0, 1});
        const point across = perp(away);
        // The pin: a triangle from E to a hatched base, away from the body.
        const double h = 0.1, half = 0.06;
        const point base = e + h * away;
        add_path(role::pivot, -1, "support" + k, {e, base + half * across, base - half * across}, true, false);
        add_path(role::pivot, -1, "ground" + k, {base + (1.6 * half) * across, base - (1.6 * half) * across}, false,
                 false);
        for (int q = 0; q <= 4; ++q) {
            const point from = base + (1.6 * half * (1 - q / 2.0)) * across;
            add_path(role::pivot, -1, "hatch", {from, from + 0.05 * away + 0.04 * across}, false, false, false, true);
        }
        add_circle(role::pivot, -1, "E" + k, e, 0.022, false);
        // R: the pivot impulse on its body, along the answer (or its positive sense); none when 0.
        const v3 r = j < dirs_.pivot.size() ? dir(dirs_.pivot[j]) : v3{};
        const point tip = e + pivot_length * unit2(proj(r), {0, 0});
        if (add_arrow(role::pivot_impulse, static_cast<int>(pv.body), "R" + k, e, tip))
            add_math(role::pivot_impulse, static_cast<int>(pv.body), "R" + k, tip, tip - e, k.empty() ? "R" : "R_" + k,
                     "R", k);
        const point label_dir = unit2(-1.0 * unit2(tip - e, {0, 0}) - away, across);
        add_math(role::pivot, -1, "E" + k, e, label_dir, k.empty() ? "E" : "E_" + k, "E", k);
    }
}

// Lever arms r_i from C_i to O, dashed, labelled two thirds of the way from O.
void builder::lever_arms(std::size_t nb, point o, point t2)
{
    for (std::size_t i = 0; i < nb; ++i) {
        if (!has_centre_[i] || p_.bodies[i].infinite_mass || centre_at_o_[i])
            continue;
        const point c = centre_at_[i];
        if (length(c) < 0.03)
            continue;
        const int bi = static_cast<int>(i);
        add_path(role::lever_arm, bi, "r" + index_[i], {c, o}, false, false, true);
        point across = unit2(perp(c), {1, 0});
        if (across.x * t2.x + across.y * t2.y < 0)
            across = -1.0 * across;
        // r_C1O = O - C1: from the centre of mass to the contact point, as the text defines r_PQ = Q - P
        add_math(role::lever_arm, bi, "r" + index_[i], (2.0 / 3.0) * c, across,
                 "\\underline{r}_{C_{" + index_[i] + "}O}", "r", "C" + index_[i] + "O");
    }
}

// The contact frame at O.
void builder::frame_axes(point o, point t2)
{
    const point et = proj(frame_length * t_), en = proj(frame_length * n_);
    add_arrow(role::frame_axis, -1, "e_t", o, et);
    add_math(role::frame_axis, -1, "e_t", et, et, "\\hat{e}_t", "\u00ea", "t");
    add_arrow(role::frame_axis, -1, "e_n", o, en);
    add_math(role::frame_axis, -1, "e_n", en, unit2(en, {0, 1}) + 0.9 * t2, "\\hat{e}_n", "\u00ea", "n");
    if (!planar_) {
        const point eb = proj(frame_length * b_);
        if (add_arrow(role::frame_axis, -1, "e_b", o, eb))
            add_math(role::frame_axis, -1, "e_b", eb, eb, "\\hat{e}_b", "\u00ea", "b");
    }
}

// Velocities before impact at the centres (a wall's on the wall), scaled so the fastest is velocity_max long.
void builder::velocity_arrows(std::size_t nb, point o, point t2)
{
    std::vector<v3> v(nb);
    double vbig = 0;
    for (std::size_t i = 0; i < nb; ++i) {
        v[i] = value(p_.bodies[i].velocity);
        vbig = std::max(vbig, max_abs(v[i]));
    }
    if (vbig > 0 && std::isfinite(vbig)) {
        double fastest = 0;
        for (v3 &x : v) {
            x = (1 / vbig) * x;
            fastest = std::max(fastest, norm(x));
        }
        for (std::size_t i = 0; i < nb; ++i) {
            const double speed = norm(v[i]);
            if (!(speed > 1e-12 * fastest) || !(fastest > 0))
                continue;
            const double len = std::clamp(velocity_max * speed / fastest, velocity_min, velocity_max);
            const v3 u = (1 / speed) * v[i];
            point from, to;
            const point along = proj(len * u);
            if (p_.bodies[i].infinite_mass) {
                from = proj((-0.75 * 0.55) * t_);
                to = from + along;
            } else if (has_centre_[i]) {
                // At C: from C, or into C when the body moves towards O (the
                // arrow then stays clear of the contact).
                const point c = centre_at_[i];
                const point to_o = unit2(o - c, {0, 0});
                const point dir = unit2(along, {0, 0});
                if (dir.x * to_o.x + dir.y * to_o.y > 0.25)
                    from = c - along, to = c;
                else
                    from = c, to = c + along;
            } else {
                continue;
            }
            const int bi = static_cast<int>(i);
            if (add_arrow(role::velocity, bi, "v" + index_[i], from, to)) {
                // The label beside the arrow's middle, on the side away from O.
                const point mid = 0.5 * (from + to), side_a = unit2(perp(to - from), {0, 1});
                const double da = length(mid + 0.1 * side_a), db = length(mid - 0.1 * side_a);
                point side = da > db ? side_a : -1.0 * side_a;
                if (std::abs(da - db) < 1e-6) // a radial arrow: the +e_t side, clear of the impulses
                    side = side_a.x * t2.x + side_a.y * t2.y >= 0 ? side_a : -1.0 * side_a;
                add_math(role::velocity, bi, "v" + index_[i], mid, side, "\\underline{v}_{C_{" + index_[i] + "}}", "v",
                         "C" + index_[i]); // the velocity of the centre of mass, v_C1 as the text names it
            }
        }
    }
}

// The contact impulse: N e_n on body 2, -N e_n on body 1, beside e_n.
void builder::contact_impulse(point t2, point n2)
{
    const v3 foot = (-impulse_gap) * t_;
    const point f = proj(foot);
    const point up = proj(foot + impulse_length * n_), down = proj(foot - impulse_length * n_);
    const point aside = -1.0 * t2;
    if (add_arrow(role::impulse, static_cast<int>(g_.body2), "N2", f, up))
        add_math(role::impulse, static_cast<int>(g_.body2), "N2", up - 0.5 * label_gap * unit2(up - f, n2), aside, "N",
                 "N", "");
    if (add_arrow(role::impulse, static_cast<int>(g_.body1), "N1", f, down))
        add_math(role::impulse, static_cast<int>(g_.body1), "N1", down - 0.5 * label_gap * unit2(down - f, n2), aside,
                 "N", "N", "");
}

// The friction impulse: F on body 2 (along the answer's tangential impulse, or +e_t for
// symbols), -F on body 1, from points just inside each body beside O.
void builder::friction_impulse(point t2)
{
    const v3 f = dir(dirs_.friction);
    if (!(norm(f) > 0))
        return;
    for (const int s : {1, -1}) {
        const std::size_t body = s > 0 ? g_.body2 : g_.body1;
        const point from = proj((s * 2 * impulse_gap) * n_), to = from + proj((s * impulse_length) * f);
        const std::string key = s > 0 ? "F2" : "F1";
        if (add_arrow(role::impulse, static_cast<int>(body), key, from, to))
            add_math(role::impulse, static_cast<int>(body), key, to, unit2(to - from, t2), "F", "F", "");
    }
}

// Each spin before impact: in the plane a turning arrow of 240 degrees about C, open towards
// O (the lever arm), its head in the sense of the spin; in 3-D the angular velocity vector at C.
void builder::spins()
{
    constexpr double spin_radius = 0.15, spin_vector = 0.3;
    for (std::size_t i = 0; i < p_.bodies.size() && i < dirs_.spin.size(); ++i) {
        const v3 w{dirs_.spin[i][0], dirs_.spin[i][1], dirs_.spin[i][2]}; // in the plane: along z
        if (!has_centre_[i] || !(norm(w) > 0))
            continue;
        const int bi = static_cast<int>(i);
        const point c = centre_at_[i];
        const std::string key = "w" + index_[i], tex = "\\omega_{" + index_[i] + "}";
        if (!planar_) {
            const point tip = c + proj(spin_vector * w);
            if (add_arrow(role::spin, bi, key, c, tip))
                add_math(role::spin, bi, key, tip, unit2(tip - c, {0, 1}), tex, "\u03c9", index_[i]);
            continue;
        }
        const point to_o = unit2(point{0, 0} - c, g_.n_hat);
        const double gap = std::atan2(to_o.y, to_o.x), sense = w.z > 0 ? 1.0 : -1.0;
        const double pi = 3.14159265358979323846;
        std::vector<point> arc;
        for (int k = 0; k <= 24; ++k) {
            const double a = gap + sense * (pi / 3 + k * (4 * pi / 3) / 24);
            arc.push_back(c + spin_radius * point{std::cos(a), std::sin(a)});
        }
        const point head = arc.back();
        add_arrow(role::spin, bi, key, arc[arc.size() - 4], head);
        arc.resize(arc.size() - 3);
        add_path(role::spin, bi, key, arc, false, false);
        // The label beyond the head, away from C.
        const point out = unit2(head - c, {0, 1});
        add_math(role::spin, bi, key, head + label_gap * out, out, tex, "\u03c9", index_[i]);
    }
}

std::string directions_note_of(const drawing &g)
{
    if (g.positive.empty())
        return "";
    std::string list;
    for (std::size_t k = 0; k < g.positive.size(); ++k)
        list += (k ? (k + 1 == g.positive.size() ? " and " : ", ") : "") + g.positive[k];
    return " Drawn in the senses in which they count positive (" + list +
           "): the sign of each value says which way it acts.";
}

// Centres on top of the lines, then O.
void builder::centre_marks(std::size_t nb, point o, point t2, point n2)
{
    for (std::size_t i = 0; i < nb; ++i) {
        if (!has_centre_[i])
            continue;
        const int bi = static_cast<int>(i);
        const point c = centre_at_[i];
        add_circle(role::centre, bi, "C" + index_[i], c, 0.03, false);
        // The label where nothing starts: away from the velocity and from O.
        point away{0, 0};
        for (const item &it : g_.items)
            if (it.kind == item::arrow && it.what == role::velocity && it.body == bi) {
                // The arrow lies on the side of its end that is not at C.
                const point other = length(it.points[1] - c) > length(it.points[0] - c) ? it.points[1] : it.points[0];
                away = away - unit2(other - c, {0, 0});
            }
        away = away - unit2(o - c, {0, 0});
        if (length(away) < 1e-6) // arrow and lever arm in line: beside them, on the -e_t side
            away = -1.0 * t2;
        add_math(role::centre, bi, "C" + index_[i], c, away, "C_{" + index_[i] + "}", "C", index_[i]);
    }
    add_circle(role::contact, -1, "O", o, 0.025, true);
    const point o_dir = unit2(t2 - n2, {1, -1});
    add_math(role::contact, -1, "O", o, o_dir, "O", "O", "");
}

void builder::decorations()
{
    const std::size_t nb = p_.bodies.size();
    const point o{0, 0};
    const point t2 = g_.t_hat, n2 = proj(n_);

    lever_arms(nb, o, t2);

    // The contact frame at O.
    frame_axes(o, t2);

    // Velocities before impact at the centres (a wall's on the wall), scaled
    // so that the fastest is velocity_max long; none shorter than velocity_min.
    velocity_arrows(nb, o, t2);

    // The contact impulse: N e_n on body 2, -N e_n on body 1, beside e_n; the friction
    // impulse F on body 2 and -F on body 1 at O, each just inside its body.
    contact_impulse(t2, n2);
    friction_impulse(t2);

    // Spins before impact, about the centres.
    spins();

    // Centres on top of the lines, then O.
    centre_marks(nb, o, t2, n2);
}

// ---------------------------------------------------------------------------
// The normal as text for describe().

std::string rational_text(const numeric &q)
{
    std::ostringstream out;
    out << q;
    return out.str();
}

std::string normal_text(const derivation &d)
{
    const int dim = d.prob.dimension == 2 ? 2 : 3;
    bool rational = true, numeric_all = true;
    for (int c = 0; c < dim; ++c) {
        if (!is_a<numeric>(d.n_hat[c])) {
            rational = false;
            if (!symbols_in(d.n_hat[c]).empty())
                numeric_all = false;
            // a constant whose float evaluation divides by a cancelled 0 is still a number
            // (number() below then evaluates it, or falls back)
        } else if (!ex_to<numeric>(d.n_hat[c]).is_rational()) {
            rational = false;
        }
    }
    if (!numeric_all)
        return "n (symbolic)";
    std::string out = "(";
    for (int c = 0; c < dim; ++c) {
        if (c)
            out += ", ";
        std::string piece;
        if (rational)
            piece = rational_text(ex_to<numeric>(d.n_hat[c]));
        if (!rational || piece.size() > 12)
            piece = detail::decimal(number(d.n_hat[c], {}, 0));
        out += piece;
    }
    return out + ")";
}

} // namespace

GiNaC::exmap schematic_values(const problem &p)
{
    return illustrative_values(p);
}

std::string directions_note(const drawing &g)
{
    return directions_note_of(g);
}

drawing draw(const derivation &d)
{
    builder b(d);
    drawing g = b.build();
    g.normal_text = normal_text(d);
    return g;
}

} // namespace impactgen::figure
