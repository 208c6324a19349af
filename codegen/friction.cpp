// Code generation for impacts with Coulomb friction (friction.hpp).
//
// The emitted function, in order:
//   1. stage A, one straight-line program (CSE over everything in it): the shared steps
//      (K = K_1 + K_2 as the sum of the bodies' responses 1/m + (I^-1 (r x e)) x r, u, u_n),
//      the validity checks of the smooth headers (restitution, masses, inertia, normal,
//      approach, then det K > 0 for the stick candidate: status singular), every
//      closed-form candidate (stick; planar: slides along +e_t and -e_t; 3-D isotropic: the
//      slide along u_t) with its impulse and the values of its conditions, and for a 3-D
//      slide without closed form the five coefficients of its angle equation
//        g(theta) = a0 + a1 cos theta + b1 sin theta + a2 cos 2 theta + b2 sin 2 theta,
//      derived here from symbolic/friction.hpp's g(c, s) (c = cos theta, s = sin theta;
//      the coefficients of c^i s^j by differentiation at 0, then c^2 = (1 + cos 2 theta)/2,
//      s^2 = (1 - cos 2 theta)/2, c s = sin 2 theta / 2), and those of lambda D, the
//      sliding speed times the normal response, of the same form: the filter with which
//      the root finder leaves out the arcs where no slide can hold (lambda D < 0);
//   2. mu = 0 (unless mu is a constant): the frictionless impact (stage S), regime smooth;
//   3. else the regime selection: each candidate holds when its conditions do (as
//      derived: > 0 or >= 0); the closed forms are selected without a branch (the first
//      that holds); the roots of g (detail::trig2_roots, codegen/runtime/friction_runtime.hpp) each
//      give a slide candidate (stage B, a program in cos theta and sin theta) with its
//      conditions; exactly one candidate holding is the answer, none is no_solution,
//      several ambiguous -- but at the stick/slide boundary within rounding, where the
//      stick candidate and a slide are one solution (impulses equal to within eps^(2/3)
//      relative): there the answer is stick when nothing else holds; and a candidate or
//      condition that is not finite makes the status overflow. Without a stick candidate
//      (K singular identically: a body pinned at a fixed point struck by one that cannot
//      move) the slides are the candidates: regime slide, no det K check, no boundary merge;
//   4. the post-impact state for the impulse of that candidate (stage C, linear in it: the
//      stick candidate's formulas, or without one symbolic/response.hpp's), the energy lost
//      as minus the work of the contact impulse (1/2 P.(a + a') per free body), the
//      finiteness of the result.
// Values stages B, C and S need from stage A (its steps, and for B and C the powers with
// negative or fractional exponents of stage A's values: 1/m, 1/I, 1/|n|, so that no
// division or square root is done twice) are stage A outputs ("links"), named in a
// canonical order. Every name goes through one identifier scope (names/identifier.hpp);
// every expression is printed by emit_cpp from canonical trees (canonical.hpp), never in
// GiNaC's order: the header is the same byte for byte in every process.
#include "friction.hpp"
#include "runtime.hpp"
#include "text.hpp"

#include "names/escape.hpp"
#include "names/identifier.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/friction.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/response.hpp"

#include <algorithm>
#include <functional>
#include <set>
#include <sstream>

namespace impactgen::codegen
{
using namespace GiNaC;

namespace
{

// ---------------------------------------------------------------------------
// Helpers

std::string counts_text(const op_counts &c)
{
    return std::to_string(c.add) + " add/sub, " + std::to_string(c.mul) + " mul, " + std::to_string(c.div) + " div, " +
           std::to_string(c.sqrt) + " sqrt";
}

void add_counts(op_counts &a, const op_counts &b)
{
    a.add += b.add;
    a.mul += b.mul;
    a.div += b.div;
    a.sqrt += b.sqrt;
}

std::string wrap_comment(const std::string &lhs, const std::string &rhs)
{
    std::string out = "//   " + lhs + " = ";
    std::size_t col = out.size();
    std::string word;
    std::istringstream is(rhs);
    bool first = true;
    while (is >> word) {
        if (!first && col + 1 + word.size() > 110) {
            out += "\n//       ";
            col = 9;
        } else if (!first) {
            out += " ";
            ++col;
        }
        out += word;
        col += word.size();
        first = false;
    }
    return out + "\n";
}

// True when the code names the identifier (not as part of a longer one).
bool uses(const std::string &code, const std::string &name)
{
    auto ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (std::size_t at = code.find(name); at != std::string::npos; at = code.find(name, at + 1))
        if ((at == 0 || !ident(code[at - 1])) && (at + name.size() == code.size() || !ident(code[at + name.size()])))
            return true;
    return false;
}

std::string balanced_sum(std::vector<std::string> level)
{
    while (level.size() > 1) {
        std::vector<std::string> next;
        for (std::size_t i = 0; i + 1 < level.size(); i += 2)
            next.push_back((level[i].find(' ') != std::string::npos ? "(" + level[i] + ")" : level[i]) + " + " +
                           (level[i + 1].find(' ') != std::string::npos ? "(" + level[i + 1] + ")" : level[i + 1]));
        if (level.size() % 2)
            next.push_back(level.back());
        level = next;
    }
    return level.empty() ? std::string() : level[0];
}

std::string indent(const std::string &code, const std::string &by)
{
    std::istringstream lines(code);
    std::string line, r;
    while (std::getline(lines, line))
        r += (line.empty() ? "" : by) + line + "\n";
    return r;
}

// The leading principal minors that make a symmetric tensor positive definite, block by
// block (as the smooth headers check them: codegen.cpp), with the determinant of a block
// of all three axes only when with_determinant.
std::vector<std::pair<ex, std::string>> positive_definite_minors(const mat3 &J, const std::array<std::string, 3> &axes,
                                                                 bool with_determinant)
{
    int block_of[3] = {0, 1, 2};
    for (int r = 0; r < 3; ++r)
        for (int c = r + 1; c < 3; ++c)
            if (!tidy(J[r][c]).is_zero()) {
                const int from = block_of[c], to = block_of[r];
                for (int &x : block_of)
                    if (x == from)
                        x = to;
            }
    std::vector<std::pair<ex, std::string>> minors;
    for (int first = 0; first < 3; ++first) {
        std::vector<std::size_t> a;
        for (std::size_t k = 0; k < 3; ++k)
            if (block_of[k] == first)
                a.push_back(k);
        if (a.empty())
            continue;
        const std::string xx = axes[a[0]] + axes[a[0]];
        minors.push_back({J[a[0]][a[0]], xx + " entry > 0, finite"});
        if (a.size() >= 2) {
            const std::string yy = axes[a[1]] + axes[a[1]], xy = axes[a[0]] + axes[a[1]];
            minors.push_back({J[a[0]][a[0]] * J[a[1]][a[1]] - J[a[0]][a[1]] * J[a[1]][a[0]],
                              "minor " + xx + " " + yy + " - " + xy + "^2 > 0, finite"});
        }
        if (a.size() == 3 && with_determinant)
            minors.push_back({det(J), "determinant > 0, finite"});
    }
    return minors;
}

bool depends_on(const ex &e, const exset &syms)
{
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it) && syms.count(*it))
            return true;
    return false;
}

void collect_symbols(const ex &e, exset &out)
{
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it))
            out.insert(*it);
}

// One straight-line program of the function: its pool, its ops, the names of its steps'
// values, its outputs and checks, and the code emitted for them.
struct stage {
    canonical_pool pool;
    program prog;
    std::map<int, std::string> names;
    std::vector<std::pair<std::string, int>> outs;
    std::vector<check> checks;
    emitted em;
    int next_step = 0;

    void bind_step(const step &st, const std::string &name)
    {
        scaled v = pool.convert(st.value);
        pool.bind_step(st.sym, next_step, name);
        prog.set_owner(name);
        const int id = prog.lower(pool, v);
        prog.set_step(next_step, id);
        ++next_step;
        if (!prog.is_leaf(id) && !names.count(id))
            names[id] = name;
    }
    int lower(const ex &e, const std::string &owner)
    {
        prog.set_owner(owner);
        return prog.lower(pool, pool.convert(e));
    }
    void output(const std::string &field, const ex &e) { outs.push_back({field, lower(e, field)}); }
    void add_check(const ex &value, check::kind_t kind, const std::string &status, const std::string &comment)
    {
        if (is_a<numeric>(value))
            return; // a constant was validated when the problem was read
        checks.push_back({kind, lower(value, "check"), status, comment});
    }
};

// ---------------------------------------------------------------------------
// The writer

// The state after the selected impulse: per body, per pivot (world axes).
struct after_state {
    std::vector<vec3> velocity, angular_velocity, pivot_impulses;
};

struct case_names {
    std::string prefix;         // "stick_", "slide_pos_", "slide_neg_", "slide_"
    std::string N;              // stage A (or B) local of the candidate's normal impulse
    std::vector<std::string> P; // world components of the impulse (dim)
    std::vector<std::string> F; // world components of the tangential impulse (dim)
    std::vector<std::string> cond;
};

class friction_writer
{
public:
    friction_writer(const problem &p, const options &o) : o_(o) { prepare(p); }

    header run()
    {
        name_everything();
        build_stages();
        emit_stages();
        banner();
        preamble();
        result_struct();
        formula_block();
        unchanged_function();
        main_function();
        array_form();
        struct_form();
        batch_form();
        tables();
        header h;
        h.text = h_.str();
        h.formula = total_;
        h.checks = a_.em.checks;
        h.inputs = input_names_;
        for (const out_field &of : outs_)
            h.outputs.push_back(of.field);
        return h;
    }

private:
    struct out_field {
        std::string field, meaning;
        output_value::kind_t kind;
        std::size_t index = 0;
        int component = 0;
        bool tangential = false;
        int axis = 0;           // tangential: world axis
        std::size_t smooth = 0; // index in the smooth plan's outputs (not tangential)
    };

