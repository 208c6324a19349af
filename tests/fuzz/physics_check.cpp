// What an answer must satisfy (shared/problem-format.md), with n^ the unit
// normal, O the contact point, N the normal impulse, P = N n^ (+ the
// tangential impulse when the answer has one) the impulse on body 2, -P on
// body 1, R the pivot impulse of a body (0 without a pivot):
//   - every body of the problem in the answer, with vectors of the right length
//     and finite numbers only;
//   - a body of finite mass: m (v' - v) = s P + R (s = -1 for body 1, +1 for
//     body 2, 0 for a body not in the contact);
//   - with rotational inertia: I (w' - w) = (O - C) x (s P) + (E - C) x R
//     (planar: the z component, I a scalar); a particle keeps w;
//   - a body of infinite mass, and a body not in the contact, is unchanged;
//   - restitution at O: (v'_B - v'_A).n^ = -e (v_B - v_A).n^ with
//     v_P = v + w x (P - C) (a particle's spin does not move its contact point,
//     an infinite mass's spin does), and the contact points approached;
//   - with "law": "poisson" or "energetic" and friction, instead of Newton's restitution: the
//     points do not approach after impact, the impulse lies in the friction cone, and "process"
//     ends at N with the regime as its last phase;
//   - N >= 0; every pivot point at rest after impact;
//   - kinetic energy of the bodies of finite mass before and after as the
//     answer says, before - after = lost, lost >= 0 unless a body of infinite
//     mass moves (then it may do work on the others) or the answer says "energy_gain" (Newton's
//     law with friction, and only then).
// Everything is computed in long double from the problem's values, each
// evaluated to double (as the answer's values are).
#include "physics_check.hpp"

#include "symbolic/problem.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

