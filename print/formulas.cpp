#include "formulas.hpp"

#include "answer.hpp"
#include "canonical.hpp"
#include "explain_system.hpp"
#include "expression.hpp"
#include "symbolic/contact_law.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/system_process.hpp"

#include <sstream>

namespace impactgen::print
{
using namespace GiNaC;

namespace
{

// One formula document, printed by a format-specific line writer.
struct formula_line {
    std::string name_text, name_tex; ///< as printed (text: symbol_text, with the symbol's role)
    ex value;
    std::string meaning;
};

// The unknowns with their values (unknown_values: unknown == value, in the derivation's
// order), but the normal impulse, which is already a step.
void add_unknowns(const derivation &d, const ex &unknown_values, std::vector<formula_line> &lines)
{
    for (std::size_t k = 0; k < d.unknowns.size(); ++k) {
        const unknown &u = d.unknowns[k];
        if (u.kind != unknown_kind::normal_impulse)
            lines.push_back({symbol_text(u.sym), symbol_latex(u.sym), unknown_values.op(k).rhs(), u.meaning});
    }
}

std::vector<formula_line> collect(const derivation &d, const solution &s)
{
    std::vector<formula_line> lines;
    for (const step &st : s.steps)
        lines.push_back({symbol_text(st.sym), symbol_latex(st.sym), st.value, st.meaning});
    add_unknowns(d, s.unknown_values, lines);
    return lines;
}

std::string header(const derivation &d)
{
    std::ostringstream os;
    os << d.prob.source << ": " << d.count_unknowns() << " unknowns, " << d.count_equations() << " equations";
    return os.str();
}

} // namespace

std::string formulas_text(const derivation &d, const solution &s)
{
    std::ostringstream os;
    os << header(d) << "\n";
    if (!d.frame_is_world || d.prob.contact().normal != vec3{0, 1, 0})
        os << "unit normal n = (" << canonical_text(d.n_hat[0]) << ", " << canonical_text(d.n_hat[1])
           << (d.prob.dimension == 3 ? ", " + canonical_text(d.n_hat[2]) : "") << ")\n";
    os << "\n";
    for (const formula_line &l : collect(d, s))
        os << l.name_text << " = " << canonical_text(l.value) << "\n    (" << l.meaning << ")\n";
    return os.str();
}

std::string formulas_latex(const derivation &d, const solution &s)
{
    std::ostringstream os;
    os << "% impactgen formulas -- " << header(d) << "\n";
    os << "\\begin{align*}\n";
    auto lines = collect(d, s);
    for (std::size_t k = 0; k < lines.size(); ++k)
        os << "  " << lines[k].name_tex << " &= " << canonical_latex(lines[k].value)
           << (k + 1 < lines.size() ? " \\\\" : "") << "\n";
    os << "\\end{align*}\n";
    return os.str();
}

// ---- friction ---------------------------------------------------------------

namespace
{

// The steps a case adds to the shared ones (every case starts with the same shared steps).
std::size_t shared_count(const friction_solution &f)
{
    if (f.cases.size() < 2)
        return 0;
    std::size_t n = 0;
    const auto &a = f.cases[0].sol.steps;
    const auto &b = f.cases[1].sol.steps;
    while (n < a.size() && n < b.size() && a[n].sym.is_equal(b[n].sym))
        ++n;
    return n;
}

std::string relation(const regime_condition &c)
{
    return c.strict ? " > 0" : " >= 0";
}

using case_line = formula_line;

std::vector<case_line> case_results(const derivation &d, const regime_case &c)
{
    std::vector<case_line> lines;
    const problem &p = d.prob;
    add_unknowns(d, c.sol.unknown_values, lines);
    if (p.dimension == 3)
        for (int a = 0; a < 3; ++a)
            if (!is_a<symbol>(c.tangential_impulse[a])) // a step already
                lines.push_back({"F_" + p.axes[a], "F_{" + p.axes[a] + "}", c.tangential_impulse[a],
                                 "tangential impulse on body 2, " + p.axes[a] + " component"});
    return lines;
}

} // namespace

// ---- restitution laws through the impact (poisson, energetic: Routh's process) -------

namespace
{

bool is_process(const derivation &d, const friction_solution &f)
{
    return law_traits_of(d.prob).process && follows_process(f.law);
}

std::string phases_text(const regime_case &c)
{
    std::string r;
    for (const process_phase &ph : c.process)
        r += (r.empty() ? "" : " -> ") + std::string(phase_name(ph.kind));
    return r;
}

std::string process_text(const derivation &d, const friction_solution &f)
{
    std::ostringstream os;
    const problem &p = d.prob;
    os << p.source << ": impact with Coulomb friction mu = " << canonical_text(f.mu) << ", restitution law "
       << law_name(f.law) << " (Routh's process), " << f.cases.size() << " phase sequence"
       << (f.cases.size() == 1 ? "" : "s") << "; exactly one holds\n";
    os << "unit normal n = (" << canonical_text(f.n_hat[0]) << ", " << canonical_text(f.n_hat[1])
       << "), tangent e_t = (" << canonical_text(f.e_t[0]) << ", " << canonical_text(f.e_t[1]) << ")\n\n";
    for (const step &st : f.shared.steps)
        os << symbol_text(st.sym) << " = " << canonical_text(st.value) << "\n    (" << st.meaning << ")\n";
    for (std::size_t ci = 0; ci < f.cases.size(); ++ci) {
        const regime_case &c = f.cases[ci];
        os << "\nSequence " << ci + 1 << ": " << phases_text(c) << "\n";
        for (const process_phase &ph : c.process)
            os << "  " << phase_name(ph.kind) << " ends at N = " << canonical_text(ph.normal_impulse_end) << "\n";
        os << "  N = " << canonical_text(c.sol.normal_impulse) << "\n  F = " << canonical_text(c.tangential_scalar)
           << "\n";
        for (const case_line &l : case_results(d, c))
            os << "  " << l.name_text << " = " << canonical_text(l.value) << "\n";
        if (!c.process_conditions.empty()) {
            os << "  holds when:\n";
            for (const process_condition &pc : c.process_conditions)
                os << "    " << pc.meaning << ":  " << canonical_text(pc.value) << (pc.strict ? " > 0" : " >= 0")
                   << "\n";
        }
    }
    os << "\nOther values (a slide whose normal velocity does not grow and whose slip never stops) wedge: "
          "no finite impulse ends the compression.\nWithout slip before impact (u_t = 0) the process starts "
          "sticking when mu K_tt >= |K_tn|, else sliding along the sign of K_tn.\n";
    return os.str();
}

std::string process_latex(const derivation &d, const friction_solution &f)
{
    std::ostringstream os;
    os << "% impactgen formulas -- " << d.prob.source << ": Coulomb friction, restitution law " << law_name(f.law)
       << " (Routh's process)\n\\begin{align*}\n";
    for (std::size_t k = 0; k < f.shared.steps.size(); ++k)
        os << "  " << symbol_latex(f.shared.steps[k].sym) << " &= " << canonical_latex(f.shared.steps[k].value)
           << (k + 1 < f.shared.steps.size() ? " \\\\" : "") << "\n";
    os << "\\end{align*}\n";
    for (const regime_case &c : f.cases) {
        os << "% phase sequence: " << phases_text(c) << "\n\\begin{align*}\n";
        os << "  N &= " << canonical_latex(c.sol.normal_impulse)
           << " \\\\\n  F &= " << canonical_latex(c.tangential_scalar);
        for (const process_condition &pc : c.process_conditions)
            os << " \\\\\n  " << canonical_latex(pc.value) << " &" << (pc.strict ? ">" : "\\geq") << " 0";
        os << "\n\\end{align*}\n";
    }
    return os.str();
}

nlohmann::ordered_json process_json(const derivation &d, const friction_solution &f)
{
    nlohmann::ordered_json out;
    out["friction"] = canonical_parser(f.mu);
    out["law"] = law_name(f.law);
    out["steps"] = nlohmann::ordered_json::array();
    for (const step &st : f.shared.steps)
        out["steps"].push_back(
            {{"name", st.sym.get_name()}, {"value", canonical_parser(st.value)}, {"meaning", st.meaning}});
    out["sequences"] = nlohmann::ordered_json::array();
    for (const regime_case &c : f.cases) {
        nlohmann::ordered_json r;
        r["process"] = nlohmann::ordered_json::array();
        for (const process_phase &ph : c.process)
            r["process"].push_back(
                {{"phase", phase_name(ph.kind)}, {"normal_impulse_end", canonical_parser(ph.normal_impulse_end)}});
        r["normal_impulse"] = canonical_parser(c.sol.normal_impulse);
        r["tangential_impulse"] = canonical_parser(c.tangential_scalar);
        r["conditions"] = nlohmann::ordered_json::array();
        for (const process_condition &pc : c.process_conditions)
            r["conditions"].push_back({{"expression", canonical_parser(pc.value)},
                                       {"relation", pc.strict ? ">" : ">="},
                                       {"meaning", pc.meaning}});
        out["sequences"].push_back(r);
    }
    (void)d;
    return out;
}

} // namespace

bool stick_can_hold(const derivation &d, const friction_solution &f)
{
    (void)d;
    // The stick impulse does not depend on mu: with numbers for the rest, its sign is known.
    const regime_case &st = f.cases.front();
    const ex N = tidy(st.sol.expand_steps(st.sol.normal_impulse));
    if (!is_constant(N))
        return true; // decided by the values: the condition N > 0 is printed with the threshold
    return decide(N) == decision::positive;
}

ex stick_threshold(const derivation &d, const friction_solution &f)
{
    const regime_case &st = f.cases.front();
    const ex Pn = st.sol.normal_impulse;
    if (d.prob.dimension == 2)
        return abs(tidy(st.sol.expand_steps(st.tangential_scalar / Pn)));
    return sqrt(dot(st.tangential_impulse, st.tangential_impulse)) / Pn;
}

std::string formulas_text(const derivation &d, const friction_solution &f)
{
    if (law_traits_of(d.prob).single_candidate) // a smooth contact: its one candidate
        return formulas_text(d, f.cases.front().sol);
    if (is_process(d, f))
        return process_text(d, f);
    std::ostringstream os;
    const problem &p = d.prob;
    os << p.source << ": impact with Coulomb friction mu = " << canonical_text(f.mu) << ", " << f.cases.size()
       << " candidate regimes; exactly one holds\n";
    auto vec_text = [&](const vec3 &v) {
        std::string r = "(";
        for (int a = 0; a < p.dimension; ++a)
            r += (a ? ", " : "") + canonical_text(v[a]);
        return r + ")";
    };
    os << "unit normal n = " << vec_text(f.n_hat) << ", tangent e_t = " << vec_text(f.e_t);
    if (p.dimension == 3)
        os << ", e_b = " << vec_text(f.e_b);
    os << "\n\n";
    const std::size_t shared = shared_count(f);
    const auto &first = f.cases.front().sol.steps;
    for (std::size_t k = 0; k < shared; ++k)
        os << symbol_text(first[k].sym) << " = " << canonical_text(first[k].value) << "\n    (" << first[k].meaning
           << ")\n";
    for (std::size_t ci = 0; ci < f.cases.size(); ++ci) {
        const regime_case &c = f.cases[ci];
        os << "\nRegime " << ci + 1 << ": " << c.name << "\n";
        for (std::size_t k = shared; k < c.sol.steps.size(); ++k)
            os << "  " << symbol_text(c.sol.steps[k].sym) << " = " << canonical_text(c.sol.steps[k].value)
               << "\n      (" << c.sol.steps[k].meaning << ")\n";
        if (c.needs_angle)
            os << "  the sliding direction d = c_d e_t + s_d e_b (c_d^2 + s_d^2 = 1) solves\n      0 = "
               << canonical_text(c.angle_equation)
               << "\n      (u'_t parallel to d: a trigonometric polynomial of degree 2 in the sliding angle)\n";
        for (const case_line &l : case_results(d, c))
            os << "  " << l.name_text << " = " << canonical_text(l.value) << "\n";
        os << "  holds when:\n";
        for (const regime_condition &rc : c.conditions)
            os << "    " << rc.meaning << ":  " << canonical_text(rc.value) << relation(rc) << "\n";
    }
    if (stick_can_hold(d, f))
        os << "\nThe stick impulse does not depend on mu, so sticking holds exactly when its N > 0 and\n  mu >= mu* = "
              "|F| / N = "
           << canonical_text(tidy(f.cases.front().sol.expand_steps(stick_threshold(d, f)))) << "\n";
    else
        os << "\nThe stick impulse pulls (N <= 0), and it does not depend on mu: no mu makes the contact stick.\n";
    return os.str();
}

std::string formulas_latex(const derivation &d, const friction_solution &f)
{
    if (law_traits_of(d.prob).single_candidate) // a smooth contact: its one candidate
        return formulas_latex(d, f.cases.front().sol);
    if (is_process(d, f))
        return process_latex(d, f);
    std::ostringstream os;
    const problem &p = d.prob;
    os << "% impactgen formulas -- " << p.source << ": impact with Coulomb friction\n";
    const std::size_t shared = shared_count(f);
    const auto &first = f.cases.front().sol.steps;
    os << "\\begin{align*}\n";
    for (std::size_t k = 0; k < shared; ++k)
        os << "  " << symbol_latex(first[k].sym) << " &= " << canonical_latex(first[k].value) << " \\\\\n";
    if (stick_can_hold(d, f))
        os << "  \\mu^{*} &= " << canonical_latex(tidy(f.cases.front().sol.expand_steps(stick_threshold(d, f))))
           << "\n";
    else
        os << "  N_{\\text{stick}} &\\leq 0 \\quad \\text{(no } \\mu \\text{ sticks)}\n";
    os << "\\end{align*}\n";
    for (const regime_case &c : f.cases) {
        os << "% regime: " << c.name << "\n\\begin{align*}\n";
        for (std::size_t k = shared; k < c.sol.steps.size(); ++k)
            os << "  " << symbol_latex(c.sol.steps[k].sym) << " &= " << canonical_latex(c.sol.steps[k].value)
               << " \\\\\n";
        if (c.needs_angle)
            os << "  0 &= " << canonical_latex(c.angle_equation) << " \\\\\n";
        for (const case_line &l : case_results(d, c))
            os << "  " << l.name_tex << " &= " << canonical_latex(l.value) << " \\\\\n";
        for (std::size_t k = 0; k < c.conditions.size(); ++k)
            os << "  " << canonical_latex(c.conditions[k].value) << " &" << (c.conditions[k].strict ? ">" : "\\geq")
               << " 0" << (k + 1 < c.conditions.size() ? " \\\\" : "") << "\n";
        os << "\\end{align*}\n";
    }
    return os.str();
}

nlohmann::ordered_json formulas_json(const derivation &d, const friction_solution &f)
{
    if (law_traits_of(d.prob).single_candidate) // a smooth contact: its one candidate, as solve --json writes it
        return answer_json(d, f.cases.front().sol, true);
    if (is_process(d, f))
        return process_json(d, f);
    const problem &p = d.prob;
    nlohmann::ordered_json out;
    out["friction"] = canonical_parser(f.mu);
    auto vec_json = [&](const vec3 &v) {
        nlohmann::ordered_json a = nlohmann::ordered_json::array();
        for (int k = 0; k < p.dimension; ++k)
            a.push_back(canonical_parser(v[k]));
        return a;
    };
    out["normal"] = vec_json(f.n_hat);
    out["regimes"] = nlohmann::ordered_json::array();
    for (const regime_case &c : f.cases) {
        nlohmann::ordered_json r;
        r["regime"] = regime_name(c.kind);
        r["case"] = c.name;
        r["steps"] = nlohmann::ordered_json::array();
        for (const step &st : c.sol.steps)
            r["steps"].push_back(
                {{"name", st.sym.get_name()}, {"value", canonical_parser(st.value)}, {"meaning", st.meaning}});
        if (c.needs_angle)
            r["angle_equation"] = {{"unknowns", {c.dir_c.get_name(), c.dir_s.get_name()}},
                                   {"direction", "d = c_d e_t + s_d e_b, c_d^2 + s_d^2 = 1"},
                                   {"e_t", vec_json(f.e_t)},
                                   {"e_b", vec_json(f.e_b)},
                                   {"equation", canonical_parser(c.angle_equation)}};
        nlohmann::ordered_json bodies = nlohmann::ordered_json::object();
        for (std::size_t i = 0; i < p.bodies.size(); ++i) {
            nlohmann::ordered_json b;
            b["velocity"] = vec_json(c.sol.after[i].velocity);
            if (p.dimension == 2) {
                b["angular_velocity"] = canonical_parser(c.sol.after[i].angular_velocity[2]);
            } else {
                nlohmann::ordered_json w = nlohmann::ordered_json::array();
                for (int k = 0; k < 3; ++k)
                    w.push_back(canonical_parser(c.sol.after[i].angular_velocity[k]));
                b["angular_velocity"] = w;
            }
            bodies[p.bodies[i].name] = b;
        }
        r["answer"] = {{"bodies", bodies},
                       {"normal_impulse", canonical_parser(c.sol.normal_impulse)},
                       {"tangential_impulse", vec_json(c.tangential_impulse)},
                       {"regime", regime_name(c.kind)}};
        nlohmann::ordered_json pivots = nlohmann::ordered_json::array();
        for (const vec3 &R : c.sol.pivot_impulses)
            pivots.push_back(vec_json(R));
        r["answer"]["pivot_impulses"] = pivots;
        r["conditions"] = nlohmann::ordered_json::array();
        for (const regime_condition &rc : c.conditions)
            r["conditions"].push_back({{"expression", canonical_parser(rc.value)},
                                       {"relation", c.needs_angle || rc.strict ? ">" : ">="},
                                       {"meaning", rc.meaning}});
        out["regimes"].push_back(r);
    }
    // null when the stick impulse pulls (N <= 0, decided for numbers): no mu sticks
    out["stick_threshold"] =
        stick_can_hold(d, f)
            ? nlohmann::ordered_json(canonical_parser(tidy(f.cases.front().sol.expand_steps(stick_threshold(d, f)))))
            : nlohmann::ordered_json(nullptr);
    return out;
}

} // namespace impactgen::print

