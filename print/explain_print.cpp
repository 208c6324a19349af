// The printers of an explanation document: text, Markdown, LaTeX. Each one
// only decides how a span, a list and a displayed row look; the content is the
// document's, and every expression goes through the canonical printer.
#include "canonical.hpp"
#include "explain.hpp"

#include "names/escape.hpp"

#include <cctype>
#include <set>
#include <sstream>
#include <stdexcept>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{

constexpr std::size_t width = 100;
// Spaces inside a formula must not break a line: held as this byte while wrapping.
constexpr char hard_space = '\x01';

std::size_t columns(const std::string &s)
{
    std::size_t n = 0;
    for (unsigned char c : s)
        if ((c & 0xC0) != 0x80)
            ++n;
    return n;
}

std::string harden(std::string s)
{
    for (char &c : s)
        if (c == ' ')
            c = hard_space;
    return s;
}

// |x| for GiNaC's abs(x): the canonical printer prints a function by name,
// abs(x) and \operatorname{abs}\left(x\right); the notes write |x|.
std::string bars_text(std::string s)
{
    for (std::size_t at = s.find("abs("); at != std::string::npos; at = s.find("abs(", at)) {
        if (at > 0 && (std::isalnum(static_cast<unsigned char>(s[at - 1])) || s[at - 1] == '_')) {
            at += 4;
            continue;
        }
        std::size_t k = at + 4;
        for (int depth = 1; k < s.size(); ++k) {
            if (s[k] == '(')
                ++depth;
            else if (s[k] == ')' && --depth == 0)
                break;
        }
        if (k >= s.size())
            break;
        s = s.substr(0, at) + "|" + s.substr(at + 4, k - at - 4) + "|" + s.substr(k + 1);
        ++at;
    }
    return s;
}

std::string bars_latex(std::string s)
{
    const std::string open = "\\operatorname{abs}\\left(";
    for (std::size_t at = s.find(open); at != std::string::npos; at = s.find(open, at)) {
        std::size_t k = at + open.size();
        int depth = 1;
        for (; k < s.size(); ++k) {
            if (s.compare(k, 5, "\\left") == 0)
                ++depth;
            else if (s.compare(k, 6, "\\right") == 0 && --depth == 0)
                break;
        }
        if (k >= s.size())
            break;
        // \right) -> \right|
        s = s.substr(0, at) + "\\left|" + s.substr(at + open.size(), k - at - open.size()) + "\\right|" +
            s.substr(k + 7);
        ++at;
    }
    return s;
}

std::string math_text(const ex &e)
{
    return bars_text(canonical_text(e));
}
std::string math_latex(const ex &e)
{
    return bars_latex(canonical_latex(e));
}

// Greedy wrap at `width` columns; `first` and `rest` are the line prefixes.
std::string wrap(const std::string &text, const std::string &first, const std::string &rest)
{
    std::istringstream in(text);
    std::string word, out, line = first;
    bool empty = true;
    while (in >> word) {
        if (!empty && columns(line) + 1 + columns(word) > width) {
            out += line + "\n";
            line = rest;
            empty = true;
        }
        line += (empty ? "" : " ") + word;
        empty = false;
    }
    out += line + "\n";
    for (char &c : out)
        if (c == hard_space)
            c = ' ';
    return out;
}

// ---------------------------------------------------------------- text

std::string text_spans(const paragraph &p)
{
    std::string out;
    for (const span &s : p.spans) {
        if (s.k == span::words)
            out += s.text;
        else if (s.k == span::math)
            out += harden(math_text(s.expr));
        else if (s.k == span::ref)
            out += "(" + s.text + ")";
        else
            out += harden(s.formula.text);
    }
    return out;
}

std::string text_row_left(const math_row &r)
{
    return r.lhs_note.text.empty() ? math_text(r.lhs) : r.lhs_note.text;
}

// ---------------------------------------------------------------- LaTeX

// Running text for LaTeX: escapes and the few Unicode signs the notes use.
// Anything else outside ASCII is an error, never silently wrong output.
std::string tex_words(const std::string &s)
{
    static const std::pair<const char *, const char *> map[] = {
        {"≤", "$\\le$"},
        {"≥", "$\\ge$"},
        {"∫", "$\\int$"},
        {"→", "$\\to$"},
        {"′", "$'$"},
        {"ω", "$\\omega$"},
        {"·", "$\\cdot$"},
        {"×", "$\\times$"},
        {"∞", "$\\infty$"},
        {"≈", "$\\approx$"},
        {"²", "$^2$"},
        {"⁻¹", "$^{-1}$"},
        {"ε", "$\\varepsilon$"},
        {"±", "$\\pm$"},
        {"τ", "$\\tau$"},
        {"|", "$|$"},
        {"<", "$<$"},
        {">", "$>$"},
        {"μ", "$\\mu$"},
        {"λ", "$\\lambda$"},
        {"θ", "$\\theta$"},
        {"≠", "$\\ne$"},
        {"√", "$\\surd$"},
        {"∓", "$\\mp$"},
        {"⁺", "$^+$"},
        {"é", "\\'{e}"},
    };
    std::string out;
    for (std::size_t i = 0; i < s.size();) {
        bool done = false;
        for (const auto &[from, to] : map) {
            std::size_t n = std::char_traits<char>::length(from);
            if (s.compare(i, n, from) == 0) {
                out += to;
                i += n;
                done = true;
                break;
            }
        }
        if (done)
            continue;
        unsigned char c = static_cast<unsigned char>(s[i]);
        if (c >= 0x80) {
            std::size_t n = 1;
            while (i + n < s.size() && (static_cast<unsigned char>(s[i + n]) & 0xC0) == 0x80)
                ++n;
            throw std::invalid_argument("the LaTeX output has no rendering for the character \"" +
                                        names::display_text(s.substr(i, n)) + "\" (in \"" + names::display_text(s, 60) +
                                        "\"); use ASCII names for --format latex");
        }
        switch (c) {
        case '_':
            out += "\\_";
            break;
        case '&':
            out += "\\&";
            break;
        case '%':
            out += "\\%";
            break;
        case '#':
            out += "\\#";
            break;
        case '$':
            out += "\\$";
            break;
        case '{':
            out += "\\{";
            break;
        case '}':
            out += "\\}";
            break;
        case '^':
            out += "\\^{}";
            break;
        case '~':
            out += "\\~{}";
            break;
        case '\\':
            out += "\\textbackslash{}";
            break;
        default:
            out += static_cast<char>(c);
        }
        ++i;
    }
    return out;
}

