#include "identifier.hpp"

#include "escape.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace impactgen::names
{

namespace
{

bool in_set(const std::set<std::string_view> &set, std::string_view s)
{
    return set.count(s) != 0;
}

const std::set<std::string_view> &keywords()
{
    static const std::set<std::string_view> set = {
        "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
        "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
        "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
        "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for",
        "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
        "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast",
        "requires", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast", "struct", "switch",
        "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid", "typename", "union",
        "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq",
        // identifiers with special meaning
        "final", "override", "import", "module"};
    return set;
}

// Standard macros and names that break code when declared as identifiers.
const std::set<std::string_view> &reserved_names()
{
    static const std::set<std::string_view> set = {
        "NULL", "EOF", "errno", "assert", "stdin", "stdout", "stderr", "offsetof", "setjmp", "va_arg", "va_start",
        "va_end", "INFINITY", "NAN", "HUGE_VAL", "HUGE_VALF", "HUGE_VALL", "FLT_MAX", "DBL_MAX", "LDBL_MAX", "FLT_MIN",
        "DBL_MIN", "CHAR_BIT", "INT_MAX", "INT_MIN", "UINT_MAX", "LONG_MAX", "LONG_MIN", "SIZE_MAX", "EXIT_SUCCESS",
        "EXIT_FAILURE", "RAND_MAX", "BUFSIZ", "FILENAME_MAX", "FOPEN_MAX", "TMP_MAX", "L_tmpnam", "SEEK_SET",
        "SEEK_CUR", "SEEK_END", "CLOCKS_PER_SEC", "MB_CUR_MAX", "math_errhandling", "FP_NAN", "FP_INFINITE", "FP_ZERO",
        "FP_NORMAL", "FP_SUBNORMAL", "isnan", "isinf", "isfinite", "signbit", "fpclassify", "isnormal", "unix", "linux",
        "i386", "major", "minor", "std", "posix", "main",
        // <cmath> / <math.h> macros (POSIX and GNU): a generated header may include <cmath>
        "M_E", "M_LOG2E", "M_LOG10E", "M_LN2", "M_LN10", "M_PI", "M_PI_2", "M_PI_4", "M_1_PI", "M_2_PI", "M_2_SQRTPI",
        "M_SQRT2", "M_SQRT1_2", "MATH_ERRNO", "MATH_ERREXCEPT", "FP_ILOGB0", "FP_ILOGBNAN", "FP_FAST_FMA",
        "FP_FAST_FMAF", "FP_FAST_FMAL", "HUGE", "MAXFLOAT", "FLT_EVAL_METHOD", "DECIMAL_DIG", "FLT_EPSILON",
        "DBL_EPSILON", "LDBL_EPSILON", "LDBL_MIN", "FLT_DIG", "DBL_DIG", "LDBL_DIG", "FLT_MANT_DIG", "DBL_MANT_DIG",
        "LDBL_MANT_DIG", "FLT_RADIX", "NDEBUG", "assert_perror", "min", "max"};
    return set;
}

bool is_ident_byte(unsigned char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

bool is_digit(unsigned char c)
{
    return c >= '0' && c <= '9';
}

char upper(char c)
{
    return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}

std::uint64_t fnv1a64(std::string_view s)
{
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (char c : s) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ULL;
    }
    return h;
}

std::string hex16(std::uint64_t v)
{
    static const char digits[] = "0123456789ABCDEF";
    std::string out(16, '0');
    for (int i = 15; i >= 0; --i) {
        out[static_cast<std::size_t>(i)] = digits[v & 0xF];
        v >>= 4;
    }
    return out;
}

// uppercase(mangle(s)) without a trailing '_'.
std::string macro_part(std::string_view s)
{
    std::string m = mangle(s);
    while (!m.empty() && m.back() == '_')
        m.pop_back();
    std::transform(m.begin(), m.end(), m.begin(), upper);
    return m;
}

} // namespace

bool is_keyword(std::string_view s)
{
    return in_set(keywords(), s);
}

bool is_reserved(std::string_view s)
{
    if (!s.empty() && s.front() == '_')
        return true;
    if (s.find("__") != std::string_view::npos)
        return true;
    if (s.substr(0, 10) == "IMPACTGEN_") // the generated headers' own macros
        return true;
    return in_set(reserved_names(), s);
}

bool is_safe_identifier(std::string_view s)
{
    if (s.empty() || is_digit(static_cast<unsigned char>(s.front())))
        return false;
    for (char c : s)
        if (!is_ident_byte(static_cast<unsigned char>(c)))
            return false;
    return !is_keyword(s) && !is_reserved(s);
}

std::string mangle(std::string_view any)
{
    std::string out;
    out.reserve(any.size() + 3);
    for (char c : any) {
        bool keep = is_ident_byte(static_cast<unsigned char>(c)) && c != '_';
        if (keep)
            out += c;
        else if (!out.empty() && out.back() != '_')
            out += '_'; // collapses runs and drops leading separators
    }
    if (!out.empty() && out.back() == '_')
        out.pop_back();
    if (out.empty())
        out = "x";
    else if (is_digit(static_cast<unsigned char>(out.front())))
        out.insert(0, "x_");
    if (out.rfind("IMPACTGEN_", 0) == 0) // the headers' own macro prefix: a suffix would not help
        out.insert(0, "x_");
    if (is_keyword(out) || is_reserved(out))
        out += '_';
    return out;
}

void identifier_scope::reserve(const std::string &s)
{
    if (!is_safe_identifier(s))
        throw std::invalid_argument("identifier_scope::reserve: \"" + display_text(s) +
                                    "\" is not a safe C++ identifier");
    taken_.insert(s);
}

std::string identifier_scope::claim(std::string_view wanted)
{
    const std::string base = mangle(wanted);
    std::string name = base;
    const std::string stem = base.back() == '_' ? base : base + '_';
    for (unsigned long n = 2; taken_.count(name) || !is_safe_identifier(name); ++n)
        name = stem + std::to_string(n);
    taken_.insert(name);
    return name;
}

std::string identifier_scope::claim_exact(std::string_view wanted)
{
    std::string name = mangle(wanted);
    if (name != wanted || taken_.count(name))
        return "";
    taken_.insert(name);
    return name;
}

bool identifier_scope::taken(const std::string &s) const
{
    return taken_.count(s) != 0;
}

std::string namespace_problem(std::string_view ns)
{
    if (ns.empty())
        return "the namespace is empty";
    std::size_t start = 0;
    for (;;) {
        std::size_t end = ns.find("::", start);
        std::string_view part = ns.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
        if (part.empty())
            return "\"" + display_text(ns) + "\" has an empty part (leading, trailing or doubled \"::\")";
        std::string shown = "part \"" + display_text(part) + "\"";
        if (is_keyword(part))
            return shown + " is a C++ keyword";
        if (is_reserved(part))
            return shown + " is reserved (a standard name or macro, a leading '_' or a \"__\")";
        if (!is_safe_identifier(part))
            return shown + " is not an identifier (ASCII letters, digits and '_', not starting with a digit)";
        if (end == std::string_view::npos)
            return "";
        start = end + 2;
    }
}

std::string guard_macro(std::string_view prefix_tag, std::string_view ns)
{
    std::string out = "IMPACTGEN_";
    if (!prefix_tag.empty())
        out += macro_part(prefix_tag) + "_";
    out += macro_part(ns);
    out += "_";
    out += hex16(fnv1a64(ns));
    return out;
}

} // namespace impactgen::names
