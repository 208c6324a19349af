// What every chapter of the explanation shares (explain_detail.hpp): the notation of
// teaching prose, the small builders of rows and spans, the figure, units and the
// symbolized twin of a numeric problem. The document is built in explain_document.cpp.
#include "explain.hpp"
#include "explain_detail.hpp"
#include "explain_smooth.hpp"

#include "canonical.hpp"
#include "contact_frame.hpp"
#include "expr/roles.hpp"
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

using detail::alnum;

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

// The scan of a prose notation, left to right: its text and TeX so far.
struct prose_scanner {
    const std::string &src;
    notation out{};
    std::size_t i = 0;
    bool after_space = false;

    // The error for the notation at byte i.
    [[noreturn]] void fail(const std::string &why) const
    {
        throw std::logic_error("explain: the prose notation \"" + src + "\" " + why + " at byte " + std::to_string(i));
    }

    // The base of an identifier at i: a run of letters, or one Greek letter with its TeX.
    void read_base(std::string &base_text, std::string &base_tex)
    {
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
    }

    // Something that is not a symbol: a number or a sign, as it is.
    void other(bool vector)
    {
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
            return;
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
    }

    // The text of an identifier as written and its TeX, appended.
    void put_identifier(std::size_t at, int marks, bool vector, const std::string &base_text,
                        const std::string &base_tex, const std::string &sub, const std::string &sup,
                        const std::string &primes_tex)
    {
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

    // An identifier after its base: its TeX name, glued digits, primes, subscript and superscript.
    void identifier(std::size_t at, int marks, bool vector, std::string &base_text, std::string &base_tex)
    {
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
        put_identifier(at, marks, vector, base_text, base_tex, sub, sup, primes_tex);
    }

    // The notation, token by token.
    void scan()
    {
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
            read_base(base_text, base_tex);
            if (base_text.empty()) {
                other(vector);
                continue;
            }
            identifier(at, marks, vector, base_text, base_tex);
        }
    }
};

} // namespace

notation prose_notation(const std::string &src)
{
    prose_scanner S{src};
    S.scan();
    notation &out = S.out;
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
    std::string role = i == p.contact().body1 ? "body 1" : i == p.contact().body2 ? "body 2" : "body";
    return b.numbered ? role : role + " (" + b.name + ")";
}

paragraph &along(paragraph &q, const std::string &axis)
{
    if (axis == "t" || axis == "n" || axis == "b") {
        const notation e = prose_notation("e_" + axis);
        return q.n(e.text, e.tex);
    }
    const bool plain = !axis.empty() && std::all_of(axis.begin(), axis.end(), alnum);
    return plain ? q.n(axis, axis.size() == 1 ? axis : "\\mathit{" + axis + "}") : q.w(axis);
}

void other_impulses(std::vector<paragraph> &items, const problem &p, const char *contact_impulse)
{
    for (const pivot &pv : p.pivots) {
        paragraph q;
        q.t("The pin at $E$ = ");
        vector_span(q, pv.point, p.dimension);
        q.t(" exerts an unknown reaction impulse $~R$ on ").w(body_ref(p, pv.body) + ".");
        items.push_back(q);
    }
    for (std::size_t i : {p.contact().body1, p.contact().body2})
        if (p.bodies[i].infinite_mass)
            items.push_back(paragraph()
                                .w(body_ref(p, i))
                                .t(" has infinite mass: the finite impulse ")
                                .t(contact_impulse)
                                .w(" does not change its motion."));
    items.push_back(
        paragraph().w("Finite forces such as gravity give no impulse over the (almost zero) contact time."));
}

paragraph component_note(const frame_component &c)
{
    paragraph q;
    q.w(c.meaning);
    return c.axis.empty() ? q : along(q.w(", component along "), c.axis);
}

