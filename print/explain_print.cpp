// The printers of an explanation document: text, Markdown, LaTeX. Each one
// only decides how a span, a list and a displayed row look; the content is the
// document's, and every expression goes through the canonical printer.
#include "canonical.hpp"
#include "explain.hpp"

#include "names/escape.hpp"

#include <cctype>
#include <sstream>
#include <stdexcept>

namespace impactgen::print {
using namespace GiNaC;

namespace {

constexpr std::size_t width = 100;
// Spaces inside a formula must not break a line: held as this byte while wrapping.
constexpr char hard_space = '\x01';

std::size_t columns(const std::string& s)
{
    std::size_t n = 0;
    for (unsigned char c : s)
        if ((c & 0xC0) != 0x80)
            ++n;
    return n;
}

std::string harden(std::string s)
{
    for (char& c : s)
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
        s = s.substr(0, at) + "\\left|" + s.substr(at + open.size(), k - at - open.size()) + "\\right|" + s.substr(k + 7);
        ++at;
    }
    return s;
}

std::string math_text(const ex& e) { return bars_text(canonical_text(e)); }
std::string math_latex(const ex& e) { return bars_latex(canonical_latex(e)); }

// Greedy wrap at `width` columns; `first` and `rest` are the line prefixes.
std::string wrap(const std::string& text, const std::string& first, const std::string& rest)
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
    for (char& c : out)
        if (c == hard_space)
            c = ' ';
    return out;
}

// ---------------------------------------------------------------- text

std::string text_spans(const paragraph& p)
{
    std::string out;
    for (const span& s : p.spans) {
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

std::string text_row_left(const math_row& r)
{
    return r.lhs_note.text.empty() ? math_text(r.lhs) : r.lhs_note.text;
}

// ---------------------------------------------------------------- LaTeX

// Running text for LaTeX: escapes and the few Unicode signs the notes use.
// Anything else outside ASCII is an error, never silently wrong output.
std::string tex_words(const std::string& s)
{
    static const std::pair<const char*, const char*> map[] = {
        {"≤", "$\\le$"},   {"≥", "$\\ge$"},       {"∫", "$\\int$"},    {"→", "$\\to$"},         {"′", "$'$"},
        {"ω", "$\\omega$"}, {"·", "$\\cdot$"},    {"×", "$\\times$"},  {"∞", "$\\infty$"},      {"≈", "$\\approx$"},
        {"²", "$^2$"},     {"⁻¹", "$^{-1}$"},     {"ε", "$\\varepsilon$"}, {"±", "$\\pm$"},     {"τ", "$\\tau$"},
        {"|", "$|$"},      {"<", "$<$"},          {">", "$>$"},           {"μ", "$\\mu$"},       {"λ", "$\\lambda$"},
        {"θ", "$\\theta$"}, {"≠", "$\\ne$"},    {"√", "$\\surd$"},    {"∓", "$\\mp$"},       {"⁺", "$^+$"},     {"é", "\\'{e}"},
    };
    std::string out;
    for (std::size_t i = 0; i < s.size();) {
        bool done = false;
        for (const auto& [from, to] : map) {
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
        case '_': out += "\\_"; break;
        case '&': out += "\\&"; break;
        case '%': out += "\\%"; break;
        case '#': out += "\\#"; break;
        case '$': out += "\\$"; break;
        case '{': out += "\\{"; break;
        case '}': out += "\\}"; break;
        case '^': out += "\\^{}"; break;
        case '~': out += "\\~{}"; break;
        case '\\': out += "\\textbackslash{}"; break;
        default: out += static_cast<char>(c);
        }
        ++i;
    }
    return out;
}

std::string tex_rel(const std::string& rel)
{
    if (rel == "→")
        return "\\to";
    if (rel == "≤")
        return "\\le";
    if (rel == "≥")
        return "\\ge";
    return rel;
}

std::string tex_spans(const paragraph& p, bool markdown)
{
    std::string out;
    for (const span& s : p.spans) {
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
            out += "$" + math_latex(s.expr) + "$";
        } else if (s.k == span::ref) {
            out += markdown ? "(" + s.text + ")" : "\\eqref{eq:" + s.text + "}";
        } else {
            out += "$" + s.formula.tex + "$";
        }
    }
    return out;
}

std::string tex_row(const math_row& r)
{
    std::string left = r.lhs_note.text.empty() ? math_latex(r.lhs) : r.lhs_note.tex;
    if (!r.rel.empty())
        left += " " + tex_rel(r.rel) + " " + math_latex(r.rhs);
    if (r.has_then)
        left += " = " + math_latex(r.then);
    return left;
}

} // namespace