    // ---- the problem, its regimes, the inputs and outputs
    void prepare(const problem &p)
    {
        if (o_.inverse_inertia)
            throw option_error(
                option_error::inverse_inertia,
                "the engine input convention is not offered for problems with friction (give masses and inertia)");
        if (o_.inverse_mass)
            throw option_error(option_error::inverse_mass,
                               "the engine input convention is not offered for problems with friction (give masses)");
        if (o_.jacobian || !o_.wrt.empty())
            throw option_error(option_error::jacobian,
                               "Jacobians are not offered for problems with friction (the regime "
                               "selection makes the impact map piecewise)");
        problem p0 = p;
        // --params mu with a numeric coefficient: mu becomes the parameter.
        if (o_.params_given && std::find(o_.params.begin(), o_.params.end(), "mu") != o_.params.end() &&
            is_a<numeric>(p0.contact.friction())) {
            bool taken = false;
            for (const symbol &s : p0.parameters())
                taken = taken || s.get_name() == "mu";
            if (!taken)
                p0.contact.set_friction(symbol_named("mu", "\\mu"));
        }
        q_ = specialise(p0, o_);
        if (!q_.has_friction())
            throw input_error(
                (q_.source.empty() ? std::string("contact") : names::display_text(q_.source) + ": contact") +
                ".friction: the coefficient of friction is 0: generate the smooth header (codegen::generate)");
        // The smooth plan of the same problem without friction: the inputs in the smooth
        // headers' order with their meanings, the outputs, the vector views, the state a
        // failed call returns.
        problem sq = q_;
        sq.contact.set_friction(0);
        std::set<std::string> rest;
        for (const symbol &s : sq.parameters())
            rest.insert(s.get_name());
        exset fsyms;
        collect_symbols(q_.contact.friction(), fsyms);
        std::set<std::string> friction_only;
        for (const ex &s : fsyms)
            if (!rest.count(ex_to<symbol>(s).get_name()))
                friction_only.insert(ex_to<symbol>(s).get_name());
        options so = o_;
        so.set.clear();
        so.params.clear();
        for (const std::string &nm : o_.params)
            if (!friction_only.count(nm))
                so.params.push_back(nm);
        pl_ = make_plan(sq, so);
        derive_options how;
        how.unit_normal = o_.unit_normal;
        how.runtime_tangent_basis = true;
        d_ = derive(q_, how);
        f_ = solve_friction(d_);

        // Inputs: the parameters in the order given, else the smooth order with the
        // symbols of mu right after those of e.
        std::map<std::string, symbol> by_name;
        for (const symbol &s : q_.parameters())
            by_name.emplace(s.get_name(), s);
        const std::string mu_meaning = is_a<symbol>(q_.contact.friction())
                                           ? "coefficient of friction mu >= 0 (Coulomb: |P_t| <= mu P_n)"
                                           : "appears in the coefficient of friction mu";
        auto smooth_meaning = [&](const symbol &s) -> std::string {
            for (std::size_t i = 0; i < pl_.inputs.size(); ++i)
                if (pl_.inputs[i].is_equal(s))
                    return pl_.input_meaning[i];
            return mu_meaning;
        };
        if (o_.params_given) {
            for (const std::string &nm : o_.params) {
                const symbol &s = by_name.at(nm);
                inputs_.push_back(s);
                input_meaning_.push_back(smooth_meaning(s));
            }
        } else {
            std::size_t at = 0;
            exset esyms;
            collect_symbols(q_.restitution, esyms);
            for (std::size_t i = 0; i < pl_.inputs.size(); ++i)
                if (esyms.count(pl_.inputs[i]))
                    at = i + 1;
            for (std::size_t i = 0; i < pl_.inputs.size(); ++i) {
                if (i == at)
                    for (const std::string &nm : friction_only) {
                        inputs_.push_back(by_name.at(nm));
                        input_meaning_.push_back(mu_meaning);
                    }
                inputs_.push_back(pl_.inputs[i]);
                input_meaning_.push_back(pl_.input_meaning[i]);
            }
            if (at >= pl_.inputs.size())
                for (const std::string &nm : friction_only) {
                    inputs_.push_back(by_name.at(nm));
                    input_meaning_.push_back(mu_meaning);
                }
        }
        // Outputs: the smooth ones with the tangential impulse after the normal impulse.
        const int dim = q_.dimension;
        for (std::size_t k = 0; k < pl_.outputs.size(); ++k) {
            const output_value &ov = pl_.outputs[k];
            out_field of;
            of.field = ov.field;
            of.meaning = ov.meaning;
            of.kind = ov.kind;
            of.index = ov.index;
            of.component = ov.component;
            of.smooth = k;
            if (ov.kind == output_value::normal_impulse)
                of.meaning = "normal impulse P.n >= 0 along the unit normal: on " + q_.bodies[q_.contact.body2].name +
                             " along +n, on " + q_.bodies[q_.contact.body1].name + " along -n";
            if (ov.kind == output_value::approach_velocity)
                of.meaning = "(v_B - v_A).n before impact along the unit normal (< 0)";
            smooth_index_[k] = outs_.size();
            outs_.push_back(of);
            if (ov.kind == output_value::normal_impulse)
                for (int a = 0; a < dim; ++a) {
                    out_field tf;
                    tf.field = "tangential_impulse_" + q_.axes[static_cast<std::size_t>(a)];
                    tf.meaning = "tangential (friction) impulse P - (P.n) n on " + q_.bodies[q_.contact.body2].name +
                                 " (on " + q_.bodies[q_.contact.body1].name + " its opposite), world " +
                                 q_.axes[static_cast<std::size_t>(a)];
                    tf.kind = output_value::normal_impulse;
                    tf.tangential = true;
                    tf.axis = a;
                    tangential_index_.push_back(outs_.size());
                    outs_.push_back(tf);
                }
        }
    }

    // ---- names (one scope for the function's names, one per struct)
    void name_everything()
    {
        for (const std::string &r : reserved())
            if (names::is_safe_identifier(r))
                scope_.reserve(r);
        for (names::identifier_scope *sc : {&in_members_, &members_})
            for (const char *own : {"view", "T", "regime"})
                sc->reserve(own);
        for (const char *suffix : {"", "_result", "_input", "_unchanged", "_batch", "_input_count", "_output_count",
                                   "_input_names", "_output_names", "_to_array"})
            scope_.reserve(o_.name + suffix);
        for (const symbol &x : inputs_) {
            input_names_.push_back(scope_.claim(x.get_name()));
            input_ident_[x] = input_names_.back();
        }
        // The tangent basis computed at run time (a normal given as inputs): locals that the
        // stages read as they read inputs.
        for (const symbol &x : d_.tangent_basis_symbols) {
            basis_names_.push_back(scope_.claim(x.get_name()));
            input_ident_[x] = basis_names_.back();
        }
        if (!basis_names_.empty()) {
            basis_t_name_ = scope_.claim("basis_t");
            basis_b_name_ = scope_.claim("basis_b");
            nb_.pool.set_input_names(input_ident_);
            for (int a = 0; a < 3; ++a)
                nb_.output(scope_.claim("basis_n_" + q_.axes[static_cast<std::size_t>(a)]),
                           q_.contact.normal[static_cast<std::size_t>(a)]);
        }
        for (out_field &of : outs_)
            of.field = members_.claim(of.field);
        for (const std::string &nm : input_names_)
            in_members_.claim(nm);
        for (const group &g : pl_.input_groups)
            in_views_.push_back(in_members_.claim(g.name));
        for (const group &g : pl_.output_groups)
            out_views_.push_back(members_.claim(g.name));
        if (q_.dimension >= 2)
            tangential_view_ = members_.claim("tangential_impulse");
    }

    std::string case_prefix(const regime_case &c) const
    {
        if (c.kind == regime::stick)
            return "stick_";
        if (c.sign > 0)
            return "slide_pos_";
        if (c.sign < 0)
            return "slide_neg_";
        return "slide_";
    }

