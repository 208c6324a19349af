// explain_friction(): the walk-through of an impact with Coulomb friction, the
// way textbooks solve it: the contact law, impulse-momentum with the tangential
// impulse, the contact response K, assume sticking and test it against the
// friction cone, else slide; the regime boundaries in mu, the energy, when the
// law has one solution, and for a numeric problem every number and the regime
// that holds. Built from solve_friction()'s closed forms (symbolic/friction.hpp);
// every formula is a GiNaC expression printed by the canonical printer.
#include "explain.hpp"
#include "explain_detail.hpp"
#include "explain_friction_detail.hpp"
#include "formulas.hpp"

#include "canonical.hpp"
#include "expression.hpp"
#include "symbolic/decide.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>

namespace impactgen::print
{
using namespace GiNaC;
using namespace detail;

namespace friction_detail
{

// ---------------------------------------------------------------- 2. the law

section law_section(const context &c)
{
    const problem &p = c.p;
    section sec{"The contact law: restitution and Coulomb friction", {}};
    std::vector<paragraph> items;
    items.push_back(
        paragraph()
            .w("The contact impulse on " + body_ref(p, c.i2))
            .t(" is $~P = N e_n + ~F$, and on ")
            .w(body_ref(p, c.i1))
            .t(" it is $-~P$ (action and reaction): $N ≥ 0$ is the normal impulse, $~F$ the friction impulse, "
               "tangential (normal to $e_n$)."));
    items.push_back(paragraph().t(
        "Newton's law of restitution acts on the normal relative velocity of the contact points, exactly as "
        "without friction: $u′_n = -e u_n$, with $u = v_B - v_A$ and $u_n = u·e_n < 0$ for an impact."));
    items.push_back(
        paragraph().t("Coulomb's law bounds the friction impulse by the cone $|F| ≤ μN$, and there are two regimes:"));
    items.push_back(paragraph().t(
        "stick: the contact points leave with no relative tangential velocity, $u′_t = 0$, with any $F$ inside "
        "the cone;"));
    items.push_back(
        paragraph().t("slide: $u′_t ≠ 0$, and friction is at its limit and opposes the sliding of $B$ relative to A: "
                      "$F = -μN u′_t/|u′_t|$."));
    other_impulses(items, p, "$~P$");
    sec.list(items);
    sec.rows({formula_row(
                  "P = N e_n + F,   |F| ≤ μ N",
                  "\\underline{P} = N\\,\\hat{\\underline{e}}_n + \\underline{F},\\quad |\\underline{F}| \\le \\mu N",
                  "the contact impulse on body 2 and Coulomb's cone"),
              formula_row("u′_n = -e u_n", "u'_n = -e\\,u_n", "restitution: the normal velocity of separation"),
              formula_row("stick: u′_t = 0", "\\text{stick: } \\underline{u}'_t = \\underline{0}", "needs $|~F| ≤ μN$"),
              formula_row("slide: F = -μ N u′_t/|u′_t|",
                          "\\text{slide: } \\underline{F} = -\\mu N\\,\\underline{u}'_t/|\\underline{u}'_t|",
                          "needs $~u′_t ≠ 0$, in the direction $~d = ~u′_t/|~u′_t|$")});
    sec.para(paragraph().w(
        "This is the algebraic law of textbooks (Newton's restitution with Coulomb friction at the level of impulses): "
        "the friction impulse has one direction for the whole impact. A contact whose sliding stops or turns "
        "during the impact needs the impact to be followed through its duration (Routh's method); the answer "
        "here is the one the law gives."));
    return sec;
}

// ---------------------------------------------------------------- 3. the equations

// The words before a group of equations: its principle, for its body, with the friction impulse.
paragraph friction_group_why(const context &c, const equation &first, principle why)
{
    const problem &p = c.p;
    std::string title = why == principle::linear_impulse ? "Linear impulse-momentum" : principle_name(why);
    title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(title[0])));
    const std::size_t i = first.bodies.empty() ? c.i1 : first.bodies[0];
    const std::string who = display_name(p.bodies[i]);
    const pivot *pv = p.pivot_of(i);
    paragraph q;
    q.w(title + ": ");
    switch (why) {
    case principle::linear_impulse:
        q.w("the change of linear momentum of " + who + " equals the impulses on it: ")
            .t(i == c.i1 ? "$-~P = -(N e_n + ~F)$" : "$~P = N e_n + ~F$")
            .t(pv ? " and the pivot impulse $~R$" : "")
            .w("; with friction the tangential components change too.");
        break;
    case principle::angular_momentum:
        if (pv)
            q.t("about the pivot $E$, fixed in the inertial frame, the pivot impulse has no moment: the change of "
                "angular "
                "momentum of ")
                .w(who)
                .t(" about $E$ is the moment $(O - E) × ~P$ of the contact impulse, its friction part included.");
        else
            q.w("the whole contact impulse on " + who)
                .t(", normal and friction part alike, acts at $O$, which is fixed in the inertial frame: it has no "
                   "moment "
                   "about $O$, so the angular momentum of ")
                .w(who)
                .t(" about $O$ is conserved, with friction as without.");
        break;
    case principle::pivot_fixed:
        q.t("the pivot $E$ of ").w(who).t(" does not move: $~v′_C + ~ω′ × ~r_CE = 0$.");
        break;
    case principle::restitution:
        q.t("Newton's coefficient of restitution: the normal velocity of separation of the contact points is $e$ "
            "times "
            "their velocity of approach.");
        break;
    default:
        q.w(first.reason + ".");
    }
    return q;
}

