// explain(): the explanation document, section by section as the notes go:
// set-up, impulses, equations, count and solution, checks.
#include "explain.hpp"
#include "explain_detail.hpp"

#include "canonical.hpp"
#include "expression.hpp"
#include "names/escape.hpp"
#include "symbolic/decide.hpp"

#include <algorithm>
#include <cctype>
#include <map>

namespace impactgen::print {
using namespace GiNaC;

namespace detail {

std::string body_ref(const problem& p, std::size_t i)
{
    const body& b = p.bodies[i];
    std::string role = i == p.contact.body1 ? "body 1" : i == p.contact.body2 ? "body 2" : "body";
    return b.numbered ? role : role + " (" + b.name + ")";
}

paragraph& vector_span(paragraph& p, const vec3& v, int n)
{
    p.w("(");
    for (int c = 0; c < n; ++c) {
        if (c)
            p.w(", ");
        p.m(v[c]);
    }
    return p.w(")");
}

namespace {
int count_nodes(const ex& e, int limit)
{
    int n = 0;
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end() && n < limit; ++it)
        ++n;
    return n;
}
} // namespace

bool printable(const ex& e, int limit) { return count_nodes(e, limit) < limit; }

math_row row(const ex& lhs, const ex& rhs, const std::string& tag, const std::string& note)
{
    math_row r;
    r.tag = tag;
    r.lhs = lhs;
    r.rhs = rhs;
    if (!note.empty())
        r.note.w(note);
    return r;
}

math_row note_row(const std::string& text, const std::string& tex, const ex& rhs, const std::string& note)
{
    math_row r = row(0, rhs, "", note);
    r.lhs_note = {text, tex};
    return r;
}

math_row formula_row(const std::string& text, const std::string& tex, const std::string& note)
{
    math_row r = note_row(text, tex, 0, note);
    r.rel = "";
    return r;
}

std::string decimal_note(const ex& v)
{
    ex x = v.evalf();
    if (!is_a<numeric>(v) || ex_to<numeric>(v).is_integer() || !is_a<numeric>(x))
        return "";
    return "≈ " + decimal(v);
}

} // namespace detail

namespace {
using namespace detail;

std::string number_word(std::size_t n) { return std::to_string(n); }

// Print-only symbols: names for quantities that are not GiNaC symbols of the problem.
symbol show(const std::string& name, const std::string& tex) { return symbol(name, tex); }

const step* find_step(const solution& s, step_role role, std::size_t body = no_body) { return s.find(role, body); }

// Substitutes the steps of the given roles (and only those), latest first.
ex expand_some(const solution& s, const ex& e, const std::vector<step_role>& roles)
{
    ex r = e;
    for (auto it = s.steps.rbegin(); it != s.steps.rend(); ++it)
        if (std::find(roles.begin(), roles.end(), it->role) != roles.end())
            r = r.subs(it->sym == it->value);
    return r;
}

// ---------------------------------------------------------------- sections

} // namespace

