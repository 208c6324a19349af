// The one header writer (writer.hpp): the text of a system's plan (rule system_sets). One
// straight-line program computes every candidate set's outputs and conditions (CSE across the
// sets: they share the Delassus matrix and the speeds before); the selection then takes the
// first set whose conditions hold within rounding, in the order solve_system tries them, and
// compares it with every other holding set: different velocities are ambiguous, different
// impulses make impulses_unique false. The energy lost is computed from the selected
// velocities (a second program).
#include "writer.hpp"

namespace impactgen::codegen::writer_detail
{

std::string nested_abs_max(const std::vector<std::string> &terms)
{
    if (terms.empty())
        return "T(0)";
    std::string r = "detail::abs_of(" + terms[0] + ")";
    for (std::size_t i = 1; i < terms.size(); ++i)
        r = "detail::max_of(" + r + ", detail::abs_of(" + terms[i] + "))";
    return r;
}

// The checks of the inputs (stage A): e in [0, 1], masses and inertia > 0; the mu's names.
void writer::system_input_checks()
{
    const system_code &sc = cp_.system;
    for (const auto &[value, kind] : sc.checks) {
        if (kind == "invalid_friction") {
            if (is_a<numeric>(value))
                continue;
            const std::string nm =
                is_a<symbol>(value) && input_ident_.count(value) ? input_ident_.at(value) : scope_.claim("mu_value");
            if (!input_ident_.count(value))
                a_.output(nm, value);
            sys_mu_.push_back(nm);
            continue;
        }
        const check::kind_t k = kind == "invalid_restitution" ? check::unit_interval : check::positive;
        const std::string what = kind == "invalid_restitution" ? "0 <= e <= 1"
                                 : kind == "invalid_mass"      ? "mass > 0, finite"
                                                               : "moment of inertia > 0, finite";
        add_check(a_, value, k, kind, what);
    }
}

// Names of the sets' locals, the speeds, the selection's locals; the programs.
void writer::build_system()
{
    const system_code &sc = cp_.system;
    a_.pool.set_input_names(input_ident_);
    system_input_checks();
    for (std::size_t r = 0; r < sc.speeds.size(); ++r) {
        sys_speed_.push_back(scope_.claim("u_row" + std::to_string(r)));
        a_.output(sys_speed_.back(), sc.speeds[r]);
    }
    for (std::size_t i = 0; i < sc.unit_mass.size(); ++i) {
        sys_unit_mass_.push_back(scope_.claim("unit_mass_c" + std::to_string(i)));
        a_.output(sys_unit_mass_.back(), sc.unit_mass[i]);
    }
    // The velocities before impact: the scale of a contact speed's rounding (near 0 too).
    for (std::size_t j : sc.velocities) {
        sys_speed_.push_back(scope_.claim("before_" + outs_[j].field));
        a_.output(sys_speed_.back(), sc.unchanged[j]);
    }
    for (std::size_t k = 0; k < sc.sets.size(); ++k) {
        const system_code_set &s = sc.sets[k];
        const std::string pre = "s" + std::to_string(k) + "_";
        std::vector<std::string> vals, conds;
        for (std::size_t j = 0; j + 1 < outs_.size(); ++j) {
            vals.push_back(scope_.claim(pre + outs_[j].field));
            a_.output(vals.back(), s.values[j]);
        }
        for (std::size_t j = 0; j < s.conditions.size(); ++j) {
            if (s.conditions[j].identically_zero) { // decided when generating: nothing to compute
                conds.push_back("0");
                continue;
            }
            conds.push_back(scope_.claim(pre + "cond" + std::to_string(j + 1)));
            a_.output(conds.back(), s.conditions[j].value);
        }
        sys_vals_.push_back(vals);
        sys_conds_.push_back(conds);
    }
    for (std::size_t j = 0; j < outs_.size(); ++j)
        sys_sel_.push_back(scope_.claim("sel_" + outs_[j].field));
    for (const char *nm :
         {"tol", "speed_scale", "sets",  "holds", "clear",  "sel",  "unique", "differ", "k",        "j",
          "x1",  "x2",          "scale", "best",  "margin", "tiny", "jac",    "status", "boundary", "near_sets"})
        sys_local_[nm] = scope_.claim(nm);
    c_.pool.set_input_names([&] {
        std::map<ex, std::string, ex_is_less> m = input_ident_;
        for (std::size_t j = 0; j < outs_.size(); ++j)
            m[sc.sel[j]] = sys_sel_[j];
        return m;
    }());
    c_.output(outs_.back().field, sc.energy_lost);
    u_.pool.set_input_names(input_ident_);
    for (std::size_t j = 0; j < outs_.size(); ++j)
        u_.output(outs_[j].field, sc.unchanged[j]);
    emit_options locals, result;
    locals.outputs = output_placement::local;
    result.energy_output = static_cast<int>(outs_.size() - 1);
    emit_one(a_, locals);
    emit_one(c_, result);
    u_.em = emit_cpp(u_.prog, u_.outs, {}, {}, scope_.names());
}

void writer::system_banner()
{
    h_ << "// Closed forms of the impact of a system (" << q_.bodies.size() << " bodies, " << q_.contacts.size()
       << " contact" << (q_.contacts.size() == 1 ? "" : "s") << ", " << q_.joints.size() << " joint"
       << (q_.joints.size() == 1 ? "" : "s") << "), specialised; "
       << (sequential() ? "the contacts acting one at\n// a time (sequential impacts), each step's contact and its "
                          "impact chosen as the law's chain chooses\n// them. Plain C++17, no dependency, no "
                          "allocation.\n"
                        : "the set of\n// acting contacts and their regimes selected by the derived inequalities. "
                          "Plain C++17, no\n// dependency, no allocation.\n");
    if (sequential())
        h_ << "// Arithmetic of the straight-line parts: " << counts_text(a_.em.formula) << " (before the chain); "
           << counts_text(seq_speeds_.em.formula) << " (each pass's speeds);\n";
    else
        h_ << "// Arithmetic of the straight-line parts: " << counts_text(a_.em.formula) << " (every candidate set);\n";
    h_ << "//   " << counts_text(c_.em.formula) << " (energy lost).\n";
    h_ << "#pragma once\n\n#include <cmath>\n#include <limits>\n\n";
}

void writer::system_formulas()
{
    const system_code &sc = cp_.system;
    h_ << "// The law (impactgen's symbolic/system.hpp): M (v' - v) = A^T lambda with every joint, pivot and\n";
    h_ << "// contact row; the joints and pivots eliminated (Schur complement) leave the Delassus matrix W\n";
    h_ << "// of the contact rows, u' = u + W lambda_C, and per contact i: 0 <= P_i _|_ u'_i + e_i u_i >= 0\n";
    h_ << "// with its friction (Coulomb, or no slip for \"inf\"). Each candidate below is one set of contact\n";
    h_ << "// regimes in closed form with the conditions under which it obeys the law. The answer is the\n";
    h_ << "// first set (in this order, the closed form's) whose conditions hold as computed; where none\n";
    h_ << "// does (inputs on a boundary between sets, within rounding) the set nearest to holding, if its\n";
    h_ << "// least condition is >= -tol times its scale (the largest contact or body speed before impact\n";
    h_ << "// for a velocity, the set's largest contact impulse for an impulse; tol = 2^-(digits/2), about 1.5e-8\n";
    h_ << "// in double); else no_solution. Another set that holds clearly (every condition >= tol times\n";
    h_ << "// its scale) with different velocities makes the call ambiguous, with different impulses makes\n";
    h_ << "// impulses_unique false. A condition that is 0 for every input (the speed of a contact at rest,\n";
    h_ << "// a corner's slip that another corner's sticking fixes at 0) is decided exactly, as the closed\n";
    h_ << "// form decides it: it holds, and its set can hold clearly.\n";
    h_ << "// The candidate sets and their conditions:\n";
    for (std::size_t k = 0; k < sc.sets.size(); ++k) {
        h_ << "//   set " << k << " " << names::comment_text(sc.sets[k].name)
           << (sc.sets[k].conditions.empty() ? "" : ":") << "\n";
        for (std::size_t j = 0; j < sc.sets[k].conditions.size(); ++j) {
            const system_code_set::condition &c = sc.sets[k].conditions[j];
            h_ << "//     " << sys_conds_[k][j] << (c.strict ? " > 0  (" : " >= 0  (") << names::comment_text(c.meaning)
               << ")" << (c.identically_zero ? (c.strict ? ", never holds" : ", holds for every input") : "") << "\n";
        }
    }
    h_ << "// This problem, step by step, as the code below computes it:\n";
    for (const auto &[lhs, rhs] : a_.em.assignments)
        h_ << wrap_comment(lhs, rhs);
    h_ << "// The energy lost for the selected velocities sel_*:\n";
    for (const auto &[lhs, rhs] : c_.em.assignments)
        h_ << wrap_comment(lhs, rhs);
}

// The tolerance of the conditions, 2^-(digits/2) of T, exact for any scalar.
void writer::system_tolerance()
{
    h_ << "namespace detail {\n";
    h_ << "/// The rounding within which " << o_.name << " counts a condition as holding: 2^-(digits/2) of T\n";
    h_ << "/// (1.5e-8 in double, 2.4e-4 in float), relative to the condition's scale.\n";
    h_ << "template <typename T> IMPACTGEN_FUNC T " << o_.name << "_tolerance() noexcept\n{\n";
    h_ << "    T r(1); // 2^-(digits/2): sqrt of the machine epsilon, without a host-only call in device code\n"
          "    for (T e = detail::machine_epsilon<T>(); e < T(1); e = e * T(4))\n        r = r / T(2);\n";
    h_ << "    return r;\n}\n} // namespace detail\n\n";
}

// The scale of condition j of set k: the speeds before impact for a velocity; for an impulse the
// set's largest contact impulse, or its contact's speed-to-impulse 1 / W_nn times the speeds
// before, the larger (an impulse near 0 is measured against what rounding makes of it).
std::string writer::system_scale(std::size_t k, std::size_t j) const
{
    const system_code_set::condition &c = cp_.system.sets[k].conditions[j];
    const std::string &vs = sys_local_.at("speed_scale");
    if (c.velocity)
        return vs;
    return "detail::max_of(s" + std::to_string(k) + "_scale, " + vs + " * " + sys_unit_mass_.at(c.contact) + ")";
}

// Whether set k holds as computed (h: every condition >= 0) and clearly (g: every condition >=
// tol times its scale); a rough contact that sticks with no normal impulse carries no
// tangential one. Its scale: the set's largest contact impulse.
std::string writer::system_holds(std::size_t k) const
{
    const system_code &sc = cp_.system;
    const system_code_set &s = sc.sets[k];
    const std::string &tol = sys_local_.at("tol");
    std::vector<std::string> imp;
    for (std::size_t j : sc.impulses)
        imp.push_back(sys_vals_[k][j]);
    const std::string is = "s" + std::to_string(k) + "_scale";
    std::vector<std::string> holds, clear;
    for (std::size_t j = 0; j < s.conditions.size(); ++j) {
        const system_code_set::condition &c = s.conditions[j];
        if (c.identically_zero) { // decided exactly, as solve decides it: 0 >= 0 holds, 0 > 0 fails
            if (c.strict) {
                holds.push_back("false");
                clear.push_back("false");
            }
            continue;
        }
        holds.push_back(sys_conds_[k][j] + (c.strict ? " > T(0)" : " >= T(0)"));
        clear.push_back(sys_conds_[k][j] + " >= " + tol + " * " + system_scale(k, j));
    }
    for (const auto &[n, ts] : s.rough_sticks)
        for (std::size_t t : ts) {
            const std::string c = "(" + sys_vals_[k][n] + " > " + tol + " * " + is + " || detail::abs_of(" +
                                  sys_vals_[k][t] + ") <= " + tol + " * " + is + ")";
            holds.push_back(c);
            clear.push_back(c);
        }
    const std::string kt = std::to_string(k);
    bool scaled = !s.rough_sticks.empty();
    for (const auto &c : s.conditions)
        scaled = scaled || (!c.velocity && !c.identically_zero);
    std::string r = scaled ? "    const T " + is + " = " + nested_abs_max(imp) + ";\n" : std::string();
    r += "    const bool h" + kt + " = " + (holds.empty() ? "true" : join(holds, " && ")) + ";\n";
    r += "    const bool g" + kt + " = " + (clear.empty() ? "true" : join(clear, " && ")) + ";\n";
    if (cp_.jacobian.on) {
        std::vector<std::string> near;
        for (std::size_t j = 0; j < s.conditions.size(); ++j)
            if (!s.conditions[j].identically_zero)
                near.push_back(sys_conds_[k][j] + " >= -" + tol + " * " + system_scale(k, j));
            else if (s.conditions[j].strict)
                near.push_back("false");
        r += "    const bool n" + kt + " = " + (near.empty() ? "true" : join(near, " && ")) + ";\n";
    }
    return r;
}

// Where no set holds as computed (inputs on a boundary between sets, within rounding): the set
// nearest to holding -- its least condition relative to its scale the largest -- if that is
// >= -tol, the first of equals.
std::string writer::system_nearest() const
{
    const system_code &sc = cp_.system;
    const std::string &tol = sys_local_.at("tol"), &sel = sys_local_.at("sel"), &best = sys_local_.at("best"),
                      &m = sys_local_.at("margin"), &tiny = sys_local_.at("tiny");
    std::string r = "    if (" + sel + " < 0) {\n";
    r += "        // No set holds as computed: the one nearest to holding, within rounding.\n";
    r += "        const T " + tiny + " = detail::smallest_normal<T>();\n";
    r += "        T " + best + " = -" + tol + ";\n";
    for (std::size_t k = 0; k < sc.sets.size(); ++k) {
        const system_code_set &s = sc.sets[k];
        std::vector<std::string> terms;
        bool never = false;
        for (std::size_t j = 0; j < s.conditions.size(); ++j) {
            never = never || (s.conditions[j].identically_zero && s.conditions[j].strict);
            if (!s.conditions[j].identically_zero)
                terms.push_back(sys_conds_[k][j] + " / detail::max_of(" + system_scale(k, j) + ", " + tiny + ")");
        }
        if (terms.empty() || never)
            continue;
        r += "        {\n            const T " + m + " = detail::min_of(" + join(terms, ", ") + ");\n";
        r += "            if (" + m + " > " + best + ") {\n                " + best + " = " + m +
             ";\n                " + sel + " = " + std::to_string(k) + ";\n            }\n        }\n";
    }
    r += "    }\n";
    return r;
}

// The selection: the first set that holds as computed (else the nearest, within rounding); every
// other set that holds clearly is compared with it.
void writer::system_select()
{
    const system_code &sc = cp_.system;
    const std::size_t nout = outs_.size(), nsets = sc.sets.size(), nv = sc.velocities.size();
    const std::string &tol = sys_local_.at("tol"), &vs = sys_local_.at("speed_scale"), &sets = sys_local_.at("sets"),
                      &holds = sys_local_.at("holds"), &clear = sys_local_.at("clear"), &sel = sys_local_.at("sel"),
                      &unique = sys_local_.at("unique"), &differ = sys_local_.at("differ"), &k = sys_local_.at("k"),
                      &j = sys_local_.at("j"), &x1 = sys_local_.at("x1"), &x2 = sys_local_.at("x2"),
                      &scale = sys_local_.at("scale");
    h_ << "    const T " << tol << " = detail::" << o_.name << "_tolerance<T>();\n";
    h_ << "    const T " << vs << " = " << nested_abs_max(sys_speed_) << ";\n";
    for (std::size_t i = 0; i < nsets; ++i)
        h_ << system_holds(i);
    for (const auto &[arr, flag] : {std::pair{holds, "h"}, std::pair{clear, "g"}}) {
        h_ << "    const bool " << arr << "[" << nsets << "] = {";
        for (std::size_t i = 0; i < nsets; ++i)
            h_ << (i ? ", " : "") << flag << i;
        h_ << "};\n";
    }
    h_ << "    const T " << sets << "[" << nsets << "][" << nout - 1 << "] = {\n";
    for (std::size_t i = 0; i < nsets; ++i)
        h_ << "        {" << join(sys_vals_[i], ", ") << "},\n";
    h_ << "    };\n";
    h_ << "    int " << sel << " = -1;\n";
    h_ << "    for (int " << k << " = 0; " << k << " < " << nsets << " && " << sel << " < 0; ++" << k << ")\n";
    h_ << "        if (" << holds << "[" << k << "])\n            " << sel << " = " << k << ";\n";
    const std::string &boundary = sys_local_.at("boundary");
    if (cp_.jacobian.on)
        h_ << "    bool " << boundary << " = " << sel << " < 0;\n";
    h_ << system_nearest();
    h_ << "    if (" << sel << " < 0)\n        return fail(friction_status::no_solution);\n";
    h_ << "    auto " << differ << " = [&](T " << x1 << ", T " << x2 << ", T " << scale << ") noexcept {\n";
    h_ << "        return !(detail::abs_of(" << x1 << " - " << x2 << ") <= " << tol << " * (" << scale
       << " + detail::abs_of(" << x1 << ") + detail::abs_of(" << x2 << ")));\n    };\n";
    h_ << "    bool " << unique << " = " << (sc.redundant_joints ? "false" : "true") << ";\n";
    if (cp_.jacobian.on) {
        h_ << "    const bool " << sys_local_.at("near_sets") << "[" << nsets << "] = {";
        for (std::size_t i = 0; i < nsets; ++i)
            h_ << (i ? ", " : "") << "n" << i;
        h_ << "};\n";
        h_ << "    for (int " << k << " = 0; " << k << " < " << nsets << "; ++" << k << ")\n";
        h_ << "        " << boundary << " = " << boundary << " || (" << k << " != " << sel << " && "
           << sys_local_.at("near_sets") << "[" << k << "]);\n";
    }
    h_ << "    for (int " << k << " = 0; " << k << " < " << nsets << "; ++" << k << ") {\n";
    h_ << "        if (" << k << " == " << sel << " || !" << clear << "[" << k << "])\n            continue;\n";
    const std::string at = sets + "[" + k + "][" + j + "], " + sets + "[" + sel + "][" + j + "]";
    if (nv > 0) {
        h_ << "        for (int " << j << " = 0; " << j << " < " << nv << "; ++" << j << ")\n";
        h_ << "            if (" << differ << "(" << at << ", " << vs << "))\n";
        h_ << "                return fail(friction_status::ambiguous);\n";
    }
    h_ << "        for (int " << j << " = " << nv << "; " << j << " < " << nout - 1 << "; ++" << j << ")\n";
    h_ << "            if (" << differ << "(" << at << ", T(0)))\n";
    h_ << "                " << unique << " = false;\n";
    h_ << "    }\n";
}

void writer::system_function()
{
    const std::size_t nout = outs_.size();
    const std::string &sets = sys_local_.at("sets"), &sel = sys_local_.at("sel"), &unique = sys_local_.at("unique");
    h_ << "/// Post-impact state of the system for the inputs below; returns friction_status::ok with\n";
    h_ << "/// out.set the candidate set that holds (" << o_.name << "_set_names) and out.impulses_unique, or\n";
    h_ << "/// why not (then out holds the state unchanged: velocities as before, impulses zero, set -1).\n";
    h_ << "/// T: float, double or long double. with_energy_lost = false: out.energy_lost is left 0.\n";
    for (std::size_t i = 0; i < input_names_.size(); ++i)
        h_ << "///   " << input_names_[i] << ": " << names::comment_text(cp_.input_meaning[i]) << "\n";
    h_ << "template <typename T, bool with_energy_lost = true>\nIMPACTGEN_FUNC friction_status " << o_.name << "("
       << params() << result() << "<T>& out) noexcept\n{\n";
    h_ << "    using std::sqrt;\n";
    fail_lambda("auto", "detail::friction_status_of", true);
    h_ << "    // Checks, the speeds before, every candidate set's outputs and conditions.\n";
    h_ << a_.em.code;
    for (const std::string &mu : sys_mu_)
        h_ << "    if (!(" << mu << " >= T(0) && detail::finite<T>(" << mu
           << "))) // mu >= 0, finite\n        return fail(friction_status::invalid_friction);\n";
    system_select();
    for (std::size_t j = 0; j + 1 < nout; ++j)
        h_ << "    const T " << sys_sel_[j] << " = " << sets << "[" << sel << "][" << j << "];\n";
    h_ << c_.em.code;
    for (std::size_t j = 0; j + 1 < nout; ++j)
        h_ << "    out." << outs_[j].field << " = " << sys_sel_[j] << ";\n";
    h_ << "    out.set = " << sel << ";\n    out.impulses_unique = " << unique << ";\n";
    if (cp_.jacobian.on)
        h_ << "    out.boundary = " << sys_local_.at("boundary") << ";\n";
    overflow_check();
    h_ << "    return friction_status::ok;\n}\n\n";
}

} // namespace impactgen::codegen::writer_detail