    // ---- the four programs
    void build_stages()
    {
        const problem &q = q_;
        const int dim = q.dimension;
        for (std::size_t i = 0; i < f_.cases.size(); ++i)
            if (f_.cases[i].needs_angle)
                angle_ = static_cast<int>(i);
        // Steps: stage A (every step of every case that does not depend on the sliding
        // angle, each once) and stage B (the angle case's own steps).
        exset shared;
        for (const step &st : f_.cases.front().sol.steps) {
            bool everywhere = true;
            for (const regime_case &c : f_.cases) {
                bool found = false;
                for (const step &s2 : c.sol.steps)
                    found = found || s2.sym.is_equal(st.sym);
                everywhere = everywhere && found;
            }
            if (everywhere)
                shared.insert(st.sym);
        }
        exset seen;
        if (angle_ >= 0) {
            local_.insert(f_.cases[static_cast<std::size_t>(angle_)].dir_c);
            local_.insert(f_.cases[static_cast<std::size_t>(angle_)].dir_s);
        }
        for (std::size_t i = 0; i < f_.cases.size(); ++i) {
            const regime_case &c = f_.cases[i];
            for (const step &st : c.sol.steps) {
                if (!seen.insert(st.sym).second)
                    continue;
                const bool in_b = static_cast<int>(i) == angle_ && depends_on(st.value, local_);
                const std::string nm = scope_.claim((shared.count(st.sym) ? "" : case_prefix(c)) + st.sym.get_name());
                if (in_b) {
                    local_.insert(st.sym);
                    b_steps_.push_back(st);
                    b_step_names_.push_back(nm);
                } else {
                    a_steps_.push_back(st);
                    a_step_names_.push_back(nm);
                    a_step_syms_.insert(st.sym);
                }
            }
        }
        for (std::size_t i = 0; i < a_steps_.size(); ++i)
            step_name_[a_steps_[i].sym] = a_step_names_[i];
        // K as the sum of the bodies' responses, 1/m + (I^{-1} (r x e_b)) x r (as the smooth
        // headers compute w = 1/m + (r x n).I^{-1}(r x n)), rather than the one fraction
        // symbolic/friction.hpp keeps for it (I1 I2 m1 m2 in its denominator under- or
        // overflows where the sum does not).
        for (step &st : a_steps_)
            if (st.role == step_role::contact_response)
                st.value = response_entry(f_.shared, st.row, st.column);

        // The selected impulse (world, on body 2), normal impulse and tangential impulse.
        for (int a = 0; a < dim; ++a) {
            const std::string ax = q.axes[static_cast<std::size_t>(a)];
            sel_P_.push_back(symbol("friction_P_" + ax));
            sel_F_.push_back(symbol("friction_F_" + ax));
            sel_P_names_.push_back(scope_.claim("sel_P_" + ax));
            sel_F_names_.push_back(scope_.claim("sel_F_" + ax));
        }
        sel_N_name_ = scope_.claim("sel_N");
        for (int a = 0; a < dim; ++a) {
            local_.insert(sel_P_[static_cast<std::size_t>(a)]);
            local_.insert(sel_F_[static_cast<std::size_t>(a)]);
        }
        local_.insert(sel_N_);

        // Stage C: the state after the impulse sel_P, the impulses, the approach velocity and
        // the energy lost.
        const after_state after = state_after_selected();
        const step *un = nullptr;
        for (const step &st : f_.shared.steps)
            if (st.role == step_role::approach_velocity)
                un = &st;
        if (!un)
            throw std::logic_error("codegen friction: no approach velocity step");
        std::vector<ex> c_values(outs_.size());
        for (std::size_t k = 0; k < outs_.size(); ++k) {
            const out_field &of = outs_[k];
            if (of.tangential) {
                c_values[k] = sel_F_[static_cast<std::size_t>(of.axis)];
                continue;
            }
            switch (of.kind) {
            case output_value::velocity:
                c_values[k] = after.velocity[of.index][of.component];
                break;
            case output_value::angular_velocity:
                c_values[k] = after.angular_velocity[of.index][of.component];
                break;
            case output_value::pivot_impulse:
                c_values[k] = after.pivot_impulses[of.index][of.component];
                break;
            case output_value::normal_impulse:
                c_values[k] = sel_N_;
                break;
            case output_value::approach_velocity:
                c_values[k] = un->sym;
                break;
            case output_value::energy_lost:
                c_values[k] = energy_lost(after);
                break;
            }
        }
        // Stage S: mu = 0, the frictionless impact: N = -(1 + e) u_n / (n.K n), P = N n.
        const vec3 &n = d_.n_hat;
        mat3 K = zero_mat();
        for (const step &st : f_.shared.steps)
            if (st.role == step_role::contact_response)
                K[static_cast<std::size_t>(st.row)][static_cast<std::size_t>(st.column)] =
                    K[static_cast<std::size_t>(st.column)][static_cast<std::size_t>(st.row)] = st.sym;
        const ex D0 = dot(n, mul(K, n));
        symbol N0("friction_N0");
        s_D0_ = D0;
        s_N0_value_ = -(1 + q.restitution) * un->sym / D0;
        s_N0_ = N0;

        // Links: stage A values that stages B, C and S use.
        auto link = [&](const ex &e) { return linkify(e); };
        for (ex &v : c_values)
            v = link(v);
        c_values_ = c_values;
        // (stage S, for mu = 0 only, computes its own reciprocals: links are computed on every call)
        s_P0_.clear();
        for (int a = 0; a < dim; ++a)
            s_P0_.push_back(N0 * n[static_cast<std::size_t>(a)]);
        if (angle_ >= 0) {
            const regime_case &c = f_.cases[static_cast<std::size_t>(angle_)];
            for (step st : b_steps_) {
                st.value = link(st.value);
                b_steps_linked_.push_back(st);
            }
            b_N_ = link(c.sol.normal_impulse);
            for (int a = 0; a < dim; ++a) {
                b_P_.push_back(link(c.impulse[static_cast<std::size_t>(a)]));
                b_F_.push_back(link(c.tangential_impulse[static_cast<std::size_t>(a)]));
            }
            for (const regime_condition &rc : c.conditions)
                b_cond_.push_back(link(rc.value));
        }
        name_links();

        build_stage_a();
        build_stage_b();
        build_stage_s();
        build_stage_c();
        build_unchanged();
    }

    // Entry (a, b) of the contact response K = K_1 + K_2: the change of the relative
    // velocity of the contact points along a per unit impulse along b on body 2 (and its
    // opposite on body 1): K_i P = P/m_i + (I_i^{-1} (r_i x P)) x r_i (a pinned body: about
    // its pivot, without the first term), with the inverse inertia as the solution has it
    // (its steps for a full tensor, 1/I for a diagonal one).
    ex response_entry(const solution &s, int a, int b) const
    {
        const problem &q = q_;
        ex k = 0;
        for (std::size_t i : {q.contact.body1, q.contact.body2}) {
            if (q.immovable(i))
                continue;
            const body &bd = q.bodies[i];
            const pivot *pv = q.pivot_of(i);
            const vec3 lever = pv ? q.contact.point - pv->point : q.contact.point - bd.position;
            if (!pv && a == b)
                k += 1 / bd.mass;
            if (bd.particle)
                continue;
            const mat3 inv = inverse_inertia(s, i);
            vec3 e = zero_vec();
            e[static_cast<std::size_t>(b)] = 1;
            k += cross(mul(inv, cross(lever, e)), lever)[static_cast<std::size_t>(a)];
        }
        return k;
    }

    // The inverse inertia of movable body i, not a particle (about its pivot when pinned), as
    // the solution s has it: its steps for a full tensor (or adj(J) / det(J) itself for a
    // tensor too simple to be a step), 1/I for a diagonal one.
    mat3 inverse_inertia(const solution &s, std::size_t i) const
    {
        const problem &q = q_;
        const body &bd = q.bodies[i];
        const pivot *pv = q.pivot_of(i);
        mat3 inv = zero_mat();
        if (q.dimension == 2) {
            const step *ie = s.find(step_role::pivot_inertia, i, 2, 2);
            ex Iz = bd.inertia[2][2];
            if (pv)
                Iz = ie ? ex(ie->sym) : inertia_about(bd, pv->point)[2][2];
            inv[2][2] = 1 / Iz;
            return inv;
        }
        const mat3 J = pv ? inertia_about(bd, pv->point) : bd.inertia;
        bool diagonal = true;
        for (std::size_t r = 0; r < 3; ++r)
            for (std::size_t c = r + 1; c < 3; ++c)
                diagonal = diagonal && tidy(J[r][c]).is_zero() && tidy(J[c][r]).is_zero();
        for (std::size_t r = 0; r < 3; ++r)
            for (std::size_t c = 0; c < 3; ++c) {
                if (diagonal) {
                    inv[r][c] = r == c ? 1 / tidy(J[r][r]) : ex(0);
                    continue;
                }
                const step *js = s.find(step_role::inverse_inertia, i, static_cast<int>(std::min(r, c)),
                                        static_cast<int>(std::max(r, c)));
                if (js) {
                    inv[r][c] = js->sym;
                    continue;
                }
                mat3 Jt;
                for (std::size_t a2 = 0; a2 < 3; ++a2)
                    for (std::size_t c2 = 0; c2 < 3; ++c2)
                        Jt[a2][c2] = tidy(J[a2][c2]);
                inv[r][c] = tidy(adjugate(Jt)[r][c] / det(Jt));
            }
        return inv;
    }

    // The bodies' velocities and the pivots' impulses after the impulse sel_P (on body 2;
    // -sel_P on body 1), linear in it: the stick candidate's formulas with its impulse
    // replaced when there is one, else the response layer's (symbolic/response.hpp, as
    // symbolic/friction.cpp finishes every candidate) with the shared steps' inverse inertia.
    after_state state_after_selected() const
    {
        const problem &q = q_;
        after_state r;
        if (const regime_case *stick = f_.stick()) {
            lst to_sel;
            for (std::size_t a = 0; a < sel_P_.size(); ++a)
                to_sel.append(stick->impulse[a] == sel_P_[a]);
            auto subs = [&](const vec3 &v) {
                vec3 x;
                for (std::size_t a = 0; a < 3; ++a)
                    x[a] = v[a].subs(to_sel);
                return x;
            };
            for (const auto &b : stick->sol.after) {
                r.velocity.push_back(subs(b.velocity));
                r.angular_velocity.push_back(subs(b.angular_velocity));
            }
            for (const vec3 &R : stick->sol.pivot_impulses)
                r.pivot_impulses.push_back(subs(R));
            return r;
        }
        for (const body &b : q.bodies) {
            r.velocity.push_back(b.velocity);
            r.angular_velocity.push_back(b.angular_velocity);
        }
        r.pivot_impulses.assign(q.pivots.size(), zero_vec());
        vec3 P = zero_vec();
        for (std::size_t a = 0; a < sel_P_.size(); ++a)
            P[a] = sel_P_[a];
        for (std::size_t i : {q.contact.body1, q.contact.body2}) {
            const body &b = q.bodies[i];
            if (b.infinite_mass)
                continue;
            const body_response br = response_of(q, i, q.contact.point);
            const vec3 Pi = ex(i == q.contact.body1 ? -1 : 1) * P;
            const mat3 inv = br.movable && !br.particle ? inverse_inertia(f_.shared, i) : zero_mat();
            const vec3 dw = spin_change(br, inv, Pi), dv = centre_velocity_change(br, Pi, dw);
            r.velocity[i] = b.velocity + dv;
            r.angular_velocity[i] = b.angular_velocity + dw;
            if (const pivot *pv = q.pivot_of(i)) {
                vec3 &R = r.pivot_impulses[static_cast<std::size_t>(pv - q.pivots.data())];
                R = pivot_impulse(br, Pi, dv);
                if (q.dimension == 2)
                    R[2] = 0;
            }
        }
        return r;
    }

