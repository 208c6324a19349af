// Unit tests of names/: identifiers and escaping for every emitter, with
// hostile input (newlines, preprocessor injection, NUL bytes, comment
// terminators, non-ASCII and invalid UTF-8) and a seeded random property test
// (seed overridable with the environment variable IMPACTGEN_SEED).
#include "names/escape.hpp"
#include "names/identifier.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using namespace impactgen::names;
using namespace std::string_literals;

namespace {

const std::vector<std::string> all_keywords = {
    "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
    "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
    "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
    "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for",
    "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
    "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast",
    "requires", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast", "struct",
    "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid", "typename",
    "union", "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq",
    "final", "override", "import", "module"};

const std::vector<std::string> listed_reserved = {
    "NULL", "EOF", "errno", "assert", "stdin", "stdout", "stderr", "offsetof", "setjmp", "va_arg", "va_start",
    "va_end", "INFINITY", "NAN", "HUGE_VAL", "HUGE_VALF", "HUGE_VALL", "FLT_MAX", "DBL_MAX", "LDBL_MAX",
    "FLT_MIN", "DBL_MIN", "CHAR_BIT", "INT_MAX", "INT_MIN", "UINT_MAX", "LONG_MAX", "LONG_MIN", "SIZE_MAX",
    "EXIT_SUCCESS", "EXIT_FAILURE", "RAND_MAX", "BUFSIZ", "FILENAME_MAX", "FOPEN_MAX", "TMP_MAX", "L_tmpnam",
    "SEEK_SET", "SEEK_CUR", "SEEK_END", "CLOCKS_PER_SEC", "MB_CUR_MAX", "math_errhandling", "FP_NAN",
    "FP_INFINITE", "FP_ZERO", "FP_NORMAL", "FP_SUBNORMAL", "isnan", "isinf", "isfinite", "signbit",
    "fpclassify", "isnormal", "unix", "linux", "i386", "major", "minor", "std", "posix", "main"};

const std::string injection = "ball\n#define private public\n//";
const std::string with_nul = "a\0b"s;
const std::string umlaut = "Kugel-\xC3\xA4";   // "Kugel-ä"
const std::string ball_cjk = "\xE7\x90\x83";   // "球"
const std::string rlo = "\xE2\x80\xAE";        // U+202E RIGHT-TO-LEFT OVERRIDE
const std::vector<std::string> invalid_utf8 = {
    "\xFF",            // never valid
    "\x80",            // stray continuation
    "\xC3",            // truncated 2-byte sequence
    "\xC0\xAF",        // overlong '/'
    "\xE0\x80\xAF",    // overlong '/'
    "\xED\xA0\x80",    // surrogate U+D800
    "\xF4\x90\x80\x80" // beyond U+10FFFF
};

bool has_control_byte(const std::string& s)
{
    for (char c : s) {
        const auto b = static_cast<unsigned char>(c);
        if (b < 0x20 || b == 0x7F)
            return true;
    }
    return false;
}

int hex_value(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

// Inverse of comment_text and display_text escaping: "\xNN" -> byte. Since
// comment_text escapes every backslash, it is exactly reversible.
std::string unescape_hex(const std::string& s)
{
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '\\' && i + 3 < s.size() && s[i + 1] == 'x' && hex_value(s[i + 2]) >= 0 &&
            hex_value(s[i + 3]) >= 0) {
            out += static_cast<char>(hex_value(s[i + 2]) * 16 + hex_value(s[i + 3]));
            i += 3;
        } else {
            out += s[i];
        }
    }
    return out;
}

