// A numeric problem written back in the problem format (shared/problem-format.md).
#include "exercises/exercises.hpp"

#include "print/expression.hpp"

#include "exercises/detail.hpp"

#include <cmath>
#include <string>

namespace impactgen::exercises
{
using namespace GiNaC;

namespace
{

/// An exact value as JSON: an integer, a decimal that reads back exactly (at most 15
/// significant digits), else an expression string in GiNaC's syntax ("1/3", "sqrt(2)/2").
nlohmann::ordered_json value_json(const ex &e)
{
    if (is_a<numeric>(e)) {
        const numeric &q = ex_to<numeric>(e);
        if (q.is_integer() && abs(q) < numeric(1000000000))
            return q.to_long();
        if (q.is_rational()) {
            const int places = detail::decimal_places(q);
            // digits before the point + places <= 15: the double's shortest form is exact
            if (places >= 0 && places <= 6 && abs(q) < numeric(1000000))
                return q.to_double();
        }
    }
    return print::parser_syntax(e);
}

nlohmann::ordered_json vector_json(const vec3 &v, int dim)
{
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (int c = 0; c < dim; ++c)
        out.push_back(value_json(v[c]));
    return out;
}

nlohmann::ordered_json body_json(const body &b, int dim)
{
    nlohmann::ordered_json out;
    out["name"] = b.name;
    out["mass"] = b.infinite_mass ? nlohmann::ordered_json("inf") : value_json(b.mass);
    if (!b.particle && !b.infinite_mass) {
        if (dim == 2) {
            out["inertia"] = value_json(b.inertia[2][2]);
        } else {
            nlohmann::ordered_json rows = nlohmann::ordered_json::array();
            for (int r = 0; r < 3; ++r) {
                nlohmann::ordered_json row = nlohmann::ordered_json::array();
                for (int c = 0; c < 3; ++c)
                    row.push_back(value_json(b.inertia[r][c]));
                rows.push_back(row);
            }
            out["inertia"] = rows;
        }
    }
    out["position"] = vector_json(b.position, dim);
    out["velocity"] = vector_json(b.velocity, dim);
    bool spins = false;
    for (const ex &w : b.angular_velocity)
        spins = spins || !w.is_zero();
    if (spins || (!b.particle && !b.infinite_mass))
        out["angular_velocity"] = dim == 2 ? value_json(b.angular_velocity[2]) : vector_json(b.angular_velocity, 3);
    return out;
}

/// One contact: its bodies, point and normal, friction ("inf" for a perfectly rough one), its own
/// restitution (in a list of contacts) and its restitution law when it is not Newton's.
nlohmann::ordered_json contact_json(const problem &p, const contact_spec &c, bool in_list)
{
    const int dim = p.dimension == 2 ? 2 : 3;
    nlohmann::ordered_json contact;
    contact["bodies"] = {p.bodies[c.body1].name, p.bodies[c.body2].name};
    contact["point"] = vector_json(c.point, dim);
    contact["normal"] = vector_json(c.normal, dim);
    if (c.rough)
        contact["friction"] = "inf";
    else if (!c.friction().is_zero())
        contact["friction"] = value_json(c.friction());
    if (in_list && c.own_restitution)
        contact["restitution"] = value_json(c.restitution);
    if (follows_process(c.law_of_restitution))
        contact["law"] = law_name(c.law_of_restitution);
    return contact;
}

} // namespace

nlohmann::ordered_json problem_json(const problem &p)
{
    const int dim = p.dimension == 2 ? 2 : 3;
    nlohmann::ordered_json out;
    if (!p.title.empty())
        out["title"] = p.title;
    if (!p.description.empty())
        out["description"] = p.description;
    out["dimension"] = dim;
    out["restitution"] = value_json(p.restitution);
    if (!p.units.empty())
        out["units"] = p.units;
    nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
    for (const body &b : p.bodies)
        bodies.push_back(body_json(b, dim));
    out["bodies"] = bodies;
    if (p.is_system()) {
        nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
        for (const contact_spec &c : p.contacts)
            contacts.push_back(contact_json(p, c, true));
        out["contacts"] = contacts;
        if (!p.joints.empty()) {
            nlohmann::ordered_json joints = nlohmann::ordered_json::array();
            for (const joint &j : p.joints)
                joints.push_back({{"bodies", {p.bodies[j.body1].name, p.bodies[j.body2].name}},
                                  {"point", vector_json(j.point, dim)}});
            out["joints"] = joints;
        }
        if (p.sequential)
            out["impacts"] = "sequential";
    } else {
        out["contact"] = contact_json(p, p.contact(), false);
    }
    if (!p.pivots.empty()) {
        nlohmann::ordered_json pivots = nlohmann::ordered_json::array();
        for (const pivot &pv : p.pivots)
            pivots.push_back({{"body", p.bodies[pv.body].name}, {"point", vector_json(pv.point, dim)}});
        out["pivots"] = pivots;
    }
    return out;
}

} // namespace impactgen::exercises