    // The energy lost by the bodies of finite mass for the impulse sel_P: minus the work
    // of the contact impulse, 1/2 Pi.(a + a') for a free body (Pi its impulse, a and a'
    // the velocities of its material point at O before and after), and for a pinned body
    // 1/2 m dv.(v + v') + 1/2 dw.I (w + w') (its pivot's impulse may work too).
    ex energy_lost(const after_state &after) const
    {
        const problem &q = q_;
        ex work = 0;
        for (std::size_t i : {q.contact.body1, q.contact.body2}) {
            const body &b = q.bodies[i];
            if (b.infinite_mass || q.immovable(i))
                continue;
            const ex s = i == q.contact.body1 ? ex(-1) : ex(1);
            const vec3 &v1 = after.velocity[i], &w1 = after.angular_velocity[i];
            if (q.pivot_of(i)) {
                const vec3 dv = v1 - b.velocity, dw = w1 - b.angular_velocity;
                work += b.mass * dot(dv, v1 + b.velocity) / 2 + dot(dw, mul(b.inertia, w1 + b.angular_velocity)) / 2;
                continue;
            }
            vec3 Pi = zero_vec();
            for (std::size_t a = 0; a < sel_P_.size(); ++a)
                Pi[a] = s * sel_P_[a];
            const vec3 before = point_velocity(b, b.velocity, b.angular_velocity, q.contact.point);
            const vec3 after = point_velocity(b, v1, w1, q.contact.point);
            work += dot(Pi, before + after) / 2;
        }
        return -work;
    }

    // Powers of stage A values with a negative or fractional exponent become links; so do
    // the stage A steps an expression of stage B, C or S uses (linked in name_links).
    ex linkify(const ex &e)
    {
        if (is_a<power>(e) && is_a<numeric>(e.op(1))) {
            const numeric x = ex_to<numeric>(e.op(1));
            if ((x.is_negative() || !x.is_integer()) && !depends_on(e.op(0), local_)) {
                exset syms;
                collect_symbols(e, syms);
                if (!syms.empty()) {
                    for (const auto &[value, sym] : power_links_)
                        if (value.is_equal(e))
                            return sym;
                    symbol s("friction_link");
                    power_links_.push_back({e, s});
                    return s;
                }
            }
        }
        if (is_a<symbol>(e) || is_a<numeric>(e) || e.nops() == 0)
            return e;
        struct mapper : map_function {
            friction_writer *w;
            explicit mapper(friction_writer *w_) : w(w_) {}
            ex operator()(const ex &x) override { return w->linkify(x); }
        } m(this);
        return e.map(m);
    }

    // Names the links in a canonical order: by the canonical key of their values.
    void name_links()
    {
        canonical_pool scratch;
        std::map<ex, std::string, ex_is_less> names = input_ident_;
        for (const auto &[sym, nm] : step_name_)
            names[sym] = nm;
        scratch.set_input_names(names);
        std::vector<std::pair<std::string, std::size_t>> keyed;
        for (std::size_t i = 0; i < power_links_.size(); ++i) {
            const scaled s = scratch.convert(power_links_[i].first);
            keyed.push_back({number_text(s.scale) + "*" + (s.node >= 0 ? scratch.at(s.node).key : std::string()), i});
        }
        std::sort(keyed.begin(), keyed.end());
        for (std::size_t k = 0; k < keyed.size(); ++k) {
            const auto &pl = power_links_[keyed[k].second];
            link_names_[pl.second] = scope_.claim("lk_" + std::to_string(k + 1));
            link_order_.push_back(pl.second);
            link_value_[pl.second] = pl.first;
        }
        // The stage A steps used downstream, in stage A's order.
        exset used;
        auto collect = [&](const ex &e) { collect_symbols(e, used); };
        for (const ex &v : c_values_)
            collect(v);
        if (!is_a<numeric>(q_.contact.friction())) { // stage S is written only when mu may be 0
            collect(s_D0_);
            collect(s_N0_value_);
            for (const ex &v : s_P0_)
                collect(v);
        }
        for (const step &st : b_steps_linked_)
            collect(st.value);
        collect(b_N_);
        for (const ex &v : b_P_)
            collect(v);
        for (const ex &v : b_F_)
            collect(v);
        for (const ex &v : b_cond_)
            collect(v);
        for (std::size_t i = 0; i < a_steps_.size(); ++i)
            if (used.count(a_steps_[i].sym)) {
                link_names_[a_steps_[i].sym] = scope_.claim("lk_" + a_step_names_[i]);
                link_order_.push_back(a_steps_[i].sym);
                link_value_[a_steps_[i].sym] = a_steps_[i].sym;
            }
    }

    // The input names of a downstream stage: the inputs, the links, and extra locals.
    void downstream_names(stage &s, const std::map<ex, std::string, ex_is_less> &extra)
    {
        std::map<ex, std::string, ex_is_less> names = input_ident_;
        for (const auto &[sym, nm] : link_names_)
            names[sym] = nm;
        for (const auto &[sym, nm] : extra)
            names[sym] = nm;
        s.pool.set_input_names(names);
    }

    void build_stage_a()
    {
        const problem &q = q_;
        const int dim = q.dimension;
        a_.pool.set_input_names(input_ident_);
        for (std::size_t i = 0; i < a_steps_.size(); ++i)
            a_.bind_step(a_steps_[i], a_step_names_[i]);
        add_checks();
        // mu as a value (when it is not simply an input or a number)
        const ex &mu = q.contact.friction();
        if (is_a<symbol>(mu) && input_ident_.count(mu)) {
            mu_name_ = input_ident_.at(mu);
        } else if (is_a<numeric>(mu)) {
            mu_name_.clear();
        } else {
            mu_name_ = scope_.claim("mu_value");
            a_.output(mu_name_, mu);
        }
        // Candidates in closed form and the conditions of each.
        for (std::size_t i = 0; i < f_.cases.size(); ++i) {
            const regime_case &c = f_.cases[i];
            case_names cn;
            cn.prefix = case_prefix(c);
            if (static_cast<int>(i) == angle_) {
                names_.push_back(cn);
                continue;
            }
            cn.N = scope_.claim("c_" + cn.prefix + "N");
            a_.output(cn.N, c.sol.normal_impulse);
            for (int a = 0; a < dim; ++a) {
                const std::string ax = q.axes[static_cast<std::size_t>(a)];
                cn.P.push_back(scope_.claim("c_" + cn.prefix + "P_" + ax));
                a_.output(cn.P.back(), c.impulse[static_cast<std::size_t>(a)]);
                cn.F.push_back(scope_.claim("c_" + cn.prefix + "F_" + ax));
                a_.output(cn.F.back(), c.tangential_impulse[static_cast<std::size_t>(a)]);
            }
            for (std::size_t j = 0; j < c.conditions.size(); ++j) {
                cn.cond.push_back(scope_.claim("c_" + cn.prefix + "cond" + std::to_string(j + 1)));
                a_.output(cn.cond.back(), c.conditions[j].value);
            }
            names_.push_back(cn);
        }
        // The angle equation's coefficients.
        if (angle_ >= 0) {
            const regime_case &c = f_.cases[static_cast<std::size_t>(angle_)];
            // g is a polynomial of degree 2 in (c, s) (g = n.(h x d), h and d of degree 1): its
            // coefficients by differentiation at c = s = 0, which keeps the factored form of
            // the closed form (expanding it multiplies out every product of sums).
            const ex &g = c.angle_equation;
            const lst zero{c.dir_c == 0, c.dir_s == 0};
            auto at0 = [&](const ex &x) { return x.subs(zero); };
            const ex gc = g.diff(c.dir_c), gs = g.diff(c.dir_s);
            const ex c00 = at0(g), c10 = at0(gc), c01 = at0(gs), c20 = at0(gc.diff(c.dir_c)) / 2,
                     c02 = at0(gs.diff(c.dir_s)) / 2, c11 = at0(gc.diff(c.dir_s));
            const ex coef[5] = {c00 + (c20 + c02) / 2, c10, c01, (c20 - c02) / 2, c11 / 2};
            const char *nm[5] = {"trig_a0", "trig_a1", "trig_b1", "trig_a2", "trig_b2"};
            for (int k = 0; k < 5; ++k) {
                trig_names_.push_back(scope_.claim(nm[k]));
                a_.output(trig_names_.back(), coef[k]);
            }
            // The filter: lambda D = D (u.d) + a (Q.d), Q = K (n - mu d), D = n.Q, a = -(1 + e) u_n,
            // of the same form; a slide holds only where it is > 0 (lambda > 0 and D > 0), so
            // the root finder may leave out the arcs where it is negative throughout.
            mat3 K = zero_mat();
            ex un;
            for (const step &x : f_.shared.steps) {
                if (x.role == step_role::contact_response)
                    K[static_cast<std::size_t>(x.row)][static_cast<std::size_t>(x.column)] =
                        K[static_cast<std::size_t>(x.column)][static_cast<std::size_t>(x.row)] = x.sym;
                if (x.role == step_role::approach_velocity)
                    un = x.sym;
            }
            vec3 u = zero_vec(), dir = zero_vec(), m = zero_vec();
            for (std::size_t a = 0; a < 3; ++a) {
                u[a] = tidy(d_.vB[a] - d_.vA[a]);
                dir[a] = c.dir_c * f_.e_t[a] + c.dir_s * f_.e_b[a];
                m[a] = d_.n_hat[a] - q.contact.friction() * dir[a];
            }
            const vec3 Q = mul(K, m);
            const ex Lambda = dot(d_.n_hat, Q) * dot(u, dir) - (1 + q.restitution) * un * dot(Q, dir);
            const ex Lc = Lambda.diff(c.dir_c), Ls = Lambda.diff(c.dir_s);
            const ex l00 = at0(Lambda), l10 = at0(Lc), l01 = at0(Ls), l20 = at0(Lc.diff(c.dir_c)) / 2,
                     l02 = at0(Ls.diff(c.dir_s)) / 2, l11 = at0(Lc.diff(c.dir_s));
            const ex lcoef[5] = {l00 + (l20 + l02) / 2, l10, l01, (l20 - l02) / 2, l11 / 2};
            for (int k = 0; k < 5; ++k) {
                keep_names_.push_back(scope_.claim("keep_" + std::to_string(k)));
                a_.output(keep_names_.back(), lcoef[k]);
            }
            // When the solution is provably unique (detail::slide_direction): with
            // a = -(1 + e) u_n, tau = P_t / N (|tau| <= mu), D(tau) = K_nn + K_nt.tau and
            // N = a / D(tau), u'_t / N = (b + M tau) / a with b = a K_tn + u_t K_nn and
            // M = a K_tt + u_t K_nt^T (tangential axes t, b). A solution (N > 0) has
            // -(b + M tau) in the normal cone of the disc |tau| <= mu at tau, so it solves the
            // variational inequality of b + M tau on the disc cut to D(tau) >= delta (any
            // delta below its D): if M + M^T is positive definite that inequality has one
            // solution only, so the law has at most one. Tested with a margin
            // (31 M11 M22 >= 32 ((M12 + M21) / 2)^2) so that rounding cannot pass a problem
            // that is not; then a stick candidate that holds is the answer, and otherwise the
            // slide's direction is the root of one monotone scalar equation.
            const vec3 nh = d_.n_hat;
            const ex a = -(1 + q.restitution) * un;
            auto Kdot = [&](const vec3 &x, const vec3 &y) { return dot(x, mul(K, y)); };
            const ex Knn = Kdot(nh, nh), Knt = Kdot(f_.e_t, nh), Knb = Kdot(f_.e_b, nh);
            const ex Ktt = Kdot(f_.e_t, f_.e_t), Ktb = Kdot(f_.e_t, f_.e_b), Kbb = Kdot(f_.e_b, f_.e_b);
            const ex ut = dot(u, f_.e_t), ub = dot(u, f_.e_b);
            const ex &mu = q.contact.friction();
            const ex M11 = a * Ktt + ut * Knt, M12 = a * Ktb + ut * Knb, M21 = a * Ktb + ub * Knt,
                     M22 = a * Kbb + ub * Knb;
            const ex fast[7] = {mu * M11,
                                mu * M12,
                                mu * M21,
                                mu * M22,
                                a * Knt + ut * Knn,
                                a * Knb + ub * Knn,
                                31 * M11 * M22 - 8 * (M12 + M21) * (M12 + M21)};
            const char *fnm[7] = {"slide_m11", "slide_m12", "slide_m21",      "slide_m22",
                                  "slide_b1",  "slide_b2",  "unique_monotone"};
            for (int k = 0; k < 7; ++k) {
                fast_names_.push_back(scope_.claim(fnm[k]));
                a_.output(fast_names_.back(), fast[k]);
            }
        }
        // Links: aliases of stage A values.
        for (const ex &s : link_order_)
            a_.output(link_names_.at(s), link_value_.at(s));
    }

