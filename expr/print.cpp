#include "print.hpp"

#include "names/escape.hpp"

#include <cctype>
#include <sstream>
#include <stdexcept>

namespace impactgen::expr
{
using namespace GiNaC;

namespace
{

// ---- MathML pieces. Every printed MathML string is a sequence of elements;
// where one element is needed (a child of <msup>, <mfrac>) it goes through one().

std::string tag(const std::string &name, const std::string &content)
{
    return "<" + name + ">" + content + "</" + name + ">";
}
std::string mn(const std::string &digits)
{
    return tag("mn", digits);
}
std::string mo(const std::string &op)
{
    return tag("mo", op);
}

// The number of top-level elements of generated MathML (text content is
// escaped, so every '<' starts a tag).
std::size_t top_level_elements(const std::string &s)
{
    std::size_t count = 0;
    int depth = 0;
    for (std::size_t k = s.find('<'); k != std::string::npos; k = s.find('<', k + 1)) {
        std::size_t end = s.find('>', k);
        if (end == std::string::npos)
            break;
        if (s[k + 1] == '/') {
            --depth;
        } else {
            if (depth == 0)
                ++count;
            if (s[end - 1] != '/')
                ++depth;
        }
        k = end;
    }
    return count;
}

std::string one(const std::string &s)
{
    return top_level_elements(s) == 1 ? s : tag("mrow", s);
}

// Parentheses or bars around MathML. They stretch (as \left( \right) do) only
// around something taller than a line of symbols with scripts: Chromium
// stretches a delimiter to the exact height of its row, and around v_{t1}
// that gives a larger, wider glyph where TeX keeps the normal one.
std::string fenced(const std::string &open, const std::string &inside, const std::string &close)
{
    bool tall = false;
    for (const char *t : {"<mfrac", "<msqrt", "<munder", "<mover", "stretchy=\"true\""})
        tall = tall || inside.find(t) != std::string::npos;
    const std::string attr = tall ? "" : " stretchy=\"false\"";
    return tag("mrow", "<mo" + attr + ">" + open + "</mo>" + inside + "<mo" + attr + ">" + close + "</mo>");
}

// MathML base^exponent: a lone <msub> (a subscripted symbol) becomes one
// <msubsup>; a base with a superscript of its own (v'_{x1}, I^{1}_{nb}) is
// put in parentheses, (I^1_nb)^2, where LaTeX braces it: a second superscript
// right after the first reads as one.
std::string mathml_power(const std::string &base, const std::string &exponent)
{
    const std::string open = "<msub>", close = "</msub>";
    const bool single = top_level_elements(base) == 1;
    if (single && base.compare(0, open.size(), open) == 0)
        return "<msubsup>" + base.substr(open.size(), base.size() - open.size() - close.size()) + exponent +
               "</msubsup>";
    if (single && (base.compare(0, 6, "<msup>") == 0 || base.compare(0, 9, "<msubsup>") == 0))
        return tag("msup", fenced("(", base, ")") + exponent);
    return tag("msup", one(base) + exponent);
}

const char *superscript(long k)
{
    static const char *sup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
    return k >= 0 && k <= 9 ? sup[k] : nullptr;
}

// A TeX name that ends in its only script, a subscript: X_{...} or X_a with
// nothing before the _ that is a script, a prime or a group. A power can be
// written right after it (r_{t1}^{2}); anything else with a script in it is
// braced first ({v'_{x1}}^{2}, {I^{1}_{nb}}^{2}), or TeX sees a double superscript.
bool subscript_only(const std::string &s)
{
    const std::size_t u = s.find('_');
    if (u == std::string::npos || u == 0 || u + 1 >= s.size() || s.find_first_of("^'{}()", 0) < u)
        return false;
    if (s[u + 1] != '{')
        return u + 2 == s.size() && std::isalnum(static_cast<unsigned char>(s[u + 1]));
    int depth = 0;
    for (std::size_t k = u + 1; k < s.size(); ++k) {
        if (s[k] == '\\') { // an escaped character (\_, \{) is not a brace
            ++k;
            continue;
        }
        if (s[k] == '{')
            ++depth;
        else if (s[k] == '}' && --depth == 0)
            return k + 1 == s.size();
    }
    return false;
}

// One walk of the tree in one syntax.
class writer
{
public:
    writer(tree &t, syntax sx, tex_to_mathml_fn mathml, bool abs_as_bars = false)
        : t_(t), sx_(sx), mathml_(mathml), bars_(abs_as_bars)
    {
    }

    printed whole(int id);
    printed product(int id);
    printed power(const factor &f);
    std::vector<std::pair<bool, std::string>> terms(int id);

private:
    printed node_uncached(int id);
    printed numeric_form(const numeric &n) const;
    printed leaf(const ex &e) const;
    printed function_form(int id);
    printed sum(int id);
    std::string factors(const std::vector<factor> &fs, const numeric &number, const std::string &times,
                        bool &single_sum, std::size_t &count, prec &sole_level);
    std::string tex_to_mathml(const std::string &tex) const;

