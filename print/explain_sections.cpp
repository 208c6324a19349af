// The smooth chapter's sections (explain_smooth.hpp): the impulses, the equations, the count
// and the solution, the checks (with the numbers of a worked example).
#include "explain.hpp"
#include "explain_detail.hpp"
#include "explain_smooth.hpp"

#include "canonical.hpp"
#include "contact_frame.hpp"
#include "expression.hpp"
#include "figure/figure.hpp"
#include "names/escape.hpp"
#include "symbolic/decide.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{
using namespace detail;
} // namespace

section detail::impulse_section(const derivation &d)
{
    const problem &p = d.prob;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    section sec{"The impulses (impulse-momentum diagram in words)", {}};
    std::vector<paragraph> items;
    items.push_back(paragraph()
                        .t("At the contact the normal reaction $N$ acts along $e_n$ for a very short time; its impulse "
                           "$∫N dt$ acts on ")
                        .w(body_ref(p, i2))
                        .t(" along $+e_n$ and on ")
                        .w(body_ref(p, i1))
                        .t(" along $-e_n$ (action and reaction)."));
    items.push_back(paragraph()
                        .t("The bodies are smooth: the tangential impulse $∫T dt = 0$, so no impulse acts along $e_t$")
                        .t(p.dimension == 3 ? " or $e_b$." : "."));
    other_impulses(items, p, "$∫N dt$");
    sec.list(items);

    std::vector<math_row> rows;
    for (std::size_t i : {i1, i2}) {
        const body &b = p.bodies[i];
        if (b.infinite_mass)
            continue;
        const bool short_label = b.label.size() == 1 && std::isalnum(static_cast<unsigned char>(b.label[0]));
        std::string L = short_label ? b.label : "," + b.label;
        std::string LT = short_label ? b.label : ",\\text{" + names::latex_text(b.label) + "}";
        std::string sign = i == i1 ? "-" : "";
        const pivot *pv = p.pivot_of(i);
        // the mass as the symbols name it: m1, m_puck (not m,puck)
        const std::string M = short_label ? "m" + b.label : "m_" + b.label;
        const std::string MT = short_label ? "m_{" + b.label + "}" : "m_{\\text{" + names::latex_text(b.label) + "}}";
        math_row r;
        r.lhs_note = {M + " (v′_C" + L + " - v_C" + L + ")",
                      MT + " (\\underline{v}'_{C" + LT + "} - \\underline{v}_{C" + LT + "})"};
        r.rel = "=";
        r.rhs = 0;
        r.lhs_note.text += " = " + sign + "∫N dt e_n" + (pv ? " + R" : "");
        r.lhs_note.tex += " = " + sign + "\\int N\\,dt\\;\\hat{\\underline{e}}_n" + (pv ? " + \\underline{R}" : "");
        r.rel = "";
        r.note.w("impulse-momentum of " + body_ref(p, i));
        rows.push_back(r);
    }
    sec.rows(rows);
    return sec;
}

namespace
{

// The words before a group of equations: its principle, for its bodies (typed).
paragraph group_why(const problem &p, const equation &first, std::size_t i, const pivot *pv)
{
    std::string title = principle_name(first.why);
    title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(title[0])));
    paragraph why;
    why.w(title + ": ");
    switch (first.why) {
    case principle::smooth_contact:
        why.w("the bodies are smooth, so no impulse acts on " + body_ref(p, i))
            .t(p.dimension == 3 ? " along $e_t$ or $e_b$: its centre-of-mass velocity along them is unchanged."
                                : " along $e_t$: its centre-of-mass velocity along $e_t$ is unchanged.");
        break;
    case principle::system_momentum:
        why.t("the impulse $N e_n$ is internal to the system of both bodies, and no other impulse acts, so their "
              "linear "
              "momentum along $e_n$ is conserved:");
        break;
    case principle::linear_impulse:
        why.w("the change of linear momentum of " + body_ref(p, i) + " equals the impulses on it, ")
            .t(i == p.contact().body1 ? "$-N e_n$" : "$+N e_n$")
            .t(pv ? " and the pivot impulse $~R$." : ".");
        break;
    case principle::angular_momentum:
        if (pv)
            why.t("about the pivot $E$, fixed in the inertial frame, the pivot impulse has no moment: the change "
                  "of angular "
                  "momentum of ")
                .w(body_ref(p, i))
                .t(" about $E$ is the moment of the contact impulse. Its angular momentum about $E$ is that about "
                   "$C$ plus "
                   "the moment of the momentum of $C$ (which is $~~I_E ~ω$, with $~~I_E$ the inertia about $E$, "
                   "while the body "
                   "turns about $E$); in components:");
        else
            why.w("the contact impulse on " + body_ref(p, i))
                .t(" passes through $O$, which is fixed in the inertial frame, so its moment about $O$ is zero and "
                   "the "
                   "angular momentum about $O$ is conserved, $~H′_O = ~H_O$. Taken about $O$, the angular momentum "
                   "is "
                   "that about $C$ plus the moment of the momentum of $C$; in components:");
        break;
    case principle::pivot_fixed:
        why.t("the pivot $E$ of ")
            .w(body_ref(p, i))
            .t(" does not move, so the body's velocity at $E$ is zero after impact:");
        break;
    case principle::restitution:
        why.t("Newton's coefficient of restitution: the normal velocity of separation of the contact points is $e$ "
              "times "
              "their velocity of approach.");
        break;
    case principle::stick:
    case principle::slide: // Coulomb's law: not an equation of the smooth impact
        break;
    }
    return why;
}

