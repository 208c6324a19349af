// The statement of an exercise, its short answers and its figure, in LaTeX and HTML.
#include "exercises/detail.hpp"
#include "symbolic/contact_law.hpp"

#include "figure/figure.hpp"
#include "figure/system.hpp"
#include "names/escape.hpp"

#include <cstdio>
#include <sstream>

namespace impactgen::exercises::detail
{
using namespace GiNaC;

namespace
{

std::string digits(const numeric &n)
{
    std::ostringstream os;
    os << n;
    return os.str();
}

/// A decimal of at most 4 places, exact ("0.25", "-3.125").
std::string exact_decimal(const numeric &q, int p)
{
    const numeric scaled = abs(q) * numeric(10).power(p);
    std::string d = digits(scaled.numer());
    while (static_cast<int>(d.size()) <= p)
        d = "0" + d;
    std::string out = p > 0 ? d.substr(0, d.size() - p) + "." + d.substr(d.size() - p) : d;
    return out;
}

std::string unit_tex(const std::string &u)
{
    if (u == "kg m2")
        return "kg\\,m$^2$";
    if (u == "N s")
        return "N\\,s";
    return u;
}

std::string unit_html(const std::string &u)
{
    return u == "kg m2" ? "kg m²" : u == "N s" ? "N s" : u;
}

} // namespace

std::string decimal4(const ex &value)
{
    const ex v = value.evalf();
    double x = is_a<numeric>(v) ? ex_to<numeric>(v).to_double() : 0;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    std::string s = buf;
    return s == "-0" ? "0" : s;
}

text &text::w(const std::string &words)
{
    s_ += f_ == format::tex ? names::latex_text(words) : names::html_text(words);
    return *this;
}

text &text::raw(const std::string &markup)
{
    s_ += markup;
    return *this;
}

text &text::sym(const std::string &tex, const std::string &html)
{
    s_ += f_ == format::tex ? "$" + tex + "$" : "<i>" + html + "</i>";
    return *this;
}

std::string text::number(const ex &value) const
{
    std::string body;
    if (is_a<numeric>(value) && ex_to<numeric>(value).is_rational()) {
        const numeric &q = ex_to<numeric>(value);
        const int p = decimal_places(q);
        const std::string minus = q.is_negative() ? (f_ == format::tex ? "-" : "\u2212") : "";
        if (q.is_integer())
            body = minus + digits(abs(q));
        else if (p >= 0 && p <= 4)
            body = minus + exact_decimal(q, p);
        else if (f_ == format::tex)
            body = minus + "\\tfrac{" + digits(abs(q.numer())) + "}{" + digits(q.denom()) + "}";
        else
            body = minus + digits(abs(q.numer())) + "/" + digits(q.denom());
    } else {
        body = decimal4(value);
    }
    return body;
}

text &text::num(const ex &value)
{
    s_ += f_ == format::tex ? "$" + number(value) + "$" : number(value);
    return *this;
}

text &text::vec(const vec3 &v, int dimension)
{
    // one formula in LaTeX, so that it never breaks inside
    std::string body = "(";
    for (int c = 0; c < dimension; ++c)
        body += (c ? (f_ == format::tex ? ",\\ " : ", ") : "") + number(v[c]);
    body += ")";
    s_ += f_ == format::tex ? "$" + body + "$" : body;
    return *this;
}

text &text::unit(const std::string &u)
{
    if (!u.empty())
        s_ += (f_ == format::tex ? "~" + unit_tex(u) : "\u00a0" + unit_html(u));
    return *this;
}

text &text::approx(const ex &value)
{
    num(value);
    if (is_a<numeric>(value) && ex_to<numeric>(value).is_rational()) {
        const int p = decimal_places(ex_to<numeric>(value));
        if (p >= 0 && p <= 4)
            return *this;
    }
    s_ += f_ == format::tex ? " $\\approx " + decimal4(value) + "$" : " \u2248 " + decimal4(value);
    return *this;
}

namespace
{

std::string body_item(const problem &p, std::size_t i, format f, bool si)
{
    const body &b = p.bodies[i];
    const int dim = p.dimension == 2 ? 2 : 3;
    auto u = [&](const std::string &x) { return si ? x : std::string(); };
    text t(f);
    t.raw(f == format::tex ? "\\textbf{" : "<b>").w(b.name).raw(f == format::tex ? "}" : "</b>").w(": ");
    bool moving = false, spinning = false;
    for (int k = 0; k < 3; ++k) {
        moving = moving || !b.velocity[k].is_zero();
        spinning = spinning || !b.angular_velocity[k].is_zero();
    }
    if (b.infinite_mass) {
        t.w("a body of infinite mass");
    } else {
        t.w("mass ").num(b.mass).unit(u("kg"));
        if (b.particle) {
            t.w(", a particle");
        } else if (dim == 2) {
            t.w(", moment of inertia about its centre of mass ").num(b.inertia[2][2]).unit(u("kg m2"));
        } else {
            bool diagonal = true;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    diagonal = diagonal && (r == c || b.inertia[r][c].is_zero());
            t.w(diagonal ? ", principal moments of inertia about its centre of mass along x, y, z "
                         : ", inertia tensor about its centre of mass with the rows ");
            if (diagonal) {
                t.vec({b.inertia[0][0], b.inertia[1][1], b.inertia[2][2]}, 3);
            } else {
                for (int r = 0; r < 3; ++r)
                    t.w(r ? ", " : "").vec(b.inertia[r], 3);
            }
            t.unit(u("kg m2"));
        }
    }
    if (b.infinite_mass && !spinning) { // its centre does not enter: the floor, a wall
        t.w(moving ? "; velocity " : "; at rest");
        if (moving)
            t.vec(b.velocity, dim).unit(u("m/s"));
        t.w(".");
        return t.str();
    }
    t.w("; centre of mass at ").vec(b.position, dim).unit(u("m"));
    if (!moving && !spinning) {
        t.w("; at rest before impact");
    } else {
        t.w("; before impact velocity ").vec(b.velocity, dim).unit(u("m/s"));
        if (spinning) {
            t.w(" and angular velocity ");
            if (dim == 2)
                t.num(b.angular_velocity[2]);
            else
                t.vec(b.angular_velocity, 3);
            t.unit(u("rad/s"));
            if (dim == 2)
                t.w(" (counter-clockwise positive)");
        }
    }
    if (const pivot *pv = p.pivot_of(i))
        t.w("; pinned at ").vec(pv->point, dim).unit(u("m")).w(" (a smooth hinge)");
    t.w(".");
    return t.str();
}

} // namespace

text &contact_geometry(text &t, const problem &p, const contact_spec &c, const std::string &normal, bool si)
{
    const int dim = p.dimension == 2 ? 2 : 3;
    return t.vec(c.point, dim)
        .unit(si ? "m" : "")
        .w("; " + normal + ", from " + p.bodies[c.body1].name + " into " + p.bodies[c.body2].name + ", is ")
        .vec(c.normal, dim);
}

std::vector<std::string> statement(const problem &p, format f, bool si)
{
    std::vector<std::string> out;
    for (std::size_t i = 0; i < p.bodies.size(); ++i)
        out.push_back(body_item(p, i, f, si));
    if (p.is_system()) {
        for (std::string &item : system_statement_items(p, f, si))
            out.push_back(std::move(item));
        return out;
    }
    const contact_spec &c = p.contact();
    text contact(f);
    // a movable body strikes an immovable one at rest (not "the floor strikes the ball")
    const body &b1 = p.bodies[c.body1], &b2 = p.bodies[c.body2];
    const bool swap = b1.infinite_mass && b1.at_rest() && !b2.infinite_mass;
    contact.w("Contact: " + (swap ? b2.name + " strikes " + b1.name : b1.name + " strikes " + b2.name) +
              " at the point ");
    contact_geometry(contact, p, c, "the common normal there", si)
        .w(". The coefficient of restitution is ")
        .sym("e", "e")
        .w(" = ")
        .num(p.restitution);
    if (!c.friction().is_zero())
        contact.w("; the coefficient of friction is ").sym("\\mu", "μ").w(" = ").num(c.friction());
    else
        contact.w("; the contact is smooth");
    contact.w(".");
    out.push_back(contact.str());
    return out;
}

std::string find_sentence(const problem &p, format f)
{
    if (p.is_system())
        return system_find_sentence(p, f);
    bool spins = false;
    for (std::size_t i = 0; i < p.bodies.size(); ++i)
        spins = spins || (!p.immovable(i) && !p.bodies[i].particle);
    std::string s = std::string("Find the velocities") + (spins ? " and angular velocities" : "") +
                    " after impact, the normal impulse";
    if (law_traits_of(p).tangential_impulse)
        s += ", the friction impulse (does the contact stick or slide?)";
    if (!p.pivots.empty())
        s += p.pivots.size() == 1 ? ", the impulse of the pivot" : ", the impulses of the pivots";
    s += " and the kinetic energy lost.";
    return text(f).w(s).str();
}

bool long_number(const ex &value)
{
    if (!is_a<numeric>(value) || !ex_to<numeric>(value).is_rational())
        return true;
    const numeric &q = ex_to<numeric>(value);
    return abs(q.numer()) > numeric(999999) || q.denom() > numeric(9999);
}

std::vector<std::string> short_answers(const exercise &e, format f)
{
    std::vector<std::string> out;
    if (e.prob.is_system())
        out.push_back(system_regimes_in_words(e, f));
    else if (!law_traits_of(e.prob).single_candidate)
        out.push_back(text(f).w("the contact " + std::string(e.regime == "stick" ? "sticks" : "slides")).str());
    for (const quantity &q : e.asked) {
        text t(f);
        t.w(q.words + " ");
        if (long_number(q.exact)) // a long fraction or a root: its decimal is the answer a person writes
            t.raw(f == format::tex ? "$\\approx " + decimal4(q.exact) + "$" : "\u2248 " + decimal4(q.exact));
        else
            t.raw(f == format::tex ? "$=$ " : "= ").approx(q.exact);
        out.push_back(t.unit(q.unit).str());
    }
    return out;
}

std::string figure_of(const problem &p, format f)
{
    if (p.is_system()) {
        const std::optional<figure::drawing> g = figure::draw_system(p);
        return !g ? "" : f == format::tex ? figure::to_tikz(*g) : figure::to_svg(*g);
    }
    const figure::drawing g = figure::draw(derive(p));
    return f == format::tex ? figure::to_tikz(g) : figure::to_svg(g);
}

int decimal_places(const numeric &q)
{
    numeric den = q.denom();
    int twos = 0, fives = 0;
    while (den.is_even()) {
        den = den / 2;
        ++twos;
    }
    while (irem(den, numeric(5)).is_zero()) {
        den = den / 5;
        ++fives;
    }
    return den == 1 ? std::max(twos, fives) : -1;
}

} // namespace impactgen::exercises::detail
