// explain(): section 1, the set-up: the bodies, the contact frame, the unknowns and
// their count (shared with explain_friction.cpp through explain_detail.hpp).
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

// "Coulomb's coefficient of friction between the bodies is μ (μ ≥ 0).", with the name the
// problem gives it when the document writes it otherwise.
paragraph friction_coefficient(const friction_setup &fr)
{
    if (!is_a<symbol>(fr.mu))
        return paragraph().t("Coulomb's coefficient of friction between the bodies is $μ$ = ").m(fr.mu).w(".");
    paragraph q;
    q.w("Coulomb's coefficient of friction between the bodies is ").m(fr.mu);
    if (fr.mu_in_problem)
        q.w(", written ").n(fr.mu_in_problem->text, fr.mu_in_problem->tex).w(" in the problem");
    return q.t(" ($μ ≥ 0$).");
}

// The set-up's opening: what strikes what, e, mu and the units.
void setup_intro(section &sec, const derivation &d, const friction_setup *fr)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    const std::string kind = fr ? std::string(dim == 2 ? "A planar (2-D)" : "A 3-D") + " impact with Coulomb friction"
                                : std::string("A smooth ") + (dim == 2 ? "planar (2-D)" : "3-D") + " impact";
    // The movable body strikes an immovable one at rest (as the figure's caption says it); a
    // moving body of infinite mass (a bat) strikes.
    paragraph strikes;
    strikes.w(kind + ": ");
    if (p.bodies[i1].infinite_mass && p.bodies[i1].at_rest() && !p.bodies[i2].infinite_mass)
        strikes.t("point $B$ of ").w(body_ref(p, i2)).t(" strikes point $A$ of ").w(body_ref(p, i1));
    else
        strikes.t("point $A$ of ").w(body_ref(p, i1)).t(" strikes point $B$ of ").w(body_ref(p, i2));
    sec.para(strikes.t(". The impulsive forces change the velocities instantly without changing the positions."));
    if (is_a<symbol>(p.restitution))
        sec.para(paragraph().t("Newton's coefficient of restitution is ").m(p.restitution).t(" ($0 ≤ e ≤ 1$)."));
    else
        sec.para(paragraph().t("Newton's coefficient of restitution is $e$ = ").m(p.restitution).w("."));
    if (fr)
        sec.para(friction_coefficient(*fr));
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
        if (b.infinite_mass)
            q.w("infinite mass (its motion is given; the impulse cannot change it)");
        else
            q.t("mass ").m(b.mass).w(unit_of(quantity::mass, b.mass));
        if (b.particle) {
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
        if (!b.particle || b.infinite_mass) {
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
void frame_paragraphs(section &sec, const derivation &d, const contact_frame_view &view)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    paragraph frame;
    frame.t("The contact point $O$ = ");
    vector_span(frame, p.contact().point, dim);
    frame.t(
        " is a geometric point, fixed in the inertial frame, where $A$ and $B$ coincide. The contact frame: $e_n$ = ");
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
    sec.para(frame);
    sec.picture(figure_of(d));
    if (view.active && !view.inputs.empty()) {
        std::vector<math_row> input_rows;
        for (const frame_component &c : view.inputs) {
            math_row r = row(c.sym, impactgen::tidy(c.world));
            r.note.w(c.meaning);
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
            r.note.w(c.meaning);
            inertia_rows.push_back(r);
        }
        sec.para(paragraph().t(
            "The inertia tensors in the contact frame, $I_tn = e_t·~~I e_n$ and so on (the angular momentum "
            "equations below use them; the tensor is symmetric, $I_nt = I_tn$):"));
        sec.rows(inertia_rows);
    }
}

void unknown_rows_of(section &sec, const contact_frame_view &view, const friction_setup *fr)
{
    // Known and unknown.
    paragraph known;
    known.t("Known before impact: the velocities $~v_C$ and angular velocities $ω$ of both bodies (above). "
            "To be found after impact:");
    sec.para(known);
    std::vector<math_row> unknown_rows;
    for (const frame_component &u : view.unknowns) {
        math_row r;
        r.lhs_note = {"", ""};
        r.lhs = u.sym;
        r.rel = "";
        r.note.w(u.meaning);
        unknown_rows.push_back(r);
    }
    if (fr)
        for (const auto &[sym, meaning] : fr->impulses) {
            math_row r;
            r.lhs = sym;
            r.rel = "";
            r.note = meaning;
            unknown_rows.push_back(r);
        }
    sec.rows(unknown_rows);
}

void why_count(section &sec, const derivation &d, const friction_setup *fr)
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
        q.w(body_ref(p, i) + ": " + number_word(nv + nw) + " unknowns");
        if (b.infinite_mass)
            q.t(i == p.contact().body2 ? " -- infinite mass: a finite impulse does not affect it, $~v′_C = ~v_C$ and "
                                         "$~ω′ = ~ω$ (the notes' $m2 → ∞$ case)"
                                       : " -- infinite mass: a finite impulse does not affect it, $~v′_C = ~v_C$ and "
                                         "$~ω′ = ~ω$ (the notes' $m2 → ∞$ "
                                         "case, with the bodies' roles exchanged)");
        else if (p.immovable(i))
            q.w(" -- a particle pinned at a fixed point cannot move");
        else if (b.particle)
            q.w(" -- a particle: " + number_word(nv) + " velocity components, no angular velocity");
        else if (dim == 2)
            q.t(" -- planar: $~v′_C$ has 2 components in the plane of $e_n$ and $e_t$, and $~ω′$ only a component "
                "along $e_b$, "
                "because $C$ lies in the plane and $e_b$ is a principal axis at $C$");
        else
            q.t(" -- 3 components of $~v′_C$ and 3 of $~ω′$");
        if (p.pivot_of(i) && !p.immovable(i))
            q.t(" (the pin at $E$ also ties $~v′_C$ to $~ω′$: $~v′_C = ~ω′ × ~r_EC$, equations the notes use without "
                "numbering them)");
        why.push_back(q);
        sum += (sum.empty() ? "" : " + ") + std::to_string(nv + nw);
    }
    if (fr) {
        std::size_t nr = 0;
        for (const unknown &u : d.unknowns)
            if (u.kind == unknown_kind::pivot_impulse)
                ++nr;
        const std::size_t nt = static_cast<std::size_t>(dim - 1);
        paragraph q;
        q.w("impulses: 1 + " + std::to_string(nt) + (nr ? " + " + std::to_string(nr) : ""))
            .t(" -- with friction the contact impulse has an unknown tangential part, so each body's impulse-momentum "
               "is written with the impulses as unknowns: the normal impulse $N$ and the ")
            .t(dim == 2 ? "friction impulse $F$ along $e_t$"
                        : "2 components of the friction impulse $~F$ in the tangent plane");
        if (nr)
            q.w(", and the " + std::to_string(nr) + " components of the pivot's reaction impulse");
        why.push_back(q);
        sum += " + 1 + " + std::to_string(nt) + (nr ? " + " + std::to_string(nr) : "");
    } else if (d.impulse_form) {
        std::size_t nr = 0;
        for (const unknown &u : d.unknowns)
            if (u.kind == unknown_kind::pivot_impulse)
                ++nr;
        why.push_back(paragraph()
                          .w("impulses: 1 + " + std::to_string(nr))
                          .t(" -- with a pivot the notes write impulse-momentum for each body separately, so the "
                             "normal impulse $∫N dt$ "
                             "and the ")
                          .w(std::to_string(nr))
                          .t(" components of the pivot's reaction impulse $~R$ become unknowns too"));
        sum += " + 1 + " + std::to_string(nr);
    }
    if (dim == 3)
        sec.para(paragraph().t("Two free rigid bodies in 3-D have 3 + 3 unknowns each ($~v′_C$ and $~ω′$): 12 in all, "
                               "the notes' general case. Here:"));
    else
        sec.para(paragraph().t(
            "A free rigid body in plane motion has 3 unknowns (2 components of $~v′_C$ and $ω′$ along $e_b$): "
            "6 for two bodies, the notes' smooth planar impact. Here:"));
    sec.list(why);
    const std::size_t extra = fr ? fr->impulses.size() : 0;
    sec.para(paragraph().w("Number of unknowns: " + sum + " = " + std::to_string(d.count_unknowns() + extra) + "."));
}