// Smooth contact for both bodies at once.
paragraph smooth_bodies_why(const problem &p)
{
    std::string title = principle_name(principle::smooth_contact);
    title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(title[0])));
    return paragraph()
        .w(title + ": ")
        .t(p.dimension == 3 ? "the bodies are smooth, so no impulse acts on either body along $e_t$ or $e_b$: each "
                              "centre-of-mass velocity along them is unchanged."
                            : "the bodies are smooth, so no impulse acts on either body along $e_t$: each "
                              "centre-of-mass velocity along $e_t$ is unchanged.");
}

// The formulas a group of equations starts from (angular momentum, a fixed pivot,
// restitution at the contact points).
void group_formulas(section &sec, const derivation &d, const contact_frame_view &view, const equation &first,
                    std::size_t i, const pivot *pv)
{
    const problem &p = d.prob;
    if (first.why == principle::angular_momentum) {
        if (pv) {
            const bool on1 = i == p.contact().body1;
            sec.rows({formula_row("H_E = I_C ω + r_EC × m v_C",
                                  "\\underline{H}_E = \\underline{\\underline{I}}_C\\,\\underline{\\omega} + "
                                  "\\underline{r}_{EC} \\times m\\,\\underline{v}_C"),
                      formula_row(on1 ? "H′_E - H_E = -r_EO × ∫N dt e_n" : "H′_E - H_E = r_EO × ∫N dt e_n",
                                  std::string("\\underline{H}'_E - \\underline{H}_E = ") + (on1 ? "-" : "") +
                                      "\\underline{r}_{EO} \\times \\int N\\,dt\\;\\hat{\\underline{e}}_n")});
        } else {
            sec.rows({formula_row("H_O = I_C ω + r_OC × m v_C",
                                  "\\underline{H}_O = \\underline{\\underline{I}}_C\\,\\underline{\\omega} + "
                                  "\\underline{r}_{OC} \\times m\\,\\underline{v}_C",
                                  ""),
                      formula_row("I_C ω′ + r_OC × m v′_C = I_C ω + r_OC × m v_C",
                                  "\\underline{\\underline{I}}_C\\,\\underline{\\omega}' + \\underline{r}_{OC} \\times "
                                  "m\\,\\underline{v}'_C = \\underline{\\underline{I}}_C\\,\\underline{\\omega} + "
                                  "\\underline{r}_{OC} \\times m\\,\\underline{v}_C")});
        }
    } else if (first.why == principle::pivot_fixed) {
        sec.rows({formula_row("v′_E = v′_C + ω′ × r_CE = 0",
                              "\\underline{v}'_E = \\underline{v}'_C + \\underline{\\omega}' \\times "
                              "\\underline{r}_{CE} = \\underline{0}")});
    } else if (first.why == principle::restitution && p.bodies[p.contact().body1].particle &&
               p.bodies[p.contact().body2].particle) {
        // particles: every point moves with the centre of mass, said once
        sec.para(paragraph().t("$e = -(v′_Bn - v′_An)/(v_Bn - v_An)$, with the normal velocities of the contact "
                               "points $A$ and $B$; every point of a particle moves with its centre of mass:"));
        const vec3 &n = d.n_hat;
        std::vector<math_row> pv_rows;
        const std::pair<const char *, const char *> names[4] = {
            {"v_An", "v_{An}"}, {"v′_An", "v'_{An}"}, {"v_Bn", "v_{Bn}"}, {"v′_Bn", "v'_{Bn}"}};
        const GiNaC::ex values[4] = {dot(d.vA, n), dot(d.vA_after, n), dot(d.vB, n), dot(d.vB_after, n)};
        for (int k = 0; k < 4; ++k) {
            math_row r;
            r.lhs_note = {names[k].first, names[k].second};
            r.rhs = view.apply(tidy_expand(values[k]));
            pv_rows.push_back(r);
        }
        sec.packed_rows(pv_rows);
        sec.para(paragraph().t("and $v′_Bn - v′_An = -e (v_Bn - v_An)$ reads:"));
    } else if (first.why == principle::restitution) {
        const std::size_t i2 = p.contact().body2;
        sec.para(paragraph().t(
            "$e = -(v′_Bn - v′_An)/(v_Bn - v_An)$: the velocities are those of the contact points $A$ and $B$, not "
            "of the "
            "centres of mass. As $A$ and $C1$ are both points of body 1, and $B$ and $C2$ of body 2:"));
        const vec3 &n = d.n_hat;
        std::vector<math_row> pv_rows;
        pv_rows.push_back(note_row("v_An = (v_C1 + ω1 × r_C1A)·e_n",
                                   "v_{An} = (\\underline{v}_{C_1} + \\underline{\\omega}_1 \\times "
                                   "\\underline{r}_{C_1A})\\cdot\\hat{\\underline{e}}_n",
                                   view.apply(tidy_expand(dot(d.vA, n)))));
        pv_rows.push_back(note_row("v′_An = (v′_C1 + ω′1 × r_C1A)·e_n",
                                   "v'_{An} = (\\underline{v}'_{C_1} + \\underline{\\omega}'_1 \\times "
                                   "\\underline{r}_{C_1A})\\cdot\\hat{\\underline{e}}_n",
                                   view.apply(tidy_expand(dot(d.vA_after, n)))));
        pv_rows.push_back(note_row("v_Bn = (v_C2 + ω2 × r_C2B)·e_n",
                                   "v_{Bn} = (\\underline{v}_{C_2} + \\underline{\\omega}_2 \\times "
                                   "\\underline{r}_{C_2B})\\cdot\\hat{\\underline{e}}_n",
                                   view.apply(tidy_expand(dot(d.vB, n)))));
        math_row last = note_row("v′_Bn = (v′_C2 + ω′2 × r_C2B)·e_n",
                                 "v'_{Bn} = (\\underline{v}'_{C_2} + \\underline{\\omega}'_2 \\times "
                                 "\\underline{r}_{C_2B})\\cdot\\hat{\\underline{e}}_n",
                                 view.apply(tidy_expand(dot(d.vB_after, n))));
        if (p.bodies[i2].infinite_mass || p.immovable(i2))
            last.note.t("$B$ is on a body the impulse cannot move: $v′_Bn = v_Bn$");
        pv_rows.push_back(last);
        sec.rows(pv_rows);
        sec.para(paragraph().t("and $v′_Bn - v′_An = -e (v_Bn - v_An)$ reads:"));
    }
}