// Coulomb's law in each regime: stick along each tangent, then slide.
std::vector<math_row> coulomb_law_rows(const context &c)
{
    std::vector<math_row> law;
    for (std::size_t t = 0; t < c.stick_law.size(); ++t) {
        const equation &eq = c.stick_law[t];
        law.push_back(row(eq.lhs, eq.rhs, eq.label, ""));
        law.back()
            .note.t("stick: $(~v′_B - ~v′_A)·$")
            .n("e_" + c.tnames[t], "\\hat{\\underline{e}}_" + c.tnames[t])
            .t(" $= 0$, the contact points leave together along ")
            .n("e_" + c.tnames[t], "\\hat{\\underline{e}}_" + c.tnames[t]);
    }
    if (c.dim == 2) {
        for (int s : {1, -1}) {
            math_row r = row(c.F[0], ex(-s) * c.mu * c.N, c.slide_tag(s));
            r.note.t(s > 0 ? "slide along $+e_t$ ($u′_t > 0$)" : "slide along $-e_t$ ($u′_t < 0$)");
            law.push_back(r);
        }
    } else {
        for (std::size_t t = 0; t < c.slide_law.size(); ++t) {
            math_row r = row(c.slide_law[t].lhs, c.slide_law[t].rhs, c.slide_law[t].label);
            if (t == 0)
                r.note.t(
                    "slide along the unit tangent $~d = (d_t, d_b) = ~u′_t/|~u′_t|$ (components along $e_t$, $e_b$)");
            law.push_back(r);
        }
    }
    return law;
}

section equations_section(const context &c)
{
    const problem &p = c.p;
    section sec{"The equations: impulse-momentum with the friction impulse", {}};
    sec.para(paragraph()
                 .t("With friction the notes' smooth-contact equations fail: they said that no impulse acts along the "
                    "tangent, "
                    "so each body's centre-of-mass velocity along $e_t$")
                 .t(c.dim == 3 ? " and $e_b$" : "")
                 .t(" is unchanged. Now the friction impulse $~F$ acts along the tangent, and $m (~v′_C - ~v_C)·e_t = "
                    "±~F·e_t$. "
                    "So impulse-momentum is written for each body with the impulses $N$ and $~F$ as unknowns."));
    sec.para(paragraph().t(
        "Angular momentum needs no change: the contact impulse $P$, friction part included, acts at the contact point "
        "$O$, "
        "so each free body's angular momentum about $O$ is still conserved (a pinned body's about its pivot $E$ "
        "changes by "
        "the moment of $P$ about $E)$. What friction changes is the linear momentum along the tangent, and the moment "
        "about the centre of mass: $I_C (ω′ - ω) = r × P$ now has a part $r × F$ from the friction impulse."));
    // Grouped by principle and bodies; the words come from those (typed), not from the ASCII reason.
    std::size_t k = 0;
    while (k < c.eqs.size()) {
        const equation &first = c.eqs[k];
        const principle why = first.why;
        std::vector<math_row> rows;
        std::size_t j = k;
        for (; j < c.eqs.size() && c.eqs[j].bodies == first.bodies && c.eqs[j].why == why; ++j) {
            const equation &eq = c.eqs[j];
            math_row r = row(eq.lhs, eq.rhs, eq.label);
            if (eq.component >= 0)
                along(r.note.w("component along "), p.axes[static_cast<std::size_t>(eq.component)]);
            rows.push_back(r);
        }
        sec.para(friction_group_why(c, first, why));
        sec.rows(rows);
        k = j;
    }
    sec.para(paragraph().w("Coulomb's law gives the remaining " + std::to_string(c.tangents.size()) +
                           (c.tangents.size() == 1 ? " equation" : " equations") + ", different in each regime:"));
    std::vector<math_row> law = coulomb_law_rows(c);
    sec.rows(law);
    const std::size_t n_eq = c.eqs.size() + c.tangents.size();
    std::size_t n_unknowns = c.d.count_unknowns() + c.F.size() + (c.d.impulse_form ? 0 : 1);
    sec.para(paragraph()
                 .w(std::to_string(n_eq) + " equations for " + std::to_string(n_unknowns) +
                    " unknowns: " + (n_eq == n_unknowns ? "the count matches" : "THE COUNT DOES NOT MATCH") +
                    " in either regime; which regime holds is decided by inequalities: stick needs ")
                 .t("$|F| ≤ μN$, slide needs the contact to slide the way friction assumed."));
    return sec;
}

// ---------------------------------------------------------------- 4. the contact response