std::string tex_rel(const std::string &rel)
{
    if (rel == "→")
        return "\\to";
    if (rel == "≤")
        return "\\le";
    if (rel == "≥")
        return "\\ge";
    return rel;
}

// ---------------------------------------------------------------- LaTeX layout
//
// TeX never breaks a displayed formula, and inside \left( ... \right) not even
// an inline one: a long closed form runs off the page. So the printers break
// formulas themselves, before TeX sees them, from an estimate of how wide TeX
// sets them. The estimate is a glyph model of the canonical LaTeX (every
// formula is printed through canonical.hpp, so its shape is known: sums joined
// by " + " and " - ", factors by spaces, \frac, \left( \right), scripts),
// deterministic and a little generous, so that what it passes fits: measured
// against the widths TeX gives every formula of the named classes' and
// example problems' documents (\sbox, \wd), it is 9% over on average for
// formulas wider than 10 em and never more than 0.15 em under.
//
// A formula is parsed into items -- atoms, binary + and - of the sum at that
// level, \left...\right groups, \frac -- and set as terms, greedily, line by
// line. A term too wide for a line of its own is opened one level down: a
// group is broken at its own + and - (the line ends with \right. and the next
// begins with \left., so every line is balanced), a fraction with a long
// numerator is set as \frac{rest}{denominator} times the numerator's sum.

// Widths are in em of the 11pt body font (10.95pt).
constexpr double em_pt = 10.95;
// The text width: A4 with 2.5 cm margins (geometry), 160 mm = 455.2 pt.
constexpr double text_width_em = 455.24 / em_pt;
// What a displayed row may fill: the text width less a margin for what the
// glyph model cannot know (kerning, large delimiters).
constexpr double row_budget_em = text_width_em - 1.5;

// The width of one character: in math mode (italic letters, binary operators
// with their spaces) or in text mode (roman). Letters: the widths of Computer
// Modern (cmmi10, cmr10) in em, rounded up.
double glyph_em(char c, bool text_mode)
{
    static const double math_lower[26] = {.53, .43, .44, .52, .47, .49, .48, .58, .35, .42, .53, .30, .88,
                                          .60, .49, .51, .45, .46, .47, .37, .58, .49, .72, .58, .49, .47};
    static const double math_upper[26] = {.75, .76, .72, .83, .74, .65, .79, .84, .45, .56, .85, .69, .97,
                                          .81, .77, .65, .80, .76, .62, .59, .69, .59, .95, .83, .59, .69};
    static const double text_lower[26] = {.50, .56, .45, .56, .45, .31, .50, .56, .28, .31, .53, .28, .84,
                                          .56, .50, .56, .53, .40, .40, .39, .56, .53, .73, .53, .53, .45};
    static const double text_upper[26] = {.75, .71, .73, .77, .69, .66, .79, .75, .37, .52,  .78, .63, .92,
                                          .75, .78, .69, .78, .74, .56, .73, .75, .75, 1.03, .75, .75, .62};
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x80 && std::islower(u))
        return text_mode ? text_lower[c - 'a'] + 0.02 : math_lower[c - 'a'] + 0.05; // and an italic correction
    if (u < 0x80 && std::isupper(u))
        return text_mode ? text_upper[c - 'A'] + 0.02 : math_upper[c - 'A'] + 0.05;
    if (u < 0x80 && std::isdigit(u))
        return 0.5;
    if (text_mode) {
        switch (c) {
        case ' ':
            return 0.34;
        case '(':
        case ')':
        case '[':
        case ']':
            return 0.39;
        case '.':
        case ',':
        case ':':
        case ';':
        case '\'':
        case '!':
            return 0.28;
        case '-':
            return 0.34;
        default:
            return 0.78; // + = < > and the rest
        }
    }
    switch (c) {
    case ' ':
        return 0;
    case '+':
    case '-':
        return 1.23; // the sign and a medium space each side
    case '=':
    case '<':
    case '>':
        return 1.34; // a relation and a thick space each side
    case '(':
    case ')':
    case '[':
    case ']':
        return 0.4;
    case '|':
        return 0.3;
    case '/':
        return 0.5;
    case ',':
    case ';':
        return 0.46; // punctuation and a thin space
    case ':':
        return 0.6;
    case '.':
        return 0.3;
    case '\'':
        return 0.32; // a prime
    case '!':
        return 0.3;
    default:
        return 0.78;
    }
}

// The end of the argument starting at `at`: a braced group, a command, or one character.
std::size_t skip_argument(const std::string &s, std::size_t at)
{
    while (at < s.size() && s[at] == ' ')
        ++at;
    if (at >= s.size())
        return at;
    if (s[at] == '{') {
        int depth = 0;
        for (std::size_t k = at; k < s.size(); ++k) {
            if (s[k] == '\\') {
                ++k; // \{ \} \\ do not count
                continue;
            }
            if (s[k] == '{')
                ++depth;
            else if (s[k] == '}' && --depth == 0)
                return k + 1;
        }
        return s.size();
    }
    if (s[at] == '\\') {
        std::size_t k = at + 1;
        while (k < s.size() && std::isalpha(static_cast<unsigned char>(s[k])))
            ++k;
        return k == at + 1 ? std::min(at + 2, s.size()) : k;
    }
    // one (UTF-8) character
    std::size_t k = at + 1;
    while (k < s.size() && (static_cast<unsigned char>(s[k]) & 0xC0) == 0x80)
        ++k;
    return k;
}

// An argument without its braces.
std::string argument_body(const std::string &s, std::size_t from, std::size_t to)
{
    while (from < to && s[from] == ' ')
        ++from;
    if (from < to && s[from] == '{' && s[to - 1] == '}')
        return s.substr(from + 1, to - from - 2);
    return s.substr(from, to - from);
}

// The width of a control symbol \d: the spaces \, \: \; \ , or a sign (\{ \| \').
double control_symbol_em(char d)
{
    switch (d) {
    case ',':
        return 0.17;
    case ':':
        return 0.23;
    case ';':
        return 0.28;
    case ' ':
        return 0.36;
    case '!':
    case '\\':
        return 0; // a negative thin space; a line break
    default:
        return 0.55;
    }
}

bool contains_fraction(const std::string &s)
{
    return s.find("\\frac") != std::string::npos;
}