// Where a principle gives no usable equation.
void remark_list(section &sec, const derivation &d)
{
    const problem &p = d.prob;
    std::vector<paragraph> items;
    for (const remark &r : d.remarks) {
        paragraph q;
        const std::string who = body_ref(p, r.body);
        switch (r.kind) {
        case remark_kind::momentum_infinite_mass:
            q.t("Linear momentum of the system along $e_n$ is not useful: ")
                .w(who)
                .t(" has infinite mass, so $m (v′_n - v_n)$ "
                   "on its side is finite but unknown (infinity times zero).");
            break;
        case remark_kind::infinite_mass_unchanged:
            q.w("The velocities of " + who)
                .t(" are unchanged: a finite impulse cannot change the motion of an infinite mass, so "
                   "it gives no angular momentum equation either.");
            break;
        case remark_kind::particle_no_rotation: {
            // every particle in one item (issue 25, defect 9)
            std::vector<std::size_t> particles;
            for (const remark &o : d.remarks)
                if (o.kind == remark_kind::particle_no_rotation)
                    particles.push_back(o.body);
            if (particles.front() != r.body)
                continue;
            if (particles.size() == 1) {
                q.w(who).t(" is a particle (no rotational inertia): it has no angular velocity unknowns, and its "
                           "angular momentum about $O$, $~r_OC × m ~v_C$, changes only through $~v_C$, which the "
                           "other equations fix: it gives no new equation.");
                break;
            }
            for (std::size_t k = 0; k < particles.size(); ++k)
                q.w((k == 0 ? "" : k + 1 == particles.size() ? " and " : ", ") + body_ref(p, particles[k]));
            q.t(" are particles (no rotational inertia): they have no angular velocity unknowns, and the angular "
                "momentum of each about $O$, $~r_OC × m ~v_C$, changes only through its $~v_C$, which the other "
                "equations fix: it gives no new equation.");
            break;
        }
        case remark_kind::pinned_particle:
            q.w(who).t(" is a particle pinned at a fixed point: it cannot rotate, so it cannot move, and its pivot "
                       "takes the whole contact impulse.");
            break;
        case remark_kind::uninvolved:
            q.w(who + " takes no part in the contact: its velocities are unchanged.");
            break;
        }
        items.push_back(q);
    }
    if (items.size() == 1) { // one remark: a sentence, not a list
        paragraph one = paragraph().w("Where a principle gives no usable equation: ");
        one.spans.insert(one.spans.end(), items[0].spans.begin(), items[0].spans.end());
        sec.para(one);
        return;
    }
    sec.para(paragraph().w("Where a principle gives no usable equation:"));
    sec.list(items);
}

} // namespace

