#include "codegen.hpp"
#include "form_text.hpp"
#include "friction.hpp"
#include "runtime.hpp"
#include "text.hpp"

#include "names/escape.hpp"
#include "names/identifier.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/response.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

namespace impactgen::codegen
{
using namespace GiNaC;

namespace
{
using namespace form_text;

const char *const tparams = "template <typename T, bool with_energy_lost = true>\n";

// A body's 3-D inertia tensor as the closed form inverts it: about its centre of mass
// (free) or about its pivot E (pinned: I_C + m (|d|^2 1 - d d^T), d = C - E), each
// entry the solution's step where it has one (the very value the code computes).
mat3 tensor_in_use(const problem &q, const solution &s, std::size_t i)
{
    const body &b = q.bodies[i];
    const pivot *pv = q.pivot_of(i);
    if (!pv)
        return b.inertia;
    mat3 J = inertia_about(b, pv->point);
    for (int r = 0; r < 3; ++r)
        for (int c = r; c < 3; ++c)
            if (const step *st = s.find(step_role::pivot_inertia, i, r, c))
                J[r][c] = J[c][r] = st->sym;
    return J;
}

// One header: the plan lowered to a program, three emitted forms of it
// (checked, fast, batch), and the text, section by section.
class writer
{
public:
    writer(const problem &p, const options &o) : o_(o), pl_(make_plan(p, o)) {}

    header run()
    {
        name_everything();
        lower_program();
        add_checks();
        emit_forms();
        banner();
        preamble();
        result_struct();
        formula_block();
        checked_function();
        fast_function();
        array_form();
        struct_form();
        jacobian_function();
        batch_form();
        tables();
        header out;
        out.text = h_.str();
        out.formula = em_.formula;
        out.checks = em_.checks;
        out.inputs = input_names_;
        for (const output_value &ov : pl_.outputs)
            out.outputs.push_back(ov.field);
        return out;
    }

private:
    // Every name the header declares comes from one scope (names/identifier.hpp):
    // the emitter's own names first, then inputs, steps and the locals derived
    // from outputs and inputs, so no user name can shadow or collide with another.
    void name_everything()
    {
        for (const std::string &r : reserved())
            if (names::is_safe_identifier(r))
                scope_.reserve(r);
        for (names::identifier_scope *sc : {&in_members_, &members_})
            for (const char *own : {"view", "T"})
                sc->reserve(own); // a member so named would hide the template parameter or the view type

        for (const char *suffix : {"", "_result", "_input", "_unchanged", "_jacobian", "_jacobian_result", "_wrt_count",
                                   "_wrt_names", "_checked", "_batch", "_batch_pass", "_input_count", "_output_count",
                                   "_input_names", "_output_names", "_ops", "_to_array"})
            scope_.reserve(o_.name + suffix);
        std::map<ex, std::string, ex_is_less> input_ident; // input symbol -> C++ parameter
        for (const symbol &x : pl_.inputs) {
            input_names_.push_back(scope_.claim(x.get_name()));
            input_ident[x] = input_names_.back();
        }
        for (output_value &ov : pl_.outputs)
            ov.field = members_.claim(ov.field);
        pool_.set_input_names(input_ident);
        for (const step &st : pl_.sol.steps)
            step_names_.push_back(scope_.claim(st.sym.get_name()));
        for (const output_value &ov : pl_.outputs) {
            local_of_[ov.field] = scope_.claim("o_" + ov.field);
            out_ptr_[ov.field] = scope_.claim("out_" + ov.field);
        }
        for (const std::string &nm : input_names_)
            in_ptr_[nm] = scope_.claim("in_" + nm);
        if (pl_.has_jacobian) {
            for (const step &st : pl_.jac.steps)
                jac_step_names_.push_back(scope_.claim(st.sym.get_name()));
            for (const symbol &x : pl_.jac.wrt)
                wrt_names_.push_back(input_ident.at(x));
            for (const output_value &ov : pl_.outputs) {
                std::vector<std::string> row;
                for (const std::string &w : wrt_names_)
                    row.push_back(scope_.claim("d_" + ov.field + "_d_" + w));
                jac_local_.push_back(row);
            }
        }
        input_ident_ = input_ident;
        status_ptr_ = scope_.claim("status_out");
        // The input struct's members are the parameters' names; the views of both
        // structs are member functions, named clear of the members.
        for (const std::string &nm : input_names_)
            in_members_.claim(nm);
        for (const group &g : pl_.input_groups)
            in_views_.push_back(in_members_.claim(g.name));
        for (const group &g : pl_.output_groups)
            out_views_.push_back(members_.claim(g.name));
    }

