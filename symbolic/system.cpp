#include "system.hpp"

#include "decide.hpp"
#include "names/escape.hpp"
#include "restitution_law.hpp"
#include "system_process.hpp"

#include <sstream>

namespace impactgen
{
using namespace GiNaC;

namespace
{

using exmat = std::vector<std::vector<ex>>;
constexpr std::size_t max_candidates = 4096;
constexpr std::size_t max_steps = 64;

// Every entry over a common denominator: the systems' closed forms are rational functions of a
// few symbols, which stay small in that form (tidy() alone would leave nested fractions).
ex simp(const ex &e)
{
    return is_constant(e) ? tidy(e) : normal(e);
}

// Decided non-zero: exactly for constants, identically for expressions with symbols.
bool nonzero(const ex &e)
{
    if (is_constant(e)) {
        const decision d = decide(e);
        if (d == decision::not_real || d == decision::out_of_range || d == decision::undecided)
            throw input_error(std::string("contacts: an entry of the impact's linear system ") + decision_text(d));
        return d != decision::zero;
    }
    return !identically_zero(e);
}

// Gauss-Jordan elimination: X with A X = B (A square); false when A is singular.
bool gauss(exmat A, exmat B, exmat &X)
{
    const std::size_t n = A.size(), k = B.empty() ? 0 : B[0].size();
    for (std::size_t c = 0; c < n; ++c) {
        std::size_t piv = n;
        for (std::size_t r = c; r < n && piv == n; ++r)
            if (nonzero(A[r][c]))
                piv = r;
        if (piv == n)
            return false;
        std::swap(A[c], A[piv]);
        std::swap(B[c], B[piv]);
        const ex inv = simp(1 / A[c][c]);
        for (std::size_t r = 0; r < n; ++r) {
            if (r == c || A[r][c].is_zero())
                continue;
            const ex f = simp(A[r][c] * inv);
            for (std::size_t j = c; j < n; ++j)
                A[r][j] = simp(A[r][j] - f * A[c][j]);
            for (std::size_t j = 0; j < k; ++j)
                B[r][j] = simp(B[r][j] - f * B[c][j]);
        }
    }
    X.assign(n, std::vector<ex>(k));
    for (std::size_t r = 0; r < n; ++r)
        for (std::size_t j = 0; j < k; ++j)
            X[r][j] = simp(B[r][j] / A[r][r]);
    return true;
}

// Row reduction of [A | b] (A rows x cols): the rank, and whether the system is consistent.
// With full column rank, x is its one solution.
std::size_t reduce(exmat A, std::vector<ex> b, bool &consistent, std::vector<ex> &x,
                   std::vector<std::size_t> *pivots = nullptr)
{
    const std::size_t rows = A.size(), cols = rows ? A[0].size() : 0;
    std::size_t rank = 0;
    std::vector<std::size_t> pivot_col;
    for (std::size_t c = 0; c < cols && rank < rows; ++c) {
        std::size_t piv = rows;
        for (std::size_t r = rank; r < rows && piv == rows; ++r)
            if (nonzero(A[r][c]))
                piv = r;
        if (piv == rows)
            continue;
        std::swap(A[rank], A[piv]);
        std::swap(b[rank], b[piv]);
        const ex inv = simp(1 / A[rank][c]);
        for (std::size_t j = c; j < cols; ++j)
            A[rank][j] = simp(A[rank][j] * inv);
        b[rank] = simp(b[rank] * inv);
        for (std::size_t r = 0; r < rows; ++r) {
            if (r == rank || A[r][c].is_zero())
                continue;
            const ex f = A[r][c];
            for (std::size_t j = c; j < cols; ++j)
                A[r][j] = simp(A[r][j] - f * A[rank][j]);
            b[r] = simp(b[r] - f * b[rank]);
        }
        pivot_col.push_back(c);
        ++rank;
    }
    consistent = true;
    for (std::size_t r = rank; r < rows; ++r)
        consistent = consistent && !nonzero(b[r]);
    x.assign(cols, ex(0));
    for (std::size_t k = 0; k < rank; ++k)
        x[pivot_col[k]] = b[k];
    if (pivots)
        *pivots = pivot_col;
    return rank;
}

// The solutions of S x = B: the one of a regular S, else the basic ones (each choice of
// columns left out at zero that leaves independent columns and a consistent system).
std::vector<std::vector<ex>> basic_solutions(const exmat &S, const exmat &B)
{
    const std::size_t u = S.size();
    exmat X;
    if (gauss(S, B, X)) {
        std::vector<ex> x;
        for (const auto &row : X)
            x.push_back(row[0]);
        return {x};
    }
    std::vector<ex> b, x;
    for (const auto &row : B)
        b.push_back(row[0]);
    bool consistent = false;
    const std::size_t rank = reduce(S, b, consistent, x);
    if (!consistent || rank == 0)
        return {};
    std::vector<std::vector<ex>> out;
    // Subsets of `rank` columns kept, in lexicographic order (at most 256 tried).
    std::vector<std::size_t> keep(rank);
    for (std::size_t k = 0; k < rank; ++k)
        keep[k] = k;
    for (int tried = 0; tried < 256; ++tried) {
        exmat A(u, std::vector<ex>(rank));
        for (std::size_t r = 0; r < u; ++r)
            for (std::size_t k = 0; k < rank; ++k)
                A[r][k] = S[r][keep[k]];
        std::vector<ex> y;
        if (reduce(A, b, consistent, y) == rank && consistent) {
            std::vector<ex> full(u, ex(0));
            for (std::size_t k = 0; k < rank; ++k)
                full[keep[k]] = y[k];
            out.push_back(full);
        }
        std::size_t i = rank;
        while (i > 0 && keep[i - 1] == u - rank + i - 1)
            --i;
        if (i == 0)
            break;
        ++keep[i - 1];
        for (std::size_t k = i; k < rank; ++k)
            keep[k] = keep[k - 1] + 1;
    }
    return out;
}

enum class row_kind { pivot, joint, normal, tangent };

// A body's share of a row: the coefficients on its generalized velocity.
struct part {
    std::size_t body;
    std::vector<ex> coef;
};
struct row {
    row_kind kind;
    std::size_t owner; ///< pivot, joint or contact index
    std::vector<part> parts;
    ex constant = 0; ///< the bodies of infinite mass: their point velocity along the row
};

struct model {
    problem p;
    std::vector<std::size_t> ndof;               ///< per body; 0 for infinite mass
    std::vector<exmat> minv;                     ///< per body: M_b^-1
    std::vector<row> rows;                       ///< bilateral (pivots, joints) first, then the contacts'
    std::size_t nb = 0;                          ///< bilateral rows
    std::vector<std::size_t> nrow;               ///< per contact: its normal row among the contact rows
    std::vector<std::vector<std::size_t>> trows; ///< per contact: its tangent rows among the contact rows
    std::vector<vec3> tangent;                   ///< per contact row: its direction (tangent rows)
    std::vector<ex> nlen;                        ///< per contact: |n_i|
    exmat W;                                     ///< the Delassus matrix of the contact rows
    exmat XJ;                                    ///< H_JJ^-1 H_JC: lambda_J = -XJ lambda_C
    bool redundant = false;           ///< dependent joint rows: left out (no impulse), the impulses not unique
    std::vector<std::vector<ex>> gv0; ///< generalized velocity before impact, per body
};

// The coefficients of the velocity along a of body b's material point Q.
std::vector<ex> point_row(const problem &p, std::size_t b, const vec3 &Q, const vec3 &a)
{
    const body &B = p.bodies[b];
    std::vector<ex> c(a.begin(), a.begin() + p.dimension);
    if (B.particle)
        return c;
    const vec3 r = Q - B.position;
    const vec3 m = cross(r, a); // w . (r x a) = a . (w x r)
    if (p.dimension == 2)
        c.push_back(simp(m[2]));
    else
        for (int k = 0; k < 3; ++k)
            c.push_back(simp(m[k]));
    return c;
}

// Adds body b's point Q along a, with the sign s, to the row.
void add_point(const model &m, row &r, std::size_t b, const vec3 &Q, const vec3 &a, int s)
{
    const body &B = m.p.bodies[b];
    if (B.infinite_mass) {
        r.constant = simp(r.constant + s * dot(point_velocity(B, Q), a));
        return;
    }
    std::vector<ex> c = point_row(m.p, b, Q, a);
    for (ex &e : c)
        e = s * e;
    r.parts.push_back({b, c});
}

void setup_bodies(model &m)
{
    const problem &p = m.p;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const body &B = p.bodies[b];
        std::vector<ex> v(B.velocity.begin(), B.velocity.begin() + p.dimension);
        const std::size_t lin = static_cast<std::size_t>(p.dimension);
        const std::size_t n = B.infinite_mass ? 0 : lin + (B.particle ? 0 : (p.dimension == 2 ? 1 : 3));
        exmat inv(n, std::vector<ex>(n, ex(0)));
        for (std::size_t k = 0; k < lin && n; ++k)
            inv[k][k] = simp(1 / B.mass);
        if (n > lin && p.dimension == 2) {
            inv[2][2] = simp(1 / B.inertia[2][2]);
            v.push_back(B.angular_velocity[2]);
        } else if (n > lin) {
            const mat3 adj = adjugate(B.inertia);
            const ex dt = det(B.inertia);
            for (int i = 0; i < 3; ++i) {
                v.push_back(B.angular_velocity[i]);
                for (int j = 0; j < 3; ++j)
                    inv[3 + i][3 + j] = simp(adj[i][j] / dt);
            }
        }
        m.ndof.push_back(n);
        m.minv.push_back(inv);
        m.gv0.push_back(v);
    }
}

vec3 axis(int k)
{
    vec3 a = zero_vec();
    a[k] = 1;
    return a;
}

void setup_rows(model &m)
{
    const problem &p = m.p;
    for (std::size_t k = 0; k < p.pivots.size(); ++k)
        for (int i = 0; i < p.dimension; ++i) {
            row r{row_kind::pivot, k, {}, 0};
            add_point(m, r, p.pivots[k].body, p.pivots[k].point, axis(i), 1);
            m.rows.push_back(r);
        }
    for (std::size_t k = 0; k < p.joints.size(); ++k)
        for (int i = 0; i < p.dimension; ++i) {
            row r{row_kind::joint, k, {}, 0};
            add_point(m, r, p.joints[k].body2, p.joints[k].point, axis(i), 1);
            add_point(m, r, p.joints[k].body1, p.joints[k].point, axis(i), -1);
            m.rows.push_back(r);
        }
    m.nb = m.rows.size();
    for (std::size_t k = 0; k < p.contacts.size(); ++k) {
        const contact_spec &c = p.contacts[k];
        std::vector<vec3> dirs{c.normal};
        if (p.dimension == 2 && (c.rough || !c.friction().is_zero()))
            dirs.push_back({-c.normal[1], c.normal[0], 0});
        if (p.dimension == 3 && c.rough) {
            int z = 0;
            while (z < 2 && !c.normal[z].is_zero())
                ++z;
            const vec3 t1 = c.normal[z].is_zero() ? cross(c.normal, axis(z)) : cross(c.normal, axis(0));
            dirs.push_back(t1);
            dirs.push_back(cross(c.normal, t1));
        }
        m.nlen.push_back(root_of(simp(dot(c.normal, c.normal))));
        m.trows.emplace_back();
        for (std::size_t d = 0; d < dirs.size(); ++d) {
            row r{d == 0 ? row_kind::normal : row_kind::tangent, k, {}, 0};
            add_point(m, r, c.body2, c.point, dirs[d], 1);
            add_point(m, r, c.body1, c.point, dirs[d], -1);
            (d == 0 ? m.nrow.emplace_back() : m.trows.back().emplace_back()) = m.rows.size() - m.nb;
            m.tangent.push_back(d == 0 ? zero_vec() : dirs[d]);
            m.rows.push_back(r);
        }
    }
}

ex h_entry(const model &m, const row &a, const row &b)
{
    ex s = 0;
    for (const part &pa : a.parts)
        for (const part &pb : b.parts) {
            if (pa.body != pb.body)
                continue;
            const exmat &inv = m.minv[pa.body];
            for (std::size_t i = 0; i < pa.coef.size(); ++i)
                for (std::size_t j = 0; j < pb.coef.size(); ++j)
                    if (!inv[i][j].is_zero())
                        s += pa.coef[i] * inv[i][j] * pb.coef[j];
        }
    return simp(s);
}

// H = A M^-1 A^T, its joint block eliminated: W and XJ.
void setup_delassus(model &m)
{
    const std::size_t R = m.rows.size(), nb = m.nb, nc = R - nb;
    exmat H(R, std::vector<ex>(R));
    for (std::size_t i = 0; i < R; ++i)
        for (std::size_t j = i; j < R; ++j)
            H[i][j] = H[j][i] = h_entry(m, m.rows[i], m.rows[j]);
    m.W.assign(nc, std::vector<ex>(nc));
    for (std::size_t i = 0; i < nc; ++i)
        for (std::size_t j = 0; j < nc; ++j)
            m.W[i][j] = H[nb + i][nb + j];
    if (nb == 0)
        return;
    exmat HJJ(nb, std::vector<ex>(nb)), HJC(nb, std::vector<ex>(nc));
    for (std::size_t i = 0; i < nb; ++i) {
        for (std::size_t j = 0; j < nb; ++j)
            HJJ[i][j] = H[i][j];
        for (std::size_t j = 0; j < nc; ++j)
            HJC[i][j] = H[i][nb + j];
    }
    if (!gauss(HJJ, HJC, m.XJ)) {
        // Redundant joints (rows of A_J dependent, so H_JJ singular): the rows of an independent
        // subset imply the others (which hold before impact), so the others are left out with
        // no impulse -- one valid choice of impulses among many.
        bool consistent = false;
        std::vector<ex> x;
        std::vector<std::size_t> keep;
        reduce(HJJ, std::vector<ex>(nb, ex(0)), consistent, x, &keep);
        exmat HK(keep.size(), std::vector<ex>(keep.size())), HC(keep.size()), XK;
        for (std::size_t i = 0; i < keep.size(); ++i) {
            for (std::size_t j = 0; j < keep.size(); ++j)
                HK[i][j] = HJJ[keep[i]][keep[j]];
            HC[i] = HJC[keep[i]];
        }
        if (!gauss(HK, HC, XK))
            throw input_error("joints: the joints' and pivots' impulses cannot be determined");
        m.XJ.assign(nb, std::vector<ex>(nc, ex(0)));
        for (std::size_t i = 0; i < keep.size(); ++i)
            m.XJ[keep[i]] = XK[i];
        m.redundant = true;
    }
    for (std::size_t i = 0; i < nc; ++i)
        for (std::size_t j = 0; j < nc; ++j) {
            ex s = m.W[i][j];
            for (std::size_t k = 0; k < nb; ++k)
                s -= H[nb + i][k] * m.XJ[k][j];
            m.W[i][j] = simp(s);
        }
}

// Poisson's and the energetic law follow one frictional contact through the impact, with any
// joints and pivots (system_process.hpp); several such contacts, 3-D or "inf" are refused.
void refuse_process_laws(const problem &p)
{
    for (std::size_t k = 0; k < p.contacts.size(); ++k) {
        const contact_spec &c = p.contacts[k];
        if (!follows_process(c.law_of_restitution) || (!c.rough && c.friction().is_zero()))
            continue;
        if (p.contacts.size() == 1 && p.dimension == 2 && !c.rough)
            continue;
        throw input_error("contacts[" + std::to_string(k) + "].law: \"" + law_name(c.law_of_restitution) +
                          "\" with friction is solved for one contact in 2-D (with any joints and pivots), "
                          "without \"friction\": \"inf\"; here only \"newton\" (or a smooth contact) is solved");
    }
}

model build_model(const problem &p)
{
    refuse_process_laws(p);
    model m;
    m.p = p;
    setup_bodies(m);
    setup_rows(m);
    setup_delassus(m);
    return m;
}

// The contact rows' relative velocities for the generalized velocities gv.
std::vector<ex> contact_velocities(const model &m, const std::vector<std::vector<ex>> &gv)
{
    std::vector<ex> w;
    for (std::size_t r = m.nb; r < m.rows.size(); ++r) {
        ex s = m.rows[r].constant;
        for (const part &pt : m.rows[r].parts)
            for (std::size_t k = 0; k < pt.coef.size(); ++k)
                s += pt.coef[k] * gv[pt.body][k];
        w.push_back(simp(s));
    }
    return w;
}

// The regimes open to contact i: open, then the acting ones.
struct option {
    contact_regime regime;
    int sign;
};
std::vector<option> options_of(const problem &p, std::size_t i)
{
    const contact_spec &c = p.contacts[i];
    if (c.rough)
        return {{contact_regime::open, 0}, {contact_regime::stick, 0}};
    if (c.friction().is_zero())
        return {{contact_regime::open, 0}, {contact_regime::smooth, 0}};
    return {
        {contact_regime::open, 0}, {contact_regime::stick, 0}, {contact_regime::slide, 1}, {contact_regime::slide, -1}};
}

// The core of one candidate: row impulses of the contacts, their velocities after, conditions.
struct core {
    std::vector<option> choice;
    std::vector<ex> lambda; ///< contact rows
    std::vector<ex> w;      ///< contact rows after impact
    std::vector<system_condition> conditions;
};

std::string pname(std::size_t i)
{
    return "contacts[" + std::to_string(i) + "]";
}

// The conditions under which the candidate's solution obeys the law.
void add_conditions(const model &m, core &c, const std::vector<ex> &q, const std::vector<bool> &considered)
{
    for (std::size_t i = 0; i < c.choice.size(); ++i) {
        if (!considered[i])
            continue;
        const std::size_t n = m.nrow[i];
        const ex e = m.p.restitution_of(i), mu = m.p.contacts[i].friction();
        const std::string who = pname(i);
        const std::string name = "contact " + std::to_string(i);
        const std::string pushes = name + " pushes (its normal impulse is not negative)";
        const std::size_t before = c.conditions.size();
        switch (c.choice[i].regime) {
        case contact_regime::open:
            c.conditions.push_back({simp(c.w[n] + e * q[n]), false,
                                    "u'_" + std::to_string(i) + " + e u_" + std::to_string(i) + " >= 0 (" + who +
                                        " leaves no slower than e times its approach)",
                                    name + " leaves no slower than e times its approach speed", true});
            break;
        case contact_regime::smooth:
            c.conditions.push_back(
                {c.lambda[n], false, "P_" + std::to_string(i) + " >= 0 (" + who + " pushes)", pushes});
            break;
        case contact_regime::stick:
            c.conditions.push_back(
                {c.lambda[n], false, "P_" + std::to_string(i) + " >= 0 (" + who + " pushes)", pushes});
            if (!m.p.contacts[i].rough) {
                const ex t = c.lambda[m.trows[i][0]];
                const std::string cone = "the impulse of " + name + " lies inside its friction cone";
                c.conditions.push_back(
                    {simp(mu * c.lambda[n] - t), false, "mu P_n - P_t >= 0 (" + who + " inside the cone)", cone});
                c.conditions.push_back(
                    {simp(mu * c.lambda[n] + t), false, "mu P_n + P_t >= 0 (" + who + " inside the cone)", cone});
            }
            break;
        case contact_regime::slide:
            c.conditions.push_back(
                {c.lambda[n], false, "P_" + std::to_string(i) + " >= 0 (" + who + " pushes)", pushes});
            // Not strict: a contact whose slip after impact is 0 with its friction impulse on the
            // cone's edge obeys Coulomb's law (|P_t| <= mu P_n where u'_t = 0), whichever way it
            // would slip. Two corners of a box on one ground line slip alike, so where one sticks
            // the other's slip is exactly 0, and the stick splits that fit both cones end at
            // such sets: without them the law would be refused where it holds.
            c.conditions.push_back({simp(c.choice[i].sign * c.w[m.trows[i][0]]), false,
                                    std::string("u'_t ") + (c.choice[i].sign > 0 ? ">= 0" : "<= 0") + " (" + who +
                                        " slides along " + (c.choice[i].sign > 0 ? "+t" : "-t") + " or does not slip)",
                                    name + " slides " +
                                        (c.choice[i].sign > 0 ? "along its tangent" : "against its tangent") +
                                        " after impact (or does not slip)",
                                    true});
            break;
        }
        for (std::size_t k = before; k < c.conditions.size(); ++k)
            c.conditions[k].contact = i;
    }
}

// Solves the candidate `choice` (contacts not considered carry no impulse). A square system
// has one solution; a singular one (redundant contacts: a box flat on four corners, two sticking
// corners) has a family, whose solutions with P >= 0 include a basic one (Caratheodory): one
// candidate per choice of columns left out that makes the rest independent and consistent.
std::vector<core> solve_core(const model &m, const std::vector<ex> &q, const std::vector<bool> &considered,
                             const core &c)
{
    const std::size_t nc = m.W.size();
    std::vector<std::vector<ex>> cols; // per unknown: its contact-row impulses per unit
    std::vector<std::size_t> eqs;      // the rows whose velocity after is prescribed
    std::vector<ex> target;
    for (std::size_t i = 0; i < c.choice.size(); ++i) {
        const option o = c.choice[i];
        if (!considered[i] || o.regime == contact_regime::open)
            continue;
        const std::size_t n = m.nrow[i];
        std::vector<ex> col(nc, ex(0));
        col[n] = 1;
        if (o.regime == contact_regime::slide)
            col[m.trows[i][0]] = simp(-o.sign * m.p.contacts[i].friction());
        cols.push_back(col);
        eqs.push_back(n);
        target.push_back(simp(-(1 + m.p.restitution_of(i)) * q[n]));
        if (o.regime == contact_regime::stick)
            for (std::size_t t : m.trows[i]) {
                std::vector<ex> ct(nc, ex(0));
                ct[t] = 1;
                cols.push_back(ct);
                eqs.push_back(t);
                target.push_back(-q[t]);
            }
    }
    const std::size_t u = cols.size();
    exmat S(u, std::vector<ex>(u)), B(u, std::vector<ex>(1));
    for (std::size_t r = 0; r < u; ++r) {
        for (std::size_t k = 0; k < u; ++k) {
            ex s = 0;
            for (std::size_t j = 0; j < nc; ++j)
                if (!cols[k][j].is_zero())
                    s += m.W[eqs[r]][j] * cols[k][j];
            S[r][k] = simp(s);
        }
        B[r][0] = target[r];
    }
    std::vector<core> out;
    for (const std::vector<ex> &x : basic_solutions(S, B)) {
        core k = c;
        k.lambda.assign(nc, ex(0));
        for (std::size_t col = 0; col < u; ++col)
            for (std::size_t j = 0; j < nc; ++j)
                if (!cols[col][j].is_zero())
                    k.lambda[j] = simp(k.lambda[j] + cols[col][j] * x[col]);
        k.w.assign(nc, ex(0));
        for (std::size_t r = 0; r < nc; ++r) {
            ex sum = q[r];
            for (std::size_t j = 0; j < nc; ++j)
                if (!k.lambda[j].is_zero())
                    sum += m.W[r][j] * k.lambda[j];
            k.w[r] = simp(sum);
        }
        add_conditions(m, k, q, considered);
        out.push_back(k);
    }
    return out;
}

// Every row impulse (bilateral, then contacts) and the generalized velocities after.
void apply_impulses(const model &m, const std::vector<ex> &lambdaC, std::vector<ex> &all,
                    std::vector<std::vector<ex>> &gv)
{
    const std::size_t nb = m.nb, nc = lambdaC.size();
    all.assign(nb + nc, ex(0));
    for (std::size_t k = 0; k < nb; ++k) {
        ex s = 0;
        for (std::size_t j = 0; j < nc; ++j)
            if (!lambdaC[j].is_zero())
                s -= m.XJ[k][j] * lambdaC[j];
        all[k] = simp(s);
    }
    for (std::size_t j = 0; j < nc; ++j)
        all[nb + j] = lambdaC[j];
    for (std::size_t r = 0; r < all.size(); ++r) {
        if (all[r].is_zero())
            continue;
        for (const part &pt : m.rows[r].parts) {
            const exmat &inv = m.minv[pt.body];
            for (std::size_t i = 0; i < inv.size(); ++i)
                for (std::size_t j = 0; j < pt.coef.size(); ++j)
                    if (!inv[i][j].is_zero())
                        gv[pt.body][i] += inv[i][j] * pt.coef[j] * all[r];
        }
    }
    for (auto &v : gv)
        for (ex &e : v)
            e = simp(e);
}

// The answer's quantities from the row impulses and the generalized velocities after.
system_candidate finish(const model &m, const std::vector<option> &choice, const std::vector<ex> &all,
                        const std::vector<std::vector<ex>> &gv, const std::vector<ex> &w)
{
    const problem &p = m.p;
    const int dim = p.dimension;
    system_candidate c;
    c.impulses = all;
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        c.regimes.push_back(choice[i].regime);
        c.slide_sign.push_back(choice[i].sign);
        const ex ln = all[m.nb + m.nrow[i]];
        c.normal_impulse.push_back(simp(ln * m.nlen[i]));
        vec3 t = zero_vec();
        for (std::size_t r : m.trows[i])
            t = t + all[m.nb + r] * m.tangent[r];
        c.tangential_impulse.push_back({simp(t[0]), simp(t[1]), simp(t[2])});
        c.normal_velocity_after.push_back(w.empty() ? ex(0) : simp(w[m.nrow[i]] / m.nlen[i]));
    }
    c.pivot_impulses.assign(p.pivots.size(), zero_vec());
    c.joint_impulses.assign(p.joints.size(), zero_vec());
    for (std::size_t r = 0; r < m.nb; ++r) {
        const int ax = static_cast<int>(r % static_cast<std::size_t>(dim));
        (m.rows[r].kind == row_kind::pivot ? c.pivot_impulses : c.joint_impulses)[m.rows[r].owner][ax] = all[r];
    }
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const body &B = p.bodies[b];
        vec3 v = B.velocity, om = B.angular_velocity;
        for (int k = 0; k < dim && !B.infinite_mass; ++k)
            v[k] = gv[b][k];
        if (!B.infinite_mass && !B.particle) {
            if (dim == 2)
                om[2] = gv[b][2];
            else
                for (int k = 0; k < 3; ++k)
                    om[k] = gv[b][3 + k];
        }
        c.velocity.push_back(v);
        c.angular_velocity.push_back(om);
    }
    return c;
}

