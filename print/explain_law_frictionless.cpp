// The document's chapter for a smooth contact (contact_law frictionless): the impulse along
// the normal alone, the notes' equations, one unconditioned candidate solved through named
// steps, and the checks (explain_sections.cpp writes those sections).
#include "explain_law.hpp"
#include "explain_smooth.hpp"

#include "expression.hpp"
#include "symbolic/decide.hpp"

#include <string>
#include <vector>

namespace impactgen::print::detail
{
using namespace GiNaC;

namespace
{

// Central or not: a body whose centre of mass lies on the line of impact feels no moment about C
// (smooth contact only: a friction impulse has a moment about C).
void central_notes(std::vector<paragraph> &out, const derivation &d)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    std::vector<std::size_t> central;
    for (std::size_t i : {i1, i2}) {
        const vec3 r = cross(p.contact().point - p.bodies[i].position, d.n_hat);
        if (p.pivot_of(i) || p.bodies[i].infinite_mass)
            continue;
        // tidy(), not expand(): a point like (a + b + ...)^12 must not be expanded
        if (impactgen::tidy(r[0]).is_zero() && impactgen::tidy(r[1]).is_zero() && impactgen::tidy(r[2]).is_zero())
            central.push_back(i);
    }
    const bool both_particles = central.size() == 2 && p.bodies[i1].particle && p.bodies[i2].particle;
    const bool both_rigid = central.size() == 2 && !p.bodies[i1].particle && !p.bodies[i2].particle;
    if (both_particles)
        out.push_back(paragraph().t(
            "A central impact: both centres of mass lie on the line of impact (through $O$ along $e_n$), so "
            "$~r_CO × e_n = 0$ for each body: the impulse has no moment about $C$, and the spin of a sphere "
            "would be unchanged by it. The bodies are therefore taken as particles, without angular velocity "
            "unknowns."));
    // In 3-D, the example that keeps the spins (its solution is checked by Prose.SpinningSpheres...).
    if (both_particles && dim == 3)
        out.push_back(paragraph().t(
            "Kept as spinning spheres instead (inertia $2 m R²/5$ about every diameter, 12 unknowns), "
            "the same equations find every spin unchanged, $~ω′ = ~ω$, and the same velocities $~v′_C$."));
    else if (both_rigid)
        out.push_back(paragraph().t(
            "A central impact: both centres of mass lie on the line of impact (through $O$ along $e_n$), so "
            "$~r_CO × e_n = 0$ for each body: the impulse has no moment about $C$. The angular momentum "
            "equations below keep the angular velocities as unknowns, and the solution finds each spin "
            "unchanged, $~ω′ = ~ω$: the impact changes only the velocities of the centres along $e_n$."));
    else
        for (std::size_t i : central)
            if (!p.bodies[i].particle)
                out.push_back(paragraph()
                                  .t("The line of impact passes through the centre of mass of ")
                                  .w(body_ref(p, i))
                                  .t(": $~r_CO × e_n = 0$, so the impulse has no moment about its $C$ and its spin is "
                                     "unchanged."));
}

// With a pivot the notes write each body's impulse-momentum with the impulses as unknowns.
paragraph impulse_count(const derivation &d)
{
    const std::string nr = std::to_string(pivot_impulse_count(d));
    return paragraph()
        .w("impulses: 1 + " + nr)
        .t(" -- with a pivot the notes write impulse-momentum for each body separately, so the normal impulse "
           "$∫N dt$ and the ")
        .w(nr)
        .t(" components of the pivot's reaction impulse $~R$ become unknowns too");
}

class frictionless_chapter : public law_chapter
{
    const explain_input &in;
    const impactgen::solution &sol;

public:
    explicit frictionless_chapter(const explain_input &i) : in(i), sol(i.s.cases.front().sol) {}
    std::string title() const override { return "Smooth impact"; }
    setup_parts setup() const override
    {
        const derivation &d = in.d;
        setup_parts law;
        law.kind = std::string("A smooth ") + (d.prob.dimension == 2 ? "planar (2-D)" : "3-D") + " impact";
        if (d.impulse_form) {
            law.count_item = impulse_count(d);
            law.count_terms = " + 1 + " + std::to_string(pivot_impulse_count(d));
        }
        central_notes(law.closing, d);
        return law;
    }
    std::vector<section> statement() const override { return {impulse_section(in.d)}; }
    std::vector<section> equations() const override { return {equations_section(in.d)}; }
    std::vector<section> solution() const override { return {solution_section(in.d, sol)}; }
    std::vector<section> results() const override
    {
        return {checks_section(in.d, sol, in.numbers ? &*in.numbers : in.example)};
    }
};

} // namespace

std::unique_ptr<law_chapter> chapter(const frictionless &, const explain_input &in)
{
    return std::make_unique<frictionless_chapter>(in);
}

} // namespace impactgen::print::detail
