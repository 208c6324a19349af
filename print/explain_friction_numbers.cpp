// Sections 9 and 10 of the friction document (explain_friction.cpp has the rest): every
// number of a numeric problem, the regime that holds (or why none or several do), the answer
// substituted back into the equations, and the energy.
#include "explain_friction_detail.hpp"

#include "canonical.hpp"
#include "expression.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace impactgen::print::detail
{
using namespace GiNaC;

// Issue 23 / 25 (defect 10): whether the slip of the contact points stops (stick) or reverses
// (a slide against the slip before impact) during the impact, from the answer's own
// velocities: u = v_B - v_A at the contact point before and after, their tangential parts.
bool slip_stops_or_reverses(const derivation &d, const regime_case &sel)
{
    const problem &p = d.prob;
    const vec3 O = p.contact().point;
    auto contact_velocity = [&](const vec3 &v, const vec3 &w, std::size_t i) {
        return v + cross(w, O - p.bodies[i].position);
    };
    const std::size_t a = p.contact().body1, b = p.contact().body2;
    const vec3 before = contact_velocity(p.bodies[b].velocity, p.bodies[b].angular_velocity, b) -
                        contact_velocity(p.bodies[a].velocity, p.bodies[a].angular_velocity, a);
    auto after_of = [&](std::size_t i) {
        vec3 v, w;
        for (int k = 0; k < 3; ++k) {
            v[k] = sel.sol.expand_steps(sel.sol.after[i].velocity[k]);
            w[k] = sel.sol.expand_steps(sel.sol.after[i].angular_velocity[k]);
        }
        return contact_velocity(v, w, i);
    };
    const vec3 after = after_of(b) - after_of(a);
    auto tangential = [&](const vec3 &u) {
        const ex un = dot(u, d.n_hat);
        vec3 t;
        for (int k = 0; k < 3; ++k)
            t[k] = u[k] - un * d.n_hat[k];
        return t;
    };
    const vec3 ut = tangential(before), ut2 = tangential(after);
    const ex slip = evalf(dot(ut, ut)), same = evalf(dot(ut, ut2));
    if (!is_a<numeric>(slip) || !is_a<numeric>(same) || ex_to<numeric>(slip).to_double() <= 1e-24)
        return false; // no slip before impact (or not a number): nothing stops or reverses
    return sel.kind == regime::stick || ex_to<numeric>(same).to_double() < 0;
}

paragraph slip_warning(bool stick)
{
    return paragraph()
        .w("Caution: ")
        .t(stick ? "the slip of the contact points stops during this impact (the answer sticks, $u′_t = 0$). "
                 : "the slip of the contact points reverses during this impact (the tangential relative velocity "
                   "$u′_t$ after impact points against $u_t$ before it). ")
        .t("The answer assumes Newton's law of restitution between the velocities at the start and at the end of "
           "the impact, with Coulomb's law for the impulse as a whole. Following the impact through its course "
           "(Routh's method: the slip, and the friction force against it, change as the normal impulse grows) "
           "gives a different answer here.");
}

} // namespace impactgen::print::detail

