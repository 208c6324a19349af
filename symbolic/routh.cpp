#include "routh.hpp"

#include "decide.hpp"
#include "names/escape.hpp"
#include "response.hpp"

#include <stdexcept>
#include <variant>

namespace impactgen
{
using namespace GiNaC;

namespace
{

// The process at one point: P_n, P_t, u_t, u_n, the normal work in compression and in
// restitution, and the phases so far.
struct walk_state {
    process_sequence seq;
    ex P = 0, Pt = 0, ut, un, W = 0, Wr = 0;
    bool compressed = false;
    bool first = true; // in the first phase
};

// A phase's slopes: dP_t = r dP_n, du_t = a dP_n, du_n = b dP_n.
struct slopes {
    phase_kind kind = phase_kind::slide;
    int s = 0; // slip sign of a slide or reverse
    ex a, b, r;
};

class walker
{
public:
    walker(const process_inputs &in, const std::string &where, bool compression_only)
        : in_(in), where_(where), compression_only_(compression_only)
    {
    }

    std::vector<process_sequence> run();

private:
    const process_inputs &in_;
    std::string where_;
    bool compression_only_;
    bool symbolic_ = false;
    std::vector<process_sequence> out_;

    ex value(const ex &x) const { return in_.values.nops() ? x.subs(in_.values) : x; }
    ex fix(const ex &x) const { return symbolic_ ? x : tidy(x); }
    // The outcomes of sign(x): +1 / -1 (an exact zero counts as zero_goes); symbols give both,
    // each with its condition (strict on the side that does not take zero).
    std::vector<std::pair<int, process_condition>> signs(const ex &x, int zero_goes, process_test kind,
                                                         const std::string &meaning) const;
    slopes slopes_of(phase_kind kind, int s) const;
    void advance(walk_state &st, const slopes &sl, const ex &x) const;
    void leaf(walk_state st, const slopes &sl);
    void phase(walk_state st, phase_kind kind, int s);
    void compression(walk_state st, const slopes &sl, bool stops, const ex &xs);
    void restitution(walk_state st, const slopes &sl, bool stops, const ex &xs, bool from_zero, const ex &fresh_xc = 0);
    void slip_stopped(walk_state st, const slopes &sl);
};

std::vector<std::pair<int, process_condition>> walker::signs(const ex &x, int zero_goes, process_test kind,
                                                             const std::string &meaning) const
{
    const ex v = value(x);
    const decision d = is_constant(v) ? decide_condition(tidy(v)) : decision::symbolic;
    switch (d) {
    case decision::positive:
        return {{1, {}}};
    case decision::negative:
        return {{-1, {}}};
    case decision::zero:
        return {{zero_goes, {}}};
    case decision::symbolic:
        break;
    default:
        throw input_error(where_ + ": whether " + meaning + " " + decision_text(d));
    }
    // The meaning says which side the branch takes; the value carries the relation (> 0 or >= 0).
    process_condition pos{x, zero_goes < 0, kind, meaning};
    process_condition neg{-x, zero_goes > 0, kind, "not: " + meaning};
    return {{1, pos}, {-1, neg}};
}

slopes walker::slopes_of(phase_kind kind, int s) const
{
    slopes sl;
    sl.kind = kind;
    sl.s = s;
    if (kind == phase_kind::stick) {
        sl.a = 0;
        sl.r = -in_.Ktn / in_.Ktt;
        sl.b = fix((in_.Knn * in_.Ktt - in_.Ktn * in_.Ktn) / in_.Ktt);
        sl.r = fix(sl.r);
        return sl;
    }
    sl.a = fix(in_.Ktn - s * in_.mu * in_.Ktt);
    sl.b = fix(in_.Knn - s * in_.mu * in_.Ktn);
    sl.r = fix(-s * in_.mu);
    return sl;
}

// Moves the state x along the phase, adding the normal work to compression or restitution.
void walker::advance(walk_state &st, const slopes &sl, const ex &x) const
{
    const ex work = st.un * x + sl.b * x * x / 2;
    if (st.compressed)
        st.Wr = fix(st.Wr + work);
    else
        st.W = fix(st.W + work);
    st.P = fix(st.P + x);
    st.Pt = fix(st.Pt + sl.r * x);
    st.ut = fix(st.ut + sl.a * x);
    st.un = fix(st.un + sl.b * x);
}

void walker::leaf(walk_state st, const slopes &sl)
{
    st.seq.phases.push_back({sl.kind, st.P});
    st.seq.normal_impulse = st.P;
    st.seq.tangential_impulse = st.Pt;
    st.seq.tangential_velocity = st.ut;
    st.seq.normal_velocity = st.un;
    out_.push_back(st.seq);
}

void walker::phase(walk_state st, phase_kind kind, int s)
{
    const slopes sl = slopes_of(kind, s);
    // Only the first slide, entered with slip, can stop (a reverse's slip only grows; see the header).
    if (kind != phase_kind::slide || st.ut.is_zero()) {
        if (st.compressed)
            restitution(st, sl, false, 0, false);
        else
            compression(st, sl, false, 0);
        return;
    }
    for (const auto &[o, cond] :
         signs(-s * sl.a, -1, process_test::slip_slows, "the slip decelerates: -s (K_tn - s mu K_tt)")) {
        walk_state b = st;
        if (!cond.meaning.empty())
            b.seq.conditions.push_back(cond);
        const ex xs = o > 0 ? fix(-st.ut / sl.a) : ex(0);
        compression(b, sl, o > 0, xs);
    }
}

void walker::compression(walk_state st, const slopes &sl, bool stops, const ex &xs)
{
    if (st.compressed) {
        restitution(st, sl, stops, xs, false);
        return;
    }
    for (const auto &[o, cond] :
         signs(sl.b, -1, process_test::normal_slope, "the normal velocity grows along the phase: b")) {
        walk_state b = st;
        if (!cond.meaning.empty())
            b.seq.conditions.push_back(cond);
        if (o < 0) { // u_n does not grow: compression cannot end in this phase
            if (stops) {
                advance(b, sl, xs);
                slip_stopped(b, sl);
                continue;
            }
            if (!symbolic_)
                throw input_error(where_ + ": the contact wedges: while it slides, the normal velocity of approach "
                                           "does not decrease (n.K(n - mu s e_t) <= 0) and the slip never stops, "
                                           "so no finite impulse ends the compression (refused under every law)");
            b.seq.wedges = true;
            out_.push_back(b.seq);
            continue;
        }
        const ex xc = fix(-b.un / sl.b);
        auto compress = [&](walk_state c, bool still_stops, const ex &rest) {
            // No work before this phase (compression ends in the first): W_c = -b x_c^2 / 2.
            const ex fresh = c.W.is_zero() ? xc : ex(0);
            advance(c, sl, xc);
            c.un = 0;
            c.compressed = true;
            c.seq.compression_impulse = c.P;
            c.seq.compression_work = c.W;
            if (compression_only_) {
                leaf(c, sl);
                return;
            }
            restitution(c, sl, still_stops, rest, true, fresh);
        };
        if (!stops) {
            compress(b, false, 0);
            continue;
        }
        for (const auto &[o2, cond2] : signs(xs - xc, 1, process_test::compression_first,
                                             "the compression ends before the slip stops: x_s - x_c")) {
            walk_state c = b;
            if (!cond2.meaning.empty())
                c.seq.conditions.push_back(cond2);
            if (o2 > 0) {
                compress(c, true, fix(xs - xc));
            } else {
                advance(c, sl, xs);
                slip_stopped(c, sl);
            }
        }
    }
}

// The distance along the phase to the end of restitution, from the state st (compressed).
void walker::restitution(walk_state st, const slopes &sl, bool stops, const ex &xs, bool from_zero, const ex &fresh_xc)
{
    // The law's own end of restitution (one case per law: restitution_law.hpp, law_cases).
    const ex xf = std::visit(
        law_cases{
            [&](const newton_restitution &) -> ex {
                throw std::logic_error("Newton's law of restitution is not followed through the impact");
            },
            [&](const poisson_restitution &) { return fix((1 + in_.e) * st.seq.compression_impulse - st.P); },
            [&](const energetic_restitution &) {
                const ex R = fix(-in_.e * in_.e * st.seq.compression_work - st.Wr);
                const ex un = value(st.un);
                if (from_zero || (is_constant(un) && decide(tidy(un)) == decision::zero)) {
                    // From u_n = 0 the work b x^2 / 2 grows only where b > 0 (b = 0: a stick with K
                    // singular, whose normal velocity stays 0 and restores nothing).
                    if (!from_zero && !symbolic_ && decide_condition(tidy(value(sl.b))) != decision::positive &&
                        decide(tidy(value(R))) != decision::zero)
                        throw input_error(where_ + ": the contact sticks with its normal velocity held at 0 (the "
                                                   "contact response K is singular): the energetic law's "
                                                   "restitution never ends");
                    // Compression in this phase from no work (fresh_xc = x_c): R = e^2 b x_c^2 / 2, so
                    // the root is e x_c exactly (e >= 0, x_c > 0), with no square root or division.
                    return from_zero && !fresh_xc.is_zero() ? fix(in_.e * fresh_xc) : fix(sqrt(2 * R / sl.b));
                }
                return fix(2 * R / (st.un + sqrt(st.un * st.un + 2 * sl.b * R)));
            },
        },
        in_.law);
    if (!stops) {
        advance(st, sl, xf);
        leaf(st, sl);
        return;
    }
    for (const auto &[o, cond] :
         signs(xs - xf, 1, process_test::ends_first, "restitution ends before the slip stops: x_s - x_f")) {
        walk_state b = st;
        if (!cond.meaning.empty())
            b.seq.conditions.push_back(cond);
        if (o > 0) {
            advance(b, sl, xf);
            leaf(b, sl);
        } else {
            advance(b, sl, xs);
            slip_stopped(b, sl);
        }
    }
}

// The slip of the slide sl reached zero: stick if the ratio is inside the cone, else reverse.
void walker::slip_stopped(walk_state st, const slopes &sl)
{
    st.seq.phases.push_back({sl.kind, st.P});
    st.ut = 0;
    st.first = false;
    for (const auto &[o, cond] : signs(in_.mu * in_.Ktt + sl.s * in_.Ktn, 1, process_test::sticks,
                                       "the sticking ratio is inside the cone: mu K_tt + s K_tn")) {
        walk_state b = st;
        if (!cond.meaning.empty())
            b.seq.conditions.push_back(cond);
        if (o > 0)
            phase(b, phase_kind::stick, 0);
        else
            phase(b, phase_kind::reverse, -sl.s);
    }
}

std::vector<process_sequence> walker::run()
{
    symbolic_ = !is_constant(value(in_.Ktt + in_.Ktn + in_.Knn + in_.ut + in_.un + in_.mu + in_.e));
    walk_state st;
    st.ut = in_.ut;
    st.un = in_.un;
    const ex ut = value(in_.ut);
    const bool no_slip = is_constant(ut) ? decide(tidy(ut)) == decision::zero : identically_zero(ut);
    if (!no_slip) {
        for (const auto &[o, cond] : signs(in_.ut, 1, process_test::initial_slip, "the initial slip u_t")) {
            walk_state b = st;
            if (!cond.meaning.empty()) { // u_t = 0 starts without slip: strict on both sides
                b.seq.conditions.push_back(cond);
                b.seq.conditions.back().strict = true;
            }
            phase(b, phase_kind::slide, o);
        }
        return out_;
    }
    st.ut = 0;
    if (!symbolic_ && decide(tidy(value(in_.Ktt))) == decision::zero) {
        if (compression_only_) // Newton's wedge check: the friction solver says why it cannot answer
            return out_;
        throw input_error(where_ + ": the contact response K is singular (K_tt = 0: the contact point cannot move "
                                   "tangentially) and the contact does not slip: the tangential impulse is not "
                                   "determined");
    }
    for (const auto &[o, cond] :
         signs(in_.mu * in_.mu * in_.Ktt * in_.Ktt - in_.Ktn * in_.Ktn, 1, process_test::sticks_at_start,
               "starting without slip, the sticking ratio is inside the cone: "
               "mu^2 K_tt^2 - K_tn^2")) {
        walk_state b = st;
        if (!cond.meaning.empty())
            b.seq.conditions.push_back(cond);
        if (o > 0) {
            phase(b, phase_kind::stick, 0);
            continue;
        }
        for (const auto &[o2, cond2] :
             signs(in_.Ktn, 1, process_test::slip_direction, "starting without slip, the slip it takes: K_tn")) {
            walk_state c = b;
            if (!cond2.meaning.empty())
                c.seq.conditions.push_back(cond2);
            phase(c, phase_kind::slide, o2);
        }
    }
    return out_;
}

} // namespace

std::vector<process_sequence> routh_process(const process_inputs &in, const std::string &where, bool compression_only)
{
    walker w(in, where, compression_only);
    return w.run();
}

namespace
{

std::string contact_where(const problem &p, const std::string &key)
{
    return (p.source.empty() ? std::string("contact") : names::display_text(p.source) + ": contact") + key;
}

using process_side = contact_side;

} // namespace

std::array<contact_side, 2> process_sides(const problem &p)
{
    const contact_spec &c = p.contact();
    std::array<process_side, 2> sd;
    sd[0].r = response_of(p, c.body1, c.point);
    sd[0].sign = -1;
    sd[1].r = response_of(p, c.body2, c.point);
    for (process_side &x : sd)
        if (x.r.movable && !x.r.particle)
            x.inv[2][2] = 1 / x.r.inertia[2][2];
    return sd;
}

namespace
{

regime_case case_of(const derivation &d, const solution &shared, const process_sequence &q)
{
    regime_case c;
    c.sol.steps = shared.steps;
    c.process = q.phases;
    c.process_conditions = q.conditions;
    c.kind = q.phases.back().kind == phase_kind::stick ? regime::stick : regime::slide;
    c.name = "process:";
    for (const process_phase &ph : q.phases)
        c.name += std::string(c.name.size() > 8 ? ", " : " ") + phase_name(ph.kind);
    c.sol.normal_impulse = q.normal_impulse;
    c.tangential_scalar = q.tangential_impulse;
    for (int a = 0; a < 3; ++a) {
        c.impulse[a] = q.normal_impulse * d.n_hat[a] + q.tangential_impulse * d.t_dir[a];
        c.tangential_impulse[a] = q.tangential_impulse * d.t_dir[a];
        c.direction[a] = 0;
    }
    c.sliding_speed = q.tangential_velocity;
    apply_impulse(d, process_sides(d.prob), c, true); // a planar process: no pivot impulse along z
    return c;
}

} // namespace

process_inputs process_inputs_of(const derivation &d, solution &s)
{
    const problem &p = d.prob;
    const std::array<process_side, 2> sd = process_sides(p);
    const vec3 &n = d.n_hat, &t = d.t_dir;
    auto K = [&](const vec3 &x, const vec3 &y) { // x.K y
        const vec3 Ky = point_velocity_change(sd[0].r, sd[0].inv, y) + point_velocity_change(sd[1].r, sd[1].inv, y);
        return tidy(dot(x, Ky));
    };
    const vec3 u = d.vB - d.vA;
    process_inputs in;
    in.mu = p.contact().friction();
    in.e = p.restitution;
    in.law = p.contact().law_of_restitution;
    const ex vals[5] = {K(t, t), K(t, n), K(n, n), tidy(dot(u, t)), tidy(dot(u, n))};
    if (p.is_numeric()) {
        in.Ktt = vals[0], in.Ktn = vals[1], in.Knn = vals[2], in.ut = vals[3], in.un = vals[4];
        return in;
    }
    step_builder sb(s, p);
    const step_role roles[5] = {step_role::contact_response, step_role::contact_response, step_role::contact_response,
                                step_role::relative_velocity, step_role::approach_velocity};
    const char *names[5] = {"K_tt", "K_tn", "K_nn", "u_t", "u_n"};
    const char *texs[5] = {"K_{tt}", "K_{tn}", "K_{nn}", "u_{t}", "u_{n}"};
    const char *meanings[5] = {"contact response e_t.K e_t: change of u_t per unit tangential impulse",
                               "contact response e_t.K n: change of u_t per unit normal impulse",
                               "contact response n.K n: change of u_n per unit normal impulse",
                               "tangential velocity u.e_t of the contact points before impact (the slip)",
                               "normal velocity of approach u.n before impact (negative for an impact)"};
    ex *slots[5] = {&in.Ktt, &in.Ktn, &in.Knn, &in.ut, &in.un};
    for (int k = 0; k < 5; ++k) {
        *slots[k] = sb.add(roles[k], no_body, -1, -1, names[k], texs[k], vals[k], meanings[k], true);
        in.values.append(*slots[k] == vals[k]);
    }
    return in;
}

impact_solution solve_routh(const derivation &d)
{
    const problem &p = d.prob;
    impact_solution f;
    f.mu = p.contact().friction();
    f.law = p.contact().law_of_restitution;
    f.n_hat = d.n_hat;
    f.e_t = d.t_dir;
    f.e_b = zero_vec();
    const process_inputs in = process_inputs_of(d, f.shared);
    for (const process_sequence &q : routh_process(in, contact_where(p, ".friction")))
        if (!q.wedges)
            f.cases.push_back(case_of(d, f.shared, q));
    return f;
}

void refuse_wedging(const derivation &d)
{
    const problem &p = d.prob;
    if (p.dimension != 2 || !p.is_numeric())
        return;
    solution unused;
    (void)routh_process(process_inputs_of(d, unused), contact_where(p, ".friction"), true);
}

void require_newton_for_output(const problem &p, const std::string &what)
{
    for (std::size_t k = 0; k < p.contacts.size(); ++k) {
        const contact_spec &c = p.contacts[k];
        if (!follows_process(c.law_of_restitution) || c.friction().is_zero())
            continue;
        const std::string key =
            p.contacts.size() == 1 ? std::string("contact.law") : "contacts[" + std::to_string(k) + "].law";
        throw input_error(
            key + ": \"" + law_name(c.law_of_restitution) + "\" with friction is not in '" + what +
            "' yet ('impactgen solve' and 'impactgen formulas' follow the process); use \"newton\" for '" + what + "'");
    }
}

} // namespace impactgen