paragraph unknown_note(const problem &p, const unknown &u)
{
    return component_note(unknown_component(p, u));
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
            along(q.t(", component along "), axis(st.row));
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
        along(q.t("$~~I⁻¹ (~r × e_n)$ for ").w(who).t(", component along "), axis(st.row));
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
        along(q.t(": change of the relative velocity $~u$ of the contact points along "), axis(st.row));
        return along(q.w(" per unit impulse on body 2 along "), axis(st.column));
    case step_role::relative_velocity:
        if (st.row < 0)
            return q.t("sliding speed $|~u_t|$ of the contact points before impact");
        return along(q.t("relative velocity $~u = ~v_B - ~v_A$ of the contact points before impact, component along "),
                     axis(st.row));
    case step_role::response_determinant:
        return q.t("$D_K = det K$, positive: $K$ is positive definite");
    case step_role::impulse_component:
        return along(q.t("contact impulse $~P$ on body 2, component along "), axis(st.row));
    case step_role::tangential_impulse:
        if (st.row < 0)
            return q.t("tangential (friction) impulse $F = ~P·e_t$ on body 2 (on body 1 the opposite)");
        return along(q.t("friction impulse $~F$ on body 2, component along "), axis(st.row));
    case step_role::slide_denominator:
        return q.t(
            "$D_s = e_n·K(e_n - μ ~d)$, the normal response while sliding: it must be positive, else $N$ would not be");
    case step_role::slide_direction:
        return along(q.t("sliding direction $~d$, component along "), axis(st.row));
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
    art.caption += figure::directions_note(g);
    return art;
}

std::string step_unit(const problem &p, step_role role)
{
    if (p.units != "SI")
        return "";
    switch (role) {
    case step_role::lever_arm:
        return " m";
    case step_role::pivot_inertia:
        return " kg·m²";
    case step_role::angular_response:
        return " kg⁻¹·m⁻¹";
    case step_role::inverse_inertia:
        return " (kg·m²)⁻¹";
    case step_role::effective_inverse_mass:
    case step_role::contact_inverse_mass:
    case step_role::contact_response:
    case step_role::slide_denominator:
        return " kg⁻¹";
    case step_role::response_determinant:
        return " (kg²)⁻¹";
    case step_role::approach_velocity:
    case step_role::relative_velocity:
    case step_role::separation_velocity:
        return " m/s";
    case step_role::normal_impulse:
    case step_role::impulse_component:
    case step_role::tangential_impulse:
        return " N·s";
    case step_role::energy_lost:
        return " J";
    case step_role::slide_direction:
    case step_role::inertia_determinant: // (kg·m²)³: not worth a unit on a hand-out
        return "";
    }
    return "";
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

bool printable(const ex &e, int limit)
{
    return expression_size(e, limit) < limit; // the same choice in every run (GiNaC's signs not counted)
}

math_row row(const ex &lhs, const ex &rhs, const std::string &tag, const paragraph &note)
{
    math_row r = row(lhs, rhs, tag);
    r.note = note;
    return r;
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

paragraph approx(const std::string &decimal)
{
    return decimal.empty() ? paragraph() : paragraph().n("≈ " + decimal, "\\approx " + decimal);
}

paragraph decimal_note(const ex &v)
{
    return approx(decimal_digits(v));
}

std::string decimal_digits(const ex &v)
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
    return buf;
}

bool alnum(char c)
{
    return std::isalnum(static_cast<unsigned char>(c)) != 0;
}

std::string number_word(std::size_t n)
{
    return std::to_string(n);
}

// Print-only symbols: names for quantities that are not GiNaC symbols of the problem.
symbol show(const std::string &name, const std::string &tex)
{
    return symbol(name, tex);
}

std::size_t pivot_impulse_count(const derivation &d)
{
    std::size_t n = 0;
    for (const unknown &u : d.unknowns)
        if (u.kind == unknown_kind::pivot_impulse)
            ++n;
    return n;
}

const step *find_step(const solution &s, step_role role, std::size_t body)
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

} // namespace detail

namespace
{
using namespace detail;
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
    q.illustrated = false; // its symbols are new: a named class's figure values are not theirs
    q.illustrative.clear();
    auto name = [&](const std::string &base, const std::string &base_tex, const std::string &axis, const body &b,
                    ex &slot, quantity what) {
        if (slot.is_zero())
            return;
        const symbol s = expr::symbol_with_role(
            quantity_name(base, axis, b.label, false), quantity_tex(base_tex, axis, b.label, false),
            what == quantity::angular_velocity ? expr::symbol_role::angular_velocity : expr::symbol_role::none);
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
    if (!q.contact().friction().is_zero()) {
        symbol mu("mu", "\\mu"); // printed μ (explain_friction writes Coulomb's coefficient so)
        values.append(mu == q.contact().friction());
        units.push_back("");
        q.contact().set_friction(mu);
    }
    return q;
}

} // namespace impactgen::print