section response_section(const context &c)
{
    const problem &p = c.p;
    section sec{"The contact response K", {}};
    sec.para(paragraph().t(
        "Every equation is linear in the impulse. Solve each body's equations for its velocities in terms of $P$ and "
        "put them into the velocities of the contact points: the relative velocity $u = v_B - v_A$ then changes "
        "linearly with $P$, through a symmetric matrix $K$, the contact response (the inverse of an effective mass):"));
    std::vector<math_row> rows;
    rows.push_back(
        formula_row("u′ = u + K P,   K = K_1 + K_2",
                    "\\underline{u}' = \\underline{u} + \\underline{\\underline{K}}\\,\\underline{P},\\quad "
                    "\\underline{\\underline{K}} = \\underline{\\underline{K}}_1 + \\underline{\\underline{K}}_2",
                    "u′ - u is the velocity change of B minus that of A; body 1 receives -P"));
    for (std::size_t i : {c.i1, c.i2}) {
        const body &b = p.bodies[i];
        const std::string who = body_ref(p, i);
        if (p.immovable(i))
            rows.push_back(
                formula_row("K_" + std::string(i == c.i1 ? "1" : "2") + " = 0",
                            "\\underline{\\underline{K}}_" + std::string(i == c.i1 ? "1" : "2") + " = 0",
                            paragraph().w(who + (b.infinite_mass ? ": infinite mass, the impulse cannot move it"
                                                                 : ": a particle pinned at a fixed point"))));
        else if (p.pivot_of(i))
            rows.push_back(formula_row(
                "K_i P = (I_E⁻¹(ρ × P)) × ρ,   ρ = O - E",
                "\\underline{\\underline{K}}_i\\underline{P} = "
                "(\\underline{\\underline{I}}_E^{-1}(\\underline{\\rho}\\times\\underline{P}))\\times\\underline{\\rho}"
                ",\\quad \\underline{\\rho} = O - E",
                paragraph().w(who).t(": it can only turn about its pivot $E$ ($~~I_E$ its inertia about $E$)")));
        else if (b.particle)
            rows.push_back(formula_row("K_i P = P/m_i",
                                       "\\underline{\\underline{K}}_i\\underline{P} = \\underline{P}/m_i",
                                       paragraph().w(who + ": a particle")));
        else
            rows.push_back(
                formula_row("K_i P = P/m_i + (I_i⁻¹(r_i × P)) × r_i,   r_i = O - C_i",
                            "\\underline{\\underline{K}}_i\\underline{P} = \\underline{P}/m_i + "
                            "(\\underline{\\underline{I}}_i^{-1}(\\underline{r}_i\\times\\underline{P}))"
                            "\\times\\underline{r}_i,\\quad \\underline{r}_i = O - C_i",
                            paragraph().w(who).t(
                                ": a free rigid body, translation plus the rotation the moment $~r_i × ~P$ gives")));
    }
    sec.rows(rows);
    if (c.has_stick())
        sec.para(paragraph().t(
            "$K$ is symmetric and positive definite (each $K_i$ is the velocity response of a body to an impulse: "
            "$P·K P > 0$ is twice the kinetic energy a unit impulse gives). Its entries in world components, then "
            "the relative velocity before impact, through named steps:"));
    else
        sec.para(paragraph().t(
            "$K$ is symmetric and positive semi-definite ($P·K P ≥ 0$ is twice the kinetic energy a unit impulse "
            "gives). Here it is singular, $det K = 0$: the only body that can move turns about a fixed pivot, so its "
            "contact point can only move across the line from the pivot, and an impulse along that line moves "
            "nothing. Its entries in world components, then the relative velocity before impact, through named "
            "steps:"));
    std::vector<math_row> steps;
    const auto &st = c.f.shared.steps;
    for (std::size_t k = 0; k < c.shared; ++k)
        steps.push_back(srow(c.p, st[k]));
    sec.rows(steps);
    sec.para(paragraph().t(
        "$u_n < 0$: the contact points approach. Its tangential part $u_t = u - u_n e_n$ is the velocity with which "
        "$B$ slides over A before impact."));
    return sec;
}

// ---------------------------------------------------------------- 5. stick

// F/N of the stick impulse in the contact frame with print-only symbols, and the threshold.
struct planar_frame {
    symbol Ktt{"K_tt", "K_{tt}"}, Ktn{"K_tn", "K_{tn}"}, Knn{"K_nn", "K_{nn}"}, ut{"u_t", "u_{t}"}, un{"u_n", "u_{n}"},
        DK{"D_K", "D_{K}"};
};

ex stick_threshold_value(const context &c)
{
    const regime_case &st = c.stick();
    if (c.dim == 2)
        return abs(st.tangential_scalar) / st.sol.normal_impulse;
    const ex Ft = tidy(dot(st.impulse, c.f.e_t)), Fb = tidy(dot(st.impulse, c.f.e_b));
    return sqrt(pow(Ft, 2) + pow(Fb, 2)) / st.sol.normal_impulse;
}

// The notes write -(u + e u_n e_n) along e_n as -(1 + e) u_n: every sum that equals (1 + e) u_n
// printed so (the value is the same; the step is not changed, nor the generated code).
ex with_one_plus_e(const ex &x, const ex &e, const ex &un)
{
    if (un.is_zero() || !is_a<symbol>(e))
        return x;
    struct fold : map_function {
        ex e, un;
        fold(const ex &ee, const ex &uu) : e(ee), un(uu) {}
        ex operator()(const ex &y) override
        {
            if (is_a<add>(y) && y.nops() == 2 && (y - (1 + e) * un).expand().is_zero())
                return (1 + e) * un;
            return y.map(*this);
        }
    } f(e, un);
    return f(x);
}

