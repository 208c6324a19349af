#include "system_input.hpp"

#include "names/escape.hpp"

namespace impactgen
{
using namespace GiNaC;
using namespace detail;

void read_joints(const json_value &root, problem &p)
{
    const json_value *jj = root.find("joints");
    if (!jj)
        return;
    if (!jj->is_array())
        throw input_error(std::string("joints: expected a list, got ") + json_value::kind_name(jj->type()));
    if (jj->items().size() > limits::joints)
        throw input_error("joints: " + std::to_string(jj->items().size()) + " joints; at most " +
                          std::to_string(limits::joints) + " are read");
    for (std::size_t k = 0; k < jj->items().size(); ++k) {
        const json_value &jv = jj->items()[k];
        const std::string where = "joints[" + std::to_string(k) + "]";
        if (!jv.is_object())
            throw input_error(where + ": expected an object, got " + json_value::kind_name(jv.type()));
        for (const auto &m : jv.members())
            if (m.first != "bodies" && m.first != "point")
                p.warnings.push_back(where + "." + names::display_text(m.first) + ": unknown key, ignored");
        const json_value &jb = required(jv, "bodies", where);
        if (!jb.is_array() || jb.items().size() != 2)
            throw input_error(where + ".bodies: expected a list of the two bodies the joint connects");
        joint j;
        j.body1 = body_index_of(p, jb.items()[0], where + ".bodies[0]");
        j.body2 = body_index_of(p, jb.items()[1], where + ".bodies[1]");
        j.point = read_vector(required(jv, "point", where), p.dimension, where + ".point");
        p.joints.push_back(j);
    }
}

namespace
{

std::string name_of(const problem &p, std::size_t b)
{
    return "\"" + names::display_text(p.bodies[b].name) + "\"";
}

void validate_contact(const problem &p, std::size_t k)
{
    const contact_spec &c = p.contacts[k];
    const std::string where = "contacts[" + std::to_string(k) + "]";
    if (c.body1 == c.body2)
        throw input_error(where + ".bodies: repeated body " + name_of(p, c.body1) + " (a body cannot strike itself)");
    if (is_zero_exactly(dot(c.normal, c.normal), where + ".normal", "|n|^2"))
        throw input_error(where + ".normal: the normal must not be zero");
    const ex e = p.restitution_of(k);
    const std::string ew = c.own_restitution ? where + ".restitution" : std::string("restitution");
    if (decided_sign(e, ew, "e") == decision::negative || decided_sign(1 - e, ew, "1 - e") == decision::negative)
        throw input_error(ew + ": e must lie in [0, 1], got " + show_value(e));
    if (decided_sign(c.friction(), where + ".friction", "mu") == decision::negative)
        throw input_error(where + ".friction: the coefficient of friction mu must be >= 0, got " +
                          show_value(c.friction()));
    if (p.immovable(c.body1) && p.immovable(c.body2))
        throw input_error(where + ".bodies: neither " + name_of(p, c.body1) + " nor " + name_of(p, c.body2) +
                          " can move (infinite mass or pinned particle): no impulse can act");
    if (p.dimension == 3 && !c.friction().is_zero() && (p.contacts.size() > 1 || !p.joints.empty()))
        throw input_error(where + ".friction: " +
                          std::string(p.contacts.size() > 1 ? "several contacts" : "a contact in a system of joints") +
                          " with a finite mu > 0 in 3-D are not solved (the sliding directions have no closed form "
                          "together); give 0 (smooth) or \"inf\" (perfectly rough)");
}

void validate_joint(const problem &p, std::size_t k)
{
    const joint &j = p.joints[k];
    const std::string where = "joints[" + std::to_string(k) + "]";
    if (j.body1 == j.body2)
        throw input_error(where + ".bodies: repeated body " + name_of(p, j.body1) +
                          " (a joint connects two different bodies)");
    if (p.bodies[j.body1].infinite_mass && p.bodies[j.body2].infinite_mass)
        throw input_error(where + ".bodies: both " + name_of(p, j.body1) + " and " + name_of(p, j.body2) +
                          " have infinite mass; the joint takes no part in the impact");
    const vec3 gap = point_velocity(p.bodies[j.body2], j.point) - point_velocity(p.bodies[j.body1], j.point);
    for (int i = 0; i < p.dimension; ++i)
        if (!is_zero_exactly(gap[i], where, "the relative velocity at the joint"))
            throw input_error(where + ": the joint comes apart before impact (the velocities of " +
                              name_of(p, j.body1) + " and " + name_of(p, j.body2) + " at its point differ: component " +
                              p.axes[i] + " = " + show_value(tidy(gap[i])) + ")");
}

} // namespace

void validate_system(const problem &p)
{
    for (std::size_t k = 0; k < p.joints.size(); ++k)
        validate_joint(p, k);
    for (std::size_t k = 0; k < p.contacts.size(); ++k)
        validate_contact(p, k);
    // An impact: at least one contact approaches ((v_B - v_A).n < 0), decided for numbers.
    bool approaches = false, unknown = false;
    std::string speeds;
    for (std::size_t k = 0; k < p.contacts.size(); ++k) {
        const contact_spec &c = p.contacts[k];
        const ex u = tidy(
            dot(point_velocity(p.bodies[c.body2], c.point) - point_velocity(p.bodies[c.body1], c.point), c.normal));
        const decision d =
            decided_sign(u, "contacts[" + std::to_string(k) + "]", "the normal velocity of approach (v_B - v_A).n");
        approaches = approaches || d == decision::negative;
        unknown = unknown || d == decision::symbolic;
        if (k < 4)
            speeds += (k ? ", " : "") + show_value(u);
    }
    if (!approaches && !unknown)
        throw input_error("contacts: not an impact: no contact approaches along its normal ((v_B - v_A).n = " + speeds +
                          (p.contacts.size() > 4 ? ", ..." : "") + ", each >= 0)");
}

} // namespace impactgen