// Calls f with each candidate choice: the considered contacts run through their options
// (contact 0 fastest), the others stay open. Refuses more than max_candidates.
template <class F> void for_each_choice(const problem &p, const std::vector<bool> &considered, F f)
{
    std::vector<std::vector<option>> opts;
    std::size_t total = 1;
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        opts.push_back(considered[i] ? options_of(p, i) : std::vector<option>{{contact_regime::open, 0}});
        total *= opts.back().size();
        if (total > max_candidates)
            throw input_error("contacts: " + std::to_string(p.contacts.size()) +
                              " contacts acting at once give more than " + std::to_string(max_candidates) +
                              " candidate sets of the law; at most " + std::to_string(max_candidates) +
                              " are tried (fewer contacts, or \"impacts\": \"sequential\")");
    }
    std::vector<std::size_t> idx(opts.size(), 0);
    for (std::size_t n = 0; n < total; ++n) {
        std::vector<option> choice;
        for (std::size_t i = 0; i < opts.size(); ++i)
            choice.push_back(opts[i][idx[i]]);
        f(choice);
        for (std::size_t i = 0; i < idx.size(); ++i) {
            if (++idx[i] < opts[i].size())
                break;
            idx[i] = 0;
        }
    }
}

bool condition_holds(const system_condition &c)
{
    const decision d = decide(c.value);
    if (d == decision::not_real || d == decision::out_of_range || d == decision::undecided)
        throw input_error("contacts: the condition " + c.meaning + " " + decision_text(d));
    if (d == decision::symbolic)
        throw input_error("contacts: the law is decided for numeric problems only");
    return d == decision::positive || (!c.strict && d == decision::zero);
}

