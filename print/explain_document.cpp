// explain(): the one builder of the explanation document, whatever the contact's law.
// The set-up, then the law's chapter (explain_law.hpp) slot by slot: statement,
// equations, solution, the regimes when the solution has more than one candidate, the
// results. The sections are numbered here, in the order they come.
#include "explain.hpp"
#include "explain_law.hpp"
#include "title.hpp"

#include <exception>
#include <variant>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{
using namespace detail;

std::unique_ptr<law_chapter> chapter_of(const explain_input &in)
{
    return std::visit([&](const auto &law) { return chapter(law, in); }, in.d.prob.contact().law);
}

void append(document &doc, std::vector<section> sections)
{
    for (section &s : sections)
        doc.sections.push_back(std::move(s));
}

document build(const explain_input &in, const law_chapter &law)
{
    document doc;
    doc.title = document_title(in.d.prob, law.title());
    doc.description = in.d.prob.description;
    if (in.depth == level::summary) {
        doc.depth = level::summary;
        doc.sections.push_back(setup_summary(in.d, law.setup()));
        doc.sections.push_back(summary_results(in));
        for (std::size_t k = 0; k < doc.sections.size(); ++k)
            doc.sections[k].title = std::to_string(k + 1) + ". " + doc.sections[k].title;
        return doc;
    }
    doc.sections.push_back(setup_section(in.d, law.setup()));
    append(doc, law.statement());
    append(doc, law.equations());
    append(doc, law.solution());
    if (in.s.cases.size() > 1)
        append(doc, law.regimes());
    append(doc, law.results());
    for (std::size_t k = 0; k < doc.sections.size(); ++k)
        doc.sections[k].title = std::to_string(k + 1) + ". " + doc.sections[k].title;
    law.finish(doc);
    return doc;
}

// A numeric problem taught as the notes teach: its symbolized twin (explain_detail.hpp)
// derived as d was, its equations and named steps in symbols first, then the numbers; the
// figure drawn from the numbers. Empty when there is no number to name, or when the twin
// cannot be derived, solved or taught (a decision that needs the numbers).
std::optional<document> taught_in_symbols(const derivation &d, const impact_solution &s, level depth)
{
    lst values;
    std::vector<std::string> units;
    const problem twin = symbolized(d.prob, values, units);
    if (values.nops() == 0)
        return std::nullopt;
    try {
        derive_options opt;
        opt.unit_normal = d.normal_assumed_unit;
        const derivation d2 = derive(twin, opt);
        const impact_solution s2 = solve_impact(d2);
        explain_input in{d2, s2, nullptr, &d, &s, std::nullopt, depth};
        in.numbers = worked_example{"the problem's numbers", values, true, units};
        document doc = build(in, *chapter_of(in));
        for (block &b : doc.sections.front().blocks)
            if (b.k == block::figure)
                b.art = figure_of(d);
        return doc;
    } catch (const std::exception &) {
        return std::nullopt;
    }
}

} // namespace

document explain(const derivation &d, const impact_solution &s, const worked_example *example, level depth)
{
    explain_input in{d, s, example, nullptr, nullptr, std::nullopt, depth};
    const std::unique_ptr<law_chapter> law = chapter_of(in);
    if (d.prob.is_numeric() && !example && law->symbols_first())
        if (std::optional<document> doc = taught_in_symbols(d, s, depth))
            return *doc;
    return build(in, *law);
}

} // namespace impactgen::print