// A C++ string literal's value as the compiler would read it (only the
// escapes cpp_string_literal produces). Fails the test on anything else.
std::string decode_literal(const std::string& lit)
{
    EXPECT_GE(lit.size(), 2u);
    std::string out;
    for (std::size_t i = 1; i + 1 < lit.size(); ++i) {
        char c = lit[i];
        if (c != '\\') {
            EXPECT_NE(c, '"') << "unescaped quote in " << lit;
            out += c;
            continue;
        }
        char e = lit[++i];
        switch (e) {
        case '\\': out += '\\'; break;
        case '"': out += '"'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case '?': out += '?'; break;
        default:
            EXPECT_TRUE(e >= '0' && e <= '7') << "unexpected escape in " << lit;
            EXPECT_TRUE(lit[i + 1] >= '0' && lit[i + 1] <= '7' && lit[i + 2] >= '0' && lit[i + 2] <= '7');
            out += static_cast<char>((e - '0') * 64 + (lit[i + 1] - '0') * 8 + (lit[i + 2] - '0'));
            i += 2;
        }
    }
    return out;
}

} // namespace

// --- identifiers -------------------------------------------------------------

TEST(Keywords, EveryListedKeywordIsRecognisedAndMangledSafely)
{
    for (const auto& k : all_keywords) {
        SCOPED_TRACE(k);
        EXPECT_TRUE(is_keyword(k));
        EXPECT_FALSE(is_safe_identifier(k));
        EXPECT_TRUE(is_safe_identifier(mangle(k)));
        EXPECT_EQ(mangle(k), k + "_");
    }
}

TEST(Keywords, NearMissesAreNotKeywords)
{
    for (const char* s : {"Class", "classes", "int_", "", "CLASS", "xor_eq_", "co_", "final2", "string", "std_"})
        EXPECT_FALSE(is_keyword(s)) << s;
    EXPECT_FALSE(is_keyword("int\0"s));
}

TEST(Reserved, ListedNamesAndUnderscoreFormsAreReserved)
{
    for (const auto& r : listed_reserved) {
        SCOPED_TRACE(r);
        EXPECT_TRUE(is_reserved(r));
        EXPECT_FALSE(is_safe_identifier(r));
        EXPECT_TRUE(is_safe_identifier(mangle(r)));
    }
    for (const char* r : {"_Foo", "_x", "_", "__", "a__b", "a__", "__init", "x___y"})
        EXPECT_TRUE(is_reserved(r)) << r;
    for (const char* ok : {"a_b", "Null", "null", "errno2", "x", "a_b_c", "STD", "detail", "out"})
        EXPECT_FALSE(is_reserved(ok)) << ok;
}

TEST(SafeIdentifier, AcceptsPlainNamesRejectsEverythingElse)
{
    for (const char* ok : {"ball", "m1", "v_t1", "Ball_2", "x", "detail", "omega"})
        EXPECT_TRUE(is_safe_identifier(ok)) << ok;
    for (const std::string& bad :
         {""s, "9a"s, "1"s, "a b"s, "a-b"s, "a::b"s, umlaut, ball_cjk, with_nul, "a\n"s, injection, "class"s, "NULL"s,
          "_x"s, "a__b"s, "ä"s, "$a"s})
        EXPECT_FALSE(is_safe_identifier(bad)) << display_text(bad);
}

TEST(Mangle, ExamplesFromTheContract)
{
    EXPECT_EQ(mangle("a b"), "a_b");
    EXPECT_EQ(mangle("a-b"), "a_b");
    EXPECT_EQ(mangle("__a__b__"), "a_b");
    EXPECT_EQ(mangle("a___b"), "a_b");
    EXPECT_EQ(mangle(""), "x");
    EXPECT_EQ(mangle("___"), "x");
    EXPECT_EQ(mangle("::"), "x");
    EXPECT_EQ(mangle("9a"), "x_9a");
    EXPECT_EQ(mangle("-9"), "x_9");
    EXPECT_EQ(mangle("class"), "class_");
    EXPECT_EQ(mangle("NULL"), "NULL_");
    EXPECT_EQ(mangle("main"), "main_");
    EXPECT_EQ(mangle("_Foo"), "Foo");
    EXPECT_EQ(mangle("a__b"), "a_b");
    EXPECT_EQ(mangle("ball"), "ball");
    EXPECT_EQ(mangle("std::x"), "std_x");
    EXPECT_EQ(mangle(" class "), "class_");
}

