// The friction header writer (friction.cpp, friction_stages.cpp, friction_select.cpp,
// friction_text.cpp): its helpers, its programs (stage) and the class friction_writer.
// Private to the codegen library; the design is described at the top of friction.cpp.
#pragma once

#include "form_text.hpp"
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

namespace friction_detail
{
void add_counts(op_counts &a, const op_counts &b);
using form_text::balanced_sum;
using form_text::check_names;
using form_text::command_line;
using form_text::counts_text;
using form_text::positive_definite_minors;
using form_text::uses;
using form_text::wrap_comment;
std::string indent(const std::string &code, const std::string &by);
bool depends_on(const ex &e, const exset &syms);
void collect_symbols(const ex &e, exset &out);

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

// ---------------------------------------------------------------------------
// The writer

class friction_writer
{
public:
    friction_writer(const problem &p, const options &o) : o_(o) { prepare(p); }

    header run();

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
    void prepare(const problem &p);
    void order_inputs(const std::set<std::string> &friction_only);
    void order_outputs();

    // ---- names (one scope for the function's names, one per struct)
    void name_everything();
    std::string case_prefix(const regime_case &c) const;

    // ---- the four programs
    void build_stages();
    void split_steps();
    void name_selected();
    std::vector<ex> stage_c_values(const after_state &after, const step *un) const;
    ex response_entry(const solution &s, int a, int b) const;
    mat3 inverse_inertia(const solution &s, std::size_t i) const;
    after_state state_after_selected() const;
    ex energy_lost(const after_state &after) const;
    ex linkify(const ex &e);
    void name_links();
    void downstream_names(stage &s, const std::map<ex, std::string, ex_is_less> &extra);
    void build_stage_a();
    void angle_outputs();
    void add_checks();
    void build_stage_b();
    void build_stage_s();
    void build_stage_c();
    void build_unchanged();
    void emit_one(stage &s, const emit_options &how);
    void emit_stages();

    // ---- text
    std::string params() const;
    std::string args() const;
    std::string result() const { return o_.name + "_result"; }
    std::string input_struct() const { return o_.name + "_input"; }

    void banner();

    // The smooth headers' preamble (codegen/runtime/impact_runtime.hpp: impact_status,
    // view, detail helpers) exactly as they write it, so that a friction header and smooth
    // ones share one copy in a namespace, then codegen/runtime/friction_runtime.hpp under
    // its own guard.
    void preamble() { h_ << impact_preamble(o_.ns) << friction_preamble(o_.ns); }

    void view_functions(const std::string &name, int rows, int cols, const std::vector<std::string> &entries,
                        const std::vector<std::string> &fixed, const std::string &meaning);

    void result_struct();
    void formula_block();
    std::string frame_text(const vec3 &v) const;
    void unchanged_function();
    std::string holds_text(const case_names &cn, const regime_case &c) const;
    std::string select_text(const case_names &cn, const std::string &regime, const std::string &ind) const;
    std::string merge_text() const;
    std::string near_text(const case_names &cn) const;
    void emit_closed_forms(const std::string &ind);
    std::string counted_text() const { return counted_.empty() ? std::string("0") : join(counted_, " + "); }

    void emit_angle_search(const std::string &ind);
    void emit_root_loop(const std::string &ind);
    void emit_unresolved(const std::string &ind);
    void main_function();
    void array_form();
    void struct_form();
    void batch_form();
    void tables();

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

} // namespace friction_detail
} // namespace impactgen::codegen
