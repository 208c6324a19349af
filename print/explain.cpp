// explain(): the explanation document, section by section as the notes go:
// set-up, impulses, equations, count and solution, checks.
#include "explain.hpp"
#include "explain_detail.hpp"

#include "canonical.hpp"
#include "contact_frame.hpp"
#include "expression.hpp"
#include "figure/figure.hpp"
#include "names/escape.hpp"
#include "symbolic/decide.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{

// Greek letters of the prose and their TeX names.
const std::pair<const char *, const char *> greek[] = {
    {"ω", "\\omega"},      {"μ", "\\mu"},  {"τ", "\\tau"},   {"λ", "\\lambda"}, {"θ", "\\theta"},
    {"ε", "\\varepsilon"}, {"ρ", "\\rho"}, {"δ", "\\delta"}, {"Δ", "\\Delta"},  {"Σ", "\\sum"},
};
// Signs of the prose and their TeX.
const std::pair<const char *, const char *> signs[] = {
    {"±", "\\pm "}, {"∓", "\\mp "},    {"×", "\\times "},  {"·", "\\cdot "}, {"≤", "\\le "},  {"≥", "\\ge "},
    {"→", "\\to "}, {"∞", "\\infty "}, {"≈", "\\approx "}, {"≠", "\\ne "},   {"⁻¹", "^{-1}"}, {"²", "^{2}"},
    {"³", "^{3}"},  {"∫", "\\int "},   {"√", "\\sqrt"},    {"′", "'"},       {"'", "'"},      {"+", "+"},
    {"-", "-"},     {"=", "="},        {"/", "/"},         {"(", "("},       {")", ")"},      {",", ",\\,"},
    {"|", "|"},     {"<", "<"},        {">", ">"},         {".", "."},       {"*", "^{*}"},   {"[", "["},
    {"]", "]"},     {":", "\\colon "},
};

bool starts(const std::string &s, std::size_t at, const char *what)
{
    return s.compare(at, std::char_traits<char>::length(what), what) == 0;
}

bool alnum(char c)
{
    return std::isalnum(static_cast<unsigned char>(c)) != 0;
}

// A subscript or superscript's TeX: one character as it is, a word of three or more
// letters upright ("lost"), else braced.
std::string script_tex(const std::string &s)
{
    if (s.size() == 1)
        return s;
    bool letters = s.size() >= 3;
    for (char c : s)
        letters = letters && std::isalpha(static_cast<unsigned char>(c));
    return letters ? "{\\mathrm{" + s + "}}" : "{" + s + "}";
}

} // namespace

notation prose_notation(const std::string &src)
{
    notation out;
    std::size_t i = 0;
    auto fail = [&](const std::string &why) {
        throw std::logic_error("explain: the prose notation \"" + src + "\" " + why + " at byte " + std::to_string(i));
    };
    bool after_space = false;
    while (i < src.size()) {
        if (src[i] == ' ') {
            out.text += ' ';
            after_space = true;
            ++i;
            continue;
        }
        // An identifier: [~] letter-or-Greek [letters/digits] [primes] [_sub] [^sup].
        int marks = 0; // ~ a vector, ~~ a tensor
        std::size_t at = i;
        while (i < src.size() && src[i] == '~' && marks < 2) {
            ++marks;
            ++i;
        }
        const bool vector = marks > 0;
        std::string base_text, base_tex;
        if (i < src.size() && std::isalpha(static_cast<unsigned char>(src[i]))) {
            std::size_t k = i;
            while (k < src.size() && std::isalpha(static_cast<unsigned char>(src[k])))
                ++k;
            base_text = src.substr(i, k - i);
            i = k;
        } else {
            for (const auto &[g, tex] : greek)
                if (starts(src, i, g)) {
                    base_text = g;
                    base_tex = tex;
                    i += std::char_traits<char>::length(g);
                    break;
                }
        }
        if (base_text.empty()) {
            if (vector)
                fail("has ~ before something that is not a symbol");
            if (std::isdigit(static_cast<unsigned char>(src[i]))) {
                std::size_t k = i;
                while (k < src.size() && (std::isdigit(static_cast<unsigned char>(src[k])) || src[k] == '.'))
                    ++k;
                out.text += src.substr(i, k - i);
                out.tex += src.substr(i, k - i);
                i = k;
                after_space = false;
                continue;
            }
            bool done = false;
            for (const auto &[sign, tex] : signs)
                if (starts(src, i, sign)) {
                    out.text += std::string(sign) == "'" ? "′" : sign;
                    out.tex += tex;
                    i += std::char_traits<char>::length(sign);
                    done = true;
                    break;
                }
            if (!done)
                fail("has a character it does not know");
            after_space = false;
            continue;
        }
        // Function names and the differential.
        static const std::pair<const char *, const char *> words[] = {
            {"dt", "\\,dt"},  {"cos", "\\cos"}, {"sin", "\\sin"}, {"max", "\\max"},
            {"min", "\\min"}, {"det", "\\det"}, {"tan", "\\tan"}, {"atan", "\\arctan"},
        };
        std::string sub, sup;
        if (base_tex.empty()) {
            for (const auto &[w, tex] : words)
                if (base_text == w && !vector) {
                    base_tex = tex;
                    break;
                }
            if (base_tex.empty()) {
                // C1, m2, w12: a letter and digits is the letter with a subscript
                std::size_t d = 1;
                while (d < base_text.size() && std::isalpha(static_cast<unsigned char>(base_text[d])))
                    ++d;
                if (d != 1 && base_text.size() > 1)
                    fail("has a multi-letter name \"" + base_text + "\" (write it as words outside the dollars)");
                base_tex = base_text.substr(0, 1);
            }
        }
        // digits glued to a one-letter base: "C1"
        if (i < src.size() && std::isdigit(static_cast<unsigned char>(src[i])) && base_text.size() <= 2) {
            std::size_t k = i;
            while (k < src.size() && alnum(src[k]))
                ++k;
            sub = src.substr(i, k - i);
            base_text += sub;
            i = k;
        }
        std::string primes_text, primes_tex;
        while (i < src.size() && (starts(src, i, "′") || src[i] == '\'')) {
            primes_text += "′";
            primes_tex += "'";
            i += src[i] == '\'' ? 1 : std::char_traits<char>::length("′");
        }
        if (sub.empty() && i < src.size() && src[i] == '_') {
            std::size_t k = i + 1;
            while (k < src.size() && (alnum(src[k]) || src[k] == ','))
                ++k;
            if (k == i + 1)
                fail("has an empty subscript");
            sub = src.substr(i + 1, k - i - 1);
            i = k;
        }
        if (i < src.size() && src[i] == '^') {
            std::size_t k = i + 1;
            while (k < src.size() && (alnum(src[k]) || src[k] == '*' || src[k] == '-'))
                ++k;
            sup = src.substr(i + 1, k - i - 1);
            i = k;
        }
        // text: as written, without the vector mark, ' as ′
        std::string written =
            src.substr(at + static_cast<std::size_t>(marks), i - at - static_cast<std::size_t>(marks));
        std::string text;
        for (std::size_t k = 0; k < written.size(); ++k)
            text += written[k] == '\'' ? std::string("′") : std::string(1, written[k]);
        out.text += text;
        std::string tex = base_tex;
        const bool unit = base_text == "e" && (sub == "t" || sub == "n" || sub == "b");
        if (unit)
            tex = "\\hat{\\underline{e}}";
        else if (marks == 2)
            tex = "\\underline{\\underline{" + base_tex + "}}";
        else if (vector)
            tex = "\\underline{" + base_tex + "}";
        if (after_space && base_text == "dt")
            tex = "\\,dt";
        tex += primes_tex;
        if (!sub.empty())
            tex += "_" + script_tex(sub);
        if (!sup.empty())
            tex += "^" + script_tex(sup);
        // a letter right after a letter needs a space in TeX: "N dt", "\omega x"
        if (!out.tex.empty() && (std::isalpha(static_cast<unsigned char>(out.tex.back()))) && tex[0] != '\\')
            out.tex += ' ';
        else if (!out.tex.empty() && out.tex.back() != ' ' && tex[0] == '\\' &&
                 std::isalpha(static_cast<unsigned char>(tex[1])))
            out.tex += ' ';
        out.tex += tex;
        after_space = false;
    }
    // trim the spaces TeX does not need at the end
    while (!out.tex.empty() && out.tex.back() == ' ')
        out.tex.pop_back();
    return out;
}

paragraph &paragraph::t(const char *prose)
{
    const std::string s = prose;
    std::size_t at = 0;
    while (at < s.size()) {
        std::size_t open = s.find('$', at);
        if (open == std::string::npos) {
            w(s.substr(at));
            break;
        }
        std::size_t close = s.find('$', open + 1);
        if (close == std::string::npos)
            throw std::logic_error("explain: an unpaired $ in the prose \"" + s + "\"");
        if (open > at)
            w(s.substr(at, open - at));
        notation f = prose_notation(s.substr(open + 1, close - open - 1));
        n(f.text, f.tex);
        at = close + 1;
    }
    return *this;
}

