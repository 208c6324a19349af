#include "answer.hpp"

#include "explain_system.hpp"
#include "expression.hpp"
#include "names/escape.hpp"

#include "symbolic/contact_law.hpp"
#include "symbolic/decide.hpp"

#include <sstream>
#include <stdexcept>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{

struct valuer {
    const solution &s;
    bool symbolic;
    nlohmann::ordered_json operator()(const ex &e, const std::string &key) const
    {
        ex v = surd_form(tidy(s.expand_steps(e)));
        if (symbolic)
            return parser_syntax(v);
        double x = 0;
        try {
            x = to_double(v);
        } catch (const no_decimal &err) {
            throw input_error("answer: " + key + ": " + err.what());
        } catch (const std::invalid_argument &) {
            throw input_error("answer: " + key +
                              ": the exact value is out of the range of double (the inputs' scales overflow it)");
        }
        // A non-zero value below the smallest subnormal double (4.9e-324) would be written as 0:
        // refused as the overflow is (a subnormal is written, with the digits it has).
        if (x == 0 && !v.is_zero()) {
            const decision sign = decide(v);
            if (sign == decision::positive || sign == decision::negative)
                throw input_error(
                    "answer: " + key +
                    ": the exact value is not 0 but below the range of double (it would be written as 0: the "
                    "inputs' scales underflow it)");
        }
        return x;
    }
};

// A moving body of infinite mass (a bat, a moving wall) can do work on the others.
bool moving_infinite_mass(const problem &p)
{
    for (const body &b : p.bodies)
        if (b.infinite_mass && !b.at_rest())
            return true;
    return false;
}

// Version 3, restitution laws: "process" and its last phase as "regime" (poisson, energetic), or
// "energy_gain": true on a Newton answer with friction whose kinetic energy rises.
void add_process_keys(const derivation &d, const regime_case &c, const valuer &val, bool symbolic,
                      nlohmann::ordered_json &out)
{
    if (!c.process.empty()) {
        nlohmann::ordered_json phases = nlohmann::ordered_json::array();
        for (const process_phase &ph : c.process)
            phases.push_back(
                {{"phase", phase_name(ph.kind)}, {"normal_impulse_end", val(ph.normal_impulse_end, "process")}});
        out["process"] = phases;
        out["regime"] = phase_name(c.process.back().kind);
        return;
    }
    if (symbolic || follows_process(d.prob.contact().law_of_restitution) || moving_infinite_mass(d.prob))
        return;
    const ex gain = tidy(c.sol.expand_steps(c.sol.energy_after - c.sol.energy_before));
    if (is_constant(gain) && decide(gain) == decision::positive)
        out["energy_gain"] = true;
}

} // namespace

nlohmann::ordered_json answer_json(const derivation &d, const solution &s, bool symbolic)
{
    const problem &p = d.prob;
    valuer val{s, symbolic};
    nlohmann::ordered_json out, bodies = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        nlohmann::ordered_json b, v = nlohmann::ordered_json::array();
        for (int c = 0; c < p.dimension; ++c)
            v.push_back(val(s.after[i].velocity[c], "bodies." + names::display_text(p.bodies[i].name) + ".velocity"));
        b["velocity"] = v;
        if (p.dimension == 2) {
            b["angular_velocity"] = val(s.after[i].angular_velocity[2],
                                        "bodies." + names::display_text(p.bodies[i].name) + ".angular_velocity");
        } else {
            nlohmann::ordered_json w = nlohmann::ordered_json::array();
            for (int c = 0; c < 3; ++c)
                w.push_back(val(s.after[i].angular_velocity[c],
                                "bodies." + names::display_text(p.bodies[i].name) + ".angular_velocity"));
            b["angular_velocity"] = w;
        }
        bodies[p.bodies[i].name] = b;
    }
    out["bodies"] = bodies;
    out["normal_impulse"] = val(s.normal_impulse, "normal_impulse");
    nlohmann::ordered_json pivots = nlohmann::ordered_json::array();
    for (const vec3 &R : s.pivot_impulses) {
        nlohmann::ordered_json r = nlohmann::ordered_json::array();
        for (int c = 0; c < p.dimension; ++c)
            r.push_back(val(R[c], "pivot_impulses"));
        pivots.push_back(r);
    }
    out["pivot_impulses"] = pivots;
    out["kinetic_energy"] = {{"before", val(s.energy_before, "kinetic_energy.before")},
                             {"after", val(s.energy_after, "kinetic_energy.after")},
                             {"lost", val(s.energy_lost, "kinetic_energy.lost")}};
    // Format version 2: a smooth contact has no tangential impulse.
    nlohmann::ordered_json zero = nlohmann::ordered_json::array();
    for (int c = 0; c < p.dimension; ++c)
        zero.push_back(symbolic ? nlohmann::ordered_json("0") : nlohmann::ordered_json(0.0));
    out["tangential_impulse"] = zero;
    out["regime"] = "smooth";
    return out;
}