TEST(Mangle, HostileInput)
{
    EXPECT_EQ(mangle(injection), "ball_define_private_public");
    EXPECT_EQ(mangle(with_nul), "a_b");
    EXPECT_EQ(mangle("\0"s), "x");
    EXPECT_EQ(mangle(umlaut), "Kugel");
    EXPECT_EQ(mangle(ball_cjk), "x");
    EXPECT_EQ(mangle("v" + ball_cjk + "2"), "v_2");
    EXPECT_EQ(mangle("*/"), "x");
    for (const auto& bad : invalid_utf8)
        EXPECT_EQ(mangle("m" + bad), "m");
    for (const std::string& s : {injection, with_nul, umlaut, ball_cjk, "*/"s, "1 2 3"s, "\xFF\xFE"s})
        EXPECT_TRUE(is_safe_identifier(mangle(s))) << display_text(s);
}

TEST(Mangle, IsAPureFunctionAndIdempotentOnSafeNames)
{
    EXPECT_EQ(mangle(injection), mangle(injection));
    for (const char* s : {"ball", "m_1", "x_9a", "class_", "NULL_"})
        EXPECT_EQ(mangle(s), s);
}

TEST(Scope, CollisionsAfterManglingGetDistinctNames)
{
    identifier_scope scope;
    const std::string a = scope.claim("a b");
    const std::string b = scope.claim("a-b");
    const std::string c = scope.claim("a__b");
    EXPECT_EQ(a, "a_b");
    EXPECT_EQ(b, "a_b_2");
    EXPECT_EQ(c, "a_b_3");
    EXPECT_TRUE(scope.taken("a_b") && scope.taken("a_b_2") && scope.taken("a_b_3"));
    EXPECT_FALSE(scope.taken("a_b_4"));
}

TEST(Scope, SuffixSkipsNamesClaimedLiterally)
{
    identifier_scope scope;
    EXPECT_EQ(scope.claim("a"), "a");
    EXPECT_EQ(scope.claim("a_2"), "a_2");
    EXPECT_EQ(scope.claim("a"), "a_3");
    EXPECT_EQ(scope.claim("a_2"), "a_2_2");
}

TEST(Scope, ReservedNamesAreNeverReturned)
{
    identifier_scope scope;
    for (const char* r : {"out", "T", "ok", "detail"})
        scope.reserve(r);
    EXPECT_TRUE(scope.taken("out"));
    EXPECT_EQ(scope.claim("out"), "out_2");
    EXPECT_EQ(scope.claim("T"), "T_2");
    EXPECT_EQ(scope.claim(" detail "), "detail_2");
    EXPECT_EQ(scope.claim("NULL"), "NULL_");
    EXPECT_EQ(scope.claim("errno"), "errno_");
    EXPECT_EQ(scope.claim("std"), "std_");
    EXPECT_EQ(scope.claim("_x"), "x");
}

TEST(Scope, KeywordSuffixNeverFormsDoubleUnderscore)
{
    identifier_scope scope;
    EXPECT_EQ(scope.claim("class"), "class_");
    EXPECT_EQ(scope.claim("class"), "class_2");
    EXPECT_EQ(scope.claim("class_"), "class_3");
    std::set<std::string> seen;
    for (int round = 0; round < 3; ++round)
        for (const auto& k : all_keywords) {
            const std::string n = scope.claim(k);
            EXPECT_TRUE(is_safe_identifier(n)) << n;
            EXPECT_EQ(n.find("__"), std::string::npos) << n;
            EXPECT_TRUE(seen.insert(n).second) << "duplicate " << n;
        }
}

TEST(Scope, ReserveRefusesUnsafeNames)
{
    identifier_scope scope;
    for (const std::string& bad : {""s, "class"s, "a b"s, "_x"s, "a__b"s, "NULL"s, "9a"s, with_nul, injection})
        EXPECT_THROW(scope.reserve(bad), std::invalid_argument) << display_text(bad);
    try {
        scope.reserve(injection);
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "message must be one line";
    }
}