section detail::equations_section(const derivation &d)
{
    const problem &p = d.prob;
    section sec{"The equations", {}};
    if (d.impulse_form)
        sec.para(paragraph().t(
            "A body is pinned, so, as in the notes' constrained collision, impulse-momentum is written for each body "
            "separately, with $∫N dt$ and the pivot impulse $~R$ as unknowns; angular impulse is taken about the pivot "
            "$E$, "
            "fixed in the inertial frame, where the pivot impulse has no moment."));
    else
        sec.para(paragraph().t(
            "The bodies are unconstrained, so the notes use conservation laws in which the unknown impulse $∫N dt$ "
            "does not appear: tangential momentum of each body, linear momentum of the system along $e_n$, "
            "angular momentum of each body about $O$, and restitution."));

    // Equations are grouped by principle and bodies; the words come from those (typed), never from the
    // derivation's ASCII sentence. In contact-frame components where the normal is not a world axis.
    const contact_frame_view view = contact_frame_view_of(d);
    std::size_t k = 0;
    while (k < view.equations.size()) {
        const equation &first = *view.equations[k].source;
        std::vector<math_row> rows;
        bool several_bodies = false;
        std::size_t j = k;
        for (; j < view.equations.size(); ++j) {
            const framed_equation &f = view.equations[j];
            const equation &eq = *f.source;
            // smooth contact: one paragraph for every body (issue 25, defect 9: said once, not per body)
            if (eq.why != first.why || (eq.bodies != first.bodies && first.why != principle::smooth_contact))
                break;
            if (eq.bodies != first.bodies)
                several_bodies = true;
            math_row r = row(f.lhs, f.rhs, eq.label);
            if (!f.axis.empty())
                along(r.note.t("component along "), f.axis);
            rows.push_back(r);
        }
        const std::size_t i = first.bodies.empty() ? no_body : first.bodies[0];
        const pivot *pv = i == no_body ? nullptr : p.pivot_of(i);
        const paragraph why = several_bodies ? smooth_bodies_why(p) : group_why(p, first, i, pv);
        sec.para(why);
        group_formulas(sec, d, view, first, i, pv);
        sec.rows(rows);
        k = j;
    }
    if (!d.remarks.empty())
        remark_list(sec, d);
    return sec;
}

section detail::solution_section(const derivation &d, const solution &s)
{
    section sec{"Count check and solution", {}};
    const bool ok = d.count_equations() == d.count_unknowns();
    sec.para(paragraph().w(
        std::to_string(d.count_equations()) + " equations for " + std::to_string(d.count_unknowns()) +
        " unknowns: " + (ok ? "the count matches, the system can be solved." : "THE COUNT DOES NOT MATCH.")));
    // the general closed form said once, in words and symbols (issue 25, defect 9: no rows that the
    // steps below repeat)
    const bool particles =
        d.prob.bodies[d.prob.contact().body1].particle && d.prob.bodies[d.prob.contact().body2].particle;
    if (particles)
        sec.para(paragraph().t(
            "Every unknown changes linearly with the normal impulse $N$ (= $∫N dt$ along $e_n$): "
            "$~v′_C = ~v_C ± N e_n/m$. Restitution then fixes $N = -(1 + e) u/(w_1 + w_2)$, with "
            "$u = (~v_B - ~v_A)·e_n$ the normal velocity of approach and $w_i = 1/m_i$ the inverse mass of body $i$ "
            "(0 for a body the impulse cannot move)."));
    else
        sec.para(paragraph().t(
            "Every unknown changes linearly with the normal impulse $N$ (= $∫N dt$ along $e_n$): a free body gets "
            "$~v′_C = ~v_C ± N e_n/m$ and $~ω′ = ~ω ± N ~~I⁻¹(~r × e_n)$, a pinned body turns about $E$. Restitution "
            "then fixes $N = -(1 + e) u/(w_1 + w_2)$, with $u = (~v_B - ~v_A)·e_n$ the normal velocity of approach "
            "and $w_i = 1/m_i + (~r_i × e_n)·~~I_i⁻¹(~r_i × e_n)$ the effective inverse mass of body $i$ at the "
            "contact point along $e_n$, $~r_i = O - C_i$ (about the pivot $E$ for a pinned body, without $1/m_i$; 0 "
            "for a body the impulse cannot move)."));

    std::vector<math_row> steps;
    const contact_frame_view view = contact_frame_view_of(d);
    for (const step &st : s.steps) {
        math_row r = row(st.sym, view.apply(st.value));
        r.note = step_note(d.prob, st);
        steps.push_back(r);
    }
    sec.para(paragraph().w("The steps, in order:"));
    if (particles) // short steps: each with its note beside it
        sec.packed_rows(steps);
    else
        sec.rows(steps);
    std::vector<math_row> unknowns;
    for (const frame_component &u : view.unknowns) // their meanings: the set-up's list
        unknowns.push_back(row(u.sym, view.apply(u.world.subs(s.unknown_values))));
    sec.para(paragraph().w("Each unknown (as listed in the set-up):"));
    sec.packed_rows(unknowns);
    return sec;
}
namespace
{

// In the contact frame, the centre-of-mass velocities before and after impact, with notes.
void frame_velocity_rows(section &sec, const derivation &d, const solution &s, const ex &values, const lst &steps)
{
    const problem &p = d.prob;
    std::vector<std::pair<std::string, vec3>> dirs;
    dirs.push_back({"t", d.e_t});
    dirs.push_back({"n", d.n_hat});
    if (p.dimension == 3)
        dirs.push_back({"b", d.e_b});
    std::vector<math_row> frame_rows;
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        if (i != p.contact().body1 && i != p.contact().body2)
            continue;
        const vec3 v0 = subs(p.bodies[i].velocity, values);
        vec3 v1 = subs(s.after[i].velocity, values);
        for (ex &c : v1)
            c = c.subs(steps);
        for (const auto &[axis, e] : dirs) {
            // roots merged before and after normal(), which keeps sqrt(3) sqrt(6) apart
            auto exact = [](const ex &x) { return surd_form(impactgen::tidy(merge_roots(tidy_expand(x)))); };
            const ex before = exact(dot(v0, e)), after = exact(dot(v1, e));
            const std::string &L = p.bodies[i].label;
            math_row r = row(show(quantity_name("v", axis, L, false), quantity_tex("v", axis, L, false)), before);
            math_row ra = row(show(quantity_name("v", axis, L, true), quantity_tex("v", axis, L, true)), after);
            // "≈ 0.914 m/s -- body 1 (ball), before", as the energies below
            const std::string u = unit(p, quantity::velocity);
            auto note = [&](const ex &value, const char *when) {
                paragraph q = decimal_note(value);
                const bool dec = !q.spans.empty();
                return q.w((dec ? u + " -- " : "") + body_ref(p, i) + when +
                           (!dec && !u.empty() ? " (in" + u + ")" : ""));
            };
            r.note = note(before, ", before");
            ra.note = note(after, ", after");
            if (axis == "t" || axis == "b")
                ra.note.t(vanishes_identically(s, after - before, "a tangential velocity")
                              ? ": unchanged, no impulse along it"
                              : "");
            frame_rows.push_back(r);
            frame_rows.push_back(ra);
        }
    }
    sec.para(
        paragraph().t("In the contact frame, the centre-of-mass velocities before and after impact ($v_t = ~v_C·e_t$, "
                      "$v_n = ~v_C·e_n$):"));
    sec.rows(frame_rows);
}