// The rolling remark: a body of infinite mass at rest, so the other body's contact point leaves at rest.
void rolling_remark(section &sec, const context &c)
{
    for (std::size_t i : {c.i1, c.i2}) {
        const std::size_t other = i == c.i1 ? c.i2 : c.i1;
        const body &b = c.p.bodies[i];
        if (b.infinite_mass && b.at_rest() && !c.p.bodies[other].particle) {
            paragraph q;
            q.w("Here " + body_ref(c.p, i))
                .t(" is at rest and cannot move, so $~u′_t = 0$ means that the contact point of ")
                .w(body_ref(c.p, other) + " leaves at rest: it rolls without slipping, equation ")
                .ref(c.stick_law[0].label)
                .w(": ");
            q.m(c.stick_law[0].lhs).t(" $= 0$.");
            sec.para(q);
        }
    }
}

// The planar threshold μ* in the contact frame, and with this problem's K and inputs when short.
void planar_threshold_rows(const context &c, const regime_case &st, const ex &mu_star, std::vector<math_row> &thr)
{
    planar_frame k;
    const ex one_e = 1 + c.e;
    // D_K F = (1 + e) K_tn u_n - K_nn u_t,  D_K N = K_tn u_t - (1 + e) K_tt u_n
    const ex num = k.Knn * k.ut - one_e * k.Ktn * k.un, den = k.Ktn * k.ut - one_e * k.Ktt * k.un;
    thr.push_back(
        formula_row("μ* = |K_nn u_t - (1 + e) K_tn u_n| / (K_tn u_t - (1 + e) K_tt u_n)",
                    "\\mu^{*} = \\frac{|K_{nn} u_t - (1 + e) K_{tn} u_n|}{K_{tn} u_t - (1 + e) K_{tt} u_n}",
                    "in the contact frame: $K_tt = e_t·K e_t$, $K_tn = e_t·K e_n$, $K_nn = e_n·K e_n$, $u_t = ~u·e_t$, "
                    "$u_n = ~u·e_n$ ($D_K$ cancels; $N > 0$ when sticking is possible)"));
    // With this problem's K when its entries are small.
    const vec3 &et = c.d.t_dir;
    const ex kt = c.kform(et, et), ktn = c.kform(et, c.n), kn = c.kform(c.n, c.n);
    const std::vector<step_role> roles = {step_role::contact_response};
    ex kvals[3] = {kt, ktn, kn};
    bool small = true;
    for (ex &v : kvals) {
        v = tidy(st.sol.expand_steps(v));
        small = small && printable(v, 16);
    }
    if (small) {
        ex r = (kvals[2] * k.ut - one_e * kvals[1] * k.un) / (kvals[1] * k.ut - one_e * kvals[0] * k.un);
        r = factored(normal(r));
        const ex shown = abs_split(r, c.e);
        if (printable(shown, 60) && short_denominator(shown) && !(shown - abs(num) / den).is_zero()) {
            math_row mr = row(mu_star, shown);
            mr.note.t("with this problem's $K$: $K_tt$ = ")
                .m(kvals[0])
                .t(", $K_tn$ = ")
                .m(kvals[1])
                .t(", $K_nn$ = ")
                .m(kvals[2]);
            thr.push_back(mr);
        }
    }
    ex ratio = tidy(st.sol.expand_steps(st.tangential_scalar / st.sol.normal_impulse));
    if (!is_constant(ratio) && printable(ratio, 60)) { // factor() is slow on large rational functions
        const ex shown = abs_split(factored(normal(ratio)), c.e);
        if (printable(shown, 80) && short_denominator(shown))
            thr.push_back(row(mu_star, shown, "", "in the inputs"));
    }
}

// A candidate's conditions, one row each: value > 0 or value ≥ 0, with its meaning.
std::vector<math_row> condition_rows(const regime_case &rc)
{
    std::vector<math_row> rows;
    for (const regime_condition &cond : rc.conditions) {
        math_row r = row(cond.value, 0);
        r.note = condition_note(cond);
        r.rel = cond.strict ? ">" : "≥";
        rows.push_back(r);
    }
    return rows;
}

