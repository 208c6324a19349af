// The one header writer (writer.cpp, writer_text.cpp, writer_straight.cpp, writer_stages.cpp,
// writer_select.cpp): it emits any code plan (code_plan.hpp). The sections every header
// has (banner, runtime, result and input structs, the unchanged state, the array and
// struct forms, the batch form, the tables) are written once; the function's body by the
// plan's selection rule: straight-line for `none` (a checked, a branchless fast and a
// vectorised form), the candidates and the selection among them otherwise (the design at
// the top of writer_stages.cpp). Private to the codegen library.
#pragma once

#include "code_plan.hpp"
#include "form_text.hpp"
#include "runtime.hpp"
#include "text.hpp"

#include "names/escape.hpp"
#include "names/identifier.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/response.hpp"

#include <algorithm>
#include <functional>
#include <set>
#include <sstream>

namespace impactgen::codegen
{
using namespace GiNaC;

namespace writer_detail
{
void add_counts(op_counts &a, const op_counts &b);
using namespace form_text;
std::string indent(const std::string &code, const std::string &by);
bool depends_on(const ex &e, const exset &syms);
std::vector<check> state_checks(const std::vector<check> &checks);
/// The `using std::sqrt;` (and std::cos, std::sin) lines a function body needs for the code of `e`.
std::string math_usings(const emitted &e);
/// The C++ text of max |t| over the terms (T(0) for none), as nested detail::max_of calls.
std::string nested_abs_max(const std::vector<std::string> &terms);
std::string position_text(const problem &q); // the convention of position vectors, as comment lines

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
};

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

// What a law's NAME_jacobian writes around its candidates' programs (writer_jacobian.cpp), filled
// by the law's part: how the function finds the candidate it selected, its names and comments.
struct jacobian_form {
    std::string fn, wrt_count, wrt_names, wrt_comment; // the function, the columns' table and its comment
    std::string row_count, row_names, row_comment;     // the rows' table (none when empty: the first outputs)
    std::string doc;                                   // the function's comment
    std::string jac, status, k;                        // its locals
    std::string program_prefix;       // each candidate's locals prefixed <prefix><k>_ (else named once, shared)
    std::string angle_c, angle_s;     // the locals of cos and sin of the sliding angle found (friction)
    bool sqrt_always = false;         // `using std::sqrt;` whether or not the programs need it
    bool trig = false;                // the selection needs std::cos and std::sin
    std::string select;               // after the status check: the statements that find the candidate
    std::string selector;             // the switch's value
    std::vector<std::size_t> selects; // per value of the selector: the candidate it selects
    bool labels_apart = false;        // each `case v:` on its own line (several values share a program)
    bool case_names = false;          // each case commented with its candidate's name
    std::function<std::string(std::size_t)> case_tail; // after a case's entries (its boundary tests)
    std::string after_switch;
    std::string boundary;    // the condition of the status ambiguous
    bool array_form = false; // also NAME_jacobian(const T* in, out, jac)
};

class writer
{
public:
    writer(code_plan cp, const options &o);

    header run();
    header run_system();

private:
    bool straight() const { return cp_.rule == selection_rule::none; }
    bool system() const { return cp_.rule == selection_rule::system_sets; }
    const char *status_type() const { return straight() ? "impact_status" : "friction_status"; }

    // ---- names (one scope for the function's names, one per struct)
    void name_everything();
    void name_basis();
    void name_straight();
    std::string case_prefix(const regime_case &c) const;

    // ---- checks (writer.cpp): the inputs' and the steps', in a program
    void add_check(stage &s, const ex &value, check::kind_t kind, const std::string &status,
                   const std::string &comment);
    void add_checks(stage &s, const std::vector<step> &steps);

    // ---- rule none: one straight-line program (writer_straight.cpp)
    void lower_program();
    void emit_forms();
    bool needs_check(int id) const;
    std::vector<int> ready_times() const;
    std::vector<bool> implied_outputs(int energy) const;
    void straight_banner();
    void straight_formulas();
    void checked_function();
    void fast_function();
    void straight_slow_paths();
    void unchecked_function();
    void jacobian_function();
    // ---- --rows: the contact's rows for an iterative solver (writer_rows.cpp)
    void build_rows();
    void rows_function();
    void rows_structs();
    std::string rows_body();
    void straight_batch();