// The kinetic energy before and after, with the loss from the steps.
void energy_rows(section &sec, const derivation &d, const solution &s, const ex &values, const lst &steps)
{
    const ex before = impactgen::tidy(s.energy_before.subs(values));
    const ex lost = impactgen::tidy(s.energy_lost.subs(values).subs(steps));
    if (is_a<numeric>(before) && is_a<numeric>(lost)) {
        const ex after = impactgen::tidy(before - lost);
        math_row t0 = row(show("T", "T"), before, "", decimal_note(before));
        math_row t1 = row(show("T'", "T'"), after, "", decimal_note(after));
        math_row tl = row(show("T_lost", "T_{\\mathrm{lost}}"), lost, "", decimal_note(lost));
        for (math_row *r : {&t0, &t1, &tl})
            r->note.w(unit(d.prob, quantity::energy));
        t0.note.w(" -- kinetic energy before impact");
        t1.note.w(" -- after impact");
        tl.note.w(" -- lost");
        sec.para(paragraph().w("The kinetic energy of the bodies of finite mass:"));
        sec.rows({t0, t1, tl});
    }
}

// Whether every equation holds with the numbers substituted back.
void residuals_verdict(section &sec, const derivation &d, const solution &s, const ex &values)
{
    bool all_zero = true, all_small = true;
    for (const ex &r : residuals(d, s, values)) {
        if (r.is_zero())
            continue;
        all_zero = false;
        // a 60-digit float residual of an irrational problem: zero to 40 digits
        const bool small = is_a<numeric>(r) && abs(ex_to<numeric>(r)) < numeric(1, 10).power(40);
        all_small = all_small && small;
    }
    const std::string range = "(1)-(" + d.equations.back().label + ")";
    sec.para(paragraph().w(all_zero    ? "Substituted back, every equation " + range + " holds exactly."
                           : all_small ? "Substituted back, every equation " + range +
                                             " holds to 40 digits (evaluated with 60-digit floats: with these "
                                             "irrational numbers exactness is not decided)."
                                       : "Substituted back, SOME EQUATION DOES NOT HOLD: this is a bug."));
}

// Exact numbers for every step and unknown, with the equations as numbers.
void numbers_walk(section &sec, const derivation &d, const solution &s, const ex &values)
{
    lst steps = s.step_values(values);
    std::vector<math_row> eqs;
    const contact_frame_view view = contact_frame_view_of(d);
    const lst frame_values = view.with_inputs(values);
    for (const framed_equation &f : view.equations)
        eqs.push_back(
            row(tidy_expand(f.lhs.subs(frame_values)), tidy_expand(f.rhs.subs(frame_values)), f.source->label));
    sec.para(paragraph().w("The equations with these numbers:"));
    sec.rows(eqs);
    std::vector<math_row> rows;
    for (std::size_t i = 0; i < s.steps.size(); ++i) {
        // The step's formula with the inputs substituted, then its number.
        ex formula = s.steps[i].value.subs(values);
        ex v = surd_form(impactgen::tidy(steps.op(i).rhs()));
        math_row out = row(s.steps[i].sym, v, "", decimal_note(v));
        out.note.w(step_unit(d.prob, s.steps[i].role)); // issue 25, defect 9: units on every step
        if (!is_a<numeric>(formula) && printable(formula)) {
            out.rhs = formula;
            out.has_then = true;
            out.then = v;
        }
        rows.push_back(out);
    }
    sec.para(paragraph().w("Step by step (each step with the numbers of the earlier ones):"));
    sec.rows(rows);
    lst unknown_numbers;
    std::vector<math_row> answers;
    for (std::size_t i = 0; i < d.unknowns.size(); ++i) {
        ex v = surd_form(impactgen::tidy(s.unknown_values.op(i).rhs().subs(values).subs(steps)));
        unknown_numbers.append(d.unknowns[i].sym == v);
        math_row r = row(d.unknowns[i].sym, v, "", decimal_note(v));
        const unknown_kind kind = d.unknowns[i].kind;
        r.note.w(unit(d.prob, kind == unknown_kind::velocity           ? quantity::velocity
                              : kind == unknown_kind::angular_velocity ? quantity::angular_velocity
                                                                       : quantity::impulse));
        answers.push_back(r);
    }
    sec.para(paragraph().w("The unknowns:"));
    sec.rows(answers);

    // Contact-frame components, where the frame is not the world's: the smooth-contact
    // equations then read v′_t = v_t, as in the notes.
    if (!d.frame_is_world && d.prob.axes[0] != "t")
        frame_velocity_rows(sec, d, s, values, steps);

    // The energy before and after, with the loss from the steps.
    energy_rows(sec, d, s, values, steps);
    residuals_verdict(sec, d, s, values);
}