nlohmann::ordered_json answer_json(const derivation &d, const regime_case &c, bool symbolic)
{
    if (!law_traits_of(d.prob).tangential_impulse) // the one candidate of a smooth contact: its closed form as it is
        return answer_json(d, c.sol, symbolic);
    nlohmann::ordered_json out = answer_json(d, c.sol, symbolic);
    valuer val{c.sol, symbolic};
    nlohmann::ordered_json t = nlohmann::ordered_json::array();
    for (int k = 0; k < d.prob.dimension; ++k)
        t.push_back(val(c.tangential_impulse[k], "tangential_impulse"));
    out["tangential_impulse"] = t;
    out["regime"] = regime_name(c.kind);
    add_process_keys(d, c, val, symbolic, out);
    return out;
}

std::string answer_text(const derivation &d, const solution &s)
{
    return answer_text(d, s, nullptr);
}

std::string answer_text(const derivation &d, const regime_case &c)
{
    return answer_text(d, c.sol, law_traits_of(d.prob).tangential_impulse ? &c : nullptr);
}

std::string answer_text(const derivation &d, const solution &s, const regime_case *friction)
{
    const problem &p = d.prob;
    std::ostringstream os;
    auto show = [&](const ex &e) {
        ex v = surd_form(tidy(s.expand_steps(e)));
        if (is_a<numeric>(v) && !ex_to<numeric>(v).is_rational()) // a float: a root found numerically
            return decimal(v);
        std::string exact = parser_syntax(v);
        try {
            std::string dec = decimal(v);
            return exact == dec ? exact : exact + " = " + dec;
        } catch (const no_decimal &err) {
            return exact + " (" + err.what() + ")";
        } catch (const std::invalid_argument &) {
            return exact + " (beyond the range of double)";
        }
    };
    auto show_vec = [&](const vec3 &v, int n) {
        std::string r = "(";
        for (int c = 0; c < n; ++c)
            r += (c ? ", " : "") + show(v[c]);
        return r + ")";
    };
    os << "Impact of " << p.bodies[p.contact().body1].name << " (body 1) on " << p.bodies[p.contact().body2].name
       << " (body 2), e = " << parser_syntax(p.restitution);
    if (friction)
        os << ", mu = " << parser_syntax(p.contact().friction());
    os << "\n\n";
    if (friction && !friction->process.empty()) { // Routh's process (poisson, energetic)
        os << "Restitution law: " << law_name(p.contact().law_of_restitution) << "\nProcess:";
        for (const process_phase &ph : friction->process)
            os << " " << phase_name(ph.kind) << " to N = " << show(ph.normal_impulse_end) << ";";
        os << "\nRegime: " << phase_name(friction->process.back().kind) << "\n\n";
    } else if (friction)
        os << "Regime: " << regime_name(friction->kind)
           << (friction->name == regime_name(friction->kind) ? std::string() : " (" + friction->name + ")") << "\n\n";
    os << "After impact:\n";
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        os << "  " << p.bodies[i].name << ":\n";
        os << "    velocity          " << show_vec(s.after[i].velocity, p.dimension) << "\n";
        if (p.dimension == 2)
            os << "    angular velocity  " << show(s.after[i].angular_velocity[2]) << "\n";
        else
            os << "    angular velocity  " << show_vec(s.after[i].angular_velocity, 3) << "\n";
    }
    os << "  normal impulse      " << show(s.normal_impulse) << "\n";
    if (friction)
        os << "  tangential impulse  " << show_vec(friction->tangential_impulse, p.dimension) << "\n";
    for (std::size_t k = 0; k < s.pivot_impulses.size(); ++k)
        os << "  pivot impulse on " << p.bodies[p.pivots[k].body].name << "  "
           << show_vec(s.pivot_impulses[k], p.dimension) << "\n";
    os << "Kinetic energy:\n";
    os << "  before  " << show(s.energy_before) << "\n";
    os << "  after   " << show(s.energy_after) << "\n";
    os << "  lost    " << show(s.energy_lost) << "\n";
    if (friction && friction->process.empty() && !follows_process(p.contact().law_of_restitution) &&
        !moving_infinite_mass(p)) {
        const ex gain = tidy(s.expand_steps(s.energy_after - s.energy_before));
        if (is_constant(gain) && decide(gain) == decision::positive)
            os << "Newton's law with friction creates energy here (Kane's paradox); the laws \"poisson\" and "
                  "\"energetic\" follow the impact through its duration.\n";
    }
    return os.str();
}

} // namespace impactgen::print

