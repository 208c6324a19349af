// explain_system(): the explanation of a system (problem format version 3: joints, several
// contacts, "friction": "inf", sequential impacts) the way the notes treat constrained
// collisions -- every body separately, every impulse an unknown.
//
// Everything shown comes from the derivation (symbolic/system_derivation.cpp: the equations,
// the unknowns, each contact's acting law) and from the solver (symbolic/system.hpp: the
// Delassus matrix, the candidates with their conditions, which one holds -- decided by the
// solver's own exact test, system_candidate_failure -- and the answer, or the chain of
// single-contact impacts). Nothing here solves or decides anything itself.
#include "explain_system.hpp"
#include "explain.hpp"
#include "explain_detail.hpp"
#include "explain_process.hpp"
#include "title.hpp"

#include "figure/system.hpp"
#include "symbolic/named_systems.hpp"
#include "symbolic/system_process.hpp"

#include <exception>
#include <optional>
#include <string>
#include <vector>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{
using namespace detail;

std::string idx(std::size_t i)
{
    return std::to_string(i);
}

// A value as math, with its decimal digits when it is a number that is not a short decimal.
paragraph &value(paragraph &q, const ex &v)
{
    if (!printable(v))
        return q.w("(an expression too long to print; 'impactgen formulas' gives it)");
    q.m(v);
    const std::string dec = decimal_digits(v);
    if (!dec.empty())
        q.w(" ").n("≈ " + dec, "\\approx " + dec);
    return q;
}

math_row value_row(const ex &lhs, const ex &rhs, const std::string &note)
{
    math_row r = row(lhs, printable(rhs) ? rhs : ex(0), "", note);
    if (!printable(rhs))
        r.note = paragraph().w("too long to print; 'impactgen formulas' gives it");
    else if (!decimal_digits(rhs).empty())
        r.note = decimal_note(rhs).w(note.empty() ? "" : ": " + note);
    return r;
}

// A body as the statement gives it: its mass, inertia, centre and motion before impact.
paragraph body_item(const problem &p, const body &B)
{
    paragraph q;
    q.w(display_name(B) + ": ");
    if (B.infinite_mass) {
        q.w("infinite mass (it keeps its motion), velocity ");
        return vector_span(q, B.velocity, p.dimension);
    }
    q.w("mass ").m(B.mass);
    if (!B.particle) {
        q.w(", moment of inertia about its centre ");
        if (p.dimension == 2)
            q.m(B.inertia[2][2]);
        else
            q.w("(a matrix)");
    }
    vector_span(q.w(", centre at "), B.position, p.dimension);
    vector_span(q.w(", velocity before "), B.velocity, p.dimension);
    if (!B.particle && p.dimension == 2)
        q.w(", angular velocity before ").m(B.angular_velocity[2]);
    else if (!B.particle)
        vector_span(q.w(", angular velocity before "), B.angular_velocity, 3);
    return q.w(B.particle ? " (a particle)" : "");
}

std::vector<paragraph> body_items(const problem &p)
{
    std::vector<paragraph> items;
    for (const body &B : p.bodies)
        items.push_back(body_item(p, B));
    return items;
}

std::vector<paragraph> link_items(const problem &p)
{
    std::vector<paragraph> items;
    for (std::size_t j = 0; j < p.joints.size(); ++j) {
        const joint &J = p.joints[j];
        paragraph q;
        q.w("Joint " + idx(j) + " (" + (p.dimension == 2 ? "a pin" : "a ball joint") + ") joins " +
            display_name(p.bodies[J.body1]) + " and " + display_name(p.bodies[J.body2]) + " at ");
        items.push_back(vector_span(q, J.point, p.dimension));
    }
    for (std::size_t k = 0; k < p.pivots.size(); ++k) {
        paragraph q;
        q.w("Pivot " + idx(k) + " holds " + display_name(p.bodies[p.pivots[k].body]) + " at the fixed point ");
        items.push_back(vector_span(q, p.pivots[k].point, p.dimension));
    }
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const contact_spec &c = p.contacts[i];
        paragraph q;
        q.w("Contact " + idx(i) + ": between " + display_name(p.bodies[c.body1]) + " and " +
            display_name(p.bodies[c.body2]) + " at ");
        vector_span(q, c.point, p.dimension);
        vector_span(q.w(", normal "), c.normal, p.dimension)
            .w(" (from " + display_name(p.bodies[c.body1]) + " into " + display_name(p.bodies[c.body2]) + "), ");
        q.n("e_" + idx(i), "e_{" + idx(i) + "}").w(" = ").m(p.restitution_of(i));
        if (c.rough)
            q.w(", perfectly rough (no slip while it pushes)");
        else if (!c.friction().is_zero())
            q.w(", Coulomb friction with the coefficient ").m(c.friction());
        else
            q.w(", smooth");
        if (!c.rough && !c.friction().is_zero() && std::holds_alternative<poisson_restitution>(c.law_of_restitution))
            q.w("; restitution measured by impulses through the impact (Poisson)");
        else if (!c.rough && !c.friction().is_zero() &&
                 std::holds_alternative<energetic_restitution>(c.law_of_restitution))
            q.w("; restitution measured by work through the impact (energetic)");
        items.push_back(q);
    }
    return items;
}

