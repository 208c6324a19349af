// The one header writer (writer.hpp), selection rule none: one straight-line program (the
// closed form's steps, the outputs, the checks; with --jacobian the derivative steps) in
// three forms: checked (a branch per check), fast (every check folded into one flag: latency)
// and the batch loop (reciprocals share divisions, no branch: it vectorises).
#include "writer.hpp"

namespace impactgen::codegen::writer_detail
{

namespace
{
const char *const tparams = "template <typename T, bool with_energy_lost = true>\n";

// The latency of an operation in cycles of a current x86 core (an estimate).
int latency(op::kind_t k)
{
    if (k == op::add || k == op::sub || k == op::neg)
        return 3;
    if (k == op::mul)
        return 4;
    if (k == op::div)
        return 14;
    if (k == op::cos_ || k == op::sin_)
        return 40;                  // a library call
    return k == op::sqrt_ ? 20 : 0; // inputs and constants are ready at once
}
} // namespace

// Canonical trees of the steps and outputs, then the straight-line program.
// Canonical trees of the steps and outputs, then the straight-line program.
void writer::lower_program()
{
    const solution &s = pl_.sol;
    for (std::size_t i = 0; i < s.steps.size(); ++i)
        main_.bind_step(s.steps[i], step_names_[i]);
    for (const code_output &ov : outs_) {
        main_.output(ov.field, ov.value);
        outs_local_.push_back({local_of_.at(ov.field), main_.outs.back().second});
    }
    if (pl_.has_jacobian) {
        for (std::size_t i = 0; i < pl_.jac.steps.size(); ++i)
            main_.bind_step(pl_.jac.steps[i], jac_step_names_[i]);
        for (std::size_t o = 0; o < outs_.size(); ++o)
            for (std::size_t j = 0; j < wrt_names_.size(); ++j)
                jac_outs_.push_back({jac_local_[o][j], main_.lower(pl_.jac.entries[o][j], jac_local_[o][j])});
    }
    lst inverses; // the engine convention: a mass m is 1/inv_m
    for (const auto &[old, inv] : pl_.inverse_of)
        inverses.append(old == 1 / inv);
    for (std::size_t k = 0; k < outs_.size(); ++k)
        unchanged_outs_.push_back({outs_[k].field, main_.lower(pl_.unchanged[k].subs(inverses), "unchanged")});
}

void writer::emit_forms()
{
    const std::vector<std::string> taken = scope_.names();
    // energy_lost: the fast and batch forms leave it 0 under with_energy_lost = false.
    int energy = -1;
    for (std::size_t k = 0; k < outs_.size(); ++k)
        if (outs_[k].kind == output_value::energy_lost)
            energy = static_cast<int>(k);
    // The energy output is written `with_energy_lost ? v : T(0)` by the emitter (emit_options).
    emit_options result;
    result.energy_output = energy;
    emit_options fast = branchless_form(false, energy), batch = branchless_form(true, energy);
    fast.energy_output = batch.energy_output = energy;
    em_ = emit_cpp(main_.prog, main_.outs, main_.checks, main_.names, taken, result);
    fast_ = emit_cpp(main_.prog, outs_local_, main_.checks, main_.names, taken, fast);
    batch_ = emit_cpp(main_.prog, outs_local_, main_.checks, main_.names, taken, batch);
    unchanged_ = emit_cpp(main_.prog, unchanged_outs_, {}, {}, taken);
    unchecked_ = emit_cpp(main_.prog, main_.outs, state_checks(main_.checks), main_.names, taken, result);
    // Inputs the outputs do not depend on still count for the finiteness check.
    std::set<std::string> reached;
    for (std::size_t i = 0; i < main_.prog.size(); ++i)
        if (main_.prog.at(static_cast<int>(i)).kind == op::input)
            reached.insert(main_.prog.at(static_cast<int>(i)).name);
    for (const auto &[field, id] : main_.outs)
        if (needs_check(id))
            sum_terms_.push_back("out." + field);
    std::vector<std::string> unused_inputs;
    for (const std::string &nm : input_names_)
        if (!reached.count(nm)) {
            sum_terms_.push_back(nm);
            unused_inputs.push_back(nm);
        }
    const std::vector<int> ready = ready_times();
    std::map<std::string, int> id_of_name;
    for (const auto &[id, nm] : main_.names)
        id_of_name[nm] = id;
    const std::vector<bool> implied = implied_outputs(energy);
    // The terms of the finiteness check in the branchless forms (local output values).
    auto finite_terms = [&](const emitted &form, bool energy_optional) {
        std::vector<sum_term> t;
        auto has = [&](const std::string &x) {
            return std::any_of(t.begin(), t.end(), [&](const sum_term &y) { return y.text == x; });
        };
        for (std::size_t k = 0; k < outs_.size(); ++k)
            if (needs_check(main_.outs[k].second) && !implied[k])
                t.push_back({local_of_.at(main_.outs[k].first), ready[static_cast<std::size_t>(main_.outs[k].second)],
                             energy_optional && static_cast<int>(k) == energy});
        for (const std::string &nm : unused_inputs)
            t.push_back({nm, 0, false});
        for (const code_term &x : form.finite_terms)
            if (!has(x.text))
                t.push_back({x.text,
                             id_of_name.count(x.text) ? ready[static_cast<std::size_t>(id_of_name.at(x.text))] : 0,
                             false, x.precedence});
        return t;
    };
    fast_terms_ = finite_terms(fast_, true);
    batch_terms_ = finite_terms(batch_, true);
    if (pl_.has_jacobian) {
        std::vector<std::pair<std::string, int>> all = outs_local_;
        all.insert(all.end(), jac_outs_.begin(), jac_outs_.end());
        jac_ = emit_cpp(main_.prog, all, main_.checks, main_.names, taken, branchless_form(false, -1));
        jac_terms_ = finite_terms(jac_, false);
        for (const auto &[local, id] : jac_outs_)
            if (needs_check(id))
                jac_terms_.push_back({local, ready[static_cast<std::size_t>(id)], false});
    }
}

// Every output but small exact constants (0, 1/2): a folded constant can be
// beyond the range of float, or of double.
bool writer::needs_check(int id) const
{
    const op &o = main_.prog.at(id);
    const numeric small(16777216); // 2^24: exact in float
    return o.kind != op::constant || !o.value.is_rational() || abs(o.value.numer()) > small || o.value.denom() > small;
}

// When each value is ready: a latency estimate from the inputs (cycles of a
// current x86 core), to add the terms of the finiteness sum in that order.
std::vector<int> writer::ready_times() const
{
    std::vector<int> ready(main_.prog.size(), 0);
    for (std::size_t i = 0; i < main_.prog.size(); ++i) {
        const op &o = main_.prog.at(static_cast<int>(i));
        const int cost = latency(o.kind);
        int before = 0;
        for (int c : {o.a, o.b})
            if (c >= 0)
                before = std::max(before, ready[static_cast<std::size_t>(c)]);
        ready[i] = before + cost;
    }
    return ready;
}

// An output is left out of the sum when the finiteness of another one implies it
// (an operand of +, -, *, negation, sqrt or the numerator of / is finite when the
// result is: N in v' = v - N/m, u in N = -(1 + e) u / k); energy_lost implies
// nothing (a form may leave it 0). Of outputs with the same value, the first stays.
std::vector<bool> writer::implied_outputs(int energy) const
{
    std::vector<bool> implied(main_.outs.size(), false);
    for (std::size_t j = 0; j < main_.outs.size(); ++j) {
        if (static_cast<int>(j) == energy)
            continue;
        std::vector<bool> seen(main_.prog.size(), false);
        std::vector<int> stack;
        auto operands = [&](int id) {
            const op &o = main_.prog.at(id);
            if (o.a >= 0)
                stack.push_back(o.a);
            if (o.b >= 0 && o.kind != op::div)
                stack.push_back(o.b);
        };
        operands(main_.outs[j].second);
        while (!stack.empty()) {
            const int id = stack.back();
            stack.pop_back();
            if (seen[static_cast<std::size_t>(id)])
                continue;
            seen[static_cast<std::size_t>(id)] = true;
            operands(id);
        }
        for (std::size_t k = 0; k < main_.outs.size(); ++k)
            if (k != j && (seen[static_cast<std::size_t>(main_.outs[k].second)] ||
                           (main_.outs[k].second == main_.outs[j].second && k > j)))
                implied[k] = true;
    }
    return implied;
}

void writer::straight_banner()
{
    h_ << "// Closed form of the smooth impact, specialised; plain C++17, no dependency, no allocation.\n";
    h_ << "// Arithmetic per call: " << counts_text(em_.formula) << " (closed form);\n";
    h_ << "//   validity checks: " << counts_text(em_.checks) << " + "
       << (sum_terms_.empty() ? 0 : sum_terms_.size() - 1) << " add (finiteness of the result), and comparisons;\n";
    h_ << "//   fast path (inputs that pass every check): " << counts_text(fast_.formula) << " + "
       << (fast_terms_.empty() ? 0 : fast_terms_.size() - 1) << " add, " << flag_counts(fast_, fast_terms_).first
       << " fma, " << mins(fast_) << " min (checks), " << flag_counts(fast_, fast_terms_).second << " tests;\n";
    h_ << "//   batch loop: " << counts_text(batch_.formula) << " + "
       << (batch_terms_.empty() ? 0 : batch_terms_.size() - 1) << " add, " << flag_counts(batch_, batch_terms_).first
       << " fma, " << mins(batch_) << " min (checks) per impact, no branch.\n";
    h_ << "#pragma once\n\n";
    if (em_.uses_sqrt || em_.uses_trig)
        h_ << "#include <cmath>\n";
    h_ << "#include <limits>\n\n"; // the runtime's smallest_normal and machine_epsilon
}

void writer::straight_formulas()
{
    h_ << position_text(pl_.prob);
    h_ << "// Formulas (impactgen's closed form; n the unit normal from body 1 into body 2,\n";
    h_ << "// s_1 = -1, s_2 = +1; r_i the lever arm above):\n";
    h_ << "//   w_i  = 1/m_i + (r_i x n) . g_i,  g_i = I_i^{-1} (r_i x n)  (free rigid body; 1/m_i for a "
          "particle;\n";
    h_ << "//          pinned: (r_i x n) . g_i with I_E = I_C + m (|d|^2 1 - d d^T), d = r_EC = C - E)\n";
    h_ << "//   u    = (v_B - v_A) . n,  v_A = v_C1 + w_1 x r_{C1 O}          (u < 0: the contact points "
          "approach)\n";
    h_ << "//   k    = w_1 + w_2,  N = -(1 + e) u / k                          (impulse per unit normal)\n";
    h_ << "//   v'_i = v_i + s_i N n / m_i (pinned: w' x r_EC),  w'_i = w_i + s_i N g_i\n";
    h_ << "//   T_lost = -sum_i (s_i N a_i + N^2 w_i / 2),  a_i = v_{contact point of i} . n\n";
    if (o_.inverse_inertia && pl_.prob.dimension == 2)
        h_ << "// Input convention: inverse moments of inertia inv_I = 1/I (as physics engines store them).\n";
    else if (o_.inverse_inertia)
        h_ << "// Input convention: inverse inertia tensors inv_I (as physics engines store them), so g_i = "
              "inv_I_i (r_i x n).\n";
    if (o_.inverse_mass)
        h_ << "// Input convention: inverse masses inv_m = 1/m.\n";
    h_ << "// This problem, step by step, as the code below computes it:\n";
    for (const auto &[lhs, rhs] : em_.assignments)
        h_ << wrap_comment(lhs, rhs);
}

// The checked version (in namespace detail, after the unchanged state): each check right
// after the value it tests, with its own status.
void writer::checked_function()
{
    h_ << "/// " << o_.name << " with each check right after the value it tests: the status of the\n";
    h_ << "/// inputs that fail the fast path of " << o_.name << " (out then holds the state unchanged).\n";
    h_ << tparams << "IMPACTGEN_COLD IMPACTGEN_FUNC impact_status " << checked() << "(" << params() << result()
       << "<T>& out) noexcept\n{\n";
    h_ << math_usings(em_);
    fail_lambda("impact_status", "", true);
    h_ << "    (void)fail; // a fully numeric problem may have no check left\n";
    h_ << em_.code;
    if (!sum_terms_.empty()) {
        h_ << "    const T check_sum = " << balanced_sum(sum_terms_) << ";\n";
        h_ << "    if (!detail::finite(check_sum) && !detail::all_finite(" << join(sum_terms_, ", ") << "))\n";
        h_ << "        return fail(impact_status::overflow);\n";
    }
    h_ << "    return impact_status::ok;\n}\n} // namespace detail\n\n";
}

// The fast path in namespace detail: every check folded into a few tests, then slow()
// for the inputs that fail one. Each entry point passes its own slow path: the function
// with the inputs as values calls the checked version with them; the array and struct
// forms pass one that reads the inputs from memory out of line (straight_slow_paths), so
// that the hot path need not keep all of them alive until the flag (g++ spilled them).
void writer::fast_function()
{
    h_ << "namespace detail {\n";
    h_ << "/// The fast path of " << o_.name << ": every check folded into a few tests (signs through\n";
    h_ << "/// a min, the finiteness of every value through sums times 0 added to it); the inputs that\n";
    h_ << "/// fail one of them return slow() (the checked version, which says which check failed).\n";
    h_ << "template <typename T, bool with_energy_lost, typename Slow>\n";
    h_ << "IMPACTGEN_HOT IMPACTGEN_FUNC impact_status " << o_.name << "_fast(" << params() << result()
       << "<T>& out, Slow slow) noexcept\n{\n";
    h_ << math_usings(em_);
    h_ << fast_.code;
    h_ << ok_flag("    ", fast_, fast_terms_, true);
    h_ << "    if (!ok) // some check failed (or a value is not finite): find which\n";
    h_ << "        return slow();\n";
    for (const code_output &ov : outs_)
        h_ << "    out." << ov.field << " = " << local_of_.at(ov.field) << ";\n";
    h_ << "    return impact_status::ok;\n}\n\n";
    straight_slow_paths();
    h_ << "} // namespace detail\n\n";
    h_ << "/// Post-impact state for the inputs below; returns impact_status::ok, or why not\n";
    h_ << "/// (then out holds the state unchanged: velocities as before, impulses zero).\n";
    h_ << "/// T: float, double, long double or alike (an autodiff scalar).\n";
    h_ << "/// The checks do not branch one by one: they are folded into a few tests (detail::" << o_.name
       << "_fast),\n";
    h_ << "/// and only inputs that fail one of them take the slow path (detail::" << checked() << ") that\n";
    h_ << "/// says which check failed. with_energy_lost = false: out.energy_lost is left 0,\n";
    h_ << "/// neither computed nor checked (the rest is the same).\n";
    for (std::size_t i = 0; i < input_names_.size(); ++i)
        h_ << "///   " << input_names_[i] << ": " << names::comment_text(cp_.input_meaning[i]) << "\n";
    h_ << tparams << "IMPACTGEN_HOT IMPACTGEN_FUNC impact_status " << o_.name << "(" << params() << result()
       << "<T>& out) noexcept\n{\n";
    // The inputs captured by value (see fail_lambda: by reference g++ keeps them in memory).
    h_ << "    return detail::" << o_.name << "_fast<T, with_energy_lost>(" << args()
       << "out, [=, &out]() noexcept { return detail::" << checked() << "<T, with_energy_lost>(" << args()
       << "out); });\n}\n\n";
}

// The slow paths of the array and struct forms: the checked version with the inputs read
// from memory, out of line (cold).
void writer::straight_slow_paths()
{
    for (bool by_name : {false, true}) {
        h_ << "/// The slow path of " << o_.name << " with the inputs " << (by_name ? "by name" : "in an array")
           << ", out of line.\n";
        h_ << "template <typename T, bool with_energy_lost>\nIMPACTGEN_COLD IMPACTGEN_FUNC impact_status " << checked()
           << "_in(" << (by_name ? "const " + input_struct() + "<T>& in, " : std::string("const T* in, ")) << result()
           << "<T>& out) noexcept\n{\n";
        if (input_names_.empty())
            h_ << "    (void)in;\n";
        h_ << "    return " << checked() << "<T, with_energy_lost>(";
        for (std::size_t i = 0; i < input_names_.size(); ++i)
            h_ << (by_name ? "in." + input_names_[i] : "in[" + std::to_string(i) + "]") << ", ";
        h_ << "out);\n}\n\n";
    }
}

// The unchecked variant: the checked form's arithmetic with only the checks of the state.
void writer::unchecked_function()
{
    h_ << "/// " << o_.name << " without the per-call validation, for inputs the caller validated once\n";
    h_ << "/// (contract: every input finite, 0 <= e <= 1, masses and moments of inertia > 0 (their\n";
    h_ << "/// inverses >= 0), inertia tensors positive definite (inverse tensors semidefinite), a\n";
    h_ << "/// normal neither zero, denormal nor too long: what " << o_.name << " would not return\n";
    h_ << "/// invalid_* or non_finite_input for). On such inputs the result is bit for bit that of\n";
    h_ << "/// " << o_.name << " whenever it returns ok; not_approaching and singular are still returned\n";
    h_ << "/// (they depend on the state), but no finiteness check guards the result (no overflow).\n";
    h_ << tparams << "IMPACTGEN_HOT IMPACTGEN_FUNC impact_status " << o_.name << "_unchecked(" << params() << result()
       << "<T>& out) noexcept\n{\n";
    h_ << math_usings(unchecked_);
    fail_lambda("impact_status", "", false);
    h_ << "    (void)fail; // a fully numeric problem may have no check left\n";
    h_ << unchecked_.code;
    h_ << "    return impact_status::ok;\n}\n\n";
}

// Values and the dense Jacobian in one straight-line program (CSE across both).
void writer::jacobian_function()
{
    if (!pl_.has_jacobian)
        return;
    const std::string jr = o_.name + "_jacobian_result";
    const std::size_t no = outs_.size(), nw = wrt_names_.size();
    h_ << "inline constexpr int " << o_.name << "_wrt_count = " << nw << ";\n";
    h_ << "/// The inputs the Jacobian differentiates by, in the order of its columns.\n";
    h_ << "inline constexpr const char* " << o_.name << "_wrt_names[] = {";
    for (const std::string &w : wrt_names_)
        h_ << names::cpp_string_literal(w) << ", ";
    h_ << "nullptr};\n\n";
    h_ << "/// The post-impact state and its derivatives: d[i][j] = d(output i)/d(input j), outputs\n";
    h_ << "/// in the order of " << o_.name << "_output_names, inputs in that of " << o_.name << "_wrt_names.\n";
    h_ << "template <typename T> struct " << jr << " {\n";
    h_ << "    " << result() << "<T> value;\n";
    h_ << "    T d[" << no << "][" << nw << "];\n";
    h_ << "};\n\n";
    h_ << "/// " << o_.name << " and the exact derivatives of its outputs (velocities, impulses,\n";
    h_ << "/// approach velocity, energy lost) by the inputs in " << o_.name << "_wrt_names: the\n";
    h_ << "/// Jacobian of the impact map, derived symbolically (chain rule through the closed\n";
    h_ << "/// form's steps) and sharing its arithmetic with the values. On a status other than ok\n";
    h_ << "/// out.value holds the state unchanged and every derivative is zero (the map is not\n";
    h_ << "/// differentiable there, or not defined); the status is overflow also when the values\n";
    h_ << "/// are finite and a derivative is not.\n";
    h_ << "template <typename T>\nIMPACTGEN_FUNC impact_status " << o_.name << "_jacobian(" << params() << jr
       << "<T>& out) noexcept\n{\n";
    h_ << math_usings(jac_);
    h_ << jac_.code;
    h_ << ok_flag("    ", jac_, jac_terms_, true);
    h_ << "    if (!ok) {\n";
    h_ << "        out = " << jr << "<T>{}; // every derivative zero\n";
    h_ << "        const impact_status why = detail::" << checked() << "<T, true>(" << args() << "out.value);\n";
    h_ << "        if (why != impact_status::ok)\n";
    h_ << "            return why;\n";
    h_ << "        // The values are finite, a derivative is not (1/m^2 overflows where 1/m does not).\n";
    h_ << "        detail::" << unchanged() << "(" << args() << "out.value);\n";
    h_ << "        return impact_status::overflow;\n";
    h_ << "    }\n";
    for (const code_output &ov : outs_)
        h_ << "    out.value." << ov.field << " = " << local_of_.at(ov.field) << ";\n";
    for (std::size_t o = 0; o < no; ++o)
        for (std::size_t j = 0; j < nw; ++j)
            h_ << "    out.d[" << o << "][" << j << "] = " << jac_local_[o][j] << ";\n";
    h_ << "    return impact_status::ok;\n}\n\n";
    h_ << "/// The same with the inputs in an array, in the order of " << o_.name << "_input_names.\n";
    h_ << "template <typename T>\nIMPACTGEN_FUNC impact_status " << o_.name << "_jacobian(const T* in, " << jr
       << "<T>& out) noexcept\n{\n";
    if (input_names_.empty())
        h_ << "    (void)in;\n";
    h_ << "    return " << o_.name << "_jacobian<T>(";
    for (std::size_t i = 0; i < input_names_.size(); ++i)
        h_ << "in[" << i << "], ";
    h_ << "out);\n}\n\n";
    h_ << "/// The same with the inputs by name.\n";
    h_ << "template <typename T>\nIMPACTGEN_FUNC impact_status " << o_.name << "_jacobian(const " << input_struct()
       << "<T>& in, " << jr << "<T>& out) noexcept\n{\n";
    h_ << "    return " << o_.name << "_jacobian<T>(";
    for (const std::string &nm : input_names_)
        h_ << "in." << nm << ", ";
    h_ << "out);\n}\n\n";
}

// Batch form over arrays (structure of arrays), branchless so that it vectorises.
void writer::straight_batch()
{
    h_ << "/// The same over n impacts in structure-of-arrays form: in[j][i] is input j\n";
    h_ << "/// (order of " << o_.name << "_input_names) of impact i, out[j][i] output j. The arrays\n";
    h_ << "/// must not overlap. A first pass computes every impact without branches (it\n";
    h_ << "/// vectorises); if any impact failed a check, a second pass redoes those one by\n";
    h_ << "/// one for their status (their outputs are then the state unchanged).\n";
    std::size_t energy_index = outs_.size();
    for (std::size_t j = 0; j < outs_.size(); ++j)
        if (outs_[j].kind == output_value::energy_lost)
            energy_index = j;
    if (energy_index < outs_.size())
        h_ << "/// with_energy_lost = false: energy_lost is neither computed nor checked, and out[" << energy_index
           << "] is not written (it may be null).\n";
    // The first pass as a kernel whose arrays are restrict-qualified parameters: the
    // no-alias promise that both g++ and clang++ honour (clang ignores it on locals),
    // with no forcing pragma that would warn where a type does not vectorise.
    std::vector<std::string> pass_params;
    for (const std::string &nm : input_names_)
        pass_params.push_back("const T* IMPACTGEN_RESTRICT " + in_ptr_.at(nm));
    for (const code_output &ov : outs_)
        pass_params.push_back("T* IMPACTGEN_RESTRICT " + out_ptr_.at(ov.field));
    pass_params.push_back("impact_status* IMPACTGEN_RESTRICT " + status_ptr_);
    h_ << "namespace detail {\n";
    h_ << "/// The first pass of " << o_.name << "_batch (every impact, no branch): 1 when some\n";
    h_ << "/// impact failed a check, else 0.\n";
    h_ << "template <typename T, bool with_energy_lost>\nIMPACTGEN_FUNC unsigned " << o_.name << "_batch_pass(long n, "
       << join(pass_params, ", ") << ") noexcept\n{\n";
    // (without it a symbolic normal's sqrt is ::sqrt(double), for float and long double too)
    h_ << math_usings(batch_);
    h_ << "    unsigned failed = 0;\n";
    h_ << "#if defined(__GNUC__) && !defined(__clang__)\n#pragma GCC ivdep\n#endif\n";
    h_ << "    for (long i = 0; i < n; ++i) {\n";
    for (const std::string &nm : input_names_)
        h_ << "        const T " << nm << " = " << in_ptr_.at(nm) << "[i];\n";
    std::istringstream lines(batch_.code + ok_flag("    ", batch_, batch_terms_, false));
    for (std::string line; std::getline(lines, line);)
        h_ << "    " << line << "\n";
    // Stored unconditionally: the second pass overwrites the outputs of failed impacts.
    for (const code_output &ov : outs_)
        h_ << (ov.kind == output_value::energy_lost ? "        if constexpr (with_energy_lost)\n    " : "")
           << "        " << out_ptr_.at(ov.field) << "[i] = " << local_of_.at(ov.field) << ";\n";
    h_ << "        " << status_ptr_ << "[i] = ok ? impact_status::ok : impact_status::overflow; // refined below\n";
    h_ << "        failed |= static_cast<unsigned>(!ok);\n";
    h_ << "    }\n";
    h_ << "    return failed;\n}\n} // namespace detail\n\n";

    h_ << tparams << "IMPACTGEN_FUNC void " << o_.name
       << "_batch(long n, const T* const* in, T* const* out, impact_status* status) noexcept\n{\n";
    if (input_names_.empty())
        h_ << "    (void)in;\n";
    for (std::size_t j = 0; j < input_names_.size(); ++j)
        h_ << "    const T* const " << in_ptr_.at(input_names_[j]) << " = in[" << j << "];\n";
    for (std::size_t j = 0; j < outs_.size(); ++j)
        h_ << "    T* const " << out_ptr_.at(outs_[j].field) << " = out[" << j << "];\n";
    std::vector<std::string> pass_args;
    for (const std::string &nm : input_names_)
        pass_args.push_back(in_ptr_.at(nm));
    for (const code_output &ov : outs_)
        pass_args.push_back(out_ptr_.at(ov.field));
    pass_args.push_back("status");
    h_ << "    const unsigned failed = detail::" << o_.name << "_batch_pass<T, with_energy_lost>(n, "
       << join(pass_args, ", ") << ");\n";
    h_ << "    if (failed == 0)\n";
    h_ << "        return;\n";
    h_ << "    for (long i = 0; i < n; ++i)\n";
    h_ << "        if (status[i] != impact_status::ok) {\n";
    h_ << "            " << result() << "<T> r;\n";
    h_ << "            status[i] = detail::" << checked() << "<T, with_energy_lost>(";
    for (const std::string &nm : input_names_)
        h_ << in_ptr_.at(nm) << "[i], ";
    h_ << "r);\n";
    for (const code_output &ov : outs_)
        h_ << (ov.kind == output_value::energy_lost ? "            if constexpr (with_energy_lost)\n    " : "")
           << "            " << out_ptr_.at(ov.field) << "[i] = r." << ov.field << ";\n";
    h_ << "        }\n";
    h_ << "}\n\n";
}

} // namespace impactgen::codegen::writer_detail