section stick_section(const context &c)
{
    const regime_case &st = c.stick();
    section sec{"Assume sticking", {}};
    sec.para(paragraph().t("Textbooks try sticking first. Then $u′_t = 0$, and restitution gives $u′_n = -e u_n$, so "
                           "$u′ = -e u_n e_n$ and "
                           "$u′ = u + K P$ becomes a linear system for the whole impulse $P$:"));
    sec.rows({formula_row(
        "K P = -(u + e u_n e_n)",
        "\\underline{\\underline{K}}\\,\\underline{P} = -(\\underline{u} + e\\,u_n\\,\\hat{\\underline{e}}_n)",
        "$~P = -K⁻¹(~u + e u_n e_n)$: $K$ is positive definite, so $D_K = det K > 0$")});
    std::vector<math_row> steps;
    for (std::size_t k = c.shared; k < st.sol.steps.size(); ++k) {
        step shown = st.sol.steps[k];
        shown.value = with_one_plus_e(shown.value, c.p.restitution, c.un());
        steps.push_back(srow(c.p, shown));
    }
    sec.rows(steps);
    sec.para(paragraph().t(
        "$μ$ does not appear: the stick impulse does not depend on $μ$. If it sticks, the bodies leave with"));
    std::vector<math_row> unknowns;
    for (std::size_t k = 0; k < c.d.unknowns.size(); ++k)
        if (c.d.unknowns[k].kind != unknown_kind::normal_impulse)
            unknowns.push_back(
                srow(c.d.unknowns[k].sym, st.sol.unknown_values.op(k).rhs(), unknown_note(c.p, c.d.unknowns[k])));
    sec.rows(unknowns);
    rolling_remark(sec, c);
    sec.para(paragraph().t("Test: the stick impulse must lie inside the friction cone, $|F| ≤ μN$:"));
    sec.rows(condition_rows(st));
    sec.para(paragraph().t("As the stick impulse does not depend on $μ$, the test is a condition on $μ$ alone: "
                           "sticking holds exactly when "
                           "the stick impulse pushes $(N > 0)$ and $μ ≥ μ*$, the threshold"));
    std::vector<math_row> thr;
    const ex mu_star = symbol("μ*", "\\mu^{*}");
    thr.push_back(row(mu_star, stick_threshold_value(c), "",
                      c.dim == 2 ? paragraph().t("$|F|/N$ of the stick impulse")
                                 : paragraph().t("$|~F|/N$ of the stick impulse, $~F = ~P - N e_n$")));
    if (!c.can_stick())
        sec.para(paragraph().t(
            "Here the stick impulse pulls $(N ≤ 0$, whatever $μ)$: no $μ$ makes the contact stick, and $μ*$ below is "
            "not a threshold."));
    if (c.dim == 2)
        planar_threshold_rows(c, st, mu_star, thr);
    sec.rows(thr);
    if (c.can_stick())
        sec.para(paragraph().t(
            "If $μ ≥ μ*$ the contact sticks and the answer is above. If $μ < μ*$ the friction the contact would "
            "need exceeds $μN$: it cannot stick, and it slides."));
    else
        sec.para(paragraph().t("Whatever $μ$, the contact cannot stick: only a slide can hold, if any does."));
    return sec;
}

// Section 5 when K is singular: no impulse makes the contact stick.
section no_stick_section(const context &)
{
    section sec{"Sticking is impossible", {}};
    sec.para(paragraph().t(
        "Textbooks try sticking first: $u′_t = 0$ and $u′_n = -e u_n$, so $u′ = -e u_n e_n$, and $u′ = u + K P$ "
        "would be a linear system for $P$:"));
    sec.rows({formula_row(
        "K P = -(u + e u_n e_n)",
        "\\underline{\\underline{K}}\\,\\underline{P} = -(\\underline{u} + e\\,u_n\\,\\hat{\\underline{e}}_n)",
        "$K$ is singular here: the system has no solution")});
    sec.para(paragraph().t(
        "But $K$ is singular: whatever the impulse, the contact point of the pinned body changes its velocity only "
        "across the line from its pivot, so the relative velocity cannot be brought to $-e u_n e_n$ (stopped "
        "along the tangent while it separates along the normal). Sticking is not a solution for any $μ$: the "
        "contact slides, and the slides below are the candidates."));
    return sec;
}

// ---------------------------------------------------------------- 6. slide

// text, then the aside in parentheses when there is one.
paragraph with_aside(paragraph text, const paragraph &aside)
{
    if (!aside.spans.empty()) {
        text.w(" (");
        for (const span &x : aside.spans)
            text.spans.push_back(x);
        text.w(")");
    }
    return text;
}