    // Validity checks as the smooth headers make them, and det K > 0 for the stick candidate.
    void add_checks()
    {
        const problem &q = q_;
        a_.add_check(q.restitution, check::unit_interval, "invalid_restitution", "0 <= e <= 1");
        for (std::size_t i : {q.contact.body1, q.contact.body2}) {
            const body &b = q.bodies[i];
            if (b.infinite_mass)
                continue;
            a_.add_check(b.mass, check::positive, "invalid_mass", "mass of " + b.name + " > 0, finite");
            if (!b.particle && q.dimension == 2)
                a_.add_check(b.inertia[2][2], check::positive, "invalid_inertia",
                             "moment of inertia of " + b.name + " > 0, finite");
        }
        for (std::size_t i : {q.contact.body1, q.contact.body2}) {
            const body &b = q.bodies[i];
            if (q.dimension != 3 || b.particle || b.infinite_mass)
                continue;
            const pivot *pv = q.pivot_of(i);
            const mat3 J = pv ? inertia_about(b, pv->point) : b.inertia;
            const std::string what =
                "inertia tensor of " + b.name + (q.pivot_of(i) ? " about its pivot" : "") + " positive definite: ";
            for (const auto &[minor, text] : positive_definite_minors(J, q.axes, false))
                a_.add_check(minor, check::positive, "invalid_inertia", what + text);
        }
        const ex nn = tidy(dot(q.contact.normal, q.contact.normal));
        if (!is_constant(nn)) {
            if (d_.normal_assumed_unit)
                a_.add_check(nn, check::near_one, "invalid_normal", "the normal is a unit vector: |n.n - 1| <= 2^-17");
            else
                a_.add_check(nn, check::normal_number, "invalid_normal",
                             "n.n a normal number: the normal neither zero, denormal nor too long");
        }
        for (const step &st : a_steps_) {
            switch (st.role) {
            case step_role::inertia_determinant:
                a_.add_check(st.sym, check::positive, "invalid_inertia",
                             "determinant of the inertia tensor > 0, finite");
                break;
            case step_role::approach_velocity:
                a_.add_check(st.sym, check::negative, "not_approaching", "the contact points approach: u_n < 0");
                break;
            case step_role::response_determinant:
                a_.add_check(st.sym, check::positive, "singular", "contact response det K > 0, finite (stick)");
                break;
            default:
                break;
            }
        }
    }

    void build_stage_b()
    {
        if (angle_ < 0)
            return;
        const regime_case &c = f_.cases[static_cast<std::size_t>(angle_)];
        const int dim = q_.dimension;
        dir_c_name_ = scope_.claim("c_d");
        dir_s_name_ = scope_.claim("s_d");
        downstream_names(b_, {{c.dir_c, dir_c_name_}, {c.dir_s, dir_s_name_}});
        for (std::size_t i = 0; i < b_steps_linked_.size(); ++i)
            b_.bind_step(b_steps_linked_[i], b_step_names_[i]);
        case_names &cn = names_[static_cast<std::size_t>(angle_)];
        cn.N = scope_.claim("c_slide_N");
        b_.output(cn.N, b_N_);
        for (int a = 0; a < dim; ++a) {
            const std::string ax = q_.axes[static_cast<std::size_t>(a)];
            cn.P.push_back(scope_.claim("c_slide_P_" + ax));
            b_.output(cn.P.back(), b_P_[static_cast<std::size_t>(a)]);
            cn.F.push_back(scope_.claim("c_slide_F_" + ax));
            b_.output(cn.F.back(), b_F_[static_cast<std::size_t>(a)]);
        }
        for (std::size_t j = 0; j < b_cond_.size(); ++j) {
            cn.cond.push_back(scope_.claim("c_slide_cond" + std::to_string(j + 1)));
            b_.output(cn.cond.back(), b_cond_[j]);
        }
    }

    void build_stage_s()
    {
        if (mu_name_.empty())
            return; // a constant mu > 0: never smooth
        downstream_names(s_, {});
        s_D0_name_ = scope_.claim("D_0");
        step d0;
        d0.sym = symbol("friction_D0");
        d0.value = s_D0_;
        s_.bind_step(d0, s_D0_name_);
        step n0;
        n0.sym = ex_to<symbol>(s_N0_);
        n0.value = s_N0_value_.subs(s_D0_ == d0.sym);
        const std::string n0_name = scope_.claim("N_0");
        s_.bind_step(n0, n0_name);
        s_.add_check(d0.sym, check::positive, "singular", "mu = 0: n.K n > 0, finite");
        s_.output(sel_N_name_, n0.sym);
        for (std::size_t a = 0; a < s_P0_.size(); ++a) {
            s_.output(sel_P_names_[a], s_P0_[a]);
            s_.output(sel_F_names_[a], 0);
        }
    }

    void build_stage_c()
    {
        std::map<ex, std::string, ex_is_less> extra;
        for (std::size_t a = 0; a < sel_P_.size(); ++a) {
            extra[sel_P_[a]] = sel_P_names_[a];
            extra[sel_F_[a]] = sel_F_names_[a];
        }
        extra[sel_N_] = sel_N_name_;
        downstream_names(c_, extra);
        for (std::size_t k = 0; k < outs_.size(); ++k)
            c_.output(outs_[k].field, c_values_[k]);
    }

    void build_unchanged()
    {
        u_.pool.set_input_names(input_ident_);
        for (std::size_t k = 0; k < outs_.size(); ++k)
            u_.output(outs_[k].field, outs_[k].tangential ? ex(0) : pl_.unchanged[outs_[k].smooth]);
    }

    // A stage's code with its outputs placed as the function uses them; the names it
    // declares are claimed.
    void emit_one(stage &s, const emit_options &how)
    {
        s.em = emit_cpp(s.prog, s.outs, s.checks, s.names, scope_.names(), how);
        for (const std::string &nm : s.em.declared)
            if (!scope_.taken(nm))
                scope_.claim(nm);
        add_counts(total_, s.em.formula);
    }