namespace detail
{

std::string body_ref(const problem &p, std::size_t i)
{
    const body &b = p.bodies[i];
    std::string role = i == p.contact.body1 ? "body 1" : i == p.contact.body2 ? "body 2" : "body";
    return b.numbered ? role : role + " (" + b.name + ")";
}

paragraph step_note(const problem &p, const step &st)
{
    paragraph q;
    const bool has_body = st.body != no_body && st.body < p.bodies.size();
    const std::string who = has_body ? body_ref(p, st.body) : std::string();
    const bool pinned = has_body && p.pivot_of(st.body);
    auto axis = [&](int c) { return c >= 0 && c < 3 ? p.axes[static_cast<std::size_t>(c)] : std::string(); };
    switch (st.role) {
    case step_role::lever_arm:
        q.t(pinned ? "lever arm of the normal about the pivot $E$ of "
                   : "lever arm of the normal about the centre of mass $C$ of ")
            .w(who);
        q.t(pinned ? ": $(~r_EO × e_n)$" : ": $(~r_CO × e_n)$");
        if (st.row >= 0)
            q.t(", component along ").w(axis(st.row));
        return q;
    case step_role::pivot_inertia:
        q.w("inertia of " + who).t(" about its pivot $E$: ");
        if (p.dimension == 2)
            q.t("$I_C + m |~r_EC|²$");
        else
            q.t("$~~I_E = ~~I_C + m (|~d|² 1 - ~d ~d^T)$, $~d = C - E$, entry ").w(axis(st.row) + axis(st.column));
        return q;
    case step_role::inertia_determinant:
        return q.w("determinant of the inertia tensor of " + who);
    case step_role::angular_response:
        q.t("$~~I⁻¹ (~r × e_n)$ for ").w(who).t(", component along ").w(axis(st.row));
        return q.t(": the change of angular velocity per unit impulse");
    case step_role::effective_inverse_mass:
        return q.w("effective inverse mass of " + who).t(" at the contact point along $e_n$");
    case step_role::approach_velocity:
        return q.t("normal velocity of approach $(~v_B - ~v_A)·e_n$ before impact (negative for an impact)");
    case step_role::contact_inverse_mass:
        return q.t("effective inverse mass of the contact: the sum of the bodies' $w_i$");
    case step_role::normal_impulse:
        return q.t("the normal impulse $∫N dt$ along $e_n$, from restitution");
    case step_role::energy_lost:
        return q.w("kinetic energy lost in the impact");
    case step_role::inverse_inertia:
        q.w("entry " + axis(st.row) + axis(st.column)).t(" of the inverse inertia tensor $~~I⁻¹$ of ").w(who);
        return q.t(pinned ? " about its pivot $E$" : " about its centre of mass $C$");
    case step_role::contact_response:
        q.t("contact response $K$, entry ").w(axis(st.row) + axis(st.column));
        return q.t(": change of the relative velocity $~u$ of the contact points along ")
            .w(axis(st.row))
            .w(" per unit impulse on body 2 along ")
            .w(axis(st.column));
    case step_role::relative_velocity:
        if (st.row < 0)
            return q.t("sliding speed $|~u_t|$ of the contact points before impact");
        return q.t("relative velocity $~u = ~v_B - ~v_A$ of the contact points before impact, component along ")
            .w(axis(st.row));
    case step_role::response_determinant:
        return q.t("$D_K = det K$, positive: $K$ is positive definite");
    case step_role::impulse_component:
        return q.t("contact impulse $~P$ on body 2, component along ").w(axis(st.row));
    case step_role::tangential_impulse:
        if (st.row < 0)
            return q.t("tangential (friction) impulse $F = ~P·e_t$ on body 2 (on body 1 the opposite)");
        return q.t("friction impulse $~F$ on body 2, component along ").w(axis(st.row));
    case step_role::slide_denominator:
        return q.t(
            "$D_s = e_n·K(e_n - μ ~d)$, the normal response while sliding: it must be positive, else $N$ would not be");
    case step_role::slide_direction:
        return q.t("sliding direction $~d$, component along ").w(axis(st.row));
    case step_role::separation_velocity:
        return q.t("sliding speed $λ = ~u′·~d$ after impact: positive when the contact keeps sliding along $~d$");
    }
    return q.w(st.meaning);
}

figure_art figure_of(const derivation &d)
{
    const figure::drawing g = figure::draw(d);
    figure_art art;
    art.tikz = figure::to_tikz(g);
    art.svg = figure::to_svg(g);
    art.alt = figure::describe(g);
    art.caption = g.schematic
                      ? "The impact, drawn to an illustrative scale (the problem's values are symbols): the bodies, "
                        "their centres of mass C, the contact point O, the contact frame, the impulses and the "
                        "velocities before impact."
                      : "The impact as the problem gives it: the bodies, their centres of mass C, the contact point O, "
                        "the contact "
                        "frame, the impulses and the velocities before impact.";
    return art;
}

std::string unit(const problem &p, quantity q)
{
    if (p.units != "SI")
        return "";
    switch (q) {
    case quantity::mass:
        return " kg";
    case quantity::inertia:
        return " kg·m²";
    case quantity::length:
        return " m";
    case quantity::velocity:
        return " m/s";
    case quantity::angular_velocity:
        return " rad/s";
    case quantity::impulse:
        return " N·s";
    case quantity::energy:
        return " J";
    }
    return "";
}

std::string units_key(const problem &p)
{
    return p.units == "SI"
               ? "SI -- masses in kg, moments of inertia in kg·m², lengths in m, velocities in m/s, angular "
                 "velocities in rad/s, impulses in N·s, energies in J"
               : "";
}

paragraph &vector_span(paragraph &p, const vec3 &v, int n)
{
    p.w("(");
    for (int c = 0; c < n; ++c) {
        if (c)
            p.w(", ");
        p.m(v[c]);
    }
    return p.w(")");
}

namespace
{
int count_nodes(const ex &e, int limit)
{
    int n = 0;
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end() && n < limit; ++it)
        ++n;
    return n;
}
} // namespace

bool printable(const ex &e, int limit)
{
    return count_nodes(e, limit) < limit;
}

math_row row(const ex &lhs, const ex &rhs, const std::string &tag, const std::string &note)
{
    math_row r;
    r.tag = tag;
    r.lhs = lhs;
    r.rhs = rhs;
    if (!note.empty())
        r.note.w(note);
    return r;
}

math_row note_row(const std::string &text, const std::string &tex, const ex &rhs, const std::string &note)
{
    math_row r = row(0, rhs, "", note);
    r.lhs_note = {text, tex};
    return r;
}

math_row formula_row(const std::string &text, const std::string &tex, const paragraph &note)
{
    math_row r = note_row(text, tex, 0);
    r.rel = "";
    r.note = note;
    return r;
}

math_row formula_row(const std::string &text, const std::string &tex, const char *note)
{
    return formula_row(text, tex, paragraph().t(note));
}

std::string decimal_note(const ex &v)
{
    // A number, or a constant such as 16·√5/35 (no symbol in it), that is not an integer.
    if (is_a<numeric>(v) ? ex_to<numeric>(v).is_integer()
                         : !is_a<GiNaC::mul>(v) && !is_a<GiNaC::add>(v) && !is_a<GiNaC::power>(v))
        return "";
    if (!is_constant(v))
        return "";
    // evaluated until two precisions agree (a value that cancels in its leading digits)
    double d = 0;
    try {
        d = to_double(v);
    } catch (const std::invalid_argument &) {
        return "";
    }
    // six significant digits: enough to read, the exact value is beside it
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", d);
    return std::string("≈ ") + buf;
}

} // namespace detail

namespace
{
using namespace detail;

std::string number_word(std::size_t n)
{
    return std::to_string(n);
}

// Print-only symbols: names for quantities that are not GiNaC symbols of the problem.
symbol show(const std::string &name, const std::string &tex)
{
    return symbol(name, tex);
}

const step *find_step(const solution &s, step_role role, std::size_t body = no_body)
{
    return s.find(role, body);
}

// Substitutes the steps of the given roles (and only those), latest first.
ex expand_some(const solution &s, const ex &e, const std::vector<step_role> &roles)
{
    ex r = e;
    for (auto it = s.steps.rbegin(); it != s.steps.rend(); ++it)
        if (std::find(roles.begin(), roles.end(), it->role) != roles.end())
            r = r.subs(it->sym == it->value);
    return r;
}

// ---------------------------------------------------------------- sections

// "Coulomb's coefficient of friction between the bodies is μ (μ ≥ 0).", with the name the
// problem gives it when the document writes it otherwise.
paragraph friction_coefficient(const friction_setup &fr)
{
    if (!is_a<symbol>(fr.mu))
        return paragraph().t("Coulomb's coefficient of friction between the bodies is $μ$ = ").m(fr.mu).w(".");
    paragraph q;
    q.w("Coulomb's coefficient of friction between the bodies is ").m(fr.mu);
    if (fr.mu_in_problem)
        q.w(", written ").n(fr.mu_in_problem->text, fr.mu_in_problem->tex).w(" in the problem");
    return q.t(" ($μ ≥ 0$).");
}
} // namespace

