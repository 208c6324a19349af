#include "escape.hpp"

#include <cstdint>

namespace impactgen::names
{

namespace
{

/// One step through the input: a well-formed UTF-8 sequence (valid, len 1-4,
/// its code point cp) or a single byte that is not part of one (!valid, len 1).
struct unit {
    std::size_t len = 1;
    std::uint32_t cp = 0;
    bool valid = false;
};

bool is_continuation(unsigned char b)
{
    return (b & 0xC0) == 0x80;
}

// RFC 3629: no overlong forms, no surrogates, nothing beyond U+10FFFF.
unit next_unit(std::string_view s, std::size_t i)
{
    const auto b0 = static_cast<unsigned char>(s[i]);
    if (b0 < 0x80)
        return {1, b0, true};
    std::size_t len = 0;
    std::uint32_t cp = 0, min = 0;
    if ((b0 & 0xE0) == 0xC0) {
        len = 2, cp = b0 & 0x1Fu, min = 0x80;
    } else if ((b0 & 0xF0) == 0xE0) {
        len = 3, cp = b0 & 0x0Fu, min = 0x800;
    } else if ((b0 & 0xF8) == 0xF0) {
        len = 4, cp = b0 & 0x07u, min = 0x10000;
    } else {
        return {1, b0, false}; // continuation byte or 0xF8..0xFF as a lead
    }
    if (i + len > s.size())
        return {1, b0, false};
    for (std::size_t k = 1; k < len; ++k) {
        const auto b = static_cast<unsigned char>(s[i + k]);
        if (!is_continuation(b))
            return {1, b0, false};
        cp = (cp << 6) | (b & 0x3Fu);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
        return {1, b0, false};
    return {len, cp, true};
}

bool is_control_byte(unsigned char c)
{
    return c < 0x20 || c == 0x7F;
}

// Well-formed code points that are invisible or reorder text: escaped in
// source comments and terminal output.
bool is_hidden(std::uint32_t cp)
{
    return (cp >= 0x80 && cp <= 0x9F) || cp == 0x061C || cp == 0x200E || cp == 0x200F || cp == 0x2028 || cp == 0x2029 ||
           (cp >= 0x202A && cp <= 0x202E) || (cp >= 0x2066 && cp <= 0x2069);
}

void append_hex_escape(std::string &out, unsigned char c)
{
    static const char digits[] = "0123456789abcdef";
    out += "\\x";
    out += digits[c >> 4];
    out += digits[c & 0xF];
}

void append_hex_escapes(std::string &out, std::string_view bytes)
{
    for (char c : bytes)
        append_hex_escape(out, static_cast<unsigned char>(c));
}

// Walks s one unit at a time; `each` appends to out what the unit stands for.
template <typename Each> std::string per_unit(std::string_view s, Each each)
{
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size();) {
        const unit u = next_unit(s, i);
        each(out, u, s.substr(i, u.len));
        i += u.len;
    }
    return out;
}

/// A character and the text that stands for it.
struct replacement {
    char c;
    const char *text;
};

// The text that stands for c in table, or null when c stands for itself.
template <std::size_t N> const char *replaced(const replacement (&table)[N], char c)
{
    for (const replacement &r : table)
        if (r.c == c)
            return r.text;
    return nullptr;
}

const replacement latex_replacements[] = {{'#', "\\#"},
                                          {'$', "\\$"},
                                          {'%', "\\%"},
                                          {'&', "\\&"},
                                          {'_', "\\_"},
                                          {'{', "\\{"},
                                          {'}', "\\}"},
                                          {'~', "\\textasciitilde{}"},
                                          {'^', "\\textasciicircum{}"},
                                          {'\\', "\\textbackslash{}"}};

const replacement html_replacements[] = {
    {'&', "&amp;"}, {'<', "&lt;"}, {'>', "&gt;"}, {'"', "&quot;"}, {'\'', "&#39;"}};

} // namespace

std::string comment_text(std::string_view s)
{
    return per_unit(s, [](std::string &out, const unit &u, std::string_view bytes) {
        if (!u.valid || (u.len > 1 && is_hidden(u.cp))) {
            append_hex_escapes(out, bytes);
            return;
        }
        if (u.len > 1) {
            out += bytes;
            return;
        }
        const auto c = static_cast<unsigned char>(bytes[0]);
        const char prev = out.empty() ? '\0' : out.back();
        const bool pair = (c == '?' && prev == '?') || (c == '/' && prev == '*') || (c == '*' && prev == '/');
        if (is_control_byte(c) || c == '\\' || pair)
            append_hex_escape(out, c);
        else
            out += static_cast<char>(c);
    });
}

std::string cpp_string_literal(std::string_view s)
{
    std::string out = "\"";
    out.reserve(s.size() + 2);
    for (char ch : s) {
        const auto c = static_cast<unsigned char>(ch);
        switch (c) {
        case '\\':
            out += "\\\\";
            break;
        case '"':
            out += "\\\"";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\r':
            out += "\\r";
            break;
        case '\t':
            out += "\\t";
            break;
        case '?':
            out += out.back() == '?' ? "\\?" : "?";
            break;
        default:
            if (c < 0x20 || c >= 0x7F) {
                out += '\\';
                out += static_cast<char>('0' + ((c >> 6) & 7));
                out += static_cast<char>('0' + ((c >> 3) & 7));
                out += static_cast<char>('0' + (c & 7));
            } else {
                out += ch;
            }
        }
    }
    out += '"';
    return out;
}

std::string latex_text(std::string_view s)
{
    return per_unit(s, [](std::string &out, const unit &u, std::string_view bytes) {
        if (!u.valid)
            out += '?';
        else if (u.len > 1)
            out += bytes;
        else if (const char *text = replaced(latex_replacements, bytes[0]))
            out += text;
        else
            out += is_control_byte(static_cast<unsigned char>(bytes[0])) ? ' ' : bytes[0];
    });
}

std::string html_text(std::string_view s)
{
    return per_unit(s, [](std::string &out, const unit &u, std::string_view bytes) {
        if (!u.valid) {
            out += "&#xFFFD;";
        } else if (u.len > 1) {
            if (u.cp > 0x9F) // C1 controls are dropped
                out += bytes;
        } else if (const char *text = replaced(html_replacements, bytes[0])) {
            out += text;
        } else if (bytes[0] == '\t' || bytes[0] == '\n' || !is_control_byte(static_cast<unsigned char>(bytes[0]))) {
            out += bytes[0];
        }
    });
}

std::string xml_text(std::string_view s)
{
    // html_text per code point, except the two non-characters XML 1.0 excludes
    // from its Char production: replaced like an invalid byte.
    return per_unit(s, [](std::string &out, const unit &u, std::string_view bytes) {
        if (u.valid && (u.cp == 0xFFFE || u.cp == 0xFFFF))
            out += "&#xFFFD;";
        else
            out += html_text(bytes);
    });
}

std::string display_text(std::string_view s, std::size_t max_bytes)
{
    std::string out;
    std::string piece;
    for (std::size_t i = 0; i < s.size();) {
        const unit u = next_unit(s, i);
        const std::string_view bytes = s.substr(i, u.len);
        i += u.len;
        piece.clear();
        if (!u.valid || (u.len == 1 && is_control_byte(static_cast<unsigned char>(bytes[0]))) ||
            (u.len > 1 && is_hidden(u.cp)))
            append_hex_escapes(piece, bytes);
        else
            piece = bytes;
        if (out.size() + piece.size() > max_bytes)
            return out + "...";
        out += piece;
    }
    return out;
}

} // namespace impactgen::names