    /// The minus sign a printed form starts with when it is negative.
    std::string minus_sign() const { return sx_ == syntax::mathml ? mo("−") : "-"; }
    bool starts_with_minus(const std::string &s) const
    {
        const std::string m = minus_sign();
        return s.size() > m.size() && s.compare(0, m.size(), m) == 0;
    }
    std::string wrap(const printed &p, prec need) const;

    /// Whether the forms are the tree's keys (remembered in its nodes).
    bool keyed() const { return sx_ == syntax::text && !bars_; }

    tree &t_;
    syntax sx_;
    tex_to_mathml_fn mathml_;
    bool bars_;
};

std::string writer::tex_to_mathml(const std::string &tex) const
{
    if (!mathml_)
        throw std::invalid_argument("canonical printer: MathML needs a TeX to MathML converter");
    return mathml_(tex);
}

std::string writer::wrap(const printed &p, prec need) const
{
    if (p.level >= need && !(p.negative && need > p_sum))
        return p.s;
    if (sx_ == syntax::mathml) // a sign inside: its own row, where it is a prefix
        return fenced("(", starts_with_minus(p.s) ? tag("mrow", p.s) : p.s, ")");
    return sx_ == syntax::latex ? "\\left(" + p.s + "\\right)" : "(" + p.s + ")";
}

printed writer::numeric_form(const numeric &n) const
{
    if (!n.is_real())
        throw std::invalid_argument("canonical printer: complex number " + number_text(n));
    bool neg = n.is_negative();
    numeric a = abs(n);
    std::string body;
    prec level = p_atom;
    if (sx_ == syntax::mathml) {
        if (a.is_integer() || !a.is_rational())
            body = mn(number_text(a));
        else
            body = tag("mfrac", mn(number_text(a.numer())) + mn(number_text(a.denom())));
        return {neg ? minus_sign() + body : body, neg ? p_sum : level, neg};
    }
    if (a.is_integer()) {
        body = number_text(a);
    } else if (a.is_rational()) {
        if (sx_ == syntax::latex) {
            body = "\\frac{" + number_text(a.numer()) + "}{" + number_text(a.denom()) + "}";
        } else {
            body = number_text(a.numer()) + "/" + number_text(a.denom());
            level = p_product;
        }
    } else {
        body = number_text(a);
    }
    return {neg ? "-" + body : body, neg ? p_sum : level, neg};
}

// A symbol or a constant (Pi).
printed writer::leaf(const ex &e) const
{
    if (is_a<symbol>(e)) {
        const symbol &s = ex_to<symbol>(e);
        if (sx_ == syntax::mathml)
            return {one(tex_to_mathml(symbol_latex(s))), p_atom};
        return {sx_ == syntax::latex ? symbol_latex(s) : sx_ == syntax::parser ? s.get_name() : symbol_text(s), p_atom};
    }
    std::ostringstream os;
    if (sx_ == syntax::latex || sx_ == syntax::mathml)
        os << GiNaC::latex;
    os << e;
    return {sx_ == syntax::mathml ? one(tex_to_mathml(os.str())) : os.str(), p_atom};
}

// base^exp with exp > 0 (negative exponents are in the denominator).
printed writer::power(const factor &f)
{
    printed b = whole(f.base);
    const ex &exponent = f.exponent;
    if (exponent.is_equal(numeric(1, 2))) {
        if (sx_ == syntax::latex)
            return {"\\sqrt{" + b.s + "}", p_atom};
        if (sx_ == syntax::mathml)
            return {tag("msqrt", b.s), p_atom};
        if (sx_ == syntax::parser)
            return {"sqrt(" + b.s + ")", p_atom};
        return {"√" + wrap(b, p_atom), p_power};
    }
    std::string bs = wrap(b, p_atom);
    if (sx_ == syntax::latex && bs.compare(0, 6, "\\left(") != 0 && bs.find_first_of("^_'") != std::string::npos &&
        !subscript_only(bs))
        bs = "{" + bs + "}";
    const bool integer = is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_pos_integer();
    if (sx_ == syntax::mathml) {
        if (integer)
            return {mathml_power(bs, mn(std::to_string(ex_to<numeric>(exponent).to_long()))), p_power};
        return {mathml_power(bs, one(whole(f.exponent_node).s)), p_power};
    }
    if (integer) {
        long k = ex_to<numeric>(exponent).to_long();
        if (sx_ == syntax::latex)
            return {bs + "^{" + std::to_string(k) + "}", p_power};
        if (const char *s = superscript(k); s && sx_ == syntax::text)
            return {bs + s, p_power};
        return {bs + "^" + std::to_string(k), p_power};
    }
    printed x = whole(f.exponent_node);
    if (sx_ == syntax::latex)
        return {bs + "^{" + x.s + "}", p_power};
    return {bs + "^" + wrap(x, p_atom), p_power};
}

// Factors (and a number before them) joined by the syntax's times; a sole factor's level in sole_level.
std::string writer::factors(const std::vector<factor> &fs, const numeric &number, const std::string &times,
                            bool &single_sum, std::size_t &count, prec &sole_level)
{
    std::string out;
    count = 0;
    single_sum = false;
    sole_level = p_atom;
    if (number != 1) {
        out = sx_ == syntax::mathml ? mn(number_text(number)) : number_text(number);
        ++count;
    }
    for (const factor &f : fs) {
        printed pf = f.exponent.is_equal(1) ? whole(f.base) : power(f);
        bool alone = fs.size() == 1 && count == 0;
        if (alone && pf.level == p_sum)
            single_sum = true;
        if (alone)
            sole_level = pf.level;
        std::string piece = alone ? pf.s : wrap(pf, p_power);
        if (!out.empty()) {
            bool digit = !piece.empty() && std::isdigit(static_cast<unsigned char>(piece[0]));
            if (sx_ == syntax::mathml)
                out += piece.compare(0, 4, "<mn>") == 0 ? mo("⋅") : times;
            else
                out += (sx_ == syntax::latex && digit) ? " \\cdot " : times;
        }
        out += piece;
        ++count;
    }
    return out;
}

// A node read as a product: numeric coefficient, numerator factors, denominator factors.
printed writer::product(int id)
{
    if (keyed() && t_.at(id).product_text)
        return *t_.at(id).product_text;
    const product_form &pf = t_.product(id);
    const numeric &coeff = pf.coefficient;
    if (!coeff.is_rational())
        throw std::invalid_argument("canonical printer: non-rational coefficient " + number_text(coeff));
    const bool neg = coeff.is_negative();
    const numeric p = abs(coeff.numer()), q = coeff.denom();

    // MathML: an invisible times (U+2062) between factors, a dot before a number.
    const std::string times = sx_ == syntax::latex    ? " "
                              : sx_ == syntax::parser ? "*"
                              : sx_ == syntax::mathml ? mo("&#x2062;")
                                                      : "·";
    prec sole_level = p_atom;
    bool num_sum = false, den_sum = false;
    std::size_t num_count = 0, den_count = 0;
    std::string top = factors(pf.numerator, p, times, num_sum, num_count, sole_level);
    const prec top_level = num_count == 1 ? sole_level : p_product;
    std::string bottom = factors(pf.denominator, q, times, den_sum, den_count, sole_level);
    if (top.empty())
        top = sx_ == syntax::mathml ? mn("1") : "1";
    printed out{"", p_product, false};
    if (den_count == 0) {
        out.s = top;
        out.level = num_count == 0 ? p_atom : top_level;
    } else if (sx_ == syntax::latex) {
        out = {"\\frac{" + top + "}{" + bottom + "}", p_atom};
    } else if (sx_ == syntax::mathml) {
        out = {tag("mfrac", one(top) + one(bottom)), p_atom};
    } else {
        if (num_sum)
            top = "(" + top + ")";
        if (den_count > 1 || den_sum)
            bottom = "(" + bottom + ")";
        out.s = top + "/" + bottom;
    }
    if (neg) {
        if (out.level == p_sum)
            out.s = wrap({out.s, p_sum}, p_product);
        out = {minus_sign() + out.s, p_sum, true};
    }
    if (keyed())
        t_.remember(id, true, out);
    return out;
}

// The terms of a sum in the order they are written, each with its sign.
std::vector<std::pair<bool, std::string>> writer::terms(int id)
{
    std::vector<std::pair<bool, std::string>> out;
    const std::vector<term> &ts = t_.at(id).terms;
    for (const term &tm : ts) {
        if (!tm.coefficient.is_real()) // |coefficient| would print a + i as a + 1
            throw std::invalid_argument("canonical printer: complex number " + number_text(tm.coefficient));
        bool neg = tm.coefficient.is_negative();
        printed p = product(tm.body);
        if (p.negative && starts_with_minus(p.s)) {
            // A sign of the product's own; "-(...)" keeps its parentheses' need.
            neg = !neg;
            p.s = p.s.substr(minus_sign().size());
            p.negative = false;
            if (p.level == p_sum)
                p.level = p_product;
        }
        out.push_back({neg, p.level == p_sum ? wrap(p, p_product) : p.s});
    }
    return out;
}

printed writer::sum(int id)
{
    const auto ts = terms(id);
    std::string out;
    for (std::size_t i = 0; i < ts.size(); ++i) {
        const auto &[neg, body] = ts[i];
        if (sx_ == syntax::mathml)
            out += (i == 0 && !neg) ? body : mo(neg ? "−" : "+") + body;
        else if (i == 0)
            out = neg ? "-" + body : body;
        else
            out += (neg ? " - " : " + ") + body;
    }
    const auto &written = t_.at(id).terms;
    return {out, p_sum, !written.empty() && written.front().negative};
}

printed writer::function_form(int id)
{
    const node &n = t_.at(id);
    const function &f = ex_to<function>(n.value);
    const std::vector<int> &args = n.args;
    std::string list;
    if (sx_ == syntax::mathml) {
        // abs(x) as |x|; others f(x, y) with a function application (U+2061).
        for (std::size_t i = 0; i < args.size(); ++i)
            list += (i ? mo(",") : "") + one(whole(args[i]).s);
        if (is_ex_the_function(f, abs))
            return {fenced("|", list, "|"), p_atom};
        return {tag("mrow", tag("mi", names::xml_text(f.get_name())) + mo("&#x2061;") + fenced("(", list, ")")),
                p_atom};
    }
    for (std::size_t i = 0; i < args.size(); ++i)
        list += (i ? ", " : "") + whole(args[i]).s;
    if (bars_ && is_ex_the_function(f, abs))
        return {sx_ == syntax::latex ? "\\left|" + list + "\\right|" : "|" + list + "|", p_atom};
    if (sx_ == syntax::latex)
        return {"\\operatorname{" + f.get_name() + "}\\left(" + list + "\\right)", p_atom};
    return {f.get_name() + "(" + list + ")", p_atom};
}

printed writer::whole(int id)
{
    if (!keyed())
        return node_uncached(id);
    if (t_.at(id).text)
        return *t_.at(id).text;
    printed p = node_uncached(id);
    t_.remember(id, false, p);
    return p;
}

printed writer::node_uncached(int id)
{
    const node &n = t_.at(id);
    switch (n.k) {
    case kind::number:
        return numeric_form(ex_to<numeric>(n.value));
    case kind::symbol:
    case kind::constant:
        return leaf(n.value);
    case kind::sum:
        return sum(id);
    case kind::product:
        return product(id);
    case kind::function:
        return function_form(id);
    case kind::other:
        break;
    }
    std::ostringstream os;
    os << n.value;
    throw std::invalid_argument("canonical printer: cannot print " + os.str());
}

} // namespace

printed print(tree &t, int id, syntax s, tex_to_mathml_fn mathml, bool abs_as_bars)
{
    return writer(t, s, mathml, abs_as_bars).whole(id);
}

printed print_product(tree &t, int id, syntax s, tex_to_mathml_fn mathml)
{
    return writer(t, s, mathml).product(id);
}

printed print_factor(tree &t, const factor &f, syntax s, tex_to_mathml_fn mathml)
{
    return writer(t, s, mathml).power(f);
}

std::vector<std::pair<bool, std::string>> print_terms(tree &t, int id, syntax s, tex_to_mathml_fn mathml)
{
    return writer(t, s, mathml).terms(id);
}

std::string mathml_one(const std::string &elements)
{
    return one(elements);
}

std::string symbol_text(const std::string &name, symbol_role role)
{
    std::string out;
    std::size_t i = 0;
    auto starts = [&](const std::string &word) {
        if (name.compare(0, word.size(), word) != 0)
            return false;
        std::size_t k = word.size();
        return k == name.size() || name[k] == '_' || name[k] == '\'';
    };
    // The Greek letters written out (tau, eps, rho: as GiNaC's TeX names show them), and the w
    // of an angular velocity (its role, set by the model: expr/roles.hpp).
    if (role == symbol_role::angular_velocity && !name.empty() && name[0] == 'w') {
        out = "ω";
        i = 1;
    } else if (starts("tau")) {
        out = "τ";
        i = 3;
    } else if (starts("eps")) {
        out = "ε";
        i = 3;
    } else if (starts("rho")) {
        out = "ρ";
        i = 3;
    }
    for (; i < name.size(); ++i)
        out += name[i] == '\'' ? std::string("′") : std::string(1, name[i]);
    return out;
}

std::string symbol_text(const symbol &s)
{
    return symbol_text(s.get_name(), role_of(s));
}

std::string symbol_latex(const symbol &s)
{
    std::string t = s.get_TeX_name();
    if (t.find('{') != std::string::npos)
        return t;
    // "v_t1" -> "v_{t1}", "m_ball" -> "m_{ball}"
    std::size_t u = t.find('_');
    if (u != std::string::npos && u + 2 < t.size())
        t = t.substr(0, u + 1) + "{" + t.substr(u + 1) + "}";
    if (t == "eps")
        t = "\\varepsilon";
    return t;
}

} // namespace impactgen::expr
