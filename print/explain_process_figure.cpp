// The figure of Routh's process: the relative velocity of the contact points (u_t, u_n) as the
// normal impulse grows, a broken line (straight in each phase) from the velocity before impact
// to the velocity after, with the phase boundaries and the end of compression marked. The
// same drawing in TikZ (LaTeX) and SVG (HTML), both from the points.
#include "explain_process.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace impactgen::print::detail
{
namespace
{

std::string fixed(double x, int digits = 3)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", digits, std::abs(x) < 5e-4 ? 0.0 : x);
    return buf;
}

std::string escaped(const std::string &s)
{
    std::string out;
    for (char ch : s)
        out += ch == '<' ? "&lt;" : ch == '>' ? "&gt;" : ch == '&' ? "&amp;" : std::string(1, ch);
    return out;
}

// The plot's window: the points and the origin, with a margin, the same scale on both axes.
struct window {
    double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    explicit window(const std::vector<path_point> &path)
    {
        x0 = x1 = y0 = y1 = 0;
        for (const path_point &p : path) {
            x0 = std::min(x0, p.ut), x1 = std::max(x1, p.ut);
            y0 = std::min(y0, p.un), y1 = std::max(y1, p.un);
        }
        const double span = std::max({x1 - x0, y1 - y0, 1e-9}), m = 0.12 * span;
        x0 -= m, x1 += m, y0 -= m, y1 += m;
    }
};

std::string tikz_of(const std::vector<path_point> &path)
{
    const window w(path);
    const double scale = std::min(9.0 / (w.x1 - w.x0), 7.0 / (w.y1 - w.y0));
    auto X = [&](double x) { return fixed(x * scale); };
    std::string t = "\\begin{tikzpicture}[font=\\small]\n";
    t += "\\draw[->,gray] (" + X(w.x0) + ",0) -- (" + X(w.x1) + ",0) node[right,black] {$u_t$};\n";
    t += "\\draw[->,gray] (0," + X(w.y0) + ") -- (0," + X(w.y1) + ") node[above,black] {$u_n$};\n";
    t += "\\draw[thick,blue]";
    for (std::size_t k = 0; k < path.size(); ++k)
        t += std::string(k ? " -- " : " ") + "(" + X(path[k].ut) + "," + X(path[k].un) + ")";
    t += ";\n";
    for (std::size_t k = 0; k < path.size(); ++k)
        t += "\\fill (" + X(path[k].ut) + "," + X(path[k].un) + ") circle (1.5pt) node[above right] {" +
             std::to_string(k) + "};\n";
    return t + "\\end{tikzpicture}";
}

std::string svg_of(const std::vector<path_point> &path, const std::string &alt)
{
    const window w(path);
    const double W = 420, H = 320, pad = 24;
    const double scale = std::min((W - 2 * pad) / (w.x1 - w.x0), (H - 2 * pad) / (w.y1 - w.y0));
    auto X = [&](double x) { return fixed(pad + (x - w.x0) * scale, 1); };
    auto Y = [&](double y) { return fixed(H - pad - (y - w.y0) * scale, 1); };
    std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fixed(W, 0) + "\" height=\"" + fixed(H, 0) +
                    "\" viewBox=\"0 0 " + fixed(W, 0) + " " + fixed(H, 0) + "\" role=\"img\">";
    s += "<title>" + escaped(alt) + "</title>";
    s +=
        "<line x1=\"" + X(w.x0) + "\" y1=\"" + Y(0) + "\" x2=\"" + X(w.x1) + "\" y2=\"" + Y(0) + "\" stroke=\"gray\"/>";
    s +=
        "<line x1=\"" + X(0) + "\" y1=\"" + Y(w.y0) + "\" x2=\"" + X(0) + "\" y2=\"" + Y(w.y1) + "\" stroke=\"gray\"/>";
    s += "<text x=\"" + X(w.x1) + "\" y=\"" + Y(0) + "\" dy=\"-4\" text-anchor=\"end\" font-size=\"14\">u_t</text>";
    s += "<text x=\"" + X(0) + "\" y=\"" + Y(w.y1) + "\" dx=\"4\" dy=\"12\" font-size=\"14\">u_n</text>";
    s += "<polyline fill=\"none\" stroke=\"blue\" stroke-width=\"2\" points=\"";
    for (std::size_t k = 0; k < path.size(); ++k)
        s += std::string(k ? " " : "") + X(path[k].ut) + "," + Y(path[k].un);
    s += "\"/>";
    for (std::size_t k = 0; k < path.size(); ++k)
        s += "<circle cx=\"" + X(path[k].ut) + "\" cy=\"" + Y(path[k].un) + "\" r=\"3.5\"/><text x=\"" + X(path[k].ut) +
             "\" y=\"" + Y(path[k].un) + "\" dx=\"6\" dy=\"-6\" font-size=\"13\">" + std::to_string(k) + "</text>";
    return s + "</svg>";
}

} // namespace

figure_art process_figure(const std::vector<path_point> &path, const std::string &caption)
{
    figure_art art;
    art.caption = caption;
    std::string points;
    for (std::size_t k = 0; k < path.size(); ++k)
        points += std::string(k ? "; " : "") + std::to_string(k) + " " + path[k].label + " (" + fixed(path[k].ut) +
                  ", " + fixed(path[k].un) + ")";
    art.alt = "The relative velocity (u_t, u_n) as the normal impulse grows: " + points + ".";
    art.tikz = tikz_of(path);
    art.svg = svg_of(path, art.alt);
    return art;
}

} // namespace impactgen::print::detail