    // Stages A, B and the normal's basis declare their outputs as locals; stage S assigns
    // the selected impulse (declared before it); stage C writes the result, the energy
    // lost under with_energy_lost.
    void emit_stages()
    {
        emit_options locals, assign, result;
        locals.outputs = output_placement::local;
        assign.outputs = output_placement::assign;
        for (std::size_t k = 0; k < outs_.size(); ++k)
            if (outs_[k].kind == output_value::energy_lost)
                result.energy_output = static_cast<int>(k);
        if (!basis_names_.empty())
            nb_.em = emit_cpp(nb_.prog, nb_.outs, {}, {}, scope_.names(), locals);
        emit_one(a_, locals);
        if (angle_ >= 0)
            emit_one(b_, locals);
        if (!mu_name_.empty())
            emit_one(s_, assign);
        emit_one(c_, result);
        u_.em = emit_cpp(u_.prog, u_.outs, {}, {}, scope_.names());
        count_name_ = scope_.claim("n_holding");
        stick_holds_name_ = scope_.claim("stick_holds");
        regime_name_ = scope_.claim("regime_now");
        roots_c_name_ = scope_.claim("root_c");
        roots_s_name_ = scope_.claim("root_s");
        n_roots_name_ = scope_.claim("n_roots");
        every_name_ = scope_.claim("every_direction");
        edge_name_ = scope_.claim("stick_edge");
        loop_name_ = scope_.claim("k");
        apart_name_ = scope_.claim("n_apart");
        at_stick_name_ = scope_.claim("at_stick");
        merge_name_ = scope_.claim("merge");
        near_name_ = scope_.claim("slide_near");
        slides_finite_name_ = scope_.claim("slides_finite");
        keep_array_name_ = scope_.claim("keep");
        unique_name_ = scope_.claim("unique");
        pass_name_ = scope_.claim("pass");
    }

    // ---- text
    std::string params() const
    {
        std::string r;
        for (const std::string &nm : input_names_)
            r += "T " + nm + ", ";
        return r;
    }
    std::string args() const
    {
        std::string r;
        for (const std::string &nm : input_names_)
            r += nm + ", ";
        return r;
    }
    std::string result() const { return o_.name + "_result"; }
    std::string input_struct() const { return o_.name + "_input"; }

    void banner()
    {
        std::string command = "impactgen codegen " + o_.source + " --name " + o_.name + " --namespace " + o_.ns;
        if (o_.params_given)
            command += " --params " + join(o_.params, ",");
        if (!o_.set.empty()) {
            std::vector<std::string> kv;
            for (auto &[k, v] : o_.set)
                kv.push_back(k + "=" + v);
            command += " --set " + join(kv, ",");
        }
        if (o_.unit_normal)
            command += " --unit-normal";
        const char *kind = angle_ >= 0         ? "3-D, sliding direction found at run time"
                           : q_.dimension == 2 ? "planar"
                                               : "3-D, the contact response isotropic: sliding along u_t";
        h_ << "// Generated by impactgen " << o_.version << " from " << names::comment_text(o_.source)
           << ". Do not edit: regenerate.\n";
        h_ << "//   " << names::comment_text(command) << "\n";
        h_ << "// Closed forms of the impact with Coulomb friction (" << kind << "), specialised;\n";
        h_ << "// the regime selected by the derived inequalities. Plain C++17, no dependency, no allocation.\n";
        h_ << "// Arithmetic of the straight-line parts: " << counts_text(a_.em.formula)
           << " (shared steps, checks, candidates)";
        if (angle_ >= 0)
            h_ << ";\n//   " << counts_text(b_.em.formula) << " per sliding direction (at most 4)";
        h_ << ";\n//   " << counts_text(c_.em.formula) << " (post-impact state).\n";
        h_ << "#pragma once\n\n#include <cmath>\n#include <limits>\n\n";
    }

    // The smooth headers' preamble (codegen/runtime/impact_runtime.hpp: impact_status,
    // view, detail helpers) exactly as they write it, so that a friction header and smooth
    // ones share one copy in a namespace, then codegen/runtime/friction_runtime.hpp under
    // its own guard.
    void preamble() { h_ << impact_preamble(o_.ns) << friction_preamble(o_.ns); }

    void view_functions(const std::string &name, int rows, int cols, const std::vector<std::string> &entries,
                        const std::vector<std::string> &fixed, const std::string &meaning)
    {
        const std::string dims = std::to_string(rows) + ", " + std::to_string(cols);
        const std::string b = "{{" + join(entries, ", ") + "}, {" + join(fixed, ", ") + "}}";
        h_ << "    /// " << names::comment_text(meaning) << (cols == 1 ? " (vector)" : " (matrix, row-major)") << "\n";
        h_ << "    IMPACTGEN_MEMBER view<T, " << dims << "> " << name << "() noexcept { return " << b << "; }\n";
        h_ << "    IMPACTGEN_MEMBER view<const T, " << dims << "> " << name << "() const noexcept { return " << b
           << "; }\n";
    }

    void result_struct()
    {
        h_ << "/// Post-impact state of " << o_.name << " (units as the inputs).\n";
        h_ << "template <typename T> struct " << result() << " {\n";
        for (const out_field &of : outs_)
            h_ << "    T " << of.field << "; ///< " << names::comment_text(of.meaning) << "\n";
        h_ << "    impact_regime regime; ///< smooth (mu = 0), stick or slide; smooth when the status is not ok\n";
        for (std::size_t g = 0; g < pl_.output_groups.size(); ++g) {
            const group &gr = pl_.output_groups[g];
            std::vector<std::string> e, f;
            for (std::size_t k : gr.outputs) {
                e.push_back("&" + outs_[smooth_index_.at(k)].field);
                f.push_back("0.0L");
            }
            view_functions(out_views_[g], gr.rows, gr.cols, e, f, gr.meaning);
        }
        {
            std::vector<std::string> e, f;
            for (std::size_t k : tangential_index_) {
                e.push_back("&" + outs_[k].field);
                f.push_back("0.0L");
            }
            view_functions(tangential_view_, static_cast<int>(e.size()), 1, e, f,
                           "tangential (friction) impulse on " + q_.bodies[q_.contact.body2].name + ", world axes");
        }
        h_ << "};\n\n";
        h_ << "/// The inputs of " << o_.name << " by name (the same as its parameters).\n";
        h_ << "template <typename T> struct " << input_struct() << " {\n";
        for (std::size_t i = 0; i < input_names_.size(); ++i)
            h_ << "    T " << input_names_[i] << "; ///< " << names::comment_text(input_meaning_[i]) << "\n";
        for (std::size_t g = 0; g < pl_.input_groups.size(); ++g) {
            const group &gr = pl_.input_groups[g];
            std::vector<std::string> e, f;
            for (const ex &x : gr.inputs) {
                if (is_a<numeric>(x)) {
                    e.push_back("nullptr");
                    f.push_back(decimal_literal(ex_to<numeric>(x)));
                } else {
                    e.push_back("&" + input_ident_.at(x));
                    f.push_back("0.0L");
                }
            }
            view_functions(in_views_[g], gr.rows, gr.cols, e, f, gr.meaning);
        }
        h_ << "};\n\n";
    }

    void formula_block()
    {
        const int dim = q_.dimension;
        h_ << "// The law (impactgen's symbolic/friction.hpp): P = P_n n + P_t the impulse on body 2 (-P on\n";
        h_ << "// body 1), u the relative velocity v_B - v_A of the contact points, u_n = u.n < 0, and\n";
        h_ << "// u' = u + K P after the impact with K = K_1 + K_2 the contact response. Newton's law\n";
        h_ << "// u'.n = -e u_n and Coulomb's |P_t| <= mu P_n give the candidates\n";
        if (f_.stick())
            h_ << "//   stick: u'_t = 0, P = -K^{-1} (u + e u_n n), holding inside the friction cone;\n";
        else
            h_ << "//   (not stick: K is singular here -- a body pinned at a fixed point struck by one that cannot\n"
               << "//   move -- so no impulse stops the tangential slip while restitution holds)\n";
        h_ << "//   slide along a unit tangent d: P = N (n - mu d), D = n.K(n - mu d), N = -(1 + e) u_n / D,\n";
        h_ << "//          holding when D > 0 and u'_t = lambda d with lambda > 0;\n";
        if (angle_ >= 0) {
            h_ << "//   d = cos(theta) e_t + sin(theta) e_b with theta a root of g(theta) = n.(h x d),\n";
            h_ << "//       h = D u + a K (n - mu d), a = -(1 + e) u_n: a trigonometric polynomial of degree 2,\n";
            h_ << "//       a0 + a1 cos + b1 sin + a2 cos 2 + b2 sin 2 (trig_* below; detail::trig2_roots);\n";
            if (basis_names_.empty())
                h_ << "//   e_t = (" << frame_text(f_.e_t) << "), e_b = (" << frame_text(f_.e_b) << ").\n";
            else
                h_ << "//   e_t, e_b: a unit tangent basis with e_b = e_t x n, computed for the normal at run time\n"
                   << "//       (detail::tangent_basis: any direction, the axes included).\n";
        } else if (dim == 2) {
            h_ << "//   d = +e_t or -e_t, e_t = (" << frame_text(d_.t_dir) << ").\n";
        } else {
            h_ << "//   d = u_t / |u_t| (K isotropic on the tangent plane and uncoupled from n).\n";
        }
        h_ << "// mu = 0 is the smooth impact. Exactly one candidate holding is the answer; none: no_solution;\n";
        if (f_.stick()) {
            h_ << "// several: ambiguous, except at the stick/slide boundary within rounding: when a slide's impulse\n";
            h_ << "// is the stick candidate's to within eps^(2/3) relative (detail::boundary_tolerance) and no\n";
            h_ << "// candidate apart from them holds, the answer is stick (the two are one solution).\n";
        } else {
            h_ << "// several: ambiguous.\n";
        }
        h_ << "// The conditions of each candidate:\n";
        for (std::size_t i = 0; i < f_.cases.size(); ++i) {
            const regime_case &c = f_.cases[i];
            for (std::size_t j = 0; j < c.conditions.size(); ++j)
                h_ << "//   " << names::comment_text(c.name) << ": " << names_[i].cond[j] << " "
                   << (c.conditions[j].strict ? "> 0" : ">= 0") << "  (" << names::comment_text(c.conditions[j].meaning)
                   << ")\n";
        }
        h_ << "// This problem, step by step, as the code below computes it (shared steps, checks, candidates):\n";
        for (const auto &[lhs, rhs] : a_.em.assignments)
            h_ << wrap_comment(lhs, rhs);
        if (angle_ >= 0) {
            h_ << "// The slide along d = " << dir_c_name_ << " e_t + " << dir_s_name_ << " e_b, at each root of g:\n";
            for (const auto &[lhs, rhs] : b_.em.assignments)
                h_ << wrap_comment(lhs, rhs);
        }
        if (!mu_name_.empty()) {
            h_ << "// mu = 0:\n";
            for (const auto &[lhs, rhs] : s_.em.assignments)
                h_ << wrap_comment(lhs, rhs);
        }
        h_ << "// The post-impact state for the impulse sel_P (normal impulse sel_N, tangential sel_F) of the "
              "regime:\n";
        for (const auto &[lhs, rhs] : c_.em.assignments)
            h_ << wrap_comment(lhs, rhs);
        h_ << "\n";
    }