std::string explain_text(const document& doc)
{
    std::ostringstream os;
    os << doc.title << "\n" << std::string(columns(doc.title), '=') << "\n";
    for (const section& sec : doc.sections) {
        os << "\n" << sec.title << "\n" << std::string(columns(sec.title), '-') << "\n";
        for (const block& b : sec.blocks) {
            switch (b.k) {
            case block::text:
                os << "\n" << wrap(text_spans(b.para), "", "");
                break;
            case block::list:
                os << "\n";
                for (const paragraph& item : b.items)
                    os << wrap(text_spans(item), "  - ", "    ");
                break;
            case block::figure:
                os << "\n" << wrap("[Figure: " + b.art.alt + "]", "", "");
                break;
            case block::rows: {
                os << "\n";
                std::size_t tag_width = 0;
                for (const math_row& r : b.math)
                    tag_width = std::max(tag_width, r.tag.empty() ? std::size_t(0) : columns(r.tag) + 2);
                for (const math_row& r : b.math) {
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
                        os << wrap(harden(line + std::string(22 - columns(line), ' ')) + note, "", std::string(24, ' '));
                    } else {
                        os << line << "\n" << wrap(note, std::string(tag_width + 8, ' '), std::string(tag_width + 8, ' '));
                    }
                }
                break;
            }
            }
        }
    }
    return os.str();
}

std::string explain_markdown(const document& doc)
{
    std::ostringstream os;
    os << "# " << doc.title << "\n";
    for (const section& sec : doc.sections) {
        os << "\n## " << sec.title << "\n";
        for (const block& b : sec.blocks) {
            switch (b.k) {
            case block::text:
                os << "\n" << tex_spans(b.para, true) << "\n";
                break;
            case block::list:
                os << "\n";
                for (const paragraph& item : b.items)
                    os << "- " << tex_spans(item, true) << "\n";
                break;
            case block::figure:
                os << "\n*Figure: " << b.art.alt << "*\n";
                break;
            case block::rows:
                os << "\n";
                for (const math_row& r : b.math) {
                    std::string note = tex_spans(r.note, true);
                    if (r.rel.empty() && r.tag.empty()) {
                        os << "- $" << tex_row(r) << "$" << (note.empty() ? "" : ": " + note) << "\n";
                        continue;
                    }
                    os << "$$" << tex_row(r) << (r.tag.empty() ? "" : " \\tag{" + r.tag + "}") << "$$\n";
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

std::string explain_latex(const document& doc)
{
    std::ostringstream os;
    os << "% Written by impactgen explain. Compile with pdflatex (needs amsmath only).\n"
          "\\documentclass[11pt]{article}\n"
          "\\usepackage[T1]{fontenc}\n"
          "\\usepackage{amsmath}\n"
          "\\setlength{\\parindent}{0pt}\n"
          "\\setlength{\\parskip}{0.5em}\n"
          "\\allowdisplaybreaks\n"
          "\\title{"
       << tex_words(doc.title)
       << "}\n\\date{}\n"
          "\\begin{document}\n\\maketitle\n";
    for (const section& sec : doc.sections) {
        os << "\n\\section*{" << tex_words(sec.title) << "}\n";
        for (const block& b : sec.blocks) {
            switch (b.k) {
            case block::text:
                os << "\n" << tex_spans(b.para, false) << "\n";
                break;
            case block::list:
                os << "\n\\begin{itemize}\n";
                for (const paragraph& item : b.items)
                    os << "  \\item " << tex_spans(item, false) << "\n";
                os << "\\end{itemize}\n";
                break;
            case block::figure:
                os << "\n\\begin{center}\n" << b.art.tikz << "\n\\end{center}\n";
                break;
            case block::rows: {
                bool plain = true;
                for (const math_row& r : b.math)
                    plain = plain && r.rel.empty() && r.tag.empty();
                if (plain) {
                    os << "\n\\begin{itemize}\n";
                    for (const math_row& r : b.math) {
                        std::string note = tex_spans(r.note, false);
                        os << "  \\item $" << tex_row(r) << "$" << (note.empty() ? "" : ": " + note) << "\n";
                    }
                    os << "\\end{itemize}\n";
                    break;
                }
                for (const math_row& r : b.math) {
                    os << "\\begin{equation*}\n  " << tex_row(r);
                    if (!r.tag.empty())
                        os << " \\tag{" << tex_words(r.tag) << "}\\label{eq:" << tex_words(r.tag) << "}";
                    os << "\n\\end{equation*}\n";
                    std::string note = tex_spans(r.note, false);
                    if (!note.empty())
                        os << "{\\small " << note << "}\\par\n";
                }
                break;
            }
            }
        }
    }
    os << "\n\\end{document}\n";
    return os.str();
}

} // namespace impactgen::print