section slide_section(const context &c)
{
    section sec{c.has_stick() ? "If the test fails: sliding" : "Sliding", {}};
    sec.para(paragraph().t(
        "A sliding contact has friction at its limit, opposite to the sliding: $F = -μN d$, where $d$ is the unit "
        "direction of $u′_t$. The impulse $P = N (e_n - μ d)$ then has one unknown $N$ (once $d$ is known), and "
        "restitution alone gives it:"));
    sec.rows({formula_row(
                  "u′_n = u_n + N e_n·K(e_n - μ d) = -e u_n",
                  "u'_n = u_n + N\\,\\hat{\\underline{e}}_n\\cdot\\underline{\\underline{K}}(\\hat{\\underline{e}}_n - "
                  "\\mu\\,\\underline{d}) = -e\\,u_n"),
              formula_row("N = -(1 + e) u_n / D_s,   D_s = e_n·K(e_n - μ d)",
                          "N = -\\frac{(1 + e)\\,u_n}{D_s},\\quad D_s = "
                          "\\hat{\\underline{e}}_n\\cdot\\underline{\\underline{K}}(\\hat{\\underline{e}}_n - "
                          "\\mu\\,\\underline{d})",
                          "$D_s$ must be positive, else $N$ would not be")});
    sec.para(paragraph().t(
        "Then check that the contact really slides along $d$ after impact: $λ = u′·d > 0$ (the sliding speed)."));
    if (c.dim == 2 && !c.has_stick())
        sec.para(paragraph().t("In the plane $d = +e_t$ or $d = -e_t$, two closed forms; the check $λ > 0$ (with "
                               "$D_s > 0$) decides which holds."));
    else if (c.dim == 2)
        sec.para(paragraph().t(
            "In the plane $d = +e_t$ or $d = -e_t$, two closed forms. The one to try is opposite to the friction the "
            "stick "
            "impulse needed: if its $F < 0$ (friction on body 2 along $-e_t)$ the contact tends to slide along $+e_t$, "
            "usually the direction of $u_t$. The check $λ > 0$ confirms it."));
    else if (c.f.isotropic)
        sec.para(paragraph().t(
            "Here $K$ does not couple the normal to the tangent plane $(K e_n$ is along $e_n)$ and is isotropic in it "
            "(the same for every tangent direction): sliding does not turn the tangential velocity, and "
            "$d = u_t/|u_t|$, the direction of sliding before impact."));
    else
        sec.para(paragraph().t(
            "Here $K$ couples the tangent directions with each other and with the normal, so the contact does not "
            "in general keep sliding the way it came: the sliding direction $d = c_d e_t + s_d e_b$ "
            "$(c_d = cos θ$, $s_d = sin θ)$ is itself unknown, and $u′_t$ along $d$ is one more equation for $θ$."));
    for (std::size_t ci = c.first_slide(); ci < c.f.cases.size(); ++ci) {
        const regime_case &sc = c.f.cases[ci];
        paragraph head;
        if (c.dim == 2)
            head.t(sc.sign > 0 ? "Slide along $+e_t$ ($~d = e_t$, $F = -μN$):"
                               : "Slide along $-e_t$ ($~d = -e_t$, $F = μN$):");
        else if (!sc.needs_angle)
            head.t("Slide along $u_t (d = u_t/|u_t|$, $F = -μN d)$:");
        else
            head.t("Slide along $d = c_d e_t + s_d e_b$:");
        sec.para(head);
        std::vector<math_row> steps;
        for (std::size_t k = c.shared; k < sc.sol.steps.size(); ++k)
            steps.push_back(srow(c.p, sc.sol.steps[k]));
        sec.rows(steps);
        if (sc.needs_angle) {
            sec.para(paragraph().t(
                "$u′_t$ along $d$, i.e. $e_n·((D_s u + a K(e_n - μ d)) × d) = 0$ with $a = -(1 + e) u_n$, is the "
                "equation for the sliding angle:"));
            math_row g = srow(0, sc.angle_equation);
            paragraph gn;
            gn.t("with $c_d² + s_d² = 1$: a trigonometric polynomial of degree 2 in $θ$, at most four roots; no closed "
                 "form, so "
                 "a numeric problem's roots are found numerically");
            g.note = with_aside(gn, g.note);
            sec.rows({g});
        }
        sec.para(paragraph().w(std::string("It holds when") + (sc.needs_angle ? " (at a root θ)" : "") + ":"));
        sec.rows(condition_rows(sc));
        sec.para(paragraph().w("and then the bodies leave with"));
        std::vector<math_row> unknowns;
        for (std::size_t k = 0; k < c.d.unknowns.size(); ++k)
            if (c.d.unknowns[k].kind != unknown_kind::normal_impulse)
                unknowns.push_back(srow(c.d.unknowns[k].sym, sc.sol.unknown_values.op(k).rhs()));
        sec.rows(unknowns);
    }
    if (c.f.cases.size() == 1)
        sec.para(paragraph().t(
            "Here the contact points have no tangential velocity before impact $(u_t = 0)$: the stick impulse has "
            "$F = 0$, inside the cone for every $μ$, and there is nothing to slide."));
    return sec;
}

// ---------------------------------------------------------------- 7. boundaries and energy

// vanishes_identically, false where a numeric problem's step divides by zero (D_s = 0).
bool identically_zero(const solution &s, const ex &value)
{
    try {
        return vanishes_identically(s, value, "an identity of the explanation");
    } catch (const std::exception &) {
        return false;
    }
}

// A solution holding the stick case's steps and then the slide case's own: both at once.
solution merged(const context &c, const regime_case &sc)
{
    solution m = c.has_stick() ? c.stick().sol : c.f.shared;
    for (std::size_t k = c.shared; k < sc.sol.steps.size(); ++k)
        m.steps.push_back(sc.sol.steps[k]);
    return m;
}

// The work of the contact impulse in the case's own quantities (see the text).
ex energy_lost_formula(const context &c, const regime_case &rc)
{
    const vec3 u = c.u_world();
    const ex N = rc.sol.normal_impulse;
    if (rc.kind == regime::stick) {
        ex Fu = 0; // F.u = sum over the tangents of (P.e_k)(u.e_k): F has no normal part
        if (c.dim == 2)
            Fu = rc.tangential_scalar * tidy(dot(u, c.d.t_dir));
        else
            for (const vec3 &t : c.tangents)
                Fu += tidy(dot(rc.impulse, t)) * tidy(dot(u, t));
        return -(Fu + (1 - c.e) * N * c.un()) / 2;
    }
    return N * (c.mu * (tidy(dot(rc.direction, u)) + rc.sliding_speed) - (1 - c.e) * c.un()) / 2;
}

