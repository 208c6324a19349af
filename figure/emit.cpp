// The printers of a drawing: TikZ, SVG and one line of alternative text.
//
// Both pictures are laid out the same way: the figure coordinates are scaled
// by the largest factor with which the geometry and an estimate of every
// label's box fit a fixed frame (8 cm x 7 cm for TikZ, 520 x 440 px for SVG),
// so a tiny or a huge problem gives a figure of the same size. Every number is
// printed with three decimals by detail::decimal(), independent of the locale.
// Body names, the only text from the problem file, go through names/escape.hpp
// (latex_text for TikZ, xml_text for SVG), after display_text() has made them
// one visible line of at most 24 bytes.
#include "figure/figure.hpp"
#include "figure/number_text.hpp"

#include "names/escape.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace impactgen::figure
{

namespace detail
{

std::string decimal(double v)
{
    if (!std::isfinite(v))
        v = 0;
    v = std::clamp(v, -1e9, 1e9);
    long long m = std::llround(v * 1000);
    const std::string sign = m < 0 ? "-" : "";
    if (m < 0)
        m = -m;
    std::string frac = std::to_string(m % 1000);
    while (frac.size() < 3)
        frac = "0" + frac;
    return sign + std::to_string(m / 1000) + "." + frac;
}

} // namespace detail

namespace
{

using detail::decimal;

/// A body name as a label shows it: one visible line, cut to 24 bytes.
std::string shown_name(const std::string &raw)
{
    return names::display_text(raw, 24);
}

/// Code points in UTF-8 text (continuation bytes do not count).
std::size_t glyphs(const std::string &s)
{
    std::size_t n = 0;
    for (unsigned char c : s)
        if ((c & 0xC0) != 0x80)
            ++n;
    return n;
}

/// The size of a label's box in output units.
struct text_metrics {
    double char_width, subscript_width, height;
};

/// Box of a label relative to its anchor point (y up): lo/hi in x and y.
struct box {
    double x0, x1, y0, y1;
};

box label_box(const label &l, const text_metrics &m)
{
    const double w = l.is_name ? static_cast<double>(glyphs(shown_name(l.name))) * m.char_width
                               : static_cast<double>(glyphs(l.text)) * m.char_width +
                                     static_cast<double>(glyphs(l.sub)) * m.subscript_width;
    const double h = m.height;
    switch (l.side) {
    case place::east:
        return {0, w, -h / 2, h / 2};
    case place::west:
        return {-w, 0, -h / 2, h / 2};
    case place::north:
        return {-w / 2, w / 2, 0, h};
    case place::south:
        return {-w / 2, w / 2, -h, 0};
    case place::north_east:
        return {0, w, 0, h};
    case place::north_west:
        return {-w, 0, 0, h};
    case place::south_east:
        return {0, w, -h, 0};
    case place::south_west:
        return {-w, 0, -h, 0};
    case place::centre:
        break;
    }
    return {-w / 2, w / 2, -h / 2, h / 2};
}

/// Output = figure * scale + shift (y up); the picture spans [0, width] x [0, height].
struct layout {
    double scale = 1, shift_x = 0, shift_y = 0, width = 0, height = 0;
    point out(point p) const { return {p.x * scale + shift_x, p.y * scale + shift_y}; }
};

point operator+(point a, point b)
{
    return {a.x + b.x, a.y + b.y};
}

/// Every point the geometry reaches, with a circle's extent.
std::vector<box> geometry_extents(const drawing &g, std::vector<point> &at)
{
    std::vector<box> r;
    for (const item &it : g.items) {
        if (it.kind == item::circle) {
            const bool marker = it.what == role::centre || it.what == role::contact || it.what == role::pivot;
            const double rad = marker ? 0 : it.radius;
            for (point q : {point{-rad, 0}, point{rad, 0}, point{0, -rad}, point{0, rad}}) {
                at.push_back(it.points[0] + q);
                r.push_back({0, 0, 0, 0});
            }
            continue;
        }
        for (const point &q : it.points) {
            at.push_back(q);
            r.push_back({0, 0, 0, 0});
        }
    }
    return r;
}

layout fit(const drawing &g, double max_width, double max_height, double margin, const text_metrics &m)
{
    std::vector<point> at;
    std::vector<box> extent = geometry_extents(g, at);
    for (const label &l : g.labels) {
        at.push_back(l.at);
        extent.push_back(label_box(l, m));
    }
    auto span = [&](double k, bool x_axis, double &lo_out) {
        double lo = 1e300, hi = -1e300;
        for (std::size_t i = 0; i < at.size(); ++i) {
            const double c = (x_axis ? at[i].x : at[i].y) * k;
            lo = std::min(lo, c + (x_axis ? extent[i].x0 : extent[i].y0));
            hi = std::max(hi, c + (x_axis ? extent[i].x1 : extent[i].y1));
        }
        if (at.empty())
            lo = hi = 0;
        lo_out = lo;
        return hi - lo;
    };
    // The largest scale at which both spans fit (they grow with the scale).
    double lo_x = 0, lo_y = 0, k_low = 0, k_high = 1e6;
    for (int i = 0; i < 80; ++i) {
        const double k = 0.5 * (k_low + k_high);
        if (span(k, true, lo_x) <= max_width && span(k, false, lo_y) <= max_height)
            k_low = k;
        else
            k_high = k;
    }
    layout out;
    out.scale = k_low > 0 ? k_low : 1e-3;
    const double w = span(out.scale, true, lo_x), h = span(out.scale, false, lo_y);
    out.shift_x = margin - lo_x;
    out.shift_y = margin - lo_y;
    out.width = w + 2 * margin;
    out.height = h + 2 * margin;
    return out;
}

bool is_vector_label(const label &l)
{
    return l.what == role::velocity || l.what == role::lever_arm;
}

// ---------------------------------------------------------------------------
// TikZ.

const char *tikz_anchor(place p)
{
    switch (p) {
    case place::east:
        return "west";
    case place::west:
        return "east";
    case place::north:
        return "south";
    case place::south:
        return "north";
    case place::north_east:
        return "south west";
    case place::north_west:
        return "south east";
    case place::south_east:
        return "north west";
    case place::south_west:
        return "north east";
    case place::centre:
        break;
    }
    return "center";
}

const char *tikz_colour(role r)
{
    switch (r) {
    case role::frame_axis:
        return "blue!70!black";
    case role::impulse:
        return "red!75!black";
    case role::pivot_impulse:
        return "orange!85!black";
    case role::velocity:
        return "green!45!black";
    case role::lever_arm:
        return "black!60";
    case role::spin:
        return "violet!80!black";
    default:
        return "black";
    }
}

std::string tikz_point(const layout &L, point p)
{
    const point q = L.out(p);
    return "(" + decimal(q.x) + "," + decimal(q.y) + ")";
}

std::string tikz_fill(const drawing &g, int body)
{
    return body >= 0 && static_cast<std::size_t>(body) == g.body2 ? "black!16" : "black!7";
}

} // namespace

std::string to_tikz(const drawing &g)
{
    // cm; \small in an 11pt article: about 0.2 cm a letter, 0.45 cm a line.
    const text_metrics m{0.22, 0.16, 0.45};
    const layout L = fit(g, 8.0, 7.0, 0.1, m);
    std::string s = "\\begin{tikzpicture}[line cap=round, line join=round, >=stealth, font=\\small]\n";
    // The frame the layout reserved, so the picture's size does not depend on the fonts.
    s += "\\path (0,0) (" + decimal(L.width) + "," + decimal(L.height) + ");\n";
    for (const item &it : g.items) {
        if (it.kind == item::circle) {
            const std::string c = tikz_point(L, it.points[0]);
            if (it.what == role::centre) {
                // The centre-of-mass symbol: a circle with two quarters filled.
                s += "\\draw[fill=white] " + c + " circle (2.4pt);\n";
                s += "\\fill " + c + " -- ++(2.4pt,0) arc (0:90:2.4pt) -- cycle;\n";
                s += "\\fill " + c + " -- ++(-2.4pt,0) arc (180:270:2.4pt) -- cycle;\n";
            } else if (it.what == role::contact) {
                s += "\\fill " + c + " circle (1.7pt);\n";
            } else if (it.what == role::pivot) {
                s += "\\draw[fill=white] " + c + " circle (1.8pt);\n";
            } else {
                s += std::string("\\draw[thick") + (it.filled ? ", fill=" + tikz_fill(g, it.body) : "") + "] " + c +
                     " circle (" + decimal(it.radius * L.scale) + ");\n";
            }
            continue;
        }
        if (it.points.size() < 2)
            continue;
        std::string style;
        if (it.kind == item::arrow) {
            style = std::string("->, ") +
                    (it.what == role::impulse || it.what == role::pivot_impulse ? "very thick" : "thick") + ", " +
                    tikz_colour(it.what);
        } else if (it.what == role::body) {
            style = it.thin ? "thin" : (it.closed ? "thick" : "very thick");
            if (it.filled)
                style += ", fill=" + tikz_fill(g, it.body);
        } else if (it.what == role::pivot) {
            style = it.thin ? "thin" : "thick";
            if (it.closed)
                style += ", fill=white";
        } else {
            style = std::string(it.what == role::spin ? "thick, " : "") + tikz_colour(it.what);
        }
        if (it.dashed)
            style += ", dashed";
        s += "\\draw[" + style + "] ";
        for (std::size_t k = 0; k < it.points.size(); ++k)
            s += (k ? " -- " : "") + tikz_point(L, it.points[k]);
        s += it.closed ? " -- cycle;\n" : ";\n";
    }
    for (const label &l : g.labels) {
        s += "\\node[anchor=" + std::string(tikz_anchor(l.side)) + ", inner sep=1.5pt";
        if (l.what != role::body && l.what != role::centre && l.what != role::contact && l.what != role::pivot)
            s += std::string(", text=") + tikz_colour(l.what);
        s += "] at " + tikz_point(L, l.at) + " {";
        // Math labels are this library's own LaTeX; a name is escaped.
        s += l.is_name ? names::latex_text(shown_name(l.name)) : "$" + l.tex + "$";
        s += "};\n";
    }
    s += "\\end{tikzpicture}";
    return s;
}

namespace
{

// ---------------------------------------------------------------------------
// SVG.

const char *svg_colour(role r)
{
    switch (r) {
    case role::frame_axis:
        return "#1f3fb0";
    case role::impulse:
        return "#b3141b";
    case role::pivot_impulse:
        return "#d46a00";
    case role::velocity:
        return "#1d7a2c";
    case role::lever_arm:
        return "#666666";
    case role::spin:
        return "#6a1b8a";
    default:
        return "#000000";
    }
}

std::string svg_fill(const drawing &g, int body)
{
    return body >= 0 && static_cast<std::size_t>(body) == g.body2 ? "#d6d6d6" : "#ededed";
}

/// SVG's y grows downwards.
point svg_out(const layout &L, point p)
{
    const point q = L.out(p);
    return {q.x, L.height - q.y};
}

std::string svg_points(const std::vector<point> &pts)
{
    std::string s;
    for (std::size_t k = 0; k < pts.size(); ++k)
        s += (k ? " " : "") + decimal(pts[k].x) + "," + decimal(pts[k].y);
    return s;
}
// A circle item: a centre's quartered disc, the contact point, a pivot or a body's disc.
void svg_circle(std::string &s, const drawing &g, const layout &L, const item &it)
{
    const point c = svg_out(L, it.points[0]);
    const std::string cx = decimal(c.x), cy = decimal(c.y);
    if (it.what == role::centre) {
        const double r = 3.4;
        const std::string rs = decimal(r);
        s += "<circle cx=\"" + cx + "\" cy=\"" + cy + "\" r=\"" + rs +
             "\" fill=\"#ffffff\" stroke=\"#000000\" stroke-width=\"1\"/>\n";
        // Two quarters filled: upper right and lower left (y down).
        s += "<path d=\"M" + cx + "," + cy + " L" + decimal(c.x + r) + "," + cy + " A" + rs + "," + rs + " 0 0 0 " +
             cx + "," + decimal(c.y - r) + " Z M" + cx + "," + cy + " L" + decimal(c.x - r) + "," + cy + " A" + rs +
             "," + rs + " 0 0 0 " + cx + "," + decimal(c.y + r) + " Z\" fill=\"#000000\"/>\n";
    } else if (it.what == role::contact) {
        s += "<circle cx=\"" + cx + "\" cy=\"" + cy + "\" r=\"2.6\" fill=\"#000000\"/>\n";
    } else if (it.what == role::pivot) {
        s += "<circle cx=\"" + cx + "\" cy=\"" + cy +
             "\" r=\"2.8\" fill=\"#ffffff\" stroke=\"#000000\" stroke-width=\"1.2\"/>\n";
    } else {
        s += "<circle cx=\"" + cx + "\" cy=\"" + cy + "\" r=\"" + decimal(it.radius * L.scale) + "\" fill=\"" +
             (it.filled ? svg_fill(g, it.body) : "none") + "\" stroke=\"#000000\" stroke-width=\"1.4\"/>\n";
    }
}

// An arrow item: a line to the foot of the head, then the head as a polygon.
void svg_arrow(std::string &s, const item &it, const std::vector<point> &pts)
{
    const point a = pts[0], b = pts[1];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (!(len > 0.5))
        return;
    const double ux = (b.x - a.x) / len, uy = (b.y - a.y) / len;
    const bool heavy = it.what == role::impulse || it.what == role::pivot_impulse;
    const double head = std::min(heavy ? 11.0 : 9.0, 0.6 * len), half = heavy ? 4.2 : 3.4;
    const point foot{b.x - head * ux, b.y - head * uy};
    const char *col = svg_colour(it.what);
    s += "<line x1=\"" + decimal(a.x) + "\" y1=\"" + decimal(a.y) + "\" x2=\"" + decimal(foot.x) + "\" y2=\"" +
         decimal(foot.y) + "\" stroke=\"" + col + "\" stroke-width=\"" + (heavy ? "2.4" : "1.6") + "\"/>\n";
    s += "<polygon points=\"" +
         svg_points({b, {foot.x - half * uy, foot.y + half * ux}, {foot.x + half * uy, foot.y - half * ux}}) +
         "\" fill=\"" + col + "\"/>\n";
}

// A label: a name in sans-serif, or italic math with its underline and subscript.
void svg_label(std::string &s, const layout &L, const label &l)
{
    const point p = svg_out(L, l.at);
    const char *anchor = "middle";
    if (l.side == place::east || l.side == place::north_east || l.side == place::south_east)
        anchor = "start";
    else if (l.side == place::west || l.side == place::north_west || l.side == place::south_west)
        anchor = "end";
    // The baseline: text above the point, below it, or centred on it.
    double base = p.y + 5;
    if (l.side == place::north || l.side == place::north_east || l.side == place::north_west)
        base = p.y - 4;
    else if (l.side == place::south || l.side == place::south_east || l.side == place::south_west)
        base = p.y + 13;
    s += "<text x=\"" + decimal(p.x) + "\" y=\"" + decimal(base) + "\" text-anchor=\"" + anchor + "\"";
    if (l.what != role::body)
        s += std::string(" fill=\"") + svg_colour(l.what) + "\"";
    if (l.is_name) {
        s += " font-family=\"sans-serif\" font-size=\"13\">" + names::xml_text(shown_name(l.name)) + "</text>\n";
        return;
    }
    s += " font-style=\"italic\">";
    // Math labels are this library's own text; escaped all the same.
    const std::string base_text = names::xml_text(l.text);
    s += is_vector_label(l) ? "<tspan text-decoration=\"underline\">" + base_text + "</tspan>" : base_text;
    if (!l.sub.empty())
        s += "<tspan dy=\"4\" font-size=\"11\">" + names::xml_text(l.sub) + "</tspan>";
    s += "</text>\n";
}

} // namespace

std::string to_svg(const drawing &g)
{
    // px; 15 px serif text.
    const text_metrics m{8.5, 6.5, 18};
    const layout L = fit(g, 520, 440, 6, m);
    const std::string w = decimal(L.width), h = decimal(L.height);
    std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + w + "\" height=\"" + h +
                    "\" viewBox=\"0 0 " + w + " " + h + "\" role=\"img\" font-family=\"serif\" font-size=\"15\">\n";
    s += "<title>" + names::xml_text(describe(g)) + "</title>\n";
    for (const item &it : g.items) {
        if (it.kind == item::circle) {
            svg_circle(s, g, L, it);
            continue;
        }
        if (it.points.size() < 2)
            continue;
        std::vector<point> pts;
        for (const point &q : it.points)
            pts.push_back(svg_out(L, q));
        if (it.kind == item::arrow) {
            svg_arrow(s, it, pts);
            continue;
        }
        std::string fill = "none", stroke = svg_colour(it.what), width = "1.4";
        if (it.what == role::body) {
            width = it.thin ? "0.8" : (it.closed ? "1.4" : "2.4");
            if (it.filled)
                fill = svg_fill(g, it.body);
        } else if (it.what == role::pivot) {
            width = it.thin ? "0.8" : "1.4";
            if (it.closed)
                fill = "#ffffff";
        } else if (it.what == role::lever_arm) {
            width = "1.1";
        }
        s += std::string(it.closed ? "<polygon" : "<polyline") + " points=\"" + svg_points(pts) + "\" fill=\"" + fill +
             "\" stroke=\"" + stroke + "\" stroke-width=\"" + width + "\"" +
             (it.dashed ? " stroke-dasharray=\"5,4\"" : "") + "/>\n";
    }
    for (const label &l : g.labels)
        svg_label(s, L, l);
    s += "</svg>";
    return s;
}

std::string describe(const drawing &g)
{
    if (!g.alt.empty())
        return g.alt;
    auto who = [&](std::size_t i) {
        if (i >= g.bodies.size())
            return std::string("a body");
        const body_summary &b = g.bodies[i];
        std::string s = names::display_text(b.name, 64) + " (" + shape_name(b.form);
        if (b.pinned)
            s += " pinned at E";
        return s + ")";
    };
    // The movable body strikes an immovable one at rest; a moving body of infinite mass strikes.
    const bool swap = g.body1 < g.bodies.size() && g.body2 < g.bodies.size() && g.bodies[g.body1].infinite_mass &&
                      g.bodies[g.body1].at_rest && !g.bodies[g.body2].infinite_mass;
    std::string s = swap ? who(g.body2) + " strikes " + who(g.body1) : who(g.body1) + " strikes " + who(g.body2);
    s += " at O; normal e_n along " + g.normal_text;
    if (g.dimension == 3)
        s += "; 3-D, oblique projection";
    if (g.schematic)
        s += "; schematic (symbols drawn with illustrative values)";
    return s;
}

} // namespace impactgen::figure
