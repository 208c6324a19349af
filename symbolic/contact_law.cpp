// The dispatch of contact_law.hpp: each a std::visit over the contact's law, so that a law
// without one of the overloads does not compile.
#include "contact_law.hpp"
#include "derivation.hpp"
#include "friction.hpp"

#include <variant>

namespace impactgen
{

law_traits law_traits_of(const problem &p)
{
    return std::visit([&](const auto &law) { return traits(law, p); }, p.contact().law);
}

void add_law_equations_of(derivation &d)
{
    std::visit([&](const auto &law) { add_law_equations(law, d); }, d.prob.contact().law);
}

impact_solution solve_law_of(const derivation &d)
{
    return std::visit([&](const auto &law) { return solve_law(law, d); }, d.prob.contact().law);
}

} // namespace impactgen
