// The one explanation builder and the hooks a contact law fills in it. Private to the
// print library.
//
// explain(derivation, impact_solution) builds every document the same way
// (explain_document.cpp): the set-up (explain_setup.cpp, with the law's parts), then the
// law's chapter in fixed slots -- its statement, its equations, its candidates' solution,
// the regimes when the solution has more than one candidate, the results -- numbered by
// the builder. A law's chapter is one file (explain_law_frictionless.cpp,
// explain_law_coulomb.cpp) defining one overload of chapter() below; a new alternative of
// contact_law (symbolic/problem.hpp) does not compile until its overload is declared here
// and defined in its own file.
#pragma once

#include "explain.hpp"
#include "explain_detail.hpp"

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impactgen::print::detail
{

/// What a document is built from.
struct explain_input {
    const derivation &d;
    const impact_solution &s;
    /// Values to substitute at the end (a symbolic problem), or null.
    const worked_example *example = nullptr;
    /// A numeric problem taught in symbols first: d and s are its symbolic twin's, these
    /// the problem's own, and `numbers` the twin's symbols with the problem's values.
    const derivation *numeric_d = nullptr;
    const impact_solution *numeric_s = nullptr;
    std::optional<worked_example> numbers;
    /// How much of the derivation the document shows.
    level depth = level::full;
};

/// The law's parts of the set-up section (explain_setup.cpp writes the rest).
struct setup_parts {
    std::string kind;              ///< "A smooth planar (2-D) impact"
    std::vector<paragraph> law;    ///< after Newton's coefficient: the law's own coefficients
    bool world_components = false; ///< the equations in world components (else the contact frame where it helps)
    std::vector<std::pair<GiNaC::ex, paragraph>> impulses; ///< impulses the law makes unknowns: symbol, meaning
    std::optional<paragraph> count_item;                   ///< the impulses' line in the count of unknowns
    std::string count_terms;                               ///< its terms in the sum, " + 1 + 2"
    std::vector<paragraph> closing;                        ///< the set-up's last paragraphs
    bool brief = false;                                    ///< a summary's set-up: the facts without comment
};

/// A contact law's chapter of the document: the sections it writes in each slot.
class law_chapter
{
public:
    virtual ~law_chapter() = default;
    /// The document's title before the problem's name: "Smooth impact".
    virtual std::string title() const = 0;
    /// Whether a numeric problem is taught in symbols first (its twin derived with symbols).
    virtual bool symbols_first() const { return true; }
    virtual setup_parts setup() const = 0;
    /// The law: the impulses it lets act and what it says of them.
    virtual std::vector<section> statement() const = 0;
    virtual std::vector<section> equations() const = 0;
    /// Each candidate's closed form.
    virtual std::vector<section> solution() const = 0;
    /// Which candidate holds when: asked only when the solution has more than one.
    virtual std::vector<section> regimes() const { return {}; }
    /// The checks and the numbers.
    virtual std::vector<section> results() const = 0;
    /// Last touches over the whole document (the symbols as the law's prose writes them).
    virtual void finish(document &) const {}
};

/// The chapters, one per alternative of contact_law (one file each).
std::unique_ptr<law_chapter> chapter(const frictionless &, const explain_input &in);
std::unique_ptr<law_chapter> chapter(const coulomb &, const explain_input &in);
/// Coulomb's chapter under Newton's law of restitution (the process chapter takes its set-up
/// from it; chapter(coulomb) gives the process chapter when the restitution law is followed
/// through the impact).
std::unique_ptr<law_chapter> newton_coulomb_chapter(const explain_input &in);

/// Section 1, the set-up: bodies, contact frame, unknowns and their count, with the law's parts.
section setup_section(const derivation &d, const setup_parts &law);
/// The set-up of a summary: what strikes what, the bodies, the contact frame and the figure.
section setup_summary(const derivation &d, const setup_parts &law);
/// The results of a summary (explain_summary.cpp): every unknown in a box, in closed form
/// in the problem's symbols where it is short, and the problem's or example's numbers.
section summary_results(const explain_input &in);

} // namespace impactgen::print::detail