TEST(Scope, IsDeterministic)
{
    const std::vector<std::string> wanted = {"a b", "a-b", "class", "class", injection, umlaut, ball_cjk,
                                             ball_cjk, "", "", "9", "NULL", "x", "x_2", "out"};
    auto run = [&] {
        identifier_scope scope;
        scope.reserve("out");
        std::vector<std::string> got;
        for (const auto& w : wanted)
            got.push_back(scope.claim(w));
        return got;
    };
    const auto first = run();
    EXPECT_EQ(first, run());
    std::set<std::string> distinct(first.begin(), first.end());
    EXPECT_EQ(distinct.size(), first.size());
    for (const auto& n : first)
        EXPECT_TRUE(is_safe_identifier(n)) << n;
    EXPECT_EQ(first[0], "a_b");
    EXPECT_EQ(first[1], "a_b_2");
    EXPECT_EQ(first[14], "out_2");
}

TEST(Scope, ClaimExactRefusesInsteadOfRenaming)
{
    identifier_scope scope;
    scope.reserve("out");
    EXPECT_EQ(scope.claim_exact("solve"), "solve");
    EXPECT_TRUE(scope.taken("solve"));
    EXPECT_EQ(scope.claim_exact("solve"), "");
    EXPECT_EQ(scope.claim_exact("out"), "");
    EXPECT_EQ(scope.claim_exact("a b"), "");
    EXPECT_FALSE(scope.taken("a_b")) << "a refused claim records nothing";
    EXPECT_EQ(scope.claim_exact("class"), "");
    EXPECT_FALSE(scope.taken("class_"));
    EXPECT_EQ(scope.claim_exact("NULL"), "");
    EXPECT_EQ(scope.claim_exact("_solve"), "");
    EXPECT_EQ(scope.claim_exact(with_nul), "");
    EXPECT_EQ(scope.claim_exact("solve2"), "solve2");
    EXPECT_EQ(scope.claim("solve"), "solve_2");
}

TEST(Namespace, InvalidPathsAreRefusedWithAOneLineReason)
{
    for (const std::string& bad : {""s, "a::"s, "::a"s, "a::::b"s, "::"s, "int"s, "class"s, "std"s, "std::x"s,
                                   "a::std"s, "9a"s, "a:b"s, "a b"s, "a::int"s, "_a"s, "a__b"s, "main"s, umlaut,
                                   with_nul, injection, "a:::b"s})
    {
        const std::string why = namespace_problem(bad);
        EXPECT_FALSE(why.empty()) << display_text(bad);
        EXPECT_FALSE(has_control_byte(why)) << why;
    }
    EXPECT_EQ(namespace_problem("int"), "part \"int\" is a C++ keyword");
    EXPECT_NE(namespace_problem("a::class").find("\"class\" is a C++ keyword"), std::string::npos);
    EXPECT_NE(namespace_problem("std::x").find("\"std\" is reserved"), std::string::npos);
    EXPECT_NE(namespace_problem("9a").find("not an identifier"), std::string::npos);
    EXPECT_NE(namespace_problem("a::").find("empty part"), std::string::npos);
}

TEST(Namespace, ValidPaths)
{
    for (const char* ok : {"a::b", "Phys", "phys", "impactgen::generated", "a::detail", "a", "a::b::c::d", "x_9"})
        EXPECT_EQ(namespace_problem(ok), "") << ok;
}

