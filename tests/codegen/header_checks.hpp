// What compile_one.cpp, jacobian_compile.cpp and friction_compile.cpp share: the list of
// generated headers one translation unit checks, a traits struct per header through which
// the checks reach its functions, and the main that runs every check.
//
// Two ways to build such a translation unit:
//  - one header: GEN_HEADER (its quoted path) and GEN_FN (its function's name) defined on
//    the command line; the header is included here (the codegen_compile_<fn> executables);
//  - a family folded into one translation unit: a driver written by
//    tests/codegen/CMakeLists.txt includes every header of the family at global scope,
//    defines IMPACTGEN_CHECKED_HEADERS(X) as X(fn, "path") for each of them, then includes
//    the family's .cpp (the codegen_compile.*, codegen_jacobian_compile.* and
//    codegen_friction_compile.* tests).
// Each family's .cpp defines IMPACTGEN_FAMILY_TRAITS(fn) (the members it needs beyond
// IMPACTGEN_HEADER_TRAITS's) and template <typename H> int check() (0 if the header passes),
// then its main is IMPACTGEN_CHECK_MAIN.
#pragma once

#ifndef IMPACTGEN_CHECKED_HEADERS
#include GEN_HEADER
// Through IMPACTGEN_CHECK_ONE so that GEN_FN is replaced by the name before X pastes it.
#define IMPACTGEN_CHECK_ONE(X, fn, path) X(fn, path)
#define IMPACTGEN_CHECKED_HEADERS(X) IMPACTGEN_CHECK_ONE(X, GEN_FN, GEN_HEADER)
#endif

#include <cstddef>
#include <cstdio>
#include <initializer_list>
#include <utility>

// The struct header_checks::fn: the header's path and counts, its names, result type, and
// fn and fn_to_array forwarded (with their overloads) as call and to_array. Every name is
// qualified: the struct shares its name with the generated function.
#define IMPACTGEN_HEADER_TRAITS(fn, path)                                                                                          \
    namespace header_checks {                                                                                                      \
    struct fn {                                                                                                                    \
        static constexpr const char* header = path;                                                                                \
        static constexpr int input_count = ::impactgen::generated::fn##_input_count;                                               \
        static constexpr int output_count = ::impactgen::generated::fn##_output_count;                                             \
        static constexpr auto& input_names = ::impactgen::generated::fn##_input_names;                                             \
        static constexpr auto& output_names = ::impactgen::generated::fn##_output_names;                                           \
        template <typename T> using result = ::impactgen::generated::fn##_result<T>;                                               \
        template <typename... A> static decltype(auto) call(A&&... a)                                                              \
        {                                                                                                                          \
            return ::impactgen::generated::fn(std::forward<A>(a)...);                                                              \
        }                                                                                                                          \
        template <typename... A> static void to_array(A&&... a)                                                                    \
        {                                                                                                                          \
            ::impactgen::generated::fn##_to_array(std::forward<A>(a)...);                                                          \
        }                                                                                                                          \
        IMPACTGEN_FAMILY_TRAITS(fn)                                                                                                \
    };                                                                                                                             \
    }

// One entry of the list run_header_checks takes.
#define IMPACTGEN_HEADER_CHECK(fn, path) header_check{path, &check<header_checks::fn>},

// Defines the traits of every listed header, and main: every check run, the failed headers named.
#define IMPACTGEN_CHECK_MAIN                                                                                                       \
    IMPACTGEN_CHECKED_HEADERS(IMPACTGEN_HEADER_TRAITS)                                                                             \
    int main() { return run_header_checks({IMPACTGEN_CHECKED_HEADERS(IMPACTGEN_HEADER_CHECK)}); }

struct header_check {
    const char* header;
    int (*check)();
};

// Runs every check (a failure does not stop the others); prints "FAILED: <header>" for each
// header whose check failed (check_compile.cmake collects these lines). 1 if any failed.
inline int run_header_checks(std::initializer_list<header_check> checks)
{
    std::size_t failed = 0;
    for (const header_check& c : checks)
        if (c.check() != 0) {
            ++failed;
            std::printf("FAILED: %s\n", c.header);
        }
    if (failed > 0)
        std::printf("%zu of %zu headers failed\n", failed, checks.size());
    return failed > 0 ? 1 : 0;
}