// Section 7 without a stick candidate: the slides' conditions, and the energy.
section slide_regimes_section(const context &c)
{
    section sec{"The regimes, and the energy", {}};
    std::vector<paragraph> items;
    for (const regime_case &sc : c.f.cases) {
        paragraph item = regime_words(sc);
        item.t(": ");
        bool first = true;
        for (const regime_condition &rc : sc.conditions) {
            if (!first)
                item.t(", ");
            item.m(rc.value).t(rc.strict ? " $> 0$" : " $≥ 0$");
            first = false;
        }
        item.t(".");
        items.push_back(item);
    }
    sec.para(paragraph().t("Without a stick candidate the regimes are the slides, each holding under its own "
                           "conditions:"));
    sec.list(items);
    sec.para(paragraph().t(
        "Energy: as $K$ is symmetric, the kinetic energy the bodies lose is the work of the contact impulse over the "
        "mean relative velocity of the contact points; while sliding $(u′ = λ d - e u_n e_n)$ it is"));
    sec.rows({formula_row("slide:   T_lost = N (μ (d·u + λ) - (1 - e) u_n)/2",
                          "\\text{slide: } T_{\\text{lost}} = N\\,(\\mu\\,(\\underline{d}\\cdot\\underline{u} + "
                          "\\lambda) - (1 - e)\\,u_n)/2",
                          "negative when a moving body of infinite mass does work on the others")});
    std::vector<math_row> energy;
    for (const regime_case &rc : c.f.cases) {
        const ex lost = energy_lost_formula(c, rc);
        if (!rc.needs_angle && !identically_zero(rc.sol, lost - rc.sol.energy_lost))
            continue;
        math_row r = srow(symbol("T_lost", "T_{\\text{lost}}"), lost);
        r.note = regime_words(rc);
        energy.push_back(r);
    }
    if (!energy.empty())
        sec.rows(energy);
    return sec;
}

// The energy the bodies lose: the general formula, its stick and slide forms, and each
// regime's loss.
void energy_part(section &sec, const context &c)
{
    const regime_case &st = c.stick();
    sec.para(paragraph().t(
        "Energy: as $K$ is symmetric, the kinetic energy the bodies lose is the work of the contact impulse over the "
        "mean relative velocity of the contact points:"));
    sec.rows(
        {formula_row("T_lost = T - T′ = -P·(u + u′)/2",
                     "T_{\\text{lost}} = T - T' = -\\underline{P}\\cdot(\\underline{u} + \\underline{u}')/2"),
         formula_row("stick (u′ = -e u_n e_n):   T_lost = -(F·u + (1 - e) N u_n)/2",
                     "\\text{stick: } T_{\\text{lost}} = -(\\underline{F}\\cdot\\underline{u} + (1 - e)\\,N u_n)/2",
                     "$(1 - e) N u_n ≤ 0$ is the loss of restitution; $~F·~u$, the work of friction on the sliding "
                     "before impact"),
         formula_row("slide (u′ = λ d - e u_n e_n):   T_lost = N (μ (d·u + λ) - (1 - e) u_n)/2",
                     "\\text{slide: } T_{\\text{lost}} = N\\,(\\mu\\,(\\underline{d}\\cdot\\underline{u} + \\lambda) - "
                     "(1 - e)\\,u_n)/2",
                     "both terms are losses when the sliding keeps its direction ($~d·~u > 0$)")});
    std::vector<math_row> energy;
    const ex T = symbol("T", "T");
    ex before = tidy(st.sol.energy_before);
    if (printable(before, 200)) {
        math_row r = row(T, before);
        r.note.t("kinetic energy before impact (bodies of finite mass); $T′ = T - T_lost$");
        energy.push_back(r);
    }
    for (const regime_case &rc : c.f.cases) {
        const ex lost = energy_lost_formula(c, rc);
        if (!rc.needs_angle && !identically_zero(rc.sol, lost - rc.sol.energy_lost))
            continue;
        math_row r = srow(symbol("T_lost", "T_{\\text{lost}}"), lost);
        paragraph note = regime_words(rc);
        r.note = with_aside(note, r.note);
        energy.push_back(r);
    }
    sec.rows(energy);
}

