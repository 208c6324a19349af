// Identifiers for generated C++: the one place that decides which names an
// emitter may declare. Every name that reaches a generated header (function,
// parameter, struct member, namespace part, guard macro) goes through here.
//
// Contract:
//  - is_safe_identifier(s) is the test; mangle() maps any byte string onto a
//    safe identifier (deterministic, pure, not injective);
//  - identifier_scope makes the names of one C++ scope unique, deterministically
//    (same calls in the same order give the same names), and never hands out a
//    name the emitter reserved for itself;
//  - namespace_problem() checks a user-given namespace path, guard_macro()
//    derives a collision-free include-guard macro from one.
// Only ASCII letters, digits and '_' are ever produced; no dependency besides
// the standard library.
#pragma once

#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace impactgen::names
{

/// True for every C++20 keyword and alternative token (and, bitor, not_eq, ...)
/// plus the identifiers with special meaning final, override, import, module.
bool is_keyword(std::string_view s);

/// True for names a generated header must not declare: anything containing
/// "__" or starting with '_' (refused in every scope, for simplicity), and a
/// fixed list of standard macros and names that break code when used as
/// identifiers (NULL, EOF, errno, assert, INFINITY, isnan, unix, major, std,
/// posix, main, the <cmath> constants M_PI, M_E, ..., min, max, ...; the list is
/// in identifier.cpp and is not exhaustive), and every name starting with
/// "IMPACTGEN_" (the generated headers' own macros).
bool is_reserved(std::string_view s);

/// True when s is non-empty, consists of ASCII letters, digits and '_', does
/// not start with a digit, and is neither a keyword nor reserved.
bool is_safe_identifier(std::string_view s);

/// Any byte string in, a safe identifier out: every byte outside [A-Za-z0-9_]
/// becomes '_'; runs of '_' collapse to one; leading and trailing '_' are
/// stripped; an empty result becomes "x"; a result starting with a digit gets
/// the prefix "x_"; a keyword or reserved result gets a trailing '_'
/// ("class" -> "class_", "NULL" -> "NULL_"). NUL and non-ASCII bytes are
/// ordinary "outside" bytes. Not injective ("a b" and "a-b" both give "a_b"):
/// use identifier_scope for uniqueness.
std::string mangle(std::string_view any);

/// Unique safe identifiers within one C++ scope.
class identifier_scope
{
public:
    identifier_scope() = default;

    /// A name the emitter itself uses in this scope ("out", "T", "detail"):
    /// claim() never returns it. Throws std::invalid_argument when s is not
    /// a safe identifier.
    void reserve(const std::string &s);

    /// mangle(wanted); when that is taken (reserved or claimed before), the
    /// first free one of base_2, base_3, ... (a base that already ends in '_',
    /// like "class_", gets class_2, class_3, ..., so no "__" is formed).
    /// Records and returns the name.
    std::string claim(std::string_view wanted);

    /// Like claim(), but returns "" and records nothing when mangle(wanted)
    /// differs from wanted or is taken: for callers that must refuse rather
    /// than rename (user-chosen function names).
    std::string claim_exact(std::string_view wanted);

    /// True when s was reserved or claimed in this scope.
    bool taken(const std::string &s) const;
    /// Every name reserved or claimed so far, sorted.
    std::vector<std::string> names() const { return {taken_.begin(), taken_.end()}; }

private:
    std::set<std::string> taken_;
};

/// Checks a C++ namespace path "a::b::c": non-empty, no empty part (so "",
/// "a::", "::a" and "a::::b" are invalid), and every part a safe identifier
/// ("std", being reserved, is refused in any position; "detail" is fine).
/// Returns "" when valid, else a one-line reason such as
/// `part "int" is a C++ keyword`.
std::string namespace_problem(std::string_view ns);

/// An include-guard style macro for a namespace path, unique per distinct
/// namespace string even when case or separators differ ("Phys" / "phys",
/// "a::b" / "a__b" / "a_b"):
///
///   "IMPACTGEN_" [ + TAG + "_" ] + NS + "_" + HASH
///
/// TAG is uppercase(mangle(prefix_tag)) and is left out when prefix_tag is
/// empty; NS is uppercase(mangle(ns)) (so "::" becomes one '_'); a trailing
/// '_' of TAG or NS (from mangle's keyword suffix) is dropped; HASH is the
/// 64-bit FNV-1a hash of the exact bytes of ns as 16 uppercase hex digits.
/// The hash covers ns only: prefix_tag is meant to be an emitter constant.
/// The result never contains "__" and never starts with '_'.
/// Example: guard_macro("PREAMBLE", "impactgen::generated") ==
/// "IMPACTGEN_PREAMBLE_IMPACTGEN_GENERATED_" + 16 hex digits.
std::string guard_macro(std::string_view prefix_tag, std::string_view ns);

} // namespace impactgen::names