namespace impactgen::print::friction_detail
{
namespace
{

// ---------------------------------------------------------------- 9. numbers

// g(c_d, s_d) with c_d = cos θ, s_d = sin θ as a0 + a1 cos θ + b1 sin θ + a2 cos 2θ + b2 sin 2θ,
// the coefficients as decimals (evaluated at 50 digits).
notation trig_form(const ex &g, const symbol &cd, const symbol &sd)
{
    const long saved = Digits;
    Digits = 50;
    notation out;
    try {
        const ex x = g.evalf().expand();
        auto co = [&](int i, int j) {
            ex v = x.coeff(cd, i).coeff(sd, j).evalf();
            if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
                throw std::invalid_argument("not a real coefficient");
            return ex_to<numeric>(v);
        };
        const numeric c00 = co(0, 0), c10 = co(1, 0), c01 = co(0, 1), c20 = co(2, 0), c02 = co(0, 2), c11 = co(1, 1);
        const numeric a[5] = {c00 + (c20 + c02) / 2, c10, c01, (c20 - c02) / 2, c11 / 2};
        numeric scale = 0;
        for (const numeric &v : a)
            scale = std::max(scale, abs(v));
        const char *text_terms[5] = {"", " cos θ", " sin θ", " cos 2θ", " sin 2θ"};
        const char *tex_terms[5] = {"", "\\cos\\theta", "\\sin\\theta", "\\cos 2\\theta", "\\sin 2\\theta"};
        std::string text, tex;
        for (int k = 0; k < 5; ++k) {
            if (abs(a[k]) <= scale * numeric(1, 10).power(40))
                continue;
            const std::string mag = decimal(abs(a[k]));
            const bool neg = a[k].is_negative();
            text += text.empty() ? (neg ? "-" : "") : (neg ? " - " : " + ");
            tex += tex.empty() ? (neg ? "-" : "") : (neg ? " - " : " + ");
            text += mag + text_terms[k];
            tex += mag + (k ? "\\," : "") + tex_terms[k];
        }
        if (!text.empty()) {
            out.text = "0 = " + text;
            out.tex = "0 = " + tex;
        }
    } catch (const std::exception &) {
        out = {};
    }
    Digits = saved;
    return out;
}

struct case_numbers {
    lst values;           ///< step == value, exact, in order (stops at D_s <= 0)
    bool stopped = false; ///< D_s <= 0: the rest of the steps divide by it
    std::vector<decision> verdicts;
    bool holds = false;
};

case_numbers evaluate(const context &c, const regime_case &rc)
{
    case_numbers out;
    for (const step &st : rc.sol.steps) {
        ex v = tidy(c.at_inputs(st.value).subs(out.values));
        out.values.append(st.sym == v);
        if (st.role == step_role::slide_denominator && decide(v) != decision::positive) {
            out.stopped = true;
            return out;
        }
    }
    out.holds = true;
    for (const regime_condition &cond : rc.conditions) {
        const decision dd = decide(tidy(c.at_inputs(cond.value).subs(out.values)));
        out.verdicts.push_back(dd);
        const bool ok = dd == decision::positive || (!cond.strict && dd == decision::zero);
        out.holds = out.holds && ok;
    }
    return out;
}

std::string verdict_word(decision dd, bool strict)
{
    switch (dd) {
    case decision::positive:
        return "holds";
    case decision::zero:
        return strict ? "fails (= 0)" : "holds (on the boundary)";
    case decision::negative:
        return "fails";
    default:
        return "cannot be decided";
    }
}

// The set of mu >= 0 where each of some conditions a - mu b > 0 (strict) or >= 0 holds.
struct mu_interval {
    numeric lo = 0, hi = 0;
    bool lo_closed = true, has_hi = false, hi_closed = false, empty = false;
};

void restrict_interval(mu_interval &iv, const numeric &a, const numeric &b, bool strict)
{
    if (iv.empty)
        return;
    if (b.is_zero()) {
        if (a.is_negative() || (strict && a.is_zero()))
            iv.empty = true;
        return;
    }
    const numeric x = a / b;
    if (b.is_positive()) { // mu < x (or <=)
        if (!iv.has_hi || x < iv.hi || (x == iv.hi && strict)) {
            iv.hi = x;
            iv.hi_closed = !strict;
            iv.has_hi = true;
        }
    } else if (x > iv.lo || (x == iv.lo && strict)) { // mu > x (or >=)
        iv.lo = x;
        iv.lo_closed = !strict;
    }
    if (iv.has_hi && (iv.hi < iv.lo || (iv.hi == iv.lo && !(iv.hi_closed && iv.lo_closed))))
        iv.empty = true;
}

std::string interval_text(const mu_interval &iv)
{
    if (iv.empty)
        return "for no μ ≥ 0";
    const std::string lo = canonical_text(iv.lo), hi = canonical_text(iv.hi);
    if (!iv.has_hi)
        return iv.lo.is_zero() && iv.lo_closed ? "for every μ ≥ 0"
                                               : "for μ " + std::string(iv.lo_closed ? "≥ " : "> ") + lo;
    if (iv.hi == iv.lo)
        return "only at μ = " + lo;
    return "for " + lo + (iv.lo_closed ? " ≤ μ " : " < μ ") + (iv.hi_closed ? "≤ " : "< ") + hi;
}

// The stick candidate's numbers in section 9: its steps, its conditions, the threshold mu*.
void stick_numbers(const context &c, section &sec, const case_numbers &cn, const std::vector<math_row> &stick_rows,
                   ex &Nst, ex &mu_star)
{
    const regime_case &st = c.stick();
    sec.para(paragraph().w("Assume sticking (section 5):"));
    sec.rows(stick_rows);
    std::vector<math_row> conds;
    for (std::size_t k = 0; k < st.conditions.size() && k < cn.verdicts.size(); ++k) {
        const ex v = tidy(c.at_inputs(st.conditions[k].value).subs(cn.values));
        math_row r = row(st.conditions[k].value, v);
        r.note = condition_note(st.conditions[k]);
        r.note.w(": " + verdict_word(cn.verdicts[k], st.conditions[k].strict));
        r.has_then = false;
        conds.push_back(r);
    }
    sec.rows(conds);
    const ex mu_star_sym = symbol("μ*", "\\mu^{*}");
    Nst = tidy(c.at_inputs(st.sol.normal_impulse).subs(cn.values));
    if (decide(Nst) == decision::positive) {
        mu_star = tidy(c.at_inputs(stick_threshold_value(c)).subs(cn.values));
        sec.rows({value_row(mu_star_sym, mu_star, paragraph().t("the stick impulse needs $μ ≥ μ*$"))});
        paragraph q;
        q.t("$μ =$ ")
            .m(c.at_inputs(c.mu))
            .w(cn.holds ? ": μ ≥ μ*, the stick test passes." : ": μ < μ*, the stick test fails -- the contact slides.");
        sec.para(q);
    } else {
        sec.para(paragraph().t("The stick impulse has $N ≤ 0$: it would pull the bodies together, so the contact "
                               "cannot stick for any $μ$."));
    }
}

// The rows of a candidate's steps from..to with their numbers (formula, then value).
std::vector<math_row> step_rows(const context &c, const regime_case &rc, const case_numbers &cn, std::size_t from,
                                std::size_t to)
{
    std::vector<math_row> rows;
    for (std::size_t k = from; k < to && k < cn.values.nops(); ++k) {
        const step &s = rc.sol.steps[k];
        const ex v = cn.values.op(k).rhs();
        const ex formula = c.at_inputs(s.value); // in the earlier steps, whose numbers are above
        math_row r = value_row(s.sym, v);
        if (!is_constant(formula) && printable(formula, 120) && !is_float(v)) {
            r.rhs = formula;
            r.has_then = true;
            r.then = v;
        }
        r.note.w(step_unit(c.numeric_d ? c.numeric_d->prob : c.d.prob, s.role)); // issue 25, defect 9
        rows.push_back(r);
    }
    return rows;
}

// The slides' numbers in section 9: steps and conditions, or the sliding equation (3-D general).
void slide_numbers(const context &c, section &sec, const std::vector<case_numbers> &nums)
{
    for (std::size_t ci = c.first_slide(); ci < c.f.cases.size(); ++ci) {
        const regime_case &sc = c.f.cases[ci];
        const case_numbers &cn = nums[ci];
        if (sc.needs_angle) {
            sec.para(paragraph().t(
                "Slide: with the numbers, the equation for the sliding direction $d = c_d e_t + s_d e_b$ is"));
            lst shared_vals;
            for (std::size_t k = 0; k < c.shared && k < nums[0].values.nops(); ++k)
                shared_vals.append(nums[0].values.op(k));
            ex g = tidy_expand(c.at_inputs(sc.angle_equation).subs(shared_vals));
            if (printable(g, 150)) {
                math_row r = row(0, g);
                r.note.t("with $c_d² + s_d² = 1$");
                sec.rows({r});
            }
            if (const auto trig = trig_form(g, sc.dir_c, sc.dir_s); !trig.text.empty())
                sec.rows(
                    {formula_row(trig.text, trig.tex, "$c_d = cos θ$, $s_d = sin θ$; the coefficients to 15 digits")});
            sec.para(paragraph().t(
                "Its roots $θ$ on the unit circle are found to 50 significant digits, isolated with bounds on "
                "the derivatives, and checks $D_s > 0$ and $λ > 0$ at each."));
            continue;
        }
        paragraph head;
        if (c.dim == 2)
            head.t(sc.sign > 0 ? "Slide along $+e_t$:" : "Slide along $-e_t$:");
        else
            head.t("Slide along $u_t$:");
        sec.para(head);
        sec.rows(step_rows(c, sc, cn, c.shared, sc.sol.steps.size()));
        if (cn.stopped) {
            sec.para(paragraph().t("$D_s ≤ 0$: the normal impulse would not be positive, so this slide cannot hold."));
            continue;
        }
        std::vector<math_row> sconds;
        for (std::size_t k = 0; k < sc.conditions.size() && k < cn.verdicts.size(); ++k) {
            math_row r = row(sc.conditions[k].value, tidy(c.at_inputs(sc.conditions[k].value).subs(cn.values)));
            r.note = condition_note(sc.conditions[k]);
            r.note.w(": " + verdict_word(cn.verdicts[k], sc.conditions[k].strict));
            sconds.push_back(r);
        }
        sec.rows(sconds);
    }
}

// Planar: the regimes along the mu axis for this problem (with a stick candidate).
void mu_axis_numbers(const context &c, section &sec, const std::vector<case_numbers> &nums, const ex &Nst)
{
    if (c.dim == 2 && c.has_stick() && c.f.cases.size() == 3) {
        const regime_case &st = c.stick();
        const step *DK = st.sol.find(step_role::response_determinant);
        std::vector<ex> vals;
        const vec3 &et = c.d.t_dir;
        const ex F = tidy(c.at_inputs(st.tangential_scalar).subs(nums[0].values)),
                 Kn = tidy(c.at_inputs(c.kform(c.n, c.n)).subs(nums[0].values)),
                 Ktn = tidy(c.at_inputs(c.kform(et, c.n)).subs(nums[0].values));
        if (DK && is_a<numeric>(F) && is_a<numeric>(Nst) && is_a<numeric>(Kn) && is_a<numeric>(Ktn) &&
            ex_to<numeric>(F).is_rational() && ex_to<numeric>(Nst).is_rational()) {
            std::vector<paragraph> items;
            const numeric nF = ex_to<numeric>(F), nN = ex_to<numeric>(Nst), nK = ex_to<numeric>(Kn),
                          nT = ex_to<numeric>(Ktn);
            // stick: mu N - |F| >= 0
            mu_interval stick;
            restrict_interval(stick, -abs(nF), -nN, false);
            items.push_back(paragraph().w("stick " + interval_text(stick)));
            for (int s : {1, -1}) {
                mu_interval iv;
                restrict_interval(iv, -numeric(s) * nF, nN, true); // -(sF + mu N) > 0
                restrict_interval(iv, nK, numeric(s) * nT, true);  // K_nn - mu s K_tn > 0
                items.push_back(
                    paragraph().t(s > 0 ? "slide along $+e_t$ " : "slide along $-e_t$ ").w(interval_text(iv)));
            }
            sec.para(paragraph().t("Along the $μ$ axis, for this problem (section 7):"));
            sec.list(items);
        }
    }
}

// "The regime that holds: ..." (and the sliding direction in 3-D).
paragraph verdict_paragraph(const context &c, const regime_case &sel)
{
    paragraph q;
    q.w("The regime that holds: ");
    for (const span &x : regime_words(sel).spans)
        q.spans.push_back(x);
    q.w(".");
    if (sel.kind == regime::slide && c.dim == 3) {
        q.t(" The sliding direction $d = ($");
        for (int a = 0; a < 3; ++a) {
            const ex x = settle(sel.direction[a]);
            if (a)
                q.w(", ");
            if (is_float(x))
                q.n(decimal(x), decimal(x));
            else
                q.m(x);
        }
        q.w(").");
    }
    return q;
}

// Why no regime is the answer: several hold, none does, or the numbers do not decide.
paragraph no_single_regime(const context &c)
{
    paragraph q;
    q.w("No single regime: ");
    std::vector<regime_case> holding;
    try {
        holding = c.numeric_d ? holding_regimes(*c.numeric_d, *c.numeric_f) : holding_regimes(c.d, c.f);
    } catch (const input_error &) {
        return q.w("these numbers do not decide which of the regimes' conditions hold.");
    }
    if (holding.empty())
        return q.w("the conditions of no regime hold for these numbers.");
    q.w("the law of restitution with Coulomb friction has more than one solution here: the regimes ");
    for (std::size_t k = 0; k < holding.size(); ++k) {
        if (k)
            q.w(k + 1 == holding.size() ? " and " : ", ");
        for (const span &x : regime_words(holding[k]).spans)
            q.spans.push_back(x);
    }
    return q.w(" all hold.");
}

// Section 10: the answer, the equations substituted back, the energy.
section answer_section(const context &c, const regime_case &sel)
{
    section ans{"The answer", {}};
    std::vector<math_row> answers;
    lst unknown_values;
    for (std::size_t k = 0; k < c.d.unknowns.size(); ++k) {
        const ex v = sel.sol.unknown_values.op(k).rhs();
        unknown_values.append(c.d.unknowns[k].sym == v);
        if (c.d.unknowns[k].kind != unknown_kind::normal_impulse)
            answers.push_back(value_row(c.d.unknowns[k].sym, v, unknown_note(c.p, c.d.unknowns[k])));
    }
    const ex Nv = sel.sol.normal_impulse;
    answers.push_back(value_row(c.N, Nv, "the normal impulse"));
    lst impulse_values{c.N == Nv};
    for (std::size_t k = 0; k < c.F.size(); ++k) {
        const ex Fk = settle(c.dim == 2 ? sel.tangential_scalar : ex(tidy(dot(sel.tangential_impulse, c.tangents[k]))));
        impulse_values.append(c.F[k] == Fk);
        {
            math_row r = value_row(c.F[k], Fk);
            r.note.w(r.note.spans.empty() ? "" : ", ")
                .w("the friction impulse on body 2 along ")
                .n("e_" + c.tnames[k], "\\hat{\\underline{e}}_" + c.tnames[k]);
            answers.push_back(r);
        }
    }
    ans.rows(answers);
    // Substituted back.
    bool exact = true, small = true;
    std::vector<equation> all = c.eqs;
    std::string law_tags;
    if (sel.kind == regime::stick) {
        all.insert(all.end(), c.stick_law.begin(), c.stick_law.end());
        law_tags = c.stick_law.front().label + (c.stick_law.size() > 1 ? "-" + c.stick_law.back().label : "");
    } else {
        for (std::size_t k = 0; k < c.slide_law.size(); ++k) {
            equation eq = c.slide_law[k];
            if (c.dim == 2)
                eq.rhs = ex(-sel.sign) * c.mu * c.N;
            else
                eq.rhs = eq.rhs.subs(c.slide_d[k] == settle(tidy(dot(sel.direction, c.tangents[k]))));
            all.push_back(eq);
        }
        law_tags = c.dim == 2
                       ? c.slide_tag(sel.sign)
                       : c.slide_law.front().label + (c.slide_law.size() > 1 ? "-" + c.slide_law.back().label : "");
    }
    for (const equation &eq : all) {
        ex r = c.at_inputs(eq.lhs - eq.rhs).subs(unknown_values).subs(impulse_values);
        r = tidy(r);
        if (r.is_zero())
            continue;
        exact = false;
        const long saved = Digits;
        Digits = 50; // the sliding angle's floats carry 50 digits
        ex x = (c.at_inputs(eq.lhs - eq.rhs).subs(unknown_values).subs(impulse_values)).evalf();
        Digits = saved;
        small = small && is_a<numeric>(x) && abs(ex_to<numeric>(x)) < numeric(1, 10).power(25);
    }
    const std::string range = "(1)-(" + c.eqs.back().label + ") and Coulomb's law (" + law_tags + ")";
    ans.para(paragraph().w(exact   ? "Substituted back, every equation " + range + " holds exactly."
                           : small ? "Substituted back, every equation " + range +
                                         " holds to 25 digits (the sliding angle is a root "
                                         "found numerically)."
                                   : "Substituted back, SOME EQUATION DOES NOT HOLD: this is a bug."));
    // Energy.
    const ex T0 = sel.sol.energy_before, T1 = sel.sol.energy_after, Tl = sel.sol.energy_lost;
    ans.rows({value_row(symbol("T", "T"), T0, "before impact"), value_row(symbol("T'", "T'"), T1, "after impact"),
              value_row(symbol("T_lost", "T_{\\text{lost}}"), Tl, "lost")});
    const decision loss = decide(is_float(Tl) ? Tl : tidy(Tl));
    bool driven = false; // a moving body of infinite mass does work on the others
    for (const body &b : c.p.bodies)
        driven = driven || (b.infinite_mass && !b.at_rest());
    if (loss == decision::negative && driven)
        ans.para(paragraph().t("The kinetic energy of the bodies of finite mass rises: $T_lost < 0$. A moving body of "
                               "infinite mass does work on them through the contact impulse; that is physics, not a "
                               "fault of the law."));
    else if (loss == decision::negative)
        ans.para(paragraph().t(
            "The kinetic energy rises in this impact: $T_lost < 0$. Newton's restitution law with friction can do that "
            "in "
            "an eccentric impact, where the friction impulse changes the normal velocity of the contact points "
            "$(K_tn ≠ 0)$ and restitution then acts on a normal velocity that friction has made. Stronge's energetic "
            "coefficient of restitution, with the impact followed through its duration, avoids it. The answer is "
            "the one the law gives."));
    else if (loss == decision::zero)
        ans.para(paragraph().w("No kinetic energy is lost."));
    return ans;
}

} // namespace

std::vector<section> numbers_sections(const context &c)
{
    section sec{"The numbers", {}};
    if (c.f.cases.empty())
        return {};
    // The shared steps are the first candidate's first steps (stick's, or a slide's without it).
    const regime_case &first = c.f.cases.front();
    if (c.inputs.nops()) {
        std::vector<math_row> given;
        for (std::size_t k = 0; k < c.inputs.nops(); ++k) {
            math_row r = value_row(c.inputs.op(k).lhs(), c.inputs.op(k).rhs());
            if (k < c.units.size() && !c.units[k].empty())
                r.note.w(r.note.spans.empty() ? "in" + c.units[k] : "," + c.units[k]);
            given.push_back(r);
        }
        sec.para(paragraph().w("The problem's numbers: substitute"));
        sec.rows(given);
        sec.para(paragraph().w("Every step above is then a number, exact where the closed form is. The shared steps:"));
    } else {
        sec.para(paragraph().w(
            "The problem is numeric: every step above is a number, exact where the closed form is. The shared steps:"));
    }
    std::vector<case_numbers> nums;
    for (const regime_case &rc : c.f.cases)
        nums.push_back(rc.needs_angle ? case_numbers{} : evaluate(c, rc));
    sec.rows(step_rows(c, first, nums[0], 0, c.shared));

    ex Nst, mu_star;
    if (c.has_stick())
        stick_numbers(c, sec, nums[0], step_rows(c, first, nums[0], c.shared, first.sol.steps.size()), Nst, mu_star);
    slide_numbers(c, sec, nums);

    if (c.dim == 2 && c.has_stick() && c.f.cases.size() == 3)
        mu_axis_numbers(c, sec, nums, Nst);

    // The verdict.
    regime_case sel;
    bool selected = false;
    try {
        sel = c.numeric_d ? select_regime(*c.numeric_d, *c.numeric_f) : select_regime(c.d, c.f);
        selected = true;
    } catch (const input_error &) {
        // none holds, several do, or the decision is too close to call
    }
    if (!selected) {
        sec.para(no_single_regime(c));
        sec.para(paragraph().t(
            "That is the situation of section 8: the law of restitution with Coulomb friction does not fix the "
            "outcome here, and no answer is given. A smaller $μ$, or weaker coupling between the normal and the "
            "tangential directions, typically leaves a single regime."));
        return {sec};
    }
    sec.para(verdict_paragraph(c, sel));
    if (slip_stops_or_reverses(c.numeric_d ? *c.numeric_d : c.d, sel))
        sec.para(slip_warning(sel.kind == regime::stick));
    section ans = answer_section(c, sel);
    return {sec, ans};
}

} // namespace impactgen::print::friction_detail
