// The solution part of a system's explanation (explain_system.hpp): the candidate sets of
// the law with their conditions -- for a numeric problem, which one holds and the first
// condition each other one fails, as the solver decides it (system_candidate_failure) -- or
// the chain of single-contact impacts (sequential), then the results of solve_system.
#include "canonical.hpp"
#include "explain_detail.hpp"
#include "explain_system.hpp"

#include <exception>
#include <optional>
#include <string>
#include <vector>

namespace impactgen::print::detail
{
using namespace GiNaC;

namespace
{

std::string idx(std::size_t i)
{
    return std::to_string(i);
}

std::string cap(std::string s)
{
    if (!s.empty() && s[0] >= 'a' && s[0] <= 'z')
        s[0] = static_cast<char>(s[0] - 'a' + 'A');
    return s;
}

std::vector<math_row> condition_rows(const system_candidate &c)
{
    std::vector<math_row> rows;
    for (const system_condition &k : c.conditions) {
        const bool fits = printable(k.value);
        math_row r = row(fits ? k.value : ex(0), 0, "", k.words + (k.strict ? ", strictly (> 0)" : ""));
        r.rel = "≥";
        if (!fits)
            r.note.w("; too long to print here");
        rows.push_back(r);
    }
    return rows;
}

section candidates_intro(const derivation &d, std::size_t n)
{
    section s{"The candidate sets", {}};
    s.para(paragraph()
               .t("Each contact is open (no impulse: $P_i = 0$) or acts (smooth; with friction sticking or sliding "
                  "one way or the other; perfectly rough: sticking). One choice per contact is a candidate set: "
                  "its acting contacts' laws make a square linear system in their impulses, $W$ restricted to "
                  "them, solved exactly. A candidate is the answer when its conditions hold: every acting contact "
                  "pushes (and stays inside its friction cone, or slides the way it pushes against), and every "
                  "open contact leaves no slower than $e_i$ times its approach.")
               .w(" " + cap(count_of(n, "candidate", "candidates")) + " for " +
                  count_of(d.prob.contacts.size(), "contact", "contacts") + ":"));
    return s;
}

// A symbolic problem: every candidate with its closed form and its conditions.
// A symbolic candidate's values over one long common denominator, written through a symbol D
// defined once (so that no row carries the long sum twice): the candidate rewritten, and D's
// value, or the candidate as it is and 0 when no denominator is long and shared.
std::pair<system_candidate, ex> over_common_denominator(const problem &p, const system_candidate &c)
{
    for (const symbol &s : p.parameters())
        if (s.get_name() == "D")
            return {c, 0};
    std::vector<ex *> values;
    system_candidate out = c;
    for (ex &v : out.normal_impulse)
        values.push_back(&v);
    for (std::vector<vec3> *vs : {&out.velocity, &out.angular_velocity})
        for (vec3 &v : *vs)
            for (ex &x : v)
                values.push_back(&x);
    for (system_condition &k : out.conditions)
        values.push_back(&k.value);
    ex D = 0;
    std::size_t longest = 40; // characters of the printed denominator worth a name
    for (ex *v : values) {
        const ex den = denom(normal(*v));
        const std::size_t n = canonical_text(den).size();
        if (n > longest)
            longest = n, D = den;
    }
    if (D.is_zero())
        return {c, 0};
    D = normal(D / D.integer_content());
    static const symbol Dsym("D");
    std::size_t shared = 0;
    for (ex *v : values) {
        const ex q = normal(*v), ratio = normal(denom(q) / D);
        if (!is_a<numeric>(ratio))
            continue;
        *v = numer(q) / (ratio * Dsym);
        ++shared;
    }
    return shared >= 2 ? std::pair<system_candidate, ex>{out, D} : std::pair<system_candidate, ex>{c, 0};
}

void symbolic_candidates(section &s, const derivation &d, const std::vector<system_candidate> &cs)
{
    for (const system_candidate &given : cs) {
        s.para(paragraph().w("Candidate " + given.name() + ":"));
        const auto [c, D] = over_common_denominator(d.prob, given);
        if (!D.is_zero())
            s.rows({note_row("D", "D", D, "the candidate's common denominator")});
        system_candidate_values(s, d, c);
        if (c.conditions.empty()) {
            s.para(paragraph().w("It needs no condition."));
            continue;
        }
        s.para(paragraph().w("It holds when:"));
        // a long condition gets its words first, as a line of their own, and its row no note
        // (a note beside a row broken over several lines would widen every line of it)
        std::vector<math_row> rows = condition_rows(c);
        std::vector<math_row> pending;
        for (std::size_t k = 0; k < rows.size(); ++k) {
            if (canonical_text(c.conditions[k].value).size() <= 80) {
                pending.push_back(rows[k]);
                continue;
            }
            if (!pending.empty())
                s.rows(pending), pending.clear();
            s.para(paragraph().w(c.conditions[k].words + (c.conditions[k].strict ? ", strictly:" : ":")));
            rows[k].note = paragraph();
            s.rows({rows[k]});
        }
        if (!pending.empty())
            s.rows(pending);
    }
}

// A numeric problem: each candidate, and the solver's verdict on it.
void numeric_candidates(section &s, const derivation &d, const std::vector<system_candidate> &cs)
{
    std::vector<paragraph> items;
    const system_candidate *first = nullptr;
    std::size_t holding = 0;
    for (const system_candidate &c : cs) {
        const long f = system_candidate_failure(c);
        paragraph q;
        q.w(c.name() + ": ");
        if (f < 0) {
            q.w("holds: every condition is satisfied");
            ++holding;
            if (!first)
                first = &c;
        } else if (static_cast<std::size_t>(f) == c.conditions.size()) {
            q.w("fails: a perfectly rough contact with no normal impulse would need a tangential one");
        } else {
            const system_condition &k = c.conditions[static_cast<std::size_t>(f)];
            q.w("fails: " + k.words + " does not hold, the value is ");
            system_value(q, k.value);
        }
        items.push_back(q);
    }
    s.list(items);
    if (!first)
        return;
    std::string why = "The law holds for " + first->name() + ".";
    if (holding > 1)
        why += " " + cap(count_of(holding, "candidate holds", "candidates hold")) +
               ", all with the same velocities after impact (had they differed, the law would not decide the "
               "outcome): the first is taken, and the impulses are not unique.";
    s.para(paragraph().w(why + " Its solution and conditions:"));
    system_candidate_values(s, d, *first);
    if (!first->conditions.empty())
        s.rows(condition_rows(*first));
}

section chain_section(const derivation &d, const system_answer &a, bool summed_below = true)
{
    section s{"The chain of single-contact impacts", {}};
    s.para(paragraph().w("Sequential impacts: the contacts act one at a time. At each step the first contact in "
                         "list order that approaches acts alone, as a single-contact impact of the whole system "
                         "(joints and pivots included), with the law above for that contact only; the velocities "
                         "after the step are the next step's velocities before."));
    for (std::size_t k = 0; k < a.steps.size(); ++k) {
        const std::size_t i = a.sequence[k];
        const system_candidate &c = a.steps[k];
        s.para(paragraph().w("Step " + idx(k + 1) + ": contact " + idx(i) + " approaches and acts (" +
                             contact_regime_name(c.regimes[i]) + "). Its impulse and the velocities after it:"));
        system_candidate_values(s, d, c);
    }
    s.para(paragraph().w("After step " + idx(a.steps.size()) +
                         " no contact approaches: the impact is over. The contacts acted in the order " +
                         [&] {
                             std::string o;
                             for (std::size_t k = 0; k < a.sequence.size(); ++k)
                                 o += (k ? ", " : "") + idx(a.sequence[k]);
                             return o;
                         }() +
                         (summed_below ? "; each contact's impulse below is summed over its steps." : ".")));
    return s;
}

// A numeric problem with several contacts: the other model of impacts (sequential against
// simultaneous), solved by solve_system, and whether it ends elsewhere; nothing when it is refused.
std::optional<section> other_model_section(const derivation &d, const system_answer &a)
{
    problem other = d.prob;
    if (other.contacts.size() < 2)
        return std::nullopt;
    other.sequential = !a.sequential;
    system_answer b;
    try {
        b = solve_system(other);
    } catch (const std::exception &) {
        return std::nullopt;
    }
    bool differ = false;
    for (std::size_t k = 0; k < a.result.velocity.size(); ++k)
        for (int i = 0; i < 3; ++i)
            differ = differ || !normal(a.result.velocity[k][i] - b.result.velocity[k][i]).is_zero() ||
                     !normal(a.result.angular_velocity[k][i] - b.result.angular_velocity[k][i]).is_zero();
    section s{"The other model of impacts", {}};
    const std::string mine = a.sequential ? "in sequence" : "at the same time";
    const std::string theirs = a.sequential ? "at the same time" : "one at a time, in sequence";
    s.para(paragraph().w("The problem lets its contacts act " + mine + ". Had they acted " + theirs +
                         ", the velocities after impact would be:"));
    std::vector<math_row> rows;
    for (std::size_t k = 0; k < d.prob.bodies.size(); ++k)
        for (int i = 0; i < 3; ++i) {
            if (is_a<symbol>(d.velocity_after[k][i]))
                rows.push_back(system_value_row(d.velocity_after[k][i], b.result.velocity[k][i], ""));
            if (is_a<symbol>(d.angular_velocity_after[k][i]))
                rows.push_back(system_value_row(d.angular_velocity_after[k][i], b.result.angular_velocity[k][i], ""));
        }
    s.rows(rows);
    if (!differ) {
        s.para(
            paragraph().w("They are the same here: the order in which the contacts act does not change the outcome."));
        return s;
    }
    s.para(paragraph().w(
        "They differ. At the same time, the contacts share the impulse through the off-diagonal entries of W: "
        "each contact's impulse changes the others' velocities in the same instant, so a body pressed from two "
        "sides passes on only part of what it receives. In sequence, each contact acts alone on the velocities "
        "the step before it left. Momentum holds in both, and so does energy where every e is 1; but with more "
        "velocities unknown than these balances, they do not fix the outcome: the law of the contacts does. "
        "Both are physics (a row of balls that touch, against one whose contacts are a hair apart); the problem "
        "has to say which it means."));
    if (b.sequential && b.steps.size() > 1) {
        section chain = chain_section(d, b, false);
        s.para(paragraph().w("The chain of the other model, step by step:"));
        for (std::size_t k = 1; k < chain.blocks.size(); ++k)
            s.blocks.push_back(chain.blocks[k]);
    }
    return s;
}

std::string meaning_of(const derivation &d, const ex &sym)
{
    for (const auto &u : d.system_unknowns)
        if (ex(u.first).is_equal(sym))
            return u.second;
    return "";
}

section results_section(const derivation &d, const system_answer &a)
{
    section s{"Results", {}};
    std::vector<math_row> rows;
    const lst values = system_unknown_values(d, a.result);
    for (const ex &r : values)
        rows.push_back(system_value_row(r.lhs(), r.rhs(), meaning_of(d, r.lhs())));
    s.rows(rows);
    std::vector<paragraph> regimes;
    for (std::size_t i = 0; i < a.result.regimes.size(); ++i)
        regimes.push_back(paragraph().w("contact " + idx(i) + ": " + contact_regime_name(a.result.regimes[i])));
    s.para(paragraph().w("The contacts' regimes:"));
    s.list(regimes);
    auto energy = [](const std::string &text, const std::string &tex, const ex &v, const std::string &what) {
        math_row r = note_row(text, tex, v);
        r.note = decimal_note(v);
        r.note.w((r.note.spans.empty() ? "" : ": ") + what);
        return r;
    };
    s.rows({energy("T", "T", a.energy_before, "kinetic energy before impact"),
            energy("T′", "T'", a.energy_after, "kinetic energy after impact"),
            energy("T − T′", "T - T'", a.energy_before - a.energy_after, "kinetic energy lost")});
    if (!a.impulses_unique)
        s.para(paragraph().w("The velocities after impact are unique, the impulses are not (redundant contacts or "
                             "joints): those above are one choice that satisfies the law."));
    if (a.energy_gain)
        s.para(paragraph().w("Kinetic energy is gained although no moving body of infinite mass does work: the "
                             "contacts' different restitution coefficients or their friction allow it under "
                             "Newton's law."));
    return s;
}

// A symbolic system's worked example: its numbers, the verdict on every candidate, the results
// and the other model of impacts, each from the numeric problem the numbers make.
std::vector<section> example_sections(const derivation &d, const worked_example &example)
{
    const problem q = substitute(d.prob, example.values);
    const derivation dq = derive(q);
    section s{"Worked example", {}};
    std::vector<math_row> given;
    for (const ex &v : example.values)
        given.push_back(row(v.lhs(), v.rhs()));
    s.para(paragraph().w("With the numbers"));
    s.rows(given);
    s.para(paragraph().w("each candidate above becomes a number, and its conditions are decided exactly:"));
    numeric_candidates(s, dq, system_candidates(q));
    const system_answer a = solve_system(q);
    std::vector<section> out{s, results_section(dq, a)};
    out.back().title = "Results of the worked example";
    if (std::optional<section> other = other_model_section(dq, a))
        out.push_back(*other);
    return out;
}

} // namespace

std::vector<section> system_solution_sections(const derivation &d, const worked_example *example)
{
    const problem &p = d.prob;
    std::vector<section> out;
    if (!p.is_numeric()) {
        const std::vector<system_candidate> cs = system_candidates(p);
        out.push_back(candidates_intro(d, cs.size()));
        symbolic_candidates(out.back(), d, cs);
        if (example)
            for (section &s : example_sections(d, *example))
                out.push_back(s);
        return out;
    }
    const system_answer a = solve_system(p);
    if (a.sequential) {
        out.push_back(chain_section(d, a));
    } else {
        const std::vector<system_candidate> cs = system_candidates(p);
        out.push_back(candidates_intro(d, cs.size()));
        numeric_candidates(out.back(), d, cs);
    }
    out.push_back(results_section(d, a));
    if (std::optional<section> s = other_model_section(d, a))
        out.push_back(*s);
    return out;
}

} // namespace impactgen::print::detail