    // Canonical trees of the steps and outputs, then the straight-line program.
    void lower_program()
    {
        const solution &s = pl_.sol;
        for (std::size_t i = 0; i < s.steps.size(); ++i) {
            const std::string &nm = step_names_[i];
            scaled v = pool_.convert(s.steps[i].value);
            pool_.bind_step(s.steps[i].sym, static_cast<int>(i), nm);
            prog_.set_owner(nm);
            int id = prog_.lower(pool_, v);
            prog_.set_step(static_cast<int>(i), id);
            if (!prog_.is_leaf(id) && !var_names_.count(id))
                var_names_[id] = nm;
        }
        for (const output_value &ov : pl_.outputs) {
            scaled v = pool_.convert(ov.value);
            prog_.set_owner(ov.field);
            outs_.push_back({ov.field, prog_.lower(pool_, v)});
            outs_local_.push_back({local_of_.at(ov.field), outs_.back().second});
        }
        if (pl_.has_jacobian) {
            const std::size_t base = s.steps.size();
            for (std::size_t i = 0; i < pl_.jac.steps.size(); ++i) {
                const std::string &nm = jac_step_names_[i];
                scaled v = pool_.convert(pl_.jac.steps[i].value);
                pool_.bind_step(pl_.jac.steps[i].sym, static_cast<int>(base + i), nm);
                prog_.set_owner(nm);
                int id = prog_.lower(pool_, v);
                prog_.set_step(static_cast<int>(base + i), id);
                if (!prog_.is_leaf(id) && !var_names_.count(id))
                    var_names_[id] = nm;
            }
            for (std::size_t o = 0; o < pl_.outputs.size(); ++o)
                for (std::size_t j = 0; j < wrt_names_.size(); ++j) {
                    prog_.set_owner(jac_local_[o][j]);
                    jac_outs_.push_back({jac_local_[o][j], prog_.lower(pool_, pool_.convert(pl_.jac.entries[o][j]))});
                }
        }
        lst inverses; // the engine convention: a mass m is 1/inv_m
        for (const auto &[old, inv] : pl_.inverse_of)
            inverses.append(old == 1 / inv);
        for (std::size_t k = 0; k < pl_.outputs.size(); ++k) {
            prog_.set_owner("unchanged");
            unchanged_outs_.push_back(
                {pl_.outputs[k].field, prog_.lower(pool_, pool_.convert(pl_.unchanged[k].subs(inverses)))});
        }
    }

    void add_check(const ex &value0, check::kind_t kind, const std::string &status, const std::string &comment)
    {
        // In the engine convention the masses (and planar inertia) are inputs only as
        // inverses: a checked value that uses them (an inertia m L^2/12) uses 1/inv_m.
        ex value = value0;
        if (!is_a<symbol>(value0) || !pl_.meaning.count(value0)) {
            lst inverses;
            for (const auto &[old, inv] : pl_.inverse_of)
                inverses.append(old == 1 / inv);
            value = value0.subs(inverses);
        }
        if (is_a<numeric>(value))
            return; // constants were validated when the problem was read
        prog_.set_owner("check");
        checks_.push_back({kind, prog_.lower(pool_, pool_.convert(value)), status, comment});
    }

