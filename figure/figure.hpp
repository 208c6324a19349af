// A figure of one impact, drawn from the problem's own geometry the way the
// lecture notes sketch it: the two bodies touching at the contact point O,
// their centres C1 and C2, the contact frame e_t, e_n (e_b in 3-D) at O, the
// lever arms r from C to O, the impulse N e_n acting on body 2 and -N e_n on
// body 1, the pivot impulse R at a pin E, and the velocities before impact.
//
// One seam, as in print/explain: draw() builds a `drawing` once -- circles,
// paths and arrows in 2-D figure coordinates, each tagged with its role and
// body -- and each output format is a small printer over it: to_tikz() (a
// tikzpicture that needs only \usepackage{tikz}), to_svg() (one self-contained
// <svg> element) and describe() (one line of alternative text).
//
// Figure coordinates are world coordinates moved so that O is the origin and
// divided by the largest distance from O of a finite body's centre or a
// pivot: every such point lies within the unit disc and the decorations
// (arrows, markers) have fixed lengths in these units. Planar problems keep
// their x, y axes; 3-D problems are drawn in a fixed oblique (cabinet)
// projection, x to the right, y up, z towards the viewer at 45 degrees down
// and to the left, foreshortened by 1/2. A problem with symbols is drawn as a
// schematic: every symbol takes a fixed illustrative value (see draw()), and
// the labels name roles (C1, O, N), never numbers.
//
// Text from the problem file (body names) is kept raw in the drawing and
// escaped by each printer for its format through names/escape.hpp.
#pragma once

