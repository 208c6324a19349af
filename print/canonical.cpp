#include "canonical.hpp"

#include "tex_to_mathml.hpp"

#include "names/escape.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{

// Binding strength of the printed form: a sum binds loosest.
enum prec { p_sum = 0, p_product = 1, p_power = 2, p_atom = 3 };

struct printed {
    std::string s;
    prec level;
    bool negative = false; ///< starts with a minus sign
};

std::string numeric_text(const numeric &n)
{
    std::ostringstream os;
    os << n;
    return os.str();
}

printed print_ex(const ex &e, syntax sx);

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

/// The minus sign a printed form starts with when it is negative.
std::string minus_sign(syntax sx)
{
    return sx == syntax::mathml ? mo("−") : "-";
}
bool starts_with_minus(const std::string &s, syntax sx)
{
    const std::string m = minus_sign(sx);
    return s.size() > m.size() && s.compare(0, m.size(), m) == 0;
}
std::string without_minus(const std::string &s, syntax sx)
{
    return s.substr(minus_sign(sx).size());
}

std::string wrap(const printed &p, prec need, syntax sx)
{
    if (p.level >= need && !(p.negative && need > p_sum))
        return p.s;
    if (sx == syntax::mathml) // a sign inside: its own row, where it is a prefix
        return fenced("(", starts_with_minus(p.s, sx) ? tag("mrow", p.s) : p.s, ")");
    return sx == syntax::latex ? "\\left(" + p.s + "\\right)" : "(" + p.s + ")";
}

