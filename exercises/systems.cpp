// Exercise sheets of systems (format version 3: joints, several contacts, sequential impacts):
// each variant solved by the system's law, what is asked of it, and its statement.
#include "exercises/detail.hpp"

#include "print/answer.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/system.hpp"

namespace impactgen::exercises::detail
{
using namespace GiNaC;

namespace
{

/// The quantities a system's exercise asks for, from its exact answer, with their pointers into
/// the answer object (print::system_answer_json). Impulses that are one valid choice among many
/// (impulses_unique false: a box landing flat on four corners) are not asked.
std::vector<quantity> system_quantities(const problem &p, const system_answer &a)
{
    const bool impulses = a.impulses_unique;
    const int dim = p.dimension == 2 ? 2 : 3;
    const system_candidate &r = a.result;
    std::vector<quantity> out;
    auto add = [&](const std::string &pointer, const std::string &words, const std::string &unit, const ex &value,
                   bool keep_zero) {
        const ex v = impactgen::tidy(value);
        if (v.is_zero() && !keep_zero)
            return;
        out.push_back({pointer, words, p.units == "SI" ? unit : "", v});
    };
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body &b = p.bodies[i];
        if (b.infinite_mass || p.immovable(i))
            continue;
        const std::string at = "/bodies/" + json_pointer_token(b.name);
        for (int k = 0; k < dim; ++k)
            add(at + "/velocity/" + std::to_string(k),
                "velocity of " + b.name + " after impact, " + p.axes[k] + " component", "m/s", r.velocity[i][k],
                !b.velocity[k].is_zero());
        if (b.particle)
            continue;
        if (dim == 2)
            add(at + "/angular_velocity", "angular velocity of " + b.name + " after impact", "rad/s",
                r.angular_velocity[i][2], !b.angular_velocity[2].is_zero());
        else
            for (int k = 0; k < 3; ++k)
                add(at + "/angular_velocity/" + std::to_string(k),
                    "angular velocity of " + b.name + " after impact, " + p.axes[k] + " component", "rad/s",
                    r.angular_velocity[i][k], !b.angular_velocity[k].is_zero());
    }
    for (std::size_t c = 0; impulses && c < p.contacts.size(); ++c) {
        const std::string at = "/contacts/" + std::to_string(c);
        const std::string name = "contact " + std::to_string(c + 1);
        add(at + "/normal_impulse", "normal impulse of " + name, "N s", r.normal_impulse[c], true);
        if (p.contacts[c].rough || !p.contacts[c].friction().is_zero())
            for (int k = 0; k < dim; ++k)
                add(at + "/tangential_impulse/" + std::to_string(k),
                    "friction impulse of " + name + ", " + p.axes[k] + " component", "N s", r.tangential_impulse[c][k],
                    false);
    }
    for (std::size_t j = 0; impulses && j < r.joint_impulses.size(); ++j)
        for (int k = 0; k < dim; ++k)
            add("/joint_impulses/" + std::to_string(j) + "/" + std::to_string(k),
                "impulse of joint " + std::to_string(j + 1) + " on " + p.bodies[p.joints[j].body2].name + ", " +
                    p.axes[k] + " component",
                "N s", r.joint_impulses[j][k], false);
    for (std::size_t j = 0; impulses && j < r.pivot_impulses.size(); ++j)
        for (int k = 0; k < dim; ++k)
            add("/pivot_impulses/" + std::to_string(j) + "/" + std::to_string(k),
                "impulse of the pivot on " + p.bodies[p.pivots[j].body].name + ", " + p.axes[k] + " component", "N s",
                r.pivot_impulses[j][k], false);
    add("/kinetic_energy/lost", "kinetic energy lost", "J", a.energy_before - a.energy_after, true);
    return out;
}

} // namespace

std::optional<outcome> system_outcome(const problem &q)
{
    try {
        validate(q);
        const system_answer a = solve_system(q);
        outcome o;
        o.regime = a.result.name();
        o.key = o.regime + (a.impulses_unique ? "" : " (impulses not unique)");
        if (a.sequential) // a chain: the order in which the contacts acted belongs to its regime
            for (std::size_t c : a.sequence)
                o.key += " " + std::to_string(c);
        o.asked = system_quantities(q, a);
        o.answer = print::system_answer_json(q, a);
        return o;
    } catch (const std::exception &) {
        return std::nullopt; // no candidate holds, two hold, not an impact: another draw
    }
}