    // ---- a selection rule: the candidates' programs (writer_stages.cpp)
    void build_stages();
    void split_steps();
    void scale_response();
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
    void build_stage_b();
    void build_stage_s();
    void build_stage_c();
    void build_unchanged();
    /// Emits a stage, its names claimed; counted: its arithmetic in the header's (not a Jacobian's).
    void emit_one(stage &s, const emit_options &how, bool counted = true);
    void emit_stages();

    // ---- a selection rule: the text of the candidates (writer_select.cpp, writer_text.cpp)
    void candidates_banner();
    void candidates_formulas();
    void process_intro();
    void conditions_and_steps();
    std::string frame_text(const vec3 &v) const;
    std::string holds_text(const case_names &cn, const regime_case &c) const;
    std::string select_text(const case_names &cn, const std::string &regime, const std::string &ind) const;
    std::string merge_text() const;
    std::string near_text(const case_names &cn) const;
    void emit_closed_forms(const std::string &ind);
    std::string counted_text() const { return counted_.empty() ? std::string("0") : join(counted_, " + "); }
    void emit_angle_search(const std::string &ind);
    void emit_root_loop(const std::string &ind);
    void emit_unresolved(const std::string &ind);
    const std::string &selection_text();
    /// The final check of a friction header: every output and input finite, or overflow.
    void overflow_check();
    void main_function(bool unchecked);
    void loop_batch();

    // ---- rule system_sets: a system's candidate sets (writer_system.cpp)
    void build_system();
    void system_banner();
    void system_formulas();
    void system_tolerance();
    std::string system_holds(std::size_t k) const;
    std::string system_nearest() const;
    std::string system_scale(std::size_t k, std::size_t j) const;
    void system_select();
    void system_function();
    void system_input_checks();

    // ---- a system's sequential impacts: the chain of single-contact impacts (writer_sequence.cpp)
    bool sequential() const { return system() && cp_.system.sequential; }
    void build_sequence();
    void sequence_formulas();
    void sequence_step(std::size_t k);
    void sequence_function();

    // ---- --jacobian with a selection rule: NAME_jacobian from the plan's candidates_jacobian
    // (writer_jacobian.cpp), the law's part filling jacobian_form
    void build_jacobian();
    void build_jacobian_programs(const std::function<void(std::size_t, stage &)> &more);
    void emit_jacobian_programs();
    void jacobian_tables();
    void candidates_jacobian_function();
    bool process_jacobian() const;
    void named_jacobian_form(const std::map<std::string, std::string> &locals, const std::string &what,
                             const std::string &rows, const std::string &row, const std::string &which);
    void process_jacobian_form();
    std::string process_scale(std::size_t i, std::size_t j) const;
    std::string process_sequence_text(const std::string &ind) const;
    void system_jacobian_form();
    // ---- Coulomb friction under Newton's law: which candidate NAME selected (writer_jacobian_friction.cpp)
    void friction_jacobian_form();
    void friction_jacobian_pre();
    std::string candidates_jacobian_selection() const;
    std::string candidates_jacobian_boundary(std::size_t k) const;
    void friction_jacobian_text();
    /// The unit tangent basis computed at run time for a normal given as inputs (else nothing).
    std::string basis_text() const;

    // ---- the sections every header has (writer_text.cpp)
    std::string params() const;
    std::string args() const;
    std::string result() const { return o_.name + "_result"; }
    std::string input_struct() const { return o_.name + "_input"; }
    std::string unchanged() const { return o_.name + "_unchanged"; }
    std::string checked() const { return o_.name + "_checked"; }
    void banner();
    // The runtime every header needs (codegen/runtime/impact_runtime.hpp: impact_status,
    // view, detail helpers), once per namespace; with candidates also
    // codegen/runtime/friction_runtime.hpp under its own guard.
    void preamble();
    void view_functions(const std::string &name, int rows, int cols, const std::vector<std::string> &entries,
                        const std::vector<std::string> &fixed, const std::string &meaning);
    void group_view(const std::string &name, const group &g);
    void result_struct();
    void unchanged_function(const emitted &code);
    void fail_lambda(const std::string &why_type, const std::string &status_of, bool inputs_checked);
    void forwarding_form(bool by_name);
    void tables();