printed print_numeric(const numeric &n, syntax sx)
{
    if (!n.is_real())
        throw std::invalid_argument("canonical printer: complex number " + numeric_text(n));
    bool neg = n.is_negative();
    numeric a = abs(n);
    std::string body;
    prec level = p_atom;
    if (sx == syntax::mathml) {
        if (a.is_integer() || !a.is_rational())
            body = mn(numeric_text(a));
        else
            body = tag("mfrac", mn(numeric_text(a.numer())) + mn(numeric_text(a.denom())));
        return {neg ? minus_sign(sx) + body : body, neg ? p_sum : level, neg};
    }
    if (a.is_integer()) {
        body = numeric_text(a);
    } else if (a.is_rational()) {
        if (sx == syntax::latex) {
            body = "\\frac{" + numeric_text(a.numer()) + "}{" + numeric_text(a.denom()) + "}";
        } else {
            body = numeric_text(a.numer()) + "/" + numeric_text(a.denom());
            level = p_product;
        }
    } else {
        body = numeric_text(a);
    }
    return {neg ? "-" + body : body, neg ? p_sum : level, neg};
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

// base^exp with exp > 0 (negative exponents are moved to denominators by the caller).
printed print_power(const ex &base, const ex &exponent, syntax sx)
{
    printed b = print_ex(base, sx);
    if (exponent.is_equal(numeric(1, 2))) {
        if (sx == syntax::latex)
            return {"\\sqrt{" + b.s + "}", p_atom};
        if (sx == syntax::mathml)
            return {tag("msqrt", b.s), p_atom};
        if (sx == syntax::parser)
            return {"sqrt(" + b.s + ")", p_atom};
        return {"√" + wrap(b, p_atom, sx), p_power};
    }
    std::string bs = wrap(b, p_atom, sx);
    if (sx == syntax::latex && bs.compare(0, 6, "\\left(") != 0 && bs.find_first_of("^_'") != std::string::npos &&
        !subscript_only(bs))
        bs = "{" + bs + "}";
    if (sx == syntax::mathml) {
        if (is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_pos_integer())
            return {mathml_power(bs, mn(std::to_string(ex_to<numeric>(exponent).to_long()))), p_power};
        return {mathml_power(bs, one(print_ex(exponent, sx).s)), p_power};
    }
    if (is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_pos_integer()) {
        long k = ex_to<numeric>(exponent).to_long();
        if (sx == syntax::latex)
            return {bs + "^{" + std::to_string(k) + "}", p_power};
        if (const char *s = superscript(k); s && sx == syntax::text)
            return {bs + s, p_power};
        return {bs + "^" + std::to_string(k), p_power};
    }
    printed x = print_ex(exponent, sx);
    if (sx == syntax::latex)
        return {bs + "^{" + x.s + "}", p_power};
    return {bs + "^" + wrap(x, p_atom, sx), p_power};
}

struct factor {
    ex base, exponent; // exponent > 0
    std::string key;   // canonical text, for sorting
};

// The sign that makes a sum canonical: -1 when its first term, in canonical
// order, is negative.
int sum_sign(const ex &s);

// The factors of a product: its numeric coefficient, its numerator and its denominator, each sorted.
void split_factors(const ex &e, numeric &coeff, std::vector<factor> &num, std::vector<factor> &den)
{
    auto add_factor = [&](ex base, ex exponent) {
        bool negative_exp = is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_negative();
        if (negative_exp)
            exponent = -exponent;
        if (is_a<add>(base) && is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_integer() && sum_sign(base) < 0) {
            base = -base;
            if (ex_to<numeric>(exponent).is_odd())
                coeff = -coeff;
        }
        factor f{base, exponent, ""};
        f.key = print_power(base, exponent, syntax::text).s;
        if (exponent.is_equal(1))
            f.key = print_ex(base, syntax::text).s;
        (negative_exp ? den : num).push_back(f);
    };
    auto visit = [&](const ex &f) {
        if (is_a<numeric>(f))
            coeff *= ex_to<numeric>(f);
        else if (is_a<power>(f))
            add_factor(f.op(0), f.op(1));
        else
            add_factor(f, 1);
    };
    if (is_a<mul>(e))
        for (std::size_t i = 0; i < e.nops(); ++i)
            visit(e.op(i));
    else
        visit(e);
    auto by_key = [](const factor &a, const factor &b) { return a.key < b.key; };
    std::sort(num.begin(), num.end(), by_key);
    std::sort(den.begin(), den.end(), by_key);
}

// Factors (and a number before them) joined by the syntax's times; a sole factor's level in sole_level.
std::string factor_text(const std::vector<factor> &fs, const numeric &number, syntax sx, const std::string &times,
                        bool &single_sum, std::size_t &count, prec &sole_level)
{
    std::string out;
    count = 0;
    single_sum = false;
    sole_level = p_atom;
    if (number != 1) {
        out = sx == syntax::mathml ? mn(numeric_text(number)) : numeric_text(number);
        ++count;
    }
    for (const factor &f : fs) {
        printed pf = f.exponent.is_equal(1) ? print_ex(f.base, sx) : print_power(f.base, f.exponent, sx);
        bool alone = fs.size() == 1 && count == 0;
        if (alone && pf.level == p_sum)
            single_sum = true;
        if (alone)
            sole_level = pf.level;
        std::string piece = alone ? pf.s : wrap(pf, p_power, sx);
        if (!out.empty()) {
            bool digit = !piece.empty() && std::isdigit(static_cast<unsigned char>(piece[0]));
            if (sx == syntax::mathml)
                out += piece.compare(0, 4, "<mn>") == 0 ? mo("⋅") : times;
            else
                out += (sx == syntax::latex && digit) ? " \\cdot " : times;
        }
        out += piece;
        ++count;
    }
    return out;
}

// A product: numeric coefficient, numerator factors, denominator factors.
printed print_product(const ex &e, syntax sx)
{
    numeric coeff = 1;
    std::vector<factor> num, den;
    split_factors(e, coeff, num, den);

    if (!coeff.is_rational())
        throw std::invalid_argument("canonical printer: non-rational coefficient " + numeric_text(coeff));
    const bool neg = coeff.is_negative();
    const numeric p = abs(coeff.numer()), q = coeff.denom();

    // MathML: an invisible times (U+2062) between factors, a dot before a number.
    const std::string times = sx == syntax::latex    ? " "
                              : sx == syntax::parser ? "*"
                              : sx == syntax::mathml ? mo("&#x2062;")
                                                     : "·";
    prec sole_level = p_atom;
    bool num_sum = false, den_sum = false;
    std::size_t num_count = 0, den_count = 0;
    std::string top = factor_text(num, p, sx, times, num_sum, num_count, sole_level);
    const prec top_level = num_count == 1 ? sole_level : p_product;
    std::string bottom = factor_text(den, q, sx, times, den_sum, den_count, sole_level);
    if (top.empty())
        top = sx == syntax::mathml ? mn("1") : "1";
    std::string body;
    prec level = p_product;
    if (den_count == 0) {
        body = top;
        level = num_count == 0 ? p_atom : top_level;
    } else if (sx == syntax::latex) {
        body = "\\frac{" + top + "}{" + bottom + "}";
        level = p_atom;
    } else if (sx == syntax::mathml) {
        body = tag("mfrac", one(top) + one(bottom));
        level = p_atom;
    } else {
        if (num_sum)
            top = "(" + top + ")";
        if (den_count > 1 || den_sum)
            bottom = "(" + bottom + ")";
        body = top + "/" + bottom;
    }
    if (neg) {
        if (level == p_sum)
            body = wrap({body, p_sum}, p_product, sx);
        return {minus_sign(sx) + body, p_sum, true};
    }
    return {body, level};
}

struct term {
    numeric coeff;
    ex rest;
    std::string key;       ///< canonical text of rest, without a leading sign
    bool negative = false; ///< the sign the term prints with
};

std::vector<term> sorted_terms(const ex &s)
{
    std::vector<term> terms;
    for (std::size_t i = 0; i < s.nops(); ++i) {
        const ex &t = s.op(i);
        term tm{1, 1, ""};
        if (is_a<numeric>(t)) {
            tm.coeff = ex_to<numeric>(t);
        } else if (is_a<mul>(t)) {
            ex rest = 1;
            for (std::size_t k = 0; k < t.nops(); ++k)
                if (is_a<numeric>(t.op(k)))
                    tm.coeff *= ex_to<numeric>(t.op(k));
                else
                    rest *= t.op(k);
            tm.rest = rest;
        } else {
            tm.rest = t;
        }
        printed r = print_product(tm.rest, syntax::text);
        // rest may print with a sign of its own (a canonicalised inner sum).
        bool rest_negative = r.negative && !r.s.empty() && r.s[0] == '-';
        tm.key = rest_negative ? r.s.substr(1) : r.s;
        tm.negative = tm.coeff.is_negative() != rest_negative;
        terms.push_back(tm);
    }
    // Numbers first ("1 + e"), otherwise by text; equal texts by coefficient.
    std::sort(terms.begin(), terms.end(), [](const term &a, const term &b) {
        bool an = a.rest.is_equal(1), bn = b.rest.is_equal(1);
        if (an != bn)
            return an;
        if (a.key != b.key)
            return a.key < b.key;
        if (a.negative != b.negative)
            return b.negative;
        return abs(a.coeff) < abs(b.coeff);
    });
    return terms;
}

int sum_sign(const ex &s)
{
    // More positive than negative terms; on a tie, the term of the longest
    // text (then the first in order) positive: m (v′ - v), e - 1.
    std::vector<term> terms = sorted_terms(s);
    int balance = 0;
    const term *lead = nullptr;
    for (const term &t : terms) {
        balance += t.negative ? -1 : 1;
        if (!lead || t.key.size() > lead->key.size())
            lead = &t;
    }
    if (balance != 0)
        return balance > 0 ? 1 : -1;
    if (!terms.empty() && terms.front().rest.is_equal(1)) // a number: 1 - e², 1 - e
        return terms.front().negative ? -1 : 1;
    return !lead || !lead->negative ? 1 : -1;
}

// The printed terms of a sum in the order they print, each with its sign.
std::vector<std::pair<bool, std::string>> print_terms(const ex &e, syntax sx)
{
    std::vector<term> terms = sorted_terms(e);
    std::stable_partition(terms.begin(), terms.end(), [](const term &t) { return !t.negative; });
    std::vector<std::pair<bool, std::string>> out;
    for (const term &t : terms) {
        bool neg = t.coeff.is_negative();
        printed p = print_product(t.rest * abs(t.coeff), sx);
        if (p.negative && starts_with_minus(p.s, sx)) {
            neg = !neg;
            p.s = without_minus(p.s, sx);
            p.negative = false;
            if (p.level == p_sum)
                p.level = p_product;
        }
        out.push_back({neg, p.level == p_sum ? wrap(p, p_product, sx) : p.s});
    }
    return out;
}

printed print_sum(const ex &e, syntax sx)
{
    std::vector<term> terms = sorted_terms(e);
    // Positive terms first, each group in canonical order.
    std::stable_partition(terms.begin(), terms.end(), [](const term &t) { return !t.negative; });
    std::string out;
    for (std::size_t i = 0; i < terms.size(); ++i) {
        const term &t = terms[i];
        bool neg = t.coeff.is_negative();
        printed p = print_product(t.rest * abs(t.coeff), sx);
        if (p.negative && starts_with_minus(p.s, sx)) {
            // A sign of the product's own; "-(...)" keeps its parentheses' need.
            neg = !neg;
            p.s = without_minus(p.s, sx);
            p.negative = false;
            if (p.level == p_sum)
                p.level = p_product;
        }
        std::string body = p.level == p_sum ? wrap(p, p_product, sx) : p.s;
        if (sx == syntax::mathml)
            out += (i == 0 && !neg) ? body : mo(neg ? "−" : "+") + body;
        else if (i == 0)
            out = neg ? "-" + body : body;
        else
            out += (neg ? " - " : " + ") + body;
    }
    return {out, p_sum, !terms.empty() && terms.front().negative};
}

printed print_ex_uncached(const ex &e, syntax sx);

// Sorting keys print every subexpression in text several times: remember them.
std::map<ex, printed, ex_is_less> &text_cache()
{
    static std::map<ex, printed, ex_is_less> cache;
    return cache;
}

printed print_ex(const ex &e, syntax sx)
{
    if (sx != syntax::text)
        return print_ex_uncached(e, sx);
    auto &cache = text_cache();
    auto it = cache.find(e);
    if (it != cache.end())
        return it->second;
    printed p = print_ex_uncached(e, sx);
    cache.emplace(e, p);
    return p;
}

printed print_ex_uncached(const ex &e, syntax sx)
{
    if (is_a<numeric>(e))
        return print_numeric(ex_to<numeric>(e), sx);
    if (is_a<symbol>(e)) {
        const symbol &s = ex_to<symbol>(e);
        if (sx == syntax::mathml)
            return {symbol_mathml(s), p_atom};
        return {sx == syntax::latex    ? symbol_latex(s)
                : sx == syntax::parser ? s.get_name()
                                       : symbol_text(s.get_name()),
                p_atom};
    }
    if (is_a<add>(e))
        return print_sum(e, sx);
    if (is_a<mul>(e) || is_a<power>(e))
        return print_product(e, sx);
    if (is_a<function>(e)) {
        const function &f = ex_to<function>(e);
        std::string args;
        if (sx == syntax::mathml) {
            // abs(x) as |x|; others f(x, y) with a function application (U+2061).
            for (std::size_t i = 0; i < e.nops(); ++i)
                args += (i ? mo(",") : "") + one(print_ex(e.op(i), sx).s);
            if (is_ex_the_function(e, abs))
                return {fenced("|", args, "|"), p_atom};
            return {tag("mrow", tag("mi", names::xml_text(f.get_name())) + mo("&#x2061;") + fenced("(", args, ")")),
                    p_atom};
        }
        for (std::size_t i = 0; i < e.nops(); ++i)
            args += (i ? ", " : "") + print_ex(e.op(i), sx).s;
        if (sx == syntax::latex)
            return {"\\operatorname{" + f.get_name() + "}\\left(" + args + "\\right)", p_atom};
        return {f.get_name() + "(" + args + ")", p_atom};
    }
    if (is_a<constant>(e)) {
        std::ostringstream os;
        if (sx == syntax::latex || sx == syntax::mathml)
            os << GiNaC::latex;
        os << e;
        return {sx == syntax::mathml ? one(tex_to_mathml(os.str())) : os.str(), p_atom};
    }
    std::ostringstream os;
    os << e;
    throw std::invalid_argument("canonical printer: cannot print " + os.str());
}

} // namespace

