#include "system_jacobian.hpp"

#include "names/escape.hpp"

#include <algorithm>

namespace impactgen
{
using namespace GiNaC;

namespace
{

std::vector<symbol> inputs_of(const problem &p, const std::vector<std::string> &names)
{
    const std::vector<symbol> all = p.parameters();
    if (all.empty())
        throw input_error("--wrt: the problem has no symbols to differentiate by (its numbers give one impact; "
                          "write the inputs as symbols)");
    if (names.empty())
        return all;
    std::vector<symbol> out;
    for (const std::string &nm : names) {
        auto it = std::find_if(all.begin(), all.end(), [&](const symbol &x) { return x.get_name() == nm; });
        if (it == all.end())
            throw input_error("--wrt: " + names::display_text(nm) + " is not a symbol of the problem");
        if (std::find(out.begin(), out.end(), *it) != out.end())
            throw input_error("--wrt: " + names::display_text(nm) + " is named twice");
        out.push_back(*it);
    }
    return out;
}

std::vector<system_velocity_output> outputs_of(const problem &p)
{
    std::vector<system_velocity_output> out;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        if (p.bodies[b].infinite_mass)
            continue;
        for (int k = 0; k < p.dimension; ++k)
            out.push_back({b, false, k});
        if (p.bodies[b].particle)
            continue;
        for (int k = p.dimension == 2 ? 2 : 0; k < 3; ++k)
            out.push_back({b, true, k});
    }
    return out;
}

} // namespace

system_jacobian system_jacobian_of(const problem &p, const std::vector<std::string> &wrt)
{
    system_jacobian j;
    j.wrt = inputs_of(p, wrt);
    j.outputs = outputs_of(p);
    for (const system_candidate &c : system_candidates(p)) {
        system_set_jacobian s{c, {}};
        for (const system_velocity_output &o : j.outputs) {
            const ex v = (o.angular ? c.angular_velocity : c.velocity)[o.body][static_cast<std::size_t>(o.component)];
            std::vector<ex> row;
            for (const symbol &x : j.wrt)
                row.push_back(normal(v.diff(x)));
            s.entries.push_back(row);
        }
        j.sets.push_back(std::move(s));
    }
    return j;
}

} // namespace impactgen