bool same(const ex &a, const ex &b)
{
    return !nonzero(a - b);
}

// Every condition of the candidate holds (decided exactly), and a perfectly rough contact with
// no normal impulse carries no tangential impulse.
bool holds(const model &m, const core &c)
{
    for (const system_condition &k : c.conditions)
        if (!condition_holds(k))
            return false;
    for (std::size_t i = 0; i < c.choice.size(); ++i)
        if (c.choice[i].regime == contact_regime::stick && !nonzero(c.lambda[m.nrow[i]]))
            for (std::size_t t : m.trows[i])
                if (nonzero(c.lambda[t]))
                    return false;
    return true;
}

// A holding candidate of a numeric problem.
struct holding {
    core c;
    std::vector<ex> all;
    std::vector<std::vector<ex>> gv;
};

// The candidates that hold for the velocities gv (contacts not considered carry no impulse).
std::vector<holding> holding_candidates(const model &m, const std::vector<std::vector<ex>> &gv,
                                        const std::vector<bool> &considered)
{
    const std::vector<ex> q = contact_velocities(m, gv);
    std::vector<holding> out;
    for_each_choice(m.p, considered, [&](const std::vector<option> &choice) {
        core start;
        start.choice = choice;
        for (const core &c : solve_core(m, q, considered, start))
            if (holds(m, c)) {
                holding h{c, {}, gv};
                apply_impulses(m, c.lambda, h.all, h.gv);
                out.push_back(h);
            }
    });
    return out;
}

