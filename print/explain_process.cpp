// The chapter of a planar contact with Coulomb friction whose restitution is Poisson's or
// Stronge's energetic law (symbolic/routh.hpp): the impact followed as the normal impulse P_n
// grows, as Routh and Stronge teach it. The relative velocity of the contact points in the
// contact frame is linear in the impulse, u = u_0 + K P; in each phase P_t is tied to P_n (a
// slide: dP_t = -s mu dP_n; a stick: u_t stays 0), so (u_t, u_n) is linear in P_n there. The
// phases, their ends and the conditions that selected them are the solution's candidates
// (regime_case::process, process_conditions); the end of compression and its work come from
// the library's process (routh_process), never from the printer.
#include "explain_process.hpp"

#include "canonical.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/routh.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <variant>

namespace impactgen::print::detail
{
using namespace GiNaC;

namespace
{

// The process's inputs as the document writes them: numbers, or the solution's own steps.
struct inputs {
    ex Ktt, Ktn, Knn, ut, un, mu, e;
};

// The library's inputs of the process (numbers, or step symbols the solution shares: the
// solver made the shared steps with process_inputs_of, the same steps in the same order, so
// each of the scratch's steps is the shared step at its place, of the same role).
process_inputs library_inputs(const explain_input &in)
{
    solution scratch;
    process_inputs q = process_inputs_of(in.d, scratch);
    exmap same;
    const std::vector<step> &shared = in.s.shared.steps;
    for (std::size_t k = 0; k < scratch.steps.size() && k < shared.size(); ++k)
        if (shared[k].role == scratch.steps[k].role)
            same[scratch.steps[k].sym] = shared[k].sym;
    for (ex *x : {&q.Ktt, &q.Ktn, &q.Knn, &q.ut, &q.un})
        *x = x->subs(same);
    return q;
}

// The sign s of the first slide: +1 when the contact slips along +e_t. From the candidate's
// conditions (symbolic) or the numbers.
int first_slip(const process_inputs &q, const std::vector<process_condition> &conditions)
{
    for (const process_condition &pc : conditions)
        if (pc.kind == process_test::initial_slip || pc.kind == process_test::slip_direction) {
            const ex s = pc.value.coeff(pc.kind == process_test::initial_slip ? q.ut : q.Ktn, 1);
            if (is_a<numeric>(s) && !s.is_zero())
                return ex_to<numeric>(s).is_positive() ? 1 : -1;
        }
    const ex u = q.ut.is_zero() ? q.Ktn : q.ut;
    return is_a<numeric>(u) && ex_to<numeric>(u.evalf()).is_negative() ? -1 : 1;
}

// The phase's slopes: dP_t/dP_n, du_t/dP_n, du_n/dP_n (routh.hpp's r, a, b).
std::array<ex, 3> slopes(const process_inputs &q, phase_kind k, int s)
{
    if (k == phase_kind::stick)
        return {-q.Ktn / q.Ktt, 0, tidy((q.Ktt * q.Knn - q.Ktn * q.Ktn) / q.Ktt)};
    const int sg = k == phase_kind::reverse ? -s : s;
    return {-sg * q.mu, tidy(q.Ktn - sg * q.mu * q.Ktt), tidy(q.Knn - sg * q.mu * q.Ktn)};
}

// "slide: the contact slips along +e_t", as prose.
paragraph &phase_words(paragraph &q, phase_kind k, int s)
{
    if (k == phase_kind::slide)
        return q.w("slide: the contact slips along ").t(s > 0 ? "$+e_t$" : "$-e_t$");
    if (k == phase_kind::reverse)
        return q.w("reverse: the slip has stopped and, unable to stick, turns to ").t(s > 0 ? "$-e_t$" : "$+e_t$");
    return q.w("stick: the slip has stopped and the impulse ratio lies inside the friction cone");
}

paragraph condition_words(const process_condition &pc)
{
    switch (pc.kind) {
    case process_test::initial_slip:
        return paragraph().w("the contact slips this way before impact");
    case process_test::sticks_at_start:
        return paragraph().w("starting without slip, the sticking ratio lies inside the cone");
    case process_test::slip_direction:
        return paragraph().w("starting without slip, outside the cone: the slip it takes");
    case process_test::slip_slows:
        return paragraph().w("the slip slows down and reaches zero");
    case process_test::normal_slope:
        return paragraph().w("the normal velocity grows in this phase");
    case process_test::compression_first:
        return paragraph().w("the compression ends before the slip stops");
    case process_test::sticks:
        return paragraph().w("the slip stopped with the sticking ratio inside the cone: it sticks");
    case process_test::ends_first:
        return paragraph().w("restitution ends before the slip stops");
    }
    return paragraph();
}

math_row value_of(const std::string &text, const std::string &tex, const ex &v, const paragraph &note = {})
{
    math_row r = note_row(text, tex, printable(v) ? v : ex(0));
    if (!printable(v))
        r.rhs = symbol("(too long to print)");
    r.note = note;
    if (r.note.spans.empty() && is_a<numeric>(v) && ex_to<numeric>(v).is_rational() && !ex_to<numeric>(v).is_integer())
        r.note = decimal_note(v);
    return r;
}

// A value as the document shows it: exact when it is a rational number or has symbols, else a
// float.
ex shown(const ex &v, bool numbers)
{
    const ex x = tidy(v);
    if (!numbers || (is_a<numeric>(x) && ex_to<numeric>(x).is_rational()))
        return x;
    return x.evalf();
}

double num(const ex &v)
{
    const ex x = v.evalf();
    return is_a<numeric>(x) ? ex_to<numeric>(x).to_double() : 0.0;
}

// The velocity (u_t, u_n) at the impulse (P_t, P_n): u = u_0 + K P.
std::pair<ex, ex> velocity_at(const process_inputs &q, const ex &pt, const ex &pn)
{
    return {q.ut + q.Ktt * pt + q.Ktn * pn, q.un + q.Ktn * pt + q.Knn * pn};
}

// Numbers the rows of the section's last block of rows, in order: (first), (first + 1), ...
void number_rows(section &sec, int first)
{
    for (math_row &r : sec.blocks.back().math)
        r.tag = std::to_string(first++);
}

// A sequence's phases as its name says them: "slide, stick".
std::string phases_name(const process_sequence &q)
{
    std::string r;
    for (const process_phase &ph : q.phases)
        r += (r.empty() ? "" : ", ") + std::string(phase_name(ph.kind));
    return r;
}

class process_chapter_impl : public law_chapter
{
    const explain_input &in;
    process_teaching t;
    std::unique_ptr<law_chapter> coulomb_parts;

public:
    explicit process_chapter_impl(const explain_input &i) : in(i)
    {
        t.q = library_inputs(i);
        t.numeric = i.d.prob.is_numeric();
        for (const process_sequence &s : routh_process(t.q, "contact.friction"))
            if (!s.wedges)
                t.seqs.push_back(s);
        coulomb_parts = newton_coulomb_chapter(in);
    }
    std::string title() const override { return words_of(in.s.law).title; }
    bool symbols_first() const override { return false; }
    setup_parts setup() const override;
    std::vector<section> statement() const override { return process_statement(t); }
    std::vector<section> equations() const override { return process_equations(t); }
    std::vector<section> solution() const override { return process_sequences(t); }
    std::vector<section> results() const override;
    void finish(document &doc) const override { coulomb_parts->finish(doc); }
};

setup_parts process_chapter_impl::setup() const
{
    setup_parts parts = coulomb_parts->setup();
    parts.kind = "A planar (2-D) impact with Coulomb friction, followed through the impact";
    parts.law.push_back(words_of(in.s.law).setup);
    return parts;
}

} // namespace

std::vector<section> process_statement(const process_teaching &t)
{
    section sec;
    sec.title = "Routh's process";
    sec.para(paragraph().t(
        "With friction, the impact is followed as the normal impulse $P_n$ grows from 0 (Routh; Stronge). "
        "At each instant Coulomb's law holds: while the contact slips along $s e_t$ ($s = ±1$) the friction "
        "impulse grows against the slip, $μ$ times as fast as the normal impulse; while it sticks, $u_t$ stays 0 "
        "and the ratio of the two impulses must lie inside the cone. The slip may stop during the impact: then "
        "the contact sticks if it can, else it slides back (a reversal)."));
    sec.rows({formula_row("dP_t = -s μ dP_n", "dP_{t} = -s\\,\\mu\\,dP_{n}", "sliding along $s e_t$"),
              formula_row("|dP_t| ≤ μ dP_n", "|dP_{t}| \\le \\mu\\,dP_{n}", "sticking")});
    number_rows(sec, t.first_row);
    sec.para(paragraph().t("Compression ends where $u_n = 0$, at $P_n = P_c$. Restitution ends by the law:"));
    sec.rows({words_of(t.q.law).end});
    number_rows(sec, t.first_row + 2);
    return {sec};
}

std::vector<section> process_equations(const process_teaching &t)
{
    const process_inputs &q = t.q;
    const bool numeric = t.numeric;
    section sec;
    sec.title = "The relative velocity as a function of the impulse";
    sec.para(paragraph().t("The impulse $P = P_t e_t + P_n e_n$ on the second body changes the relative velocity "
                           "of the contact points by the contact response $K$, written in the contact frame:"));
    sec.rows({formula_row("u_t(P) = u_t + K_tt P_t + K_tn P_n", "u_{t}(P) = u_{t} + K_{tt} P_{t} + K_{tn} P_{n}"),
              formula_row("u_n(P) = u_n + K_tn P_t + K_nn P_n", "u_{n}(P) = u_{n} + K_{tn} P_{t} + K_{nn} P_{n}")});
    number_rows(sec, t.first_row + 3);
    sec.para(paragraph().t("with $u_t$, $u_n$ the velocities before impact and"));
    sec.rows({value_of("K_tt", "K_{tt}", shown(q.Ktt, numeric)), value_of("K_tn", "K_{tn}", shown(q.Ktn, numeric)),
              value_of("K_nn", "K_{nn}", shown(q.Knn, numeric)), value_of("u_t", "u_{t}", shown(q.ut, numeric)),
              value_of("u_n", "u_{n}", shown(q.un, numeric))});
    sec.para(paragraph().t("In each phase $P_t$ is tied to $P_n$, so $u_t$ and $u_n$ are linear in $P_n$, with "
                           "the slopes"));
    sec.rows(
        {formula_row(
             "du_t/dP_n = K_tn - s μ K_tt,  du_n/dP_n = K_nn - s μ K_tn",
             "\\frac{du_{t}}{dP_{n}} = K_{tn} - s\\mu K_{tt},\\quad \\frac{du_{n}}{dP_{n}} = K_{nn} - s\\mu K_{tn}",
             "sliding along $s e_t$"),
         formula_row(
             "du_t/dP_n = 0,  du_n/dP_n = (K_tt K_nn - K_tn²)/K_tt",
             "\\frac{du_{t}}{dP_{n}} = 0,\\quad \\frac{du_{n}}{dP_{n}} = \\frac{K_{tt}K_{nn} - K_{tn}^{2}}{K_{tt}}",
             "sticking")});
    number_rows(sec, t.first_row + 5);
    return {sec};
}

namespace
{

section sequence_section(const process_teaching &t, std::size_t k)
{
    const process_inputs &q = t.q;
    const bool numeric = t.numeric;
    const process_sequence &c = t.seqs[k];
    const int s = first_slip(q, c.conditions);
    section sec;
    sec.title = t.seqs.size() > 1 ? "Phase sequence " + std::to_string(k + 1) + ": " + phases_name(c)
                                  : "The phases: " + phases_name(c);
    if (!c.conditions.empty()) {
        sec.para(paragraph().w("This sequence is the process when:"));
        std::vector<math_row> rows;
        for (const process_condition &pc : c.conditions) {
            math_row r = row(tidy(pc.value), 0);
            r.rel = pc.strict ? ">" : "≥";
            r.note = condition_words(pc);
            rows.push_back(r);
        }
        sec.rows(rows);
    }
    ex start = 0;
    for (std::size_t j = 0; j < c.phases.size(); ++j) {
        const process_phase &ph = c.phases[j];
        const std::array<ex, 3> r = slopes(q, ph.kind, s);
        paragraph w;
        w.w("Phase " + std::to_string(j + 1) + ", ");
        sec.para(phase_words(w, ph.kind, s).w(", from ").m(shown(start, numeric)).w(" to the normal impulse below:"));
        sec.rows({value_of("dP_t/dP_n", "dP_{t}/dP_{n}", shown(r[0], numeric)),
                  value_of("du_t/dP_n", "du_{t}/dP_{n}", shown(r[1], numeric)),
                  value_of("du_n/dP_n", "du_{n}/dP_{n}", shown(r[2], numeric)),
                  value_of("P_n", "P_{n}", shown(ph.normal_impulse_end, numeric),
                           paragraph().w(j + 1 == c.phases.size() ? "restitution ends (the law)"
                                                                  : "the slip stops (u_t = 0)"))});
        start = ph.normal_impulse_end;
    }
    sec.para(paragraph().t("Compression ends where $u_n = 0$:"));
    std::vector<math_row> rows{value_of("P_c", "P_{c}", shown(c.compression_impulse, numeric))};
    if (words_of(q.law).compression_work)
        rows.push_back(value_of("W_c", "W_{c}", shown(c.compression_work, numeric),
                                paragraph().w("the normal work of compression")));
    sec.rows(rows);
    sec.para(paragraph().w("At the end of the impact:"));
    sec.rows({value_of("P_n", "P_{n}", shown(c.normal_impulse, numeric)),
              value_of("P_t", "P_{t}", shown(c.tangential_impulse, numeric)),
              value_of("u'_t", "u'_{t}", shown(c.tangential_velocity, numeric)),
              value_of("u'_n", "u'_{n}", shown(c.normal_velocity, numeric))});
    return sec;
}

std::vector<path_point> path(const process_teaching &t, std::size_t k)
{
    const process_inputs &q = t.q;
    const process_sequence &c = t.seqs[k];
    const int s = first_slip(q, c.conditions);
    std::vector<path_point> pts{{0, num(q.ut), num(q.un), "before impact"}};
    const double pc = num(c.compression_impulse);
    ex pn0 = 0, pt0 = 0;
    for (std::size_t j = 0; j < c.phases.size(); ++j) {
        const ex r = slopes(q, c.phases[j].kind, s)[0];
        const ex pn1 = c.phases[j].normal_impulse_end;
        if (pc > num(pn0) && pc < num(pn1)) {
            const ex at = c.compression_impulse;
            const auto u = velocity_at(q, pt0 + r * (at - pn0), at);
            pts.push_back({pc, num(u.first), 0.0, "compression ends"});
        }
        pt0 = pt0 + r * (pn1 - pn0);
        const auto u = velocity_at(q, pt0, pn1);
        const bool last = j + 1 == c.phases.size();
        pts.push_back({num(pn1), num(u.first), num(u.second), last ? "after impact" : "slip stops"});
        pn0 = pn1;
    }
    return pts;
}

} // namespace

std::vector<section> process_sequences(const process_teaching &t)
{
    std::vector<section> out;
    for (std::size_t k = 0; k < t.seqs.size(); ++k)
        out.push_back(sequence_section(t, k));
    return out;
}

section process_path_section(const process_teaching &t)
{
    section sec;
    sec.title = "The path of the relative velocity";
    const std::vector<path_point> pts = path(t, 0);
    sec.para(paragraph().t("The relative velocity $(u_t, u_n)$ moves on a straight line in each phase; the "
                           "numbered points are:"));
    std::vector<paragraph> items;
    for (std::size_t j = 0; j < pts.size(); ++j) {
        char text[160], tex[200];
        std::snprintf(text, sizeof text, "P_n = %.4g, u_t = %.4g, u_n = %.4g", pts[j].pn, pts[j].ut, pts[j].un);
        std::snprintf(tex, sizeof tex, "P_{n} = %.4g,\\ u_{t} = %.4g,\\ u_{n} = %.4g", pts[j].pn, pts[j].ut, pts[j].un);
        items.push_back(paragraph().w(std::to_string(j) + ": " + pts[j].label + ", ").n(text, tex));
    }
    sec.list(items);
    sec.picture(process_figure(pts, "The relative velocity of the contact points during the impact"));
    return sec;
}

namespace
{

std::vector<section> process_chapter_impl::results() const
{
    if (!t.numeric || in.s.cases.size() != 1)
        return {};
    const regime_case &c = in.s.cases.front();
    const section sec = process_path_section(t);
    section res;
    res.title = "Results";
    const ex before = c.sol.expand_steps(c.sol.energy_before), after = c.sol.expand_steps(c.sol.energy_after);
    res.rows({value_of("P_n", "P_{n}", shown(c.sol.normal_impulse, true)),
              value_of("P_t", "P_{t}", shown(c.tangential_scalar, true)),
              value_of("T", "T", shown(before, true), paragraph().w("kinetic energy before")),
              value_of("T'", "T'", shown(after, true), paragraph().w("kinetic energy after")),
              value_of("T - T'", "T - T'", shown(before - after, true), paragraph().w("kinetic energy lost"))});
    std::vector<paragraph> bodies;
    const problem &p = in.d.prob;
    for (std::size_t b = 0; b < p.bodies.size(); ++b)
        if (!p.bodies[b].infinite_mass) {
            vec3 v;
            for (int a = 0; a < 3; ++a)
                v[a] = shown(c.sol.expand_steps(c.sol.after[b].velocity[a]), true);
            paragraph q;
            q.w(body_ref(p, b) + " after impact: ").t("$v'_C$ = ");
            vector_span(q, v, 2).t(", $ω'$ = ").m(shown(c.sol.expand_steps(c.sol.after[b].angular_velocity[2]), true));
            bodies.push_back(q.w("."));
        }
    res.list(bodies);
    return {sec, res};
}

} // namespace

// ---- the laws' words (explain_process.hpp: the one document hook of a restitution law) ----

restitution_words words_of(const restitution_law &law)
{
    return std::visit(
        law_cases{
            [](const newton_restitution &) -> restitution_words {
                throw std::logic_error("Newton's law of restitution is not followed through the impact");
            },
            [](const poisson_restitution &) {
                restitution_words w;
                w.title = "Impact with friction, Poisson's restitution";
                w.setup = paragraph().t("Restitution is measured by impulses (Poisson): $e$ is the ratio of the "
                                        "normal impulse of restitution to that of compression.");
                w.end = formula_row("P_n = (1 + e) P_c", "P_{n} = (1 + e)\\,P_{c}",
                                    "Poisson: the impulse of restitution is e times that of compression");
                w.summary_end = formula_row("end of restitution (Poisson): N = (1 + e) N_c",
                                            "\\text{end of restitution (Poisson): } N = (1 + e)\\,N_c");
                return w;
            },
            [](const energetic_restitution &) {
                restitution_words w;
                w.title = "Impact with friction, energetic restitution";
                w.setup = paragraph().t("Restitution is measured by work (Stronge's energetic coefficient): $e²$ is "
                                        "the ratio of the work the normal force gives back in restitution to the "
                                        "work it absorbs in compression.");
                w.end = formula_row("W_r = -e² W_c,  W = ∫ u_n dP_n",
                                    "W_{r} = -e^{2}\\,W_{c},\\quad W = \\int u_{n}\\,dP_{n}",
                                    "energetic: the work given back is e² times the work absorbed; it never "
                                    "creates energy");
                w.summary_end = formula_row("end of restitution (Stronge): W_r = -e² W_c, the normal work",
                                            "\\text{end of restitution (Stronge): } W_r = -e^2 W_c\\ "
                                            "\\text{(the work of the normal impulse)}");
                w.compression_work = true;
                return w;
            },
        },
        law);
}

std::unique_ptr<law_chapter> process_chapter(const explain_input &in)
{
    return std::make_unique<process_chapter_impl>(in);
}

} // namespace impactgen::print::detail
