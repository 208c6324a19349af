// Small text helpers shared by the code generator's planning and emitting stages.
#pragma once

#include <string>
#include <vector>

namespace impactgen::codegen
{

/// The items joined by sep ("a, b, c").
inline std::string join(const std::vector<std::string> &items, const std::string &sep)
{
    std::string r;
    for (const std::string &s : items)
        r += (r.empty() ? "" : sep) + s;
    return r;
}

} // namespace impactgen::codegen