section detail::setup_section(const derivation& d, const friction_setup* fr)
{
    const problem& p = d.prob;
    const int dim = p.dimension;
    const std::size_t i1 = p.contact.body1, i2 = p.contact.body2;
    section sec{"1. Set-up", {}};

    const std::string kind = fr ? std::string(dim == 2 ? "A planar (2-D)" : "A 3-D") + " impact with Coulomb friction"
                                : std::string("A smooth ") + (dim == 2 ? "planar (2-D)" : "3-D") + " impact";
    sec.para(paragraph()
                 .w(kind + ": point A of " + body_ref(p, i1) + " strikes point B of " + body_ref(p, i2) +
                    ". The impulsive forces change the velocities instantly without changing the positions."));
    if (is_a<symbol>(p.restitution))
        sec.para(paragraph().w("Newton's coefficient of restitution is ").m(p.restitution).w(" (0 ≤ e ≤ 1)."));
    else
        sec.para(paragraph().w("Newton's coefficient of restitution is e = ").m(p.restitution).w("."));
    if (fr) {
        if (is_a<symbol>(fr->mu))
            sec.para(paragraph().w("Coulomb's coefficient of friction between the bodies is ").m(fr->mu).w(" (μ ≥ 0)."));
        else
            sec.para(paragraph().w("Coulomb's coefficient of friction between the bodies is μ = ").m(fr->mu).w("."));
    }

    std::vector<paragraph> bodies;
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body& b = p.bodies[i];
        paragraph q;
        q.w(body_ref(p, i) + ": ");
        if (b.infinite_mass)
            q.w("infinite mass (its motion is given; the impulse cannot change it)");
        else
            q.w("mass ").m(b.mass);
        if (b.particle) {
            q.w(", a particle (no rotational inertia)");
        } else if (dim == 2) {
            q.w(", moment of inertia about C (along e_b) ").m(b.inertia[2][2]);
        } else {
            q.w(", inertia tensor about C with rows ");
            for (int r = 0; r < 3; ++r) {
                if (r)
                    q.w(", ");
                vector_span(q, b.inertia[r], 3);
            }
        }
        q.w("; centre of mass C at ");
        vector_span(q, b.position, dim);
        q.w("; before impact v_C = ");
        vector_span(q, b.velocity, dim);
        if (!b.particle || b.infinite_mass) {
            q.w(", ω = ");
            if (dim == 2)
                q.m(b.angular_velocity[2]);
            else
                vector_span(q, b.angular_velocity, 3);
        }
        q.w(".");
        if (const pivot* pv = p.pivot_of(i)) {
            q.w(" Pinned at the fixed point E = ");
            vector_span(q, pv->point, dim);
            q.w(": it can only rotate about E.");
        }
        bodies.push_back(q);
    }
    sec.list(bodies);

    paragraph frame;
    frame.w("The contact point O = ");
    vector_span(frame, p.contact.point, dim);
    frame.w(" is a geometric point, fixed in the inertial frame, where A and B coincide. The contact frame: e_n = ");
    vector_span(frame, d.n_hat, dim);
    frame.w(" (the common normal, from body 1 into body 2), e_t along ");
    vector_span(frame, d.t_dir, dim);
    if (dim == 3) {
        frame.w(", e_b along ");
        vector_span(frame, d.b_dir, 3);
    } else {
        frame.w(", and e_b normal to the plane of motion");
    }
    frame.w(".");
    if (p.axes[0] == "t")
        frame.w(" The world axes are named t, n, b: a component with subscript t, n or b is along e_t, e_n or e_b.");
    else if (d.frame_is_world)
        frame.w(" These are world axes (up to sign), so components can be read off directly.");
    sec.para(frame);

    // Known and unknown.
    paragraph known;
    known.w("Known before impact: the velocities v_C and angular velocities ω of both bodies (above). "
            "To be found after impact:");
    sec.para(known);
    std::vector<math_row> unknown_rows;
    for (const unknown& u : d.unknowns) {
        math_row r;
        r.lhs_note = {"", ""};
        r.lhs = u.sym;
        r.rel = "";
        r.note.w(u.meaning);
        unknown_rows.push_back(r);
    }
    if (fr)
        for (const auto& [sym, meaning] : fr->impulses) {
            math_row r;
            r.lhs = sym;
            r.rel = "";
            r.note.w(meaning);
            unknown_rows.push_back(r);
        }
    sec.rows(unknown_rows);

    // Why this many.
    std::vector<paragraph> why;
    std::string sum;
    for (std::size_t i : {i1, i2}) {
        const body& b = p.bodies[i];
        std::size_t nv = 0, nw = 0;
        for (const unknown& u : d.unknowns)
            if (u.owner == i && u.kind == unknown_kind::velocity)
                ++nv;
            else if (u.owner == i && u.kind == unknown_kind::angular_velocity)
                ++nw;
        paragraph q;
        q.w(body_ref(p, i) + ": " + number_word(nv + nw) + " unknowns");
        if (b.infinite_mass)
            q.w(" -- infinite mass: a finite impulse does not affect it, v′_C = v_C and ω′ = ω (the notes' m2 → ∞ case)");
        else if (p.immovable(i))
            q.w(" -- a particle pinned at a fixed point cannot move");
        else if (b.particle)
            q.w(" -- a particle: " + number_word(nv) + " velocity components, no angular velocity");
        else if (dim == 2)
            q.w(" -- planar: v′_C has 2 components in the e_n-e_t plane and ω′ only a component along e_b, "
                "because C lies in the plane and e_b is a principal axis at C");
        else
            q.w(" -- 3 components of v′_C and 3 of ω′");
        if (p.pivot_of(i) && !p.immovable(i))
            q.w(" (the pin at E also ties v′_C to ω′, an extra equation)");
        why.push_back(q);
        sum += (sum.empty() ? "" : " + ") + std::to_string(nv + nw);
    }
    if (fr) {
        std::size_t nr = 0;
        for (const unknown& u : d.unknowns)
            if (u.kind == unknown_kind::pivot_impulse)
                ++nr;
        const std::size_t nt = static_cast<std::size_t>(dim - 1);
        std::string text = "impulses: 1 + " + std::to_string(nt) + (nr ? " + " + std::to_string(nr) : "") +
                           " -- with friction the contact impulse has an unknown tangential part, so each body's impulse-momentum "
                           "is written with the impulses as unknowns: the normal impulse N and the " +
                           (dim == 2 ? std::string("friction impulse F along e_t") : std::string("2 components of the friction impulse F in the tangent plane"));
        if (nr)
            text += ", and the " + std::to_string(nr) + " components of the pivot's reaction impulse";
        why.push_back(paragraph().w(text));
        sum += " + 1 + " + std::to_string(nt) + (nr ? " + " + std::to_string(nr) : "");
    } else if (d.impulse_form) {
        std::size_t nr = 0;
        for (const unknown& u : d.unknowns)
            if (u.kind == unknown_kind::pivot_impulse)
                ++nr;
        why.push_back(paragraph().w("impulses: 1 + " + std::to_string(nr) +
                                    " -- with a pivot the notes write impulse-momentum for each body separately, so the normal impulse ∫N dt "
                                    "and the " + std::to_string(nr) + " components of the pivot's reaction impulse become unknowns too"));
        sum += " + 1 + " + std::to_string(nr);
    }
    sec.para(paragraph().w("Two free rigid bodies in 3-D have 3 + 3 unknowns each: 12 in all. Here:"));
    sec.list(why);
    const std::size_t extra = fr ? fr->impulses.size() : 0;
    sec.para(paragraph().w("Number of unknowns: " + sum + " = " + std::to_string(d.count_unknowns() + extra) + "."));
    return sec;
}

