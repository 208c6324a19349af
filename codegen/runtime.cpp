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

const std::set<std::string> &reserved()
{
    static const std::set<std::string> r = {"out",
                                            "fail",
                                            "why",
                                            "T",
                                            "in",
                                            "detail",
                                            "check_sum",
                                            "ok",
                                            "status",
                                            "failed",
                                            "with_energy_lost",
                                            "impact_status",
                                            "op_count",
                                            "to_string",
                                            "finite",
                                            "all_finite",
                                            "min_of",
                                            "max_of",
                                            "abs_of",
                                            "sqrt",
                                            "std",
                                            "i",
                                            "n",
                                            "r",
                                            "a",
                                            "view",
                                            "friction_status",
                                            "impact_regime",
                                            "friction_status_of",
                                            "boundary_tolerance",
                                            "trig2_roots",
                                            "slide_direction",
                                            "constant"};
    return r;
}

} // namespace impactgen::codegen