section detail::setup_section(const derivation &d, const friction_setup *fr)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const std::size_t i1 = p.contact.body1, i2 = p.contact.body2;
    section sec{"1. Set-up", {}};
    // With friction the equations stay in world components (explain_friction.cpp).
    const contact_frame_view view = fr ? world_components_view(d) : contact_frame_view_of(d);

    const std::string kind = fr ? std::string(dim == 2 ? "A planar (2-D)" : "A 3-D") + " impact with Coulomb friction"
                                : std::string("A smooth ") + (dim == 2 ? "planar (2-D)" : "3-D") + " impact";
    // The movable body strikes an immovable one at rest (as the figure's caption says it); a
    // moving body of infinite mass (a bat) strikes.
    paragraph strikes;
    strikes.w(kind + ": ");
    if (p.bodies[i1].infinite_mass && p.bodies[i1].at_rest() && !p.bodies[i2].infinite_mass)
        strikes.t("point $B$ of ").w(body_ref(p, i2)).t(" strikes point $A$ of ").w(body_ref(p, i1));
    else
        strikes.t("point $A$ of ").w(body_ref(p, i1)).t(" strikes point $B$ of ").w(body_ref(p, i2));
    sec.para(strikes.t(". The impulsive forces change the velocities instantly without changing the positions."));
    if (is_a<symbol>(p.restitution))
        sec.para(paragraph().t("Newton's coefficient of restitution is ").m(p.restitution).t(" ($0 ≤ e ≤ 1$)."));
    else
        sec.para(paragraph().t("Newton's coefficient of restitution is $e$ = ").m(p.restitution).w("."));
    if (fr)
        sec.para(friction_coefficient(*fr));
    if (!p.units.empty())
        sec.para(paragraph().w("Units: " + units_key(p) + "."));

    // A unit follows numbers only, never a symbol (a numeric problem is taught in symbols first).
    auto unit_of = [&](quantity q, const ex &a, const ex &b = 0, const ex &c = 0) {
        return is_a<numeric>(a) && is_a<numeric>(b) && is_a<numeric>(c) ? unit(p, q) : std::string();
    };
    std::vector<paragraph> bodies;
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body &b = p.bodies[i];
        paragraph q;
        q.w(body_ref(p, i) + ": ");
        if (b.infinite_mass)
            q.w("infinite mass (its motion is given; the impulse cannot change it)");
        else
            q.t("mass ").m(b.mass).w(unit_of(quantity::mass, b.mass));
        if (b.particle) {
            q.w(", a particle (no rotational inertia)");
        } else if (dim == 2) {
            q.t(", moment of inertia about $C$ (along $e_b$) ")
                .m(b.inertia[2][2])
                .w(unit_of(quantity::inertia, b.inertia[2][2]));
        } else {
            q.t(", inertia tensor about $C$ with rows ");
            for (int r = 0; r < 3; ++r) {
                if (r)
                    q.w(", ");
                vector_span(q, b.inertia[r], 3);
            }
            q.w(unit_of(quantity::inertia, b.inertia[0][0], b.inertia[1][1], b.inertia[2][2]));
        }
        q.t("; centre of mass $C$ at ");
        vector_span(q, b.position, dim).w(unit_of(quantity::length, b.position[0], b.position[1], b.position[2]));
        q.t("; before impact $~v_C$ = ");
        vector_span(q, b.velocity, dim).w(unit_of(quantity::velocity, b.velocity[0], b.velocity[1], b.velocity[2]));
        if (!b.particle || b.infinite_mass) {
            q.t(", $ω$ = ");
            if (dim == 2)
                q.m(b.angular_velocity[2]);
            else
                vector_span(q, b.angular_velocity, 3);
            q.w(unit_of(quantity::angular_velocity, b.angular_velocity[0], b.angular_velocity[1],
                        b.angular_velocity[2]));
        }
        q.w(".");
        if (const pivot *pv = p.pivot_of(i)) {
            q.t(" Pinned at the fixed point $E$ = ");
            vector_span(q, pv->point, dim);
            q.t(": it can only rotate about $E$.");
        }
        bodies.push_back(q);
    }
    sec.list(bodies);

    paragraph frame;
    frame.t("The contact point $O$ = ");
    vector_span(frame, p.contact.point, dim);
    frame.t(
        " is a geometric point, fixed in the inertial frame, where $A$ and $B$ coincide. The contact frame: $e_n$ = ");
    vector_span(frame, d.n_hat, dim);
    frame.t(" (the common normal, from body 1 into body 2), $e_t$ along ");
    vector_span(frame, d.t_dir, dim);
    if (dim == 3) {
        frame.t(", $e_b$ along ");
        vector_span(frame, d.b_dir, 3);
    } else {
        frame.t(", and $e_b$ normal to the plane of motion");
    }
    frame.w(".");
    if (p.axes[0] == "t")
        frame.t(" The world axes are named $t$, $n$, $b$: a component with subscript $t$, $n$ or $b$ is along $e_t$, "
                "$e_n$ or $e_b$.");
    else if (d.frame_is_world)
        frame.w(" These are world axes (up to sign), so components can be read off directly.");
    else if (view.active)
        frame.t(
            p.dimension == 3
                ? " The equations below are written in contact-frame components, as in the notes: a vector $~a$ has "
                  "$a_t = ~a·e_t$, $a_n = ~a·e_n$ and $a_b = ~a·e_b$, so that $~a = a_t e_t + a_n e_n + a_b e_b$ "
                  "(the answer at the end is in world components)."
                : " The equations below are written in contact-frame components, as in the notes: a velocity $~v$ has "
                  "$v_t = ~v·e_t$ and $v_n = ~v·e_n$, so that $~v = v_t e_t + v_n e_n$; spins are along $e_b$ "
                  "(the answer at the end is in world components).");
    else
        frame.t(" The equations below are written in world components; the contact-frame components "
                "of a velocity are $v_t = ~v·e_t$ and $v_n = ~v·e_n$; the numbers at the end give "
                "them for both bodies.");
    sec.para(frame);
    sec.picture(figure_of(d));
    if (view.active && !view.inputs.empty()) {
        std::vector<math_row> input_rows;
        for (const frame_component &c : view.inputs) {
            math_row r = row(c.sym, impactgen::tidy(c.world));
            r.note.w(c.meaning);
            input_rows.push_back(r);
        }
        sec.para(paragraph().w(p.dimension == 3 ? "The velocities and spins before impact in the contact frame:"
                                                : "The velocities before impact in the contact frame:"));
        sec.rows(input_rows);
    }
    if (view.active && !view.inertia.empty()) {
        std::vector<math_row> inertia_rows;
        for (const frame_component &c : view.inertia) {
            math_row r = row(c.sym, c.world);
            r.note.w(c.meaning);
            inertia_rows.push_back(r);
        }
        sec.para(paragraph().t(
            "The inertia tensors in the contact frame, $I_tn = e_t·~~I e_n$ and so on (the angular momentum "
            "equations below use them; the tensor is symmetric, $I_nt = I_tn$):"));
        sec.rows(inertia_rows);
    }

    // Known and unknown.
    paragraph known;
    known.t("Known before impact: the velocities $~v_C$ and angular velocities $ω$ of both bodies (above). "
            "To be found after impact:");
    sec.para(known);
    std::vector<math_row> unknown_rows;
    for (const frame_component &u : view.unknowns) {
        math_row r;
        r.lhs_note = {"", ""};
        r.lhs = u.sym;
        r.rel = "";
        r.note.w(u.meaning);
        unknown_rows.push_back(r);
    }
    if (fr)
        for (const auto &[sym, meaning] : fr->impulses) {
            math_row r;
            r.lhs = sym;
            r.rel = "";
            r.note = meaning;
            unknown_rows.push_back(r);
        }
    sec.rows(unknown_rows);

    // Why this many.
    std::vector<paragraph> why;
    std::string sum;
    for (std::size_t i : {i1, i2}) {
        const body &b = p.bodies[i];
        std::size_t nv = 0, nw = 0;
        for (const unknown &u : d.unknowns)
            if (u.owner == i && u.kind == unknown_kind::velocity)
                ++nv;
            else if (u.owner == i && u.kind == unknown_kind::angular_velocity)
                ++nw;
        paragraph q;
        q.w(body_ref(p, i) + ": " + number_word(nv + nw) + " unknowns");
        if (b.infinite_mass)
            q.t(i == p.contact.body2 ? " -- infinite mass: a finite impulse does not affect it, $~v′_C = ~v_C$ and "
                                       "$~ω′ = ~ω$ (the notes' $m2 → ∞$ case)"
                                     : " -- infinite mass: a finite impulse does not affect it, $~v′_C = ~v_C$ and "
                                       "$~ω′ = ~ω$ (the notes' $m2 → ∞$ "
                                       "case, with the bodies' roles exchanged)");
        else if (p.immovable(i))
            q.w(" -- a particle pinned at a fixed point cannot move");
        else if (b.particle)
            q.w(" -- a particle: " + number_word(nv) + " velocity components, no angular velocity");
        else if (dim == 2)
            q.t(" -- planar: $~v′_C$ has 2 components in the plane of $e_n$ and $e_t$, and $~ω′$ only a component "
                "along $e_b$, "
                "because $C$ lies in the plane and $e_b$ is a principal axis at $C$");
        else
            q.t(" -- 3 components of $~v′_C$ and 3 of $~ω′$");
        if (p.pivot_of(i) && !p.immovable(i))
            q.t(" (the pin at $E$ also ties $~v′_C$ to $~ω′$: $~v′_C = ~ω′ × ~r_EC$, equations the notes use without "
                "numbering them)");
        why.push_back(q);
        sum += (sum.empty() ? "" : " + ") + std::to_string(nv + nw);
    }
    if (fr) {
        std::size_t nr = 0;
        for (const unknown &u : d.unknowns)
            if (u.kind == unknown_kind::pivot_impulse)
                ++nr;
        const std::size_t nt = static_cast<std::size_t>(dim - 1);
        paragraph q;
        q.w("impulses: 1 + " + std::to_string(nt) + (nr ? " + " + std::to_string(nr) : ""))
            .t(" -- with friction the contact impulse has an unknown tangential part, so each body's impulse-momentum "
               "is written with the impulses as unknowns: the normal impulse $N$ and the ")
            .t(dim == 2 ? "friction impulse $F$ along $e_t$"
                        : "2 components of the friction impulse $~F$ in the tangent plane");
        if (nr)
            q.w(", and the " + std::to_string(nr) + " components of the pivot's reaction impulse");
        why.push_back(q);
        sum += " + 1 + " + std::to_string(nt) + (nr ? " + " + std::to_string(nr) : "");
    } else if (d.impulse_form) {
        std::size_t nr = 0;
        for (const unknown &u : d.unknowns)
            if (u.kind == unknown_kind::pivot_impulse)
                ++nr;
        why.push_back(paragraph()
                          .w("impulses: 1 + " + std::to_string(nr))
                          .t(" -- with a pivot the notes write impulse-momentum for each body separately, so the "
                             "normal impulse $∫N dt$ "
                             "and the ")
                          .w(std::to_string(nr))
                          .t(" components of the pivot's reaction impulse $~R$ become unknowns too"));
        sum += " + 1 + " + std::to_string(nr);
    }
    if (dim == 3)
        sec.para(paragraph().t("Two free rigid bodies in 3-D have 3 + 3 unknowns each ($~v′_C$ and $~ω′$): 12 in all, "
                               "the notes' general case. Here:"));
    else
        sec.para(paragraph().t(
            "A free rigid body in plane motion has 3 unknowns (2 components of $~v′_C$ and $ω′$ along $e_b$): "
            "6 for two bodies, the notes' smooth planar impact. Here:"));
    sec.list(why);
    const std::size_t extra = fr ? fr->impulses.size() : 0;
    sec.para(paragraph().w("Number of unknowns: " + sum + " = " + std::to_string(d.count_unknowns() + extra) + "."));
    // Central or not: a body whose centre of mass lies on the line of impact feels no moment about C
    // (smooth contact only: a friction impulse has a moment about C).
    if (!fr) {
        std::vector<std::size_t> central;
        for (std::size_t i : {i1, i2}) {
            const vec3 r = cross(p.contact.point - p.bodies[i].position, d.n_hat);
            if (p.pivot_of(i) || p.bodies[i].infinite_mass)
                continue;
            // tidy(), not expand(): a point like (a + b + ...)^12 must not be expanded
            if (impactgen::tidy(r[0]).is_zero() && impactgen::tidy(r[1]).is_zero() && impactgen::tidy(r[2]).is_zero())
                central.push_back(i);
        }
        const bool both_particles = central.size() == 2 && p.bodies[i1].particle && p.bodies[i2].particle;
        const bool both_rigid = central.size() == 2 && !p.bodies[i1].particle && !p.bodies[i2].particle;
        if (both_particles)
            sec.para(paragraph().t(
                "A central impact: both centres of mass lie on the line of impact (through $O$ along $e_n$), so "
                "$~r_CO × e_n = 0$ for each body: the impulse has no moment about $C$, and the spin of a sphere "
                "would be unchanged by it. The bodies are therefore taken as particles, without angular velocity "
                "unknowns."));
        // In 3-D, the example that keeps the spins (its solution is checked by Prose.SpinningSpheres...).
        if (both_particles && dim == 3)
            sec.para(paragraph().t(
                "Kept as spinning spheres instead (inertia $2 m R²/5$ about every diameter, 12 unknowns: "
                "the example spinning-spheres.json in examples/problems of impactgen's sources), the same "
                "equations find every spin unchanged, $~ω′ = ~ω$, and the same velocities $~v′_C$."));
        else if (both_rigid)
            sec.para(paragraph().t(
                "A central impact: both centres of mass lie on the line of impact (through $O$ along $e_n$), so "
                "$~r_CO × e_n = 0$ for each body: the impulse has no moment about $C$. The angular momentum "
                "equations below keep the angular velocities as unknowns, and the solution finds each spin "
                "unchanged, $~ω′ = ~ω$: the impact changes only the velocities of the centres along $e_n$."));
        else
            for (std::size_t i : central)
                if (!p.bodies[i].particle)
                    sec.para(paragraph()
                                 .t("The line of impact passes through the centre of mass of ")
                                 .w(body_ref(p, i))
                                 .t(": $~r_CO × e_n = 0$, so the impulse has no moment about its $C$ and its spin is "
                                    "unchanged."));
    }
    if (d.impulse_form && !fr && dim == 2)
        sec.para(paragraph().t(
            "The notes' hinged-rod example names 6 unknowns -- the ball's $v′_1$, the rod's $~v′_G$ (2 components) and "
            "$ω′_3$, $∫N dt$ and the pin's $∫A_1 dt$ -- and numbers 5 equations; the sixth, that the pin is fixed "
            "($v′_G1 = ω′_3 l/2$), they use without a number. Here every velocity and impulse component is an unknown, "
            "also those the notes know to be zero at sight, and every equation is written out."));
    return sec;
}

