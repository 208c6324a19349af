// The one header writer (writer.hpp): --jacobian under Routh's process (rule process). The
// function selects its phase sequence as without --jacobian and also reports which one
// (out.sequence) and whether another sequence with a different closed form holds within
// rounding (out.boundary: the impact map is continuous there but in general not
// differentiable). NAME_jacobian then computes the selected sequence's derivatives, each
// sequence's closed form differentiated exactly through the contact's steps
// (symbolic/process_jacobian.hpp, the machinery of `formulas --jacobian`), as a system's
// header does for its candidate sets (writer_system.cpp).
#include "writer.hpp"

namespace impactgen::codegen::writer_detail
{

bool writer::process_jacobian() const
{
    return cp_.rule == selection_rule::process && cp_.process.has_jacobian;
}

// The names of the selection's locals and of the Jacobian's entries; one stage per distinct
// closed form (the steps bound unscaled, then the derivative steps, then the entries).
void writer::build_process_jacobian()
{
    const process_code &pc = cp_.process;
    for (const char *nm : {"sequence_now", "boundary_now", "near_sequence", "form_of", "tol", "jac", "status", "k"})
        seq_local_[nm] = scope_.claim(nm);
    std::vector<std::string> step_names;
    for (const step &st : pc.steps)
        step_names.push_back(scope_.claim(st.sym.get_name()));
    for (std::size_t k : pc.outputs)
        for (const symbol &x : pc.wrt)
            seq_jac_names_.push_back(scope_.claim("d_" + outs_[k].field + "_d_" + input_ident_.at(x)));
    seq_jac_.resize(pc.jacobian.size());
    emit_options locals;
    locals.outputs = output_placement::local;
    for (std::size_t c = 0; c < pc.jacobian.size(); ++c) {
        if (pc.same_as[c] != c)
            continue;
        stage &st = seq_jac_[c];
        st.pool.set_input_names(input_ident_);
        for (std::size_t i = 0; i < pc.steps.size(); ++i)
            st.bind_step(pc.steps[i], step_names[i]);
        for (std::size_t i = 0; i < pc.outputs.size(); ++i)
            for (std::size_t w = 0; w < pc.wrt.size(); ++w)
                st.output(seq_jac_names_[i * pc.wrt.size() + w], pc.jacobian[c][i][w]);
        emit_one(st, locals);
    }
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
    const process_code &pc = cp_.process;
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
        forms.push_back(std::to_string(pc.same_as[closed_[i]]));
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

// NAME_jacobian: NAME, then the derivatives of the selected sequence's outputs.
void writer::process_jacobian_function()
{
    const process_code &pc = cp_.process;
    const std::size_t nw = pc.wrt.size(), no = pc.outputs.size();
    const std::string &jac = seq_local_.at("jac"), &status = seq_local_.at("status"), &k = seq_local_.at("k");
    h_ << "inline constexpr int " << o_.name << "_wrt_count = " << nw << ";\n";
    h_ << "/// The inputs the Jacobian differentiates by, in the order of its columns.\n";
    h_ << "inline constexpr const char* " << o_.name << "_wrt_names[] = {";
    for (const symbol &x : pc.wrt)
        h_ << names::cpp_string_literal(input_ident_.at(x)) << ", ";
    h_ << "nullptr};\n";
    h_ << "inline constexpr int " << o_.name << "_jacobian_output_count = " << no << ";\n";
    h_ << "/// The outputs the Jacobian differentiates, in the order of its rows (members of " << result() << ").\n";
    h_ << "inline constexpr const char* " << o_.name << "_jacobian_output_names[] = {";
    for (std::size_t i : pc.outputs)
        h_ << names::cpp_string_literal(outs_[i].field) << ", ";
    h_ << "nullptr};\n\n";
    h_ << "/// " << o_.name << " and the Jacobian of the velocities and impulses after impact (" << o_.name
       << "_jacobian_output_names)\n";
    h_ << "/// by the inputs " << o_.name << "_wrt_names: " << jac << "[i * " << nw
       << " + j] = d(output i)/d(input j), the selected phase sequence's\n";
    h_ << "/// closed form differentiated exactly. Returns the status of " << o_.name
       << " (jac zero unless ok), or ambiguous where\n";
    h_ << "/// the impact map is not differentiable (out.boundary): another phase sequence with a different\n";
    h_ << "/// closed form holds within rounding (out and jac then hold the selected sequence's values and\n";
    h_ << "/// its one-sided derivatives), or mu = 0, the edge of mu's domain (the smooth impact; jac zero).\n";
    h_ << "template <typename T>\nIMPACTGEN_FUNC friction_status " << o_.name << "_jacobian(" << params() << result()
       << "<T>& out, T* " << jac << ") noexcept\n{\n";
    h_ << "    const friction_status " << status << " = " << o_.name << "<T>(" << args() << "out);\n";
    h_ << "    for (int " << k << " = 0; " << k << " < " << no * nw << "; ++" << k << ")\n        " << jac << "[" << k
       << "] = T(0);\n";
    h_ << "    if (" << status << " != friction_status::ok)\n        return " << status << ";\n";
    bool sq = false, trig = false;
    for (const stage &st : seq_jac_) {
        sq = sq || st.em.uses_sqrt;
        trig = trig || st.em.uses_trig;
    }
    h_ << (sq ? "    using std::sqrt;\n" : "") << (trig ? "    using std::cos;\n    using std::sin;\n" : "");
    h_ << "    switch (out.sequence) {\n";
    for (std::size_t c = 0; c < seq_jac_.size(); ++c) {
        if (pc.same_as[c] != c)
            continue;
        for (std::size_t i = 0; i < closed_.size(); ++i)
            if (pc.same_as[closed_[i]] == c)
                h_ << "    case " << i << ":\n";
        h_ << "    {\n" << indent(seq_jac_[c].em.code, "    ");
        for (std::size_t i = 0; i < seq_jac_names_.size(); ++i)
            h_ << "        " << jac << "[" << i << "] = " << seq_jac_names_[i] << ";\n";
        h_ << "        break;\n    }\n";
    }
    h_ << "    default:\n        break;\n    }\n";
    h_ << "    return out.boundary ? friction_status::ambiguous : friction_status::ok;\n}\n\n";
}

} // namespace impactgen::codegen::writer_detail