std::string set_name(const std::vector<option> &choice)
{
    std::string s = "{";
    for (std::size_t i = 0; i < choice.size(); ++i)
        s += (i ? ", " : "") + std::to_string(i) + " " + contact_regime_name(choice[i].regime) +
             (choice[i].regime == contact_regime::slide ? (choice[i].sign > 0 ? " +t" : " -t") : "");
    return s + "}";
}

// The one answer among the holding candidates: refused when none holds or two differ in velocities.
const holding &choose(const std::vector<holding> &h, bool &unique, const std::string &step)
{
    if (h.empty())
        throw input_error("contacts: no set of contacts and regimes satisfies the law" + step +
                          " (no contact can take the impulse the others need: e.g. a moving body striking one "
                          "that its pivots hold fast, or a perfectly rough contact that would need a pulling normal "
                          "impulse to stick)");
    unique = true;
    for (std::size_t k = 1; k < h.size(); ++k) {
        for (std::size_t b = 0; b < h[0].gv.size(); ++b)
            for (std::size_t i = 0; i < h[0].gv[b].size(); ++i)
                if (!same(h[0].gv[b][i], h[k].gv[b][i]))
                    throw input_error("contacts: the law holds for more than one set of contacts with different "
                                      "velocities after impact" +
                                      step + ": " + set_name(h[0].c.choice) + " and " + set_name(h[k].c.choice));
        for (std::size_t r = 0; r < h[0].all.size(); ++r)
            unique = unique && same(h[0].all[r], h[k].all[r]);
    }
    return h[0];
}