namespace
{

section impulse_section(const derivation &d)
{
    const problem &p = d.prob;
    const std::size_t i1 = p.contact.body1, i2 = p.contact.body2;
    section sec{"2. The impulses (impulse-momentum diagram in words)", {}};
    std::vector<paragraph> items;
    items.push_back(paragraph()
                        .t("At the contact the normal reaction $N$ acts along $e_n$ for a very short time; its impulse "
                           "$∫N dt$ acts on ")
                        .w(body_ref(p, i2))
                        .t(" along $+e_n$ and on ")
                        .w(body_ref(p, i1))
                        .t(" along $-e_n$ (action and reaction)."));
    items.push_back(paragraph()
                        .t("The bodies are smooth: the tangential impulse $∫T dt = 0$, so no impulse acts along $e_t$")
                        .t(p.dimension == 3 ? " or $e_b$." : "."));
    for (const pivot &pv : p.pivots) {
        paragraph q;
        q.t("The pin at $E$ = ");
        vector_span(q, pv.point, p.dimension);
        q.t(" exerts an unknown reaction impulse $~R$ on ").w(body_ref(p, pv.body) + ".");
        items.push_back(q);
    }
    for (std::size_t i : {i1, i2})
        if (p.bodies[i].infinite_mass)
            items.push_back(paragraph()
                                .w(body_ref(p, i))
                                .t(" has infinite mass: the finite impulse $∫N dt$ does not change its motion."));
    items.push_back(
        paragraph().w("Finite forces such as gravity give no impulse over the (almost zero) contact time."));
    sec.list(items);

    std::vector<math_row> rows;
    for (std::size_t i : {i1, i2}) {
        const body &b = p.bodies[i];
        if (b.infinite_mass)
            continue;
        const bool short_label = b.label.size() == 1 && std::isalnum(static_cast<unsigned char>(b.label[0]));
        std::string L = short_label ? b.label : "," + b.label;
        std::string LT = short_label ? b.label : ",\\text{" + names::latex_text(b.label) + "}";
        std::string sign = i == i1 ? "-" : "";
        const pivot *pv = p.pivot_of(i);
        // the mass as the symbols name it: m1, m_puck (not m,puck)
        const std::string M = short_label ? "m" + b.label : "m_" + b.label;
        const std::string MT = short_label ? "m_{" + b.label + "}" : "m_{\\text{" + names::latex_text(b.label) + "}}";
        math_row r;
        r.lhs_note = {M + " (v′_C" + L + " - v_C" + L + ")",
                      MT + " (\\underline{v}'_{C" + LT + "} - \\underline{v}_{C" + LT + "})"};
        r.rel = "=";
        r.rhs = 0;
        r.lhs_note.text += " = " + sign + "∫N dt e_n" + (pv ? " + R" : "");
        r.lhs_note.tex += " = " + sign + "\\int N\\,dt\\;\\hat{\\underline{e}}_n" + (pv ? " + \\underline{R}" : "");
        r.rel = "";
        r.note.w("impulse-momentum of " + body_ref(p, i));
        rows.push_back(r);
    }
    sec.rows(rows);
    return sec;
}

section equations_section(const derivation &d)
{
    const problem &p = d.prob;
    section sec{"3. The equations", {}};
    if (d.impulse_form)
        sec.para(paragraph().t(
            "A body is pinned, so, as in the notes' constrained collision, impulse-momentum is written for each body "
            "separately, with $∫N dt$ and the pivot impulse $~R$ as unknowns; angular impulse is taken about the pivot "
            "$E$, "
            "fixed in the inertial frame, where the pivot impulse has no moment."));
    else
        sec.para(paragraph().t(
            "The bodies are unconstrained, so the notes use conservation laws in which the unknown impulse $∫N dt$ "
            "does not appear: tangential momentum of each body, linear momentum of the system along $e_n$, "
            "angular momentum of each body about $O$, and restitution."));

    // Equations are grouped by principle and bodies; the words come from those (typed), never from the
    // derivation's ASCII sentence. In contact-frame components where the normal is not a world axis.
    const contact_frame_view view = contact_frame_view_of(d);
    std::size_t k = 0;
    while (k < view.equations.size()) {
        const equation &first = *view.equations[k].source;
        std::vector<math_row> rows;
        std::size_t j = k;
        for (; j < view.equations.size(); ++j) {
            const framed_equation &f = view.equations[j];
            const equation &eq = *f.source;
            if (eq.why != first.why || eq.bodies != first.bodies)
                break;
            math_row r = row(f.lhs, f.rhs, eq.label);
            if (f.axis == "t")
                r.note.t("component along $e_t$");
            else if (f.axis == "n")
                r.note.t("component along $e_n$");
            else if (f.axis == "b")
                r.note.t("component along $e_b$");
            else if (!f.axis.empty())
                r.note.t("component along ").w(f.axis);
            rows.push_back(r);
        }
        const std::size_t i = first.bodies.empty() ? no_body : first.bodies[0];
        const pivot *pv = i == no_body ? nullptr : p.pivot_of(i);
        std::string title = principle_name(first.why);
        title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(title[0])));
        paragraph why;
        why.w(title + ": ");
        switch (first.why) {
        case principle::smooth_contact:
            why.w("the bodies are smooth, so no impulse acts on " + body_ref(p, i))
                .t(p.dimension == 3 ? " along $e_t$ or $e_b$: its centre-of-mass velocity along them is unchanged."
                                    : " along $e_t$: its centre-of-mass velocity along $e_t$ is unchanged.");
            break;
        case principle::system_momentum:
            why.t("the impulse $N e_n$ is internal to the system of both bodies, and no other impulse acts, so their "
                  "linear "
                  "momentum along $e_n$ is conserved:");
            break;
        case principle::linear_impulse:
            why.w("the change of linear momentum of " + body_ref(p, i) + " equals the impulses on it, ")
                .t(i == p.contact.body1 ? "$-N e_n$" : "$+N e_n$")
                .t(pv ? " and the pivot impulse $~R$." : ".");
            break;
        case principle::angular_momentum:
            if (pv)
                why.t("about the pivot $E$, fixed in the inertial frame, the pivot impulse has no moment: the change "
                      "of angular "
                      "momentum of ")
                    .w(body_ref(p, i))
                    .t(" about $E$ is the moment of the contact impulse. Its angular momentum about $E$ is that about "
                       "$C$ plus "
                       "the moment of the momentum of $C$ (which is $~~I_E ~ω$, with $~~I_E$ the inertia about $E$, "
                       "while the body "
                       "turns about $E$); in components:");
            else
                why.w("the contact impulse on " + body_ref(p, i))
                    .t(" passes through $O$, which is fixed in the inertial frame, so its moment about $O$ is zero and "
                       "the "
                       "angular momentum about $O$ is conserved, $~H′_O = ~H_O$. Taken about $O$, the angular momentum "
                       "is "
                       "that about $C$ plus the moment of the momentum of $C$; in components:");
            break;
        case principle::pivot_fixed:
            why.t("the pivot $E$ of ")
                .w(body_ref(p, i))
                .t(" does not move, so the body's velocity at $E$ is zero after impact:");
            break;
        case principle::restitution:
            why.t("Newton's coefficient of restitution: the normal velocity of separation of the contact points is $e$ "
                  "times "
                  "their velocity of approach.");
            break;
        case principle::stick:
        case principle::slide: // Coulomb's law: not an equation of the smooth impact
            break;
        }
        sec.para(why);
        if (first.why == principle::angular_momentum) {
            if (pv) {
                const bool on1 = i == p.contact.body1;
                sec.rows({formula_row("H_E = I_C ω + r_EC × m v_C",
                                      "\\underline{H}_E = \\underline{\\underline{I}}_C\\,\\underline{\\omega} + "
                                      "\\underline{r}_{EC} \\times m\\,\\underline{v}_C"),
                          formula_row(on1 ? "H′_E - H_E = -r_EO × ∫N dt e_n" : "H′_E - H_E = r_EO × ∫N dt e_n",
                                      std::string("\\underline{H}'_E - \\underline{H}_E = ") + (on1 ? "-" : "") +
                                          "\\underline{r}_{EO} \\times \\int N\\,dt\\;\\hat{\\underline{e}}_n")});
            } else {
                sec.rows(
                    {formula_row("H_O = I_C ω + r_OC × m v_C",
                                 "\\underline{H}_O = \\underline{\\underline{I}}_C\\,\\underline{\\omega} + "
                                 "\\underline{r}_{OC} \\times m\\,\\underline{v}_C",
                                 ""),
                     formula_row("I_C ω′ + r_OC × m v′_C = I_C ω + r_OC × m v_C",
                                 "\\underline{\\underline{I}}_C\\,\\underline{\\omega}' + \\underline{r}_{OC} \\times "
                                 "m\\,\\underline{v}'_C = \\underline{\\underline{I}}_C\\,\\underline{\\omega} + "
                                 "\\underline{r}_{OC} \\times m\\,\\underline{v}_C")});
            }
        } else if (first.why == principle::pivot_fixed) {
            sec.rows({formula_row("v′_E = v′_C + ω′ × r_CE = 0",
                                  "\\underline{v}'_E = \\underline{v}'_C + \\underline{\\omega}' \\times "
                                  "\\underline{r}_{CE} = \\underline{0}")});
        } else if (first.why == principle::restitution) {
            const std::size_t i2 = p.contact.body2;
            sec.para(paragraph().t(
                "$e = -(v′_Bn - v′_An)/(v_Bn - v_An)$: the velocities are those of the contact points $A$ and $B$, not "
                "of the "
                "centres of mass. As $A$ and $C1$ are both points of body 1, and $B$ and $C2$ of body 2:"));
            const vec3 &n = d.n_hat;
            std::vector<math_row> pv_rows;
            pv_rows.push_back(note_row("v_An = (v_C1 + ω1 × r_AC1)·e_n",
                                       "v_{An} = (\\underline{v}_{C_1} + \\underline{\\omega}_1 \\times "
                                       "\\underline{r}_{AC_1})\\cdot\\hat{\\underline{e}}_n",
                                       view.apply(tidy_expand(dot(d.vA, n)))));
            pv_rows.push_back(note_row("v′_An = (v′_C1 + ω′1 × r_AC1)·e_n",
                                       "v'_{An} = (\\underline{v}'_{C_1} + \\underline{\\omega}'_1 \\times "
                                       "\\underline{r}_{AC_1})\\cdot\\hat{\\underline{e}}_n",
                                       view.apply(tidy_expand(dot(d.vA_after, n)))));
            pv_rows.push_back(note_row("v_Bn = (v_C2 + ω2 × r_BC2)·e_n",
                                       "v_{Bn} = (\\underline{v}_{C_2} + \\underline{\\omega}_2 \\times "
                                       "\\underline{r}_{BC_2})\\cdot\\hat{\\underline{e}}_n",
                                       view.apply(tidy_expand(dot(d.vB, n)))));
            math_row last = note_row("v′_Bn = (v′_C2 + ω′2 × r_BC2)·e_n",
                                     "v'_{Bn} = (\\underline{v}'_{C_2} + \\underline{\\omega}'_2 \\times "
                                     "\\underline{r}_{BC_2})\\cdot\\hat{\\underline{e}}_n",
                                     view.apply(tidy_expand(dot(d.vB_after, n))));
            if (p.bodies[i2].infinite_mass || p.immovable(i2))
                last.note.t("$B$ is on a body the impulse cannot move: $v′_Bn = v_Bn$");
            pv_rows.push_back(last);
            sec.rows(pv_rows);
            sec.para(paragraph().t("and $v′_Bn - v′_An = -e (v_Bn - v_An)$ reads:"));
        }
        sec.rows(rows);
        k = j;
    }
    if (!d.remarks.empty()) {
        sec.para(paragraph().w("Where a principle gives no usable equation:"));
        std::vector<paragraph> items;
        for (const remark &r : d.remarks) {
            paragraph q;
            const std::string who = body_ref(p, r.body);
            switch (r.kind) {
            case remark_kind::momentum_infinite_mass:
                q.t("Linear momentum of the system along $e_n$ is not useful: ")
                    .w(who)
                    .t(" has infinite mass, so $m (v′_n - v_n)$ "
                       "on its side is finite but unknown (infinity times zero).");
                break;
            case remark_kind::infinite_mass_unchanged:
                q.w("The velocities of " + who)
                    .t(" are unchanged: a finite impulse cannot change the motion of an infinite mass, so "
                       "it gives no angular momentum equation either.");
                break;
            case remark_kind::particle_no_rotation:
                q.w(who).t(" is a particle (no rotational inertia): it has no angular velocity unknowns, and its "
                           "angular momentum "
                           "about $O$, $~r_OC × m ~v_C$, changes only through $~v_C$, which the other equations fix: "
                           "it gives no new equation.");
                break;
            case remark_kind::pinned_particle:
                q.w(who).t(" is a particle pinned at a fixed point: it cannot rotate, so it cannot move, and its pivot "
                           "takes the whole contact impulse.");
                break;
            case remark_kind::uninvolved:
                q.w(who + " takes no part in the contact: its velocities are unchanged.");
                break;
            }
            items.push_back(q);
        }
        sec.list(items);
    }
    return sec;
}

