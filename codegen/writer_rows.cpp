// The one header writer (writer.hpp), option --rows: the contact's rows for an iterative
// (sequential-impulse) solver, NAME_rows. For each direction d of the contact (the unit
// normal n; the tangent t = (n_y, -n_x) in the plane, or the unit tangents t, b of a
// branch-free basis of n in 3-D) the Jacobian row of the relative velocity u.d = J_d V,
// V = (v_1, w_1, v_2, w_2): (-d, -r_1 x d, d, r_2 x d) with r_i = r_{Ci O} = O - C_i, the
// effective mass 1 / (d.K d) = 1 / (1/m_1 + 1/m_2 + (r_1 x d).I_1^{-1} (r_1 x d) + (r_2 x d).I_2^{-1}
// (r_2 x d)) (0 where no body can move along d), the velocity u.d before impact, and the
// velocity bias of restitution -e u_n (Newton's law: the normal velocity after impact). The
// inverse masses and world inverse inertia are given too, so that a solver applies an impulse
// lambda along d as v_1 -= lambda d / m_1, w_1 -= lambda I_1^{-1} (r_1 x d), v_2 += ..., w_2 += ....
// The primitive values (inverse masses and inertia, C_i, O, the unit normal, velocities, e)
// are one straight-line program of the header's inputs; the rows are plain arithmetic on them.
#include "writer.hpp"

#include <cctype>