void require_numeric(const problem &p)
{
    if (!p.is_numeric())
        throw input_error("contacts: the law of a system is decided for numeric problems only; 'impactgen formulas' "
                          "gives every candidate with its conditions");
}

void set_energy(const problem &p, system_answer &a)
{
    a.energy_before = system_kinetic_energy(
        p,
        [&] {
            std::vector<vec3> v;
            for (const body &b : p.bodies)
                v.push_back(b.velocity);
            return v;
        }(),
        [&] {
            std::vector<vec3> w;
            for (const body &b : p.bodies)
                w.push_back(b.angular_velocity);
            return w;
        }());
    a.energy_after = system_kinetic_energy(p, a.result.velocity, a.result.angular_velocity);
    bool moving_infinite = false;
    for (const body &b : p.bodies)
        moving_infinite = moving_infinite || (b.infinite_mass && !b.at_rest());
    a.energy_gain = !moving_infinite && decide(a.energy_after - a.energy_before) == decision::positive;
}

system_answer sequential_answer(const model &m)
{
    const problem &p = m.p;
    system_answer a;
    a.sequential = true;
    std::vector<std::vector<ex>> gv = m.gv0;
    std::vector<ex> sum(m.rows.size(), ex(0));
    std::vector<option> last(p.contacts.size(), option{contact_regime::open, 0});
    for (std::size_t step = 0;; ++step) {
        const std::vector<ex> q = contact_velocities(m, gv);
        std::size_t k = p.contacts.size();
        for (std::size_t i = 0; i < p.contacts.size() && k == p.contacts.size(); ++i)
            if (decide(q[m.nrow[i]]) == decision::negative)
                k = i;
        if (k == p.contacts.size())
            break;
        if (step == max_steps)
            throw input_error("impacts: the sequence of single-contact impacts does not end within " +
                              std::to_string(max_steps) + " steps");
        std::vector<bool> considered(p.contacts.size(), false);
        considered[k] = true;
        bool unique = true;
        const holding h = choose(holding_candidates(m, gv, considered), unique,
                                 " at step " + std::to_string(step + 1) + " (" + pname(k) + ")");
        a.impulses_unique = a.impulses_unique && unique;
        for (std::size_t r = 0; r < sum.size(); ++r)
            sum[r] = simp(sum[r] + h.all[r]);
        gv = h.gv;
        last[k] = h.c.choice[k];
        a.sequence.push_back(k);
        a.steps.push_back(finish(m, h.c.choice, h.all, h.gv, h.c.w));
    }
    a.result = finish(m, last, sum, gv, {});
    const std::vector<ex> w = contact_velocities(m, gv);
    for (std::size_t i = 0; i < p.contacts.size(); ++i)
        a.result.normal_velocity_after[i] = simp(w[m.nrow[i]] / m.nlen[i]);
    return a;
}

} // namespace