#include "symbolic/derivation.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace impactgen::figure
{

struct point {
    double x = 0, y = 0;
};

/// What an item of the figure shows.
enum class role {
    body,          ///< a body's outline (disc, rod, plate, box, wall and its hatching, marker)
    centre,        ///< the centre of mass C_i
    contact,       ///< the contact point O
    frame_axis,    ///< e_t, e_n, e_b at O
    lever_arm,     ///< r from C_i to O (dashed)
    impulse,       ///< N e_n on body 2, -N e_n on body 1, at O
    pivot_impulse, ///< R at a pin E
    velocity,      ///< a centre's velocity before impact (scaled)
    pivot,         ///< the pin support drawn at E
    spin           ///< a body's angular velocity before impact: a turning arrow about C (2-D), the vector at C (3-D)
};
const char *role_name(role r);

/// How a body is drawn.
enum class shape {
    disc,  ///< a particle or a sphere: radius |O - C| when C - O is along the normal, else small
    rod,   ///< a slender rod: through a pin E, C and O, or a free rod whose end is at O
    plate, ///< a pinned body whose E, C and O are not in line: a parallelogram with centroid C
    box,   ///< a free rigid body: a box about C with one face in the tangent plane through O
    wall,  ///< a body of infinite mass: a hatched wall (plane in 3-D) through O
    marker ///< anything else: a small square at C
};
const char *shape_name(shape s);

/// One stroke or fill. Points are in figure coordinates.
struct item {
    enum kind_t { circle, path, arrow } kind = path;
    role what = role::body;
    int body = -1; ///< index into problem::bodies, -1 for none
    /// What it is: "body", "hatch", "C1", "C2", "O", "e_t", "e_n", "e_b", "r1", "N1" (on body 1),
    /// "N2", "F1" and "F2" (the friction impulse on body 1 and 2), "v1", "w1" (the spin of body 1:
    /// its arc, and its arrow head), "E" and "R" (E1, R1, ... with several pivots), "support", "ground".
    std::string key;
    /// circle: {centre}; path: its vertices; arrow: {tail, tip}.
    std::vector<point> points;
    double radius = 0;   ///< circle only; the printers draw role centre and contact circles at a fixed size
    bool closed = false; ///< path: join the last vertex to the first
    bool filled = false; ///< circle or closed path: shaded like a body
    bool dashed = false;
    bool thin = false; ///< a hairline (hatching, construction)
};

/// Where a label sits relative to its point.
enum class place { centre, north, south, east, west, north_east, north_west, south_east, south_west };

/// A label. Math labels are written by this library (tex is LaTeX math
/// without dollars; text + sub is the same in plain Unicode); a name label
/// carries a body name from the problem file, raw, for the printers to escape.
struct label {
    point at;
    place side = place::centre;
    role what = role::body;
    int body = -1;
    std::string key; ///< as in item::key
    bool is_name = false;
    std::string tex;       ///< math label: "C_1", "\\hat{e}_n"
    std::string text, sub; ///< math label in Unicode: "C" + "1", "\u00ea" + "n"
    std::string name;      ///< name label: the raw name
};

/// One body as the figure shows it (for describe() and for tests).
struct body_summary {
    std::string name; ///< display_name(): "body 1" or the problem's name, raw
    shape form = shape::marker;
    bool infinite_mass = false;
    bool at_rest = false; ///< velocity and angular velocity exactly zero before impact
    bool pinned = false;
};

struct drawing {
    int dimension = 2;
    bool schematic = false;    ///< drawn with illustrative values for the problem's symbols
    std::vector<item> items;   ///< drawn in this order (bodies first, markers last)
    std::vector<label> labels; ///< drawn on top, in this order
    std::vector<body_summary> bodies;
    std::size_t body1 = 0, body2 = 1; ///< the contact's bodies (indices into bodies)
    std::string normal_text;          ///< the unit normal, "(3/5, 4/5)", or "n (symbolic)"
    point n_hat, t_hat, b_hat;        ///< the contact frame as drawn (unit in 2-D; projected in 3-D)
    /// The pivot and friction impulses are drawn along the answer (a numeric problem with one
    /// answer); otherwise in the senses in which they count positive, listed in `positive`.
    bool impulses_from_answer = false;
    std::vector<std::string> positive; ///< in words: "the pivot impulse towards +x", "each spin counter-clockwise"
    std::string alt;                   ///< when set, describe() returns it (a system's figure: figure/system.hpp)
};

/// The impact drawn from its derivation (problem + contact frame d.n_hat,
/// d.t_dir, d.b_dir). Symbols left in the problem take illustrative values:
/// for a named class the values it gave its quantities (problem::illustrate: bodies
/// on their own side of the tangent plane, approaching); for a problem file a value by the symbol's first role
/// (masses and diagonal inertias 1, off-diagonal inertias 0, e = 1/2, the
/// contact point 0, a centre 0.8 from O on its body's side, a pivot beyond
/// the centre, velocities that approach, spins 0). Never throws for a
/// derivation that derive() returned; degenerate geometry (C at O, zero or
/// extreme values, a symbolic normal) still gives finite coordinates.
drawing draw(const impactgen::derivation &d);

/// The illustrative value draw() gives each symbol of the problem (empty for a numeric
/// problem): decimals such as 0.8 or -0.9, placed by what each symbol is (see draw()).
GiNaC::exmap schematic_values(const impactgen::problem &p);

/// What a caption adds about the drawn directions: "" when nothing is assumed, else one
/// sentence, starting with a space, saying that the unknown impulses (and spins given by
/// symbols) are drawn in the senses in which they count positive.
std::string directions_note(const drawing &g);

/// "\\begin{tikzpicture}...\\end{tikzpicture}", at most about 8.5 cm wide and
/// 7.5 cm high (within 0.8\linewidth of an 11pt article); needs only tikz.
std::string to_tikz(const drawing &g);

/// One self-contained "<svg xmlns=... viewBox=...><title>..</title>...</svg>"
/// element: no scripts, no external or internal references (arrow heads are
/// drawn as polygons, so several figures can share one page).
std::string to_svg(const drawing &g);

/// One line of alternative text, e.g. "ball (disc) strikes rod (rod pinned at
/// E) at O; normal e_n along (1, 0)". Body names are made one-line by
/// names::display_text but not escaped for any format: the caller escapes the
/// line for its output (latex_text, html_text, xml_text).
std::string describe(const drawing &g);

} // namespace impactgen::figure
