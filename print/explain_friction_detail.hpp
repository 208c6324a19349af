// What the files of the Coulomb chapter of the document share (explain_law_coulomb.cpp: the
// chapter; explain_friction.cpp: the law, equations, candidates and regimes;
// explain_friction_numbers.cpp: the numbers and the answer): the chapter's context and its
// small printers. Not an interface of the library.
#pragma once

#include "explain.hpp"
#include "explain_detail.hpp"
#include "formulas.hpp"
#include "symbolic/decide.hpp"

#include <string>
#include <vector>

namespace impactgen::print::friction_detail
{
using namespace GiNaC;
using namespace detail;

struct context {
    const derivation &d;
    const friction_solution &f;
    const problem &p;
    int dim;
    std::size_t i1, i2;
    ex e, mu;
    vec3 n;
    std::vector<vec3> tangents;                 // e_t (and e_b): unit
    std::vector<std::string> tnames;            // "t" (and "b")
    ex N;                                       // print symbol of the normal impulse (the derivation's N with a pivot)
    std::vector<ex> F;                          // print symbols of the friction impulse along the tangents
    std::size_t shared = 0;                     // steps every case shares (K, u, u_n)
    std::vector<equation> eqs;                  // impulse-momentum, pivot, restitution
    std::vector<equation> stick_law, slide_law; // Coulomb's law, one per tangent
    std::vector<ex> slide_d;                    // print symbols of d's components (3-D)
    bool numeric = false;
    // A numeric problem taught in symbols first: d and f are its symbolic twin's, these
    // are the problem's own (the numbers, the regime that holds, the answer).
    const derivation *numeric_d = nullptr;
    const friction_solution *numeric_f = nullptr;
    lst inputs;                     // symbol == number for the twin's symbols
    std::vector<std::string> units; // the unit of each

    context(const derivation &dd, const friction_solution &ff) : d(dd), f(ff), p(dd.prob) {}
    // Whether the stick impulse can push (N > 0 for some μ): decided on the problem's numbers
    bool can_stick() const { return numeric_d ? stick_can_hold(*numeric_d, *numeric_f) : stick_can_hold(d, f); }
    // x with the problem's numbers for the twin's symbols
    ex at_inputs(const ex &x) const { return inputs.nops() ? x.subs(inputs) : x; }

    // The stick candidate (absent when K is singular) and the index of the first slide.
    const regime_case &stick() const { return *f.stick(); }
    bool has_stick() const { return f.stick() != nullptr; }
    std::size_t first_slide() const { return has_stick() ? 1 : 0; }
    ex un() const
    {
        const step *s = f.shared.find(step_role::approach_velocity);
        return s ? ex(s->sym) : ex(0);
    }
    // The relative velocity u of the contact points in world components: steps, or inline values.
    vec3 u_world() const
    {
        vec3 u = zero_vec();
        for (int a = 0; a < dim; ++a) {
            const step *s = f.shared.find(step_role::relative_velocity, no_body, a);
            // along a normal +e_a, u's component is the approach step u_n (symbolic/friction.cpp)
            u[a] = s ? ex(s->sym) : n[a].is_equal(1) ? un() : tidy(d.vB[a] - d.vA[a]);
        }
        return u;
    }
    ex K(int a, int b) const
    {
        const step *s = f.shared.find(step_role::contact_response, no_body, std::min(a, b), std::max(a, b));
        return s ? ex(s->sym) : ex(0);
    }
    // The tag of a planar slide's law F = -sign μ N: the derivation's one equation (8′) is two,
    // one per direction, and two different equations never share a number: (8′) along +e_t,
    // (8″) along -e_t.
    std::string slide_tag(int sign) const { return slide_law.front().label + (sign > 0 ? "" : "'"); }
    // x.K y in world steps.
    ex kform(const vec3 &x, const vec3 &y) const
    {
        ex r = 0;
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b)
                r += x[a] * K(a, b) * y[b];
        return tidy(r);
    }
};

// |r| split over the factors of a product (numbers by their absolute value, (1 + e) and e kept).
ex abs_split(const ex &r, const ex &e);
bool is_float(const ex &v);
ex settle(const ex &v);
math_row value_row(const ex &sym, const ex &value, const std::string &note = "");
math_row value_row(const ex &sym, const ex &value, const paragraph &note);
paragraph regime_words(const regime_case &rc);
paragraph condition_note(const regime_condition &rc);
math_row srow(const ex &lhs, const ex &rhs, const std::string &note = "");
math_row srow(const ex &lhs, const ex &rhs, const paragraph &note);
math_row srow(const problem &p, const step &st);
bool short_denominator(const ex &x);
/// |F|/N of the stick impulse (the threshold mu* when N > 0).
ex stick_threshold_value(const context &c);

// The sections of the chapter (explain_law_coulomb.cpp puts them in their slots).
section law_section(const context &c);           ///< the contact law: restitution and Coulomb's cone
section equations_section(const context &c);     ///< impulse-momentum with the friction impulse
section response_section(const context &c);      ///< the contact response K and the shared steps
section stick_section(const context &c);         ///< the stick candidate tested against the cone
section no_stick_section(const context &c);      ///< K singular: no stick candidate
section slide_section(const context &c);         ///< the slides, each with its conditions
section regimes_section(const context &c);       ///< the regimes as conditions on mu, the energy
section slide_regimes_section(const context &c); ///< without a stick candidate: the slides' conditions, the energy
section existence_section(const context &c);     ///< one regime, none, or several
/// A numeric problem's numbers and the regime that holds, then its answer (when one regime holds).
std::vector<section> numbers_sections(const context &c);

} // namespace impactgen::print::friction_detail