// The figure of a numeric planar system, joint impulses drawn along the answer; or nothing.
// A symbolic system is drawn with its worked example's numbers, when it has one.
std::optional<figure_art> system_figure(const problem &symbolic, const worked_example *example)
{
    const bool illustrated = !symbolic.is_numeric() && example;
    const problem p = illustrated ? substitute(symbolic, example->values) : symbolic;
    std::optional<system_answer> a;
    try {
        a = solve_system(p);
    } catch (const std::exception &) {
        a.reset();
    }
    const std::optional<figure::drawing> g = figure::draw_system(p, a ? &a->result.joint_impulses : nullptr);
    if (!g)
        return std::nullopt;
    figure_art art;
    art.tikz = figure::to_tikz(*g);
    art.svg = figure::to_svg(*g);
    art.alt = figure::describe(*g);
    art.caption = "The system as the problem gives it: every body through its joints, pivots and contact points, "
                  "the joints J with their impulse on the second body and the reaction on the first" +
                  std::string(a ? " (along the answer)" : "") +
                  ", the contact points O with the normal impulses P, and the velocities before impact." +
                  (illustrated ? std::string(" Drawn with the worked example's numbers.") : std::string()) +
                  figure::directions_note(*g);
    return art;
}

// "A planar (2-D) system of 3 bodies, 1 joint, no pivot and 2 contacts; ..."
std::string system_sentence(const problem &p)
{
    std::vector<std::string> parts{count_of(p.bodies.size(), "body", "bodies")};
    if (!p.joints.empty())
        parts.push_back(count_of(p.joints.size(), "joint", "joints"));
    if (!p.pivots.empty())
        parts.push_back(count_of(p.pivots.size(), "pivot", "pivots"));
    parts.push_back(count_of(p.contacts.size(), "contact", "contacts"));
    std::string out = "A " + std::string(p.dimension == 2 ? "planar (2-D)" : "spatial (3-D)") + " system of ";
    for (std::size_t k = 0; k < parts.size(); ++k)
        out += (k == 0 ? "" : k + 1 == parts.size() ? " and " : ", ") + parts[k];
    if (p.contacts.size() < 2)
        return out + ".";
    return out + (p.sequential ? "; the contacts act one at a time, in sequence."
                               : "; the contacts act at the same time (simultaneous impacts).");
}

section setup(const derivation &d, const worked_example *example, bool summary = false)
{
    const problem &p = d.prob;
    section s{"The system", {}};
    s.para(paragraph().w(system_sentence(p)));
    s.list(body_items(p));
    s.list(link_items(p));
    if (const std::optional<figure_art> art = system_figure(p, example))
        s.picture(*art);
    if (summary)
        return s;
    s.para(paragraph().t("The notes' method for constrained collisions: write the impulse-momentum of each body "
                         "separately, with every impulse that acts on it -- at each joint, pivot and contact -- "
                         "as an unknown. A joint's impulse acts on its second body and its opposite on the first "
                         "(action and reaction). Finite forces (gravity) give no impulse."));
    return s;
}