namespace impactgen::fuzz {

namespace {

using real = long double;
using rvec = std::array<real, 3>;
using json = nlohmann::json;

// Tolerance of every law, relative to the largest term that enters it (a
// momentum, an impulse, a moment, a velocity, an energy). The answer is the
// exact rational solution rounded once to double (relative error <= 2^-53 per
// value), the problem's values are rounded the same way, and each law is a
// sum of a few products of them evaluated in long double: its residual is a
// few ulps of its largest term, about 1e-15 of the scale. 1e-9 leaves six
// orders of magnitude for rounding while any real error in a law (a wrong
// formula, a dropped or mis-signed term, a value of the wrong body) shows at
// the size of the term concerned, far above it.
constexpr real tolerance = 1e-9L;
// Below the normal range of double (2.2e-308) values lose relative precision
// when rounded to double; residuals under this absolute floor are not errors.
constexpr real floor_abs = 1e-290L;

rvec operator-(const rvec& a, const rvec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
rvec operator+(const rvec& a, const rvec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
rvec operator*(real s, const rvec& a) { return {s * a[0], s * a[1], s * a[2]}; }
real dot(const rvec& a, const rvec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
real norm(const rvec& a) { return std::sqrt(dot(a, a)); }
rvec cross(const rvec& a, const rvec& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

struct rbody {
    std::string name;
    bool infinite = false, particle = true;
    real m = 0;
    std::array<rvec, 3> I{};
    rvec c{}, v{}, w{};   // before
    rvec v1{}, w1{};      // after (from the answer)
};

rvec mul(const std::array<rvec, 3>& I, const rvec& x) { return {dot(I[0], x), dot(I[1], x), dot(I[2], x)}; }
real frobenius(const std::array<rvec, 3>& I) { return std::sqrt(dot(I[0], I[0]) + dot(I[1], I[1]) + dot(I[2], I[2])); }

class checker {
public:
    std::vector<std::string> failures;

    void fail(const std::string& what) { failures.push_back(what); }

    // |residual| <= tolerance * scale (or below the absolute floor).
    void near_zero(real residual, real scale, const std::string& law)
    {
        if (!(std::abs(residual) <= std::max(tolerance * scale, floor_abs))) {
            std::ostringstream os;
            os.precision(17);
            os << law << ": residual " << static_cast<double>(residual) << " at scale " << static_cast<double>(scale);
            fail(os.str());
        }
    }

    void near_zero(const rvec& residual, real scale, const std::string& law, int dim)
    {
        for (int c = 0; c < dim; ++c)
            near_zero(residual[c], scale, law + " (component " + "xyz"[c] + ")");
    }

    real number(const json& j, const std::string& where)
    {
        if (!j.is_number()) {
            fail(where + ": expected a finite number, got " + j.dump());
            return 0;
        }
        double x = j.get<double>();
        if (!std::isfinite(x))
            fail(where + ": not finite");
        return x;
    }

    rvec vector(const json& j, int dim, const std::string& where)
    {
        rvec r{0, 0, 0};
        if (!j.is_array() || static_cast<int>(j.size()) != dim) {
            fail(where + ": expected a list of " + std::to_string(dim) + " numbers, got " + j.dump());
            return r;
        }
        for (int c = 0; c < dim; ++c)
            r[c] = number(j[static_cast<std::size_t>(c)], where + "[" + std::to_string(c) + "]");
        return r;
    }

    real value(const GiNaC::ex& e, const std::string& where)
    {
        GiNaC::ex x = e.evalf();
        if (!GiNaC::is_a<GiNaC::numeric>(x) || !GiNaC::ex_to<GiNaC::numeric>(x).is_real()) {
            std::ostringstream os;
            os << e;
            fail("problem value " + where + " is not a real number: " + os.str());
            return 0;
        }
        return GiNaC::ex_to<GiNaC::numeric>(x).to_double();
    }

    rvec value(const vec3& v, const std::string& where)
    {
        return {value(v[0], where), value(v[1], where), value(v[2], where)};
    }
};

// Velocity of the point q of a body; a particle of finite mass is a point.
rvec point_velocity(const rbody& b, const rvec& v, const rvec& w, const rvec& q)
{
    return b.particle && !b.infinite ? v : v + cross(w, q - b.c);
}
// The largest term of that velocity, for the scale of a law.
real point_speed_scale(const rbody& b, const rvec& v, const rvec& w, const rvec& q)
{
    return b.particle && !b.infinite ? norm(v) : norm(v) + norm(w) * norm(q - b.c);
}

real kinetic_energy(const rbody& b, const rvec& v, const rvec& w)
{
    real t = b.m * dot(v, v) / 2;
    if (!b.particle)
        t += dot(w, mul(b.I, w)) / 2;
    return t;
}

// A system (format version 3): each body's impulse-momentum with every impulse of the answer
// (contacts, joints, pivots), the joints together and the pivots at rest after impact, and
// per contact the law: N_i >= 0, "open" exactly when N_i = 0, u'_i + e_i u_i >= 0 with equality
// where N_i > 0 (simultaneous), no contact approaching at the end (sequential, or a contact whose
// answer carries Routh's process: poisson, energetic).
void check_system(checker& ck, const problem& p, const json& a, const std::vector<rbody>& bodies)
{
    const int dim = p.dimension;
    const std::size_t nb = bodies.size();
    std::vector<rvec> F(nb, rvec{0, 0, 0}), M(nb, rvec{0, 0, 0});
    std::vector<real> scale(nb, 0);
    auto act = [&](std::size_t b, const rvec& q, const rvec& P) {
        F[b] = F[b] + P;
        M[b] = M[b] + cross(q - bodies[b].c, P);
        scale[b] += norm(P) * (1 + norm(q - bodies[b].c));
    };
    const json cs = a.value("contacts", json());
    if (!cs.is_array() || cs.size() != p.contacts.size()) {
        ck.fail("contacts: expected a list of " + std::to_string(p.contacts.size()));
        return;
    }
    std::vector<real> N(p.contacts.size());
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const contact_spec& c = p.contacts[i];
        const std::string w = "contacts[" + std::to_string(i) + "]";
        rvec n = ck.value(c.normal, w + ".normal");
        n = (1 / norm(n)) * n;
        N[i] = ck.number(cs[i].value("normal_impulse", json()), "answer " + w + ".normal_impulse");
        if (!(N[i] >= 0))
            ck.fail(w + ": normal_impulse < 0");
        if ((cs[i].value("regime", json()) == "open") != (N[i] == 0))
            ck.fail(w + ": regime \"open\" is not the same as no normal impulse");
        const rvec P = N[i] * n + ck.vector(cs[i].value("tangential_impulse", json()), dim, "answer " + w);
        const rvec q = ck.value(c.point, w + ".point");
        act(c.body2, q, P);
        act(c.body1, q, real(-1) * P);
    }
    const json js = a.value("joint_impulses", json()), ps = a.value("pivot_impulses", json());
    if (!js.is_array() || js.size() != p.joints.size() || !ps.is_array() || ps.size() != p.pivots.size()) {
        ck.fail("joint_impulses or pivot_impulses: not one per joint and pivot");
        return;
    }
    auto after = [&](std::size_t b, const rvec& q) { return point_velocity(bodies[b], bodies[b].v1, bodies[b].w1, q); };
    auto before = [&](std::size_t b, const rvec& q) { return point_velocity(bodies[b], bodies[b].v, bodies[b].w, q); };
    auto speed = [&](std::size_t b, const rvec& q) {
        return point_speed_scale(bodies[b], bodies[b].v, bodies[b].w, q) +
               point_speed_scale(bodies[b], bodies[b].v1, bodies[b].w1, q);
    };
    for (std::size_t j = 0; j < p.joints.size(); ++j) {
        const rvec q = ck.value(p.joints[j].point, "joint point");
        const rvec J = ck.vector(js[j], dim, "answer joint_impulses");
        act(p.joints[j].body2, q, J);
        act(p.joints[j].body1, q, real(-1) * J);
        ck.near_zero(after(p.joints[j].body2, q) - after(p.joints[j].body1, q),
                     speed(p.joints[j].body1, q) + speed(p.joints[j].body2, q), "joint together after impact", dim);
    }
    for (std::size_t k = 0; k < p.pivots.size(); ++k) {
        const rvec q = ck.value(p.pivots[k].point, "pivot point");
        act(p.pivots[k].body, q, ck.vector(ps[k], dim, "answer pivot_impulses"));
        ck.near_zero(after(p.pivots[k].body, q), speed(p.pivots[k].body, q), "pivot at rest after impact", dim);
    }
    for (std::size_t b = 0; b < nb; ++b) {
        const rbody& B = bodies[b];
        if (B.infinite)
            continue;
        const real sc = scale[b] + B.m * (norm(B.v) + norm(B.v1));
        ck.near_zero(B.m * (B.v1 - B.v) - F[b], sc, "impulse-momentum of " + B.name, dim);
        const rvec dL = mul(B.I, B.w1 - B.w) - M[b];
        const real sl = sc + frobenius(B.I) * (norm(B.w) + norm(B.w1));
        if (!B.particle && dim == 2)
            ck.near_zero(dL[2], sl, "angular impulse-momentum of " + B.name);
        else if (!B.particle)
            ck.near_zero(dL, sl, "angular impulse-momentum of " + B.name, 3);
    }
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const contact_spec& c = p.contacts[i];
        rvec n = ck.value(c.normal, "normal");
        n = (1 / norm(n)) * n;
        const rvec q = ck.value(c.point, "point");
        const real u = dot(before(c.body2, q) - before(c.body1, q), n);
        const real u1 = dot(after(c.body2, q) - after(c.body1, q), n);
        const real e = ck.value(p.restitution_of(i), "restitution");
        const real sc = speed(c.body1, q) + speed(c.body2, q);
        const std::string w = "contacts[" + std::to_string(i) + "]";
        if (p.sequential || cs[i].contains("process")) { // (Routh's process: separating at its end)
            if (u1 < -tolerance * sc)
                ck.fail(w + ": still approaching after the impact");
        } else if (u1 + e * u < -tolerance * sc) {
            ck.fail(w + ": u' + e u < 0 (the contact passes through)");
        } else if (N[i] > 0) {
            ck.near_zero(u1 + e * u, sc, w + ": restitution where the contact acts");
        }
    }
}

} // namespace

std::vector<std::string> check_answer(const std::string& problem_text, const std::string& answer_text)
{
    checker ck;
    problem p;
    try {
        p = read_problem(problem_text, "case.json");
    } catch (const std::exception& e) {
        ck.fail(std::string("the library refuses the problem that solve answered: ") + e.what());
        return ck.failures;
    }
    json a;
    try {
        a = json::parse(answer_text);
    } catch (const std::exception& e) {
        ck.fail(std::string("the answer is not JSON: ") + e.what());
        return ck.failures;
    }
    if (!a.is_object() || !a.contains("bodies") || !a["bodies"].is_object()) {
        ck.fail("the answer has no \"bodies\" object");
        return ck.failures;
    }
    const int dim = p.dimension;
    const std::size_t n_bodies = p.bodies.size();
    if (a["bodies"].size() != n_bodies)
        ck.fail("the answer has " + std::to_string(a["bodies"].size()) + " bodies, the problem " + std::to_string(n_bodies));

    std::vector<rbody> bodies(n_bodies);
    for (std::size_t i = 0; i < n_bodies; ++i) {
        const body& src = p.bodies[i];
        rbody& b = bodies[i];
        const std::string where = "bodies[" + std::to_string(i) + "]";
        b.name = src.name;
        b.infinite = src.infinite_mass;
        b.particle = src.particle;
        b.m = b.infinite ? 0 : ck.value(src.mass, where + ".mass");
        for (int r = 0; r < 3; ++r)
            b.I[r] = ck.value(src.inertia[r], where + ".inertia");
        b.c = ck.value(src.position, where + ".position");
        b.v = ck.value(src.velocity, where + ".velocity");
        b.w = ck.value(src.angular_velocity, where + ".angular_velocity");
        auto it = a["bodies"].find(src.name);
        if (it == a["bodies"].end() || !it->is_object()) {
            ck.fail("the answer lacks body " + where);
            continue;
        }
        const json& ab = *it;
        b.v1 = ck.vector(ab.value("velocity", json()), dim, "answer " + where + ".velocity");
        if (dim == 2)
            b.w1 = {0, 0, ck.number(ab.value("angular_velocity", json()), "answer " + where + ".angular_velocity")};
        else
            b.w1 = ck.vector(ab.value("angular_velocity", json()), 3, "answer " + where + ".angular_velocity");
    }

    if (p.is_system()) {
        check_system(ck, p, a, bodies);
        return ck.failures;
    }
    const real e = ck.value(p.restitution, "restitution");
    // Poisson's or the energetic law with friction: restitution is not Newton's ratio of velocities.
    const bool process_law = follows_process(p.contact().law_of_restitution) && !p.contact().friction().is_zero();
    const rvec o = ck.value(p.contact().point, "contact.point");
    rvec n = ck.value(p.contact().normal, "contact.normal");
    n = (1 / norm(n)) * n;
    const real N = ck.number(a.value("normal_impulse", json()), "answer normal_impulse");
    rvec P = N * n;
    if (a.contains("tangential_impulse"))
        P = P + ck.vector(a["tangential_impulse"], dim, "answer tangential_impulse");
    // The exact N rounded to double keeps its sign: no tolerance.
    if (!(N >= 0))
        ck.fail("normal_impulse < 0");

    std::vector<rvec> R(n_bodies, rvec{0, 0, 0}), E(n_bodies, rvec{0, 0, 0});
    std::vector<bool> has_pivot(n_bodies, false);
    const json pj = a.value("pivot_impulses", json());
    if (!pj.is_array() || pj.size() != p.pivots.size()) {
        ck.fail("pivot_impulses: expected a list of " + std::to_string(p.pivots.size()) + ", got " + pj.dump());
    } else {
        for (std::size_t k = 0; k < p.pivots.size(); ++k) {
            std::size_t i = p.pivots[k].body;
            R[i] = ck.vector(pj[k], dim, "answer pivot_impulses[" + std::to_string(k) + "]");
            E[i] = ck.value(p.pivots[k].point, "pivots[" + std::to_string(k) + "].point");
            has_pivot[i] = true;
        }
    }
    if (!ck.failures.empty())
        return ck.failures; // the laws below need a complete answer

    const std::size_t i1 = p.contact().body1, i2 = p.contact().body2;
    bool infinite_moves = false;
    for (std::size_t i = 0; i < n_bodies; ++i) {
        rbody& b = bodies[i];
        const std::string who = "body \"" + b.name + "\"";
        const real s = i == i1 ? -1 : i == i2 ? 1 : 0;
        if (b.infinite && (norm(b.v) > 0 || norm(b.w) > 0))
            infinite_moves = true;
        if (b.infinite || s == 0) {
            const real scale = norm(b.v) + norm(b.v1) + norm(b.w) + norm(b.w1);
            ck.near_zero(b.v1 - b.v, scale, who + " (infinite mass or not in the contact) keeps its velocity", dim);
            ck.near_zero(b.w1 - b.w, scale, who + " (infinite mass or not in the contact) keeps its angular velocity", 3);
            if (b.infinite)
                continue;
        }
        const rvec sP = s * P;
        // Linear momentum: m (v' - v) = s P + R.
        {
            const real scale = std::max({b.m * norm(b.v1), b.m * norm(b.v), norm(P), norm(R[i])});
            ck.near_zero(b.m * (b.v1 - b.v) - (sP + R[i]), scale, who + ": m (v' - v) = s N n + R", dim);
        }
        // Angular momentum about C: I (w' - w) = (O - C) x s P + (E - C) x R; a particle keeps w.
        if (b.particle) {
            ck.near_zero(b.w1 - b.w, norm(b.w) + norm(b.w1), who + ": a particle keeps its angular velocity", 3);
        } else {
            const rvec moment = cross(o - b.c, sP) + cross(E[i] - b.c, R[i]);
            const real Inorm = frobenius(b.I);
            const real scale = std::max({Inorm * norm(b.w1), Inorm * norm(b.w), norm(o - b.c) * norm(P),
                                         norm(E[i] - b.c) * norm(R[i])});
            const rvec residual = mul(b.I, b.w1 - b.w) - moment;
            if (dim == 2)
                ck.near_zero(residual[2], scale, who + ": I (w' - w) = (O - C) x s N n + (E - C) x R (z)");
            else
                ck.near_zero(residual, scale, who + ": I (w' - w) = (O - C) x s N n + (E - C) x R", 3);
        }
        if (has_pivot[i]) {
            const rvec vE = point_velocity(b, b.v1, b.w1, E[i]);
            const real scale = std::max(point_speed_scale(b, b.v1, b.w1, E[i]),
                                        point_speed_scale(bodies[i1], bodies[i1].v, bodies[i1].w, o) +
                                            point_speed_scale(bodies[i2], bodies[i2].v, bodies[i2].w, o));
            ck.near_zero(vE, scale, who + ": the pivot point is at rest after impact", dim);
        }
    }

    // Restitution at the contact point.
    {
        const rbody& A = bodies[i1];
        const rbody& B = bodies[i2];
        const real u = dot(point_velocity(B, B.v, B.w, o) - point_velocity(A, A.v, A.w, o), n);
        const real u1 = dot(point_velocity(B, B.v1, B.w1, o) - point_velocity(A, A.v1, A.w1, o), n);
        const real scale = point_speed_scale(A, A.v, A.w, o) + point_speed_scale(B, B.v, B.w, o) +
                           point_speed_scale(A, A.v1, A.w1, o) + point_speed_scale(B, B.v1, B.w1, o);
        if (u > tolerance * scale)
            ck.fail("solved a problem whose contact points do not approach ((v_B - v_A).n > 0)");
        if (!process_law) {
            ck.near_zero(u1 + e * u, scale, "restitution: (v'_B - v'_A).n = -e (v_B - v_A).n");
        } else { // Routh's process (poisson, energetic): the points part, within the cone, process ends at N
            if (u1 < -tolerance * scale)
                ck.fail("law " + std::string(law_name(p.contact().law_of_restitution)) +
                        ": the contact points still approach after impact");
            const real mu = ck.value(p.contact().friction(), "contact.friction");
            const real Pt = norm(P - N * n);
            if (Pt > mu * N + tolerance * (norm(P) + 1e-300))
                ck.fail("the tangential impulse lies outside the friction cone");
            const json& pr = a.value("process", json());
            if (!pr.is_array() || pr.empty() || !pr.back().is_object())
                ck.fail("law " + std::string(law_name(p.contact().law_of_restitution)) + " with friction: no process");
            else if (pr.back().value("phase", json()) != a.value("regime", json()))
                ck.fail("regime is not the last phase of the process");
            else
                ck.near_zero(ck.number(pr.back().value("normal_impulse_end", json()), "process") - N, std::abs(N),
                             "the last phase ends at the normal impulse");
        }
    }

    // Kinetic energy of the bodies of finite mass.
    {
        real before = 0, after = 0;
        for (const rbody& b : bodies)
            if (!b.infinite) {
                before += kinetic_energy(b, b.v, b.w);
                after += kinetic_energy(b, b.v1, b.w1);
            }
        const json& k = a.value("kinetic_energy", json::object());
        const real b0 = ck.number(k.value("before", json()), "answer kinetic_energy.before");
        const real a0 = ck.number(k.value("after", json()), "answer kinetic_energy.after");
        const real lost = ck.number(k.value("lost", json()), "answer kinetic_energy.lost");
        const real scale = std::max({before, after, std::abs(b0), std::abs(a0), std::abs(lost)});
        ck.near_zero(b0 - before, scale, "kinetic_energy.before = sum of 1/2 m v.v + 1/2 w.I w");
        ck.near_zero(a0 - after, scale, "kinetic_energy.after = sum of 1/2 m v'.v' + 1/2 w'.I w'");
        ck.near_zero(b0 - a0 - lost, scale, "kinetic_energy: before - after = lost");
        // Newton's law with friction may gain energy (Kane's paradox): then the answer says so.
        const bool gain = a.value("energy_gain", false);
        if (gain && (process_law || p.contact().friction().is_zero() || infinite_moves || lost >= 0))
            ck.fail("energy_gain: true on an answer that may not carry it (or loses energy)");
        if (!infinite_moves && !gain && lost < -tolerance * scale)
            ck.fail("kinetic_energy.lost < 0 with no moving body of infinite mass");
    }
    return ck.failures;
}

} // namespace impactgen::fuzz
