// The quantities an exercise asks for, with their exact values and where the answer file
// holds them.
#include "exercises/detail.hpp"
#include "exercises/exercises.hpp"
#include "symbolic/contact_law.hpp"

#include "symbolic/decide.hpp"

namespace impactgen::exercises
{
using namespace GiNaC;

std::string detail::json_pointer_token(const std::string &s)
{
    std::string out;
    for (char c : s)
        out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    return out;
}

namespace
{

struct collector {
    const problem &p;
    const solution &s;
    std::vector<quantity> out;
    void add(const std::string &pointer, const std::string &words, const std::string &unit, const ex &value,
             bool keep_zero)
    {
        const ex v = impactgen::tidy(s.expand_steps(value));
        if (v.is_zero() && !keep_zero)
            return;
        out.push_back({pointer, words, p.units == "SI" ? unit : "", v});
    }
};

} // namespace

std::vector<quantity> asked_quantities(const derivation &d, const regime_case &c)
{
    const problem &p = d.prob;
    const solution &s = c.sol;
    const int dim = p.dimension == 2 ? 2 : 3;
    collector q{p, s, {}};
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body &b = p.bodies[i];
        if (p.immovable(i))
            continue;
        const std::string at = "/bodies/" + detail::json_pointer_token(b.name);
        for (int k = 0; k < dim; ++k) // a component that is 0 before and after is not asked
            q.add(at + "/velocity/" + std::to_string(k),
                  "velocity of " + b.name + " after impact, " + p.axes[k] + " component", "m/s", s.after[i].velocity[k],
                  !b.velocity[k].is_zero());
        if (b.particle)
            continue;
        if (dim == 2)
            q.add(at + "/angular_velocity", "angular velocity of " + b.name + " after impact", "rad/s",
                  s.after[i].angular_velocity[2], !b.angular_velocity[2].is_zero());
        else
            for (int k = 0; k < 3; ++k)
                q.add(at + "/angular_velocity/" + std::to_string(k),
                      "angular velocity of " + b.name + " after impact, " + p.axes[k] + " component", "rad/s",
                      s.after[i].angular_velocity[k], !b.angular_velocity[k].is_zero());
    }
    q.add("/normal_impulse", "normal impulse", "N s", s.normal_impulse, true);
    if (law_traits_of(p).tangential_impulse)
        for (int k = 0; k < dim; ++k)
            q.add("/tangential_impulse/" + std::to_string(k),
                  "friction impulse on " + p.bodies[p.contact().body2].name + ", " + p.axes[k] + " component", "N s",
                  c.tangential_impulse[k], false);
    for (std::size_t j = 0; j < s.pivot_impulses.size(); ++j)
        for (int k = 0; k < dim; ++k)
            q.add("/pivot_impulses/" + std::to_string(j) + "/" + std::to_string(k),
                  "impulse of the pivot on " + p.bodies[p.pivots[j].body].name + ", " + p.axes[k] + " component", "N s",
                  s.pivot_impulses[j][k], false);
    q.add("/kinetic_energy/lost", "kinetic energy lost", "J", s.energy_lost, true);
    return q.out;
}

} // namespace impactgen::exercises