section unknowns(const derivation &d)
{
    section s{"The unknowns", {}};
    std::vector<paragraph> items;
    for (const auto &u : d.system_unknowns)
        items.push_back(paragraph().m(u.first).w(": " + u.second));
    std::size_t law_rows = 0;
    for (const auto &l : d.system_laws)
        law_rows += l.size();
    s.para(paragraph().w(idx(d.system_unknowns.size()) + " unknowns, body by body and then every impulse:"));
    s.list(items);
    s.para(paragraph().w("The bodies and joints give " + idx(d.equations.size()) +
                         " equations below; each contact adds, while it acts, its law (" + idx(law_rows) +
                         " equations in all), or else carries no impulse. Which contacts act is what the law "
                         "decides."));
    return s;
}

std::vector<section> equation_sections(const derivation &d)
{
    section bodies{"Impulse and momentum of each body", {}}, links{"The joints' and pivots' conditions", {}};
    const problem &p = d.prob;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        std::vector<math_row> rows;
        for (const equation &e : d.equations)
            if (e.why != principle::pivot_fixed && e.bodies.size() == 1 && e.bodies[0] == b)
                rows.push_back(row(e.lhs, e.rhs, e.label, e.reason));
        if (rows.empty())
            continue;
        bodies.para(paragraph().w(display_name(p.bodies[b]) + ":"));
        bodies.rows(rows);
    }
    std::vector<math_row> rows;
    for (const equation &e : d.equations)
        if (e.why == principle::pivot_fixed)
            rows.push_back(row(e.lhs, e.rhs, e.label, e.reason));
    std::vector<section> out{bodies};
    if (!rows.empty()) {
        links.para(paragraph().t("A joint has no restitution: the two bodies' material points at the joint move "
                                 "together after impact (they did before), and a pivot point stays at rest."));
        links.rows(rows);
        out.push_back(links);
    }
    return out;
}

section law_section(const derivation &d)
{
    const problem &p = d.prob;
    section s{"The contact law", {}};
    s.para(paragraph().t("With $u_i$ the normal velocity of approach of contact $i$ before impact (along its "
                         "normal, from the first body into the second) and $u'_i$ after, every contact obeys at "
                         "the same time the generalized Newton law: its impulse pushes, the contact does not "
                         "interpenetrate, and it pushes only when it leaves at exactly $e_i$ times its approach:"));
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const std::string n = idx(i);
        std::vector<math_row> rows{formula_row("0 ≤ P_" + n + ",  u′_" + n + " + e_" + n + " u_" + n + " ≥ 0,  P_" + n +
                                                   " (u′_" + n + " + e_" + n + " u_" + n + ") = 0",
                                               "0 \\le P_" + n + ",\\quad u'_" + n + " + e_" + n + " u_" + n +
                                                   " \\ge 0,\\quad P_" + n + "\\,(u'_" + n + " + e_" + n + " u_" + n +
                                                   ") = 0",
                                               paragraph().w("contact " + n))};
        for (const equation &e : d.system_laws[i])
            rows.push_back(row(e.lhs, e.rhs, "", e.reason));
        paragraph head;
        head.w("Contact " + n + " ");
        if (p.contacts[i].rough)
            head.w("(perfectly rough: while it pushes it sticks)");
        else if (p.contacts[i].friction().is_zero())
            head.w("(smooth: no tangential impulse)");
        else
            head.t("(Coulomb: it sticks inside the cone $|F| ≤ μ P$, else slides with $|F| = μ P$ against the slip)");
        s.para(head.w(":"));
        s.rows(rows);
    }
    return s;
}