// The centre of percussion of a pinned body in plane motion: where the contact
// impulse must act for the pin to take none along e_n. With d = C - E and the
// lever arms c = (d × n)_z of C and s = ((O - E) × n)_z of the impulse about E, the
// body's angular impulse about E gives I_E Δω = s N and its momentum along n
// m c Δω = N + R·n; so R·n = N (m c s / I_E - 1), zero when s = I_E/(m c).
void percussion(section &sec, const derivation &d, const solution &s)
{
    const problem &p = d.prob;
    if (p.dimension != 2)
        return;
    for (const pivot &pv : p.pivots) {
        const body &b = p.bodies[pv.body];
        if (b.particle || b.infinite_mass)
            continue;
        const vec3 dC = b.position - pv.point, dO = p.contact().point - pv.point;
        const ex c = impactgen::tidy(dC[0] * d.n_hat[1] - dC[1] * d.n_hat[0]);
        const ex lever = impactgen::tidy(dO[0] * d.n_hat[1] - dO[1] * d.n_hat[0]);
        const ex IE = impactgen::tidy(b.inertia[2][2] + b.mass * (dC[0] * dC[0] + dC[1] * dC[1]));
        if (c.is_zero())
            continue;
        const ex star = impactgen::tidy(IE / (b.mass * c));
        sec.para(paragraph()
                     .t("Centre of percussion of ")
                     .w(body_ref(p, pv.body))
                     .t(": about its pivot $E$ the angular impulse gives $I_E Δω = s N$ and its momentum along $e_n$ "
                        "gives "
                        "$m c Δω = ± N + R_n$, with $c$ and $s$ the lever arms of $C$ and of the impulse about $E$. So "
                        "the pin takes no impulse along $e_n$ when the impulse acts at the distance $s* = I_E/(m c)$ "
                        "from "
                        "$E$ "
                        "(the centre of percussion; its part along $e_t$, $m Δω (e_b × ~r_EC)·e_t$, is zero when the "
                        "line "
                        "from $E$ to $C$ is perpendicular to $e_n$):"));
        math_row rc = note_row("c = ((C - E) × e_n)·e_b",
                               "c = ((C - E) \\times \\hat{\\underline{e}}_n)\\cdot\\hat{\\underline{e}}_b", c);
        math_row rs = note_row("s = ((O - E) × e_n)·e_b",
                               "s = ((O - E) \\times \\hat{\\underline{e}}_n)\\cdot\\hat{\\underline{e}}_b", lever);
        rs.note.w("the lever arm of the impulse in this problem");
        math_row rstar = note_row("s*", "s^{*}", star);
        rstar.note.w(vanishes_identically(s, lever - star, "the centre of percussion")
                         ? "the impulse acts at the centre of percussion: the pin takes no impulse along the normal"
                         : "the impulse acts elsewhere, so the pin takes an impulse along the normal");
        sec.rows({rc, rs, rstar});
    }
}
} // namespace

