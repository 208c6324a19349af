// The one header writer (writer.hpp): the part of NAME_jacobian (writer_jacobian.cpp) that is
// Coulomb friction's under Newton's law (rules first_that_holds and sliding_angle, --jacobian).
//
// NAME_jacobian calls NAME (its values, status and regime unchanged), then finds the candidate
// NAME selected from what it returned: stick when out.regime is stick; otherwise the slide whose
// direction is that of the contact's tangential velocity after impact, u'_t = (u + K P)_t with
// P = N n + F the impulse returned (the planar slide along +e_t or -e_t by its sign, the isotropic
// 3-D slide, or the 3-D slide without a closed form at c = u'_t.e_t/|u'_t|, s = u'_t.e_b/|u'_t|, the
// root NAME found). One straight-line program per candidate (its steps, the derivative steps of
// symbolic/friction_jacobian.hpp and its conditions) runs in a switch. The map is
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

// The names of NAME_jacobian and the program of the selected impulse's slip after impact (fj_pre_).
void writer::friction_jacobian_pre()
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
}

// The form: the candidates' programs with their conditions (the entries by the one writer), the
// selection of the candidate from the impulse returned, the boundary tests, the overflow check.
void writer::friction_jacobian_form()
{
    friction_jacobian_pre();
    jf_.program_prefix = "j";
    jf_.angle_c = fj_local_.at("c_d");
    jf_.angle_s = fj_local_.at("s_d");
    build_jacobian_programs([this](std::size_t k, stage &st) {
        const regime_case &c = f_.cases[k];
        std::vector<std::string> conds;
        for (std::size_t j = 0; j < c.conditions.size(); ++j) {
            if (c.conditions[j].kind == condition_kind::slide_denominator) { // (no boundary: see below)
                conds.emplace_back();
                continue;
            }
            conds.push_back(scope_.claim("j" + std::to_string(k) + "_cond" + std::to_string(j + 1)));
            st.output(conds.back(), c.conditions[j].value);
        }
        fj_conds_.push_back(conds);
    });
    emit_options locals;
    locals.outputs = output_placement::local;
    emit_one(fj_pre_, locals, false);
    emit_jacobian_programs();
    friction_jacobian_text();
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

// The names, comment and texts of NAME_jacobian around the candidates' programs.
void writer::friction_jacobian_text()
{
    const candidates_jacobian &cj = cp_.jacobian;
    const std::size_t nw = cj.wrt.size();
    jf_.fn = fj_local_.at("_jacobian");
    jf_.wrt_count = fj_local_.at("_wrt_count");
    jf_.wrt_names = fj_local_.at("_wrt_names");
    jf_.wrt_comment = "The inputs " + jf_.fn + " differentiates by, in the order of its columns.";
    jf_.row_count = fj_local_.at("_jacobian_row_count");
    jf_.row_names = fj_local_.at("_jacobian_row_names");
    jf_.row_comment =
        "The outputs " + jf_.fn + " differentiates (velocities, spins and impulses after impact), the rows.";
    jf_.jac = fj_local_.at("jac");
    jf_.status = fj_local_.at("status");
    jf_.k = fj_local_.at("k");
    std::ostringstream doc;
    doc << "/// " << o_.name << " and the Jacobian of its velocities and impulses after impact by the inputs\n";
    doc << "/// " << jf_.wrt_names << ": " << jf_.jac << "[i * " << nw << " + j] = d(" << jf_.row_names
        << "[i])/d(input j), the selected regime's\n";
    doc << "/// closed form differentiated exactly (the 3-D slide without a closed form through the implicit\n";
    doc << "/// function theorem of its angle equation). Returns the status of " << o_.name << " (jac zero unless\n";
    doc << "/// ok); ambiguous where the input lies on a regime boundary within rounding (a condition of the\n";
    doc << "/// regime within eps^(2/3) of 0): the impact map is not differentiable there, out and jac then hold\n";
    doc << "/// the regime's values and its one-sided derivatives; overflow where a derivative is not finite\n";
    doc << "/// (at a double root of the angle equation the sliding direction's derivative is unbounded).\n";
    doc << "/// mu = 0 (regime smooth): the derivatives of the slide, by mu one-sided (mu >= 0).\n";
    jf_.doc = doc.str();
    jf_.sqrt_always = true;
    jf_.trig = fj_pre_.em.uses_trig || nb_.em.uses_trig;
    std::string select = basis_text();
    std::vector<std::string> impulse;
    for (const auto &[local, field] : fj_sel_) {
        select += "    const T " + local + " = " + field + ";\n";
        impulse.push_back(local);
    }
    select += "    // The slip after impact for the impulse returned: which candidate it is.\n";
    select += fj_pre_.em.code + candidates_jacobian_selection();
    select += "    const T " + fj_local_.at("tol") + " = detail::boundary_tolerance<T>();\n";
    if (fj_impulse_scale_)
        select += "    const T " + fj_local_.at("impulse_scale") + " = (T(1) + detail::abs_of<T>(" + fj_mu_ + ")) * (" +
                  abs_sum(impulse) + ");\n";
    if (fj_speed_scale_)
        select += "    const T " + fj_local_.at("speed_scale") + " = " + abs_sum(fj_speed_) + ";\n";
    jf_.select = select;
    jf_.selector = fj_local_.at("candidate");
    for (std::size_t k = 0; k < f_.cases.size(); ++k)
        jf_.selects.push_back(k);
    jf_.case_names = true;
    jf_.case_tail = [this](std::size_t k) { return candidates_jacobian_boundary(k); };
    const std::string &sum = fj_local_.at("check_sum"), &k = jf_.k, &jac = jf_.jac,
                      n = std::to_string(cj.rows.size() * nw);
    jf_.after_switch = "    T " + sum + " = T(0);\n    for (int " + k + " = 0; " + k + " < " + n + "; ++" + k +
                       ")\n        " + sum + " = " + sum + " + " + jac + "[" + k + "];\n    if (!detail::finite<T>(" +
                       sum + ")) {\n        for (int " + k + " = 0; " + k + " < " + n + "; ++" + k + ")\n            " +
                       jac + "[" + k + "] = T(0);\n        return friction_status::overflow;\n    }\n";
    jf_.boundary = fj_local_.at("boundary");
    jf_.array_form = true;
}

} // namespace impactgen::codegen::writer_detail
