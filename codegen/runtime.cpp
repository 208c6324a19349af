#include "runtime.hpp"

#include "names/identifier.hpp"

#include <cstdint>
#include <cstdio>

namespace impactgen::codegen
{

std::string guarded_runtime(const char *prefix, const std::string &ns, const char *text)
{
    const std::string body = std::string(text) + "#endif\n\n";
    std::uint32_t hash = 2166136261u;
    for (unsigned char c : body)
        hash = (hash ^ c) * 16777619u;
    char tag[64];
    std::snprintf(tag, sizeof tag, "%s_%08X", prefix, static_cast<unsigned>(hash));
    const std::string guard = names::guard_macro(tag, ns);
    return "#ifndef " + guard + "\n#define " + guard + "\n" + body;
}

std::string impact_preamble(const std::string &ns)
{
    return "namespace " + ns + " {\n\n" + guarded_runtime("PREAMBLE", ns, impact_runtime);
}

std::string friction_preamble(const std::string &ns)
{
    return guarded_runtime("FRICTION_PREAMBLE", ns, friction_runtime);
}

} // namespace impactgen::codegen