section regimes_section(const context &c)
{
    section sec{"The regimes as conditions on μ, and the energy", {}};
    const regime_case &st = c.stick();
    const ex mu_star = symbol("μ*", "\\mu^{*}");
    std::vector<paragraph> items;
    items.push_back(
        paragraph().w("stick: μ ≥ μ*" + std::string(c.dim == 3 ? " (and N ≥ 0)" : "") + ", from section 5."));
    if (c.dim == 2) {
        sec.para(paragraph().t("In the plane each slide's conditions are linear in $μ$. With $N = -(1 + e) u_n/D_s$ "
                               "put into $λ$, and $F$, $N$, $D_K$ "
                               "those of the stick impulse (section 5):"));
        std::vector<math_row> rows;
        for (std::size_t ci = c.first_slide(); ci < c.f.cases.size(); ++ci) {
            const regime_case &sc = c.f.cases[ci];
            const step *Ds = sc.sol.find(step_role::slide_denominator);
            const step *DK = st.sol.find(step_role::response_determinant);
            if (!Ds || !DK)
                continue;
            // lambda D_s = -D_K (s F + mu N), F and N of the stick impulse: checked, not assumed.
            solution m = merged(c, sc);
            const ex claim =
                sc.sliding_speed * Ds->sym + DK->sym * (sc.sign * st.tangential_scalar + c.mu * st.sol.normal_impulse);
            if (!identically_zero(m, claim))
                continue;
            const std::string s = sc.sign > 0 ? "" : "-";
            const std::string sf = sc.sign > 0 ? "F" : "-F";
            rows.push_back(formula_row("λ·D_s = -D_K·(" + sf + " + μ·N)", "\\lambda D_s = -D_K\\,(" + sf + " + \\mu N)",
                                       sc.sign > 0 ? "slide along $+e_t$ ($F$, $N$, $D_K$ of the stick impulse)"
                                                   : "slide along $-e_t$ ($F$, $N$, $D_K$ of the stick impulse)"));
            items.push_back(paragraph()
                                .t(sc.sign > 0 ? "slide along $+e_t$: $μN < -F$" : "slide along $-e_t$: $μN < F$")
                                .t(" ($F$, $N$ of the stick impulse) and $D_s$ = ")
                                .m(Ds->value)
                                .t(" $> 0$."));
        }
        sec.rows(rows);
        sec.para(paragraph().t("$D_K > 0$, so with $D_s > 0$ the slide holds exactly when $μN < ∓F$: when $N > 0$, "
                               "that is $μ < μ*$ on the side "
                               "where the stick impulse's friction points. The regimes:"));
    } else if (c.f.isotropic) {
        sec.para(paragraph().t(
            "With $K e_n$ along $e_n$ the slide has the same $N$ as the stick impulse, $D_s = K_nn·(e_n$, $e_n) > 0$, "
            "and "
            "$λ = |u_t| - μ N k_t$ with $k_t$ the tangential entry of $K$; the stick impulse has $|F| = |u_t|/k_t$, so "
            "$λ > 0$ exactly when $μ < μ*$. The regimes:"));
        items.push_back(paragraph().t("slide along $u_t$: $μ < μ*$."));
    } else {
        sec.para(paragraph().t(
            "In 3-D with coupling the slide's conditions depend on $μ$ through the sliding angle too: no interval in "
            "closed form. The regimes:"));
        items.push_back(paragraph().t("slide: at a root $θ$ of the sliding equation, $D_s > 0$ and $λ > 0$."));
    }
    sec.list(items);
    if (c.dim == 2 || c.f.isotropic)
        sec.para(paragraph().t(
            "At $μ = μ*$ the stick impulse lies on the edge of the cone: there $λ = 0$ and the slide's impulse equals "
            "the stick impulse, so the answer changes continuously with $μ$."));

    energy_part(sec, c);
    return sec;
}

// ---------------------------------------------------------------- 8. existence and uniqueness

section existence_section(const context &c)
{
    section sec{"One regime, none, or several?", {}};
    if (!c.has_stick()) {
        if (c.dim == 2)
            sec.para(paragraph().t(
                "In the plane at most one slide holds: the impulse moves the contact point along one line only, so "
                "restitution fixes its velocity after impact whichever way friction acts. $u′_t$ is the same for "
                "both slides, and $λ = u′·d$ is positive for one direction of $d$ only; that slide holds if its "
                "$D_s > 0$."));
        else
            sec.para(paragraph().t(
                "Without sticking, a sliding direction holds where its conditions do; the numbers decide which, and "
                "with strong coupling none or several may hold (then the law of impulses does not decide the "
                "outcome, and the impact has to be followed through its duration)."));
    } else if (c.dim == 2) {
        sec.para(paragraph().t(
            "In the plane, with $K$ positive definite and $u_n < 0$, the law has exactly one solution for every $μ ≥ "
            "0$. "
            "If the stick impulse has $N > 0$, sticking holds for $μ ≥ μ*$, and for $μ < μ*$ exactly the slide "
            "opposite "
            "to the stick impulse's friction: its $D_s$ could only be $≤ 0$ for $μ ≥ K_nn/|K_tn|$, which is larger "
            "than $μ*$. "
            "If strong coupling of the normal and tangential directions makes the stick impulse pull "
            "$(N < 0$, i.e. $K_tn·u_t < (1 + e)·K_tt·u_n)$, sticking is impossible and exactly the slide along $u_t$ "
            "holds. "
            "$D_s ≤ 0$ -- friction that would drive the contact points together faster than the normal impulse "
            "separates them, the jam of Painleve's paradox -- only ever rules out a slide that fails anyway."));
    } else if (c.f.isotropic) {
        sec.para(paragraph().t("With this $K$ (isotropic, not coupling the normal to the tangent plane) exactly one "
                               "regime holds for every "
                               "$μ ≥ 0$: stick for $μ ≥ μ*$, slide along $u_t$ for $μ < μ*$."));
    } else {
        sec.para(paragraph().t(
            "In 3-D with coupling the sliding direction is itself unknown, and the algebraic law can have several "
            "solutions: with strong coupling between the normal and the tangential directions $(K_tn$, $K_nb$ large "
            "against $K_nn)$ and a large $μ$, sticking and one or more sliding directions can all satisfy their "
            "conditions at once; a sliding direction with $D_s ≤ 0$ (friction wedging the contact shut) is excluded, "
            "and in principle none might remain. Then the law of impulses does not decide the outcome, and the impact "
            "has to be "
            "followed through its duration (Routh's method, or integrating the contact in the normal impulse, "
            "Darboux-Keller)."));
    }
    return sec;
}

} // namespace friction_detail

} // namespace impactgen::print