namespace impactgen::print
{

namespace
{
nlohmann::ordered_json vector_json(const valuer &val, const vec3 &v, int n, const std::string &key)
{
    nlohmann::ordered_json r = nlohmann::ordered_json::array();
    for (int c = 0; c < n; ++c)
        r.push_back(val(v[c], key));
    return r;
}
} // namespace

nlohmann::ordered_json system_answer_json(const problem &p, const system_answer &a)
{
    const solution none;
    const valuer val{none, false};
    const int n = p.dimension;
    const system_candidate &r = a.result;
    nlohmann::ordered_json out, bodies = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const std::string key = "bodies." + names::display_text(p.bodies[i].name);
        nlohmann::ordered_json b;
        b["velocity"] = vector_json(val, r.velocity[i], n, key + ".velocity");
        b["angular_velocity"] = n == 2 ? val(r.angular_velocity[i][2], key + ".angular_velocity")
                                       : vector_json(val, r.angular_velocity[i], 3, key + ".angular_velocity");
        bodies[p.bodies[i].name] = b;
    }
    out["bodies"] = bodies;
    nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        const std::string key = "contacts[" + std::to_string(i) + "]";
        contacts.push_back(
            {{"normal_impulse", val(r.normal_impulse[i], key + ".normal_impulse")},
             {"tangential_impulse", vector_json(val, r.tangential_impulse[i], n, key + ".tangential_impulse")},
             {"regime", contact_regime_name(r.regimes[i])}});
        if (i == 0 && !r.process.empty()) { // Routh's process: its phases, the regime the last one
            nlohmann::ordered_json phases = nlohmann::ordered_json::array();
            for (const process_phase &ph : r.process)
                phases.push_back({{"phase", phase_name(ph.kind)},
                                  {"normal_impulse_end", val(ph.normal_impulse_end, key + ".process")}});
            contacts.back()["process"] = phases;
            contacts.back()["regime"] = phase_name(r.process.back().kind);
        }
    }
    out["contacts"] = contacts;
    nlohmann::ordered_json joints = nlohmann::ordered_json::array(), pivots = nlohmann::ordered_json::array();
    for (const vec3 &J : r.joint_impulses)
        joints.push_back(vector_json(val, J, n, "joint_impulses"));
    for (const vec3 &R : r.pivot_impulses)
        pivots.push_back(vector_json(val, R, n, "pivot_impulses"));
    out["joint_impulses"] = joints;
    out["pivot_impulses"] = pivots;
    out["kinetic_energy"] = {{"before", val(a.energy_before, "kinetic_energy.before")},
                             {"after", val(a.energy_after, "kinetic_energy.after")},
                             {"lost", val(a.energy_before - a.energy_after, "kinetic_energy.lost")}};
    out["impulses_unique"] = a.impulses_unique;
    if (a.sequential)
        out["sequence"] = a.sequence;
    if (a.energy_gain)
        out["energy_gain"] = true;
    return out;
}