// The estimated width of TeX (math mode, or text mode inside \text{...}) at `scale`.
double tex_width(const std::string &s, double scale = 1, bool text_mode = false)
{
    double w = 0;
    double script = -1; // the width of a sub- or superscript just set: x^{a}_{b} stacks them
    for (std::size_t i = 0; i < s.size();) {
        const char c = s[i];
        if (c == '^' || c == '_') {
            std::size_t end = skip_argument(s, i + 1);
            const double sw = tex_width(argument_body(s, i + 1, end), scale * 0.75, text_mode) + 0.05 * scale;
            w += script < 0 ? sw : std::max(0.0, sw - script);
            script = script < 0 ? sw : -1;
            i = end;
            continue;
        }
        script = -1;
        if (c == '\\') {
            std::size_t j = i + 1;
            while (j < s.size() && std::isalpha(static_cast<unsigned char>(s[j])))
                ++j;
            const std::string name = s.substr(i + 1, j - i - 1);
            if (name.empty()) { // \, \; \! \{ \| \  \' and the like
                const char d = j < s.size() ? s[j] : ' ';
                w += scale * control_symbol_em(d);
                i = std::min(j + 1, s.size());
                continue;
            }
            i = j;
            auto arg = [&] {
                std::size_t end = skip_argument(s, i);
                std::string a = argument_body(s, i, end);
                i = end;
                return a;
            };
            if (name == "frac" || name == "dfrac" || name == "tfrac") {
                std::string top = arg(), bottom = arg();
                w += std::max(tex_width(top, scale, false), tex_width(bottom, scale, false)) + 0.3 * scale;
            } else if (name == "sqrt") {
                w += 0.9 * scale + tex_width(arg(), scale, false);
            } else if (name == "text" || name == "textrm" || name == "mbox" || name == "mathrm" ||
                       name == "operatorname" || name == "textit" || name == "emph") {
                w += tex_width(arg(), scale, true);
            } else if (name == "underline" || name == "hat" || name == "bar" || name == "vec" || name == "overline" ||
                       name == "mathbf" || name == "mathit" || name == "boldsymbol" || name == "tilde" ||
                       name == "dot" || name == "ddot" || name == "widehat" || name == "mathcal") {
                w += tex_width(arg(), scale, text_mode) + 0.05 * scale;
            } else if (name == "left" || name == "right" || name == "bigl" || name == "bigr" || name == "Bigl" ||
                       name == "Bigr") {
                std::size_t end = skip_argument(s, i);
                const bool null = s.compare(i, end - i, ".") == 0;
                i = end;
                w += scale * (null ? 0.12 : 0.62);
            } else if (name == "quad") {
                w += scale;
            } else if (name == "qquad") {
                w += 2 * scale;
            } else if (name == "cdot" || name == "ldots" || name == "cdots") {
                w += 0.75 * scale;
            } else if (name == "times" || name == "pm" || name == "mp" || name == "setminus") {
                w += 1.24 * scale;
            } else if (name == "le" || name == "ge" || name == "leq" || name == "geq" || name == "ne" ||
                       name == "neq" || name == "to" || name == "approx" || name == "equiv" || name == "rightarrow" ||
                       name == "sim" || name == "mapsto" || name == "in" || name == "propto" || name == "simeq") {
                w += 1.34 * scale;
            } else if (name == "tag" || name == "label" || name == "eqref" || name == "ref") {
                arg(); // tags are measured by the caller
                if (name == "eqref" || name == "ref")
                    w += 2 * scale;
            } else if (name == "small") {
                scale *= 0.92; // to the end of the group
            } else if (name == "allowbreak" || name == "displaystyle" || name == "textstyle" || name == "nonumber" ||
                       name == "notag" || name == "limits" || name == "nolimits" || name == "begin" || name == "end") {
                if (name == "begin" || name == "end")
                    arg();
            } else if (name == "sin" || name == "cos" || name == "tan" || name == "exp" || name == "log" ||
                       name == "ln" || name == "arctan" || name == "max" || name == "min" || name == "sgn" ||
                       name == "det") {
                w += scale * (0.55 * static_cast<double>(name.size()) + 0.17); // upright, and a thin space
            } else if (name == "infty" || name == "int" || name == "sum" || name == "prod") {
                w += 1.1 * scale;
            } else if (text_mode && name.size() > 4 && name.compare(0, 4, "text") == 0) {
                w += 0.55 * scale; // \textbackslash
            } else {
                w += 0.72 * scale; // a Greek letter or another symbol
            }
            continue;
        }
        if (c == '{') {
            std::size_t end = skip_argument(s, i);
            w += tex_width(argument_body(s, i, end), scale, text_mode);
            i = end;
            continue;
        }
        if (c == '$') {
            text_mode = !text_mode;
            ++i;
            continue;
        }
        if (c == '}' || c == '&') {
            ++i;
            continue;
        }
        if (static_cast<unsigned char>(c) >= 0x80) { // a UTF-8 character (Markdown): one glyph
            std::size_t end = skip_argument(s, i);
            w += 0.8 * scale;
            i = end;
            continue;
        }
        w += scale * glyph_em(c, text_mode);
        ++i;
    }
    return w;
}

// One item of a formula at one level of its nesting.
struct tex_item {
    enum kind { atom, op, group, frac } k = atom;
    std::string tex;             ///< atom: its TeX; op: "+" or "-"; group: the opening delimiter; frac: the denominator
    std::string close;           ///< group: the closing delimiter
    std::vector<tex_item> inner; ///< group: the contents; frac: the numerator
    double width = 0;            ///< estimated, em
};
using tex_seq = std::vector<tex_item>;

double seq_width(const tex_seq &seq)
{
    double w = 0;
    for (const tex_item &it : seq)
        w += it.width;
    return w;
}

std::string render(const tex_seq &seq);

std::string render(const tex_item &it)
{
    switch (it.k) {
    case tex_item::atom:
        return it.tex;
    case tex_item::op:
        return it.tex;
    case tex_item::group:
        return it.tex + render(it.inner) + it.close;
    case tex_item::frac:
        return "\\frac{" + render(it.inner) + "}{" + it.tex + "}";
    }
    return it.tex;
}

// Items joined as canonical.cpp joins them: spaces between factors, " + " around operators.
std::string render(const tex_seq &seq)
{
    std::string out;
    for (const tex_item &it : seq) {
        if (!out.empty())
            out += ' ';
        out += render(it);
    }
    return out;
}