namespace {

section impulse_section(const derivation& d)
{
    const problem& p = d.prob;
    const std::size_t i1 = p.contact.body1, i2 = p.contact.body2;
    section sec{"2. The impulses (impulse-momentum diagram in words)", {}};
    std::vector<paragraph> items;
    items.push_back(paragraph().w("At the contact the normal reaction N acts along e_n for a very short time; its impulse ∫N dt acts on " +
                                  body_ref(p, i2) + " along +e_n and on " + body_ref(p, i1) + " along -e_n (action and reaction)."));
    items.push_back(paragraph().w(std::string("The bodies are smooth: the tangential impulse ∫T dt = 0, so no impulse acts along e_t") +
                                  (p.dimension == 3 ? " or e_b." : ".")));
    for (const pivot& pv : p.pivots) {
        paragraph q;
        q.w("The pin at E = ");
        vector_span(q, pv.point, p.dimension);
        q.w(" exerts an unknown reaction impulse R on " + body_ref(p, pv.body) + ".");
        items.push_back(q);
    }
    for (std::size_t i : {i1, i2})
        if (p.bodies[i].infinite_mass)
            items.push_back(paragraph().w(body_ref(p, i) + " has infinite mass: the finite impulse ∫N dt does not change its motion."));
    items.push_back(paragraph().w("Finite forces such as gravity give no impulse over the (almost zero) contact time."));
    sec.list(items);

    std::vector<math_row> rows;
    for (std::size_t i : {i1, i2}) {
        const body& b = p.bodies[i];
        if (b.infinite_mass)
            continue;
        const bool short_label = b.label.size() == 1 && std::isalnum(static_cast<unsigned char>(b.label[0]));
        std::string L = short_label ? b.label : "," + b.label;
        std::string LT = short_label ? b.label : ",\\text{" + names::latex_text(b.label) + "}";
        std::string sign = i == i1 ? "-" : "";
        const pivot* pv = p.pivot_of(i);
        math_row r;
        r.lhs_note = {"m" + L + " (v′_C" + L + " - v_C" + L + ")", "m_{" + LT + "} (\\underline{v}'_{C" + LT + "} - \\underline{v}_{C" + LT + "})"};
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

section equations_section(const derivation& d)
{
    const problem& p = d.prob;
    section sec{"3. The equations", {}};
    if (d.impulse_form)
        sec.para(paragraph().w("A body is pinned, so, as in the notes' constrained collision, impulse-momentum is written for each body "
                               "separately, with ∫N dt and the pivot impulse as unknowns; angular impulse is taken about the pivot E, "
                               "fixed in the inertial frame, where the pivot impulse has no moment."));
    else
        sec.para(paragraph().w("The bodies are unconstrained, so the notes use conservation laws in which the unknown impulse ∫N dt "
                               "does not appear: tangential momentum of each body, linear momentum of the system along e_n, "
                               "angular momentum of each body about O, and restitution."));

    std::size_t k = 0;
    while (k < d.equations.size()) {
        const std::string& base = d.equations[k].reason;
        principle why = d.equations[k].why;
        std::vector<math_row> rows;
        std::size_t j = k;
        for (; j < d.equations.size(); ++j) {
            const equation& eq = d.equations[j];
            if (eq.reason != base || eq.why != why)
                break;
            const std::string c = eq.component >= 0 ? p.axes[static_cast<std::size_t>(eq.component)] + " component" : "";
            rows.push_back(row(eq.lhs, eq.rhs, eq.label, c));
        }
        std::string title = principle_name(why);
        title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(title[0])));
        sec.para(paragraph().w(title + ": " + base + "."));
        if (why == principle::restitution) {
            const std::size_t i1 = p.contact.body1, i2 = p.contact.body2;
            sec.para(paragraph().w("e = -(v′_Bn - v′_An)/(v_Bn - v_An): the velocities are those of the contact points A and B, not of the "
                                   "centres of mass. As A and C1 are both points of body 1, and B and C2 of body 2:"));
            const vec3& n = d.n_hat;
            std::vector<math_row> pv;
            pv.push_back(note_row("v_An = (v_C1 + ω1 × r_AC1)·e_n", "v_{An} = (\\underline{v}_{C_1} + \\underline{\\omega}_1 \\times \\underline{r}_{AC_1})\\cdot\\hat{\\underline{e}}_n",
                                  tidy_expand(dot(d.vA, n))));
            pv.push_back(note_row("v′_An = (v′_C1 + ω′1 × r_AC1)·e_n", "v'_{An} = (\\underline{v}'_{C_1} + \\underline{\\omega}'_1 \\times \\underline{r}_{AC_1})\\cdot\\hat{\\underline{e}}_n",
                                  tidy_expand(dot(d.vA_after, n))));
            pv.push_back(note_row("v_Bn = (v_C2 + ω2 × r_BC2)·e_n", "v_{Bn} = (\\underline{v}_{C_2} + \\underline{\\omega}_2 \\times \\underline{r}_{BC_2})\\cdot\\hat{\\underline{e}}_n",
                                  tidy_expand(dot(d.vB, n))));
            pv.push_back(note_row("v′_Bn = (v′_C2 + ω′2 × r_BC2)·e_n", "v'_{Bn} = (\\underline{v}'_{C_2} + \\underline{\\omega}'_2 \\times \\underline{r}_{BC_2})\\cdot\\hat{\\underline{e}}_n",
                                  tidy_expand(dot(d.vB_after, n)),
                                  p.bodies[i2].infinite_mass || p.immovable(i2) ? "B is on a body the impulse cannot move: v′_Bn = v_Bn" : ""));
            (void)i1;
            sec.rows(pv);
            sec.para(paragraph().w("and (v′_Bn - v′_An) = -e (v_Bn - v_An) reads:"));
        }
        sec.rows(rows);
        k = j;
    }
    if (!d.remarks.empty()) {
        sec.para(paragraph().w("Where a principle gives no usable equation:"));
        std::vector<paragraph> items;
        for (const std::string& r : d.remarks)
            items.push_back(paragraph().w(r));
        sec.list(items);
    }
    return sec;
}

section solution_section(const derivation& d, const solution& s)
{
    section sec{"4. Count check and solution", {}};
    const bool ok = d.count_equations() == d.count_unknowns();
    sec.para(paragraph().w(std::to_string(d.count_equations()) + " equations for " + std::to_string(d.count_unknowns()) +
                           " unknowns: " + (ok ? "the count matches, the system can be solved." : "THE COUNT DOES NOT MATCH.")));
    sec.para(paragraph().w("Every unknown changes linearly with the normal impulse N (= ∫N dt along e_n): a free body gets "
                           "v′_C = v_C ± N e_n/m and ω′ = ω ± N I⁻¹(r × e_n), a pinned body turns about E. "
                           "Restitution then fixes N. In closed form, through named intermediates:"));
    sec.rows({note_row("w_i = 1/m_i + (r_i × e_n)·I_i⁻¹(r_i × e_n)", "w_i = \\frac{1}{m_i} + (\\underline{r}_i\\times\\hat{\\underline{e}}_n)\\cdot \\underline{\\underline{I}}_i^{-1}(\\underline{r}_i\\times\\hat{\\underline{e}}_n)", 0,
                       "effective inverse mass of body i at the contact point along e_n, r_i = O - C_i; about the pivot E for a pinned body "
                       "(without 1/m_i); 0 for a body the impulse cannot move"),
              note_row("u = (v_B - v_A)·e_n", "u = (\\underline{v}_B - \\underline{v}_A)\\cdot\\hat{\\underline{e}}_n", 0,
                       "normal velocity of approach, negative for an impact"),
              note_row("N = -(1 + e)·u/(w_1 + w_2)", "N = -\\frac{(1 + e)\\,u}{w_1 + w_2}", 0,
                       "the restitution equation solved for the normal impulse")});
    // The notation rows above carry no value: mark them by an empty relation.
    for (math_row& r : sec.blocks.back().math)
        r.rel = "";

    std::vector<math_row> steps;
    for (const step& st : s.steps)
        steps.push_back(row(st.sym, st.value, "", st.meaning));
    sec.para(paragraph().w("The steps, in order:"));
    sec.rows(steps);
    std::vector<math_row> unknowns;
    for (std::size_t i = 0; i < d.unknowns.size(); ++i)
        unknowns.push_back(row(d.unknowns[i].sym, s.unknown_values.op(i).rhs(), "", d.unknowns[i].meaning));
    sec.para(paragraph().w("Each unknown:"));
    sec.rows(unknowns);
    return sec;
}

// Exact numbers for every step and unknown, with the equations as numbers.
void numbers_walk(section& sec, const derivation& d, const solution& s, const ex& values)
{
    lst steps = s.step_values(values);
    std::vector<math_row> eqs;
    for (const equation& eq : d.equations)
        eqs.push_back(row(tidy_expand(eq.lhs.subs(values)), tidy_expand(eq.rhs.subs(values)), eq.label));
    sec.para(paragraph().w("The equations with these numbers:"));
    sec.rows(eqs);
    std::vector<math_row> rows;
    for (std::size_t i = 0; i < s.steps.size(); ++i) {
        // The step's formula with the inputs substituted, then its number.
        ex formula = s.steps[i].value.subs(values);
        ex v = impactgen::tidy(steps.op(i).rhs());
        math_row out = row(s.steps[i].sym, v, "", decimal_note(v));
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
        ex v = impactgen::tidy(s.unknown_values.op(i).rhs().subs(values).subs(steps));
        unknown_numbers.append(d.unknowns[i].sym == v);
        answers.push_back(row(d.unknowns[i].sym, v, "", decimal_note(v)));
    }
    sec.para(paragraph().w("The unknowns:"));
    sec.rows(answers);
    bool all_zero = true, all_small = true;
    for (const ex& r : residuals(d, s, values)) {
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
                                             " holds to 40 digits (evaluated with 60-digit floats: with these irrational numbers exactness is not decided)."
                                       : "Substituted back, SOME EQUATION DOES NOT HOLD: this is a bug."));
}

