// The one header writer (writer.hpp): NAME_jacobian of a header with Coulomb friction under
// Newton's law (rules first_that_holds and sliding_angle, --jacobian).
//
// NAME_jacobian calls NAME (its values, status and regime unchanged), then finds the candidate
// NAME selected from what it returned: stick when out.regime is stick; otherwise the slide whose
// direction is that of the contact's tangential velocity after impact, u'_t = (u + K P)_t with
// P = N n + F the impulse returned (the planar slide along +e_t or -e_t by its sign, the isotropic
// 3-D slide, or the 3-D slide without a closed form at c = u'_t.e_t/|u'_t|, s = u'_t.e_b/|u'_t|, the
// root NAME found). One straight-line program per candidate (its steps, the derivative steps of
// symbolic/friction_jacobian.hpp and its conditions, CSE inside it) runs in a switch. The map is
// not differentiable where a condition of the selected candidate is 0 (a regime boundary): within
// rounding -- |condition| <= eps^(2/3) of its scale, the tolerance NAME merges stick and slide
// with -- the status is ambiguous, out and jac then hold the candidate's values and its
// one-sided derivatives.
#include "writer.hpp"

namespace impactgen::codegen::writer_detail
{

namespace
{

std::string abs_sum(const std::vector<std::string> &terms)
{
    if (terms.empty())
        return "T(0)";
    std::string r;
    for (std::size_t i = 0; i < terms.size(); ++i)
        r += (i ? " + " : "") + std::string("detail::abs_of<T>(") + terms[i] + ")";
    return r;
}

} // namespace

// The names and programs of NAME_jacobian: the selected impulse's slip after impact (stage
// fj_pre_), then per candidate its derivatives and conditions.
void writer::build_candidates_jacobian()
{
    const problem &q = q_;
    const int dim = q.dimension;
    for (const char *suffix : {"_jacobian", "_wrt_count", "_wrt_names", "_jacobian_row_count", "_jacobian_row_names"})
        fj_local_[suffix] = scope_.claim(o_.name + suffix);
    for (const char *nm : {"jac", "status", "k", "candidate", "boundary", "tol", "impulse_scale", "speed_scale",
                           "slip_speed", "friction_size", "c_d", "s_d", "check_sum"})
        fj_local_[nm] = scope_.claim(std::string("j_") + nm);
    // The impulse NAME returned, as inputs of stage fj_pre_: N and the tangential components.
    std::map<ex, std::string, ex_is_less> names = input_ident_;
    symbol selN("j_sel_N");
    std::vector<symbol> selF;
    names[selN] = scope_.claim("j_sel_N");
    for (const code_output &of : outs_)
        if (of.kind == output_value::normal_impulse && !of.tangential)
            fj_sel_.push_back({names[selN], "out." + of.field});
    for (std::size_t k : cp_.tangential) {
        selF.emplace_back("j_sel_F" + std::to_string(selF.size()));
        names[selF.back()] = scope_.claim("j_sel_F_" + q.axes[static_cast<std::size_t>(outs_[k].axis)]);
        fj_sel_.push_back({names[selF.back()], "out." + outs_[k].field});
    }
    fj_pre_.pool.set_input_names(names);
    for (const regime_case &c : f_.cases) // the scales the boundary tests need
        for (const regime_condition &rc : c.conditions) {
            fj_speed_scale_ = fj_speed_scale_ || rc.kind == condition_kind::slides;
            fj_impulse_scale_ = fj_impulse_scale_ ||
                                (rc.kind != condition_kind::slides && rc.kind != condition_kind::slide_denominator);
        }
    for (const step &st : f_.shared.steps)
        fj_pre_.bind_step(st, scope_.claim("j_" + st.sym.get_name()));
    mat3 K = zero_mat();
    for (const step &st : f_.shared.steps)
        if (st.role == step_role::contact_response)
            K[static_cast<std::size_t>(st.row)][static_cast<std::size_t>(st.column)] =
                K[static_cast<std::size_t>(st.column)][static_cast<std::size_t>(st.row)] = st.sym;
    vec3 P = zero_vec(), after = zero_vec();
    for (int a = 0; a < dim; ++a)
        P[static_cast<std::size_t>(a)] =
            selN * d_.n_hat[static_cast<std::size_t>(a)] + selF[static_cast<std::size_t>(a)];
    const vec3 KP = mul(K, P);
    for (int a = 0; a < dim; ++a) {
        const auto i = static_cast<std::size_t>(a);
        const ex u = d_.vB[i] - d_.vA[i];
        after[i] = u + KP[i];
        if (!fj_speed_scale_)
            continue;
        fj_speed_.push_back(scope_.claim("j_u_" + q.axes[i]));
        fj_pre_.output(fj_speed_.back(), u);
    }
    vec3 F = zero_vec();
    for (int a = 0; a < dim; ++a)
        F[static_cast<std::size_t>(a)] = selF[static_cast<std::size_t>(a)];
    fj_slip_.push_back(scope_.claim("j_slip_t"));
    fj_pre_.output(fj_slip_.back(), dot(after, d_.e_t));
    const bool friction_read = dim == 2 || angle_ >= 0; // (the isotropic slide is the one slide)
    if (friction_read) {
        fj_friction_.push_back(scope_.claim("j_friction_t"));
        fj_pre_.output(fj_friction_.back(), dot(F, d_.e_t));
    }
    if (dim == 3) {
        fj_slip_.push_back(scope_.claim("j_slip_b"));
        fj_pre_.output(fj_slip_.back(), dot(after, d_.e_b));
    }
    if (dim == 3 && friction_read) {
        fj_friction_.push_back(scope_.claim("j_friction_b"));
        fj_pre_.output(fj_friction_.back(), dot(F, d_.e_b));
    }
    if (fj_impulse_scale_) {
        fj_mu_ = scope_.claim("j_mu");
        fj_pre_.output(fj_mu_, q.contact().friction());
    }
    for (std::size_t k = 0; k < f_.cases.size(); ++k)
        build_candidate_jacobian_stage(k);
    emit_options locals;
    locals.outputs = output_placement::local;
    fj_pre_.em = emit_cpp(fj_pre_.prog, fj_pre_.outs, {}, fj_pre_.names, scope_.names(), locals);
    for (const std::string &nm : fj_pre_.em.declared)
        if (!scope_.taken(nm))
            scope_.claim(nm);
    for (stage &st : fj_stages_) {
        st.em = emit_cpp(st.prog, st.outs, {}, st.names, scope_.names(), locals);
        for (const std::string &nm : st.em.declared)
            if (!scope_.taken(nm))
                scope_.claim(nm);
    }
}

// Candidate k's program: its steps, the derivative steps, the entries and the conditions (c and s
// of the slide without a closed form read as the locals of the selection).
void writer::build_candidate_jacobian_stage(std::size_t k)
{
    const candidates_jacobian &cj = cp_.jacobian;
    const std::size_t nw = cj.wrt.size();
    const regime_case &c = f_.cases[k];
    const regime_jacobian &r = cj.jac.regimes[k];
    const std::string pre = "j" + std::to_string(k) + "_";
    stage st;
    std::map<ex, std::string, ex_is_less> in = input_ident_;
    if (c.needs_angle) {
        in[c.dir_c] = fj_local_.at("c_d");
        in[c.dir_s] = fj_local_.at("s_d");
    }
    st.pool.set_input_names(in);
    for (const step &s : c.sol.steps)
        st.bind_step(s, scope_.claim(pre + s.sym.get_name()));
    for (const step &s : cj.jac.derivative_steps)
        st.bind_step(s, scope_.claim(pre + s.sym.get_name()));
    for (const step &s : r.derivative_steps)
        st.bind_step(s, scope_.claim(pre + s.sym.get_name()));
    std::vector<std::string> entries, conds;
    for (std::size_t i = 0; i < cj.rows.size(); ++i)
        for (std::size_t w = 0; w < nw; ++w) {
            entries.push_back(scope_.claim(pre + "d_" + outs_[cj.rows[i]].field + "_d_" + input_ident_.at(cj.wrt[w])));
            st.output(entries.back(), r.entries[i][w]);
        }
    for (std::size_t j = 0; j < c.conditions.size(); ++j) {
        if (c.conditions[j].kind == condition_kind::slide_denominator) { // (no boundary: see below)
            conds.emplace_back();
            continue;
        }
        conds.push_back(scope_.claim(pre + "cond" + std::to_string(j + 1)));
        st.output(conds.back(), c.conditions[j].value);
    }
    fj_entries_.push_back(entries);
    fj_conds_.push_back(conds);
    fj_stages_.push_back(std::move(st));
}

// Which candidate NAME selected, as C++ statements setting j_candidate (and j_boundary where the
// slip after impact is 0 although NAME found a slide: on the stick/slide boundary).
std::string writer::candidates_jacobian_selection() const
{
    const std::string &cand = fj_local_.at("candidate"), &bd = fj_local_.at("boundary"),
                      &speed = fj_local_.at("slip_speed"), &cd = fj_local_.at("c_d"), &sd = fj_local_.at("s_d");
    int stick = -1, pos = -1, neg = -1, iso = -1;
    for (std::size_t k = 0; k < f_.cases.size(); ++k) {
        const regime_case &c = f_.cases[k];
        const int i = static_cast<int>(k);
        if (c.kind == regime::stick)
            stick = i;
        else if (i == angle_)
            continue;
        else if (c.sign > 0)
            pos = i;
        else if (c.sign < 0)
            neg = i;
        else
            iso = i;
    }
    // The sliding direction: against the friction impulse where there is one (the root NAME found,
    // exactly), else (mu = 0) along the slip after impact.
    std::string r;
    const bool three = q_.dimension == 3;
    const std::string &fs = fj_local_.at("friction_size");
    auto size = [&](const std::vector<std::string> &v) {
        return three ? "sqrt(" + v[0] + " * " + v[0] + " + " + v[1] + " * " + v[1] + ")"
                     : "detail::abs_of<T>(" + v[0] + ")";
    };
    r += "    const T " + speed + " = " + size(fj_slip_) + ";\n";
    if (angle_ >= 0 || !three)
        r += "    const T " + fs + " = " + size(fj_friction_) + ";\n";
    if (angle_ >= 0)
        r += "    const T " + cd + " = " + fs + " > T(0) ? -" + fj_friction_[0] + " / " + fs + " : " + speed +
             " > T(0) ? " + fj_slip_[0] + " / " + speed + " : T(1);\n" + "    const T " + sd + " = " + fs +
             " > T(0) ? -" + fj_friction_[1] + " / " + fs + " : " + speed + " > T(0) ? " + fj_slip_[1] + " / " + speed +
             " : T(0);\n";
    const std::string slide = three ? std::to_string(iso >= 0 ? iso : angle_)
                                    : "(" + fs + " > T(0) ? " + fj_friction_[0] + " < T(0) : " + fj_slip_[0] +
                                          " > T(0)) ? " + std::to_string(pos) + " : " + std::to_string(neg);
    r += "    int " + cand + " = " + slide + ";\n";
    r += "    bool " + bd + " = false;\n";
    if (stick >= 0) {
        r += "    if (out.regime == impact_regime::stick || !(" + speed + " > T(0))) {\n";
        r += "        " + bd + " = out.regime != impact_regime::stick; // no slip: stick and slide are one answer\n";
        r += "        " + cand + " = " + std::to_string(stick) + ";\n    }\n";
    } else {
        r += "    " + bd + " = !(" + speed + " > T(0)); // no slip after impact: a boundary between the slides\n";
    }
    return r;
}

// The boundary test of candidate k's conditions: |condition| <= tol times its scale (an impulse
// condition: (1 + |mu|) times the impulse's size, squared for the cone's; the sliding speed: the
// contact's speed before impact). D_s > 0 is no boundary: N grows without bound as D_s -> 0.
std::string writer::candidates_jacobian_boundary(std::size_t k) const
{
    const regime_case &c = f_.cases[k];
    const std::string &bd = fj_local_.at("boundary"), &tol = fj_local_.at("tol"), &is = fj_local_.at("impulse_scale"),
                      &vs = fj_local_.at("speed_scale");
    std::string r;
    for (std::size_t j = 0; j < c.conditions.size(); ++j) {
        std::string scale;
        switch (c.conditions[j].kind) {
        case condition_kind::slide_denominator:
            continue;
        case condition_kind::slides:
            scale = vs;
            break;
        case condition_kind::cone:
            scale = is + " * " + is;
            break;
        default:
            scale = is;
            break;
        }
        r += "        " + bd + " = " + bd + " || detail::abs_of<T>(" + fj_conds_[k][j] + ") <= " + tol + " * " + scale +
             ";\n";
    }
    return r;
}

void writer::candidates_jacobian_function()
{
    const candidates_jacobian &cj = cp_.jacobian;
    if (!cj.on)
        return;
    const std::size_t nw = cj.wrt.size(), nr = cj.rows.size();
    const std::string &fn = fj_local_.at("_jacobian"), &jac = fj_local_.at("jac"), &status = fj_local_.at("status"),
                      &k = fj_local_.at("k"), &cand = fj_local_.at("candidate"), &bd = fj_local_.at("boundary"),
                      &tol = fj_local_.at("tol"), &sum = fj_local_.at("check_sum");
    h_ << "inline constexpr int " << fj_local_.at("_wrt_count") << " = " << nw << ";\n";
    h_ << "/// The inputs " << fn << " differentiates by, in the order of its columns.\n";
    h_ << "inline constexpr const char* " << fj_local_.at("_wrt_names") << "[] = {";
    for (const symbol &x : cj.wrt)
        h_ << names::cpp_string_literal(input_ident_.at(x)) << ", ";
    h_ << "nullptr};\n";
    h_ << "inline constexpr int " << fj_local_.at("_jacobian_row_count") << " = " << nr << ";\n";
    h_ << "/// The outputs " << fn << " differentiates (velocities, spins and impulses after impact), the rows.\n";
    h_ << "inline constexpr const char* " << fj_local_.at("_jacobian_row_names") << "[] = {";
    for (std::size_t i : cj.rows)
        h_ << names::cpp_string_literal(outs_[i].field) << ", ";
    h_ << "nullptr};\n\n";
    h_ << "/// " << o_.name << " and the Jacobian of its velocities and impulses after impact by the inputs\n";
    h_ << "/// " << fj_local_.at("_wrt_names") << ": " << jac << "[i * " << nw << " + j] = d("
       << fj_local_.at("_jacobian_row_names") << "[i])/d(input j), the selected regime's\n";
    h_ << "/// closed form differentiated exactly (the 3-D slide without a closed form through the implicit\n";
    h_ << "/// function theorem of its angle equation). Returns the status of " << o_.name << " (jac zero unless\n";
    h_ << "/// ok); ambiguous where the input lies on a regime boundary within rounding (a condition of the\n";
    h_ << "/// regime within eps^(2/3) of 0): the impact map is not differentiable there, out and jac then hold\n";
    h_ << "/// the regime's values and its one-sided derivatives; overflow where a derivative is not finite\n";
    h_ << "/// (at a double root of the angle equation the sliding direction's derivative is unbounded).\n";
    h_ << "/// mu = 0 (regime smooth): the derivatives of the slide, by mu one-sided (mu >= 0).\n";
    h_ << "template <typename T>\nIMPACTGEN_FUNC friction_status " << fn << "(" << params() << result()
       << "<T>& out, T* " << jac << ") noexcept\n{\n";
    h_ << "    const friction_status " << status << " = " << o_.name << "<T>(" << args() << "out);\n";
    h_ << "    for (int " << k << " = 0; " << k << " < " << nr * nw << "; ++" << k << ")\n        " << jac << "[" << k
       << "] = T(0);\n";
    h_ << "    if (" << status << " != friction_status::ok)\n        return " << status << ";\n";
    h_ << "    using std::sqrt;\n";
    bool trig = fj_pre_.em.uses_trig || nb_.em.uses_trig;
    for (const stage &st : fj_stages_)
        trig = trig || st.em.uses_trig;
    if (trig)
        h_ << "    using std::cos;\n    using std::sin;\n";
    h_ << basis_text();
    for (const auto &[local, field] : fj_sel_)
        h_ << "    const T " << local << " = " << field << ";\n";
    h_ << "    // The slip after impact for the impulse returned: which candidate it is.\n";
    h_ << fj_pre_.em.code;
    h_ << candidates_jacobian_selection();
    std::vector<std::string> impulse;
    for (const auto &[local, field] : fj_sel_)
        impulse.push_back(local);
    h_ << "    const T " << tol << " = detail::boundary_tolerance<T>();\n";
    if (fj_impulse_scale_)
        h_ << "    const T " << fj_local_.at("impulse_scale") << " = (T(1) + detail::abs_of<T>(" << fj_mu_ << ")) * ("
           << abs_sum(impulse) << ");\n";
    if (fj_speed_scale_)
        h_ << "    const T " << fj_local_.at("speed_scale") << " = " << abs_sum(fj_speed_) << ";\n";
    h_ << "    switch (" << cand << ") {\n";
    for (std::size_t c = 0; c < fj_stages_.size(); ++c) {
        h_ << "    case " << c << ": { // " << names::comment_text(f_.cases[c].name) << "\n"
           << indent(fj_stages_[c].em.code, "    ");
        for (std::size_t i = 0; i < fj_entries_[c].size(); ++i)
            h_ << "        " << jac << "[" << i << "] = " << fj_entries_[c][i] << ";\n";
        h_ << candidates_jacobian_boundary(c);
        h_ << "        break;\n    }\n";
    }
    h_ << "    default:\n        break;\n    }\n";
    h_ << "    T " << sum << " = T(0);\n";
    h_ << "    for (int " << k << " = 0; " << k << " < " << nr * nw << "; ++" << k << ")\n        " << sum << " = "
       << sum << " + " << jac << "[" << k << "];\n";
    h_ << "    if (!detail::finite<T>(" << sum << ")) {\n";
    h_ << "        for (int " << k << " = 0; " << k << " < " << nr * nw << "; ++" << k << ")\n            " << jac
       << "[" << k << "] = T(0);\n";
    h_ << "        return friction_status::overflow;\n    }\n";
    h_ << "    return " << bd << " ? friction_status::ambiguous : friction_status::ok;\n}\n\n";
    h_ << "/// " << fn << " with the inputs in an array, in the order of " << o_.name << "_input_names.\n";
    h_ << "template <typename T>\nIMPACTGEN_FUNC friction_status " << fn << "(const T* in, " << result()
       << "<T>& out, T* " << jac << ") noexcept\n{\n    return " << fn << "<T>(";
    for (std::size_t i = 0; i < input_names_.size(); ++i)
        h_ << "in[" << i << "], ";
    h_ << "out, " << jac << ");\n}\n\n";
}

} // namespace impactgen::codegen::writer_detail