namespace
{

// Two particles: no rotational inertia to speak of.
bool particles(const problem &p)
{
    return p.bodies[p.contact().body1].particle && p.bodies[p.contact().body2].particle;
}

// The limits of e: the plastic and the elastic impulse.
void limits_of_e(section &sec, const derivation &de, const ex &N, const ex &N_val, const symbol &e_sym, const ex &u)
{
    ex sep_symbolic = -e_sym * u;
    sec.para(paragraph()
                 .t("The limits of $e$, in the normal impulse and the normal velocity of separation $(~v′_B - "
                    "~v′_A)·e_n = -e u$ (equation ")
                 .ref(de.equations.back().label)
                 .w("):"));
    std::vector<math_row> lim;
    math_row r0 = row(N, N_val.subs(e_sym == 0), "e = 0");
    r0.note.t("plastic: the contact points move on together, $(~v′_B - ~v′_A)·e_n$ = ")
        .m(sep_symbolic.subs(e_sym == 0));
    math_row r1 = row(N, N_val.subs(e_sym == 1), "e = 1");
    r1.note.t("elastic: twice the plastic impulse, $(~v′_B - ~v′_A)·e_n$ = ")
        .m(sep_symbolic.subs(e_sym == 1))
        .t(" = $|u|$, the contact points separate as fast as they approached");
    lim.push_back(r0);
    lim.push_back(r1);
    sec.rows(lim);
}

// m2 -> infinity: the notes' massive case as body 2 grows heavy.
void heavy_body_limit(section &sec, const problem &p, const solution &se, const symbol &e_sym, const ex &u, const ex &N)
{
    const std::size_t i2 = p.contact().body2;
    const body &b2 = p.bodies[i2];
    if (b2.infinite_mass) {
        sec.para(paragraph().t("$m2 → ∞$: body 2 already has infinite mass; the notes' massive case, $w_2 = 0$ and $N "
                               "= -(1 + e) u/w_1$."));
    } else if (p.immovable(i2)) {
        sec.para(paragraph().t("$m2 → ∞$: body 2 cannot move under the impulse already ($w_2 = 0$)."));
    } else if (p.immovable(p.contact().body1)) {
        // Body 1 already cannot move: making body 2 heavy too would leave nothing to move.
        sec.para(paragraph().t(
            "$m2 → ∞$ is not taken here: body 1 cannot move under the impulse already ($w_1 = 0$), so this is "
            "the notes' massive case with the bodies' roles exchanged, $N = -(1 + e) u/w_2$; were body 2 "
            "infinitely heavy as well, nothing could move."));
    } else {
        // Body 2 grows heavy with its shape kept: m2 -> m2/eps, I_2 -> I_2/eps. Its
        // effective inverse mass scales exactly: w_2(eps) = eps w_2 (1/m and I^-1
        // both scale with eps, about C or about the pivot alike), so with
        // k = w_1 + eps w_2 the impulse tends to the notes' massive case and body
        // 2's velocity change N n eps/m2 tends to zero. No symbolic limit is
        // taken (normal() of a 3-D closed form has no useful time bound).
        const step *w1 = find_step(se, step_role::effective_inverse_mass, p.contact().body1);
        const ex w1_value =
            w1 ? ex(w1->sym) : (p.immovable(p.contact().body1) ? ex(0) : 1 / p.bodies[p.contact().body1].mass);
        paragraph q;
        if (particles(p) && !w1_value.is_zero()) { // two particles: the limit in one sentence
            q.t("$m2 → ∞$: $w_2 = 1/m2 → 0$, so $N → -(1 + e) u/w_1$, the notes' massive case, and the change "
                "of body 2's velocity, $N/m2$, tends to 0: body 2 is unaffected.");
            sec.para(q);
            return;
        }
        q.t("$m2 → ∞$: let body 2 grow heavy with its shape kept, $m2 → m2/ε$ and its inertia $~~I → ~~I/ε$, and "
            "take $ε → 0$. Both $1/m2$ and $~~I⁻¹$ scale with $ε$, so $w_2 → ε w_2$ exactly and "
            "$k → w_1 + ε w_2$:");
        sec.para(q);
        std::vector<math_row> rows;
        math_row rw = row(show("w_2", "w_2"), 0, "", "body 2 no longer yields at B");
        rw.rel = "→";
        rows.push_back(rw);
        if (!w1_value.is_zero()) {
            ex N_inf = -(1 + e_sym) * u / w1_value;
            math_row rn = row(N, N_inf);
            rn.note.t("finite: the notes' massive case, $N = -(1 + e) u/w_1$");
            rn.rel = "→";
            rows.push_back(rn);
            math_row rv = note_row("|v′_C2 - v_C2|²", "|\\underline{v}'_{C_2} - \\underline{v}_{C_2}|^2", 0);
            rv.note.t("$~ω′_2 ≈ ~ω_2$ and $~v′_C2 ≈ ~v_C2$: body 2 is unaffected (its change $N ε/m2 → 0$)");
            rv.rel = "→";
            rows.push_back(rv);
        }
        sec.rows(rows);
    }
}

// The numbers: a numeric problem's, or a worked example's substituted.
void numbers_part(section &sec, const derivation &d, const solution &s, const worked_example *example)
{
    const problem &p = d.prob;
    if (p.is_numeric()) {
        sec.para(paragraph().w("The problem is numeric: every step and unknown above is an exact number."));
        numbers_walk(sec, d, s, lst{});
    } else if (example) {
        if (example->problem_numbers)
            sec.para(paragraph().w("The problem's numbers: substitute"));
        else
            sec.para(paragraph().w("Worked example (" + example->caption + "): substitute"));
        std::vector<math_row> vals;
        for (std::size_t k = 0; k < example->values.nops(); ++k) {
            const ex rel = example->values.op(k);
            math_row r = row(rel.lhs(), rel.rhs());
            if (k < example->units.size())
                r.note.w(example->units[k]);
            vals.push_back(r);
        }
        sec.rows(vals);
        numbers_walk(sec, d, s, example->values);
    }
}

// The energy checks: the loss as the work of the contact impulse, its textbook form, and at e = 1.
void energy_checks(section &sec, const problem &p, const derivation &de, const solution &se, const symbol &e_sym,
                   const ex &u, const step *u_step, const ex &kk, const ex &lost, const std::vector<step_role> &core)
{
    sec.para(paragraph().w("Kinetic energy lost (bodies of finite mass), the work of the contact impulse:"));
    std::vector<math_row> energy;
    const step *lost_step = find_step(se, step_role::energy_lost);
    ex textbook = kk.is_zero() ? ex(0) : (1 - e_sym * e_sym) * pow(u, 2) / (2 * kk);
    bool textbook_ok =
        !kk.is_zero() && u_step && vanishes_identically(se, lost - expand_some(se, textbook, core), "the energy check");
    if (lost_step && !textbook_ok) // else the step (section 4) is not repeated: its textbook form follows
        energy.push_back(row(lost_step->sym, lost_step->value));
    if (textbook_ok && lost_step) {
        math_row r = row(lost_step->sym, textbook);
        r.note.t("with $N = -(1 + e) u/k$ substituted and simplified: $1 - e² ≥ 0$ and $k > 0$, so $T_lost ≥ 0$");
        energy.push_back(r);
    }
    ex at_one = impactgen::tidy(lost.subs(e_sym == 1));
    // Against a moving body of infinite mass the loss at e = 1 is not zero. Expanded it runs
    // over lines (massive-3d: 17 terms); through the named steps it is short: with N = -2u/k,
    // T_lost = -2 u v_Bn/k when body 2 has the infinite mass (v_Bn = v_B·e_n, its contact
    // point's normal velocity), +2 u v_An/k when body 1 has. Shown when it checks out.
    std::vector<math_row> named_at_one;
    if (lost_step && !at_one.is_zero() && u_step && !kk.is_zero()) {
        const bool two = p.bodies[p.contact().body2].infinite_mass, one = p.bodies[p.contact().body1].infinite_mass;
        if (two != one) {
            const ex vn = impactgen::tidy(tidy_expand(dot(two ? de.vB : de.vA, de.n_hat)));
            const symbol vn_sym = two ? symbol("v_Bn", "v_{Bn}") : symbol("v_An", "v_{An}");
            const ex form = (two ? -2 : 2) * u * vn_sym / kk;
            bool holds = false;
            try {
                holds = vanishes_identically(se, lost.subs(e_sym == 1) - form.subs(vn_sym == vn), "the loss at e = 1");
            } catch (const std::exception &) {
                holds = false;
            }
            if (holds && printable(vn, 120)) {
                math_row r = row(lost_step->sym, form);
                r.note.t(two ? "at $e = 1$ (the impulse twice the plastic one): the work of the moving body of "
                               "infinite mass, "
                               "whose contact point $B$ has the normal velocity"
                             : "at $e = 1$ (the impulse twice the plastic one): the work of the moving body of "
                               "infinite mass, "
                               "whose contact point $A$ has the normal velocity");
                named_at_one.push_back(r);
                named_at_one.push_back(row(vn_sym, vn));
            }
        }
    }
    if (lost_step && !named_at_one.empty()) {
        for (const math_row &r : named_at_one)
            energy.push_back(r);
    } else if (lost_step) {
        math_row r = row(lost_step->sym, at_one);
        r.note.t(at_one.is_zero() ? "at $e = 1$: the elastic impact conserves kinetic energy" : "at $e = 1$");
        energy.push_back(r);
    }
    sec.rows(energy);
    sec.para(paragraph().t(particles(p) ? "The energy before impact is $T = Σ 1/2 m |~v_C|²$ over the bodies of "
                                          "finite mass, and after it $T′ = T - T_lost$."
                                        : "The energy before impact is $T = Σ (1/2 m |~v_C|² + 1/2 ~ω·~~I_C ~ω)$ "
                                          "over the bodies of finite mass, and after it $T′ = T - T_lost$."));
    if (!at_one.is_zero())
        sec.para(paragraph().t(
            "At $e = 1$ the loss is not zero: a moving body of infinite mass does work on the other body, and "
            "its own energy is not counted."));
}

} // namespace