// Central or not: a body whose centre of mass lies on the line of impact feels no moment about C
// (smooth contact only: a friction impulse has a moment about C).
void central_notes(section &sec, const derivation &d)
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
        sec.para(paragraph().t(
            "A central impact: both centres of mass lie on the line of impact (through $O$ along $e_n$), so "
            "$~r_CO × e_n = 0$ for each body: the impulse has no moment about $C$, and the spin of a sphere "
            "would be unchanged by it. The bodies are therefore taken as particles, without angular velocity "
            "unknowns."));
    // In 3-D, the example that keeps the spins (its solution is checked by Prose.SpinningSpheres...).
    if (both_particles && dim == 3)
        sec.para(
            paragraph().t("Kept as spinning spheres instead (inertia $2 m R²/5$ about every diameter, 12 unknowns: "
                          "the example spinning-spheres.json in examples/problems of impactgen's sources), the same "
                          "equations find every spin unchanged, $~ω′ = ~ω$, and the same velocities $~v′_C$."));
    else if (both_rigid)
        sec.para(paragraph().t(
            "A central impact: both centres of mass lie on the line of impact (through $O$ along $e_n$), so "
            "$~r_CO × e_n = 0$ for each body: the impulse has no moment about $C$. The angular momentum "
            "equations below keep the angular velocities as unknowns, and the solution finds each spin "
            "unchanged, $~ω′ = ~ω$: the impact changes only the velocities of the centres along $e_n$."));
    else
        for (std::size_t i : central)
            if (!p.bodies[i].particle)
                sec.para(paragraph()
                             .t("The line of impact passes through the centre of mass of ")
                             .w(body_ref(p, i))
                             .t(": $~r_CO × e_n = 0$, so the impulse has no moment about its $C$ and its spin is "
                                "unchanged."));
}

} // namespace

section detail::setup_section(const derivation &d, const friction_setup *fr)
{
    const problem &p = d.prob;
    const int dim = p.dimension;
    section sec{"1. Set-up", {}};
    // With friction the equations stay in world components (explain_friction.cpp).
    const contact_frame_view view = fr ? world_components_view(d) : contact_frame_view_of(d);

    setup_intro(sec, d, fr);

    const std::vector<paragraph> bodies = body_list(p);
    sec.list(bodies);

    frame_paragraphs(sec, d, view);

    unknown_rows_of(sec, view, fr);

    why_count(sec, d, fr);
    if (!fr)
        central_notes(sec, d);
    if (d.impulse_form && !fr && dim == 2)
        sec.para(paragraph().t(
            "The notes' hinged-rod example names 6 unknowns -- the ball's $v′_1$, the rod's $~v′_G$ (2 components) and "
            "$ω′_3$, $∫N dt$ and the pin's $∫A_1 dt$ -- and numbers 5 equations; the sixth, that the pin is fixed "
            "($v′_G1 = ω′_3 l/2$), they use without a number. Here every velocity and impulse component is an unknown, "
            "also those the notes know to be zero at sight, and every equation is written out."));
    return sec;
}

} // namespace impactgen::print