std::string system_answer_text(const problem &p, const system_answer &a)
{
    std::ostringstream os;
    auto show = [](const ex &e) {
        ex v = surd_form(tidy(e));
        std::string exact = parser_syntax(v);
        try {
            std::string dec = decimal(v);
            return exact == dec ? exact : exact + " = " + dec;
        } catch (const std::exception &) {
            return exact;
        }
    };
    auto show_vec = [&](const vec3 &v, int n) {
        std::string r = "(";
        for (int c = 0; c < n; ++c)
            r += (c ? ", " : "") + show(v[c]);
        return r + ")";
    };
    const system_candidate &r = a.result;
    const int n = p.dimension;
    using detail::body_label;
    using detail::count_of;
    os << "System of " << count_of(p.bodies.size(), "body", "bodies") << ", "
       << count_of(p.contacts.size(), "contact", "contacts") << ", " << count_of(p.joints.size(), "joint", "joints")
       << ", " << count_of(p.pivots.size(), "pivot", "pivots") << "; impacts "
       << (a.sequential ? "sequential" : "simultaneous") << "\n\n";
    if (a.sequential) {
        os << "Sequence of contacts:";
        for (std::size_t k : a.sequence)
            os << " " << k;
        os << "\n\n";
    }
    os << "After impact:\n";
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        os << "  " << body_label(p.bodies[i].name) << ":\n";
        os << "    velocity          " << show_vec(r.velocity[i], n) << "\n";
        os << "    angular velocity  " << (n == 2 ? show(r.angular_velocity[i][2]) : show_vec(r.angular_velocity[i], 3))
           << "\n";
    }
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        os << "  contacts[" << i << "]  "
           << (i == 0 && !r.process.empty() ? phase_name(r.process.back().kind) : contact_regime_name(r.regimes[i]))
           << ", normal impulse " << show(r.normal_impulse[i]) << ", tangential impulse "
           << show_vec(r.tangential_impulse[i], n) << "\n";
        if (i == 0 && !r.process.empty()) {
            os << "    process:";
            for (const process_phase &ph : r.process)
                os << " " << phase_name(ph.kind) << " until N = " << show(ph.normal_impulse_end) << ";";
            os << "\n";
        }
    }
    for (std::size_t j = 0; j < r.joint_impulses.size(); ++j)
        os << "  joint impulse " << j << " on " << body_label(p.bodies[p.joints[j].body2].name) << "  "
           << show_vec(r.joint_impulses[j], n) << "\n";
    for (std::size_t k = 0; k < r.pivot_impulses.size(); ++k)
        os << "  pivot impulse on " << body_label(p.bodies[p.pivots[k].body].name) << "  "
           << show_vec(r.pivot_impulses[k], n) << "\n";
    if (!a.impulses_unique)
        os << "  (the impulses are not unique: these are one valid choice; the velocities are unique)\n";
    os << "Kinetic energy:\n";
    os << "  before  " << show(a.energy_before) << "\n";
    os << "  after   " << show(a.energy_after) << "\n";
    os << "  lost    " << show(a.energy_before - a.energy_after) << (a.energy_gain ? "  (energy gained)" : "") << "\n";
    return os.str();
}

} // namespace impactgen::print
