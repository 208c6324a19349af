// The set-up section of every document: the bodies, the contact frame, the unknowns and
// their count, with the parts the contact law adds (explain_law.hpp).
#include "explain.hpp"
#include "explain_detail.hpp"
#include "explain_law.hpp"

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

// The set-up's opening: what strikes what, e, mu and the units.
void setup_intro(section &sec, const derivation &d, const setup_parts &law)
{
    const problem &p = d.prob;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    // The movable body strikes an immovable one at rest (as the figure's caption says it); a
    // moving body of infinite mass (a bat) strikes.
    paragraph strikes;
    strikes.w(law.kind + ": ");
    if (p.bodies[i1].infinite_mass && p.bodies[i1].at_rest() && !p.bodies[i2].infinite_mass)
        strikes.t("point $B$ of ").w(body_ref(p, i2)).t(" strikes point $A$ of ").w(body_ref(p, i1));
    else
        strikes.t("point $A$ of ").w(body_ref(p, i1)).t(" strikes point $B$ of ").w(body_ref(p, i2));
    sec.para(law.brief ? strikes.w(".")
                       : strikes.t(". The impulsive forces change the velocities instantly without changing the "
                                   "positions."));
    if (is_a<symbol>(p.restitution))
        sec.para(paragraph().t("Newton's coefficient of restitution is ").m(p.restitution).t(" ($0 ≤ e ≤ 1$)."));
    else
        sec.para(paragraph().t("Newton's coefficient of restitution is $e$ = ").m(p.restitution).w("."));
    for (const paragraph &q : law.law)
        sec.para(q);
    if (!p.units.empty())
        sec.para(paragraph().w("Units: " + units_key(p) + "."));
}

// Each body: its mass, inertia, position, velocities and pivot.
std::vector<paragraph> body_list(const problem &p)
{
    const int dim = p.dimension;
    // A unit follows numbers only, never a symbol (a numeric problem is taught in symbols first).
    auto unit_of = [&](quantity q, const ex &a, const ex &b = 0, const ex &c = 0) {
        return is_a<numeric>(a) && is_a<numeric>(b) && is_a<numeric>(c) ? unit(p, q) : std::string();
    };
    std::vector<paragraph> bodies;
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body &b = p.bodies[i];
        paragraph q;
        q.w(body_ref(p, i) + ": ");
        // A body of infinite mass has no inertia to speak of: at rest it is a fixed body (the
        // floor, a wall), moving it has the motion given (its spin, where it has one, moves B).
        if (b.infinite_mass && b.at_rest() && !p.pivot_of(i)) {
            bodies.push_back(q.w("infinite mass, at rest: a fixed body, the impulse cannot move it."));
            continue;
        }
        if (b.infinite_mass)
            q.w("infinite mass (its motion is given; the impulse cannot change it)");
        else
            q.t("mass ").m(b.mass).w(unit_of(quantity::mass, b.mass));
        if (b.infinite_mass) {
        } else if (b.particle) {
            q.w(", a particle (no rotational inertia)");
        } else if (dim == 2) {
            q.t(", moment of inertia about $C$ (along $e_b$) ")
                .m(b.inertia[2][2])
                .w(unit_of(quantity::inertia, b.inertia[2][2]));
        } else {
            q.t(", inertia tensor about $C$ with rows ");
            for (int r = 0; r < 3; ++r) {
                if (r)
                    q.w(", ");
                vector_span(q, b.inertia[r], 3);
            }
            q.w(unit_of(quantity::inertia, b.inertia[0][0], b.inertia[1][1], b.inertia[2][2]));
        }
        q.t("; centre of mass $C$ at ");
        vector_span(q, b.position, dim).w(unit_of(quantity::length, b.position[0], b.position[1], b.position[2]));
        q.t("; before impact $~v_C$ = ");
        vector_span(q, b.velocity, dim).w(unit_of(quantity::velocity, b.velocity[0], b.velocity[1], b.velocity[2]));
        bool spins = !b.particle;
        for (int k = 0; k < 3; ++k)
            spins = spins || (b.infinite_mass && !b.angular_velocity[k].is_zero());
        if (spins) {
            q.t(", $ω$ = ");
            if (dim == 2)
                q.m(b.angular_velocity[2]);
            else
                vector_span(q, b.angular_velocity, 3);
            q.w(unit_of(quantity::angular_velocity, b.angular_velocity[0], b.angular_velocity[1],
                        b.angular_velocity[2]));
        }
        q.w(".");
        if (const pivot *pv = p.pivot_of(i)) {
            q.t(" Pinned at the fixed point $E$ = ");
            vector_span(q, pv->point, dim);
            q.t(": it can only rotate about $E$.");
        }
        bodies.push_back(q);
    }
    return bodies;
}

