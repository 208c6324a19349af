// The one header writer (writer.hpp): NAME_jacobian of a header with a selection rule, from the
// plan's candidates_jacobian (code_plan.hpp), whatever the law. NAME_jacobian calls NAME (its
// values and status unchanged), finds the candidate NAME selected, and runs that candidate's
// straight-line program (its steps, the derivative steps and the entries, CSE inside it) in a
// switch; the status is ambiguous where the map is not differentiable (the input on a boundary
// between candidates within rounding: out and jac then hold the candidate's values and its
// one-sided derivatives). What differs between the laws is how the candidate is found, which the
// law's part writes into a jacobian_form:
//   Coulomb friction under Newton's law (writer_jacobian_friction.cpp): from the impulse NAME
//     returned (its slip after impact), with the boundary tests of the candidate's conditions;
//   Routh's process: NAME reports its phase sequence (out.sequence) and whether another with a
//     different closed form holds within rounding (out.boundary); one program per closed form;
//   a system's sets: NAME reports its set (out.set) and out.boundary likewise.
#include "writer.hpp"

namespace impactgen::codegen::writer_detail
{

bool writer::process_jacobian() const
{
    return cp_.rule == selection_rule::process && cp_.jacobian.on;
}

void writer::build_jacobian()
{
    if (!cp_.jacobian.on)
        return;
    if (system())
        system_jacobian_form();
    else if (cp_.rule == selection_rule::process)
        process_jacobian_form();
    else
        friction_jacobian_form();
}

// One program per distinct closed form: the shared steps, the candidate's own steps, then the
// entries (and what `more` adds). Its locals are prefixed per candidate, or named once for all.
void writer::build_jacobian_programs(const std::function<void(std::size_t, stage &)> &more)
{
    const candidates_jacobian &cj = cp_.jacobian;
    const std::size_t nw = cj.wrt.size();
    std::map<ex, std::string, ex_is_less> step_once; // without a prefix: each name claimed once
    std::map<std::string, std::string> entry_once;
    jac_stages_.resize(cj.candidates.size());
    jac_entries_.resize(cj.candidates.size());
    for (std::size_t k = 0; k < cj.candidates.size(); ++k) {
        const candidate_jacobian &cand = cj.candidates[k];
        if (cand.same_as != k)
            continue;
        const std::string pre = jf_.program_prefix.empty() ? "" : jf_.program_prefix + std::to_string(k) + "_";
        auto named = [&](auto &once, const auto &key, const std::string &base) -> std::string {
            if (!pre.empty())
                return scope_.claim(pre + base);
            if (!once.count(key))
                once.emplace(key, scope_.claim(base));
            return once.at(key);
        };
        stage &st = jac_stages_[k];
        std::map<ex, std::string, ex_is_less> in = input_ident_;
        if (!cand.angle.empty()) {
            in[cand.angle[0]] = jf_.angle_c;
            in[cand.angle[1]] = jf_.angle_s;
        }
        st.pool.set_input_names(in);
        for (const std::vector<step> *steps : {&cj.steps, &cand.steps})
            for (const step &s : *steps)
                st.bind_step(s, named(step_once, s.sym, s.sym.get_name()));
        for (std::size_t i = 0; i < cj.rows.size(); ++i)
            for (std::size_t w = 0; w < nw; ++w) {
                const std::string base = "d_" + outs_[cj.rows[i]].field + "_d_" + input_ident_.at(cj.wrt[w]);
                jac_entries_[k].push_back(named(entry_once, base, base));
                st.output(jac_entries_[k].back(), cand.entries[i][w]);
            }
        if (more)
            more(k, st);
    }
}

void writer::emit_jacobian_programs()
{
    emit_options locals;
    locals.outputs = output_placement::local;
    for (std::size_t k = 0; k < jac_stages_.size(); ++k) {
        if (cp_.jacobian.candidates[k].same_as != k)
            continue;
        emit_one(jac_stages_[k], locals, false);
    }
}

// The tables of the columns (the inputs differentiated by) and of the rows.
void writer::jacobian_tables()
{
    const candidates_jacobian &cj = cp_.jacobian;
    h_ << "inline constexpr int " << jf_.wrt_count << " = " << cj.wrt.size() << ";\n";
    h_ << "/// " << jf_.wrt_comment << "\n";
    h_ << "inline constexpr const char* " << jf_.wrt_names << "[] = {";
    for (const symbol &x : cj.wrt)
        h_ << names::cpp_string_literal(input_ident_.at(x)) << ", ";
    h_ << "nullptr};\n";
    if (!jf_.row_count.empty()) {
        h_ << "inline constexpr int " << jf_.row_count << " = " << cj.rows.size() << ";\n";
        h_ << "/// " << jf_.row_comment << "\n";
        h_ << "inline constexpr const char* " << jf_.row_names << "[] = {";
        for (std::size_t i : cj.rows)
            h_ << names::cpp_string_literal(outs_[i].field) << ", ";
        h_ << "nullptr};\n";
    }
    h_ << "\n";
}

// NAME_jacobian: NAME, the candidate it selected, that candidate's program.
void writer::candidates_jacobian_function()
{
    const candidates_jacobian &cj = cp_.jacobian;
    if (!cj.on)
        return;
    const std::string n = std::to_string(cj.rows.size() * cj.wrt.size()), &jac = jf_.jac, &k = jf_.k;
    jacobian_tables();
    h_ << jf_.doc;
    h_ << "template <typename T>\nIMPACTGEN_FUNC friction_status " << jf_.fn << "(" << params() << result()
       << "<T>& out, T* " << jac << ") noexcept\n{\n";
    h_ << "    const friction_status " << jf_.status << " = " << o_.name << "<T>(" << args() << "out);\n";
    h_ << "    for (int " << k << " = 0; " << k << " < " << n << "; ++" << k << ")\n        " << jac << "[" << k
       << "] = T(0);\n";
    h_ << "    if (" << jf_.status << " != friction_status::ok)\n        return " << jf_.status << ";\n";
    bool sq = jf_.sqrt_always, trig = jf_.trig;
    for (const stage &st : jac_stages_) {
        sq = sq || st.em.uses_sqrt;
        trig = trig || st.em.uses_trig;
    }
    h_ << (sq ? "    using std::sqrt;\n" : "") << (trig ? "    using std::cos;\n    using std::sin;\n" : "");
    h_ << jf_.select;
    h_ << "    switch (" << jf_.selector << ") {\n";
    for (std::size_t c = 0; c < cj.candidates.size(); ++c) {
        if (cj.candidates[c].same_as != c)
            continue;
        std::vector<std::size_t> labels;
        for (std::size_t v = 0; v < jf_.selects.size(); ++v)
            if (cj.candidates[jf_.selects[v]].same_as == c)
                labels.push_back(v);
        for (std::size_t v : labels)
            h_ << "    case " << v << (jf_.labels_apart ? ":\n" : ": {");
        h_ << (jf_.labels_apart ? "    {" : "")
           << (jf_.case_names ? " // " + names::comment_text(f_.cases[c].name) : std::string()) << "\n"
           << indent(jac_stages_[c].em.code, "    ");
        for (std::size_t i = 0; i < jac_entries_[c].size(); ++i)
            h_ << "        " << jac << "[" << i << "] = " << jac_entries_[c][i] << ";\n";
        h_ << (jf_.case_tail ? jf_.case_tail(c) : std::string()) << "        break;\n    }\n";
    }
    h_ << "    default:\n        break;\n    }\n";
    h_ << jf_.after_switch;
    h_ << "    return " << jf_.boundary << " ? friction_status::ambiguous : friction_status::ok;\n}\n\n";
    if (!jf_.array_form)
        return;
    h_ << "/// " << jf_.fn << " with the inputs in an array, in the order of " << o_.name << "_input_names.\n";
    h_ << "template <typename T>\nIMPACTGEN_FUNC friction_status " << jf_.fn << "(const T* in, " << result()
       << "<T>& out, T* " << jac << ") noexcept\n{\n    return " << jf_.fn << "<T>(";
    for (std::size_t i = 0; i < input_names_.size(); ++i)
        h_ << "in[" << i << "], ";
    h_ << "out, " << jac << ");\n}\n\n";
}

// ---- Routh's process: NAME reports the sequence and whether another holds within rounding.

// The names of NAME_jacobian and its tables that come from NAME (a process's, a system's), its
// locals, and the start of its comment: the Jacobian of `what` after impact (`rows`), d(`row`
// i)/d(input j), the selected `which` closed form.
void writer::named_jacobian_form(const std::map<std::string, std::string> &locals, const std::string &what,
                                 const std::string &rows, const std::string &row, const std::string &which)
{
    jf_.fn = o_.name + "_jacobian";
    jf_.wrt_count = o_.name + "_wrt_count";
    jf_.wrt_names = o_.name + "_wrt_names";
    jf_.wrt_comment = "The inputs the Jacobian differentiates by, in the order of its columns.";
    jf_.jac = locals.at("jac");
    jf_.status = locals.at("status");
    jf_.k = locals.at("k");
    jf_.doc = "/// " + o_.name + " and the Jacobian of the " + what + " after impact (" + rows +
              ")\n/// by the inputs " + o_.name + "_wrt_names: " + jf_.jac + "[i * " +
              std::to_string(cp_.jacobian.wrt.size()) + " + j] = d(" + row + " i)/d(input j), the selected " + which +
              "\n/// closed form differentiated exactly. Returns " + "the status of " + o_.name +
              " (jac zero unless ok), or ambiguous";
    jf_.boundary = "out.boundary";
}

void writer::process_jacobian_form()
{
    for (const char *nm : {"sequence_now", "boundary_now", "near_sequence", "form_of", "tol", "jac", "status", "k"})
        seq_local_[nm] = scope_.claim(nm);
    named_jacobian_form(seq_local_, "velocities and impulses", o_.name + "_jacobian_output_names", "output",
                        "phase sequence's");
    jf_.row_count = o_.name + "_jacobian_output_count";
    jf_.row_names = o_.name + "_jacobian_output_names";
    jf_.row_comment =
        "The outputs the Jacobian differentiates, in the order of its rows (members of " + result() + ").";
    jf_.doc += " where\n/// the impact map is not differentiable (out.boundary): another phase sequence with a "
               "different\n/// closed form holds within rounding (out and jac then hold the selected sequence's "
               "values and\n/// its one-sided derivatives), or mu = 0, the edge of mu's domain (the smooth impact; "
               "jac zero).\n";
    jf_.selector = "out.sequence";
    for (std::size_t i = 0; i < f_.cases.size(); ++i) // out.sequence numbers the closed forms (closed_)
        if (static_cast<int>(i) != angle_)
            jf_.selects.push_back(i);
    jf_.labels_apart = true;
    build_jacobian_programs({});
    emit_jacobian_programs();
}

// The scale of condition j of candidate i: the speed before impact, the contact response (its
// square for mu^2 K_tt^2 - K_tn^2), or an impulse (the candidate's normal impulse plus the
// speed over the response) for the comparisons of two impulses.
std::string writer::process_scale(std::size_t i, std::size_t j) const
{
    const process_condition &c = f_.cases[i].process_conditions[j];
    switch (c.kind) {
    case process_test::initial_slip:
        return speed_name_;
    case process_test::sticks_at_start:
        return "(" + response_name_ + " * " + response_name_ + ")";
    case process_test::compression_first:
    case process_test::ends_first:
        return "(detail::abs_of(" + names_[i].N + ") + " + speed_name_ + " / " + response_name_ + ")";
    default:
        return response_name_;
    }
}

// After the selection (the closed-form candidates' flags known): the index of the sequence
// selected and whether another of a different closed form holds within rounding.
std::string writer::process_sequence_text(const std::string &ind) const
{
    const candidates_jacobian &cj = cp_.jacobian;
    const std::size_t n = closed_.size();
    const std::string &tol = seq_local_.at("tol"), &near = seq_local_.at("near_sequence"),
                      &form = seq_local_.at("form_of"), &now = seq_local_.at("sequence_now"),
                      &boundary = seq_local_.at("boundary_now"), &k = seq_local_.at("k");
    std::string r = ind + "const T " + tol + " = detail::" + o_.name + "_tolerance<T>();\n";
    r += ind + "const bool " + near + "[" + std::to_string(n) + "] = {\n";
    for (std::size_t i = 0; i < n; ++i) {
        std::vector<std::string> parts;
        for (std::size_t j = 0; j < names_[closed_[i]].cond.size(); ++j)
            parts.push_back(names_[closed_[i]].cond[j] + " >= -" + tol + " * " + process_scale(closed_[i], j));
        r += ind + "    " + (parts.empty() ? std::string("true") : join(parts, " && ")) + ",\n";
    }
    r += ind + "};\n";
    std::vector<std::string> forms;
    for (std::size_t i = 0; i < n; ++i)
        forms.push_back(std::to_string(cj.candidates[closed_[i]].same_as));
    r += ind + "const int " + form + "[" + std::to_string(n) + "] = {" + join(forms, ", ") + "};\n";
    std::string sel = std::to_string(n - 1);
    for (std::size_t i = n - 1; i-- > 0;)
        sel = holds_[i] + " ? " + std::to_string(i) + " : " + sel;
    r += ind + now + " = " + sel + ";\n";
    r += ind + boundary + " = false;\n";
    r += ind + "for (int " + k + " = 0; " + k + " < " + std::to_string(n) + "; ++" + k + ")\n";
    r += ind + "    " + boundary + " = " + boundary + " || (" + near + "[" + k + "] && " + form + "[" + k +
         "] != " + form + "[" + now + "]);\n";
    return r;
}

// ---- a system's sets: NAME reports the set and whether another holds within rounding.

void writer::system_jacobian_form()
{
    named_jacobian_form(sys_local_, "velocities",
                        "the first " + std::to_string(cp_.jacobian.rows.size()) + " of " + o_.name + "_output_names",
                        "velocity", "set's");
    jf_.doc += "\n/// where another set holds within rounding (out.boundary): the impact map is not "
               "differentiable\n/// there; out and jac then hold the selected set's values and its one-sided "
               "derivatives.\n";
    jf_.sqrt_always = true;
    jf_.selector = "out.set";
    for (std::size_t k = 0; k < cp_.jacobian.candidates.size(); ++k)
        jf_.selects.push_back(k);
    build_jacobian_programs({});
    emit_jacobian_programs();
}

} // namespace impactgen::codegen::writer_detail