// The end of a \left...\right group whose \left starts at `at`: the index after
// the closing delimiter, and the positions of the contents; npos when unbalanced.
struct group_span {
    std::size_t open_end = std::string::npos, close_start = 0, end = 0;
};
group_span find_group(const std::string &s, std::size_t at)
{
    group_span g;
    g.open_end = skip_argument(s, at + 5); // after "\left" and its delimiter
    int depth = 1;
    for (std::size_t k = g.open_end; k < s.size(); ++k) {
        if (s.compare(k, 5, "\\left") == 0 &&
            (k + 5 >= s.size() || !std::isalpha(static_cast<unsigned char>(s[k + 5])))) {
            ++depth;
        } else if (s.compare(k, 6, "\\right") == 0 &&
                   (k + 6 >= s.size() || !std::isalpha(static_cast<unsigned char>(s[k + 6]))) && --depth == 0) {
            g.close_start = k;
            g.end = skip_argument(s, k + 6);
            return g;
        }
    }
    g.open_end = std::string::npos;
    return g;
}

tex_seq parse_tex(const std::string &s)
{
    tex_seq out;
    std::string cur;
    auto flush = [&] {
        std::size_t a = cur.find_first_not_of(' '), b = cur.find_last_not_of(' ');
        if (a != std::string::npos) {
            tex_item it;
            it.tex = cur.substr(a, b - a + 1);
            it.width = tex_width(it.tex);
            out.push_back(it);
        }
        cur.clear();
    };
    // Something since the last operator, not an opening parenthesis, comma or
    // relation: a + or - here is binary.
    auto has_operand = [&] {
        std::size_t last = cur.find_last_not_of(' ');
        if (last != std::string::npos)
            return std::string("([{,=<>").find(cur[last]) == std::string::npos;
        return !out.empty() && out.back().k != tex_item::op;
    };
    for (std::size_t i = 0; i < s.size();) {
        const char c = s[i];
        if ((c == '+' || c == '-') && has_operand()) {
            flush();
            tex_item it;
            it.k = tex_item::op;
            it.tex = std::string(1, c);
            it.width = 1.24;
            out.push_back(it);
            ++i;
            continue;
        }
        if (s.compare(i, 5, "\\left") == 0 &&
            !(i + 5 < s.size() && std::isalpha(static_cast<unsigned char>(s[i + 5])))) {
            group_span g = find_group(s, i);
            if (g.open_end != std::string::npos) {
                flush();
                tex_item it;
                it.k = tex_item::group;
                it.tex = s.substr(i, g.open_end - i);
                it.close = s.substr(g.close_start, g.end - g.close_start);
                const std::string body = s.substr(g.open_end, g.close_start - g.open_end);
                it.inner = parse_tex(body);
                // delimiters (taller around a fraction) and the thin spaces around an inner atom
                it.width = seq_width(it.inner) + (contains_fraction(body) ? 1.7 : 1.3);
                out.push_back(it);
                i = g.end;
                continue;
            }
        }
        if (s.compare(i, 5, "\\frac") == 0 &&
            !(i + 5 < s.size() && std::isalpha(static_cast<unsigned char>(s[i + 5])))) {
            std::size_t a = skip_argument(s, i + 5), b = skip_argument(s, a);
            flush();
            tex_item it;
            it.k = tex_item::frac;
            it.inner = parse_tex(argument_body(s, i + 5, a));
            it.tex = argument_body(s, a, b);
            it.width = std::max(seq_width(it.inner), tex_width(it.tex)) + 0.3;
            out.push_back(it);
            i = b;
            continue;
        }
        if (c == '\\') {
            // a command and the braced arguments that follow it
            std::size_t end = skip_argument(s, i);
            while (end < s.size() && s[end] == '{')
                end = skip_argument(s, end);
            cur += s.substr(i, end - i);
            i = end;
            continue;
        }
        if (c == '{' || c == '^' || c == '_') {
            std::size_t end = skip_argument(s, c == '{' ? i : i + 1);
            cur += s.substr(i, end - i);
            i = end;
            continue;
        }
        cur += c;
        ++i;
    }
    flush();
    return out;
}

// The terms of a sum: each with the operator before it ("" for the first).
std::vector<std::pair<std::string, tex_seq>> terms_of(const tex_seq &seq)
{
    std::vector<std::pair<std::string, tex_seq>> out(1);
    for (const tex_item &it : seq) {
        if (it.k == tex_item::op)
            out.push_back({it.tex, {}});
        else
            out.back().second.push_back(it);
    }
    return out;
}

// How many \left minus how many \right: the groups a piece of TeX leaves open.
int open_groups(const std::string &s)
{
    int n = 0;
    for (std::size_t k = s.find('\\'); k != std::string::npos; k = s.find('\\', k + 1)) {
        if (s.compare(k, 5, "\\left") == 0 && !(k + 5 < s.size() && std::isalpha(static_cast<unsigned char>(s[k + 5]))))
            ++n;
        else if (s.compare(k, 6, "\\right") == 0 &&
                 !(k + 6 < s.size() && std::isalpha(static_cast<unsigned char>(s[k + 6]))))
            --n;
    }
    return n;
}

// A unit of line filling: one term of a sum at some depth, with the TeX that
// opens its enclosing groups before it (head) or closes them after it (tail).
struct piece {
    std::string op;   ///< "+" or "-" before it; "" for the first term of a formula
    std::string head; ///< e.g. "m_{1} \left(" when the term starts a group
    tex_seq term;
    std::string tail; ///< e.g. "\right) \omega_{t1}" when it ends one
    int open = 0;     ///< \left groups open where a line may break before it

    double width() const
    {
        return (op.empty() ? 0 : 1.24) + tex_width(head) + seq_width(term) + (term.size() > 1 ? 0.2 : 0) +
               tex_width(tail);
    }
    std::string tex(bool line_start) const
    {
        std::string body = head;
        std::string t = render(term);
        if (!t.empty())
            body += (body.empty() ? "" : " ") + t;
        if (!tail.empty())
            body += (body.empty() ? "" : " ") + tail;
        if (op.empty())
            return body;
        // {}+ keeps the sign binary (its spaces) at the start of a line
        return (line_start ? "{}" : "") + op + " " + body;
    }
};

std::vector<piece> pieces_of(const std::string &tex)
{
    std::vector<piece> out;
    for (auto &[op, term] : terms_of(parse_tex(tex)))
        out.push_back({op, "", term, "", 0});
    return out;
}