namespace impactgen::print
{

namespace
{
std::string sys_expr(const ex &e, bool latex)
{
    const ex v = surd_form(tidy(e));
    return latex ? canonical_latex(v) : parser_syntax(v);
}

// The quantities a system candidate reports, each with its name.
std::vector<std::pair<std::string, ex>> system_values(const problem &p, const system_candidate &c)
{
    std::vector<std::pair<std::string, ex>> out;
    const char *ax[3] = {"x", "y", "z"};
    for (std::size_t b = 0; b < p.bodies.size(); ++b) {
        if (p.bodies[b].infinite_mass)
            continue;
        for (int k = 0; k < p.dimension; ++k)
            out.push_back({"v'_" + std::string(ax[k]) + "," + p.bodies[b].name, c.velocity[b][k]});
        if (p.bodies[b].particle)
            continue;
        if (p.dimension == 2)
            out.push_back({"w'_" + p.bodies[b].name, c.angular_velocity[b][2]});
        else
            for (int k = 0; k < 3; ++k)
                out.push_back({"w'_" + std::string(ax[k]) + "," + p.bodies[b].name, c.angular_velocity[b][k]});
    }
    for (std::size_t i = 0; i < p.contacts.size(); ++i) {
        out.push_back({"P_" + std::to_string(i), c.normal_impulse[i]});
        if (c.regimes[i] == contact_regime::stick || c.regimes[i] == contact_regime::slide)
            for (int k = 0; k < p.dimension; ++k)
                out.push_back({"P_t" + std::string(ax[k]) + "," + std::to_string(i), c.tangential_impulse[i][k]});
    }
    for (std::size_t j = 0; j < c.joint_impulses.size(); ++j)
        for (int k = 0; k < p.dimension; ++k)
            out.push_back({"J_" + std::string(ax[k]) + "," + std::to_string(j), c.joint_impulses[j][k]});
    for (std::size_t j = 0; j < c.pivot_impulses.size(); ++j)
        for (int k = 0; k < p.dimension; ++k)
            out.push_back({"R_" + std::string(ax[k]) + "," + std::to_string(j), c.pivot_impulses[j][k]});
    return out;
}
} // namespace

std::string system_formulas_text(const problem &p, bool latex)
{
    const std::vector<system_candidate> cs = system_candidates(p);
    std::ostringstream os;
    os << (latex ? "% " : "") << "System: " << detail::count_of(p.contacts.size(), "contact", "contacts") << ", "
       << detail::count_of(p.joints.size(), "joint", "joints") << ", "
       << detail::count_of(p.pivots.size(), "pivot", "pivots") << ". "
       << (system_follows_process(p)
               ? "Candidates of Routh's process at contact 0 (restitution by the " +
                     std::string(law_name(p.contacts[0].law_of_restitution)) +
                     " law, the joints eliminated): open, and one per phase sequence"
               : std::string("Candidates of the law 0 <= P_i _|_ u'_i + e_i u_i >= 0, one per set of regimes "
                             "(open, smooth, stick, slide)"))
       << "; a candidate is the answer where its conditions hold.\n";
    for (const system_candidate &c : cs) {
        os << "\n" << (latex ? "% " : "") << "Candidate " << c.name() << ":\n";
        for (const auto &v : system_values(p, c))
            os << (latex ? "" : "  ") << v.first << " = " << sys_expr(v.second, latex) << (latex ? " \\\\" : "")
               << "\n";
        os << (latex ? "% " : "  ") << "conditions:" << (c.conditions.empty() ? " none" : "") << "\n";
        for (const system_condition &k : c.conditions)
            os << (latex ? "% " : "    ") << k.meaning << ":  " << sys_expr(k.value, latex)
               << (k.strict ? " > 0" : " >= 0") << "\n";
    }
    return os.str();
}

nlohmann::ordered_json system_formulas_json(const problem &p)
{
    nlohmann::ordered_json out, list = nlohmann::ordered_json::array();
    for (const system_candidate &c : system_candidates(p)) {
        nlohmann::ordered_json j, answer = nlohmann::ordered_json::object(), conds = nlohmann::ordered_json::array();
        j["set"] = c.name();
        nlohmann::ordered_json regimes = nlohmann::ordered_json::array();
        for (contact_regime r : c.regimes)
            regimes.push_back(contact_regime_name(r));
        j["regimes"] = regimes;
        for (const auto &v : system_values(p, c))
            answer[v.first] = sys_expr(v.second, false);
        j["answer"] = answer;
        for (const system_condition &k : c.conditions)
            conds.push_back({{"value", sys_expr(k.value, false)}, {"strict", k.strict}, {"meaning", k.meaning}});
        j["conditions"] = conds;
        list.push_back(j);
    }
    out["candidates"] = list;
    return out;
}

namespace
{
// The name of a velocity after impact, as system_values writes it.
std::string output_name(const problem &p, const system_velocity_output &o)
{
    const char *ax[3] = {"x", "y", "z"};
    const std::string &b = p.bodies[o.body].name;
    if (!o.angular)
        return "v'_" + std::string(ax[o.component]) + "," + b;
    return p.dimension == 2 ? "w'_" + b : "w'_" + std::string(ax[o.component]) + "," + b;
}
} // namespace

std::string system_jacobian_text(const problem &p, const system_jacobian &j, bool latex)
{
    std::ostringstream os;
    const std::string c = latex ? "% " : "";
    os << "\n"
       << c << "Jacobian of the impact map per candidate set, d(velocity after impact)/d(input), each set's closed\n"
       << c << "form differentiated exactly (inputs:";
    for (const symbol &x : j.wrt)
        os << " " << x.get_name();
    os << ").\n"
       << c << "Where a set's conditions hold strictly the map is smooth; on a boundary between sets (a condition\n"
       << c << "= 0) its derivative is one-sided: each neighbouring set's own.\n";
    for (const system_set_jacobian &s : j.sets) {
        os << "\n" << c << "Set " << s.candidate.name() << ":\n";
        std::size_t zeros = 0;
        for (std::size_t o = 0; o < j.outputs.size(); ++o)
            for (std::size_t w = 0; w < j.wrt.size(); ++w) {
                if (s.entries[o][w].is_zero()) {
                    ++zeros;
                    continue;
                }
                os << (latex ? "" : "  ") << "d " << output_name(p, j.outputs[o]) << " / d " << j.wrt[w].get_name()
                   << " = " << sys_expr(s.entries[o][w], latex) << (latex ? " \\\\" : "") << "\n";
            }
        os << c << (latex ? "" : "  ") << "(" << zeros << " of the " << j.outputs.size() * j.wrt.size()
           << " entries are 0 and not listed)\n";
    }
    return os.str();
}

nlohmann::ordered_json system_jacobian_json(const problem &p, const system_jacobian &j)
{
    nlohmann::ordered_json out, wrt = nlohmann::ordered_json::array(), sets = nlohmann::ordered_json::array();
    for (const symbol &x : j.wrt)
        wrt.push_back(x.get_name());
    for (const system_set_jacobian &s : j.sets) {
        nlohmann::ordered_json js, conds = nlohmann::ordered_json::array(), m = nlohmann::ordered_json::object();
        js["set"] = s.candidate.name();
        for (const system_condition &k : s.candidate.conditions)
            conds.push_back({{"value", sys_expr(k.value, false)}, {"strict", k.strict}, {"meaning", k.meaning}});
        js["conditions"] = conds;
        for (std::size_t o = 0; o < j.outputs.size(); ++o) {
            nlohmann::ordered_json row = nlohmann::ordered_json::object();
            for (std::size_t w = 0; w < j.wrt.size(); ++w)
                row[j.wrt[w].get_name()] = sys_expr(s.entries[o][w], false);
            m[output_name(p, j.outputs[o])] = row;
        }
        js["matrix"] = m;
        sets.push_back(js);
    }
    out["wrt"] = wrt;
    out["sets"] = sets;
    out["boundary"] = "on a boundary between sets (a condition = 0) the derivative is one-sided";
    return out;
}

} // namespace impactgen::print
