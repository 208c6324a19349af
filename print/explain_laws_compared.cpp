// After the results of a numeric planar problem with friction under Newton's law: why Newton's
// law gains kinetic energy here (when the answer does), and the same problem solved under the
// three laws of restitution side by side -- each solved by the library (derive, solve_impact,
// select_candidate) with only the contact's law changed.
#include "explain_process.hpp"

#include "symbolic/decide.hpp"

#include <array>
#include <cstdio>
#include <exception>
#include <functional>

namespace impactgen::print::detail
{
using namespace GiNaC;

namespace
{

struct law_answer {
    const char *name;
    regime_case c;
};

bool moving_infinite(const problem &p)
{
    for (const body &b : p.bodies)
        if (b.infinite_mass && !b.at_rest())
            return true;
    return false;
}

// x in the candidate's numbers: exact when rational, else a float.
ex value(const regime_case &c, const ex &x)
{
    const ex v = tidy(c.sol.expand_steps(x));
    return is_a<numeric>(v) && ex_to<numeric>(v).is_rational() ? v : v.evalf();
}

// v to six significant digits, as notation (a column of the comparison).
paragraph &digits(paragraph &q, const ex &v)
{
    const ex x = v.evalf();
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.6g", is_a<numeric>(x) ? ex_to<numeric>(x).to_double() : 0.0);
    std::string s = std::string(buf) == "-0" ? "0" : buf;
    return q.n(s, s);
}

// The problem solved under each law, or empty when one of them cannot be solved.
std::vector<law_answer> three_laws(const derivation &nd)
{
    std::vector<law_answer> out;
    const std::array<std::pair<const char *, restitution_law>, 3> laws{
        {{"Newton", newton_restitution{}}, {"Poisson", poisson_restitution{}}, {"energetic", energetic_restitution{}}}};
    try {
        for (const auto &[name, law] : laws) {
            problem p = nd.prob;
            p.contact().law_of_restitution = law;
            derive_options opt;
            opt.unit_normal = nd.normal_assumed_unit;
            const derivation d = derive(p, opt);
            out.push_back({name, select_candidate(d, solve_impact(d))});
        }
    } catch (const std::exception &) {
        return {};
    }
    return out;
}

section gain_section(const derivation &nd, const law_answer &newton, const law_answer &energetic)
{
    const ex before = value(newton.c, newton.c.sol.energy_before), after = value(newton.c, newton.c.sol.energy_after);
    section sec;
    sec.title = "Why Newton's law gains energy here";
    sec.para(
        paragraph().t("Newton's law sets the normal velocity after impact, $u'_n = -e u_n$, and Coulomb's law is "
                      "applied to the impulse as a whole, as if the contact kept one regime through the impact. On "
                      "this contact the response couples the directions ($K_tn ≠ 0$): the friction impulse changes "
                      "the normal velocity, and the normal impulse the slip. When the slip stops or turns during the "
                      "impact, the normal impulse Newton's law needs to reach $u'_n = -e u_n$ is more than the "
                      "contact can give back: the work the impulses do on the bodies is positive."));
    sec.rows({note_row("T", "T", before, "kinetic energy before"), note_row("T'", "T'", after, "after, Newton's law"),
              note_row("T' - T", "T' - T", after - before, "gained")});
    (void)nd;
    sec.para(paragraph()
                 .t("Followed through the impact (Routh's process), restitution measured by work (Stronge's "
                    "energetic coefficient) gives back at most what compression absorbed; here it loses ")
                 .m(value(energetic.c, energetic.c.sol.energy_before - energetic.c.sol.energy_after))
                 .w("."));
    return sec;
}

paragraph quantity_item(const std::string &what, const std::vector<law_answer> &laws,
                        const std::function<void(paragraph &, const regime_case &)> &show)
{
    paragraph q;
    q.w(what + ": ");
    for (std::size_t k = 0; k < laws.size(); ++k) {
        q.w(std::string(k ? "; " : "") + laws[k].name + " ");
        show(q, laws[k].c);
    }
    return q.w(".");
}

section table_section(const derivation &nd, const std::vector<law_answer> &laws)
{
    const problem &p = nd.prob;
    section sec;
    sec.title = "The three laws side by side";
    sec.para(paragraph().t("The same problem solved under each law of restitution (Newton: velocities; Poisson: "
                           "impulses; energetic: work), with the same friction:"));
    std::vector<paragraph> items;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        if (p.bodies[b].infinite_mass)
            continue;
        items.push_back(
            quantity_item("velocity of " + body_ref(p, b) + " after", laws, [&](paragraph &q, const regime_case &c) {
                vec3 v;
                for (int a = 0; a < 3; ++a)
                    v[a] = value(c, c.sol.after[b].velocity[a]);
                digits(q.w("("), v[0]).w(", ");
                digits(q, v[1]).w(")");
            }));
        items.push_back(quantity_item(
            "angular velocity of " + body_ref(p, b) + " after", laws,
            [&](paragraph &q, const regime_case &c) { digits(q, value(c, c.sol.after[b].angular_velocity[2])); }));
    }
    items.push_back(quantity_item("normal impulse", laws, [&](paragraph &q, const regime_case &c) {
        digits(q, value(c, c.sol.normal_impulse));
    }));
    items.push_back(quantity_item("friction impulse", laws, [&](paragraph &q, const regime_case &c) {
        digits(q, value(c, c.tangential_scalar));
    }));
    items.push_back(quantity_item("kinetic energy lost", laws, [&](paragraph &q, const regime_case &c) {
        digits(q, value(c, c.sol.energy_before - c.sol.energy_after));
    }));
    sec.list(items);
    return sec;
}

} // namespace

std::vector<section> laws_compared(const explain_input &in)
{
    const derivation &nd = in.numeric_d ? *in.numeric_d : in.d;
    const problem &p = nd.prob;
    if (!p.is_numeric() || p.dimension != 2 || p.contacts.size() != 1 ||
        follows_process(p.contact().law_of_restitution))
        return {};
    const std::vector<law_answer> laws = three_laws(nd);
    if (laws.size() != 3)
        return {};
    std::vector<section> out;
    const ex gain = value(laws[0].c, laws[0].c.sol.energy_after - laws[0].c.sol.energy_before);
    if (!moving_infinite(p) && decide(gain) == decision::positive)
        out.push_back(gain_section(nd, laws[0], laws[2]));
    out.push_back(table_section(nd, laws));
    return out;
}

} // namespace impactgen::print::detail