// The piece opened one level down (see above), or nothing when it cannot be.
std::vector<piece> open_up(const piece &p)
{
    // the widest group or fraction of the term that has a sum to break
    std::size_t best = p.term.size();
    for (std::size_t k = 0; k < p.term.size(); ++k) {
        const tex_item &it = p.term[k];
        bool breakable = false;
        if (it.k == tex_item::group)
            breakable = terms_of(it.inner).size() > 1;
        if (it.k == tex_item::frac) {
            breakable = terms_of(it.inner).size() > 1;
            for (const tex_item &f : it.inner)
                breakable = breakable || (f.k == tex_item::group && terms_of(f.inner).size() > 1);
        }
        if (breakable && (best == p.term.size() || it.width > p.term[best].width))
            best = k;
    }
    if (best == p.term.size())
        return {};
    const tex_item &it = p.term[best];
    std::string open, close, lead;
    tex_seq sum;
    if (it.k == tex_item::group) {
        open = it.tex;
        close = it.close;
        sum = it.inner;
    } else if (terms_of(it.inner).size() > 1) {
        // \frac{a + b}{c} -> \frac{1}{c} \left(a + b\right)
        lead = "\\frac{1}{" + it.tex + "}";
        open = "\\left(";
        close = "\\right)";
        sum = it.inner;
    } else {
        // \frac{2 \left(a + b\right) x}{c} -> \frac{2 x}{c} \left(a + b\right)
        std::size_t g = it.inner.size();
        for (std::size_t k = 0; k < it.inner.size(); ++k)
            if (it.inner[k].k == tex_item::group && terms_of(it.inner[k].inner).size() > 1 &&
                (g == it.inner.size() || it.inner[k].width > it.inner[g].width))
                g = k;
        tex_seq rest;
        for (std::size_t k = 0; k < it.inner.size(); ++k)
            if (k != g)
                rest.push_back(it.inner[k]);
        lead = "\\frac{" + (rest.empty() ? std::string("1") : render(rest)) + "}{" + it.tex + "}";
        open = it.inner[g].tex;
        close = it.inner[g].close;
        sum = it.inner[g].inner;
    }
    tex_seq before(p.term.begin(), p.term.begin() + static_cast<std::ptrdiff_t>(best));
    tex_seq after(p.term.begin() + static_cast<std::ptrdiff_t>(best) + 1, p.term.end());
    std::string head = p.head;
    for (const std::string &part : {render(before), lead, open})
        if (!part.empty())
            head += (head.empty() ? "" : " ") + part;
    std::string tail = close;
    for (const std::string &part : {render(after), p.tail})
        if (!part.empty())
            tail += " " + part;
    std::vector<std::pair<std::string, tex_seq>> terms = terms_of(sum);
    const int inside = p.open + open_groups(head);
    std::vector<piece> out;
    for (std::size_t k = 0; k < terms.size(); ++k)
        out.push_back({k == 0 ? p.op : terms[k].first, k == 0 ? head : "", terms[k].second,
                       k + 1 == terms.size() ? tail : "", k == 0 ? p.open : inside});
    return out;
}

std::string repeat(const std::string &s, int n)
{
    std::string out;
    for (int k = 0; k < n; ++k)
        out += s;
    return out;
}

// Sets pieces into lines: the first has room `first` em, the others `rest`.
// A break inside groups closes them with \right. and reopens them with \left.
std::vector<std::string> fill_lines(std::vector<piece> pieces, double first, double rest)
{
    std::vector<std::string> lines;
    std::string line;
    double used = 0, room = first;
    bool empty = true;
    for (std::size_t i = 0; i < pieces.size();) {
        const piece &p = pieces[i];
        const double w = p.width();
        if (used + w <= room || (empty && w <= room)) {
            line += (line.empty() ? "" : " ") + p.tex(empty);
            used += w;
            empty = false;
            ++i;
            continue;
        }
        if (!empty) {
            line += repeat(" \\right.", p.open);
            lines.push_back(line);
            line = repeat("\\left.", p.open);
            used = 0.12 * p.open;
            room = rest;
            empty = true;
            continue;
        }
        std::vector<piece> finer = open_up(p);
        if (!finer.empty()) {
            pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(i));
            pieces.insert(pieces.begin() + static_cast<std::ptrdiff_t>(i), finer.begin(), finer.end());
            continue;
        }
        // one atom wider than a line: nothing to break at
        line += (line.empty() ? "" : " ") + p.tex(empty);
        used += w;
        empty = false;
        ++i;
    }
    lines.push_back(line);
    return lines;
}

// A displayed row as TeX: its parts and where the printers put it.
struct row_tex {
    std::string left;                                        ///< lhs (or its notation)
    std::vector<std::pair<std::string, std::string>> rights; ///< (relation, rhs), then ("=", then)
};

row_tex tex_row_parts(const math_row &r)
{
    row_tex out;
    out.left = r.lhs_note.text.empty() ? math_latex(r.lhs) : r.lhs_note.tex;
    if (!r.rel.empty())
        out.rights.push_back({tex_rel(r.rel), math_latex(r.rhs)});
    if (r.has_then)
        out.rights.push_back({"=", math_latex(r.then)});
    return out;
}

std::string one_line(const row_tex &row)
{
    std::string s = row.left;
    for (const auto &[rel, rhs] : row.rights)
        s += " " + rel + " " + rhs;
    return s;
}

// A short lhs stays in a column left of the relations; a longer one goes
// into the formula's lines.
bool short_lhs(double width)
{
    return width <= 0.3 * row_budget_em;
}