const char *contact_regime_name(contact_regime r)
{
    switch (r) {
    case contact_regime::open:
        return "open";
    case contact_regime::smooth:
        return "smooth";
    case contact_regime::stick:
        return "stick";
    case contact_regime::slide:
        return "slide";
    }
    return "?";
}

std::string system_candidate::name() const
{
    if (!process.empty()) { // Routh's process at contact 0: its phases
        std::string s = "{0";
        for (std::size_t k = 0; k < process.size(); ++k)
            s += std::string(k ? " then " : " ") + phase_name(process[k].kind);
        return s + "}";
    }
    std::vector<option> choice;
    for (std::size_t i = 0; i < regimes.size(); ++i)
        choice.push_back({regimes[i], slide_sign[i]});
    return set_name(choice);
}

system_candidate system_candidate_of_impulses(const problem &p, const std::vector<ex> &lambda, contact_regime regime,
                                              int slide_sign)
{
    const model m = build_model(p);
    std::vector<ex> all;
    std::vector<std::vector<ex>> gv = m.gv0;
    apply_impulses(m, lambda, all, gv);
    std::vector<ex> w = contact_velocities(m, m.gv0);
    for (std::size_t r = 0; r < w.size(); ++r) {
        for (std::size_t j = 0; j < w.size(); ++j)
            w[r] += m.W[r][j] * lambda[j];
        w[r] = simp(w[r]);
    }
    std::vector<option> choice(p.contacts.size(), option{contact_regime::open, 0});
    choice[0] = {regime, slide_sign};
    return finish(m, choice, all, gv, w);
}

