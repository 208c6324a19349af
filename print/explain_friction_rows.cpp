// The friction document's small printers (explain_friction_detail.hpp): rows of a value with
// its decimal, a step's row, the words of a regime and of a condition.
#include "explain_friction_detail.hpp"

#include "canonical.hpp"
#include "expression.hpp"

#include <cctype>
#include <cstdio>

namespace impactgen::print::friction_detail
{

// |r| split over the factors of a product: numbers by their absolute value, even
// powers as they are, (1 + e) and e (e >= 0 the restitution) as they are.
ex abs_split(const ex &r, const ex &e)
{
    if (is_a<numeric>(r))
        return abs(ex_to<numeric>(r));
    if (is_a<GiNaC::mul>(r)) {
        ex out = 1;
        for (std::size_t k = 0; k < r.nops(); ++k)
            out *= abs_split(r.op(k), e);
        return out;
    }
    if (is_a<power>(r) && is_a<numeric>(r.op(1)) && ex_to<numeric>(r.op(1)).is_integer()) {
        if (ex_to<numeric>(r.op(1)).is_even())
            return r;
        return pow(abs_split(r.op(0), e), r.op(1));
    }
    // a polynomial in e alone with non-negative coefficients and a positive constant term
    if (is_a<symbol>(e) && r.is_polynomial(e)) {
        ex x = r.expand();
        bool positive = true;
        const int deg = x.degree(e);
        for (int k = 0; k <= deg && positive; ++k) {
            ex c = x.coeff(e, k);
            positive =
                is_a<numeric>(c) && !ex_to<numeric>(c).is_negative() && (k > 0 || ex_to<numeric>(c).is_positive());
        }
        if (positive && x.has(e))
            return r;
        bool negative = true; // -(1 + e): factor() may choose either sign
        for (int k = 0; k <= deg && negative; ++k) {
            ex c = x.coeff(e, k);
            negative =
                is_a<numeric>(c) && !ex_to<numeric>(c).is_positive() && (k > 0 || ex_to<numeric>(c).is_negative());
        }
        if (negative && x.has(e))
            return -r;
    }
    // |x| = |-x|: the sign that prints without a leading minus, so the output does not
    // depend on the sign normal() or factor() happened to choose
    const std::string plus = canonical_text(r), minus = canonical_text(-r);
    if (!plus.empty() && plus[0] == '-' && !(minus.size() && minus[0] == '-'))
        return abs(-r);
    if ((plus[0] == '-') == (minus[0] == '-') && minus < plus)
        return abs(-r);
    return abs(r);
}

bool is_float(const ex &v)
{
    return is_a<numeric>(v) && !ex_to<numeric>(v).is_rational();
}

// A value with a float in it (the sliding angle found numerically) as one float.
ex settle(const ex &v)
{
    for (const_preorder_iterator it = v.preorder_begin(); it != v.preorder_end(); ++it)
        if (is_a<numeric>(*it) && !ex_to<numeric>(*it).is_rational()) {
            const long saved = Digits;
            Digits = 50; // as many digits as the root carries
            ex x = v.evalf();
            Digits = saved;
            return x;
        }
    return v;
}

// sym = value; a float (a root found numerically) as 15 significant digits.
math_row value_row(const ex &sym, const ex &value, const std::string &note)
{
    return value_row(sym, value, note.empty() ? paragraph() : paragraph().w(note));
}

math_row value_row(const ex &sym, const ex &value, const paragraph &note)
{
    if (is_float(value)) {
        const std::string dec = decimal(value);
        return formula_row(canonical_text(sym) + " ≈ " + dec, canonical_latex(sym) + " \\approx " + dec, note);
    }
    if (!is_constant(value) || !is_a<numeric>(value))
        for (const_preorder_iterator it = value.preorder_begin(); it != value.preorder_end(); ++it)
            if (is_float(*it))
                return value_row(sym, value.evalf(), note);
    if (is_constant(value) && !is_a<numeric>(value) && canonical_text(value).size() > 60) {
        // exact but unreadable (nested roots of large rationals): its decimal
        const std::string dec = decimal(value.evalf());
        return formula_row(canonical_text(sym) + " ≈ " + dec, canonical_latex(sym) + " \\approx " + dec, note);
    }
    paragraph n = decimal_note(value);
    if (!note.spans.empty() && !n.spans.empty())
        n.w(", ");
    for (const span &x : note.spans)
        n.spans.push_back(x);
    return row(sym, value, "", n);
}

// A regime's name in teaching prose, from its kind, sign and angle.
paragraph regime_words(const regime_case &rc)
{
    paragraph q;
    if (rc.kind == regime::stick)
        return q.w("stick");
    if (rc.sign > 0)
        return q.t("slide along $+e_t$");
    if (rc.sign < 0)
        return q.t("slide along $-e_t$");
    if (rc.has_angle) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.6g", rc.angle);
        return q.w(std::string("slide at the angle ") + buf).t(" rad from $e_t$ towards $e_b$");
    }
    if (rc.needs_angle)
        return q.t("slide along $~d$ (at a root $θ$)");
    return q.t("slide along $u_t$");
}

// A regime condition in teaching prose, from its kind.
paragraph condition_note(const regime_condition &rc)
{
    paragraph q;
    switch (rc.kind) {
    case condition_kind::cone_below:
        return q.t("$μN - F ≥ 0$ (the impulse inside the friction cone)");
    case condition_kind::cone_above:
        return q.t("$μN + F ≥ 0$ (the impulse inside the friction cone)");
    case condition_kind::pushes:
        return q.t("$N ≥ 0$ (the contact pushes)");
    case condition_kind::cone:
        return q.t("$μ² N² - |~F|² ≥ 0$ (the impulse inside the friction cone)");
    case condition_kind::slide_denominator:
        return q.t("$D_s > 0$ (the normal impulse $N$ is positive)");
    case condition_kind::slides:
        return q.t("$λ = ~u′_t·~d > 0$ (the contact slides along $~d$ after impact)");
    }
    return q.w(rc.meaning);
}

// lhs = rhs, or, when rhs is too long to read (a 3-D problem with a tilted normal), lhs = … and
// a note that says so.
math_row srow(const ex &lhs, const ex &rhs, const std::string &note)
{
    return srow(lhs, rhs, note.empty() ? paragraph() : paragraph().w(note));
}

math_row srow(const ex &lhs, const ex &rhs, const paragraph &note)
{
    if (printable(rhs, 400))
        return row(lhs, rhs, "", note);
    const std::string more = "too long to print here";
    paragraph q = note;
    q.w(note.spans.empty() ? more : " (" + more + ")");
    return formula_row(canonical_text(lhs) + " = …", canonical_latex(lhs) + " = \\ldots", q);
}

// A step's row, its meaning from its role (teaching prose with symbols in math).
math_row srow(const problem &p, const step &st)
{
    math_row r = srow(st.sym, st.value);
    paragraph note = step_note(p, st);
    if (!r.note.spans.empty()) { // too long to print: the note says so
        note.w(" (");
        for (const span &x : r.note.spans)
            note.spans.push_back(x);
        note.w(")");
    }
    r.note = note;
    return r;
}

// A line can be broken in a sum, not in the denominator of a fraction: a formula whose
// denominator is a long sum does not fit a printed page's column (LaTeX, HTML), so the
// optional forms of a formula are shown only when their denominator is short.
bool short_denominator(const ex &x)
{
    return printable(x.denom(), 24);
}

} // namespace impactgen::print::friction_detail