// A row too wide for one line, as the lines of an align* (or aligned)
// environment, each within `budget` em: "lhs &= a + b", "&\quad {}+ c".
// A short lhs stays left of the relation, aligned on it; a long one takes
// the first line(s), "lhs =", and the right side follows, indented. `column`: the width of
// the lhs column when the row shares an align* with others (at least its own
// short lhs).
std::vector<std::string> break_row(const row_tex &row, double budget, double column = 0)
{
    std::vector<std::string> lines;
    const double left = tex_width(row.left);
    if (short_lhs(left)) {
        column = std::max(column, left);
        for (std::size_t k = 0; k < row.rights.size(); ++k) {
            const auto &[rel, rhs] = row.rights[k];
            const double room = budget - column - tex_width(rel) - 0.5;
            std::vector<std::string> part = fill_lines(pieces_of(rhs), room, budget - column - 1);
            for (std::size_t j = 0; j < part.size(); ++j)
                lines.push_back(j == 0 ? (k == 0 ? row.left + " " : "") + "&" + rel + " " + part[j]
                                       : "&\\quad " + part[j]);
        }
        return lines;
    }
    // "lhs =" first, then each right side on lines of its own, the next
    // relation at the end of its last line
    budget -= column;
    auto rel_room = [&](std::size_t k) { return k < row.rights.size() ? tex_width(row.rights[k].first) + 0.5 : 0.0; };
    for (const std::string &part : fill_lines(pieces_of(row.left), budget - rel_room(0), budget - 1 - rel_room(0)))
        lines.push_back(lines.empty() ? "&" + part : "&\\quad " + part);
    for (std::size_t k = 0; k < row.rights.size(); ++k) {
        lines.back() += " " + row.rights[k].first;
        const double room = budget - 1 - rel_room(k + 1);
        std::vector<std::string> part = fill_lines(pieces_of(row.rights[k].second), room, room - 1);
        for (std::size_t j = 0; j < part.size(); ++j)
            lines.push_back(j == 0 ? "&\\quad " + part[j] : "&\\qquad " + part[j]);
    }
    return lines;
}

// Inline math: as one $...$ when it is short; a long formula as several, one
// per piece of at most a quarter of the line, so that the paragraph can break
// between them, inside \left( \right) too. Between two pieces, a break that
// may leave its line ragged (by up to a third of it): stretch that a break keeps at
// the end of the line and that cancels out when there is no break.
std::string inline_math(const std::string &tex)
{
    if (tex_width(tex) <= 0.45 * text_width_em)
        return "$" + tex + "$";
    std::string out;
    for (const std::string &part : fill_lines(pieces_of(tex), 0.25 * text_width_em, 0.25 * text_width_em))
        out += (out.empty() ? "$" : "$\\nobreak\\hskip 0pt plus 15em\\penalty0\\hskip 0pt plus -15em\\relax$") + part;
    return out + "$";
}