    std::string frame_text(const vec3 &v) const
    {
        std::vector<std::string> parts;
        for (int a = 0; a < q_.dimension; ++a) {
            std::ostringstream os;
            const ex x = tidy(v[static_cast<std::size_t>(a)]);
            if (is_a<numeric>(x))
                os << x;
            else
                os << "...";
            parts.push_back(os.str());
        }
        return join(parts, ", ");
    }

    void unchanged_function()
    {
        h_ << "namespace detail {\n";
        h_ << "/// What a failed call of " << o_.name << " returns: the state unchanged (velocities as\n";
        h_ << "/// before; impulses, approach velocity and energy lost zero; regime smooth).\n";
        h_ << "template <typename T> IMPACTGEN_COLD IMPACTGEN_FUNC void " << o_.name << "_unchanged(";
        for (const std::string &nm : input_names_)
            h_ << "T " << (uses(u_.em.code, nm) ? nm : "/*" + nm + "*/") << ", ";
        h_ << result() << "<T>& out) noexcept\n{\n";
        if (u_.em.uses_sqrt)
            h_ << "    using std::sqrt;\n";
        h_ << u_.em.code;
        h_ << "    out.regime = impact_regime::smooth;\n";
        h_ << "}\n} // namespace detail\n\n";
    }

    // The conditions of a candidate, folded as unsigned (no branch implied, and nothing for
    // clang's -Wbitwise-instead-of-logical to say).
    std::string holds_text(const case_names &cn, const regime_case &c) const
    {
        std::vector<std::string> parts;
        for (std::size_t j = 0; j < cn.cond.size(); ++j)
            parts.push_back("static_cast<unsigned>(" + cn.cond[j] +
                            (c.conditions[j].strict ? " > T(0))" : " >= T(0))"));
        if (parts.empty())
            return "true";
        if (parts.size() == 1)
            return "(" + parts[0] + " != 0u)";
        return "((" + join(parts, " & ") + ") != 0u)";
    }

    std::string select_text(const case_names &cn, const std::string &regime, const std::string &ind) const
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
    std::string merge_text() const
    {
        const case_names &sn = names_.front();
        std::string size = "detail::abs_of(" + sn.P[0] + ")";
        for (std::size_t a = 1; a < sn.P.size(); ++a)
            size = "detail::max_of(" + size + ", detail::abs_of(" + sn.P[a] + "))";
        return "detail::boundary_tolerance<T>() * " + size;
    }
    std::string near_text(const case_names &cn) const
    {
        const case_names &sn = names_.front();
        std::vector<std::string> parts;
        for (std::size_t a = 0; a < cn.P.size(); ++a)
            parts.push_back("detail::abs_of(" + cn.P[a] + " - " + sn.P[a] + ") <= " + merge_name_);
        return join(parts, " && ");
    }

    // Counting the closed-form candidates that hold; they are selected without a branch (the
    // first that holds: stick when there is one, then the slides; the last when none does:
    // replaced below). Only the rare boundary and failure cases branch.
    void emit_closed_forms(const std::string &ind)
    {
        const bool stick = f_.stick() != nullptr;
        for (std::size_t i = 0; i < f_.cases.size(); ++i)
            if (static_cast<int>(i) != angle_) {
                closed_.push_back(i);
                holds_.push_back(stick && i == 0 ? stick_holds_name_ : scope_.claim(names_[i].prefix + "holds"));
                h_ << ind << "const bool " << holds_.back() << " = " << holds_text(names_[i], f_.cases[i]) << "; // "
                   << names::comment_text(f_.cases[i].name) << "\n";
            }
        for (const std::string &hname : holds_)
            counted_.push_back("static_cast<int>(" + hname + ")");
        h_ << ind << "int " << count_name_ << " = " << counted_text() << ";\n";
        if (stick)
            h_ << ind << regime_name_ << " = " << stick_holds_name_
               << " ? impact_regime::stick : impact_regime::slide;\n";
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
    }
    std::string counted_text() const { return counted_.empty() ? std::string("0") : join(counted_, " + "); }