std::vector<std::string> system_statement_items(const problem &p, format f, bool si)
{
    const int dim = p.dimension == 2 ? 2 : 3;
    std::vector<std::string> out;
    for (std::size_t j = 0; j < p.joints.size(); ++j) {
        const joint &jt = p.joints[j];
        text t(f);
        t.w("Joint " + std::to_string(j + 1) + ": " + p.bodies[jt.body1].name + " and " + p.bodies[jt.body2].name +
            " are pinned together at ")
            .vec(jt.point, dim)
            .unit(si ? "m" : "")
            .w(dim == 2 ? " (a smooth pin)." : " (a smooth ball joint).");
        out.push_back(t.str());
    }
    for (std::size_t c = 0; c < p.contacts.size(); ++c) {
        const contact_spec &k = p.contacts[c];
        text t(f);
        t.w("Contact " + std::to_string(c + 1) + ": between " + p.bodies[k.body1].name + " and " +
            p.bodies[k.body2].name + " at the point ");
        contact_geometry(t, p, k, "the normal", si).w("; ").sym("e", "e").w(" = ").num(p.restitution_of(c));
        if (k.rough)
            t.w("; perfectly rough (it does not slip)");
        else if (!k.friction().is_zero())
            t.w("; ").sym("\\mu", "μ").w(" = ").num(k.friction());
        else
            t.w("; smooth");
        out.push_back(t.w(".").str());
    }
    out.push_back(text(f)
                      .w(p.sequential ? "The contacts act one at a time: the first in the list that approaches acts "
                                        "alone, until none approaches."
                                      : "The contacts act at the same time.")
                      .str());
    return out;
}

std::string system_find_sentence(const problem &p, format f)
{
    bool spins = false;
    for (std::size_t i = 0; i < p.bodies.size(); ++i)
        spins = spins || (!p.immovable(i) && !p.bodies[i].particle);
    bool friction = false;
    for (const contact_spec &c : p.contacts)
        friction = friction || c.rough || !c.friction().is_zero();
    bool unique = true; // redundant contacts: the velocities are asked, the impulses are not
    try {
        unique = solve_system(p).impulses_unique;
    } catch (const std::exception &) {
    }
    if (!unique)
        return text(f)
            .w(std::string("Find the velocities") + (spins ? " and angular velocities" : "") +
               " after impact and the kinetic energy lost. Are the contacts' impulses determined?")
            .str();
    std::string s = std::string("Find the velocities") + (spins ? " and angular velocities" : "") +
                    " after impact, the normal impulse of each contact (which contacts act?)";
    if (friction)
        s += ", the friction impulses";
    if (!p.joints.empty())
        s += p.joints.size() == 1 ? ", the impulse of the joint" : ", the impulses of the joints";
    if (!p.pivots.empty())
        s += p.pivots.size() == 1 ? ", the impulse of the pivot" : ", the impulses of the pivots";
    s += " and the kinetic energy lost.";
    return text(f).w(s).str();
}

std::string system_regimes_in_words(const exercise &e, format f)
{
    if (!e.answer.value("impulses_unique", true))
        return text(f)
            .w("the velocities are determined, the contacts' impulses are not: the contacts are redundant, and "
               "impulses in many proportions give the same velocities")
            .str();
    std::string s;
    const nlohmann::ordered_json &contacts = e.answer.at("contacts");
    for (std::size_t c = 0; c < contacts.size(); ++c) {
        const std::string regime = contacts[c].at("regime").get<std::string>();
        s += (c ? ", " : "") + std::string("contact ") + std::to_string(c + 1) + " " +
             (regime == "open"    ? "carries no impulse"
              : regime == "stick" ? "acts and sticks"
              : regime == "slide" ? "acts and slides"
                                  : "acts");
    }
    if (e.answer.contains("sequence")) {
        s += "; the contacts acted in the order";
        for (const auto &c : e.answer.at("sequence"))
            s += " " + std::to_string(c.get<std::size_t>() + 1);
    }
    return text(f).w(s).str();
}

print::document worked_solution(const problem &p)
{
    const derivation d = derive(p);
    return p.is_system() ? print::explain_system(d) : print::explain(d, solve_impact(d));
}

} // namespace impactgen::exercises::detail
