// The LaTeX layout of the explanation printers (tex_layout.hpp).
#include "tex_layout.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace impactgen::print::tex_layout
{

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

// The width of the control word \name at i (i then past its arguments) added to w; \small scales the rest.
void control_word_width(const std::string &s, std::size_t &i, const std::string &name, double &w, double &scale,
                        bool text_mode)
{
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
    } else if (name == "text" || name == "textrm" || name == "mbox" || name == "mathrm" || name == "operatorname" ||
               name == "textit" || name == "emph") {
        w += tex_width(arg(), scale, true);
    } else if (name == "underline" || name == "hat" || name == "bar" || name == "vec" || name == "overline" ||
               name == "mathbf" || name == "mathit" || name == "boldsymbol" || name == "tilde" || name == "dot" ||
               name == "ddot" || name == "widehat" || name == "mathcal") {
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
    } else if (name == "le" || name == "ge" || name == "leq" || name == "geq" || name == "ne" || name == "neq" ||
               name == "to" || name == "approx" || name == "equiv" || name == "rightarrow" || name == "sim" ||
               name == "mapsto" || name == "in" || name == "propto" || name == "simeq") {
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
    } else if (name == "sin" || name == "cos" || name == "tan" || name == "exp" || name == "log" || name == "ln" ||
               name == "arctan" || name == "max" || name == "min" || name == "sgn" || name == "det") {
        w += scale * (0.55 * static_cast<double>(name.size()) + 0.17); // upright, and a thin space
    } else if (name == "infty" || name == "int" || name == "sum" || name == "prod") {
        w += 1.1 * scale;
    } else if (text_mode && name.size() > 4 && name.compare(0, 4, "text") == 0) {
        w += 0.55 * scale; // \textbackslash
    } else {
        w += 0.72 * scale; // a Greek letter or another symbol
    }
}

// The estimated width of TeX (math mode, or text mode inside \text{...}) at `scale`.
double tex_width(const std::string &s, double scale, bool text_mode)
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
            control_word_width(s, i, name, w, scale, text_mode);
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
std::vector<std::string> break_row(const row_tex &row, double budget, double column)
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

} // namespace impactgen::print::tex_layout