// The contact point and frame, the figure, and the frame components of the inputs and
// inertia tensors.
// A summary (`brief`) shows no equations: nothing is said of their components.
void frame_paragraphs(section &sec, const derivation &d, const contact_frame_view &view, bool brief = false)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    paragraph frame;
    frame.t("The contact point $O$ = ");
    vector_span(frame, p.contact().point, dim);
    frame.t(brief
                ? ", where $A$ and $B$ coincide; $e_n$ = "
                : " is a geometric point, fixed in the inertial frame, where $A$ and $B$ coincide. The contact frame: "
                  "$e_n$ = ");
    vector_span(frame, d.n_hat, dim);
    frame.t(" (the common normal, from body 1 into body 2), $e_t$ along ");
    vector_span(frame, d.t_dir, dim);
    if (dim == 3) {
        frame.t(", $e_b$ along ");
        vector_span(frame, d.b_dir, 3);
    } else {
        frame.t(", and $e_b$ normal to the plane of motion");
    }
    frame.w(".");
    if (p.axes[0] == "t")
        frame.t(" The world axes are named $t$, $n$, $b$: a component with subscript $t$, $n$ or $b$ is along $e_t$, "
                "$e_n$ or $e_b$.");
    else if (d.frame_is_world)
        frame.w(" These are world axes (up to sign), so components can be read off directly.");
    else if (brief)
        ;
    else if (view.active)
        frame.t(
            p.dimension == 3
                ? " The equations below are written in contact-frame components, as in the notes: a vector $~a$ has "
                  "$a_t = ~a·e_t$, $a_n = ~a·e_n$ and $a_b = ~a·e_b$, so that $~a = a_t e_t + a_n e_n + a_b e_b$ "
                  "(the answer at the end is in world components)."
                : " The equations below are written in contact-frame components, as in the notes: a velocity $~v$ has "
                  "$v_t = ~v·e_t$ and $v_n = ~v·e_n$, so that $~v = v_t e_t + v_n e_n$; spins are along $e_b$ "
                  "(the answer at the end is in world components).");
    else
        frame.t(" The equations below are written in world components; the contact-frame components "
                "of a velocity are $v_t = ~v·e_t$ and $v_n = ~v·e_n$; the numbers at the end give "
                "them for both bodies.");
    if (!brief) // one convention for every position vector of the document (issue 25, defect 5)
        frame.t(" A position vector $~r_PQ = Q - P$ goes from the point $P$ to the point $Q$: $~r_CO = O - C$ "
                "locates the contact point from a centre of mass.");
    sec.para(frame);
    sec.picture(figure_of(d));
    if (view.active && !view.inputs.empty()) {
        std::vector<math_row> input_rows;
        for (const frame_component &c : view.inputs) {
            math_row r = row(c.sym, impactgen::tidy(c.world));
            r.note = component_note(c);
            input_rows.push_back(r);
        }
        sec.para(paragraph().w(p.dimension == 3 ? "The velocities and spins before impact in the contact frame:"
                                                : "The velocities before impact in the contact frame:"));
        sec.rows(input_rows);
    }
    if (view.active && !view.inertia.empty()) {
        std::vector<math_row> inertia_rows;
        for (const frame_component &c : view.inertia) {
            math_row r = row(c.sym, c.world);
            r.note = component_note(c);
            inertia_rows.push_back(r);
        }
        sec.para(paragraph().t(
            "The inertia tensors in the contact frame, $I_tn = e_t·~~I e_n$ and so on (the angular momentum "
            "equations below use them; the tensor is symmetric, $I_nt = I_tn$):"));
        sec.rows(inertia_rows);
    }
}

