#include "system_process.hpp"

#include "decide.hpp"
#include "routh.hpp"

namespace impactgen
{
using namespace GiNaC;

namespace
{

// A condition of the process in a person's words, for documents (its formula is `meaning`).
std::string words_of(const process_condition &c)
{
    const bool no = c.meaning.rfind("not: ", 0) == 0;
    switch (c.kind) {
    case process_test::initial_slip:
        return no ? "contact 0 slips against its tangent before impact"
                  : "contact 0 slips along its tangent before impact";
    case process_test::sticks_at_start:
        return no ? "starting without slip, contact 0 cannot stick" : "starting without slip, contact 0 sticks";
    case process_test::slip_direction:
        return no ? "starting without slip, contact 0 slips against its tangent"
                  : "starting without slip, contact 0 slips along its tangent";
    case process_test::slip_slows:
        return no ? "the slip of contact 0 does not slow down" : "the slip of contact 0 slows down";
    case process_test::normal_slope:
        return no ? "while contact 0 slides, its approach does not slow down"
                  : "while contact 0 slides, its approach slows down";
    case process_test::compression_first:
        return no ? "the slip of contact 0 stops before it stops approaching"
                  : "contact 0 stops approaching before its slip stops";
    case process_test::sticks:
        return no ? "once its slip stops, contact 0 slips back" : "once its slip stops, contact 0 sticks";
    case process_test::ends_first:
        return no ? "the slip of contact 0 stops before the impact ends"
                  : "the impact ends before the slip of contact 0 stops";
    }
    return c.meaning;
}

// The sign of x for a numeric problem (0 when it has symbols or is zero).
int sign_of(const ex &x)
{
    if (!is_constant(x))
        return 0;
    const decision d = decide(tidy(x));
    return d == decision::positive ? 1 : d == decision::negative ? -1 : 0;
}

} // namespace

bool system_follows_process(const problem &p)
{
    if (p.contacts.size() != 1 || p.dimension != 2)
        return false;
    const contact_spec &c = p.contacts[0];
    return follows_process(c.law_of_restitution) && !c.rough && !c.friction().is_zero();
}

std::vector<system_candidate> system_process_candidates(const problem &p)
{
    const system_delassus D = system_delassus_of(p);
    std::size_t n = 0, t = 1;
    if (D.rows.size() != 2)
        throw std::logic_error("system_process_candidates: expected a normal and a tangent row");
    if (D.rows[0] != "n0")
        std::swap(n, t);
    const contact_spec &c = p.contacts[0];
    const ex L = root_of(tidy(dot(c.normal, c.normal))); // the rows' length: P = L lambda
    const ex qn = D.u[n];
    std::vector<system_candidate> out;
    const system_condition approaches{-qn, true, "u_0 < 0 (contacts[0] approaches)", "contact 0 approaches"};
    const int approach = sign_of(-qn);
    if (approach <= 0) { // open: no impulse (symbols: with its condition)
        system_candidate o = system_candidate_of_impulses(p, {0, 0}, contact_regime::open, 0);
        o.conditions = {{qn, false, "u_0 >= 0 (contacts[0] does not approach)", "contact 0 does not approach"}};
        out.push_back(o);
        if (is_constant(qn))
            return out;
    }
    process_inputs in;
    in.Ktt = D.W[t][t];
    in.Ktn = D.W[t][n];
    in.Knn = D.W[n][n];
    in.ut = D.u[t];
    in.un = qn;
    in.mu = c.friction();
    in.e = p.restitution_of(0);
    in.law = c.law_of_restitution;
    for (const process_sequence &q : routh_process(in, "contacts[0].friction")) {
        if (q.wedges)
            continue;
        std::vector<ex> lambda(2);
        lambda[n] = q.normal_impulse;
        lambda[t] = q.tangential_impulse;
        const bool sticks = q.phases.back().kind == phase_kind::stick;
        system_candidate s =
            system_candidate_of_impulses(p, lambda, sticks ? contact_regime::stick : contact_regime::slide,
                                         sticks ? 0 : sign_of(q.tangential_velocity));
        for (process_phase ph : q.phases) {
            ph.normal_impulse_end = tidy(ph.normal_impulse_end * L);
            s.process.push_back(ph);
        }
        s.conditions.push_back(approaches);
        for (const process_condition &pc : q.conditions)
            s.conditions.push_back({pc.value, pc.strict, pc.meaning + " (contacts[0])", words_of(pc)});
        out.push_back(s);
    }
    return out;
}

} // namespace impactgen