section delassus_section(const problem &p, const system_delassus &D)
{
    section s{"The Delassus matrix", {}};
    s.para(paragraph().t(
        "Collect the generalized velocities $v$ (per body: its centre's velocity, then its angular velocity) "
        "and write every joint, pivot and contact direction as a row $a_r$ of the relative velocity it "
        "constrains. Then $M (v' - v) = A^T λ$ and the rows' velocities change by $H λ$ with $H = A M⁻¹ A^T$."));
    s.para(paragraph().t(
        "The joints and pivots are kept as rows whose velocity after impact is zero and whose impulse is free, "
        "and are eliminated once: $λ_J = -H_JJ⁻¹ H_JC λ_C$. What is left is the Delassus matrix of the "
        "contacts, $W = H_CC - H_CJ H_JJ⁻¹ H_JC$, with $u' = u + W λ_C$. Kept as rows rather than replaced by "
        "generalized coordinates, the joints' impulses come out in world components (the joint and pivot "
        "impulses of the results) and no basis of the joints' free motions is needed; since the joints' velocities "
        "before impact are zero, the elimination leaves the contacts' velocities before impact as they are."));
    if (D.redundant_joints)
        s.para(paragraph().w("The joints' rows are dependent: the rows implied by the others are left out "
                             "(with no impulse), so the impulses are one valid choice, not unique."));
    std::vector<math_row> rows;
    for (std::size_t i = 0; i < D.W.size(); ++i)
        for (std::size_t j = i; j < D.W.size(); ++j)
            rows.push_back(note_row("W[" + D.rows[i] + "," + D.rows[j] + "]",
                                    "W_{" + D.rows[i] + "\\," + D.rows[j] + "}", D.W[i][j]));
    for (std::size_t i = 0; i < D.u.size(); ++i)
        rows.push_back(
            note_row("u[" + D.rows[i] + "]", "u_{" + D.rows[i] + "}", D.u[i], "the row's velocity before impact"));
    paragraph rows_note;
    rows_note.t("Rows: $n_i$ along contact $i$'s normal as given, $t_i$ (and $b_i$) along its tangents");
    if (p.dimension == 2)
        rows_note.t(" ($t = (-n_y, n_x)$)");
    s.para(rows_note.t(". Entries (symmetric):"));
    s.rows(rows);
    return s;
}

void candidate_values(section &s, const derivation &d, const system_candidate &c)
{
    std::vector<math_row> rows;
    for (std::size_t i = 0; i < c.regimes.size(); ++i)
        rows.push_back(value_row(d.system_normal_impulse[i], c.normal_impulse[i], "normal impulse"));
    for (std::size_t b = 0; b < d.prob.bodies.size(); ++b)
        for (int k = 0; k < 3; ++k) {
            if (is_a<symbol>(d.velocity_after[b][k]))
                rows.push_back(value_row(d.velocity_after[b][k], c.velocity[b][k], ""));
            if (is_a<symbol>(d.angular_velocity_after[b][k]))
                rows.push_back(value_row(d.angular_velocity_after[b][k], c.angular_velocity[b][k], ""));
        }
    s.rows(rows);
}

// The one contact's rows of the Delassus matrix as its response K in the contact frame, and the
// process run on them (as system_process_candidates runs it).
process_teaching contact_process(const derivation &d, const system_delassus &D)
{
    const problem &p = d.prob;
    std::size_t n = 0, t = 1;
    if (D.rows[0] != "n0")
        std::swap(n, t);
    process_teaching pt;
    pt.first_row = static_cast<int>(d.equations.size()) + 1; // after the bodies' and joints' equations
    pt.q.Ktt = D.W[t][t];
    pt.q.Ktn = D.W[t][n];
    pt.q.Knn = D.W[n][n];
    pt.q.ut = D.u[t];
    pt.q.un = D.u[n];
    pt.q.mu = p.contacts[0].friction();
    pt.q.e = p.restitution_of(0);
    pt.q.law = p.contacts[0].law_of_restitution;
    pt.numeric = p.is_numeric();
    if (pt.numeric && !is_a<numeric>(pt.q.un.evalf()))
        return pt;
    if (pt.numeric && !ex_to<numeric>(pt.q.un.evalf()).is_negative())
        return pt; // the contact does not approach: no process
    for (const process_sequence &q : routh_process(pt.q, "contacts[0].friction"))
        if (!q.wedges)
            pt.seqs.push_back(q);
    return pt;
}

section contact_frame_section(const problem &p)
{
    section s{"The contact's response in its frame", {}};
    const ex L2 = tidy(dot(p.contacts[0].normal, p.contacts[0].normal));
    if (L2.is_equal(1))
        s.para(paragraph().t("The normal $n_0$ has unit length, so the contact's rows $t_0$, $n_0$ are its frame "
                             "$(e_t, e_n)$, and the Delassus matrix on them is the contact's response $K$: with "
                             "the joints and pivots eliminated, the impulse $P = P_t e_t + P_n e_n$ on the second "
                             "body changes the relative velocity of the contact points by $K P$."));
    else
        s.para(paragraph().t("The rows $t_0$, $n_0$ are the contact's frame $(e_t, e_n)$ scaled by the length of "
                             "its normal as given; in the rows' units the Delassus matrix on them is the "
                             "contact's response $K$ (Coulomb's cone, the ratio of normal impulses and the normal "
                             "work are the same in either units), and the impulses below are the rows' impulses."));
    s.rows({formula_row("K_tt = W[t0,t0],  K_tn = W[t0,n0],  K_nn = W[n0,n0]",
                        "K_{tt} = W_{t0\\,t0},\\quad K_{tn} = W_{t0\\,n0},\\quad K_{nn} = W_{n0\\,n0}"),
            formula_row("u_t = u[t0],  u_n = u[n0]", "u_{t} = u_{t0},\\quad u_{n} = u_{n0}")});
    return s;
}