    // ---- state: the plan
    const options &o_;
    code_plan cp_;
    plan &pl_;
    problem &q_;
    derivation &d_;
    impact_solution &f_;
    std::vector<code_output> &outs_;
    int angle_ = -1;
    // ---- names
    names::identifier_scope scope_, members_, in_members_;
    std::vector<std::string> input_names_;
    std::map<ex, std::string, ex_is_less> input_ident_;
    std::vector<std::string> in_views_, out_views_; // member functions of the input and result structs, per group
    std::string tangential_view_;
    op_counts total_, checks_total_;
    std::ostringstream h_;

    // ---- rule none: the program and its forms
    stage main_;
    std::vector<std::string> step_names_;
    std::map<std::string, std::string> local_of_, out_ptr_, in_ptr_; // output -> local / pointer; input -> pointer
    std::string status_ptr_;
    std::vector<std::string> jac_step_names_, wrt_names_;
    std::vector<std::vector<std::string>> jac_local_; // [output][wrt] local of the derivative
    std::vector<std::pair<std::string, int>> jac_outs_, outs_local_, unchanged_outs_;
    emitted em_, fast_, batch_, jac_, unchanged_, unchecked_;
    std::vector<std::string> sum_terms_;
    std::vector<sum_term> fast_terms_, batch_terms_, jac_terms_;

    // ---- a selection rule: the candidates' programs and names
    // A normal given as inputs (3-D): the tangent basis computed at run time.
    stage nb_;
    std::vector<std::string> basis_names_;
    std::string basis_t_name_, basis_b_name_;
    exset local_, a_step_syms_;
    std::vector<step> a_steps_, b_steps_, b_steps_linked_;
    std::vector<std::string> a_step_names_, b_step_names_;
    std::map<ex, std::string, ex_is_less> step_name_;
    std::vector<symbol> sel_P_, sel_F_;
    symbol sel_N_{"friction_N"};
    ex scale_ = 0; // the scale of K (n.K n) the candidates divide it by, or 0
    ex det_K_ = 0; // det K of the stick candidate (its step), when the stick candidate may be dropped at run time
    std::string det_K_name_, stick_possible_name_;
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
    emitted a_unchecked_;   // stage A with only the checks of the state (the unchecked variant)
    std::string selection_; // the selection and the post-impact state, as both functions write them

    // ---- rule system_sets: names of the locals
    std::vector<std::string> sys_mu_, sys_speed_, sys_sel_;
    std::vector<std::vector<std::string>> sys_vals_, sys_conds_;
    std::map<std::string, std::string> sys_local_;
    std::vector<std::string> sys_unit_mass_;
    // ---- rule process with --jacobian: the selection's locals, the scales of its rounding
    std::map<std::string, std::string> seq_local_;
    std::string speed_name_, response_name_;
    // sequential: the state, its speeds' stage, one stage per contact's step
    std::vector<std::string> seq_state_, seq_sum_, seq_speed_, seq_before_;
    stage seq_speeds_;
    std::vector<stage> seq_steps_;
    stage rows_; // --rows: the primitive values of the rows
    // ---- --jacobian with a selection rule: the form, per candidate its program and entries' names
    jacobian_form jf_;
    std::vector<stage> jac_stages_;
    std::vector<std::vector<std::string>> jac_entries_; // [candidate][row * wrt + column]
    // with friction: names and the program of the slip after impact
    std::map<std::string, std::string> fj_local_;
    std::vector<std::pair<std::string, std::string>> fj_sel_;   // local of the impulse returned, out.field
    std::vector<std::string> fj_speed_, fj_slip_, fj_friction_; // u before (world); slip, friction along e_t (, e_b)
    std::string fj_mu_;
    bool fj_impulse_scale_ = false, fj_speed_scale_ = false; // a condition of an impulse, of the sliding speed
    stage fj_pre_;
    std::vector<std::vector<std::string>> fj_conds_; // [candidate][j]
    std::map<std::string, std::string> rows_name_;
};

} // namespace writer_detail
} // namespace impactgen::codegen