    // The 3-D slide without closed form: its directions (pass 0: the one direction when the
    // solution is provably unique; pass 1: every root of g), each a candidate.
    void emit_angle_search(const std::string &ind)
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
           << fast_names_[4] << ", " << fast_names_[5] << ", " << roots_c_name_ << "[0], " << roots_s_name_
           << "[0]))\n";
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
    void emit_root_loop(const std::string &ind)
    {
        const bool stick = f_.stick() != nullptr;
        const case_names &cn = names_[static_cast<std::size_t>(angle_)];
        const regime_case &c = f_.cases[static_cast<std::size_t>(angle_)];
        const std::string i2 = ind + "    ";
        h_ << ind << "for (int " << loop_name_ << " = 0; " << loop_name_ << " < " << n_roots_name_ << "; ++"
           << loop_name_ << ") {\n";
        h_ << i2 << "const T " << dir_c_name_ << " = " << roots_c_name_ << "[" << loop_name_ << "];\n";
        h_ << i2 << "const T " << dir_s_name_ << " = " << roots_s_name_ << "[" << loop_name_ << "];\n";
        h_ << indent(b_.em.code, ind);
        std::vector<std::string> slide_values = cn.cond;
        slide_values.push_back(cn.N);
        h_ << i2 << slides_finite_name_ << " = " << slides_finite_name_ << " && detail::finite("
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
    void emit_unresolved(const std::string &ind)
    {
        const bool stick = f_.stick() != nullptr;
        const std::string i2 = ind + "    ";
        std::vector<std::string> values;
        for (std::size_t i = 0; i < names_.size(); ++i) {
            if (static_cast<int>(i) == angle_)
                continue;
            const case_names &cn = names_[i];
            values.push_back(cn.N);
            values.insert(values.end(), cn.P.begin(), cn.P.end());
            values.insert(values.end(), cn.cond.begin(), cn.cond.end());
        }
        values.insert(values.end(), trig_names_.begin(), trig_names_.end());
        const std::string finite = "if (!detail::finite(" + balanced_sum(values) + ")" +
                                   (angle_ >= 0 ? " || !" + slides_finite_name_ : std::string()) + ")\n";
        const std::string verdict =
            "return fail(" + count_name_ + " == 0 ? friction_status::no_solution : friction_status::ambiguous);\n";
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

    void main_function()
    {
        h_ << "/// Post-impact state for the inputs below, with Coulomb friction at the contact; returns\n";
        h_ << "/// friction_status::ok with out.regime the regime that holds, or why not (then out holds the\n";
        h_ << "/// state unchanged: velocities as before, impulses zero). T: float, double or long double.\n";
        h_ << "/// with_energy_lost = false: out.energy_lost is left 0 (the rest is the same).\n";
        for (std::size_t i = 0; i < input_names_.size(); ++i)
            h_ << "///   " << input_names_[i] << ": " << names::comment_text(input_meaning_[i]) << "\n";
        h_ << "template <typename T, bool with_energy_lost = true>\nIMPACTGEN_FUNC friction_status " << o_.name << "("
           << params() << result() << "<T>& out) noexcept\n{\n";
        h_ << "    using std::sqrt;\n";
        h_ << "    auto fail = [&](auto why) noexcept {\n";
        h_ << "        detail::" << o_.name << "_unchanged(" << args() << "out);\n";
        if (input_names_.empty())
            h_ << "        return detail::friction_status_of(why);\n";
        else
            h_ << "        return detail::all_finite(" << join(input_names_, ", ")
               << ") ? detail::friction_status_of(why) : friction_status::non_finite_input;\n";
        h_ << "    };\n";
        const ex &mu = q_.contact.friction();
        const bool mu_input = is_a<symbol>(mu) && input_ident_.count(mu);
        const std::string mu_check =
            "    if (!(" + mu_name_ + " >= T(0) && detail::finite(" + mu_name_ +
            "))) // mu >= 0, finite\n        return fail(friction_status::invalid_friction);\n";
        if (mu_input)
            h_ << mu_check;
        if (!basis_names_.empty()) {
            h_ << "    // The unit tangent basis e_t, e_b of the contact plane for this normal (any direction).\n";
            h_ << nb_.em.code;
            h_ << "    T " << basis_t_name_ << "[3], " << basis_b_name_ << "[3];\n";
            h_ << "    detail::tangent_basis<T>(" << nb_.outs[0].first << ", " << nb_.outs[1].first << ", "
               << nb_.outs[2].first << ", " << basis_t_name_ << ", " << basis_b_name_ << ");\n";
            for (std::size_t k = 0; k < basis_names_.size(); ++k)
                h_ << "    const T " << basis_names_[k] << " = " << (k < 3 ? basis_t_name_ : basis_b_name_) << "["
                   << k % 3 << "];\n";
        }
        h_ << "    // Shared steps, checks, the candidates and their conditions.\n";
        h_ << a_.em.code;
        if (!mu_input && !mu_name_.empty())
            h_ << mu_check;
        h_ << "    // The regime that holds: its impulse (world axes, on "
           << names::comment_text(q_.bodies[q_.contact.body2].name) << "), normal and tangential impulse.\n";
        h_ << "    T " << sel_N_name_ << " = T(0);\n";
        for (std::size_t a = 0; a < sel_P_names_.size(); ++a)
            h_ << "    T " << sel_P_names_[a] << " = T(0);\n    T " << sel_F_names_[a] << " = T(0);\n";
        h_ << "    impact_regime " << regime_name_ << " = impact_regime::smooth;\n";
        std::string ind = "    ";
        if (!mu_name_.empty()) {
            h_ << "    if (" << mu_name_ << " == T(0)) { // the smooth impact\n";
            h_ << indent(s_.em.code, "    ");
            h_ << "    } else {\n";
            ind = "        ";
        } else {
            h_ << "    {\n";
            ind = "        ";
        }
        emit_closed_forms(ind);
        if (angle_ >= 0)
            emit_angle_search(ind);
        emit_unresolved(ind);
        h_ << "    }\n";
        h_ << "    // The post-impact state.\n";
        h_ << c_.em.code;
        h_ << "    out.regime = " << regime_name_ << ";\n";
        std::vector<std::string> terms;
        for (const out_field &of : outs_)
            terms.push_back("out." + of.field);
        for (const std::string &nm : input_names_)
            terms.push_back(nm);
        h_ << "    const T check_sum = " << balanced_sum(terms) << ";\n";
        h_ << "    if (!detail::finite(check_sum))\n";
        h_ << "        return fail(friction_status::overflow);\n";
        h_ << "    return friction_status::ok;\n}\n\n";
    }

    void array_form()
    {
        h_ << "/// The same with the inputs in an array, in the order of " << o_.name << "_input_names.\n";
        h_ << "template <typename T, bool with_energy_lost = true>\nIMPACTGEN_HOT IMPACTGEN_FUNC friction_status "
           << o_.name << "(const T* in, " << result() << "<T>& out) noexcept\n{\n";
        if (input_names_.empty())
            h_ << "    (void)in;\n";
        h_ << "    return " << o_.name << "<T, with_energy_lost>(";
        for (std::size_t i = 0; i < input_names_.size(); ++i)
            h_ << "in[" << i << "], ";
        h_ << "out);\n}\n\n";
    }

    void struct_form()
    {
        h_ << "/// The same with the inputs by name: " << input_struct() << "<T> in{}; in.e = ...;\n";
        h_ << "template <typename T, bool with_energy_lost = true>\nIMPACTGEN_HOT IMPACTGEN_FUNC friction_status "
           << o_.name << "(const " << input_struct() << "<T>& in, " << result() << "<T>& out) noexcept\n{\n";
        if (input_names_.empty())
            h_ << "    (void)in;\n";
        h_ << "    return " << o_.name << "<T, with_energy_lost>(";
        for (const std::string &nm : input_names_)
            h_ << "in." << nm << ", ";
        h_ << "out);\n}\n\n";
    }

    void batch_form()
    {
        std::size_t energy_index = outs_.size();
        for (std::size_t j = 0; j < outs_.size(); ++j)
            if (outs_[j].kind == output_value::energy_lost)
                energy_index = j;
        h_ << "/// The same over n impacts in structure-of-arrays form: in[j][i] is input j (order of\n";
        h_ << "/// " << o_.name << "_input_names) of impact i, out[j][i] output j (order of " << o_.name
           << "_output_names),\n";
        h_ << "/// status[i] its status and, unless regime is null, regime[i] its regime. One call of " << o_.name
           << "\n";
        h_ << "/// per impact (the regime selection branches).";
        if (energy_index < outs_.size())
            h_ << " with_energy_lost = false: out[" << energy_index << "] is not written (it may be null).";
        h_ << "\n";
        h_ << "template <typename T, bool with_energy_lost = true>\nIMPACTGEN_FUNC void " << o_.name
           << "_batch(long n, const T* const* in, T* const* out, friction_status* status, impact_regime* regime) "
              "noexcept\n{\n";
        if (input_names_.empty())
            h_ << "    (void)in;\n";
        h_ << "    for (long i = 0; i < n; ++i) {\n";
        h_ << "        " << result() << "<T> r;\n";
        h_ << "        status[i] = " << o_.name << "<T, with_energy_lost>(";
        for (std::size_t j = 0; j < input_names_.size(); ++j)
            h_ << "in[" << j << "][i], ";
        h_ << "r);\n";
        for (std::size_t j = 0; j < outs_.size(); ++j)
            h_ << (j == energy_index ? "        if constexpr (with_energy_lost)\n    " : "") << "        out[" << j
               << "][i] = r." << outs_[j].field << ";\n";
        h_ << "        if (regime)\n            regime[i] = r.regime;\n";
        h_ << "    }\n}\n\n";
    }

    void tables()
    {
        h_ << "inline constexpr int " << o_.name << "_input_count = " << input_names_.size() << ";\n";
        h_ << "inline constexpr int " << o_.name << "_output_count = " << outs_.size() << ";\n";
        h_ << "inline constexpr const char* " << o_.name << "_input_names[] = {";
        for (const std::string &nm : input_names_)
            h_ << names::cpp_string_literal(nm) << ", ";
        h_ << "nullptr};\n";
        h_ << "inline constexpr const char* " << o_.name << "_output_names[] = {";
        for (const out_field &of : outs_)
            h_ << names::cpp_string_literal(of.field) << ", ";
        h_ << "nullptr};\n\n";
        h_ << "/// The members of r in the order of " << o_.name << "_output_names (the regime is not among them).\n";
        h_ << "template <typename T> IMPACTGEN_FUNC void " << o_.name << "_to_array(const " << result()
           << "<T>& r, T* a) noexcept\n{\n";
        for (std::size_t i = 0; i < outs_.size(); ++i)
            h_ << "    a[" << i << "] = r." << outs_[i].field << ";\n";
        h_ << "}\n\n} // namespace " << o_.ns << "\n";
    }

    // ---- state
    const options &o_;
    problem q_;
    plan pl_;
    derivation d_;
    friction_solution f_;
    int angle_ = -1;
    std::vector<symbol> inputs_;
    std::vector<std::string> input_meaning_, input_names_;
    std::map<ex, std::string, ex_is_less> input_ident_;
    std::vector<out_field> outs_;
    std::map<std::size_t, std::size_t> smooth_index_;
    std::vector<std::size_t> tangential_index_;
    // A normal given as inputs (3-D): the tangent basis computed at run time.
    stage nb_;
    std::vector<std::string> basis_names_;
    std::string basis_t_name_, basis_b_name_;
    names::identifier_scope scope_, members_, in_members_;
    std::vector<std::string> in_views_, out_views_;
    std::string tangential_view_;
    exset local_, a_step_syms_;
    std::vector<step> a_steps_, b_steps_, b_steps_linked_;
    std::vector<std::string> a_step_names_, b_step_names_;
    std::map<ex, std::string, ex_is_less> step_name_;
    std::vector<symbol> sel_P_, sel_F_;
    symbol sel_N_{"friction_N"};
    std::vector<std::string> sel_P_names_, sel_F_names_;
    std::string sel_N_name_;
    std::vector<ex> c_values_;
    ex s_D0_, s_N0_, s_N0_value_;
    std::vector<ex> s_P0_;
    std::string s_D0_name_;
    ex b_N_;
    std::vector<ex> b_P_, b_F_, b_cond_;
    std::vector<std::pair<ex, symbol>> power_links_;
    std::map<ex, std::string, ex_is_less> link_names_;
    std::map<ex, ex, ex_is_less> link_value_;
    std::vector<ex> link_order_;
    std::vector<case_names> names_;
    std::vector<std::size_t> closed_;  // the closed-form candidates, stick first (when there is one)
    std::vector<std::string> holds_;   // their flags
    std::vector<std::string> counted_; // the flags as ints
    std::vector<std::string> trig_names_, keep_names_, fast_names_;
    std::string mu_name_, dir_c_name_, dir_s_name_;
    std::string keep_array_name_, unique_name_, pass_name_;
    std::string loop_name_, tau_name_, slides_finite_name_, apart_name_, at_stick_name_, merge_name_, near_name_;
    std::string count_name_, stick_holds_name_, regime_name_, roots_c_name_, roots_s_name_, n_roots_name_, every_name_,
        edge_name_;
    stage a_, b_, s_, c_, u_;
    op_counts total_;
    std::ostringstream h_;
};

} // namespace

bool has_friction(const problem &p, const options &o)
{
    if (!p.has_friction())
        return false;
    try {
        options so = o;
        so.params_given = false; // only --set can make mu 0
        so.params.clear();
        return specialise(p, so).has_friction();
    } catch (const std::exception &) {
        return true;
    }
}

header generate_friction(const problem &p, const options &o)
{
    if (!names::is_safe_identifier(o.name) || reserved().count(o.name) || o.name.back() == '_')
        throw option_error(
            option_error::function_name,
            "\"" + names::display_text(o.name) +
                "\" is not a usable C++ identifier (letters, digits and single underscores, not ending in one; "
                "not a keyword or a reserved name)");
    if (std::string why = names::namespace_problem(o.ns); !why.empty())
        throw option_error(option_error::name_space, "\"" + names::display_text(o.ns) + "\": " + why);
    return friction_writer(p, o).run();
}

} // namespace impactgen::codegen