// A system document's opening: its title, the set-up, the unknowns and each body's equations.
document opening(const derivation &d, const worked_example *example)
{
    document doc;
    doc.title = document_title(d.prob, "System impact");
    doc.description = d.prob.description;
    doc.sections.push_back(setup(d, example));
    doc.sections.push_back(unknowns(d));
    for (section &s : equation_sections(d))
        doc.sections.push_back(s);
    return doc;
}

// A system whose one contact follows Routh's process: the bodies' impulse-momentum with every
// impulse, the Delassus matrix, the contact's 2x2 response from it, then the process as the
// single contact's chapter teaches it, and for numbers the path and the answer.
document process_system(const derivation &d, const worked_example *example)
{
    const problem &p = d.prob;
    const system_delassus D = system_delassus_of(p);
    const process_teaching t = contact_process(d, D);
    document doc = opening(d, example);
    doc.sections.push_back(delassus_section(p, D));
    doc.sections.push_back(contact_frame_section(p));
    for (const auto &part : {process_statement(t), process_equations(t), process_sequences(t)})
        for (const section &s : part)
            doc.sections.push_back(s);
    if (t.numeric && t.seqs.size() == 1) {
        doc.sections.push_back(process_path_section(t));
        for (const system_candidate &c : system_process_candidates(p))
            if (!c.process.empty()) {
                section res{"Results", {}};
                res.para(paragraph().w("The impulses and the velocities after impact (every joint and pivot "
                                       "impulse follows from them):"));
                candidate_values(res, d, c);
                doc.sections.push_back(res);
            }
    }
    for (std::size_t k = 0; k < doc.sections.size(); ++k)
        doc.sections[k].title = std::to_string(k + 1) + ". " + doc.sections[k].title;
    return doc;
}

} // namespace

document explain_system(const derivation &d, const worked_example *example, level depth)
{
    const problem &p = d.prob;
    if (p.is_numeric() || (example && example->values.nops() == 0))
        example = nullptr;
    if (system_follows_process(p) && depth != level::summary)
        return process_system(d, example);
    if (depth == level::summary)
        return detail::system_summary(d, setup(d, example, true), example);
    document doc = opening(d, example);
    doc.sections.push_back(law_section(d));
    doc.sections.push_back(delassus_section(p, system_delassus_of(p)));
    for (section &s : detail::system_solution_sections(d, example))
        doc.sections.push_back(s);
    for (std::size_t k = 0; k < doc.sections.size(); ++k)
        doc.sections[k].title = std::to_string(k + 1) + ". " + doc.sections[k].title;
    return doc;
}

bool system_example(const std::string &class_name, worked_example &out)
{
    const GiNaC::lst values = system_class_example_values(class_name);
    if (values.nops() == 0)
        return false;
    out = worked_example{};
    out.values = values;
    out.caption = "Worked example";
    return true;
}

namespace detail
{
std::string count_of(std::size_t n, const std::string &one, const std::string &many)
{
    static const char *const small[] = {"no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine"};
    const std::string number = n < 10 ? small[n] : std::to_string(n);
    return number + " " + (n <= 1 ? one : many); // "no joint", "one joint", "two joints"
}
std::string body_label(const std::string &name)
{
    const bool number = !name.empty() && name.find_first_not_of("0123456789") == std::string::npos;
    return number ? "body " + name : name;
}
void system_candidate_values(section &s, const derivation &d, const system_candidate &c)
{
    candidate_values(s, d, c);
}
paragraph &system_value(paragraph &q, const ex &v)
{
    return value(q, v);
}
math_row system_value_row(const ex &lhs, const ex &rhs, const std::string &note)
{
    return value_row(lhs, rhs, note);
}
} // namespace detail

} // namespace impactgen::print