section solution_section(const derivation &d, const solution &s)
{
    section sec{"4. Count check and solution", {}};
    const bool ok = d.count_equations() == d.count_unknowns();
    sec.para(paragraph().w(
        std::to_string(d.count_equations()) + " equations for " + std::to_string(d.count_unknowns()) +
        " unknowns: " + (ok ? "the count matches, the system can be solved." : "THE COUNT DOES NOT MATCH.")));
    sec.para(paragraph().t(
        "Every unknown changes linearly with the normal impulse $N$ (= $∫N dt$ along $e_n$): a free body gets "
        "$~v′_C = ~v_C ± N e_n/m$ and $~ω′ = ~ω ± N ~~I⁻¹(~r × e_n)$, a pinned body turns about $E$. "
        "Restitution then fixes $N$. In closed form, through named intermediates:"));
    math_row w_row = note_row("w_i = 1/m_i + (r_i × e_n)·I_i⁻¹(r_i × e_n)",
                              "w_i = \\frac{1}{m_i} + (\\underline{r}_i\\times\\hat{\\underline{e}}_n)\\cdot "
                              "\\underline{\\underline{I}}_i^{-1}(\\underline{r}_i\\times\\hat{\\underline{e}}_n)",
                              0);
    w_row.note.t("effective inverse mass of body $i$ at the contact point along $e_n$, $~r_i = O - C_i$; about the "
                 "pivot $E$ for a pinned body "
                 "(without $1/m_i$); 0 for a body the impulse cannot move");
    math_row u_row =
        note_row("u = (v_B - v_A)·e_n", "u = (\\underline{v}_B - \\underline{v}_A)\\cdot\\hat{\\underline{e}}_n", 0);
    u_row.note.t("normal velocity of approach, negative for an impact");
    math_row n_row = note_row("N = -(1 + e)·u/(w_1 + w_2)", "N = -\\frac{(1 + e)\\,u}{w_1 + w_2}", 0);
    n_row.note.t("the restitution equation solved for the normal impulse");
    sec.rows({w_row, u_row, n_row});
    // The notation rows above carry no value: mark them by an empty relation.
    for (math_row &r : sec.blocks.back().math)
        r.rel = "";

    std::vector<math_row> steps;
    const contact_frame_view view = contact_frame_view_of(d);
    for (const step &st : s.steps) {
        math_row r = row(st.sym, view.apply(st.value));
        r.note = step_note(d.prob, st);
        steps.push_back(r);
    }
    sec.para(paragraph().w("The steps, in order:"));
    sec.rows(steps);
    std::vector<math_row> unknowns;
    for (const frame_component &u : view.unknowns)
        unknowns.push_back(row(u.sym, view.apply(u.world.subs(s.unknown_values)), "", u.meaning));
    sec.para(paragraph().w("Each unknown:"));
    sec.rows(unknowns);
    return sec;
}