void unknown_rows_of(section &sec, const problem &p, const contact_frame_view &view, const setup_parts &law)
{
    // Known and unknown.
    paragraph known;
    bool spins = false; // a body with rotational inertia: it has an angular velocity
    for (const body &b : p.bodies)
        spins = spins || !b.particle;
    known.t(spins ? "Known before impact: the velocities $~v_C$ and angular velocities $ω$ of both bodies (above). "
                    "To be found after impact:"
                  : "Known before impact: the velocities $~v_C$ of both bodies (above). To be found after impact:");
    sec.para(known);
    // the components of one vector said once: "v′_t1, v′_n1: velocity of ..., components along e_t, e_n"
    std::vector<paragraph> items;
    for (std::size_t k = 0; k < view.unknowns.size();) {
        std::size_t end = k + 1;
        while (end < view.unknowns.size() && view.unknowns[end].meaning == view.unknowns[k].meaning &&
               !view.unknowns[k].axis.empty() && !view.unknowns[end].axis.empty())
            ++end;
        paragraph q;
        for (std::size_t j = k; j < end; ++j)
            q.m(view.unknowns[j].sym).w(j + 1 < end ? ", " : ": ");
        q.w(view.unknowns[k].meaning);
        if (end - k == 1 && !view.unknowns[k].axis.empty())
            along(q.w(", component along "), view.unknowns[k].axis);
        else if (end - k > 1) {
            q.w(", components along ");
            for (std::size_t j = k; j < end; ++j)
                along(j > k ? q.w(", ") : q, view.unknowns[j].axis);
        }
        items.push_back(q);
        k = end;
    }
    for (const auto &[sym, meaning] : law.impulses) {
        paragraph q;
        q.m(sym).w(": ");
        q.spans.insert(q.spans.end(), meaning.spans.begin(), meaning.spans.end());
        items.push_back(q);
    }
    sec.list(items);
}

