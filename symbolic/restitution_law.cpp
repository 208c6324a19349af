#include "law_reader.hpp"

#include "decide.hpp"
#include "names/escape.hpp"

namespace impactgen
{

const char *law_name(const restitution_law &law)
{
    if (std::holds_alternative<poisson_restitution>(law))
        return "poisson";
    if (std::holds_alternative<energetic_restitution>(law))
        return "energetic";
    return "newton";
}

restitution_law law_from_name(const std::string &name, const std::string &where)
{
    if (name == "newton")
        return newton_restitution{};
    if (name == "poisson")
        return poisson_restitution{};
    if (name == "energetic")
        return energetic_restitution{};
    throw input_error(where + ": unknown law \"" + names::display_text(name, 40) +
                      "\"; expected \"newton\", \"poisson\" or \"energetic\"");
}

const char *phase_name(phase_kind k)
{
    switch (k) {
    case phase_kind::slide:
        return "slide";
    case phase_kind::stick:
        return "stick";
    case phase_kind::reverse:
        return "reverse";
    }
    return "?";
}

namespace
{

// A "friction" value that is not the plain number 0 (a symbolic mu counts as friction).
bool has_friction_key(const json_value &jc)
{
    const json_value *jf = jc.find("friction");
    if (!jf)
        return false;
    if (jf->is_number()) { // the mantissa's digits: 0, 0.0, -0e5 are no friction
        const std::string &t = jf->text();
        return t.substr(0, t.find_first_of("eE")).find_first_of("123456789") != std::string::npos;
    }
    return true;
}

} // namespace

void read_law_of_restitution(const json_value &jc, const std::string &where, contact_spec &c)
{
    const json_value *jl = jc.find("law");
    if (!jl)
        return;
    if (!jl->is_string())
        throw input_error(where + ".law: expected \"newton\", \"poisson\" or \"energetic\", got " +
                          json_value::kind_name(jl->type()));
    c.law_of_restitution = law_from_name(jl->text(), where + ".law");
    if (!follows_process(c.law_of_restitution))
        return;
    if (const json_value *jf = jc.find("friction"))
        if (jf->is_string() && jf->text() == "inf")
            throw input_error(where + ".law: \"" + jl->text() +
                              "\" with \"friction\": \"inf\" is refused: a perfectly rough contact never slips, so "
                              "there is no sliding process to follow (use \"newton\")");
}

void refuse_process_laws_in_systems(const json_value &list)
{
    if (!list.is_array() || list.items().size() < 2)
        return;
    for (std::size_t k = 0; k < list.items().size(); ++k) {
        const json_value &jc = list.items()[k];
        if (!jc.is_object())
            continue;
        const json_value *jl = jc.find("law");
        if (!jl || !jl->is_string() || jl->text() == "newton" || !has_friction_key(jc))
            continue;
        const std::string where = "contacts[" + std::to_string(k) + "].law";
        (void)law_from_name(jl->text(), where); // an unknown name is refused as such
        throw input_error(where + ": \"" + jl->text() + "\" with friction applies to one contact; with " +
                          std::to_string(list.items().size()) +
                          " contacts the process has no closed form (use \"newton\", or no friction)");
    }
}

void check_law_of_restitution(const problem &p)
{
    const bool one = p.contacts.size() == 1;
    for (std::size_t k = 0; k < p.contacts.size(); ++k) {
        const contact_spec &c = p.contacts[k];
        if (!follows_process(c.law_of_restitution) || c.friction().is_zero())
            continue;
        const std::string where = (one ? std::string("contact") : "contacts[" + std::to_string(k) + "]") + ".law";
        const std::string name = law_name(c.law_of_restitution);
        if (!one)
            throw input_error(where + ": \"" + name + "\" with friction applies to one contact; with " +
                              std::to_string(p.contacts.size()) +
                              " contacts the process has no closed form (use \"newton\", or no friction)");
        if (p.dimension == 3)
            throw input_error(where + ": \"" + name +
                              "\" with friction is solved in 2-D only: in 3-D the slip direction turns "
                              "continuously during the impact and the process has no closed form (use \"newton\", "
                              "or no friction)");
    }
}

} // namespace impactgen