section checks_section(const derivation& d, const solution& s, const worked_example* example)
{
    const problem& p = d.prob;
    section sec{"5. Checks", {}};

    // A copy of the problem with a symbol for e, to vary e.
    ex e_val = p.restitution;
    symbol e_sym = is_a<symbol>(e_val) ? ex_to<symbol>(e_val) : symbol_named("e");
    problem pe = p;
    pe.restitution = e_sym;
    derivation de = is_a<symbol>(e_val) ? d : derive(pe);
    solution se = is_a<symbol>(e_val) ? s : solve(de);
    if (!is_a<symbol>(e_val))
        sec.para(paragraph().w("To vary e, the checks below keep e as a symbol; the problem has e = ").m(e_val).w("."));

    const std::vector<step_role> core = {step_role::energy_lost, step_role::normal_impulse, step_role::contact_inverse_mass,
                                         step_role::approach_velocity};
    ex lost = expand_some(se, se.energy_lost, core);
    const step* u_step = find_step(se, step_role::approach_velocity);
    const step* k_step = find_step(se, step_role::contact_inverse_mass);
    const step* N_step = find_step(se, step_role::normal_impulse);
    ex N_val = N_step ? N_step->value : ex(se.normal_impulse);
    ex u = u_step ? ex(u_step->sym) : ex(0);
    // k as N's formula has it: w_1 + w_2, or w_1 alone against an infinite mass.
    ex kk = k_step ? ex(k_step->sym) : (u_step ? impactgen::tidy(-(1 + e_sym) * u / N_val) : ex(0));

    // Energy.
    sec.para(paragraph().w("Kinetic energy lost (bodies of finite mass), the work of the contact impulse:"));
    std::vector<math_row> energy;
    const step* lost_step = find_step(se, step_role::energy_lost);
    if (lost_step)
        energy.push_back(row(lost_step->sym, lost_step->value));
    ex textbook = kk.is_zero() ? ex(0) : (1 - e_sym * e_sym) * pow(u, 2) / (2 * kk);
    bool textbook_ok = !kk.is_zero() && u_step &&
                       vanishes_identically(se, lost - expand_some(se, textbook, core), "the energy check");
    if (textbook_ok && lost_step)
        energy.push_back(row(lost_step->sym, textbook, "", "with N = -(1 + e)·u/k substituted and normal(): 1 - e² ≥ 0 and k > 0, so T_lost ≥ 0"));
    ex at_one = impactgen::tidy(lost.subs(e_sym == 1));
    if (lost_step)
        energy.push_back(row(lost_step->sym, at_one, "", "at e = 1 (substitute e = 1, normal())"));
    sec.rows(energy);
    if (at_one.is_zero())
        sec.para(paragraph().w("At e = 1 no energy is lost: the elastic impact conserves kinetic energy."));
    else
        sec.para(paragraph().w("At e = 1 the loss is not zero: a moving body of infinite mass does work on the other body, and "
                               "its own energy is not counted (see problem-format: that is physics, not an error)."));

    // Limits of e.
    ex N = se.normal_impulse;
    ex sep_symbolic = -e_sym * u;
    sec.para(paragraph().w("The limits of e, in the normal impulse and the normal velocity of separation (v′_B - v′_A)·e_n = -e·u "
                           "(equation (" + de.equations.back().label + ")):"));
    std::vector<math_row> lim;
    math_row r0 = row(N, N_val.subs(e_sym == 0), "e = 0", "plastic: the contact points move on together,");
    r0.note.w(" (v′_B - v′_A)·e_n = ").m(sep_symbolic.subs(e_sym == 0));
    math_row r1 = row(N, N_val.subs(e_sym == 1), "e = 1", "elastic: twice the plastic impulse,");
    r1.note.w(" (v′_B - v′_A)·e_n = ").m(sep_symbolic.subs(e_sym == 1)).w(" = |u|, the contact points separate as fast as they approached");
    lim.push_back(r0);
    lim.push_back(r1);
    sec.rows(lim);

    // m2 -> infinity.
    const std::size_t i2 = p.contact.body2;
    const body& b2 = p.bodies[i2];
    if (b2.infinite_mass) {
        sec.para(paragraph().w("m2 → ∞: body 2 already has infinite mass; the notes' massive case, w_2 = 0 and N = -(1 + e)·u/w_1."));
    } else if (p.immovable(i2)) {
        sec.para(paragraph().w("m2 → ∞: body 2 cannot move under the impulse already (w_2 = 0)."));
    } else {
        // Body 2 grows heavy with its shape kept: m2 -> m2/eps, I_2 -> I_2/eps. Its
        // effective inverse mass scales exactly: w_2(eps) = eps w_2 (1/m and I^-1
        // both scale with eps, about C or about the pivot alike), so with
        // k = w_1 + eps w_2 the impulse tends to the notes' massive case and body
        // 2's velocity change N n eps/m2 tends to zero. No symbolic limit is
        // taken (normal() of a 3-D closed form has no useful time bound).
        const step* w1 = find_step(se, step_role::effective_inverse_mass, p.contact.body1);
        const ex w1_value = w1 ? ex(w1->sym) : (p.immovable(p.contact.body1) ? ex(0) : 1 / p.bodies[p.contact.body1].mass);
        paragraph q;
        q.w("m2 → ∞: let body 2 grow heavy with its shape kept, m2 → m2/ε and its inertia → I/ε, and take ε → 0. "
            "Both 1/m2 and I⁻¹ scale with ε, so w_2 → ε·w_2 exactly and k → w_1 + ε·w_2:");
        sec.para(q);
        std::vector<math_row> rows;
        math_row rw = row(show("w_2", "w_2"), 0, "", "body 2 no longer yields at B");
        rw.rel = "→";
        rows.push_back(rw);
        if (!w1_value.is_zero()) {
            ex N_inf = -(1 + e_sym) * u / w1_value;
            math_row rn = row(N, N_inf, "", "finite: the notes' massive case, N = -(1 + e)·u/w_1");
            rn.rel = "→";
            rows.push_back(rn);
            math_row rv = note_row("|v′_C2 - v_C2|²", "|\\underline{v}'_{C_2} - \\underline{v}_{C_2}|^2", 0,
                                   "ω′_2 ≈ ω_2 and v′_C2 ≈ v_C2: body 2 is unaffected (its change N·ε/m2 → 0)");
            rv.rel = "→";
            rows.push_back(rv);
        }
        sec.rows(rows);
    }

    // Numbers.
    if (p.is_numeric()) {
        sec.para(paragraph().w("The problem is numeric: every step and unknown above is an exact number."));
        numbers_walk(sec, d, s, lst{});
    } else if (example) {
        sec.para(paragraph().w("Worked example (" + example->caption + "): substitute"));
        std::vector<math_row> vals;
        for (const ex& rel : example->values)
            vals.push_back(row(rel.lhs(), rel.rhs()));
        sec.rows(vals);
        numbers_walk(sec, d, s, example->values);
    }
    return sec;
}

} // namespace

bool notes_example(const std::string& class_name, worked_example& out)
{
    if (class_name != "pinned-planar")
        return false;
    out.caption = "the notes' example: a ball of 0.5 kg at 5 m/s strikes the lower end of a hanging rod of 2 kg and 1 m, e = 0.8";
    out.values = lst{symbol_named("m1") == numeric(1, 2), symbol_named("v1") == 5, symbol_named("m2") == 2,
                     symbol_named("l") == 1, symbol_named("e") == numeric(4, 5)};
    return true;
}

document explain(const derivation& d, const solution& s, const worked_example* example)
{
    document doc;
    doc.title = "Smooth impact: " + d.prob.source;
    doc.sections.push_back(setup_section(d));
    doc.sections.push_back(impulse_section(d));
    doc.sections.push_back(equations_section(d));
    doc.sections.push_back(solution_section(d, s));
    doc.sections.push_back(checks_section(d, s, example));
    return doc;
}

} // namespace impactgen::print
