// The one header writer (writer.hpp): the text of a system's plan with sequential impacts
// (rule system_sets, system_code::sequential). The contacts act one at a time, as solve_system's
// chain has them: from the velocities before impact (the state), each pass computes every
// contact's normal speed, takes the first contact in list order that approaches (its speed below
// -tol times the speeds before impact: rounding of a contact that has just left at 0 is not an
// approach), applies that contact's single-contact impact in closed form (its own e; the joints
// and pivots acting with it) to the state and adds its impulses to the sums; the chain ends when
// no contact approaches, or returns no_solution after max_steps steps (NAME_max_steps, 64 as
// solve's limit, or the function's template argument).
#include "writer.hpp"

namespace impactgen::codegen::writer_detail
{

namespace
{

bool is_velocity(const code_output &of)
{
    return of.kind == output_value::velocity || of.kind == output_value::angular_velocity;
}

} // namespace

// The checks and the speeds before (stage A), the state and the sums, the speeds in the state,
// each contact's step in the state, the energy lost in the final state.
void writer::build_sequence()
{
    const system_code &sc = cp_.system;
    const system_sequence &sq = sc.sequence;
    a_.pool.set_input_names(input_ident_);
    system_input_checks();
    for (std::size_t r = 0; r < sc.speeds.size(); ++r) {
        sys_speed_.push_back(scope_.claim("u_row" + std::to_string(r)));
        a_.output(sys_speed_.back(), sc.speeds[r]);
    }
    seq_state_.assign(outs_.size(), "");
    seq_sum_.assign(outs_.size(), "");
    seq_before_.assign(outs_.size(), "");
    for (std::size_t j : sc.velocities) {
        sys_speed_.push_back(scope_.claim("before_" + outs_[j].field));
        seq_before_[j] = sys_speed_.back();
        a_.output(sys_speed_.back(), sc.unchanged[j]);
    }
    std::map<ex, std::string, ex_is_less> state_names = input_ident_;
    for (std::size_t j = 0; j + 1 < outs_.size(); ++j) {
        if (is_velocity(outs_[j])) {
            seq_state_[j] = scope_.claim("state_" + outs_[j].field);
            state_names[sq.state[j]] = seq_state_[j];
        } else {
            seq_sum_[j] = scope_.claim("sum_" + outs_[j].field);
        }
    }
    seq_speeds_.pool.set_input_names(state_names);
    for (std::size_t i = 0; i < sq.speeds.size(); ++i) {
        seq_speed_.push_back(scope_.claim("u_c" + std::to_string(i)));
        seq_speeds_.output(seq_speed_.back(), sq.speeds[i]);
    }
    seq_steps_.resize(sq.steps.size());
    for (std::size_t k = 0; k < sq.steps.size(); ++k) {
        const system_code_set &s = sq.steps[k];
        stage &st = seq_steps_[k];
        st.pool.set_input_names(state_names);
        const std::string pre = "t" + std::to_string(k) + "_";
        std::vector<std::string> vals, conds;
        for (std::size_t j = 0; j < s.values.size() && j + 1 < outs_.size(); ++j) {
            vals.push_back(scope_.claim(pre + outs_[j].field));
            st.output(vals.back(), s.values[j]);
        }
        for (std::size_t j = 0; j < s.conditions.size(); ++j) {
            if (s.conditions[j].identically_zero) {
                conds.push_back("0");
                continue;
            }
            conds.push_back(scope_.claim(pre + "cond" + std::to_string(j + 1)));
            st.output(conds.back(), s.conditions[j].value);
        }
        sys_vals_.push_back(vals);
        sys_conds_.push_back(conds);
    }
    for (std::size_t j = 0; j < outs_.size(); ++j)
        sys_sel_.push_back(scope_.claim("sel_" + outs_[j].field));
    for (const char *nm : {"tol", "speed_scale", "speeds", "next", "k", "n_steps", "last", "status_now"})
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
    emit_one(seq_speeds_, locals);
    for (stage &st : seq_steps_)
        emit_one(st, locals);
    emit_one(c_, result);
    u_.em = emit_cpp(u_.prog, u_.outs, {}, {}, scope_.names());
}

void writer::sequence_formulas()
{
    const system_sequence &sq = cp_.system.sequence;
    h_ << "// The law (impactgen's symbolic/system.hpp), sequential impacts: the contacts act one at a time,\n";
    h_ << "// as a chain of single-contact impacts of the whole system (joints and pivots included). From\n";
    h_ << "// the velocities before impact (the state), each pass computes every contact's normal speed u_k\n";
    h_ << "// (along n_k as given) and takes the first contact in list order that approaches, u_k < -tol\n";
    h_ << "// times the speeds before impact (the largest contact or body speed; tol = 2^-(digits/2), about\n";
    h_ << "// 1.5e-8 in double: a contact that has just left at speed 0 is not approaching through\n";
    h_ << "// rounding). That contact acts alone (every other contact open): M (v' - v) = A^T lambda with\n";
    h_ << "// its row and the joints' and pivots', u'_k = -e_k u_k; the state becomes the velocities after\n";
    h_ << "// the step and its impulses are added to the sums. The chain ends when no contact approaches\n";
    h_ << "// (none at the start: not_approaching); a chain longer than max_steps (the template argument,\n";
    h_ << "// by default " << o_.name << "_max_steps = 64, the limit of impactgen solve) returns no_solution\n";
    h_ << "// with out.steps = max_steps + 1. A chain whose approach speeds shrink below rounding (e = 0 in\n";
    h_ << "// a line of equal balls: without end in exact arithmetic) ends there.\n";
    h_ << "// Each contact's step (set k of " << o_.name << "_set_names) and its condition:\n";
    for (std::size_t k = 0; k < sq.steps.size(); ++k) {
        const system_code_set &s = sq.steps[k];
        h_ << "//   contact " << k << " " << names::comment_text(s.name)
           << (s.values.empty() ? ": no closed form (it cannot take an impulse): no_solution when it approaches\n"
                                : (s.conditions.empty() ? "\n" : ":\n"));
        for (std::size_t j = 0; j < s.conditions.size(); ++j)
            h_ << "//     " << sys_conds_[k][j] << (s.conditions[j].strict ? " > 0  (" : " >= 0  (")
               << names::comment_text(s.conditions[j].meaning) << ")\n";
    }
    h_ << "// This problem, step by step, as the code below computes it. Before the chain:\n";
    for (const auto &[lhs, rhs] : a_.em.assignments)
        h_ << wrap_comment(lhs, rhs);
    h_ << "// Each pass, the contacts' speeds in the state state_*:\n";
    for (const auto &[lhs, rhs] : seq_speeds_.em.assignments)
        h_ << wrap_comment(lhs, rhs);
    for (std::size_t k = 0; k < seq_steps_.size(); ++k) {
        if (sq.steps[k].values.empty())
            continue;
        h_ << "// Contact " << k << " acting alone (velocities after the step, its impulses):\n";
        for (const auto &[lhs, rhs] : seq_steps_[k].em.assignments)
            h_ << wrap_comment(lhs, rhs);
    }
    h_ << "// The energy lost for the final velocities sel_*:\n";
    for (const auto &[lhs, rhs] : c_.em.assignments)
        h_ << wrap_comment(lhs, rhs);
}

// The case of the pass's switch for contact k: its step, its condition, the state and the sums.
void writer::sequence_step(std::size_t k)
{
    const system_code_set &s = cp_.system.sequence.steps[k];
    h_ << "        case " << k << ": {\n";
    if (s.values.empty()) {
        h_ << "            return fail(friction_status::no_solution); // contact " << k << " cannot take an impulse\n";
        h_ << "        }\n";
        return;
    }
    h_ << indent(seq_steps_[k].em.code, "        ");
    std::vector<std::string> holds;
    for (std::size_t j = 0; j < s.conditions.size(); ++j) {
        if (s.conditions[j].identically_zero) {
            if (s.conditions[j].strict)
                holds.push_back("false");
            continue;
        }
        holds.push_back(sys_conds_[k][j] + (s.conditions[j].strict ? " > T(0)" : " >= T(0)"));
    }
    if (!holds.empty())
        h_ << "            if (!(" << join(holds, " && ") << "))\n"
           << "                return fail(friction_status::no_solution);\n";
    for (std::size_t j = 0; j + 1 < outs_.size(); ++j) {
        if (!seq_state_[j].empty())
            h_ << "            " << seq_state_[j] << " = " << sys_vals_[k][j] << ";\n";
        else
            h_ << "            " << seq_sum_[j] << " = " << seq_sum_[j] << " + " << sys_vals_[k][j] << ";\n";
    }
    h_ << "            break;\n        }\n";
}

void writer::sequence_function()
{
    const system_code &sc = cp_.system;
    const std::size_t nout = outs_.size(), nc = sc.sequence.steps.size();
    const auto &L = sys_local_;
    const std::string &tol = L.at("tol"), &vs = L.at("speed_scale"), &speeds = L.at("speeds"), &next = L.at("next"),
                      &k = L.at("k"), &n = L.at("n_steps"), &last = L.at("last"), &why = L.at("status_now");
    h_ << "/// The longest chain " << o_.name
       << " follows by default: 64 single-contact impacts, as impactgen solve.\n";
    h_ << "inline constexpr int " << o_.name << "_max_steps = 64;\n\n";
    h_ << "/// Post-impact state of the system for the inputs below, the contacts acting one at a time\n";
    h_ << "/// (sequential impacts: the chain described above); returns friction_status::ok with out.steps\n";
    h_ << "/// the number of single-contact impacts, out.set the last one's contact (" << o_.name
       << "_set_names) and each\n";
    h_ << "/// impulse summed over the chain, or why not (then out holds the state unchanged: velocities as\n";
    h_ << "/// before, impulses zero, set -1): not_approaching (no contact approaches), no_solution (a\n";
    h_ << "/// contact that cannot take an impulse approaches, or the chain is longer than max_steps: then\n";
    h_ << "/// out.steps = max_steps + 1). T: float, double or long double. with_energy_lost = false:\n";
    h_ << "/// out.energy_lost is left 0.\n";
    for (std::size_t i = 0; i < input_names_.size(); ++i)
        h_ << "///   " << input_names_[i] << ": " << names::comment_text(cp_.input_meaning[i]) << "\n";
    h_ << "template <typename T, bool with_energy_lost = true, int max_steps = " << o_.name
       << "_max_steps>\nIMPACTGEN_FUNC friction_status " << o_.name << "(" << params() << result()
       << "<T>& out) noexcept\n{\n";
    h_ << "    using std::sqrt;\n";
    fail_lambda("auto", "detail::friction_status_of", true);
    h_ << "    // Checks, the speeds before.\n";
    h_ << a_.em.code;
    h_ << "    const T " << tol << " = detail::" << o_.name << "_tolerance<T>();\n";
    h_ << "    const T " << vs << " = " << nested_abs_max(sys_speed_) << ";\n";
    h_ << "    // The state (velocities before the next step) and the impulses summed over the steps.\n";
    for (std::size_t j = 0; j + 1 < nout; ++j)
        h_ << "    T " << (seq_state_[j].empty() ? seq_sum_[j] + " = T(0)" : seq_state_[j] + " = " + seq_before_[j])
           << ";\n";
    h_ << "    int " << n << " = 0, " << last << " = -1;\n";
    h_ << "    for (;;) {\n";
    h_ << indent(seq_speeds_.em.code, "    ");
    h_ << "        const T " << speeds << "[" << nc << "] = {" << join(seq_speed_, ", ") << "};\n";
    h_ << "        int " << next << " = -1;\n";
    h_ << "        for (int " << k << " = 0; " << k << " < " << nc << " && " << next << " < 0; ++" << k << ")\n";
    h_ << "            if (" << speeds << "[" << k << "] < -" << tol << " * " << vs << ")\n";
    h_ << "                " << next << " = " << k << ";\n";
    h_ << "        if (" << next << " < 0)\n            break;\n";
    h_ << "        if (" << n << " == max_steps) {\n";
    h_ << "            const friction_status " << why << " = fail(friction_status::no_solution);\n";
    h_ << "            out.steps = max_steps + 1; // the chain goes on\n";
    h_ << "            return " << why << ";\n        }\n";
    h_ << "        ++" << n << ";\n        " << last << " = " << next << ";\n";
    h_ << "        switch (" << next << ") {\n";
    for (std::size_t c = 0; c < nc; ++c)
        sequence_step(c);
    h_ << "        default:\n            break;\n        }\n    }\n";
    h_ << "    if (" << n << " == 0)\n        return fail(impact_status::not_approaching);\n";
    for (std::size_t j = 0; j + 1 < nout; ++j)
        h_ << "    const T " << sys_sel_[j] << " = " << (seq_state_[j].empty() ? seq_sum_[j] : seq_state_[j]) << ";\n";
    h_ << c_.em.code;
    for (std::size_t j = 0; j + 1 < nout; ++j)
        h_ << "    out." << outs_[j].field << " = " << sys_sel_[j] << ";\n";
    h_ << "    out.set = " << last << ";\n    out.impulses_unique = " << (sc.redundant_joints ? "false" : "true")
       << ";\n    out.steps = " << n << ";\n";
    overflow_check();
    h_ << "    return friction_status::ok;\n}\n\n";
}

} // namespace impactgen::codegen::writer_detail
