// The document's chapter for Coulomb friction (contact_law coulomb): the contact law, the
// impulse-momentum equations with the friction impulse, the contact response K, stick tested
// against the cone, then the slides; the regimes as conditions on mu, existence and
// uniqueness; for a numeric problem every number and the regime that holds (sections in
// explain_friction.cpp and explain_friction_numbers.cpp). Coulomb's coefficient and the
// sliding speed are written mu and lambda where no other symbol prints so.
#include "explain_friction_detail.hpp"
#include "explain_law.hpp"
#include "explain_process.hpp"

#include "canonical.hpp"

#include <algorithm>

namespace impactgen::print::friction_detail
{
namespace
{

// How the document writes Coulomb's coefficient and the sliding speed: as the prose does,
// μ and λ.
const symbol mu_shown("μ", "\\mu"), lambda_shown("λ", "\\lambda");

// Whether x prints as `shown` does, in text or in TeX (a problem's symbol mu is \mu in TeX).
bool prints_as(const ex &x, const symbol &shown)
{
    return canonical_text(x) == canonical_text(shown) || canonical_latex(x) == canonical_latex(shown);
}

// Whether a symbol of the problem, or an unknown, other than `self` prints as `shown`
// does: then writing `self` so would make two symbols look alike.
bool shown_elsewhere(const derivation &d, const ex &self, const symbol &shown)
{
    for (const symbol &s : d.prob.parameters())
        if (!self.is_equal(s) && prints_as(s, shown))
            return true;
    for (const unknown &u : d.unknowns)
        if (prints_as(u.sym, shown))
            return true;
    return false;
}

// Coulomb's coefficient (friction_solution::mu, whatever its name in the problem) as μ,
// and each slide's sliding speed (the step regime_case::sliding_speed names) as λ, where
// that makes no two symbols look alike.
exmap display_names(const derivation &d, const friction_solution &f)
{
    exmap m;
    if (is_a<symbol>(f.mu) && !shown_elsewhere(d, f.mu, mu_shown))
        m[f.mu] = mu_shown;
    for (const regime_case &rc : f.cases) {
        const bool named_step = std::any_of(rc.sol.steps.begin(), rc.sol.steps.end(), [&](const step &st) {
            return st.role == step_role::separation_velocity && rc.sliding_speed.is_equal(st.sym);
        });
        if (named_step && !shown_elsewhere(d, rc.sliding_speed, lambda_shown))
            m[rc.sliding_speed] = lambda_shown;
    }
    return m;
}

// Writes the symbols of m as m gives them, in every expression of the document.
void rename(document &doc, const exmap &m)
{
    if (m.empty())
        return;
    auto fix = [&](ex &e) { e = e.subs(m); };
    auto fix_para = [&](paragraph &p) {
        for (span &s : p.spans)
            if (s.k == span::math)
                fix(s.expr);
    };
    for (section &sec : doc.sections)
        for (block &b : sec.blocks) {
            fix_para(b.para);
            for (paragraph &p : b.items)
                fix_para(p);
            for (math_row &r : b.math) {
                fix(r.lhs);
                fix(r.rhs);
                fix(r.then);
                fix_para(r.note);
            }
        }
}

// "Coulomb's coefficient of friction between the bodies is μ (μ ≥ 0).", with the name the
// problem gives it when the document writes it otherwise.
paragraph friction_coefficient(const ex &mu, const std::optional<notation> &mu_in_problem)
{
    if (!is_a<symbol>(mu))
        return paragraph().t("Coulomb's coefficient of friction between the bodies is $μ$ = ").m(mu).w(".");
    paragraph q;
    q.w("Coulomb's coefficient of friction between the bodies is ").m(mu);
    if (mu_in_problem)
        q.w(", written ").n(mu_in_problem->text, mu_in_problem->tex).w(" in the problem");
    return q.t(" ($μ ≥ 0$).");
}

context context_of(const explain_input &in)
{
    const derivation &d = in.d;
    const problem &p = d.prob;
    context c(d, in.s);
    c.dim = p.dimension;
    c.i1 = p.contact().body1;
    c.i2 = p.contact().body2;
    c.e = p.restitution;
    c.mu = in.s.mu;
    c.n = d.n_hat;
    c.numeric = p.is_numeric() || in.numbers;
    if (in.numbers) {
        c.numeric_d = in.numeric_d;
        c.numeric_f = in.numeric_s;
        c.inputs = in.numbers->values;
        c.units = in.numbers->units;
    }
    c.tnames = c.dim == 2 ? std::vector<std::string>{"t"} : std::vector<std::string>{"t", "b"};
    c.shared = in.s.shared.steps.size();
    // The equations and the impulse's unknowns are the derivation's (derive() writes them).
    c.tangents = d.friction.tangents;
    c.N = d.friction.N;
    c.F = d.friction.F;
    c.slide_d = d.friction.slide_d;
    c.eqs = d.friction.equations;
    c.stick_law = d.friction.stick_law;
    c.slide_law = d.friction.slide_law;
    return c;
}

class coulomb_chapter : public law_chapter
{
    const explain_input &in;
    context c;
    exmap shown; // the symbols written as mu and lambda

public:
    explicit coulomb_chapter(const explain_input &i) : in(i), c(context_of(i)), shown(display_names(i.d, i.s)) {}
    std::string title() const override { return "Impact with Coulomb friction"; }
    // The contact frame must be rational for the symbols to read well: with a normal such
    // as (0.2, 1, 0.1), of length sqrt(21/20), every step of the twin would carry products
    // of unlike roots; the numbers are clearer there.
    bool symbols_first() const override
    {
        for (const vec3 *v : {&in.d.n_hat, &in.s.e_t, &in.s.e_b})
            for (const ex &x : *v)
                if (!is_a<numeric>(x) || !ex_to<numeric>(x).is_rational())
                    return false;
        return true;
    }
    setup_parts setup() const override;
    std::vector<section> statement() const override { return {law_section(c)}; }
    std::vector<section> equations() const override { return {equations_section(c)}; }
    std::vector<section> solution() const override
    {
        return {response_section(c), c.has_stick() ? stick_section(c) : no_stick_section(c), slide_section(c)};
    }
    std::vector<section> regimes() const override
    {
        return {c.has_stick() ? regimes_section(c) : slide_regimes_section(c), existence_section(c)};
    }
    std::vector<section> results() const override
    {
        std::vector<section> out = c.numeric ? numbers_sections(c) : std::vector<section>{};
        for (section &s : laws_compared(in)) // the energy, the three restitution laws (explain_laws_compared.cpp)
            out.push_back(std::move(s));
        return out;
    }
    void finish(document &doc) const override { rename(doc, shown); }
};

setup_parts coulomb_chapter::setup() const
{
    const derivation &d = in.d;
    const problem &p = d.prob;
    const int dim = p.dimension;
    setup_parts law;
    law.kind = std::string(dim == 2 ? "A planar (2-D)" : "A 3-D") + " impact with Coulomb friction";
    std::optional<notation> mu_in_problem;
    if (shown.count(c.mu) && !prints_as(c.mu, mu_shown))
        mu_in_problem = notation{canonical_text(c.mu), canonical_latex(c.mu)};
    law.law.push_back(friction_coefficient(c.mu, mu_in_problem));
    law.world_components = true; // the equations stay in world components
    const std::string body2 = display_name(p.bodies[c.i2]), body1 = display_name(p.bodies[c.i1]);
    if (!d.impulse_form)
        law.impulses.push_back({c.N, paragraph()
                                         .t("normal impulse $∫N dt$, on ")
                                         .w(body2)
                                         .t(" along $+e_n$ and on ")
                                         .w(body1)
                                         .t(" along $-e_n$")});
    for (std::size_t k = 0; k < c.F.size(); ++k)
        law.impulses.push_back({c.F[k], paragraph()
                                            .w("friction impulse on " + body2 + " along ")
                                            .n("e_" + c.tnames[k], "\\hat{\\underline{e}}_" + c.tnames[k])
                                            .w(" (on " + body1 + " the opposite)")});
    const std::size_t nr = pivot_impulse_count(d);
    const std::string nt = std::to_string(dim - 1), more = nr ? " + " + std::to_string(nr) : "";
    paragraph q;
    q.w("impulses: 1 + " + nt + more)
        .t(" -- with friction the contact impulse has an unknown tangential part, so each body's impulse-momentum "
           "is written with the impulses as unknowns: the normal impulse $N$ and the ")
        .t(dim == 2 ? "friction impulse $F$ along $e_t$"
                    : "2 components of the friction impulse $~F$ in the tangent plane");
    if (nr)
        q.w(", and the " + std::to_string(nr) + " components of the pivot's reaction impulse");
    law.count_item = q;
    law.count_terms = " + 1 + " + nt + more;
    return law;
}

} // namespace
} // namespace impactgen::print::friction_detail

namespace impactgen::print::detail
{

std::unique_ptr<law_chapter> newton_coulomb_chapter(const explain_input &in)
{
    return std::make_unique<friction_detail::coulomb_chapter>(in);
}

std::unique_ptr<law_chapter> chapter(const coulomb &, const explain_input &in)
{
    if (follows_process(in.s.law)) // Routh's process (explain_process.cpp)
        return process_chapter(in);
    return newton_coulomb_chapter(in);
}

} // namespace impactgen::print::detail