void why_count(section &sec, const derivation &d, const setup_parts &law)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    // Why this many.
    std::vector<paragraph> why;
    std::string sum;
    for (std::size_t i : {i1, i2}) {
        const body &b = p.bodies[i];
        std::size_t nv = 0, nw = 0;
        for (const unknown &u : d.unknowns)
            if (u.owner == i && u.kind == unknown_kind::velocity)
                ++nv;
            else if (u.owner == i && u.kind == unknown_kind::angular_velocity)
                ++nw;
        paragraph q;
        q.w(std::to_string(nv + nw) + " unknowns");
        if (b.infinite_mass)
            q.t(i == p.contact().body2 ? " -- infinite mass: a finite impulse does not affect it, $~v′_C = ~v_C$ and "
                                         "$~ω′ = ~ω$ (the notes' $m2 → ∞$ case)"
                                       : " -- infinite mass: a finite impulse does not affect it, $~v′_C = ~v_C$ and "
                                         "$~ω′ = ~ω$ (the notes' $m2 → ∞$ "
                                         "case, with the bodies' roles exchanged)");
        else if (p.immovable(i))
            q.w(" -- a particle pinned at a fixed point cannot move");
        else if (b.particle)
            q.w(" -- a particle: " + std::to_string(nv) + " velocity components, no angular velocity");
        else if (dim == 2)
            q.t(" -- planar: $~v′_C$ has 2 components in the plane of $e_n$ and $e_t$, and $~ω′$ only a component "
                "along $e_b$, "
                "because $C$ lies in the plane and $e_b$ is a principal axis at $C$");
        else
            q.t(" -- 3 components of $~v′_C$ and 3 of $~ω′$");
        if (p.pivot_of(i) && !p.immovable(i))
            q.t(" (the pin at $E$ also ties $~v′_C$ to $~ω′$: $~v′_C = ~ω′ × ~r_EC$)");
        why.push_back(q);
        sum += (sum.empty() ? "" : " + ") + std::to_string(nv + nw);
    }
    // the same for both bodies: said once (issue 25, defect 9)
    auto words_of = [](const paragraph &q) {
        std::string out;
        for (const span &x : q.spans)
            out += std::to_string(x.k) + x.text + x.formula.tex + "|";
        return out;
    };
    if (words_of(why[0]) == words_of(why[1])) {
        paragraph both;
        both.w(body_ref(p, i1) + " and " + body_ref(p, i2) + ", each: ");
        both.spans.insert(both.spans.end(), why[0].spans.begin(), why[0].spans.end());
        why = {both};
    } else {
        for (std::size_t k = 0; k < 2; ++k) {
            paragraph named;
            named.w(body_ref(p, k ? i2 : i1) + ": ");
            named.spans.insert(named.spans.end(), why[k].spans.begin(), why[k].spans.end());
            why[k] = named;
        }
    }
    const bool particles = p.bodies[i1].particle && p.bodies[i2].particle && !p.bodies[i1].infinite_mass &&
                           !p.bodies[i2].infinite_mass && !p.immovable(i1) && !p.immovable(i2);
    if (particles && !law.count_item) { // two free particles: one sentence, no rigid bodies to compare with
        sec.para(paragraph().w("Number of unknowns: " + sum + " = " + std::to_string(d.count_unknowns()) + " (" +
                               std::to_string(dim) + " velocity components for each particle)."));
        return;
    }
    if (law.count_item) {
        why.push_back(*law.count_item);
        sum += law.count_terms;
    }
    if (dim == 3)
        sec.para(paragraph().t("Two free rigid bodies in 3-D have 3 + 3 unknowns each ($~v′_C$ and $~ω′$): 12 in all, "
                               "the notes' general case. Here:"));
    else
        sec.para(paragraph().t(
            "A free rigid body in plane motion has 3 unknowns (2 components of $~v′_C$ and $ω′$ along $e_b$): "
            "6 for two bodies, the notes' smooth planar impact. Here:"));
    sec.list(why);
    const std::size_t extra = law.impulses.size();
    sec.para(paragraph().w("Number of unknowns: " + sum + " = " + std::to_string(d.count_unknowns() + extra) + "."));
}

} // namespace

section detail::setup_section(const derivation &d, const setup_parts &law)
{
    section sec{"Set-up", {}};
    const contact_frame_view view = law.world_components ? world_components_view(d) : contact_frame_view_of(d);
    setup_intro(sec, d, law);
    sec.list(body_list(d.prob));
    frame_paragraphs(sec, d, view);
    unknown_rows_of(sec, d.prob, view, law);
    why_count(sec, d, law);
    for (const paragraph &q : law.closing)
        sec.para(q);
    // Two particles: a short set-up, the figure beside the text that follows it.
    const problem &p = d.prob;
    if (p.bodies[p.contact().body1].particle && p.bodies[p.contact().body2].particle)
        for (std::size_t k = 0; k < sec.blocks.size(); ++k)
            if (sec.blocks[k].k == block::figure) {
                std::size_t n = 0;
                while (k + 1 + n < sec.blocks.size() &&
                       (sec.blocks[k + 1 + n].k == block::text || sec.blocks[k + 1 + n].k == block::list))
                    ++n;
                sec.blocks[k].beside = n;
            }
    return sec;
}

section detail::setup_summary(const derivation &d, const setup_parts &law)
{
    section sec{"Set-up", {}};
    contact_frame_view none;
    setup_parts brief = law;
    brief.brief = true;
    setup_intro(sec, d, brief);
    sec.list(body_list(d.prob));
    frame_paragraphs(sec, d, none, true);
    return sec;
}

} // namespace impactgen::print