namespace impactgen::codegen::writer_detail
{

// The primitive values of the rows, as outputs of the stage rows_ (locals rw_*).
void writer::build_rows()
{
    if (!o_.rows)
        return;
    const problem &q = straight() ? pl_.prob : q_;
    if (!q.pivots.empty())
        throw option_error(option_error::rows, "a body on a pivot has no contact rows of its own (the pivot is a "
                                               "constraint of the solver): --rows needs free bodies");
    const int dim = q.dimension;
    rows_.pool.set_input_names(input_ident_);
    auto inverse = [&](const ex &x) -> ex {
        auto it = pl_.inverse_of.find(x);
        return it == pl_.inverse_of.end() ? ex(1 / x) : ex(it->second);
    };
    auto out = [&](const std::string &key, const ex &e) {
        rows_name_[key] = scope_.claim("rw_" + key);
        rows_.output(rows_name_[key], e);
    };
    const std::size_t ids[2] = {q.contact().body1, q.contact().body2};
    for (int k = 0; k < 2; ++k) {
        const body &b = q.bodies[ids[k]];
        const std::string s = std::to_string(k + 1);
        out("inv_m" + s, b.infinite_mass ? ex(0) : inverse(b.mass));
        mat3 J = zero_mat();
        if (!b.infinite_mass && !b.particle && dim == 2) {
            J[2][2] = inverse(b.inertia[2][2]);
        } else if (!b.infinite_mass && !b.particle) {
            auto inv = pl_.inverse_tensor.find(ids[k]);
            if (inv != pl_.inverse_tensor.end()) {
                J = inv->second;
            } else {
                matrix m(3, 3);
                for (unsigned r = 0; r < 3; ++r)
                    for (unsigned c = 0; c < 3; ++c)
                        m(r, c) = b.inertia[r][c];
                const matrix mi = m.inverse();
                for (unsigned r = 0; r < 3; ++r)
                    for (unsigned c = 0; c < 3; ++c)
                        J[r][c] = normal(mi(r, c));
            }
        }
        if (dim == 2)
            out("inv_I" + s + "_0", J[2][2]);
        else
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    out("inv_I" + s + "_" + std::to_string(3 * r + c), J[r][c]);
        for (int c = 0; c < dim; ++c) {
            out("C" + s + "_" + std::to_string(c), b.position[c]);
            out("v" + s + "_" + std::to_string(c), b.velocity[c]);
        }
        for (int c = dim == 2 ? 2 : 0; c < 3; ++c)
            out("w" + s + "_" + std::to_string(dim == 2 ? 0 : c), b.angular_velocity[c]);
    }
    const vec3 &n = q.contact().normal;
    const bool unit = straight() ? pl_.deriv.normal_assumed_unit : d_.normal_assumed_unit;
    ex len = 1;
    if (!unit) {
        ex nn = 0;
        for (int c = 0; c < dim; ++c)
            nn += n[c] * n[c];
        len = sqrt(tidy(nn));
    }
    for (int c = 0; c < dim; ++c) {
        out("O_" + std::to_string(c), q.contact().point[c]);
        out("n_" + std::to_string(c), n[c] / len);
    }
    out("e", q.restitution);
    emit_options locals;
    locals.outputs = output_placement::local;
    rows_.em = emit_cpp(rows_.prog, rows_.outs, {}, {}, scope_.names(), locals);
}
// The row and rows structs.
void writer::rows_structs()
{
    const int dim = (straight() ? pl_.prob : q_).dimension, A = dim == 2 ? 1 : 3;
    const std::string D = std::to_string(dim), As = std::to_string(A), row = o_.name + "_row",
                      res = o_.name + "_rows_result";
    h_ << "/// One row of the contact for a sequential-impulse solver: the relative velocity along the\n"
       << "/// unit direction dir is u.dir = J V with J = (-dir, -ang1, dir, ang2), V = (v_1, w_1, v_2, w_2).\n"
       << "template <typename T> struct " << row << " {\n"
       << "    T dir[" << D << "];  ///< unit direction, world axes (the normal: from body 1 into body 2)\n"
       << "    T ang1[" << As << "]; ///< r_1 x dir, r_1 = r_{C1 O} = O - C_1 (body 1's angular part, with -)\n"
       << "    T ang2[" << As << "]; ///< r_2 x dir, r_2 = r_{C2 O} = O - C_2 (body 2's angular part)\n"
       << "    T effective_mass; ///< 1 / (dir.K dir); 0 where no body can move along dir\n"
       << "    T velocity;       ///< u.dir before impact, u = v_B - v_A of the contact points\n"
       << "};\n\n";
    h_ << "/// The rows of the contact of " << o_.name << ": the normal, the tangent" << (dim == 3 ? "s" : "")
       << ", the bias of restitution,\n"
       << "/// the bodies' inverse masses and world inverse inertia.\n"
       << "template <typename T> struct " << res << " {\n"
       << "    " << row << "<T> normal;\n"
       << "    " << row << "<T> tangent[" << dim - 1 << "]; ///< "
       << (dim == 2 ? "t = (n_y, -n_x)" : "t, b: a branch-free unit basis of the plane, t x b = n") << "\n"
       << "    T bias; ///< -e u_n: the normal velocity after impact by Newton's law\n"
       << "    T inv_m1, inv_m2; ///< inverse masses (0: infinite mass)\n"
       << "    T inv_I1[" << A * A << "], inv_I2[" << A * A
       << "]; ///< world inverse inertia, row-major (0: no rotation)\n"
       << "};\n\n";
}

// The body of NAME_rows (after its signature), its locals named clear of the inputs.
std::string writer::rows_body()
{
    const int dim = (straight() ? pl_.prob : q_).dimension, A = dim == 2 ? 1 : 3;
    const std::string D = std::to_string(dim), As = std::to_string(A), row = o_.name + "_row",
                      res = o_.name + "_rows_result";
    auto R = [&](const std::string &key) { return rows_name_.at(key); };
    auto list = [&](const std::string &key, int count) {
        std::vector<std::string> items;
        for (int c = 0; c < count; ++c)
            items.push_back(R(key + "_" + std::to_string(c)));
        return "{" + join(items, ", ") + "}";
    };
    std::ostringstream f; // the body, with @name for the locals named below
    if (rows_.em.uses_sqrt)
        f << "    using std::sqrt;\n";
    f << "    out = " << res << "<T>{}; // zero where a status other than ok returns early\n";
    if (!input_names_.empty())
        f << "    if (!detail::all_finite(" << join(input_names_, ", ") << "))\n"
          << "        return impact_status::non_finite_input;\n";
    f << rows_.em.code;
    f << "    const T @n[" << D << "] = " << list("n", dim) << ";\n";
    f << "    if (!detail::all_finite(" << R("n_0") << ", " << R("n_1") << (dim == 3 ? ", " + R("n_2") : std::string())
      << "))\n"
      << "        return impact_status::invalid_normal;\n";
    for (int k = 1; k <= 2; ++k) {
        const std::string s = std::to_string(k);
        std::vector<std::string> r;
        for (int c = 0; c < dim; ++c)
            r.push_back(R("O_" + std::to_string(c)) + " - " + R("C" + s + "_" + std::to_string(c)));
        f << "    const T @r" << s << "[" << D << "] = {" << join(r, ", ") << "}; // r_{C" << s << " O} = O - C_" << s
          << "\n";
        f << "    const T @v" << s << "[" << D << "] = " << list("v" + s, dim) << ";\n";
        f << "    const T @w" << s << "[" << As << "] = " << list("w" + s, A) << ";\n";
        f << "    out.inv_m" << s << " = " << R("inv_m" + s) << ";\n";
        for (int c = 0; c < A * A; ++c)
            f << "    out.inv_I" << s << "[" << c << "] = " << R("inv_I" + s + "_" + std::to_string(c)) << ";\n";
    }
    f << "    auto @fill = [&](const T* @d, " << row << "<T>& @rw) {\n";
    f << "        T @k = out.inv_m1 + out.inv_m2, @u = T(0);\n";
    f << "        for (int @c = 0; @c < " << D << "; ++@c) {\n"
      << "            @rw.dir[@c] = @d[@c];\n"
      << "            @u += @d[@c] * (@v2[@c] - @v1[@c]);\n"
      << "        }\n";
    if (dim == 2) {
        f << "        @rw.ang1[0] = @r1[0] * @d[1] - @r1[1] * @d[0];\n"
          << "        @rw.ang2[0] = @r2[0] * @d[1] - @r2[1] * @d[0];\n"
          << "        @k += @rw.ang1[0] * out.inv_I1[0] * @rw.ang1[0] + @rw.ang2[0] * out.inv_I2[0] * @rw.ang2[0];\n"
          << "        @u += @rw.ang2[0] * @w2[0] - @rw.ang1[0] * @w1[0];\n";
    } else {
        f << "        for (int @c = 0; @c < 3; ++@c) {\n"
          << "            const int @i = (@c + 1) % 3, @j = (@c + 2) % 3;\n"
          << "            @rw.ang1[@c] = @r1[@i] * @d[@j] - @r1[@j] * @d[@i];\n"
          << "            @rw.ang2[@c] = @r2[@i] * @d[@j] - @r2[@j] * @d[@i];\n"
          << "        }\n"
          << "        for (int @i = 0; @i < 3; ++@i) {\n"
          << "            for (int @j = 0; @j < 3; ++@j)\n"
          << "                @k += @rw.ang1[@i] * out.inv_I1[3 * @i + @j] * @rw.ang1[@j] + @rw.ang2[@i] * "
             "out.inv_I2[3 * @i "
             "+ @j] * @rw.ang2[@j];\n"
          << "            @u += @rw.ang2[@i] * @w2[@i] - @rw.ang1[@i] * @w1[@i];\n"
          << "        }\n";
    }
    f << "        @rw.effective_mass = @k > T(0) ? T(1) / @k : T(0);\n"
      << "        @rw.velocity = @u;\n"
      << "    };\n";
    f << "    @fill(@n, out.normal);\n";
    if (dim == 2) {
        f << "    const T @t[2] = {@n[1], -@n[0]};\n    @fill(@t, out.tangent[0]);\n";
    } else {
        f << "    // The branch-free unit basis of the plane normal to n (continuous except across n_z = 0).\n"
          << "    const T @sgn = @n[2] >= T(0) ? T(1) : T(-1);\n"
          << "    const T @a = T(-1) / (@sgn + @n[2]);\n"
          << "    const T @p = @n[0] * @n[1] * @a;\n"
          << "    const T @t[3] = {T(1) + @sgn * @n[0] * @n[0] * @a, @sgn * @p, -@sgn * @n[0]};\n"
          << "    const T @b[3] = {@p, @sgn + @n[1] * @n[1] * @a, -@n[1]};\n"
          << "    @fill(@t, out.tangent[0]);\n    @fill(@b, out.tangent[1]);\n";
    }
    f << "    out.bias = -" << R("e") << " * out.normal.velocity;\n";
    f << "    if (!(out.normal.effective_mass > T(0) && detail::finite(out.normal.effective_mass)))\n"
      << "        return impact_status::singular;\n";
    f << "    return impact_status::ok;\n";
    // The fixed locals, named clear of the inputs and of each other (-Wshadow).
    std::string text = f.str();
    names::identifier_scope local = scope_;
    for (const char *nm : {"fill", "sgn", "rw", "r1", "r2", "v1", "v2", "w1", "w2", "n",
                           "t",    "b",   "a",  "p",  "d",  "k",  "u",  "c",  "i",  "j"}) {
        const std::string tag = std::string("@") + nm, claimed = local.claim(nm);
        for (std::size_t at = text.find(tag); at != std::string::npos; at = text.find(tag, at + claimed.size())) {
            const std::size_t end = at + tag.size();
            if (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_'))
                continue; // a longer tag
            text.replace(at, tag.size(), claimed);
        }
    }
    return text;
}

// The structs and the function NAME_rows, with its array form.
void writer::rows_function()
{
    if (!o_.rows)
        return;
    const std::string res = o_.name + "_rows_result";
    rows_structs();
    h_ << "/// The contact's rows for an iterative solver (Box2D, Bullet style), for the inputs of " << o_.name << "\n"
       << "/// (validated as for " << o_.name << "_unchecked). Applying an impulse lambda along a row's dir:\n"
       << "/// v_1 -= inv_m1 lambda dir, w_1 -= inv_I1 lambda ang1, v_2 += inv_m2 lambda dir, w_2 += inv_I2\n"
       << "/// lambda ang2. For this one contact one projected step along the normal,\n"
       << "/// lambda = max(0, effective_mass (bias - velocity)), is the impulse of " << o_.name
       << " without friction.\n"
       << "/// Returns ok, non_finite_input, invalid_normal (zero or not finite) or singular (no body\n"
       << "/// can move along the normal).\n"
       << "template <typename T>\nIMPACTGEN_FUNC impact_status " << o_.name << "_rows(" << params() << res
       << "<T>& out) noexcept\n{\n";
    h_ << rows_body() << "}\n\n";
    std::vector<std::string> from;
    for (std::size_t k = 0; k < input_names_.size(); ++k)
        from.push_back("in[" + std::to_string(k) + "]");
    h_ << "/// " << o_.name << "_rows with the inputs as an array (order of " << o_.name << "_input_names).\n"
       << "template <typename T>\nIMPACTGEN_FUNC impact_status " << o_.name << "_rows(const T* in, " << res
       << "<T>& out) noexcept\n{\n";
    if (from.empty())
        h_ << "    (void)in;\n";
    from.push_back("out");
    h_ << "    return " << o_.name << "_rows<T>(" << join(from, ", ") << ");\n}\n\n";
}

} // namespace impactgen::codegen::writer_detail