// Exact numbers for every step and unknown, with the equations as numbers.
void numbers_walk(section &sec, const derivation &d, const solution &s, const ex &values)
{
    lst steps = s.step_values(values);
    std::vector<math_row> eqs;
    const contact_frame_view view = contact_frame_view_of(d);
    const lst frame_values = view.with_inputs(values);
    for (const framed_equation &f : view.equations)
        eqs.push_back(
            row(tidy_expand(f.lhs.subs(frame_values)), tidy_expand(f.rhs.subs(frame_values)), f.source->label));
    sec.para(paragraph().w("The equations with these numbers:"));
    sec.rows(eqs);
    std::vector<math_row> rows;
    for (std::size_t i = 0; i < s.steps.size(); ++i) {
        // The step's formula with the inputs substituted, then its number.
        ex formula = s.steps[i].value.subs(values);
        ex v = surd_form(impactgen::tidy(steps.op(i).rhs()));
        math_row out = row(s.steps[i].sym, v, "", decimal_note(v));
        if (!is_a<numeric>(formula) && printable(formula)) {
            out.rhs = formula;
            out.has_then = true;
            out.then = v;
        }
        rows.push_back(out);
    }
    sec.para(paragraph().w("Step by step (each step with the numbers of the earlier ones):"));
    sec.rows(rows);
    lst unknown_numbers;
    std::vector<math_row> answers;
    for (std::size_t i = 0; i < d.unknowns.size(); ++i) {
        ex v = surd_form(impactgen::tidy(s.unknown_values.op(i).rhs().subs(values).subs(steps)));
        unknown_numbers.append(d.unknowns[i].sym == v);
        math_row r = row(d.unknowns[i].sym, v, "", decimal_note(v));
        const unknown_kind kind = d.unknowns[i].kind;
        r.note.w(unit(d.prob, kind == unknown_kind::velocity           ? quantity::velocity
                              : kind == unknown_kind::angular_velocity ? quantity::angular_velocity
                                                                       : quantity::impulse));
        answers.push_back(r);
    }
    sec.para(paragraph().w("The unknowns:"));
    sec.rows(answers);

    // Contact-frame components, where the frame is not the world's: the smooth-contact
    // equations then read v′_t = v_t, as in the notes.
    if (!d.frame_is_world && d.prob.axes[0] != "t") {
        const problem &p = d.prob;
        std::vector<std::pair<std::string, vec3>> dirs;
        dirs.push_back({"t", d.e_t});
        dirs.push_back({"n", d.n_hat});
        if (p.dimension == 3)
            dirs.push_back({"b", d.e_b});
        std::vector<math_row> frame_rows;
        for (std::size_t i = 0; i < p.bodies.size(); ++i) {
            if (i != p.contact.body1 && i != p.contact.body2)
                continue;
            const vec3 v0 = subs(p.bodies[i].velocity, values);
            vec3 v1 = subs(s.after[i].velocity, values);
            for (ex &c : v1)
                c = c.subs(steps);
            for (const auto &[axis, e] : dirs) {
                // roots merged before and after normal(), which keeps sqrt(3) sqrt(6) apart
                auto exact = [](const ex &x) { return surd_form(impactgen::tidy(merge_roots(tidy_expand(x)))); };
                const ex before = exact(dot(v0, e)), after = exact(dot(v1, e));
                const std::string &L = p.bodies[i].label;
                math_row r = row(show(quantity_name("v", axis, L, false), quantity_tex("v", axis, L, false)), before);
                math_row ra = row(show(quantity_name("v", axis, L, true), quantity_tex("v", axis, L, true)), after);
                // "≈ 0.914 m/s -- body 1 (ball), before", as the energies below
                const std::string u = unit(p, quantity::velocity);
                auto note = [&](const ex &value, const char *when) {
                    const std::string dec = decimal_note(value);
                    return (dec.empty() ? "" : dec + u + " -- ") + body_ref(p, i) + when +
                           (dec.empty() && !u.empty() ? " (in" + u + ")" : "");
                };
                r.note.w(note(before, ", before"));
                ra.note.w(note(after, ", after"));
                if (axis == "t" || axis == "b")
                    ra.note.t(vanishes_identically(s, after - before, "a tangential velocity")
                                  ? ": unchanged, no impulse along it"
                                  : "");
                frame_rows.push_back(r);
                frame_rows.push_back(ra);
            }
        }
        sec.para(paragraph().t(
            "In the contact frame, the centre-of-mass velocities before and after impact ($v_t = ~v_C·e_t$, "
            "$v_n = ~v_C·e_n$):"));
        sec.rows(frame_rows);
    }

    // The energy before and after, with the loss from the steps.
    const ex before = impactgen::tidy(s.energy_before.subs(values));
    const ex lost = impactgen::tidy(s.energy_lost.subs(values).subs(steps));
    if (is_a<numeric>(before) && is_a<numeric>(lost)) {
        const ex after = impactgen::tidy(before - lost);
        math_row t0 = row(show("T", "T"), before, "", decimal_note(before));
        math_row t1 = row(show("T'", "T'"), after, "", decimal_note(after));
        math_row tl = row(show("T_lost", "T_{\\mathrm{lost}}"), lost, "", decimal_note(lost));
        for (math_row *r : {&t0, &t1, &tl})
            r->note.w(unit(d.prob, quantity::energy));
        t0.note.w(" -- kinetic energy before impact");
        t1.note.w(" -- after impact");
        tl.note.w(" -- lost");
        sec.para(paragraph().w("The kinetic energy of the bodies of finite mass:"));
        sec.rows({t0, t1, tl});
    }
    bool all_zero = true, all_small = true;
    for (const ex &r : residuals(d, s, values)) {
        if (r.is_zero())
            continue;
        all_zero = false;
        // a 60-digit float residual of an irrational problem: zero to 40 digits
        const bool small = is_a<numeric>(r) && abs(ex_to<numeric>(r)) < numeric(1, 10).power(40);
        all_small = all_small && small;
    }
    const std::string range = "(1)-(" + d.equations.back().label + ")";
    sec.para(paragraph().w(all_zero    ? "Substituted back, every equation " + range + " holds exactly."
                           : all_small ? "Substituted back, every equation " + range +
                                             " holds to 40 digits (evaluated with 60-digit floats: with these "
                                             "irrational numbers exactness is not decided)."
                                       : "Substituted back, SOME EQUATION DOES NOT HOLD: this is a bug."));
}