namespace
{

// The candidates with the contacts `considered` acting (the others open), in the order
// solve_system tries them.
std::vector<system_candidate> candidates_considering(const problem &p, const std::vector<bool> &considered)
{
    const model m = build_model(p);
    const std::vector<ex> q = contact_velocities(m, m.gv0);
    std::vector<system_candidate> out;
    for_each_choice(p, considered, [&](const std::vector<option> &choice) {
        core start;
        start.choice = choice;
        for (const core &c : solve_core(m, q, considered, start)) {
            std::vector<ex> all;
            std::vector<std::vector<ex>> gv = m.gv0;
            apply_impulses(m, c.lambda, all, gv);
            system_candidate s = finish(m, choice, all, gv, c.w);
            s.conditions = c.conditions;
            out.push_back(s);
        }
    });
    return out;
}

} // namespace

std::vector<system_candidate> system_candidates(const problem &p)
{
    if (p.sequential)
        throw input_error("impacts: sequential impacts have no closed-form candidates (which contact acts next "
                          "depends on the numbers); 'impactgen solve' follows the chain of a numeric problem");
    if (system_follows_process(p))
        return system_process_candidates(p);
    return candidates_considering(p, std::vector<bool>(p.contacts.size(), true));
}

std::vector<system_candidate> system_step_candidates(const problem &p, std::size_t k)
{
    if (system_follows_process(p))
        return system_process_candidates(p);
    std::vector<bool> considered(p.contacts.size(), false);
    considered.at(k) = true;
    return candidates_considering(p, considered);
}

