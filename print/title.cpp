#include "print/title.hpp"

#include <utility>

namespace impactgen::print
{

std::string class_name_in_words(const std::string &name)
{
    // The classes of symbolic/named_classes.cpp, as a teacher would head a sheet about them.
    static const std::pair<const char *, const char *> words[] = {
        {"central-direct", "Direct central impact of two particles"},
        {"central-oblique", "Oblique central impact of two spheres"},
        {"noncentral-3d", "Eccentric impact of two rigid bodies in space"},
        {"massive-3d", "A rigid body strikes a moving body of infinite mass"},
        {"planar", "Eccentric impact of two rigid bodies in the plane"},
        {"pinned-planar", "A ball strikes a hinged rod"},
        {"planar-friction", "Impact of two rigid bodies in the plane with Coulomb friction"},
        {"ball-floor-friction", "A spinning ball bounces on a rough floor"},
        {"noncentral-3d-friction", "Impact of two rigid bodies in space with Coulomb friction"},
        {"rod-rough-floor", "A slender rod falls on a rough floor"},
    };
    for (const auto &[key, text] : words)
        if (name == key)
            return text;
    return "";
}

std::string source_stem(const std::string &source)
{
    std::string s = source;
    const std::size_t slash = s.find_last_of("/\\");
    if (slash != std::string::npos)
        s = s.substr(slash + 1);
    const std::string ext = ".json";
    if (s.size() > ext.size() && s.compare(s.size() - ext.size(), ext.size(), ext) == 0)
        s.resize(s.size() - ext.size());
    return s;
}

std::string document_title(const problem &p, const std::string &kind)
{
    if (!p.title.empty())
        return p.title;
    const std::string words = class_name_in_words(p.source);
    if (!words.empty())
        return words;
    const std::string stem = source_stem(p.source);
    return stem.empty() ? kind : kind + ": " + stem;
}

} // namespace impactgen::print
