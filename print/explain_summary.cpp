// The results of a summary document (level::summary): each candidate's unknowns in a box,
// in closed form in the problem's symbols where that is short -- the numerator gathered on
// the velocities before impact, as textbooks write v′₁ = ((m₁ - e m₂) v₁ + (1 + e) m₂ v₂)/(m₁ + m₂)
// -- else through the named steps it needs; then the problem's (or the example's) numbers.
#include "explain_law.hpp"

#include "canonical.hpp"
#include "explain_process.hpp"
#include "expression.hpp"
#include "symbolic/decide.hpp"

#include <set>
#include <string>
#include <vector>

namespace impactgen::print::detail
{
using namespace GiNaC;

namespace
{

// Short enough for a summary's box.
constexpr int closed_form_nodes = 60;

quantity quantity_of(unknown_kind k)
{
    return k == unknown_kind::velocity           ? quantity::velocity
           : k == unknown_kind::angular_velocity ? quantity::angular_velocity
                                                 : quantity::impulse;
}

// The symbols of the velocities and angular velocities before impact.
std::vector<ex> before_symbols(const problem &p)
{
    std::vector<ex> out;
    std::set<ex, ex_is_less> seen;
    for (const body &b : p.bodies)
        for (const vec3 *v : {&b.velocity, &b.angular_velocity})
            for (int k = 0; k < 3; ++k)
                for (const_preorder_iterator it = (*v)[k].preorder_begin(); it != (*v)[k].preorder_end(); ++it)
                    if (is_a<symbol>(*it) && seen.insert(*it).second)
                        out.push_back(*it);
    return out;
}

// x over one denominator, its numerator gathered on the velocities before impact, every
// coefficient factored.
ex gathered(const ex &x, const std::vector<ex> &velocities)
{
    const ex q = normal(x);
    const ex num = expand(numer(q));
    ex out = 0, rest = num;
    for (const ex &v : velocities) {
        const ex c = num.coeff(v, 1);
        if (c.is_zero())
            continue;
        out += factored(c) * v;
        rest -= c * v;
    }
    return (out + factored(expand(rest))) / factored(denom(q));
}

// The rows of one candidate: its normal impulse and each unknown, closed or in steps; `used`
// collects the steps they need.
std::vector<math_row> candidate_rows(const derivation &d, const solution &s, std::vector<bool> &used)
{
    const std::vector<ex> velocities = before_symbols(d.prob);
    std::vector<ex> in_steps;
    std::vector<math_row> rows;
    const step *n = s.find(step_role::normal_impulse);
    bool n_closed = false;
    bool n_unknown = false; // with a pivot the normal impulse is an unknown: its row comes with theirs
    for (const unknown &u : d.unknowns)
        n_unknown = n_unknown || (n && u.kind == unknown_kind::normal_impulse);
    if (n && !n_unknown) {
        const ex closed = s.expand_steps(n->value);
        n_closed = printable(closed, closed_form_nodes);
        if (n_closed)
            rows.push_back(row(n->sym, closed, "", step_note(d.prob, *n)));
        else {
            rows.push_back(row(n->sym, n->value, "", step_note(d.prob, *n)));
            in_steps.push_back(n->value);
        }
    }
    for (std::size_t i = 0; i < d.unknowns.size() && i < s.unknown_values.nops(); ++i) {
        const ex value = s.unknown_values.op(i).rhs();
        const ex closed = s.expand_steps(value);
        ex shown = value;
        if (printable(closed, 150)) {
            const ex g = gathered(closed, velocities);
            if (printable(g, closed_form_nodes))
                shown = g;
        }
        if (shown.is_equal(value))
            in_steps.push_back(value);
        rows.push_back(row(d.unknowns[i].sym, shown)); // their meaning: the legend before the box
    }
    // steps refer to earlier steps only: one pass from the last marks every step needed
    for (std::size_t k = s.steps.size(); k-- > 0;) {
        if (n_closed && s.steps[k].sym == n->sym)
            continue; // shown in closed form above
        bool need = used[k];
        for (const ex &e : in_steps)
            need = need || e.has(s.steps[k].sym);
        for (std::size_t j = k + 1; j < s.steps.size() && !need; ++j)
            need = used[j] && s.steps[j].value.has(s.steps[k].sym);
        used[k] = need;
    }
    return rows;
}

std::vector<math_row> step_rows(const problem &p, const solution &s, const std::vector<bool> &used)
{
    std::vector<math_row> rows;
    for (std::size_t k = 0; k < s.steps.size(); ++k)
        if (used[k] && s.steps[k].role != step_role::normal_impulse)
            rows.push_back(row(s.steps[k].sym, s.steps[k].value, "", step_note(p, s.steps[k])));
    return rows;
}

// Rows whose value is 0 merged into one, "v′_y1 = R_y2 = 0", after the others.
std::vector<math_row> zeros_merged(const std::vector<math_row> &rows)
{
    std::vector<math_row> out;
    std::string text, tex;
    for (const math_row &r : rows) {
        if (r.rel == "=" && r.lhs_note.text.empty() && !r.has_then && r.rhs.is_zero() && is_a<symbol>(r.lhs)) {
            text += canonical_text(r.lhs) + " = ";
            tex += symbol_latex(ex_to<symbol>(r.lhs)) + " = ";
        } else {
            out.push_back(r);
        }
    }
    if (!text.empty())
        out.push_back(formula_row(text + "0", tex + "0"));
    return out;
}

paragraph case_heading(const regime_case &c)
{
    paragraph q;
    if (c.kind == regime::stick)
        return q.t("If the contact sticks ($u′_t = 0$):");
    q.t("If the contact slides");
    if (c.sign > 0)
        q.t(" along $+e_t$");
    else if (c.sign < 0)
        q.t(" along $-e_t$");
    return q.w(":");
}

bool has_float(const ex &v)
{
    for (const_preorder_iterator it = v.preorder_begin(); it != v.preorder_end(); ++it)
        if (is_a<numeric>(*it) && !ex_to<numeric>(*it).is_rational())
            return true;
    return false;
}

// The numbers: every unknown of the numeric problem's regime that holds, or of the worked example.
void numbers(section &sec, const explain_input &in)
{
    const derivation *nd = in.numeric_d ? in.numeric_d : in.d.prob.is_numeric() ? &in.d : nullptr;
    const impact_solution *ns = in.numeric_s ? in.numeric_s : &in.s;
    const problem &p = nd ? nd->prob : in.d.prob;
    std::vector<math_row> rows;
    const std::vector<unknown> &unknowns = nd ? nd->unknowns : in.d.unknowns;
    lst values;
    solution sol;
    if (nd) {
        try {
            const regime_case c = select_candidate(*nd, *ns);
            sol = c.sol;
            if (ns->cases.size() > 1)
                sec.para(paragraph()
                             .t("With the problem's numbers the contact ")
                             .t(c.kind == regime::stick ? "sticks"
                                : c.sign > 0            ? "slides along $+e_t$"
                                : c.sign < 0            ? "slides along $-e_t$"
                                                        : "slides")
                             .w("."));
            if (ns->cases.size() > 1 && slip_stops_or_reverses(*nd, c))
                sec.para(slip_warning(c.kind == regime::stick));
        } catch (const std::exception &e) {
            sec.para(paragraph().w("With the problem's numbers no single regime holds: " + std::string(e.what())));
            return;
        }
    } else if (in.example && in.s.cases.size() == 1) {
        values = in.example->values;
        sol = in.s.cases.front().sol;
        sec.para(paragraph().w("Worked example (" + in.example->caption + "):"));
    } else {
        return;
    }
    for (std::size_t i = 0; i < unknowns.size() && i < sol.unknown_values.nops(); ++i) {
        const ex v = surd_form(impactgen::tidy(sol.expand_steps(sol.unknown_values.op(i).rhs()).subs(values)));
        if (has_float(v)) {
            // a root found numerically (3-D sliding): its last digits follow GiNaC's run-to-run
            // order of evaluation, so it is given to 15 digits, as the full document gives it
            const std::string dec = decimal(v), u = unit(p, quantity_of(unknowns[i].kind));
            rows.push_back(formula_row(canonical_text(unknowns[i].sym) + " ≈ " + dec + u,
                                       canonical_latex(unknowns[i].sym) + " \\approx " + dec +
                                           (u.empty() ? "" : "\\text{" + u + "}")));
            continue;
        }
        math_row r = row(unknowns[i].sym, v, "", decimal_note(v));
        r.note.w(unit(p, quantity_of(unknowns[i].kind)));
        rows.push_back(r);
    }
    sec.boxed_rows(zeros_merged(rows));
}

// Every value of x's own steps (the candidate's, not the shared ones) substituted, last first:
// a step refers to earlier steps only.
ex through_own_steps(const solution &s, const std::set<ex, ex_is_less> &shared, ex x)
{
    for (std::size_t k = s.steps.size(); k-- > 0;)
        if (!shared.count(s.steps[k].sym))
            x = x.subs(s.steps[k].sym == s.steps[k].value);
    return x;
}

// The step of s that stands for the same quantity as st (its role, body and component), when
// exactly one does: candidates name their steps with symbols of their own.
const step *counterpart(const solution &s, const step &st)
{
    const step *found = nullptr;
    for (const step &x : s.steps)
        if (x.role == st.role && x.body == st.body && x.row == st.row && x.column == st.column) {
            if (found)
                return nullptr;
            found = &x;
        }
    return found;
}

// The shared steps that rows' values need (steps refer to earlier steps only).
std::vector<math_row> shared_rows(const problem &p, const solution &shared, const std::vector<ex> &values)
{
    std::vector<bool> used(shared.steps.size(), false);
    for (std::size_t k = shared.steps.size(); k-- > 0;) {
        bool need = false;
        for (const ex &e : values)
            need = need || e.has(shared.steps[k].sym);
        for (std::size_t j = k + 1; j < shared.steps.size() && !need; ++j)
            need = used[j] && shared.steps[j].value.has(shared.steps[k].sym);
        used[k] = need;
    }
    return step_rows(p, shared, used);
}

// Several candidates whose unknowns read the same in the contact impulse's components (Coulomb
// friction): the unknowns once, then each candidate's impulse through the shared steps alone.
bool candidates_by_impulse(section &sec, const explain_input &in)
{
    const solution &first = in.s.cases.front().sol;
    // each candidate names its steps with symbols of its own: map them onto the first's by what they are
    for (const regime_case &c : in.s.cases) {
        exmap rename;
        for (const step &st : c.sol.steps)
            if (const step *f = counterpart(first, st))
                rename[st.sym] = f->sym;
        if (c.sol.unknown_values.nops() != first.unknown_values.nops())
            return false;
        for (std::size_t i = 0; i < first.unknown_values.nops(); ++i)
            if (!expand(c.sol.unknown_values.op(i).rhs().subs(rename) - first.unknown_values.op(i).rhs()).is_zero())
                return false;
    }
    std::set<ex, ex_is_less> shared;
    for (const step &st : in.s.shared.steps)
        shared.insert(st.sym);
    std::vector<ex> impulse; // the candidate's steps the unknowns name
    for (const step &st : first.steps)
        if (!shared.count(st.sym) && first.unknown_values.has(st.sym))
            impulse.push_back(st.sym);
    std::vector<ex> values;
    std::vector<math_row> impulses; // every regime's, its name on the symbol: P_t^stick
    for (const regime_case &c : in.s.cases) {
        const std::string tex = c.kind == regime::stick ? "\\text{stick}"
                                : c.sign > 0            ? "\\text{slide}+"
                                : c.sign < 0            ? "\\text{slide}-"
                                                        : "\\text{slide}";
        const std::string text = c.kind == regime::stick ? "stick"
                                 : c.sign > 0            ? "slide along +e_t"
                                 : c.sign < 0            ? "slide along -e_t"
                                                         : "slide";
        for (const ex &sym : impulse)
            for (const step &f : first.steps)
                if (const step *mine = sym.is_equal(f.sym) ? counterpart(c.sol, f) : nullptr) {
                    const step &st = *mine;
                    const ex v = through_own_steps(c.sol, shared, st.value);
                    math_row r = row(sym, v);
                    r.lhs_note = {canonical_text(sym) + " (" + text + ")", symbol_latex(st.sym) + "^{" + tex + "}"};
                    impulses.push_back(r);
                    values.push_back(v);
                }
    }
    std::vector<math_row> with = shared_rows(in.d.prob, in.s.shared, values);
    if (!with.empty()) {
        for (math_row &r : with) { // K_tt = 1/m1 + 1/m2 + r_n1²/I1 + ... reads flatter than over one denominator
            r.note = paragraph();
            const ex flat = expand(r.rhs);
            if (printable(flat, closed_form_nodes))
                r.rhs = flat;
        }
        sec.para(paragraph().t("With the entries of the contact response $~~K$ (the change of the relative velocity "
                               "$~u = ~v_B - ~v_A$ of the contact points per unit impulse on body 2) and $~u$ "
                               "before impact:"));
        sec.packed_rows(with);
    }
    std::vector<math_row> unknowns;
    for (std::size_t i = 0; i < in.d.unknowns.size() && i < first.unknown_values.nops(); ++i)
        unknowns.push_back(row(in.d.unknowns[i].sym, first.unknown_values.op(i).rhs()));
    sec.para(paragraph().w("In every regime:"));
    sec.boxed_rows(zeros_merged(unknowns));
    sec.para(paragraph().t("The impulse in each regime, stick ($u′_t = 0$) or slide; the contact sticks when the "
                           "stick impulse has $|P_t| ≤ μ P_n$, else it slides:"));
    sec.boxed_rows(impulses);
    return true;
}

// Routh's process in a summary: the phases, the end of compression and the end of restitution by
// the contact's law (Poisson's impulse ratio or Stronge's work ratio).
void process_rows(std::vector<math_row> &rows, const std::string &e_n, const explain_input &in)
{
    rows.push_back(formula_row("slide along d: dP = (e_n - μ d) dN;  stick: u_t = 0 with |P_t| ≤ μ P_n",
                               "\\text{slide along } \\hat{\\underline{d}}:\\ d\\underline{P} = (" + e_n +
                                   " - \\mu\\hat{\\underline{d}})\\,dN;\\quad \\text{stick: } u_t = 0,\\ |P_t| "
                                   "\\le \\mu P_n"));
    rows.push_back(formula_row("end of compression: u_n = 0 at N = N_c",
                               "\\text{end of compression: } u_n = 0 \\text{ at } N = N_c"));
    rows.push_back(words_of(in.d.prob.contact().law_of_restitution).summary_end);
}

// The rows of a summary in vector form, for free bodies whose steps are too many to list (3-D
// bodies with full inertia tensors): r_i = O - C_i locates the contact point from body i's
// centre of mass; the impulse P acts on body 2 and -P on body 1.
void vector_form(section &sec, const explain_input &in)
{
    const bool friction = in.s.cases.size() > 1;
    const std::string e_n = "\\hat{\\underline{e}}_n", P = friction ? "\\underline{P}" : "N\\," + e_n;
    const std::string Pt = friction ? "P" : "N e_n";
    paragraph with;
    with.t("With $~r_1 = O - C1$ and $~r_2 = O - C2$ (the contact point seen from each centre of mass), $~u = ~v_B - "
           "~v_A$ the relative velocity of the contact points before impact and $u_n = ~u·e_n$");
    if (friction)
        with.t(", and $~~K$ the contact response ($~u + ~~K ~P$ is the relative velocity after impact)");
    sec.para(with.w(":"));
    std::vector<math_row> rows;
    if (!friction)
        rows.push_back(formula_row("N = -(1 + e) u_n/(w_1 + w_2),  w_i = 1/m_i + (r_i × e_n)·I_i⁻¹(r_i × e_n)",
                                   "N = -\\frac{(1 + e)\\,u_n}{w_1 + w_2},\\quad w_i = \\frac{1}{m_i} + "
                                   "(\\underline{r}_i \\times " +
                                       e_n +
                                       ")\\cdot\\underline{\\underline{I}}_i^{-1}"
                                       "(\\underline{r}_i \\times " +
                                       e_n + ")"));
    const std::size_t ids[2] = {in.d.prob.contact().body1, in.d.prob.contact().body2};
    for (int k = 0; k < 2; ++k) {
        const body &b = in.d.prob.bodies[ids[k]];
        const std::string i = std::to_string(k + 1), sign = k ? " + " : " - ";
        if (b.infinite_mass) {
            rows.push_back(formula_row("v′_C" + i + " = v_C" + i + ",  ω′_" + i + " = ω_" + i,
                                       "\\underline{v}'_{C" + i + "} = \\underline{v}_{C" + i +
                                           "},\\quad \\underline{\\omega}'_" + i + " = \\underline{\\omega}_" + i,
                                       "(infinite mass)"));
            continue;
        }
        std::string text = "v′_C" + i + " = v_C" + i + sign + Pt + "/m_" + i,
                    tex = "\\underline{v}'_{C" + i + "} = \\underline{v}_{C" + i + "}" + sign + "\\frac{" + P + "}{m_" +
                          i + "}";
        if (!b.particle) {
            text += ",  ω′_" + i + " = ω_" + i + sign + "I_" + i + "⁻¹(r_" + i + " × " + Pt + ")";
            tex += ",\\quad \\underline{\\omega}'_" + i + " = \\underline{\\omega}_" + i + sign +
                   "\\underline{\\underline{I}}_" + i + "^{-1}(\\underline{r}_" + i + " \\times " + P + ")";
        }
        rows.push_back(formula_row(text, tex));
    }
    if (friction && follows_process(in.d.prob.contact().law_of_restitution)) {
        // restitution followed through the impact (Routh): the impulse grows phase by phase, so
        // the law is stated, not Newton's end-of-impact formula
        process_rows(rows, e_n, in);
        sec.boxed_rows(rows);
        sec.para(paragraph().t("The contact's relative velocity changes linearly with the impulse within each phase; "
                               "the phases, where each ends and the impulse $~P$ at the end of restitution are "
                               "derived phase by phase in the full derivation."));
        return;
    }
    if (friction) {
        rows.push_back(formula_row("stick (u′_t = 0): P = -K⁻¹(u + e u_n e_n)",
                                   "\\text{stick } (u'_t = 0):\\quad \\underline{P} = -\\underline{\\underline{K}}^{-1}"
                                   "(\\underline{u} + e\\,u_n " +
                                       e_n + ")"));
        rows.push_back(formula_row("slide along d: P = N (e_n - μ d),  N = -(1 + e) u_n/(e_n·K(e_n - μ d))",
                                   "\\text{slide along } \\hat{\\underline{d}}:\\quad \\underline{P} = N(" + e_n +
                                       " - \\mu\\hat{\\underline{d}}),\\quad N = -\\frac{(1 + e)\\,u_n}{" + e_n +
                                       "\\cdot\\underline{\\underline{K}}(" + e_n + " - \\mu\\hat{\\underline{d}})}"));
    }
    sec.boxed_rows(rows);
}

} // namespace

section summary_results(const explain_input &in)
{
    section sec{"Results", {}};
    section parts{"", {}};
    const bool several = in.s.cases.size() > 1;
    paragraph legend;
    legend.t("A prime marks a value after impact; $~v$ is the velocity of a centre of mass, $ω$ an angular velocity");
    if (several)
        legend.t(", $~P$ the contact impulse on body 2");
    if (!in.d.prob.pivots.empty())
        legend.t(", $R$ a pivot's impulse");
    sec.para(legend.t("; the subscripts name the axis and the body."));
    // several candidates: the unknowns once in the impulse's components where they read the same
    const bool by_impulse = several && candidates_by_impulse(parts, in);
    // A problem worked with its numbers only (Routh's process is not taught in symbols first):
    // its candidates' rows are the values numbers() boxes below with their decimals.
    const bool numbers_only = !in.numeric_d && in.d.prob.is_numeric();
    for (std::size_t k = 0; k < in.s.cases.size() && !by_impulse && !numbers_only; ++k) {
        const regime_case &c = in.s.cases[k];
        std::vector<bool> used(c.sol.steps.size(), false);
        const std::vector<math_row> rows = candidate_rows(in.d, c.sol, used);
        if (several)
            parts.para(case_heading(c));
        const std::vector<math_row> steps = step_rows(in.d.prob, c.sol, used);
        if (!steps.empty()) {
            parts.para(paragraph().w("With"));
            parts.packed_rows(steps);
        }
        parts.boxed_rows(zeros_merged(rows));
    }
    if (several && !by_impulse)
        parts.para(paragraph().t("The contact sticks when the stick impulse has $|P_t| ≤ μ P_n$; else it slides."));
    // too many steps to list (bodies with full inertia tensors): the vector form instead
    std::size_t listed = 0;
    for (const block &b : parts.blocks)
        listed += b.k == block::rows && !b.boxed ? b.math.size() : 0;
    if (listed > 5 && in.d.prob.pivots.empty())
        vector_form(sec, in);
    else
        for (block &b : parts.blocks)
            sec.blocks.push_back(b);
    numbers(sec, in);
    return sec;
}

} // namespace impactgen::print::detail