system_answer solve_system(const problem &p)
{
    require_numeric(p);
    const model m = build_model(p);
    system_answer a;
    if (system_follows_process(p)) { // one contact: sequential or simultaneous alike
        a.result = system_process_candidates(p).at(0);
        a.impulses_unique = !m.redundant;
        a.sequential = p.sequential;
        if (p.sequential && a.result.regimes[0] != contact_regime::open) {
            a.sequence = {0};
            a.steps = {a.result};
        }
    } else if (p.sequential) {
        a = sequential_answer(m);
        a.impulses_unique = a.impulses_unique && !m.redundant;
    } else {
        const std::vector<bool> considered(p.contacts.size(), true);
        const std::vector<holding> hs = holding_candidates(m, m.gv0, considered);
        const holding &h = choose(hs, a.impulses_unique, "");
        a.impulses_unique = a.impulses_unique && !m.redundant;
        a.result = finish(m, h.c.choice, h.all, h.gv, h.c.w);
        a.result.conditions = h.c.conditions;
    }
    set_energy(p, a);
    return a;
}

long system_candidate_failure(const system_candidate &c)
{
    for (std::size_t k = 0; k < c.conditions.size(); ++k)
        if (!condition_holds(c.conditions[k]))
            return static_cast<long>(k);
    for (std::size_t i = 0; i < c.regimes.size(); ++i)
        if (c.regimes[i] == contact_regime::stick && !nonzero(c.normal_impulse[i]))
            for (const ex &t : c.tangential_impulse[i])
                if (nonzero(t))
                    return static_cast<long>(c.conditions.size());
    return -1;
}

system_delassus system_delassus_of(const problem &p)
{
    const model m = build_model(p);
    system_delassus out;
    out.W = m.W;
    out.u = contact_velocities(m, m.gv0);
    out.rows.resize(out.u.size());
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        out.rows[m.nrow[i]] = "n" + std::to_string(i);
        for (std::size_t k = 0; k < m.trows[i].size(); ++k)
            out.rows[m.trows[i][k]] = (k ? "b" : "t") + std::to_string(i);
    }
    out.redundant_joints = m.redundant;
    return out;
}

ex system_kinetic_energy(const problem &p, const std::vector<vec3> &v, const std::vector<vec3> &w)
{
    ex T = 0;
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        const body &B = p.bodies[b];
        if (B.infinite_mass)
            continue;
        T += B.mass * dot(v[b], v[b]) / 2;
        if (!B.particle)
            T += dot(w[b], mul(B.inertia, w[b])) / 2;
    }
    return simp(T);
}

void refuse_system_for(const problem &p, const std::string &command)
{
    if (!p.is_system())
        return;
    std::string what = p.contacts.size() > 1 ? "several contacts"
                       : !p.joints.empty()   ? "joints"
                       : p.sequential        ? "sequential impacts"
                                             : "a perfectly rough contact (\"friction\": \"inf\")";
    throw input_error(command + ": a system (" + what + ") is not handled by " + command +
                      " yet; 'impactgen solve' and 'impactgen formulas' solve it");
}

} // namespace impactgen
