// The one-page summary of a system (explain --level summary): the set-up with its figure, then
// the results in a box -- the velocities after impact, the impulses and which contacts act.
// A numeric system boxes its answer; a symbolic one with a worked example boxes, in its symbols,
// the candidate that holds for the example's numbers (where its formulas are short), then the
// example's numbers; a symbolic one without an example lists its candidates with their conditions.
#include "canonical.hpp"
#include "explain_detail.hpp"
#include "explain_system.hpp"
#include "title.hpp"

#include <string>
#include <vector>

namespace impactgen::print::detail
{
using namespace GiNaC;

namespace
{

// Short enough for a box on one page: its printed text (the printer's canonical form, so the
// decision does not depend on how GiNaC happens to hold the expression) within this many bytes.
constexpr std::size_t box_bytes = 64;

bool short_value(const ex &x)
{
    return printable(x) && canonical_text(x).size() <= box_bytes;
}

std::string idx(std::size_t i)
{
    return std::to_string(i);
}

// "contact 0 sticks, contact 1 leaves (no impulse)"
paragraph acting(const system_candidate &c)
{
    std::string out;
    for (std::size_t i = 0; i < c.regimes.size(); ++i) {
        const contact_regime r = c.regimes[i];
        out += (i ? "; " : "") + std::string("contact ") + idx(i) + " " +
               (r == contact_regime::open    ? "leaves (no impulse)"
                : r == contact_regime::stick ? "pushes and sticks"
                : r == contact_regime::slide ? "pushes and slides"
                                             : "pushes");
    }
    return paragraph().w("Which contacts act: " + out + ".");
}

// The unknowns of a candidate (velocities after impact, then impulses), each as a row; with
// `short_only`, a row only where the value is short, and `left` counts the others.
std::vector<math_row> value_rows(const derivation &d, const system_candidate &c, bool short_only, std::size_t &left,
                                 paragraph *zeros = nullptr)
{
    std::vector<math_row> rows;
    bool first_zero = true;
    for (const ex &r : system_unknown_values(d, c)) {
        const ex v = r.rhs();
        if (zeros && v.is_zero()) { // listed once, after the box
            zeros->w(first_zero ? "" : ", ").m(r.lhs());
            first_zero = false;
            continue;
        }
        if (short_only && !short_value(v)) {
            ++left;
            continue;
        }
        rows.push_back(short_only ? row(r.lhs(), v) : system_value_row(r.lhs(), v, ""));
    }
    return rows;
}

// The zero values, after a box: "Zero: v′_y,1, P_1."
void zero_line(section &s, const paragraph &zeros)
{
    if (zeros.spans.empty())
        return;
    paragraph q;
    q.w("Zero: ");
    q.spans.insert(q.spans.end(), zeros.spans.begin(), zeros.spans.end());
    s.para(q.w("."));
}

void numeric_results(section &s, const derivation &d, const system_answer &a, bool say_acting = true)
{
    std::size_t left = 0;
    paragraph zeros;
    s.boxed_rows(value_rows(d, a.result, false, left, &zeros));
    zero_line(s, zeros);
    if (say_acting)
        s.para(acting(a.result));
    if (!a.impulses_unique)
        s.para(paragraph().w("The velocities are unique, the impulses are not: those above are one choice."));
    if (a.sequential)
        s.para(paragraph().w("The contacts acted one at a time; each impulse is summed over its steps."));
}

section symbolic_results(const derivation &d, const worked_example *example)
{
    section s{"Results", {}};
    const problem &p = d.prob;
    const std::vector<system_candidate> cs = system_candidates(p);
    if (!example) {
        std::vector<paragraph> items;
        for (const system_candidate &c : cs) {
            std::string when;
            for (const system_condition &k : c.conditions)
                when += (when.empty() ? "" : "; ") + k.words;
            items.push_back(paragraph().w(c.name() + (when.empty() ? "" : ": when " + when)));
        }
        s.para(paragraph().w("The answer is the candidate set whose conditions hold:"));
        s.list(items);
        return s;
    }
    const problem q = substitute(p, example->values);
    const system_answer a = solve_system(q);
    const system_candidate *holds = nullptr;
    for (const system_candidate &c : cs)
        if (!holds && c.regimes == a.result.regimes && c.slide_sign == a.result.slide_sign)
            holds = &c;
    if (holds && !p.sequential) {
        // The formulas in symbols, boxed where every velocity after impact is short.
        bool short_enough = true;
        for (const ex &r : system_unknown_values(d, *holds))
            for (std::size_t b = 0; b < p.bodies.size(); ++b)
                for (int k = 0; k < 3; ++k)
                    if (r.lhs().is_equal(d.velocity_after[b][k]) || r.lhs().is_equal(d.angular_velocity_after[b][k]))
                        short_enough = short_enough && short_value(r.rhs());
        s.para(paragraph().w("Where the conditions of " + holds->name() +
                             " hold (as for the worked example's numbers)" +
                             (short_enough ? ":"
                                           : ", as in the worked example below; in symbols its formulas are long "
                                             "(the full explanation gives them).")));
        std::size_t left = 0;
        paragraph zeros;
        if (short_enough) {
            s.boxed_rows(value_rows(d, *holds, true, left, &zeros));
            zero_line(s, zeros);
        }
        if (left > 0)
            s.para(paragraph().w("(" + count_of(left, "longer formula is", "longer formulas are") +
                                 " in the full explanation.)"));
        s.para(acting(*holds));
    }
    const derivation dq = derive(q);
    section ex{"", {}};
    numeric_results(ex, dq, a, !holds || p.sequential);
    s.para(paragraph().w("Worked example:"));
    std::vector<math_row> given;
    for (const GiNaC::ex &v : example->values)
        given.push_back(row(v.lhs(), v.rhs()));
    s.packed_rows(given);
    for (const block &b : ex.blocks)
        s.blocks.push_back(b);
    return s;
}

} // namespace

document system_summary(const derivation &d, section setup, const worked_example *example)
{
    document doc;
    doc.depth = level::summary;
    doc.title = document_title(d.prob, "System impact");
    doc.description = d.prob.description;
    setup.title = "1. " + setup.title;
    doc.sections.push_back(setup);
    section results{"Results", {}};
    if (d.prob.is_numeric()) {
        numeric_results(results, d, solve_system(d.prob));
    } else {
        results = symbolic_results(d, example);
    }
    results.title = "2. " + results.title;
    doc.sections.push_back(results);
    return doc;
}

} // namespace impactgen::print::detail
