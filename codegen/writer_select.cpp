// The one header writer (writer.hpp), a plan with a selection rule: the main function, the regime
// selection (the closed-form candidates, the sliding-angle search, the root loop).
#include "writer.hpp"

namespace impactgen::codegen::writer_detail
{

// The conditions of a candidate, folded as unsigned (no branch implied, and nothing for
// clang's -Wbitwise-instead-of-logical to say).
std::string writer::holds_text(const case_names &cn, const regime_case &c) const
{
    std::vector<std::string> parts;
    for (std::size_t j = 0; j < cn.cond.size(); ++j)
        parts.push_back("static_cast<unsigned>(" + cn.cond[j] + (c.conditions[j].strict ? " > T(0))" : " >= T(0))"));
    if (parts.empty())
        return "true";
    if (parts.size() == 1)
        return "(" + parts[0] + " != 0u)";
    return "((" + join(parts, " & ") + ") != 0u)";
}

std::string writer::select_text(const case_names &cn, const std::string &regime, const std::string &ind) const
{
    std::string r = ind + regime_name_ + " = impact_regime::" + regime + ";\n";
    r += ind + sel_N_name_ + " = " + cn.N + ";\n";
    for (std::size_t a = 0; a < cn.P.size(); ++a) {
        r += ind + sel_P_names_[a] + " = " + cn.P[a] + ";\n";
        r += ind + sel_F_names_[a] + " = " + cn.F[a] + ";\n";
    }
    return r;
}

// The stick/slide boundary within rounding: a slide whose impulse is the stick
// candidate's to within boundary_tolerance times its size is the same solution.
std::string writer::merge_text() const
{
    const case_names &sn = names_.front();
    std::string size = "detail::abs_of<T>(" + sn.P[0] + ")";
    for (std::size_t a = 1; a < sn.P.size(); ++a)
        size = "detail::max_of<T>(" + size + ", detail::abs_of<T>(" + sn.P[a] + "))";
    return "detail::boundary_tolerance<T>() * " + size;
}

std::string writer::near_text(const case_names &cn) const
{
    const case_names &sn = names_.front();
    std::vector<std::string> parts;
    for (std::size_t a = 0; a < cn.P.size(); ++a)
        parts.push_back("detail::abs_of<T>(" + cn.P[a] + " - " + sn.P[a] + ") <= " + merge_name_);
    if (!stick_possible_name_.empty()) // no stick candidate: no slide is it
        parts.insert(parts.begin(), stick_possible_name_);
    return join(parts, " && ");
}

// Counting the closed-form candidates that hold; they are selected without a branch (the
// first that holds: stick when there is one, then the slides; the last when none does:
// replaced below). Only the rare boundary and failure cases branch.
void writer::emit_closed_forms(const std::string &ind)
{
    const bool stick = f_.stick() != nullptr;
    const bool droppable = stick && !stick_possible_name_.empty();
    if (droppable) // K singular here (within rounding): no stick candidate, the slides may hold
        h_ << ind << "const bool " << stick_possible_name_ << " = ((static_cast<unsigned>(" << det_K_name_
           << " > T(0)) & static_cast<unsigned>(detail::finite<T>(" << det_K_name_
           << "))) != 0u); // det K > 0, finite: the stick candidate exists\n";
    for (std::size_t i = 0; i < f_.cases.size(); ++i)
        if (static_cast<int>(i) != angle_) {
            closed_.push_back(i);
            holds_.push_back(stick && i == 0 ? stick_holds_name_ : scope_.claim(names_[i].prefix + "holds"));
            std::string holds = holds_text(names_[i], f_.cases[i]);
            if (droppable && i == 0)
                holds = "((static_cast<unsigned>(" + stick_possible_name_ + ") & static_cast<unsigned>(" + holds +
                        ")) != 0u)";
            h_ << ind << "const bool " << holds_.back() << " = " << holds << "; // "
               << names::comment_text(f_.cases[i].name) << "\n";
        }
    for (const std::string &hname : holds_)
        counted_.push_back("static_cast<int>(" + hname + ")");
    h_ << ind << "int " << count_name_ << " = " << counted_text() << ";\n";
    if (cp_.rule == selection_rule::process) {
        // Routh's process: the regime is the last phase of the sequence selected.
        std::string r = "impact_regime::slide";
        for (std::size_t k = closed_.size(); k-- > 0;)
            if (f_.cases[closed_[k]].process.back().kind == phase_kind::stick)
                r = holds_[k] + " ? impact_regime::stick : " + r;
            else if (r != "impact_regime::slide")
                r = holds_[k] + " ? impact_regime::slide : " + r;
        h_ << ind << regime_name_ << " = " << r << ";\n";
    } else if (stick)
        h_ << ind << regime_name_ << " = " << stick_holds_name_ << " ? impact_regime::stick : impact_regime::slide;\n";
    else
        h_ << ind << regime_name_ << " = impact_regime::slide; // no stick candidate (K singular)\n";
    if (closed_.empty())
        return; // the slides of the angle search select themselves
    auto first_of = [&](auto field) {
        std::string r = field(names_[closed_.back()]);
        for (std::size_t k = closed_.size() - 1; k-- > 0;)
            r = holds_[k] + " ? " + field(names_[closed_[k]]) + " : " + r;
        return r;
    };
    h_ << ind << sel_N_name_ << " = " << first_of([](const case_names &cn) { return cn.N; }) << ";\n";
    for (std::size_t a = 0; a < sel_P_names_.size(); ++a) {
        h_ << ind << sel_P_names_[a] << " = " << first_of([a](const case_names &cn) { return cn.P[a]; }) << ";\n";
        h_ << ind << sel_F_names_[a] << " = " << first_of([a](const case_names &cn) { return cn.F[a]; }) << ";\n";
    }
    if (process_jacobian())
        h_ << process_sequence_text(ind);
}

// The 3-D slide without closed form: its directions (pass 0: the one direction when the
// solution is provably unique; pass 1: every root of g), each a candidate.
void writer::emit_angle_search(const std::string &ind)
{
    const bool stick = f_.stick() != nullptr;
    const std::string i2 = ind + "    ", j2 = i2 + "    ";
    if (stick) {
        h_ << ind << "int " << apart_name_ << " = 0; // slides holding that are not the stick solution\n";
        h_ << ind << "bool " << at_stick_name_ << " = " << stick_holds_name_
           << "; // some candidate is the stick solution\n";
        h_ << ind << "const T " << merge_name_ << " = " << merge_text() << ";\n";
    }
    h_ << ind << "// The sliding directions: roots of g (cos and sin of the angle from e_t towards e_b),\n";
    h_ << ind << "// only where lambda D may be > 0 (the filter keep_*).\n";
    h_ << ind << "T " << roots_c_name_ << "[4];\n" << ind << "T " << roots_s_name_ << "[4];\n";
    h_ << ind << "const T " << keep_array_name_ << "[5] = {" << join(keep_names_, ", ") << "};\n";
    h_ << ind << "// At most one solution when M + M^T is positive definite (with a margin;\n";
    if (stick)
        h_ << ind << "// detail::slide_direction): then pass 0 takes the stick candidate when it\n"
           << ind << "// holds, else the one slide; pass 1 (not unique, or the slide not confirmed within\n"
           << ind << "// rounding) searches every direction and counts what holds.\n";
    else
        h_ << ind << "// detail::slide_direction): then pass 0 takes the one slide; pass 1 (not unique,\n"
           << ind << "// or the slide not confirmed within rounding) searches every direction and counts\n"
           << ind << "// what holds.\n";
    h_ << ind << "const bool " << unique_name_ << " = ((static_cast<unsigned>(" << fast_names_[0]
       << " > T(0)) & static_cast<unsigned>(" << fast_names_[6] << " > T(0))) != 0u);\n";
    h_ << ind << "bool " << slides_finite_name_ << " = true;\n";
    h_ << ind << "for (int " << pass_name_ << " = " << unique_name_ << " ? 0 : 1; " << pass_name_ << " < 2; ++"
       << pass_name_ << ") {\n";
    h_ << i2 << "int " << n_roots_name_ << " = 0;\n";
    h_ << i2 << "if (" << pass_name_ << " == 0) {\n";
    h_ << j2 << "if (" << (stick ? "!" + stick_holds_name_ + " && " : std::string()) << "!detail::slide_direction("
       << fast_names_[0] << ", " << fast_names_[1] << ", " << fast_names_[2] << ", " << fast_names_[3] << ", "
       << fast_names_[4] << ", " << fast_names_[5] << ", " << roots_c_name_ << "[0], " << roots_s_name_ << "[0]))\n";
    h_ << j2 << "    continue;\n";
    h_ << j2 << n_roots_name_ << " = " << (stick ? stick_holds_name_ + " ? 0 : 1" : std::string("1")) << ";\n";
    h_ << i2 << "} else {\n";
    h_ << j2 << n_roots_name_ << " = detail::trig2_roots(" << join(trig_names_, ", ") << ", " << keep_array_name_
       << ", " << roots_c_name_ << ", " << roots_s_name_ << ");\n";
    h_ << i2 << "}\n";
    h_ << i2 << "if (" << n_roots_name_ << " == -2) // a coefficient of g overflowed\n"
       << j2 << "return fail(friction_status::overflow);\n";
    h_ << i2 << "// g = 0 identically: every direction satisfies it; a slide that holds in any of\n";
    h_ << i2 << "// these four is one of infinitely many (ambiguous)\n";
    h_ << i2 << "const bool " << every_name_ << " = " << n_roots_name_ << " == -1;\n";
    h_ << i2 << "if (" << every_name_ << ") {\n";
    const char *cs[4][2] = {{"T(1)", "T(0)"}, {"T(0)", "T(1)"}, {"T(-1)", "T(0)"}, {"T(0)", "T(-1)"}};
    for (int k = 0; k < 4; ++k)
        h_ << j2 << roots_c_name_ << "[" << k << "] = " << cs[k][0] << ";\n"
           << j2 << roots_s_name_ << "[" << k << "] = " << cs[k][1] << ";\n";
    h_ << j2 << n_roots_name_ << " = 4;\n" << i2 << "}\n";
    emit_root_loop(i2);
    // Pass 0 found the one solution, or starts over with every direction.
    h_ << i2 << "if (" << pass_name_ << " == 0) {\n";
    h_ << j2 << "if (" << count_name_ << " == 1)\n" << j2 << "    break;\n";
    h_ << j2 << count_name_ << " = " << counted_text() << ";\n";
    if (stick) {
        h_ << j2 << apart_name_ << " = 0;\n";
        h_ << j2 << at_stick_name_ << " = " << stick_holds_name_ << ";\n";
    }
    h_ << j2 << slides_finite_name_ << " = true;\n";
    h_ << i2 << "}\n";
    h_ << ind << "}\n";
}

// The loop over the roots of g (inside the passes): the slide along each, counted when
// it holds, the first selected.
void writer::emit_root_loop(const std::string &ind)
{
    const bool stick = f_.stick() != nullptr;
    const case_names &cn = names_[static_cast<std::size_t>(angle_)];
    const regime_case &c = f_.cases[static_cast<std::size_t>(angle_)];
    const std::string i2 = ind + "    ";
    h_ << ind << "for (int " << loop_name_ << " = 0; " << loop_name_ << " < " << n_roots_name_ << "; ++" << loop_name_
       << ") {\n";
    h_ << i2 << "const T " << dir_c_name_ << " = " << roots_c_name_ << "[" << loop_name_ << "];\n";
    h_ << i2 << "const T " << dir_s_name_ << " = " << roots_s_name_ << "[" << loop_name_ << "];\n";
    h_ << indent(b_.em.code, ind);
    std::vector<std::string> slide_values = cn.cond;
    slide_values.push_back(cn.N);
    h_ << i2 << slides_finite_name_ << " = " << slides_finite_name_ << " && detail::finite<T>("
       << balanced_sum(slide_values) << ");\n";
    const std::string step = "(" + every_name_ + " ? 2 : 1)";
    if (stick) {
        h_ << i2 << "const bool " << near_name_ << " = " << near_text(cn) << ";\n";
        h_ << i2 << at_stick_name_ << " = " << at_stick_name_ << " || " << near_name_ << ";\n";
    }
    h_ << i2 << "if (" << holds_text(cn, c) << ") {\n";
    if (stick)
        h_ << i2 << "    " << apart_name_ << " += " << near_name_ << " ? 0 : " << step << ";\n";
    h_ << i2 << "    " << count_name_ << " += " << step << ";\n";
    h_ << i2 << "    if (" << count_name_ << " == " << step << ") {\n"
       << select_text(cn, "slide", i2 + "        ") << i2 << "    }\n";
    h_ << i2 << "}\n";
    h_ << ind << "}\n";
}

// Not exactly one candidate holding: at the stick/slide boundary within rounding (the
// stick candidate holding or a slide with its impulse, and nothing else holding) the
// stick solution; else overflow when a candidate or condition is not finite (it decides
// nothing), no_solution or ambiguous.
void writer::emit_unresolved(const std::string &ind)
{
    const bool stick = f_.stick() != nullptr;
    const std::string i2 = ind + "    ";
    // The values of the candidates: a stick candidate that does not exist (det K <= 0) is not
    // one of them, and where nothing else holds K singular is the reason.
    const bool droppable = stick && !stick_possible_name_.empty();
    std::vector<std::string> values, stick_values;
    for (std::size_t i = 0; i < names_.size(); ++i) {
        if (static_cast<int>(i) == angle_)
            continue;
        const case_names &cn = names_[i];
        std::vector<std::string> &to = droppable && i == 0 ? stick_values : values;
        to.push_back(cn.N);
        to.insert(to.end(), cn.P.begin(), cn.P.end());
        to.insert(to.end(), cn.cond.begin(), cn.cond.end());
    }
    values.insert(values.end(), trig_names_.begin(), trig_names_.end());
    std::vector<std::string> not_finite;
    if (!values.empty())
        not_finite.push_back("!detail::finite<T>(" + balanced_sum(values) + ")");
    if (droppable)
        not_finite.push_back("(" + stick_possible_name_ + " && !detail::finite<T>(" + balanced_sum(stick_values) +
                             "))");
    if (angle_ >= 0)
        not_finite.push_back("!" + slides_finite_name_);
    const std::string finite = "if (" + join(not_finite, " || ") + ")\n";
    const std::string none =
        droppable ? "(" + stick_possible_name_ + " ? friction_status::no_solution : friction_status::singular)"
                  : std::string("friction_status::no_solution");
    const std::string verdict = "return fail(" + count_name_ + " == 0 ? " + none + " : friction_status::ambiguous);\n";
    if (cp_.rule == selection_rule::process) {
        // The phase sequences split the inputs by comparisons of closed forms: where two hold
        // (on a phase boundary within rounding) they give the same impact, the first is taken;
        // none holding is a contact that wedges (no_solution) or a value that is not finite.
        h_ << ind << "if (" << count_name_ << " == 0) {\n";
        h_ << i2 << finite << i2 << "    return fail(friction_status::overflow);\n";
        h_ << i2 << "return fail(friction_status::no_solution);\n" << ind << "}\n";
        return;
    }
    h_ << ind << "if (" << count_name_ << " != 1) {\n";
    if (!stick) {
        h_ << i2 << finite << i2 << "    return fail(friction_status::overflow);\n" << i2 << verdict;
        h_ << ind << "}\n";
        return;
    }
    h_ << i2 << "// On the stick/slide boundary within rounding (the stick candidate holding or a slide\n";
    h_ << i2 << "// with its impulse, and nothing else holding): the stick solution.\n";
    if (angle_ < 0) {
        h_ << i2 << "const T " << merge_name_ << " = " << merge_text() << ";\n";
        h_ << i2 << "int " << apart_name_ << " = 0; // slides holding that are not the stick solution\n";
        h_ << i2 << "bool " << at_stick_name_ << " = " << stick_holds_name_
           << "; // some candidate is the stick solution\n";
    }
    for (std::size_t k = 1; k < closed_.size(); ++k) {
        const std::string nr = scope_.claim(names_[closed_[k]].prefix + "near");
        h_ << i2 << "const bool " << nr << " = " << near_text(names_[closed_[k]]) << ";\n";
        h_ << i2 << at_stick_name_ << " = " << at_stick_name_ << " || " << nr << ";\n";
        h_ << i2 << apart_name_ << " += " << holds_[k] << " && !" << nr << " ? 1 : 0;\n";
    }
    h_ << i2 << "if (" << apart_name_ << " == 0 && " << at_stick_name_ << ") {\n";
    h_ << i2 << "    " << count_name_ << " = 1;\n"
       << select_text(names_.front(), "stick", i2 + "    ") << i2 << "} else {\n";
    h_ << i2 << "    " << finite << i2 << "        return fail(friction_status::overflow);\n";
    h_ << i2 << "    " << verdict << i2 << "}\n";
    h_ << ind << "}\n";
}

// The selection among the candidates and the post-impact state: the same text in the
// function and its unchecked variant, made once.
const std::string &writer::selection_text()
{
    if (!selection_.empty())
        return selection_;
    std::ostringstream text;
    text.swap(h_); // write the selection into a stream of its own
    h_ << "    // The regime that holds: its impulse (world axes, on "
       << names::comment_text(q_.bodies[q_.contact().body2].name) << "), normal and tangential impulse.\n";
    h_ << "    T " << sel_N_name_ << " = T(0);\n";
    for (std::size_t a = 0; a < sel_P_names_.size(); ++a)
        h_ << "    T " << sel_P_names_[a] << " = T(0);\n    T " << sel_F_names_[a] << " = T(0);\n";
    h_ << "    impact_regime " << regime_name_ << " = impact_regime::smooth;\n";
    if (process_jacobian()) // mu = 0 (the smooth impact) is the edge of mu's domain: no sequence, a boundary
        h_ << "    int " << seq_local_.at("sequence_now") << " = -1;\n    bool " << seq_local_.at("boundary_now")
           << " = true;\n";
    if (!mu_name_.empty()) {
        h_ << "    if (" << mu_name_ << " == T(0)) { // the smooth impact\n";
        h_ << indent(s_.em.code, "    ");
        h_ << "    } else {\n";
    } else {
        h_ << "    {\n";
    }
    const std::string ind = "        ";
    emit_closed_forms(ind);
    if (angle_ >= 0)
        emit_angle_search(ind);
    emit_unresolved(ind);
    h_ << "    }\n";
    h_ << "    // The post-impact state.\n";
    h_ << c_.em.code;
    h_ << "    out.regime = " << regime_name_ << ";\n";
    if (process_jacobian())
        h_ << "    out.sequence = " << seq_local_.at("sequence_now")
           << ";\n    out.boundary = " << seq_local_.at("boundary_now") << ";\n";
    text.swap(h_);
    selection_ = text.str();
    return selection_;
}

// The function (checked: every input and the result validated) or its unchecked variant
// (the caller validated the inputs once: no check of restitution, friction, masses,
// inertia, normal, nor of finiteness; the same arithmetic, the same selection).
void writer::main_function(bool unchecked)
{
    if (unchecked) {
        h_ << "/// " << o_.name << " without the per-call validation, for inputs the caller validated once\n";
        h_ << "/// (contract: every input finite, 0 <= e <= 1, mu >= 0, masses and moments of inertia\n";
        h_ << "/// > 0, inertia tensors positive definite, a normal neither zero, denormal nor too long;\n";
        h_ << "/// what " << o_.name << " would not return invalid_* or non_finite_input for). On such inputs\n";
        h_ << "/// the result is bit for bit that of " << o_.name << " whenever it returns ok; the statuses that\n";
        h_ << "/// depend on the state (not_approaching, singular, no_solution, ambiguous, overflow of a\n";
        h_ << "/// candidate) are still returned, but no finiteness check guards the result.\n";
        h_ << "template <typename T, bool with_energy_lost = true>\nIMPACTGEN_HOT IMPACTGEN_FUNC friction_status "
           << o_.name << "_unchecked(" << params() << result() << "<T>& out) noexcept\n{\n";
    } else {
        h_ << "/// Post-impact state for the inputs below, with Coulomb friction at the contact; returns\n";
        h_ << "/// friction_status::ok with out.regime the regime that holds, or why not (then out holds the\n";
        h_ << "/// state unchanged: velocities as before, impulses zero). T: float, double or long double.\n";
        h_ << "/// with_energy_lost = false: out.energy_lost is left 0 (the rest is the same).\n";
        for (std::size_t i = 0; i < input_names_.size(); ++i)
            h_ << "///   " << input_names_[i] << ": " << names::comment_text(cp_.input_meaning[i]) << "\n";
        h_ << "template <typename T, bool with_energy_lost = true>\nIMPACTGEN_FUNC friction_status " << o_.name << "("
           << params() << result() << "<T>& out) noexcept\n{\n";
    }
    h_ << "    using std::sqrt;\n";
    for (const stage *st : {&nb_, &a_, &b_, &s_, &c_, &u_})
        if (st->em.uses_trig) { // an angle among the inputs (a rod's): cos and sin of it
            h_ << "    using std::cos;\n    using std::sin;\n";
            break;
        }
    fail_lambda("auto", "detail::friction_status_of", !unchecked);
    const ex &mu = q_.contact().friction();
    const bool mu_input = is_a<symbol>(mu) && input_ident_.count(mu);
    const std::string mu_check = unchecked ? std::string()
                                           : "    if (!(" + mu_name_ + " >= T(0) && detail::finite<T>(" + mu_name_ +
                                                 "))) // mu >= 0, finite\n        return "
                                                 "fail(friction_status::invalid_friction);\n";
    if (mu_input)
        h_ << mu_check;
    h_ << basis_text();
    h_ << (unchecked ? "    // Shared steps, the checks of the state, the candidates and their conditions.\n"
                     : "    // Shared steps, checks, the candidates and their conditions.\n");
    h_ << (unchecked ? a_unchecked_.code : a_.em.code);
    if (!mu_input && !mu_name_.empty())
        h_ << mu_check;
    h_ << selection_text();
    if (!unchecked)
        overflow_check();
    h_ << "    return friction_status::ok;\n}\n\n";
}

std::string writer::basis_text() const
{
    if (basis_names_.empty())
        return "";
    std::ostringstream os;
    os << "    // The unit tangent basis e_t, e_b of the contact plane for this normal (any direction).\n";
    os << nb_.em.code;
    os << "    T " << basis_t_name_ << "[3], " << basis_b_name_ << "[3];\n";
    os << "    detail::tangent_basis<T>(" << nb_.outs[0].first << ", " << nb_.outs[1].first << ", " << nb_.outs[2].first
       << ", " << basis_t_name_ << ", " << basis_b_name_ << ");\n";
    for (std::size_t k = 0; k < basis_names_.size(); ++k)
        os << "    const T " << basis_names_[k] << " = " << (k < 3 ? basis_t_name_ : basis_b_name_) << "[" << k % 3
           << "];\n";
    return os.str();
}

void writer::overflow_check()
{
    std::vector<std::string> terms;
    for (const code_output &of : outs_)
        terms.push_back("out." + of.field);
    for (const std::string &nm : input_names_)
        terms.push_back(nm);
    // (a sum of finite values may overflow: then each is tested, as the smooth headers do)
    h_ << "    const T check_sum = " << balanced_sum(terms) << ";\n";
    h_ << "    if (!detail::finite<T>(check_sum) && !detail::all_finite(" << join(terms, ", ") << "))\n";
    h_ << "        return fail(friction_status::overflow);\n";
}

} // namespace impactgen::codegen::writer_detail