// A label key for a tag: letters and digits as they are, any other byte (and
// 'z', the escape) as "z" and two hex digits: 3' -> 3z27. Distinct tags get
// distinct keys, and every key is safe in \label and \eqref.
std::string label_key(const std::string &tag)
{
    static const char hex[] = "0123456789abcdef";
    std::string out = "eq:";
    for (unsigned char c : tag) {
        if (std::isalnum(c) && c < 0x80 && c != 'z') {
            out += static_cast<char>(c);
        } else {
            out += 'z';
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    return out;
}

std::string tex_spans(const paragraph &p, bool markdown)
{
    std::string out;
    for (const span &s : p.spans) {
        if (s.k == span::words) {
            if (markdown) {
                std::string w;
                for (char c : s.text)
                    w += (c == '_' || c == '*') ? std::string("\\") + c : std::string(1, c);
                out += w;
            } else {
                out += tex_words(s.text);
            }
        } else if (s.k == span::math) {
            out += markdown ? "$" + math_latex(s.expr) + "$" : inline_math(math_latex(s.expr));
        } else if (s.k == span::ref) {
            out += markdown ? "(" + s.text + ")" : "\\eqref{" + label_key(s.text) + "}";
        } else {
            out += markdown ? "$" + s.formula.tex + "$" : inline_math(s.formula.tex);
        }
    }
    return out;
}

// A displayed row for Markdown ($$...$$, MathJax or KaTeX): one line when it
// fits the same width as in LaTeX, else broken the same way inside aligned.
std::string markdown_row(const math_row &r)
{
    row_tex parts = tex_row_parts(r);
    std::string tag = r.tag.empty() ? "" : " \\tag{" + r.tag + "}";
    const double budget = row_budget_em - (r.tag.empty() ? 0 : tex_width("(" + r.tag + ")", 1, true) + 1.5);
    std::string line = one_line(parts);
    if (tex_width(line) <= budget)
        return "$$" + line + tag + "$$";
    std::string out = "$$\\begin{aligned}";
    std::vector<std::string> lines = break_row(parts, budget);
    for (std::size_t k = 0; k < lines.size(); ++k)
        out += (k ? " \\\\ " : "") + lines[k];
    return out + "\\end{aligned}" + tag + "$$";
}

// " \tag{3}\label{eq:3}": the label only where the tag first appears (the
// worked example shows the equations again under their tags; a reference
// goes to the equation as first stated).
std::string tag_tex(const std::string &tag, std::set<std::string> &labelled)
{
    if (tag.empty())
        return "";
    std::string out = " \\tag{" + tex_words(tag) + "}";
    if (labelled.insert(label_key(tag)).second)
        out += "\\label{" + label_key(tag) + "}";
    return out;
}

// The room a tag takes at the end of a line: "(3)" and the space before it.
double tag_width_em(const std::string &tag)
{
    return tag.empty() ? 0 : tex_width("(" + tex_words(tag) + ")", 1, true) + 1.5;
}

// The width of the box a note under a row is set in: as wide as the note
// (the estimate is generous), at most what is left of the line after
// `column` and at most five eighths of the text width, which keeps a long
// note a compact paragraph under its formula.
std::string note_box(const std::string &note, double column)
{
    const double width =
        std::min({row_budget_em - column - 1, 0.625 * text_width_em, tex_width(note, 0.92, true) + 0.5});
    const long tenths = static_cast<long>(width * 10);
    return "\\parbox[t]{" + std::to_string(tenths / 10) + "." + std::to_string(tenths % 10) + "em}";
}

// A note under a row of an align*: the next line, in the column of the
// relations (`column`: the width of the lhs column). \\* keeps it on the
// page of its row.
std::string note_line(const std::string &note, double column)
{
    return " \\\\*\n  &" + note_box(note, column) + "{\\small\\raggedright " + note + "}";
}

// A displayed row for LaTeX, alone. One line: equation*, a short note beside
// it (before the tag); a long note centred under it (gather*). Too wide:
// align*, broken into lines (allowdisplaybreaks lets a long row continue on
// the next page), the note under the relations.
std::string latex_row(const math_row &r, std::set<std::string> &labelled)
{
    row_tex parts = tex_row_parts(r);
    const std::string tag = tag_tex(r.tag, labelled);
    const double tag_width = tag_width_em(r.tag);
    const std::string note = tex_spans(r.note, false);
    const double budget = row_budget_em - tag_width;
    const std::string line = one_line(parts);
    const double width = tex_width(line);
    if (width <= budget) {
        if (note.empty() || width + 2 + tex_width(note, 0.92, true) <= budget) {
            std::string beside = note.empty() ? "" : "\\qquad\\text{\\small " + note + "}";
            return "\\begin{equation*}\n  " + line + beside + tag + "\n\\end{equation*}\n";
        }
        return "\\begin{gather*}\n  " + line + tag + " \\\\*\n  " + note_box(note, 0) + "{\\small\\centering " + note +
               "}\n\\end{gather*}\n";
    }
    // the lhs column: a short lhs, or nothing (as break_row decides)
    const double left = tex_width(parts.left);
    std::vector<std::string> lines = break_row(parts, budget);
    std::string out = "\\begin{align*}\n";
    for (std::size_t k = 0; k < lines.size(); ++k)
        out += "  " + lines[k] + (k + 1 < lines.size() ? " \\\\\n" : tag);
    if (!note.empty())
        out += note_line(note, short_lhs(left) ? left : 0);
    return out + "\n\\end{align*}\n";
}

// A block of displayed rows for LaTeX. Several rows are one align*, aligned
// on their relations (a long lhs goes into the formula's lines), each with
// its tag; a row too wide for one line broken as in break_row; the notes in a
// column of their own beside the rows when every row is one line and they all
// fit there, else each under its row. One row alone: latex_row.
std::string latex_rows(const std::vector<math_row> &rows, std::set<std::string> &labelled)
{
    if (rows.size() == 1)
        return latex_row(rows.front(), labelled);
    struct laid {
        row_tex parts;
        std::string tag, note; // the tag as the row has it
        double left = 0, right = 0, tag_width = 0;
    };
    std::vector<laid> all;
    double column = 0, right = 0, tags = 0, notes = 0;
    for (const math_row &r : rows) {
        laid l;
        l.parts = tex_row_parts(r);
        l.tag = r.tag;
        l.tag_width = tag_width_em(r.tag);
        l.note = tex_spans(r.note, false);
        l.left = tex_width(l.parts.left);
        l.right = tex_width(one_line(l.parts)) - l.left;
        // a row that fits on one line joins the lhs column, however long its lhs
        if (l.left + l.right + l.tag_width <= row_budget_em)
            column = std::max(column, l.left);
        tags = std::max(tags, l.tag_width);
        if (!l.note.empty())
            notes = std::max(notes, tex_width(l.note, 0.92, true));
        all.push_back(l);
    }
    // one line each: a short lhs and its right side beside the lhs column, with the tag
    bool one_line_each = true;
    for (const laid &l : all) {
        one_line_each = one_line_each && column + l.right + l.tag_width <= row_budget_em;
        right = std::max(right, l.right);
    }
    const bool beside = one_line_each && notes > 0 && column + right + 2 + notes + tags <= row_budget_em;
    std::string out = "\\begin{align*}\n";
    for (std::size_t k = 0; k < all.size(); ++k) {
        const laid &l = all[k];
        std::vector<std::string> lines;
        if (l.left <= column && column + l.right + l.tag_width <= row_budget_em) {
            std::string line = l.parts.left + " &";
            for (std::size_t j = 0; j < l.parts.rights.size(); ++j)
                line += (j ? " " : "") + l.parts.rights[j].first + " " + l.parts.rights[j].second;
            lines.push_back(line);
        } else {
            lines = break_row(l.parts, row_budget_em - l.tag_width, column);
        }
        for (std::size_t j = 0; j + 1 < lines.size(); ++j)
            out += "  " + lines[j] + " \\\\\n";
        out += "  " + lines.back();
        if (beside && !l.note.empty())
            out += " &&\\text{\\small " + l.note + "}";
        out += tag_tex(l.tag, labelled);
        if (!beside && !l.note.empty())
            out += note_line(l.note, column);
        // rows with notes under them a little apart, so that each note reads with its row
        out += k + 1 < all.size() ? (notes > 0 && !beside ? " \\\\[1ex]\n" : " \\\\[0.3ex]\n") : "\n";
    }
    return out + "\\end{align*}\n";
}

bool has_figures(const document &doc)
{
    for (const section &sec : doc.sections)
        for (const block &b : sec.blocks)
            if (b.k == block::figure)
                return true;
    return false;
}

} // namespace

std::string explain_text(const document &doc)
{
    std::ostringstream os;
    os << doc.title << "\n" << std::string(columns(doc.title), '=') << "\n";
    for (const section &sec : doc.sections) {
        os << "\n" << sec.title << "\n" << std::string(columns(sec.title), '-') << "\n";
        for (const block &b : sec.blocks) {
            switch (b.k) {
            case block::text:
                os << "\n" << wrap(text_spans(b.para), "", "");
                break;
            case block::list:
                os << "\n";
                for (const paragraph &item : b.items)
                    os << wrap(text_spans(item), "  - ", "    ");
                break;
            case block::figure:
                os << "\n" << wrap("[Figure: " + b.art.alt + "]", "", "");
                break;
            case block::rows: {
                os << "\n";
                std::size_t tag_width = 0;
                for (const math_row &r : b.math)
                    tag_width = std::max(tag_width, r.tag.empty() ? std::size_t(0) : columns(r.tag) + 2);
                for (const math_row &r : b.math) {
                    std::string tag = r.tag.empty() ? "" : "(" + r.tag + ")";
                    std::string line = "  " + tag + std::string(tag_width - columns(tag) + (tag_width ? 2 : 0), ' ') +
                                       text_row_left(r);
                    if (!r.rel.empty())
                        line += " " + r.rel + " " + math_text(r.rhs);
                    if (r.has_then)
                        line += " = " + math_text(r.then);
                    std::string note = text_spans(r.note);
                    if (note.empty()) {
                        os << line << "\n";
                    } else if (r.rel.empty() && r.lhs_note.text.empty() && columns(line) < 22) {
                        os << wrap(harden(line + std::string(22 - columns(line), ' ')) + note, "",
                                   std::string(24, ' '));
                    } else {
                        os << line << "\n"
                           << wrap(note, std::string(tag_width + 8, ' '), std::string(tag_width + 8, ' '));
                    }
                }
                break;
            }
            }
        }
    }
    return os.str();
}

std::string explain_markdown(const document &doc)
{
    std::ostringstream os;
    os << "# " << doc.title << "\n";
    for (const section &sec : doc.sections) {
        os << "\n## " << sec.title << "\n";
        for (const block &b : sec.blocks) {
            switch (b.k) {
            case block::text:
                os << "\n" << tex_spans(b.para, true) << "\n";
                break;
            case block::list:
                os << "\n";
                for (const paragraph &item : b.items)
                    os << "- " << tex_spans(item, true) << "\n";
                break;
            case block::figure:
                os << "\n*Figure: " << b.art.alt << "*\n";
                break;
            case block::rows:
                os << "\n";
                for (const math_row &r : b.math) {
                    std::string note = tex_spans(r.note, true);
                    if (r.rel.empty() && r.tag.empty()) {
                        os << "- $" << one_line(tex_row_parts(r)) << "$" << (note.empty() ? "" : ": " + note) << "\n";
                        continue;
                    }
                    os << markdown_row(r) << "\n";
                    if (!note.empty())
                        os << "\n> " << note << "\n";
                    os << "\n";
                }
                break;
            }
        }
    }
    return os.str();
}

std::string explain_latex(const document &doc)
{
    const bool figures = has_figures(doc);
    std::set<std::string> labelled;
    std::ostringstream os;
    // A hand-out: A4 with 2.5 cm margins (row_budget_em assumes that text
    // width), Computer Modern in its Type 1 outlines (OT1: T1 would need cm-super
    // or lmodern, which texlive-latex-base does not have, and fall back to bitmaps),
    // emergency stretch for paragraphs with long formulas in them. Every package
    // is in texlive-latex-base, tikz (only with a figure) in texlive-pictures.
    os << "% Written by impactgen explain. Compile with pdflatex (needs amsmath, geometry, hyperref"
       << (figures ? "; tikz for the figure" : "") << ").\n"
       << "\\documentclass[11pt,a4paper]{article}\n"
          "\\usepackage[margin=2.5cm]{geometry}\n"
          "\\usepackage{amsmath}\n";
    if (figures)
        os << "\\usepackage{tikz}\n"
              "\\newsavebox{\\figurebox}\n";
    os << "\\usepackage[hidelinks]{hyperref}\n"; // equation references link to their equations
    os << "\\setlength{\\parindent}{0pt}\n"
          "\\setlength{\\parskip}{0.5em}\n"
          "\\setlength{\\emergencystretch}{3em}\n"
          "\\allowdisplaybreaks\n"
          "\\title{"
       << tex_words(doc.title)
       << "}\n\\author{}\n\\date{}\n"
          "\\begin{document}\n\\maketitle\n";
    for (const section &sec : doc.sections) {
        os << "\n\\section*{" << tex_words(sec.title) << "}\n";
        for (const block &b : sec.blocks) {
            switch (b.k) {
            case block::text:
                os << "\n" << tex_spans(b.para, false) << "\n";
                break;
            case block::list:
                os << "\n\\begin{itemize}\n";
                for (const paragraph &item : b.items)
                    os << "  \\item " << tex_spans(item, false) << "\n";
                os << "\\end{itemize}\n";
                break;
            case block::figure:
                // scaled down to the line when it is wider, never up
                os << "\n\\begin{center}\n\\sbox{\\figurebox}{%\n"
                   << b.art.tikz
                   << "%\n}%\n\\ifdim\\wd\\figurebox>\\linewidth\\resizebox{\\linewidth}{!}{\\usebox{\\figurebox}}"
                      "\\else\\usebox{\\figurebox}\\fi\n";
                if (!b.art.caption.empty())
                    os << "\\par{\\small " << tex_words(b.art.caption) << "}\n";
                os << "\\end{center}\n";
                break;
            case block::rows: {
                bool plain = true;
                for (const math_row &r : b.math)
                    plain = plain && r.rel.empty() && r.tag.empty();
                bool bare = plain; // formulas without notes: displayed, one per line
                for (const math_row &r : b.math)
                    bare = bare && r.note.spans.empty();
                if (bare) {
                    os << "\\begin{gather*}\n";
                    for (std::size_t k = 0; k < b.math.size(); ++k)
                        os << "  " << one_line(tex_row_parts(b.math[k])) << (k + 1 < b.math.size() ? " \\\\\n" : "\n");
                    os << "\\end{gather*}\n";
                    break;
                }
                if (plain) {
                    os << "\n\\begin{itemize}\n";
                    for (const math_row &r : b.math) {
                        std::string note = tex_spans(r.note, false);
                        os << "  \\item " << inline_math(one_line(tex_row_parts(r)))
                           << (note.empty() ? "" : ": " + note) << "\n";
                    }
                    os << "\\end{itemize}\n";
                    break;
                }
                os << latex_rows(b.math, labelled);
                break;
            }
            }
        }
    }
    os << "\n\\end{document}\n";
    // Every character outside ASCII has been mapped (tex_words) or escaped; one that has not
    // (a body named μ set in \\text{} or in the figure's labels) would stop pdflatex with an
    // error: refuse it here, as tex_words does, naming it.
    const std::string out = os.str();
    for (std::size_t k = 0; k < out.size(); ++k)
        if (static_cast<unsigned char>(out[k]) >= 0x80) {
            std::size_t n = 1;
            while (k + n < out.size() && (static_cast<unsigned char>(out[k + n]) & 0xC0) == 0x80)
                ++n;
            const std::size_t from = out.rfind('\n', k), to = out.find('\n', k);
            const std::string line =
                out.substr(from == std::string::npos ? 0 : from + 1,
                           (to == std::string::npos ? out.size() : to) - (from == std::string::npos ? 0 : from + 1));
            throw std::invalid_argument("the LaTeX output has no rendering for the character \"" +
                                        names::display_text(out.substr(k, n)) + "\" (in \"" +
                                        names::display_text(line, 60) + "\"); use ASCII names for --format latex");
        }
    return out;
}

} // namespace impactgen::print

// The width model of the LaTeX layout, for its tests (tests/explain/latex_tools.hpp
// declares the first two), and its row breaking for the HTML page (explain_html.cpp).
namespace impactgen::print::layout
{
double estimated_width_em(const std::string &tex)
{
    return tex_width(tex);
}
double row_budget_em()
{
    return print::row_budget_em;
}
std::vector<std::string> broken_row_lines(const math_row &r, double budget)
{
    const row_tex parts = tex_row_parts(r);
    if (tex_width(one_line(parts)) <= budget)
        return {};
    return break_row(parts, budget);
}
} // namespace impactgen::print::layout