    // Validity checks of the inputs and of the steps, by the steps' roles.
    void add_checks()
    {
        const problem &q = pl_.prob;
        const solution &s = pl_.sol;
        add_check(q.restitution, check::unit_interval, "invalid_restitution", "0 <= e <= 1");
        auto inverse = [&](const ex &x) -> const symbol * {
            auto it = pl_.inverse_of.find(x);
            return it == pl_.inverse_of.end() ? nullptr : &it->second;
        };
        for (std::size_t i : {q.contact().body1, q.contact().body2}) {
            const body &b = q.bodies[i];
            if (b.infinite_mass)
                continue;
            const symbol *inv_m = inverse(b.mass);
            add_check(inv_m ? ex(*inv_m) : b.mass, check::positive, "invalid_mass",
                      (inv_m ? "inverse mass of " : "mass of ") + b.name + " > 0, finite");
            if (!b.particle && q.dimension == 2) {
                const symbol *inv_I = inverse(b.inertia[2][2]);
                add_check(inv_I ? ex(*inv_I) : b.inertia[2][2], check::positive, "invalid_inertia",
                          (inv_I ? "inverse moment of inertia of " : "moment of inertia of ") + b.name +
                              " > 0, finite");
            }
        }
        // Positive definiteness of each 3-D inertia tensor the closed form inverts (about C,
        // or about the pivot E), or in the engine convention of the inverse tensor given:
        // leading principal minors, block by block. Entries or minors that are numbers
        // were validated when the problem was read; the determinant is its own step below.
        for (std::size_t i : {q.contact().body1, q.contact().body2}) {
            const body &b = q.bodies[i];
            if (q.dimension != 3 || b.particle || b.infinite_mass)
                continue;
            auto inv = pl_.inverse_tensor.find(i);
            const bool inverse_given = inv != pl_.inverse_tensor.end();
            const std::string what = (inverse_given ? "inverse inertia tensor of " : "inertia tensor of ") + b.name +
                                     (q.pivot_of(i) && !inverse_given ? " about its pivot" : "") +
                                     " positive definite: ";
            for (const auto &[minor, text] :
                 positive_definite_minors(inverse_given ? inv->second : tensor_in_use(q, s, i), q.axes, inverse_given))
                add_check(minor, check::positive, "invalid_inertia", what + text);
        }
        // A normal with symbols: its squared length a normal number before anything divides
        // by the length; declared unit (--unit-normal), of length 1 within 2^-17.
        const ex nn = tidy(dot(q.contact().normal, q.contact().normal));
        if (!is_constant(nn)) {
            if (pl_.deriv.normal_assumed_unit)
                add_check(nn, check::near_one, "invalid_normal", "the normal is a unit vector: |n.n - 1| <= 2^-17");
            else
                add_check(nn, check::normal_number, "invalid_normal",
                          "n.n a normal number: the normal neither zero, denormal nor too long");
        }
        const bool has_k = s.find(step_role::contact_inverse_mass) != nullptr;
        for (const step &st : s.steps) {
            switch (st.role) {
            case step_role::normal_impulse:
                if (!has_k) // k = w_1 + w_2 too simple to be a step: N's denominator
                    add_check(st.value.denom(), check::positive, "singular", "effective inverse mass k > 0, finite");
                break;
            case step_role::inertia_determinant:
                add_check(st.sym, check::positive, "invalid_inertia", "determinant of the inertia tensor > 0, finite");
                break;
            case step_role::approach_velocity:
                add_check(st.sym, check::negative, "not_approaching", "the contact points approach: u < 0");
                break;
            case step_role::contact_inverse_mass:
                add_check(st.sym, check::positive, "singular", "effective inverse mass k > 0, finite");
                break;
            default:
                break;
            }
        }
    }

    // The checked form (a division each, a branch per check), the fast form (one flag,
    // one branch: latency) and the batch form (reciprocals share divisions: throughput).
    void emit_forms()
    {
        const std::vector<std::string> taken = scope_.names();
        // energy_lost: the fast and batch forms leave it 0 under with_energy_lost = false.
        int energy = -1;
        for (std::size_t k = 0; k < pl_.outputs.size(); ++k)
            if (pl_.outputs[k].kind == output_value::energy_lost)
                energy = static_cast<int>(k);
        em_ = emit_cpp(prog_, outs_, checks_, var_names_, taken);
        fast_ = emit_cpp(prog_, outs_local_, checks_, var_names_, taken, branchless_form(false, energy));
        batch_ = emit_cpp(prog_, outs_local_, checks_, var_names_, taken, branchless_form(true, energy));
        unchanged_ = emit_cpp(prog_, unchanged_outs_, {}, {}, taken);
        // Inputs the outputs do not depend on still count for the finiteness check.
        std::set<std::string> reached;
        for (std::size_t i = 0; i < prog_.size(); ++i)
            if (prog_.at(static_cast<int>(i)).kind == op::input)
                reached.insert(prog_.at(static_cast<int>(i)).name);
        for (const auto &[field, id] : outs_)
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
        for (const auto &[id, nm] : var_names_)
            id_of_name[nm] = id;
        const std::vector<bool> implied = implied_outputs(energy);
        // The terms of the finiteness check in the branchless forms (local output values).
        auto finite_terms = [&](const emitted &form, bool energy_optional) {
            std::vector<sum_term> t;
            auto has = [&](const std::string &x) {
                return std::any_of(t.begin(), t.end(), [&](const sum_term &y) { return y.text == x; });
            };
            for (std::size_t k = 0; k < outs_.size(); ++k)
                if (needs_check(outs_[k].second) && !implied[k])
                    t.push_back({local_of_.at(outs_[k].first), ready[static_cast<std::size_t>(outs_[k].second)],
                                 energy_optional && static_cast<int>(k) == energy});
            for (const std::string &nm : unused_inputs)
                t.push_back({nm, 0, false});
            for (const std::string &x : form.finite_terms)
                if (!has(x))
                    t.push_back(
                        {x, id_of_name.count(x) ? ready[static_cast<std::size_t>(id_of_name.at(x))] : 0, false});
            return t;
        };
        fast_terms_ = finite_terms(fast_, true);
        batch_terms_ = finite_terms(batch_, true);
        if (pl_.has_jacobian) {
            std::vector<std::pair<std::string, int>> all = outs_local_;
            all.insert(all.end(), jac_outs_.begin(), jac_outs_.end());
            jac_ = emit_cpp(prog_, all, checks_, var_names_, taken, branchless_form(false, -1));
            jac_terms_ = finite_terms(jac_, false);
            for (const auto &[local, id] : jac_outs_)
                if (needs_check(id))
                    jac_terms_.push_back({local, ready[static_cast<std::size_t>(id)], false});
        }
    }