section detail::checks_section(const derivation &d, const solution &s, const worked_example *example)
{
    const problem &p = d.prob;
    section sec{"Checks", {}};

    // A copy of the problem with a symbol for e, to vary e.
    ex e_val = p.restitution;
    symbol e_sym = is_a<symbol>(e_val) ? ex_to<symbol>(e_val) : symbol_named("e");
    problem pe = p;
    pe.restitution = e_sym;
    derivation de = is_a<symbol>(e_val) ? d : derive(pe);
    solution se = is_a<symbol>(e_val) ? s : solve(de);
    if (!is_a<symbol>(e_val))
        sec.para(paragraph()
                     .t("To vary $e$, the checks below keep $e$ as a symbol; the problem has $e$ = ")
                     .m(e_val)
                     .w("."));

    const std::vector<step_role> core = {step_role::energy_lost, step_role::normal_impulse,
                                         step_role::contact_inverse_mass, step_role::approach_velocity};
    ex lost = expand_some(se, se.energy_lost, core);
    const step *u_step = find_step(se, step_role::approach_velocity);
    const step *k_step = find_step(se, step_role::contact_inverse_mass);
    const step *N_step = find_step(se, step_role::normal_impulse);
    ex N_val = N_step ? N_step->value : ex(se.normal_impulse);
    ex u = u_step ? ex(u_step->sym) : ex(0);
    // k as N's formula has it: w_1 + w_2, or w_1 alone against an infinite mass.
    ex kk = k_step ? ex(k_step->sym) : (u_step ? impactgen::tidy(-(1 + e_sym) * u / N_val) : ex(0));

    // Energy.
    energy_checks(sec, p, de, se, e_sym, u, u_step, kk, lost, core);

    // Limits of e.
    ex N = se.normal_impulse;
    limits_of_e(sec, de, N, N_val, e_sym, u);

    heavy_body_limit(sec, p, se, e_sym, u, N);

    percussion(sec, d, s);

    numbers_part(sec, d, s, example);
    return sec;
}

} // namespace impactgen::print