// The centre of percussion of a pinned body in plane motion: where the contact
// impulse must act for the pin to take none along e_n. With d = C - E and the
// lever arms c = (d × n)_z of C and s = ((O - E) × n)_z of the impulse about E, the
// body's angular impulse about E gives I_E Δω = s N and its momentum along n
// m c Δω = N + R·n; so R·n = N (m c s / I_E - 1), zero when s = I_E/(m c).
void percussion(section &sec, const derivation &d, const solution &s)
{
    const problem &p = d.prob;
    if (p.dimension != 2)
        return;
    for (const pivot &pv : p.pivots) {
        const body &b = p.bodies[pv.body];
        if (b.particle || b.infinite_mass)
            continue;
        const vec3 dC = b.position - pv.point, dO = p.contact.point - pv.point;
        const ex c = impactgen::tidy(dC[0] * d.n_hat[1] - dC[1] * d.n_hat[0]);
        const ex lever = impactgen::tidy(dO[0] * d.n_hat[1] - dO[1] * d.n_hat[0]);
        const ex IE = impactgen::tidy(b.inertia[2][2] + b.mass * (dC[0] * dC[0] + dC[1] * dC[1]));
        if (c.is_zero())
            continue;
        const ex star = impactgen::tidy(IE / (b.mass * c));
        sec.para(
            paragraph()
                .t("Centre of percussion of ")
                .w(body_ref(p, pv.body))
                .t(": about its pivot $E$ the angular impulse gives $I_E Δω = s N$ and its momentum along $e_n$ gives "
                   "$m c Δω = ± N + R_n$, with $c$ and $s$ the lever arms of $C$ and of the impulse about $E$. So "
                   "the pin takes no impulse along $e_n$ when the impulse acts at the distance $s* = I_E/(m c)$ from "
                   "$E$ "
                   "(the centre of percussion; its part along $e_t$, $m Δω (e_b × ~r_EC)·e_t$, is zero when the line "
                   "from $E$ to $C$ is perpendicular to $e_n$):"));
        math_row rc = note_row("c = ((C - E) × e_n)·e_b",
                               "c = ((C - E) \\times \\hat{\\underline{e}}_n)\\cdot\\hat{\\underline{e}}_b", c);
        math_row rs = note_row("s = ((O - E) × e_n)·e_b",
                               "s = ((O - E) \\times \\hat{\\underline{e}}_n)\\cdot\\hat{\\underline{e}}_b", lever);
        rs.note.w("the lever arm of the impulse in this problem");
        math_row rstar = note_row("s*", "s^{*}", star);
        rstar.note.w(vanishes_identically(s, lever - star, "the centre of percussion")
                         ? "the impulse acts at the centre of percussion: the pin takes no impulse along the normal"
                         : "the impulse acts elsewhere, so the pin takes an impulse along the normal");
        sec.rows({rc, rs, rstar});
    }
}

section checks_section(const derivation &d, const solution &s, const worked_example *example)
{
    const problem &p = d.prob;
    section sec{"5. Checks", {}};

    // A copy of the problem with a symbol for e, to vary e.
    ex e_val = p.restitution;
    symbol e_sym = is_a<symbol>(e_val) ? ex_to<symbol>(e_val) : symbol_named("e");
    problem pe = p;
    pe.restitution = e_sym;
    derivation de = is_a<symbol>(e_val) ? d : derive(pe);
    solution se = is_a<symbol>(e_val) ? s : solve(de);
    if (!is_a<symbol>(e_val))
        sec.para(paragraph()
                     .t("To vary $e$, the checks below keep $e$ as a symbol; the problem has $e$ = ")
                     .m(e_val)
                     .w("."));

    const std::vector<step_role> core = {step_role::energy_lost, step_role::normal_impulse,
                                         step_role::contact_inverse_mass, step_role::approach_velocity};
    ex lost = expand_some(se, se.energy_lost, core);
    const step *u_step = find_step(se, step_role::approach_velocity);
    const step *k_step = find_step(se, step_role::contact_inverse_mass);
    const step *N_step = find_step(se, step_role::normal_impulse);
    ex N_val = N_step ? N_step->value : ex(se.normal_impulse);
    ex u = u_step ? ex(u_step->sym) : ex(0);
    // k as N's formula has it: w_1 + w_2, or w_1 alone against an infinite mass.
    ex kk = k_step ? ex(k_step->sym) : (u_step ? impactgen::tidy(-(1 + e_sym) * u / N_val) : ex(0));

    // Energy.
    sec.para(paragraph().w("Kinetic energy lost (bodies of finite mass), the work of the contact impulse:"));
    std::vector<math_row> energy;
    const step *lost_step = find_step(se, step_role::energy_lost);
    if (lost_step)
        energy.push_back(row(lost_step->sym, lost_step->value));
    ex textbook = kk.is_zero() ? ex(0) : (1 - e_sym * e_sym) * pow(u, 2) / (2 * kk);
    bool textbook_ok =
        !kk.is_zero() && u_step && vanishes_identically(se, lost - expand_some(se, textbook, core), "the energy check");
    if (textbook_ok && lost_step) {
        math_row r = row(lost_step->sym, textbook);
        r.note.t("with $N = -(1 + e) u/k$ substituted and simplified: $1 - e² ≥ 0$ and $k > 0$, so $T_lost ≥ 0$");
        energy.push_back(r);
    }
    ex at_one = impactgen::tidy(lost.subs(e_sym == 1));
    // Against a moving body of infinite mass the loss at e = 1 is not zero. Expanded it runs
    // over lines (massive-3d: 17 terms); through the named steps it is short: with N = -2u/k,
    // T_lost = -2 u v_Bn/k when body 2 has the infinite mass (v_Bn = v_B·e_n, its contact
    // point's normal velocity), +2 u v_An/k when body 1 has. Shown when it checks out.
    std::vector<math_row> named_at_one;
    if (lost_step && !at_one.is_zero() && u_step && !kk.is_zero()) {
        const bool two = p.bodies[p.contact.body2].infinite_mass, one = p.bodies[p.contact.body1].infinite_mass;
        if (two != one) {
            const ex vn = impactgen::tidy(tidy_expand(dot(two ? de.vB : de.vA, de.n_hat)));
            const symbol vn_sym = two ? symbol("v_Bn", "v_{Bn}") : symbol("v_An", "v_{An}");
            const ex form = (two ? -2 : 2) * u * vn_sym / kk;
            bool holds = false;
            try {
                holds = vanishes_identically(se, lost.subs(e_sym == 1) - form.subs(vn_sym == vn), "the loss at e = 1");
            } catch (const std::exception &) {
                holds = false;
            }
            if (holds && printable(vn, 120)) {
                math_row r = row(lost_step->sym, form);
                r.note.t(two ? "at $e = 1$ (the impulse twice the plastic one): the work of the moving body of "
                               "infinite mass, "
                               "whose contact point $B$ has the normal velocity"
                             : "at $e = 1$ (the impulse twice the plastic one): the work of the moving body of "
                               "infinite mass, "
                               "whose contact point $A$ has the normal velocity");
                named_at_one.push_back(r);
                named_at_one.push_back(row(vn_sym, vn));
            }
        }
    }
    if (lost_step && !named_at_one.empty()) {
        for (const math_row &r : named_at_one)
            energy.push_back(r);
    } else if (lost_step) {
        math_row r = row(lost_step->sym, at_one);
        r.note.t("at $e = 1$");
        energy.push_back(r);
    }
    sec.rows(energy);
    sec.para(paragraph().t(
        "The energy before impact is $T = Σ (1/2 m |~v_C|² + 1/2 ~ω·~~I_C ~ω)$ over the bodies of finite mass, "
        "and after it $T′ = T - T_lost$."));
    if (at_one.is_zero())
        sec.para(paragraph().t("At $e = 1$ no energy is lost: the elastic impact conserves kinetic energy."));
    else
        sec.para(paragraph().t(
            "At $e = 1$ the loss is not zero: a moving body of infinite mass does work on the other body, and "
            "its own energy is not counted (see problem-format: that is physics, not an error)."));

    // Limits of e.
    ex N = se.normal_impulse;
    ex sep_symbolic = -e_sym * u;
    sec.para(paragraph()
                 .t("The limits of $e$, in the normal impulse and the normal velocity of separation $(~v′_B - "
                    "~v′_A)·e_n = -e u$ (equation ")
                 .ref(de.equations.back().label)
                 .w("):"));
    std::vector<math_row> lim;
    math_row r0 = row(N, N_val.subs(e_sym == 0), "e = 0");
    r0.note.t("plastic: the contact points move on together, $(~v′_B - ~v′_A)·e_n$ = ")
        .m(sep_symbolic.subs(e_sym == 0));
    math_row r1 = row(N, N_val.subs(e_sym == 1), "e = 1");
    r1.note.t("elastic: twice the plastic impulse, $(~v′_B - ~v′_A)·e_n$ = ")
        .m(sep_symbolic.subs(e_sym == 1))
        .t(" = $|u|$, the contact points separate as fast as they approached");
    lim.push_back(r0);
    lim.push_back(r1);
    sec.rows(lim);

    // m2 -> infinity.
    const std::size_t i2 = p.contact.body2;
    const body &b2 = p.bodies[i2];
    if (b2.infinite_mass) {
        sec.para(paragraph().t("$m2 → ∞$: body 2 already has infinite mass; the notes' massive case, $w_2 = 0$ and $N "
                               "= -(1 + e) u/w_1$."));
    } else if (p.immovable(i2)) {
        sec.para(paragraph().t("$m2 → ∞$: body 2 cannot move under the impulse already ($w_2 = 0$)."));
    } else if (p.immovable(p.contact.body1)) {
        // Body 1 already cannot move: making body 2 heavy too would leave nothing to move.
        sec.para(paragraph().t(
            "$m2 → ∞$ is not taken here: body 1 cannot move under the impulse already ($w_1 = 0$), so this is "
            "the notes' massive case with the bodies' roles exchanged, $N = -(1 + e) u/w_2$; were body 2 "
            "infinitely heavy as well, nothing could move."));
    } else {
        // Body 2 grows heavy with its shape kept: m2 -> m2/eps, I_2 -> I_2/eps. Its
        // effective inverse mass scales exactly: w_2(eps) = eps w_2 (1/m and I^-1
        // both scale with eps, about C or about the pivot alike), so with
        // k = w_1 + eps w_2 the impulse tends to the notes' massive case and body
        // 2's velocity change N n eps/m2 tends to zero. No symbolic limit is
        // taken (normal() of a 3-D closed form has no useful time bound).
        const step *w1 = find_step(se, step_role::effective_inverse_mass, p.contact.body1);
        const ex w1_value =
            w1 ? ex(w1->sym) : (p.immovable(p.contact.body1) ? ex(0) : 1 / p.bodies[p.contact.body1].mass);
        paragraph q;
        q.t("$m2 → ∞$: let body 2 grow heavy with its shape kept, $m2 → m2/ε$ and its inertia $~~I → ~~I/ε$, and take "
            "$ε → 0$. "
            "Both $1/m2$ and $~~I⁻¹$ scale with $ε$, so $w_2 → ε w_2$ exactly and $k → w_1 + ε w_2$:");
        sec.para(q);
        std::vector<math_row> rows;
        math_row rw = row(show("w_2", "w_2"), 0, "", "body 2 no longer yields at B");
        rw.rel = "→";
        rows.push_back(rw);
        if (!w1_value.is_zero()) {
            ex N_inf = -(1 + e_sym) * u / w1_value;
            math_row rn = row(N, N_inf);
            rn.note.t("finite: the notes' massive case, $N = -(1 + e) u/w_1$");
            rn.rel = "→";
            rows.push_back(rn);
            math_row rv = note_row("|v′_C2 - v_C2|²", "|\\underline{v}'_{C_2} - \\underline{v}_{C_2}|^2", 0);
            rv.note.t("$~ω′_2 ≈ ~ω_2$ and $~v′_C2 ≈ ~v_C2$: body 2 is unaffected (its change $N ε/m2 → 0$)");
            rv.rel = "→";
            rows.push_back(rv);
        }
        sec.rows(rows);
    }

    percussion(sec, d, s);

    // Numbers.
    if (p.is_numeric()) {
        sec.para(paragraph().w("The problem is numeric: every step and unknown above is an exact number."));
        numbers_walk(sec, d, s, lst{});
    } else if (example) {
        if (example->problem_numbers)
            sec.para(paragraph().w("The problem's numbers: substitute"));
        else
            sec.para(paragraph().w("Worked example (" + example->caption + "): substitute"));
        std::vector<math_row> vals;
        for (std::size_t k = 0; k < example->values.nops(); ++k) {
            const ex rel = example->values.op(k);
            math_row r = row(rel.lhs(), rel.rhs());
            if (k < example->units.size())
                r.note.w(example->units[k]);
            vals.push_back(r);
        }
        sec.rows(vals);
        numbers_walk(sec, d, s, example->values);
    }
    return sec;
}

} // namespace

