// The runtime the generated headers need, written once as C++ in codegen/runtime/ and
// emitted verbatim: impact_runtime.hpp in every header (the hooks, impact_status, view,
// op_count, the detail helpers), friction_runtime.hpp in addition in the headers with
// Coulomb friction (friction_status, impact_regime, the tangent basis, the root finder
// detail::trig2_roots). The build embeds the files' bytes into the library
// (codegen/runtime/embed.cmake writes their definitions); a ctest compiles each file on
// its own (tests/codegen/runtime_compile.cpp).
#pragma once

#include <set>
#include <string>

namespace impactgen::codegen
{

/// The text of codegen/runtime/impact_runtime.hpp, byte for byte.
extern const char *const impact_runtime;
/// The text of codegen/runtime/friction_runtime.hpp, byte for byte.
extern const char *const friction_runtime;

/// A runtime text under its include guard, as a header emits it (inside namespace ns):
/// "#ifndef G\n#define G\n" + text + "#endif\n\n". G is guard_macro(tag, ns) with tag the
/// prefix followed by "_" and the FNV-1a hash (8 hex digits) of the guarded text (text +
/// "#endif\n\n"): headers from an impactgen whose runtime differs do not skip this one
/// (they clash loudly instead).
std::string guarded_runtime(const char *prefix, const std::string &ns, const char *text);

/// What every header writes first after its includes: the opening of its namespace ns and
/// impact_runtime under a guard ("PREAMBLE"). The smooth and the friction writers both
/// write it, so that headers of both kinds share one copy in a namespace.
std::string impact_preamble(const std::string &ns);

/// What a header with friction writes after impact_preamble: friction_runtime under a
/// guard of its own ("FRICTION_PREAMBLE").
std::string friction_preamble(const std::string &ns);

/// The names the emitted code and the runtime use in a header's functions and namespace
/// (never handed to an input, a step or a local; keywords and reserved C++ names never come
/// out of names::mangle): one list for the smooth and the friction writer.
const std::set<std::string> &reserved();

} // namespace impactgen::codegen
