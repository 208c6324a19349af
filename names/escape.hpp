// Escaping of arbitrary text (body names, file names, user strings) for every
// place an emitter writes it: C++ comments and string literals, LaTeX, HTML,
// and one-line terminal or error messages. Each function takes any byte
// string (NUL bytes, invalid UTF-8, control characters) and returns text that
// cannot break out of its context.
//
// Shared rules: input is treated as UTF-8; a byte that is not part of a
// well-formed sequence (stray continuation, overlong form, surrogate, beyond
// U+10FFFF, truncated sequence) is "invalid" and handled per function. In the
// two source/terminal contexts (comment_text, display_text) the well-formed
// but invisible or reordering code points C1 controls U+0080-U+009F, U+061C,
// U+200E, U+200F, U+2028, U+2029, U+202A-U+202E and U+2066-U+2069 (bidi
// controls, "Trojan Source") are escaped like control bytes too.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace impactgen::names
{

/// Text safe inside a C++ `//` line comment and on one line, and also safe
/// inside a `/* */` comment: control bytes (< 0x20, including NUL, '\n',
/// '\r', '\t') and 0x7f become "\xNN" (four visible characters, lowercase
/// hex); a backslash becomes "\x5c" (so the text never ends in a backslash
/// and no line splice can occur; doubling it would still end in one); invalid
/// UTF-8 bytes and the code points listed above become "\xNN" per byte;
/// other valid UTF-8 is kept. The output never contains "??" (trigraphs),
/// "*/" or "/*": the second character of such a pair is written "\x3f",
/// "\x2f" or "\x2a".
std::string comment_text(std::string_view s);

/// A C++ narrow string literal including the quotes. \\ \" \n \r \t are
/// escaped as such; other bytes < 0x20, 0x7f and every byte >= 0x80 as a
/// three-digit octal escape \ooo (a following digit can never extend it); a
/// '?' right after a '?' as \? . The output is printable ASCII only.
std::string cpp_string_literal(std::string_view s);

/// LaTeX text mode: # $ % & _ { } become \# \$ \% \& \_ \{ \}; the tilde,
/// caret and backslash become \textasciitilde{} \textasciicircum{} and
/// \textbackslash{}. Control bytes (< 0x20 including newlines, and 0x7f)
/// become a space; valid UTF-8 is kept; an invalid UTF-8 byte becomes '?'.
std::string latex_text(std::string_view s);

/// HTML text or (quoted) attribute value: & < > " ' become &amp; &lt; &gt;
/// &quot; &#39;. Control bytes other than '\t' and '\n' (and 0x7f, and the C1
/// controls U+0080-U+009F) are dropped; each invalid UTF-8 byte becomes
/// "&#xFFFD;"; other valid UTF-8 is kept.
std::string html_text(std::string_view s);

/// XML 1.0 text or (quoted) attribute value, e.g. inside an SVG <title> or
/// <text>: html_text's rules, and in addition the two code points that XML 1.0
/// forbids although they are valid UTF-8, U+FFFE and U+FFFF, become
/// "&#xFFFD;" like an invalid byte (a parser would reject the document).
/// The output is well-formed XML character data for any input.
std::string xml_text(std::string_view s);

/// One line for a terminal or an error message: control bytes (including
/// '\n' and NUL), invalid UTF-8 bytes and the code points listed above are
/// shown as "\xNN" per byte; a backslash is kept as is. When the escaped text
/// is longer than max_bytes it is cut to at most max_bytes bytes, never inside
/// a UTF-8 sequence or an escape, and "..." is appended.
std::string display_text(std::string_view s, std::size_t max_bytes = 200);

} // namespace impactgen::names