std::string symbol_text(const std::string &name)
{
    std::string out;
    std::size_t i = 0;
    auto starts = [&](const std::string &word) {
        if (name.compare(0, word.size(), word) != 0)
            return false;
        std::size_t k = word.size();
        return k == name.size() || name[k] == '_' || name[k] == '\'';
    };
    // w is ω for angular velocities only (w′..., w_b1, w_z,ball), not for the
    // effective inverse masses w_1, w_ball.
    auto angular = [&] {
        if (name.size() > 1 && name[1] == '\'')
            return true;
        if (name.size() < 4 || name[1] != '_' || std::string("tnbxyz").find(name[2]) == std::string::npos)
            return false;
        if (name[3] == ',')
            return true;
        for (std::size_t k = 3; k < name.size(); ++k)
            if (!std::isdigit(static_cast<unsigned char>(name[k])))
                return false;
        return true;
    };
    if (starts("w") && angular()) {
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

std::string symbol_mathml(const symbol &s)
{
    return one(tex_to_mathml(symbol_latex(s)));
}

std::vector<std::pair<bool, std::string>> canonical_terms(const ex &e, syntax s)
{
    if (!is_a<add>(e))
        return {{false, canonical(e, s)}};
    auto out = print_terms(e, s);
    if (text_cache().size() > 100000)
        text_cache().clear();
    return out;
}

std::string canonical(const ex &e, syntax s)
{
    std::string out = print_ex(e, s).s;
    if (s == syntax::mathml) // one element: a leading minus is first in its row, a prefix sign
        out = one(out);
    if (text_cache().size() > 100000)
        text_cache().clear();
    return out;
}

} // namespace impactgen::print