    // Every output but small exact constants (0, 1/2): a folded constant can be
    // beyond the range of float, or of double.
    bool needs_check(int id) const
    {
        const op &o = prog_.at(id);
        const numeric small(16777216); // 2^24: exact in float
        return o.kind != op::constant || !o.value.is_rational() || abs(o.value.numer()) > small ||
               o.value.denom() > small;
    }

    // When each value is ready: a latency estimate from the inputs (cycles of a
    // current x86 core), to add the terms of the finiteness sum in that order.
    std::vector<int> ready_times() const
    {
        std::vector<int> ready(prog_.size(), 0);
        for (std::size_t i = 0; i < prog_.size(); ++i) {
            const op &o = prog_.at(static_cast<int>(i));
            int cost = 0;
            switch (o.kind) {
            case op::input:
            case op::constant:
                cost = 0;
                break;
            case op::add:
            case op::sub:
            case op::neg:
                cost = 3;
                break;
            case op::mul:
                cost = 4;
                break;
            case op::div:
                cost = 14;
                break;
            case op::sqrt_:
                cost = 20;
                break;
            }
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
    std::vector<bool> implied_outputs(int energy) const
    {
        std::vector<bool> implied(outs_.size(), false);
        for (std::size_t j = 0; j < outs_.size(); ++j) {
            if (static_cast<int>(j) == energy)
                continue;
            std::vector<bool> seen(prog_.size(), false);
            std::vector<int> stack;
            auto operands = [&](int id) {
                const op &o = prog_.at(id);
                if (o.a >= 0)
                    stack.push_back(o.a);
                if (o.b >= 0 && o.kind != op::div)
                    stack.push_back(o.b);
            };
            operands(outs_[j].second);
            while (!stack.empty()) {
                const int id = stack.back();
                stack.pop_back();
                if (seen[static_cast<std::size_t>(id)])
                    continue;
                seen[static_cast<std::size_t>(id)] = true;
                operands(id);
            }
            for (std::size_t k = 0; k < outs_.size(); ++k)
                if (k != j &&
                    (seen[static_cast<std::size_t>(outs_[k].second)] || (outs_[k].second == outs_[j].second && k > j)))
                    implied[k] = true;
        }
        return implied;
    }

    void banner()
    {
        const std::string command = command_line(o_);
        h_ << "// Generated by impactgen " << o_.version << " from " << names::comment_text(o_.source)
           << ". Do not edit: regenerate.\n";
        h_ << "//   " << names::comment_text(command) << "\n";
        h_ << "// Closed form of the smooth impact, specialised; plain C++17, no dependency, no allocation.\n";
        h_ << "// Arithmetic per call: " << counts_text(em_.formula) << " (closed form);\n";
        h_ << "//   validity checks: " << counts_text(em_.checks) << " + "
           << (sum_terms_.empty() ? 0 : sum_terms_.size() - 1) << " add (finiteness of the result), and comparisons;\n";
        h_ << "//   fast path (inputs that pass every check): " << counts_text(fast_.formula) << " + "
           << (fast_terms_.empty() ? 0 : fast_terms_.size() - 1) << " add, " << flag_counts(fast_, fast_terms_).first
           << " fma, " << mins(fast_) << " min (checks), " << flag_counts(fast_, fast_terms_).second << " tests;\n";
        h_ << "//   batch loop: " << counts_text(batch_.formula) << " + "
           << (batch_terms_.empty() ? 0 : batch_terms_.size() - 1) << " add, "
           << flag_counts(batch_, batch_terms_).first << " fma, " << mins(batch_)
           << " min (checks) per impact, no branch.\n";
        h_ << "#pragma once\n\n";
        if (em_.uses_sqrt)
            h_ << "#include <cmath>\n";
        h_ << "#include <limits>\n\n"; // the runtime's smallest_normal and machine_epsilon
    }

    // The status enum and helpers (codegen/runtime/impact_runtime.hpp), once per
    // namespace (a guard unique to it and to the text).
    void preamble() { h_ << impact_preamble(o_.ns); }

    // A view's two member functions (mutable and const) for one group.
    void view_functions(const std::string &name, const group &g)
    {
        std::vector<std::string> entries, fixed;
        if (!g.outputs.empty()) {
            for (std::size_t k : g.outputs) {
                entries.push_back("&" + pl_.outputs[k].field);
                fixed.push_back("0.0");
            }
        } else {
            for (const ex &x : g.inputs) {
                if (is_a<numeric>(x)) {
                    entries.push_back("nullptr");
                    fixed.push_back(decimal_literal(ex_to<numeric>(x)));
                } else {
                    entries.push_back("&" + input_ident_.at(x));
                    fixed.push_back("0.0");
                }
            }
        }
        const std::string dims = std::to_string(g.rows) + ", " + std::to_string(g.cols);
        const std::string body = "{{" + join(entries, ", ") + "}, {" + join(fixed, ", ") + "}}";
        h_ << "    /// " << names::comment_text(g.meaning) << (g.cols == 1 ? " (vector)" : " (matrix, row-major)")
           << "\n";
        h_ << "    IMPACTGEN_MEMBER view<T, " << dims << "> " << name << "() noexcept { return " << body << "; }\n";
        h_ << "    IMPACTGEN_MEMBER view<const T, " << dims << "> " << name << "() const noexcept { return " << body
           << "; }\n";
    }

    void result_struct()
    {
        h_ << "/// Post-impact state of " << o_.name << " (units as the inputs).\n";
        h_ << "template <typename T> struct " << result() << " {\n";
        for (const output_value &ov : pl_.outputs)
            h_ << "    T " << ov.field << "; ///< " << names::comment_text(ov.meaning) << "\n";
        for (std::size_t g = 0; g < pl_.output_groups.size(); ++g)
            view_functions(out_views_[g], pl_.output_groups[g]);
        h_ << "};\n\n";
        h_ << "/// The inputs of " << o_.name << " by name (the same as its parameters).\n";
        h_ << "template <typename T> struct " << input_struct() << " {\n";
        for (std::size_t i = 0; i < input_names_.size(); ++i)
            h_ << "    T " << input_names_[i] << "; ///< " << names::comment_text(pl_.input_meaning[i]) << "\n";
        for (std::size_t g = 0; g < pl_.input_groups.size(); ++g)
            view_functions(in_views_[g], pl_.input_groups[g]);
        h_ << "};\n\n";
    }

    void formula_block()
    {
        h_ << "// Formulas (impactgen's closed form; n the unit normal from body 1 into body 2,\n";
        h_ << "// s_1 = -1, s_2 = +1; r_i = O - C_i for a free body, O - E for a body pinned at E):\n";
        h_ << "//   w_i  = 1/m_i + (r_i x n) . g_i,  g_i = I_i^{-1} (r_i x n)  (free rigid body; 1/m_i for a "
              "particle;\n";
        h_ << "//          pinned: (r_i x n) . g_i with I_E = I_C + m (|d|^2 1 - d d^T), d = C - E)\n";
        h_ << "//   u    = (v_B - v_A) . n,  v_A = v_C1 + w_1 x (O - C_1)        (u < 0: the contact points "
              "approach)\n";
        h_ << "//   k    = w_1 + w_2,  N = -(1 + e) u / k                          (impulse per unit normal)\n";
        h_ << "//   v'_i = v_i + s_i N n / m_i (pinned: w' x (C - E)),  w'_i = w_i + s_i N g_i\n";
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

    // The checked version: each check right after the value it tests, with its own status.
    void checked_function()
    {
        h_ << "\nnamespace detail {\n";
        h_ << "/// What a failed call of " << o_.name << " returns: the state unchanged (velocities as\n";
        h_ << "/// before, impulses, approach velocity and energy lost zero).\n";
        h_ << "template <typename T> IMPACTGEN_COLD IMPACTGEN_FUNC void " << unchanged() << "(";
        for (const std::string &nm : input_names_)
            h_ << "T " << (uses(unchanged_.code, nm) ? nm : "/*" + nm + "*/") << ", ";
        h_ << result() << "<T>& out) noexcept\n{\n";
        if (unchanged_.uses_sqrt)
            h_ << "    using std::sqrt;\n";
        h_ << unchanged_.code << "}\n\n";
        h_ << "/// " << o_.name << " with each check right after the value it tests: the status of the\n";
        h_ << "/// inputs that fail the fast path of " << o_.name << " (out then holds the state unchanged).\n";
        h_ << tparams << "IMPACTGEN_COLD IMPACTGEN_FUNC impact_status " << checked() << "(" << params() << result()
           << "<T>& out) noexcept\n{\n";
        if (em_.uses_sqrt)
            h_ << "    using std::sqrt;\n";
        h_ << "    auto fail = [&](impact_status why) noexcept {\n";
        h_ << "        detail::" << unchanged() << "(" << params_call() << "out);\n";
        if (input_names_.empty())
            h_ << "        return why;\n";
        else
            h_ << "        return detail::all_finite(" << join(input_names_, ", ")
               << ") ? why : impact_status::non_finite_input;\n";
        h_ << "    };\n";
        h_ << "    (void)fail; // a fully numeric problem may have no check left\n";
        h_ << energy_optional(em_.code, "    out.energy_lost = ");
        if (!sum_terms_.empty()) {
            h_ << "    const T check_sum = " << balanced_sum(sum_terms_) << ";\n";
            h_ << "    if (!detail::finite(check_sum) && !detail::all_finite(" << join(sum_terms_, ", ") << "))\n";
            h_ << "        return fail(impact_status::overflow);\n";
        }
        h_ << "    return impact_status::ok;\n}\n} // namespace detail\n\n";
    }

    // The function: every check folded into a few tests, then one slow path.
    void fast_function()
    {
        h_ << "/// Post-impact state for the inputs below; returns impact_status::ok, or why not\n";
        h_ << "/// (then out holds the state unchanged: velocities as before, impulses zero).\n";
        h_ << "/// T: float, double, long double or alike (an autodiff scalar).\n";
        h_ << "/// The checks do not branch one by one: they are folded into a few tests (signs\n";
        h_ << "/// through a min, the finiteness of every value through sums times 0 added to\n";
        h_ << "/// it), and only inputs that fail one of them take the slow path (detail::" << checked() << ") that\n";
        h_ << "/// says which check failed. with_energy_lost = false: out.energy_lost is left 0,\n";
        h_ << "/// neither computed nor checked (the rest is the same).\n";
        for (std::size_t i = 0; i < input_names_.size(); ++i)
            h_ << "///   " << input_names_[i] << ": " << names::comment_text(pl_.input_meaning[i]) << "\n";
        h_ << tparams << "IMPACTGEN_HOT IMPACTGEN_FUNC impact_status " << o_.name << "(" << params() << result()
           << "<T>& out) noexcept\n{\n";
        if (em_.uses_sqrt)
            h_ << "    using std::sqrt;\n";
        h_ << energy_optional(fast_.code, "    const T " + local_of_.at("energy_lost") + " = ");
        h_ << ok_flag("    ", fast_, fast_terms_, true);
        h_ << "    if (!ok) // some check failed (or a value is not finite): find which\n";
        h_ << "        return detail::" << checked() << "<T, with_energy_lost>(";
        for (const std::string &nm : input_names_)
            h_ << nm << ", ";
        h_ << "out);\n";
        for (const output_value &ov : pl_.outputs)
            h_ << "    out." << ov.field << " = " << local_of_.at(ov.field) << ";\n";
        h_ << "    return impact_status::ok;\n}\n\n";
    }

    void array_form()
    {
        h_ << "/// The same with the inputs in an array, in the order of " << o_.name << "_input_names.\n";
        h_ << tparams << "IMPACTGEN_HOT IMPACTGEN_FUNC impact_status " << o_.name << "(const T* in, " << result()
           << "<T>& out) noexcept\n{\n";
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
        h_ << tparams << "IMPACTGEN_HOT IMPACTGEN_FUNC impact_status " << o_.name << "(const " << input_struct()
           << "<T>& in, " << result() << "<T>& out) noexcept\n{\n";
        if (input_names_.empty())
            h_ << "    (void)in;\n";
        h_ << "    return " << o_.name << "<T, with_energy_lost>(";
        for (const std::string &nm : input_names_)
            h_ << "in." << nm << ", ";
        h_ << "out);\n}\n\n";
    }

    // Values and the dense Jacobian in one straight-line program (CSE across both).
    void jacobian_function()
    {
        if (!pl_.has_jacobian)
            return;
        const std::string jr = o_.name + "_jacobian_result";
        const std::size_t no = pl_.outputs.size(), nw = wrt_names_.size();
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
        if (jac_.uses_sqrt)
            h_ << "    using std::sqrt;\n";
        h_ << jac_.code;
        h_ << ok_flag("    ", jac_, jac_terms_, true);
        h_ << "    if (!ok) {\n";
        h_ << "        out = " << jr << "<T>{}; // every derivative zero\n";
        h_ << "        const impact_status why = detail::" << checked() << "<T, true>(" << params_call()
           << "out.value);\n";
        h_ << "        if (why != impact_status::ok)\n";
        h_ << "            return why;\n";
        h_ << "        // The values are finite, a derivative is not (1/m^2 overflows where 1/m does not).\n";
        h_ << "        detail::" << unchanged() << "(" << params_call() << "out.value);\n";
        h_ << "        return impact_status::overflow;\n";
        h_ << "    }\n";
        for (const output_value &ov : pl_.outputs)
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
    void batch_form()
    {
        h_ << "/// The same over n impacts in structure-of-arrays form: in[j][i] is input j\n";
        h_ << "/// (order of " << o_.name << "_input_names) of impact i, out[j][i] output j. The arrays\n";
        h_ << "/// must not overlap. A first pass computes every impact without branches (it\n";
        h_ << "/// vectorises); if any impact failed a check, a second pass redoes those one by\n";
        h_ << "/// one for their status (their outputs are then the state unchanged).\n";
        std::size_t energy_index = pl_.outputs.size();
        for (std::size_t j = 0; j < pl_.outputs.size(); ++j)
            if (pl_.outputs[j].kind == output_value::energy_lost)
                energy_index = j;
        if (energy_index < pl_.outputs.size())
            h_ << "/// with_energy_lost = false: energy_lost is neither computed nor checked, and out[" << energy_index
               << "] is not written (it may be null).\n";
        // The first pass as a kernel whose arrays are restrict-qualified parameters: the
        // no-alias promise that both g++ and clang++ honour (clang ignores it on locals),
        // with no forcing pragma that would warn where a type does not vectorise.
        std::vector<std::string> pass_params;
        for (const std::string &nm : input_names_)
            pass_params.push_back("const T* IMPACTGEN_RESTRICT " + in_ptr_.at(nm));
        for (const output_value &ov : pl_.outputs)
            pass_params.push_back("T* IMPACTGEN_RESTRICT " + out_ptr_.at(ov.field));
        pass_params.push_back("impact_status* IMPACTGEN_RESTRICT " + status_ptr());
        h_ << "namespace detail {\n";
        h_ << "/// The first pass of " << o_.name << "_batch (every impact, no branch): 1 when some\n";
        h_ << "/// impact failed a check, else 0.\n";
        h_ << "template <typename T, bool with_energy_lost>\nIMPACTGEN_FUNC unsigned " << o_.name
           << "_batch_pass(long n, " << join(pass_params, ", ") << ") noexcept\n{\n";
        if (batch_.uses_sqrt) // (else a symbolic normal's sqrt is ::sqrt(double), for float and long double too)
            h_ << "    using std::sqrt;\n";
        h_ << "    unsigned failed = 0;\n";
        h_ << "#if defined(__GNUC__) && !defined(__clang__)\n#pragma GCC ivdep\n#endif\n";
        h_ << "    for (long i = 0; i < n; ++i) {\n";
        for (const std::string &nm : input_names_)
            h_ << "        const T " << nm << " = " << in_ptr_.at(nm) << "[i];\n";
        std::istringstream lines(energy_optional(batch_.code, "    const T " + local_of_.at("energy_lost") + " = ") +
                                 ok_flag("    ", batch_, batch_terms_, false));
        for (std::string line; std::getline(lines, line);)
            h_ << "    " << line << "\n";
        // Stored unconditionally: the second pass overwrites the outputs of failed impacts.
        for (const output_value &ov : pl_.outputs)
            h_ << (ov.kind == output_value::energy_lost ? "        if constexpr (with_energy_lost)\n    " : "")
               << "        " << out_ptr_.at(ov.field) << "[i] = " << local_of_.at(ov.field) << ";\n";
        h_ << "        " << status_ptr()
           << "[i] = ok ? impact_status::ok : impact_status::overflow; // refined below\n";
        h_ << "        failed |= static_cast<unsigned>(!ok);\n";
        h_ << "    }\n";
        h_ << "    return failed;\n}\n} // namespace detail\n\n";

        h_ << tparams << "IMPACTGEN_FUNC void " << o_.name
           << "_batch(long n, const T* const* in, T* const* out, impact_status* status) noexcept\n{\n";
        if (input_names_.empty())
            h_ << "    (void)in;\n";
        for (std::size_t j = 0; j < input_names_.size(); ++j)
            h_ << "    const T* const " << in_ptr_.at(input_names_[j]) << " = in[" << j << "];\n";
        for (std::size_t j = 0; j < pl_.outputs.size(); ++j)
            h_ << "    T* const " << out_ptr_.at(pl_.outputs[j].field) << " = out[" << j << "];\n";
        std::vector<std::string> pass_args;
        for (const std::string &nm : input_names_)
            pass_args.push_back(in_ptr_.at(nm));
        for (const output_value &ov : pl_.outputs)
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
        for (const output_value &ov : pl_.outputs)
            h_ << (ov.kind == output_value::energy_lost ? "            if constexpr (with_energy_lost)\n    " : "")
               << "            " << out_ptr_.at(ov.field) << "[i] = r." << ov.field << ";\n";
        h_ << "        }\n";
        h_ << "}\n\n";
    }

    // Names and counts of inputs and outputs, the operation count, the array form of a result.
    void tables()
    {
        h_ << "inline constexpr int " << o_.name << "_input_count = " << input_names_.size() << ";\n";
        h_ << "inline constexpr int " << o_.name << "_output_count = " << pl_.outputs.size() << ";\n";
        h_ << "inline constexpr const char* " << o_.name << "_input_names[] = {";
        for (const std::string &nm : input_names_)
            h_ << names::cpp_string_literal(nm) << ", ";
        h_ << "nullptr};\n";
        h_ << "inline constexpr const char* " << o_.name << "_output_names[] = {";
        for (const output_value &ov : pl_.outputs)
            h_ << names::cpp_string_literal(ov.field) << ", ";
        h_ << "nullptr};\n";
        h_ << "/// Arithmetic of the closed form per call (validity checks not included).\n";
        h_ << "inline constexpr op_count " << o_.name << "_ops{" << em_.formula.add << ", " << em_.formula.mul << ", "
           << em_.formula.div << ", " << em_.formula.sqrt << "};\n\n";
        h_ << "/// The members of r in the order of " << o_.name << "_output_names.\n";
        h_ << "template <typename T> IMPACTGEN_FUNC void " << o_.name << "_to_array(const " << result()
           << "<T>& r, T* a) noexcept\n{\n";
        for (std::size_t i = 0; i < pl_.outputs.size(); ++i)
            h_ << "    a[" << i << "] = r." << pl_.outputs[i].field << ";\n";
        h_ << "}\n\n} // namespace " << o_.ns << "\n";
    }

    std::string result() const { return o_.name + "_result"; }
    std::string status_ptr() const { return status_ptr_; }
    std::string input_struct() const { return o_.name + "_input"; }
    std::string unchanged() const { return o_.name + "_unchanged"; }
    std::string params_call() const
    {
        std::string r;
        for (const std::string &nm : input_names_)
            r += nm + ", ";
        return r;
    }
    std::string checked() const { return o_.name + "_checked"; }
    std::string params() const
    {
        std::string r;
        for (const std::string &nm : input_names_)
            r += "T " + nm + ", ";
        return r;
    }

    const options &o_;
    plan pl_;
    names::identifier_scope scope_, members_, in_members_;
    std::vector<std::string> in_views_, out_views_; // member functions of the input and result structs, per group
    std::map<ex, std::string, ex_is_less> input_ident_;
    std::vector<std::pair<std::string, int>> unchanged_outs_;
    std::string status_ptr_;
    std::vector<std::string> jac_step_names_, wrt_names_;
    std::vector<std::vector<std::string>> jac_local_; // [output][wrt] local of the derivative
    std::vector<std::pair<std::string, int>> jac_outs_;
    emitted jac_;
    std::vector<sum_term> jac_terms_;
    emitted unchanged_;
    std::vector<std::string> input_names_, step_names_;
    std::map<std::string, std::string> local_of_, out_ptr_,
        in_ptr_; // member -> local value / output pointer; input -> input pointer
    canonical_pool pool_;
    program prog_;
    std::map<int, std::string> var_names_;
    std::vector<std::pair<std::string, int>> outs_, outs_local_;
    std::vector<check> checks_;
    emitted em_, fast_, batch_;
    std::vector<std::string> sum_terms_;
    std::vector<sum_term> fast_terms_, batch_terms_;
    std::ostringstream h_;
};

} // namespace

std::string default_function_name(const std::string &stem)
{
    std::string name = names::mangle(stem);
    while (name.size() > 1 && name.back() == '_') // "int" mangles to int_; int__result would be reserved
        name.pop_back();
    return names::is_safe_identifier(name) && !reserved().count(name) ? name : name + "_impact";
}

header generate(const problem &p, const options &o)
{
    check_names(o);
    // Coulomb friction (mu not 0 once --set is folded in): the regime-selecting header.
    if (has_friction(p, o))
        return generate_friction(p, o);
    return writer(p, o).run();
}

bool write_if_changed(const std::string &path, const std::string &text)
{
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw input_error(names::display_text(path) +
                          ": not a regular file (the header is written only to a regular file or "
                          "standard output)");
    if (std::filesystem::exists(status)) {
        std::ifstream in(path, std::ios::binary);
        if (in) {
            std::stringstream ss;
            ss << in.rdbuf();
            if (ss.str() == text)
                return false;
        }
    }
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out)
        throw input_error("cannot write " + names::display_text(path));
    out << text;
    out.close();
    if (!out)
        throw input_error("cannot write " + names::display_text(path));
    return true;
}

} // namespace impactgen::codegen