TEST(GuardMacro, FormatAndUniqueness)
{
    const std::string g = guard_macro("", "impactgen::generated");
    ASSERT_EQ(g.size(), std::string("IMPACTGEN_IMPACTGEN_GENERATED_").size() + 16);
    EXPECT_EQ(g.rfind("IMPACTGEN_IMPACTGEN_GENERATED_", 0), 0u);
    for (char c : g.substr(g.size() - 16))
        EXPECT_TRUE((c >= '0' && c <= '9') || (c >= 'A' && c <= 'F')) << g;
    EXPECT_EQ(guard_macro("PREAMBLE", "impactgen::generated").rfind("IMPACTGEN_PREAMBLE_IMPACTGEN_GENERATED_", 0),
              0u);
    EXPECT_EQ(g, guard_macro("", "impactgen::generated")) << "deterministic";

    const std::vector<std::string> namespaces = {"Phys", "phys", "PHYS", "a::b", "a__b", "a_b", "a b", "class",
                                                 "class_", "", "std", "9a", injection, with_nul, "a"};
    std::set<std::string> seen;
    for (const auto& ns : namespaces) {
        for (const char* tag : {"", "PREAMBLE", "class"}) {
            const std::string m = guard_macro(tag, ns);
            SCOPED_TRACE(m);
            EXPECT_EQ(m.find("__"), std::string::npos);
            EXPECT_NE(m.front(), '_');
            EXPECT_NE(m.back(), '_');
            EXPECT_EQ(m.rfind("IMPACTGEN_", 0), 0u); // our own macro prefix, reserved for user names
            for (char c : m)
                EXPECT_TRUE((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_');
            EXPECT_TRUE(seen.insert(m).second) << "duplicate guard";
        }
    }
    EXPECT_NE(guard_macro("", "Phys"), guard_macro("", "phys"));
    EXPECT_NE(guard_macro("", "a::b"), guard_macro("", "a__b"));
    EXPECT_NE(guard_macro("", "a::b"), guard_macro("", "a_b"));
    EXPECT_NE(guard_macro("", "a__b"), guard_macro("", "a_b"));
}

// --- escaping ------------------------------------------------------------------

TEST(CommentText, InjectionStaysOnOneLine)
{
    const std::string c = comment_text(injection);
    EXPECT_EQ(c, "ball\\x0a#define private public\\x0a//");
    EXPECT_EQ(c.find('\n'), std::string::npos);
    EXPECT_EQ(comment_text("a\r\nb"), "a\\x0d\\x0ab");
    EXPECT_EQ(comment_text(with_nul), "a\\x00b");
    EXPECT_EQ(comment_text("\t\x7F"), "\\x09\\x7f");
}

TEST(CommentText, CommentTerminatorsTrigraphsAndBackslashes)
{
    EXPECT_EQ(comment_text("*/"), "*\\x2f");
    EXPECT_EQ(comment_text("/*"), "/\\x2a");
    EXPECT_EQ(comment_text("/*/"), "/\\x2a/");
    EXPECT_EQ(comment_text("?" "?="), "?\\x3f=");
    EXPECT_EQ(comment_text("??" "?/"), "?\\x3f?/");
    EXPECT_EQ(comment_text("a\\"), "a\\x5c");
    EXPECT_EQ(comment_text("C:\\dir"), "C:\\x5cdir");
    EXPECT_EQ(comment_text("x*y/z"), "x*y/z");
    for (const std::string& s : {"*/"s, "/*"s, "*/*/"s, "/*/*"s, "**//"s, "??????"s, "?\\?"s, "a\\"s, "\\\\\n"s}) {
        const std::string c = comment_text(s);
        EXPECT_EQ(c.find("*/"), std::string::npos) << c;
        EXPECT_EQ(c.find("/*"), std::string::npos) << c;
        EXPECT_EQ(c.find("??"), std::string::npos) << c;
        EXPECT_NE(c.back(), '\\') << c;
        EXPECT_EQ(unescape_hex(c), s);
    }
}

TEST(CommentText, Utf8KeptInvalidAndBidiEscaped)
{
    EXPECT_EQ(comment_text(umlaut), umlaut);
    EXPECT_EQ(comment_text(ball_cjk), ball_cjk);
    EXPECT_EQ(comment_text("\xF0\x9F\x8E\xB1"), "\xF0\x9F\x8E\xB1"); // U+1F3B1, a 4-byte sequence
    EXPECT_EQ(comment_text("\xFF"), "\\xff");
    EXPECT_EQ(comment_text("\xC3"), "\\xc3");
    EXPECT_EQ(comment_text("\xC3" "a"), "\\xc3a");
    EXPECT_EQ(comment_text("\xC0\xAF"), "\\xc0\\xaf");
    EXPECT_EQ(comment_text("\xED\xA0\x80"), "\\xed\\xa0\\x80");
    EXPECT_EQ(comment_text("\xF4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");
    EXPECT_EQ(comment_text("a" + rlo + "b"), "a\\xe2\\x80\\xaeb");
    EXPECT_EQ(comment_text("\xC2\x85"), "\\xc2\\x85"); // U+0085 NEXT LINE
    EXPECT_EQ(comment_text("\xE2\x80\xA8"), "\\xe2\\x80\\xa8"); // U+2028 LINE SEPARATOR
    for (const auto& bad : invalid_utf8)
        EXPECT_EQ(unescape_hex(comment_text(bad)), bad);
}

TEST(CppStringLiteral, EscapesAndOctal)
{
    EXPECT_EQ(cpp_string_literal(""), "\"\"");
    EXPECT_EQ(cpp_string_literal("ball"), "\"ball\"");
    EXPECT_EQ(cpp_string_literal("a\"b\\c"), "\"a\\\"b\\\\c\"");
    EXPECT_EQ(cpp_string_literal("\n\r\t"), "\"\\n\\r\\t\"");
    EXPECT_EQ(cpp_string_literal("\0"s + "1"), "\"\\0001\"") << "a following digit must not extend the escape";
    EXPECT_EQ(cpp_string_literal("\x01" "7"), "\"\\0017\"");
    EXPECT_EQ(cpp_string_literal("\x7F"), "\"\\177\"");
    EXPECT_EQ(cpp_string_literal("\xFF"), "\"\\377\"");
    EXPECT_EQ(cpp_string_literal("\xC3\xA4"), "\"\\303\\244\"");
    EXPECT_EQ(cpp_string_literal("?" "?="), "\"?\\?=\"");
    EXPECT_EQ(cpp_string_literal("???"), "\"?\\?\\?\"");
    EXPECT_EQ(cpp_string_literal("*/"), "\"*/\"");
    const std::string lit = cpp_string_literal(injection);
    EXPECT_EQ(lit, "\"ball\\n#define private public\\n//\"");
    for (const std::string& s : {injection, with_nul, umlaut, ball_cjk, "\"\\"s, "?" "?/"s, "\xFF\x80"s})
        EXPECT_EQ(decode_literal(cpp_string_literal(s)), s);
}

TEST(LatexText, SpecialCharacters)
{
    EXPECT_EQ(latex_text("#$%&~_^\\{}"),
              "\\#\\$\\%\\&\\textasciitilde{}\\_\\textasciicircum{}\\textbackslash{}\\{\\}");
    EXPECT_EQ(latex_text("v_1"), "v\\_1");
    EXPECT_EQ(latex_text("a\nb\r\tc"), "a b  c");
    EXPECT_EQ(latex_text(with_nul), "a b");
    EXPECT_EQ(latex_text(umlaut), umlaut);
    EXPECT_EQ(latex_text(ball_cjk), ball_cjk);
    EXPECT_EQ(latex_text("\xFF" "a\xC3"), "?a?");
    EXPECT_EQ(latex_text("\\end{document}"), "\\textbackslash{}end\\{document\\}");
    EXPECT_FALSE(has_control_byte(latex_text(injection)));
}

TEST(HtmlText, EntitiesAndDroppedBytes)
{
    EXPECT_EQ(html_text("<script>alert('x')&\"</script>"),
              "&lt;script&gt;alert(&#39;x&#39;)&amp;&quot;&lt;/script&gt;");
    EXPECT_EQ(html_text("a\tb\nc"), "a\tb\nc");
    EXPECT_EQ(html_text("a\rb"), "ab");
    EXPECT_EQ(html_text(with_nul), "ab");
    EXPECT_EQ(html_text("\x7F\x1B[31m"), "[31m");
    EXPECT_EQ(html_text(umlaut), umlaut);
    EXPECT_EQ(html_text(ball_cjk), ball_cjk);
    EXPECT_EQ(html_text("\xFF"), "&#xFFFD;");
    EXPECT_EQ(html_text("\xC0\xAF"), "&#xFFFD;&#xFFFD;");
    EXPECT_EQ(html_text("\xC2\x85x"), "x");
    EXPECT_EQ(html_text("&amp;"), "&amp;amp;");
}

TEST(XmlText, HtmlRulesAndNonCharacters)
{
    // Everything html_text escapes, escaped the same way.
    EXPECT_EQ(xml_text("</svg><script>alert('x')&\"</script>"),
              "&lt;/svg&gt;&lt;script&gt;alert(&#39;x&#39;)&amp;&quot;&lt;/script&gt;");
    EXPECT_EQ(xml_text(with_nul), "ab");
    EXPECT_EQ(xml_text("a\rb\x1B"), "ab");
    EXPECT_EQ(xml_text(umlaut), umlaut);
    EXPECT_EQ(xml_text(ball_cjk), ball_cjk);
    EXPECT_EQ(xml_text("\xFF"), "&#xFFFD;");
    EXPECT_EQ(xml_text("\xC2\x85x"), "x");
    // U+FFFE and U+FFFF are valid UTF-8 but not XML characters.
    EXPECT_EQ(xml_text("a\xEF\xBF\xBE" "b\xEF\xBF\xBF"), "a&#xFFFD;b&#xFFFD;");
    // U+FFFD itself and the last plane's characters are kept.
    EXPECT_EQ(xml_text("\xEF\xBF\xBD"), "\xEF\xBF\xBD");
    EXPECT_EQ(xml_text("\xF4\x8F\xBF\xBD"), "\xF4\x8F\xBF\xBD");
}

TEST(DisplayText, OneLineAndVisibleBytes)
{
    EXPECT_EQ(display_text(injection), "ball\\x0a#define private public\\x0a//");
    EXPECT_EQ(display_text(with_nul), "a\\x00b");
    EXPECT_EQ(display_text("\x1B[2J"), "\\x1b[2J");
    EXPECT_EQ(display_text(umlaut), umlaut);
    EXPECT_EQ(display_text(ball_cjk), ball_cjk);
    EXPECT_EQ(display_text("\xFF" "a"), "\\xffa");
    EXPECT_EQ(display_text("\xC2\x9B" "31m"), "\\xc2\\x9b31m"); // C1 CSI
    EXPECT_EQ(display_text(rlo), "\\xe2\\x80\\xae");
    EXPECT_EQ(display_text("C:\\dir"), "C:\\dir");
}

TEST(DisplayText, Truncation)
{
    EXPECT_EQ(display_text(std::string(200, 'a')), std::string(200, 'a'));
    EXPECT_EQ(display_text(std::string(201, 'a')), std::string(200, 'a') + "...");
    EXPECT_EQ(display_text(std::string(300, 'a'), 10), std::string(10, 'a') + "...");
    EXPECT_EQ(display_text("\xC3\xA4\xC3\xA4\xC3\xA4", 5), "\xC3\xA4\xC3\xA4...") << "no cut inside UTF-8";
    EXPECT_EQ(display_text("\xE7\x90\x83\xE7\x90\x83", 4), "\xE7\x90\x83...");
    EXPECT_EQ(display_text("aaaa\n", 5), "aaaa...") << "no cut inside an escape";
    EXPECT_EQ(display_text("aaaa\n", 8), "aaaa\\x0a");
    EXPECT_EQ(display_text("", 0), "");
    EXPECT_EQ(display_text("a", 0), "...");
}

// --- property test -------------------------------------------------------------

TEST(Property, RandomByteStrings)
{
    unsigned seed = 20240611u;
    if (const char* env = std::getenv("IMPACTGEN_SEED"))
        seed = static_cast<unsigned>(std::strtoul(env, nullptr, 10));
    SCOPED_TRACE("IMPACTGEN_SEED=" + std::to_string(seed));
    std::mt19937 rng(seed);

    // Half of the pieces are random bytes, half are fragments that trip escapers.
    const std::vector<std::string> fragments = {"?", "??", "*", "/", "*/", "/*", "\\", "\n", "\r", "\0"s, "\"",
                                                "_", "__", "::", "class", "NULL", "9", "\xC3", "\xA4", "\xE2\x80\xAE",
                                                "\xE7\x90\x83", "<", "&", "#", "%", " ", "'", "\x7F", "\xFF", "a"};
    std::uniform_int_distribution<int> length(0, 24);
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_int_distribution<int> coin(0, 1);
    std::uniform_int_distribution<std::size_t> pick(0, fragments.size() - 1);

    for (int n = 0; n < 2000; ++n) {
        std::string s;
        for (int k = length(rng); k > 0; --k) {
            if (coin(rng))
                s += static_cast<char>(byte(rng));
            else
                s += fragments[pick(rng)];
        }
        SCOPED_TRACE("input " + display_text(s, 400));

        const std::string m = mangle(s);
        ASSERT_TRUE(is_safe_identifier(m)) << m;
        ASSERT_EQ(mangle(m), m);

        const std::string c = comment_text(s);
        ASSERT_EQ(c.find('\n'), std::string::npos);
        ASSERT_EQ(c.find('\r'), std::string::npos);
        ASSERT_EQ(c.find('\0'), std::string::npos);
        ASSERT_FALSE(has_control_byte(c));
        ASSERT_TRUE(c.empty() || c.back() != '\\');
        ASSERT_EQ(c.find("*/"), std::string::npos);
        ASSERT_EQ(c.find("/*"), std::string::npos);
        ASSERT_EQ(c.find("??"), std::string::npos);
        ASSERT_EQ(unescape_hex(c), s);

        const std::string lit = cpp_string_literal(s);
        ASSERT_GE(lit.size(), 2u);
        ASSERT_EQ(lit.front(), '"');
        ASSERT_EQ(lit.back(), '"');
        for (char ch : lit)
            ASSERT_TRUE(static_cast<unsigned char>(ch) >= 0x20 && static_cast<unsigned char>(ch) < 0x7F);
        ASSERT_EQ(lit.find("??"), std::string::npos);
        ASSERT_EQ(decode_literal(lit), s);

        ASSERT_FALSE(has_control_byte(latex_text(s)));

        const std::string h = html_text(s);
        ASSERT_EQ(h.find('<'), std::string::npos);
        ASSERT_EQ(h.find('>'), std::string::npos);
        ASSERT_EQ(h.find('"'), std::string::npos);
        ASSERT_EQ(h.find('\0'), std::string::npos);
        ASSERT_EQ(h.find('\r'), std::string::npos);

        const std::string d = display_text(s, 30);
        ASSERT_FALSE(has_control_byte(d));
        ASSERT_LE(d.size(), 33u);

        identifier_scope scope;
        const std::string first = scope.claim(s);
        const std::string second = scope.claim(s);
        ASSERT_NE(first, second);
        ASSERT_TRUE(is_safe_identifier(second)) << second;
        ASSERT_EQ(guard_macro("P", s).find("__"), std::string::npos);
    }
}

namespace {

TEST(Reserved, CmathMacrosAndOwnMacros)
{
    using namespace impactgen::names;
    // Found by a hostile review: a symbol M_PI reached a header that includes <cmath>;
    // --name IMPACTGEN_COLD redefined the header's own macro.
    for (const char* s : {"M_PI", "M_E", "M_SQRT2", "MATH_ERRNO", "FP_ILOGB0", "IMPACTGEN_COLD", "IMPACTGEN_HOT", "min", "max"}) {
        EXPECT_TRUE(is_reserved(s)) << s;
        EXPECT_FALSE(is_safe_identifier(s)) << s;
        EXPECT_TRUE(is_safe_identifier(mangle(s))) << s;
        EXPECT_NE(mangle(s), s) << s;
    }
    EXPECT_FALSE(is_reserved("M_ball"));
    EXPECT_FALSE(is_reserved("A"));
}

} // namespace
