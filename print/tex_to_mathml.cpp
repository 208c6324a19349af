// TeX math -> presentation MathML for the subset listed in tex_to_mathml.hpp.
//
// A recursive-descent reader over the TeX string. A list of atoms is read up
// to the end, a closing brace or \right; each atom (a letter, a number, an
// operator, a group, a command with its arguments) may carry primes, a
// subscript and a superscript, which become <msub>, <msup> or <msubsup>
// around it once the atom is complete. Every piece of text is escaped with
// names::xml_text (XML-safe: & < > " ' are written as entities).
#include "tex_to_mathml.hpp"

#include "names/escape.hpp"

#include <cctype>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace impactgen::print
{

namespace
{

struct command_symbol {
    const char *name;
    const char *element; ///< "mi" or "mo"
    const char *text;    ///< UTF-8
};

// Control words that stand for one character.
constexpr command_symbol symbols[] = {
    {"alpha", "mi", "α"},      {"beta", "mi", "β"},       {"gamma", "mi", "γ"},  {"delta", "mi", "δ"},
    {"epsilon", "mi", "ϵ"},    {"varepsilon", "mi", "ε"}, {"zeta", "mi", "ζ"},   {"eta", "mi", "η"},
    {"theta", "mi", "θ"},      {"vartheta", "mi", "ϑ"},   {"iota", "mi", "ι"},   {"kappa", "mi", "κ"},
    {"lambda", "mi", "λ"},     {"mu", "mi", "μ"},         {"nu", "mi", "ν"},     {"xi", "mi", "ξ"},
    {"pi", "mi", "π"},         {"varpi", "mi", "ϖ"},      {"rho", "mi", "ρ"},    {"varrho", "mi", "ϱ"},
    {"sigma", "mi", "σ"},      {"varsigma", "mi", "ς"},   {"tau", "mi", "τ"},    {"upsilon", "mi", "υ"},
    {"phi", "mi", "ϕ"},        {"varphi", "mi", "φ"},     {"chi", "mi", "χ"},    {"psi", "mi", "ψ"},
    {"omega", "mi", "ω"},      {"ell", "mi", "ℓ"},        {"infty", "mi", "∞"},  {"prime", "mo", "′"},
    {"cdot", "mo", "⋅"},       {"times", "mo", "×"},      {"pm", "mo", "±"},     {"mp", "mo", "∓"},
    {"le", "mo", "≤"},         {"leq", "mo", "≤"},        {"ge", "mo", "≥"},     {"geq", "mo", "≥"},
    {"ne", "mo", "≠"},         {"neq", "mo", "≠"},        {"approx", "mo", "≈"}, {"to", "mo", "→"},
    {"rightarrow", "mo", "→"}, {"ldots", "mo", "…"},      {"dots", "mo", "…"},   {"cdots", "mo", "⋯"},
    {"int", "mo", "∫"},        {"sum", "mo", "∑"},
};

// Function names TeX sets upright (\cos x): one multi-letter <mi>.
constexpr const char *functions[] = {"cos", "sin", "tan", "arctan", "max", "min", "det"};

// Upper-case Greek: upright, as TeX prints them.
constexpr command_symbol upright_symbols[] = {
    {"Gamma", "mi", "Γ"}, {"Delta", "mi", "Δ"}, {"Theta", "mi", "Θ"}, {"Lambda", "mi", "Λ"},
    {"Xi", "mi", "Ξ"},    {"Pi", "mi", "Π"},    {"Sigma", "mi", "Σ"}, {"Upsilon", "mi", "Υ"},
    {"Phi", "mi", "Φ"},   {"Psi", "mi", "Ψ"},   {"Omega", "mi", "Ω"},
};

// Horizontal space commands and their widths.
constexpr std::pair<const char *, const char *> spaces[] = {
    {",", "0.1667em"}, {":", "0.2222em"}, {";", "0.2778em"}, {" ", "0.3333em"}, {"quad", "1em"}, {"qquad", "2em"},
};

std::string element(const std::string &tag, const std::string &content, const std::string &attributes = "")
{
    return "<" + tag + attributes + ">" + content + "</" + tag + ">";
}

std::string mo(const std::string &text, bool fixed = false)
{
    return element("mo", names::xml_text(text), fixed ? " stretchy=\"false\"" : "");
}

// A prime as a superscript. The prime character (U+2032) is drawn raised
// already, and Chromium raises a script again: larger and lowered, it sits
// where TeX puts x'.
std::string prime()
{
    return "<mpadded voffset=\"-0.3em\"><mo mathsize=\"130%\">′</mo></mpadded>";
}

// Whether MathML is taller than a line of letters with scripts: a fraction,
// a root, an accent or a stretched fence in it. Delimiters grow around it
// only: Chromium stretches a delimiter to the exact height of its row, and
// around v_{t1} that is a larger, wider glyph where TeX keeps the normal one.
bool tall(const std::string &mathml)
{
    for (const char *t : {"<mfrac", "<msqrt", "<munder", "<mover", "stretchy=\"true\""})
        if (mathml.find(t) != std::string::npos)
            return true;
    return false;
}

// One element for a list of them: the element itself, or an <mrow>.
std::string row(const std::vector<std::string> &items)
{
    if (items.size() == 1)
        return items.front();
    std::string out;
    for (const std::string &s : items)
        out += s;
    return element("mrow", out);
}

bool is_letter(char c)
{
    return std::isalpha(static_cast<unsigned char>(c)) != 0;
}
bool is_digit(char c)
{
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

const std::string opening_bar = "<mo form=\"prefix\" stretchy=\"false\">|</mo>";
const std::string closing_bar = "<mo form=\"postfix\" stretchy=\"false\">|</mo>";

class translator
{
public:
    explicit translator(const std::string &tex) : tex_(tex) {}

    std::string run()
    {
        std::vector<std::string> out = list(stop::end);
        std::string s;
        for (const std::string &e : out)
            s += e;
        return s;
    }

private:
    enum class stop { end, brace, right };

    /// An atom and what is attached to it.
    struct item {
        std::string base;
        std::string sub;
        std::vector<std::string> sup; ///< primes, then the ^ argument
        bool has_sub = false, has_caret = false;
    };

    const std::string &tex_;
    std::size_t i_ = 0;
    bool upright_ = false; ///< inside \mathrm or \operatorname: letters upright, runs joined

    [[noreturn]] void fail(const std::string &what) const
    {
        throw std::invalid_argument("TeX to MathML: " + what + " at offset " + std::to_string(i_) + " in \"" +
                                    names::display_text(tex_, 120) + "\"");
    }

    bool at_end() const { return i_ >= tex_.size(); }
    char peek() const { return at_end() ? '\0' : tex_[i_]; }

    void skip_spaces()
    {
        while (!at_end() && (tex_[i_] == ' ' || tex_[i_] == '\n' || tex_[i_] == '\t'))
            ++i_;
    }

    /// After a backslash: a control word (letters) or a control symbol (one character).
    std::string control_name()
    {
        ++i_; // the backslash
        if (at_end())
            fail("a lone backslash");
        std::size_t start = i_;
        if (is_letter(tex_[i_])) {
            while (!at_end() && is_letter(tex_[i_]))
                ++i_;
        } else {
            ++i_;
        }
        return tex_.substr(start, i_ - start);
    }

    bool looking_at_right() const
    {
        return tex_.compare(i_, 6, "\\right") == 0 && (i_ + 6 >= tex_.size() || !is_letter(tex_[i_ + 6]));
    }

    /// Whether a + or - that follows these items is a prefix sign.
    static bool sign_position(const std::vector<item> &items)
    {
        for (auto it = items.rbegin(); it != items.rend(); ++it) {
            if (it->base.compare(0, 7, "<mspace") == 0)
                continue;
            if (it->has_sub || !it->sup.empty() || it->base.compare(0, 3, "<mo") != 0)
                return false;
            static const char *const before_sign[] = {"=", "≤", "≥", "&lt;", "&gt;", "≈", "→", "≠", "(", "[",
                                                      ",", ";", ":", "+",    "−",    "×", "⋅", "±", "∓", "/"};
            for (const char *op : before_sign)
                if (it->base == mo(op) || it->base == mo(op, true))
                    return true;
            return it->base == opening_bar;
        }
        return true;
    }

    static std::string finish(const item &it)
    {
        std::string base = it.base.empty() ? element("mrow", "") : it.base;
        std::string sup = it.sup.empty() ? "" : row(it.sup);
        if (it.has_sub && !sup.empty())
            return element("msubsup", base + it.sub + sup);
        if (it.has_sub)
            return element("msub", base + it.sub);
        if (!sup.empty())
            return element("msup", base + sup);
        return base;
    }

    std::vector<std::string> list(stop until)
    {
        std::vector<item> items;
        for (;;) {
            skip_spaces();
            if (at_end()) {
                if (until == stop::brace)
                    fail("a missing }");
                if (until == stop::right)
                    fail("\\left without \\right");
                break;
            }
            const char c = tex_[i_];
            if (c == '}') {
                if (until != stop::brace)
                    fail("an unbalanced }");
                ++i_;
                break;
            }
            if (until == stop::right && looking_at_right())
                break;
            if (c == '_' || c == '^' || c == '\'') {
                if (items.empty())
                    items.push_back({});
                item &last = items.back();
                ++i_;
                if (c == '\'') {
                    if (last.has_caret)
                        fail("a double superscript (a prime after ^)");
                    last.sup.push_back(prime());
                } else if (c == '_') {
                    if (last.has_sub)
                        fail("a double subscript");
                    last.has_sub = true;
                    last.sub = argument("_");
                } else {
                    if (last.has_caret)
                        fail("a double superscript");
                    last.has_caret = true;
                    last.sup.push_back(argument("^"));
                }
                continue;
            }
            std::string a = atom(false);
            // A sign after a relation, an operator or an opening (or first) is
            // a sign of what follows, not a binary operator: = -\int N\,dt.
            if ((a == mo("−") || a == mo("+")) && sign_position(items))
                a = element("mo", a == mo("−") ? "−" : "+", " form=\"prefix\"");
            // |x|: a bar where a sign would be a prefix opens, any other closes
            // (MathML would space a bar inside a row as a binary operator).
            if (a == mo("|", true))
                a = sign_position(items) ? opening_bar : closing_bar;
            if (!a.empty())
                items.push_back({a, "", {}, false, false});
        }
        std::vector<std::string> out;
        for (const item &it : items)
            out.push_back(finish(it));
        return out;
    }

    /// The argument of a command or a script: a braced group, a command, or
    /// one character.
    std::string argument(const std::string &of)
    {
        skip_spaces();
        if (at_end())
            fail("a missing argument of " + of);
        if (tex_[i_] == '{') {
            ++i_;
            return row(list(stop::brace));
        }
        if (tex_[i_] == '}' || tex_[i_] == '_' || tex_[i_] == '^')
            fail("a missing argument of " + of);
        std::string a = atom(true);
        if (a.empty())
            fail("a missing argument of " + of);
        return a;
    }

    /// The raw text of a braced group (for \text), its braces balanced.
    std::string raw_group(const std::string &of)
    {
        skip_spaces();
        if (peek() != '{')
            fail("a missing { after " + of);
        std::size_t start = ++i_;
        for (int depth = 1; !at_end(); ++i_) {
            if (tex_[i_] == '\\') {
                ++i_; // an escaped character never closes the group
                continue;
            }
            if (tex_[i_] == '{')
                ++depth;
            else if (tex_[i_] == '}' && --depth == 0)
                return tex_.substr(start, i_++ - start);
        }
        fail("a missing } after " + of);
    }

    /// Text mode (\text{...}): the escapes names::latex_text writes, read back.
    std::string text_mode(const std::string &raw)
    {
        std::string out;
        for (std::size_t k = 0; k < raw.size();) {
            char c = raw[k];
            if (c == '{' || c == '}') { // grouping only: {} after \textasciitilde
                ++k;
                continue;
            }
            if (c == '$' || c == '^' || c == '_')
                fail(std::string("\"") + c + "\" inside \\text");
            if (c == '~') {
                out += "\u00A0";
                ++k;
                continue;
            }
            if (c != '\\') {
                out += c;
                ++k;
                continue;
            }
            ++k;
            if (k >= raw.size())
                fail("a lone backslash inside \\text");
            if (std::string_view("%_#{}&$ ").find(raw[k]) != std::string_view::npos) {
                out += raw[k++];
                continue;
            }
            std::size_t start = k;
            while (k < raw.size() && is_letter(raw[k]))
                ++k;
            const std::string name = raw.substr(start, k - start);
            if (name == "textasciitilde")
                out += "~";
            else if (name == "textasciicircum")
                out += "^";
            else if (name == "textbackslash")
                out += "\\";
            else
                fail("the unknown control sequence \\" + (name.empty() ? std::string(1, raw[k]) : name) +
                     " inside \\text");
        }
        // MathML trims the spaces at both ends of a token: keep them as no-break spaces.
        std::size_t lead = 0;
        while (lead < out.size() && out[lead] == ' ')
            ++lead;
        std::size_t trail = 0;
        while (trail < out.size() - lead && out[out.size() - 1 - trail] == ' ')
            ++trail;
        std::string nbsp;
        for (std::size_t k = 0; k < lead; ++k)
            nbsp += "\u00A0";
        std::string body = nbsp + out.substr(lead, out.size() - lead - trail);
        for (std::size_t k = 0; k < trail; ++k)
            body += "\u00A0";
        return element("mtext", names::xml_text(body));
    }

    /// The delimiter after \left or \right: its character, "" for none (".").
    std::string delimiter(const std::string &of)
    {
        skip_spaces();
        if (at_end())
            fail("a missing delimiter after " + of);
        char c = tex_[i_];
        if (c == '.') {
            ++i_;
            return "";
        }
        if (std::string_view("()[]|").find(c) != std::string_view::npos) {
            ++i_;
            return std::string(1, c);
        }
        if (c == '\\') {
            std::string name = control_name();
            if (name == "{" || name == "}")
                return name;
            if (name == "|")
                return "‖";
            fail("the unknown delimiter \\" + name + " after " + of);
        }
        fail(std::string("the unknown delimiter \"") + c + "\" after " + of);
    }

    /// One character that is not a letter, digit, brace, backslash or script sign.
    std::string character(std::size_t &k)
    {
        const char c = tex_[k];
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x80) { // a UTF-8 sequence: a letter-like identifier unless it is a known sign
            std::size_t n = 1;
            while (k + n < tex_.size() && (static_cast<unsigned char>(tex_[k + n]) & 0xC0) == 0x80)
                ++n;
            std::string ch = tex_.substr(k, n);
            k += n;
            for (const char *op : {"≤", "≥", "≈", "×", "·", "⋅", "−", "→", "…", "±", "∓", "≠", "′", "∫"})
                if (ch == op)
                    return mo(ch);
            return element("mi", names::xml_text(ch));
        }
        ++k;
        switch (c) {
        case '-':
            return mo("−");
        case '*':
            return mo("∗");
        case '(':
        case ')':
        case '[':
        case ']':
        case '|':
            return mo(std::string(1, c), true);
        case '~':
            return element("mspace", "", " width=\"0.3333em\"");
        case '/':
            return element("mo", "/", " lspace=\"0\" rspace=\"0\""); // a/b: no space, as in TeX
        default:
            if (u < 0x20 || u == 0x7F)
                fail("a control character");
            return mo(std::string(1, c));
        }
    }

    /// One atom. `single`: the argument of a script or a command, where a
    /// number is one digit (x^23 is x^2 3, as in TeX). Returns "" for
    /// nothing to print.
    std::string atom(bool single)
    {
        const char c = tex_[i_];
        if (c == '{') {
            ++i_;
            return row(list(stop::brace));
        }
        if (is_digit(c) || (c == '.' && i_ + 1 < tex_.size() && is_digit(tex_[i_ + 1]) && !single)) {
            std::size_t start = i_++;
            if (!single)
                while (!at_end() &&
                       (is_digit(tex_[i_]) || (tex_[i_] == '.' && i_ + 1 < tex_.size() && is_digit(tex_[i_ + 1]))))
                    ++i_;
            return element("mn", tex_.substr(start, i_ - start));
        }
        if (is_letter(c)) {
            std::size_t start = i_++;
            if (upright_ && !single) {
                while (!at_end() && is_letter(tex_[i_]))
                    ++i_;
                std::string run = tex_.substr(start, i_ - start);
                return element("mi", run, run.size() == 1 ? " mathvariant=\"normal\"" : "");
            }
            return element("mi", std::string(1, c));
        }
        if (c != '\\')
            return character(i_);
        return command(control_name());
    }

    std::string command(const std::string &name)
    {
        for (const command_symbol &s : symbols)
            if (name == s.name)
                return element(s.element, s.text);
        for (const command_symbol &s : upright_symbols)
            if (name == s.name)
                return element(s.element, s.text, " mathvariant=\"normal\"");
        for (const auto &[n, width] : spaces)
            if (name == n)
                return element("mspace", "", std::string(" width=\"") + width + "\"");
        for (const char *f : functions)
            if (name == f) { // \det K: a thin space after the name, none before a parenthesis
                skip_spaces();
                if (at_end() || peek() == '(' || peek() == '[' || tex_.compare(i_, 5, "\\left") == 0)
                    return element("mi", name);
                return element("mrow", element("mi", name) + element("mspace", "", " width=\"0.1667em\""));
            }
        if (name == "colon") // a punctuation colon: f\colon A -> B
            return element("mo", ":", " lspace=\"0\" rspace=\"0.2778em\"");
        if (name.size() == 1 && std::string_view("_#%&${}").find(name[0]) != std::string_view::npos)
            return name == "{" || name == "}" ? mo(name, true) : element("mi", names::xml_text(name));
        if (name == "frac") {
            std::string num = argument("\\frac");
            std::string den = argument("\\frac");
            return element("mfrac", num + den);
        }
        if (name == "sqrt") {
            skip_spaces();
            if (peek() == '[')
                fail("\\sqrt[...] (only square roots are in the subset)");
            return element("msqrt", argument("\\sqrt"));
        }
        // A small circumflex (U+02C6) like TeX's \hat; an overline character
        // (U+203E) stretched under the argument draws \underline.
        if (name == "hat")
            return element("mover", argument("\\hat") + mo("ˆ"), " accent=\"true\"");
        if (name == "underline")
            return element("munder", argument("\\underline") + element("mo", "‾", " stretchy=\"true\""),
                           " accentunder=\"true\"");
        if (name == "text")
            return text_mode(raw_group("\\text"));
        if (name == "mathrm" || name == "operatorname") {
            bool was = upright_;
            upright_ = true;
            std::string a = argument("\\" + name);
            upright_ = was;
            return a;
        }
        if (name == "left") {
            std::string open = delimiter("\\left");
            std::vector<std::string> inside = list(stop::right);
            control_name(); // \right, seen by list()
            std::string close = delimiter("\\right");
            std::string body;
            for (const std::string &e : inside)
                body += e;
            const std::string stretch = tall(body) ? " stretchy=\"true\"" : " stretchy=\"false\"";
            return element("mrow", (open.empty() ? "" : element("mo", open, stretch)) + body +
                                       (close.empty() ? "" : element("mo", close, stretch)));
        }
        if (name == "right")
            fail("\\right without \\left");
        fail("the unknown control sequence \\" + name);
    }
};

} // namespace

std::string tex_to_mathml(const std::string &tex)
{
    return translator(tex).run();
}

} // namespace impactgen::print