bool notes_example(const std::string &class_name, worked_example &out)
{
    if (class_name != "pinned-planar")
        return false;
    out.caption =
        "the notes' example: a ball of 0.5 kg at 5 m/s strikes the lower end of a hanging rod of 2 kg and 1 m, e = 0.8";
    out.values = lst{symbol_named("m1") == numeric(1, 2), symbol_named("v1") == 5, symbol_named("m2") == 2,
                     symbol_named("l") == 1, symbol_named("e") == numeric(4, 5)};
    return true;
}

// A numeric problem's twin for teaching: a symbol for every non-zero mass, moment
// of inertia entry, velocity and angular velocity component, for e and for a non-zero
// friction coefficient μ, named as the unknowns are (v_x1, ω_z,puck); the geometry
// (positions, contact, normal, pivots) keeps its numbers, so the formulas stay short.
// `values` gets symbol == number.
problem detail::symbolized(const problem &p, lst &values, std::vector<std::string> &units)
{
    problem q = p;
    auto name = [&](const std::string &base, const std::string &base_tex, const std::string &axis, const body &b,
                    ex &slot, quantity what) {
        if (slot.is_zero())
            return;
        symbol s(quantity_name(base, axis, b.label, false), quantity_tex(base_tex, axis, b.label, false));
        values.append(s == slot);
        units.push_back(unit(p, what));
        slot = s;
    };
    for (body &b : q.bodies) {
        if (!b.infinite_mass) {
            // "m1", or "m_ball" for a named body
            const bool one = b.label.size() == 1 && std::isalnum(static_cast<unsigned char>(b.label[0]));
            symbol m(one ? "m" + b.label : "m_" + b.label,
                     one ? "m_{" + b.label + "}" : "m_{\\text{" + names::latex_text(b.label) + "}}");
            values.append(m == b.mass);
            units.push_back(unit(p, quantity::mass));
            b.mass = m;
        }
        const int n = p.dimension;
        for (int c = 0; c < n; ++c)
            name("v", "v", q.axes[static_cast<std::size_t>(c)], b, b.velocity[static_cast<std::size_t>(c)],
                 quantity::velocity);
        if (!b.particle || b.infinite_mass) {
            for (int c = n == 2 ? 2 : 0; c < 3; ++c)
                name("w", "\\omega", q.axes[static_cast<std::size_t>(c)], b,
                     b.angular_velocity[static_cast<std::size_t>(c)], quantity::angular_velocity);
        }
        if (!b.particle && !b.infinite_mass) {
            if (n == 2) {
                name("I", "I", q.axes[2], b, b.inertia[2][2], quantity::inertia);
            } else {
                for (std::size_t r = 0; r < 3; ++r)
                    for (std::size_t c = r; c < 3; ++c) {
                        ex before = b.inertia[r][c];
                        name("I", "I", q.axes[r] + q.axes[c], b, b.inertia[r][c], quantity::inertia);
                        if (c != r && !before.is_zero())
                            b.inertia[c][r] = b.inertia[r][c];
                    }
            }
        }
    }
    if (!q.restitution.is_zero()) {
        symbol e("e", "e");
        values.append(e == q.restitution);
        units.push_back("");
        q.restitution = e;
    }
    if (!q.contact.friction().is_zero()) {
        symbol mu("mu", "\\mu"); // printed μ (explain_friction writes Coulomb's coefficient so)
        values.append(mu == q.contact.friction());
        units.push_back("");
        q.contact.set_friction(mu);
    }
    return q;
}

std::optional<document> detail::taught_in_symbols(
    const derivation &d,
    const std::function<document(const derivation &, const lst &, const std::vector<std::string> &)> &teach)
{
    lst values;
    std::vector<std::string> units;
    const problem twin = symbolized(d.prob, values, units);
    if (values.nops() == 0)
        return std::nullopt;
    try {
        derive_options opt;
        opt.unit_normal = d.normal_assumed_unit;
        document doc = teach(derive(twin, opt), values, units);
        // the figure from the numbers, not from the symbols
        for (block &b : doc.sections.front().blocks)
            if (b.k == block::figure)
                b.art = figure_of(d);
        return doc;
    } catch (const std::exception &) {
        return std::nullopt; // the twin needs a decision only the numbers allow: taught with the numbers
    }
}

namespace
{

document explain_document(const derivation &d, const solution &s, const worked_example *example)
{
    document doc;
    doc.title = "Smooth impact: " + d.prob.source;
    doc.sections.push_back(setup_section(d));
    doc.sections.push_back(impulse_section(d));
    doc.sections.push_back(equations_section(d));
    doc.sections.push_back(solution_section(d, s));
    doc.sections.push_back(checks_section(d, s, example));
    return doc;
}

} // namespace

document explain(const derivation &d, const solution &s, const worked_example *example)
{
    // A numeric problem is taught as the notes teach: the equations and the named
    // steps in symbols first, then the numbers. When the symbolic twin cannot be
    // derived (a decision that needs the numbers), the numbers are shown directly.
    if (d.prob.is_numeric() && !example) {
        lst values;
        std::vector<std::string> units;
        problem twin = symbolized(d.prob, values, units);
        if (values.nops() > 0) {
            try {
                derive_options opt;
                opt.unit_normal = d.normal_assumed_unit;
                derivation d2 = derive(twin, opt);
                solution s2 = solve(d2);
                worked_example numbers{"the problem's numbers", values, true, units};
                document doc = explain_document(d2, s2, &numbers);
                // the figure from the numbers, not from the symbols
                for (block &b : doc.sections.front().blocks)
                    if (b.k == block::figure)
                        b.art = figure_of(d);
                return doc;
            } catch (const std::exception &) {
                // fall through to the numbers
            }
        }
    }
    return explain_document(d, s, example);
}

document explain(const derivation &d, const impact_solution &s, const worked_example *example)
{
    if (!d.prob.has_friction())
        return explain(d, s.cases.front().sol, example);
    return explain_friction(d, s);
}

} // namespace impactgen::print
