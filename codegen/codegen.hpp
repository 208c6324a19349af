// Code generation: a problem (named class or problem file), specialised by the
// caller's choice of parameters, becomes one dependency-free C++17 header with
// a noexcept function template that computes the post-impact state.
//
//   problem --(--set, --params: fold the rest in)--> derive --> solve (named steps)
//           --> canonical trees (canonical.hpp) --> straight-line program with
//               value numbering = CSE (program.hpp) --> C++ (emit_cpp)
#pragma once

#include "program.hpp"
#include "symbolic/solution.hpp"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace impactgen::codegen
{

struct options {
    std::string name; ///< function name (a C++ identifier)
    std::string ns = "impactgen::generated";
    std::string source;  ///< what the banner names as the input (class or file as given)
    std::string version; ///< impactgen's version, for the banner
    bool params_given = false;
    std::vector<std::string> params;                      ///< symbols or quantity names that stay parameters, in order
    std::vector<std::pair<std::string, std::string>> set; ///< symbol = value folded in as constants
    bool inverse_inertia = false; ///< inertia inputs of free bodies are I^{-1} (3-D) or 1/I (planar): engine convention
    bool inverse_mass = false;    ///< mass inputs are 1/m (engine convention)
    bool unit_normal = false;     ///< the normal inputs are a unit vector: no normalisation (engine convention)
    bool jacobian = false;        ///< also emit <name>_jacobian: values and d(outputs)/d(wrt)
    std::vector<std::string> wrt; ///< inputs the Jacobian differentiates by (empty: every input), in order
    bool rows = false;            ///< also emit <name>_rows: the contact's rows for an iterative solver
};

/// An option that cannot be honoured. The library names the option by `which`
/// (the command line turns it into its flag); the message names the problem.
class option_error : public input_error
{
public:
    enum option {
        set,
        params,
        inverse_inertia,
        inverse_mass,
        function_name,
        name_space,
        unit_normal,
        jacobian,
        wrt,
        rows
    };
    option_error(option which, const std::string &message, std::string symbol = "")
        : input_error(message), which(which), symbol(std::move(symbol))
    {
    }
    static const char *option_name(option o); ///< "set", "params", "inverse-inertia", ...
    option which;
    std::string symbol; ///< a symbol that needs a value or a parameter slot, when that is the problem
};

/// The problem with set values folded in and the quantities named in
/// --params made symbols; throws input_error when a symbol is neither a
/// parameter nor given a value.
problem specialise(const problem &p, const options &o);

/// The name of each liftable quantity of a problem ("m1", "v_x_ball", ...)
/// with its current value, in problem order.
std::vector<std::pair<std::string, GiNaC::ex>> quantity_names(const problem &p);

struct output_value {
    enum kind_t { velocity, angular_velocity, normal_impulse, pivot_impulse, approach_velocity, energy_lost };
    kind_t kind;
    std::size_t index = 0; ///< body (velocities) or pivot (pivot impulse)
    int component = 0;     ///< world axis
    std::string field;     ///< member of the result struct
    GiNaC::ex value;       ///< in inputs and steps
    std::string meaning;
};

/// Inputs or outputs that form a vector or a matrix (row-major): the views the
/// structs offer to adapters (impactgen/eigen.hpp). An input entry is an input
/// symbol or a number the header fixed; an output entry is an index into plan::outputs.
struct group {
    std::string name; ///< v1, w_ball, r1, I1, inv_I1, O, n, E1, R1 (before the identifier layer)
    int rows = 3, cols = 1;
    std::vector<GiNaC::ex> inputs;
    std::vector<std::size_t> outputs;
    std::string meaning;
};

/// Derivatives of the impact map, by the chain rule through the solution's steps
/// (forward mode, symbolically): every step s_k = f_k(inputs, earlier steps) gets
/// d s_k/d x_j = df_k/dx_j + sum_m df_k/ds_m d s_m/d x_j, named as a step of its
/// own when it is more than a number or a symbol, so that the values and the
/// derivatives share one straight-line program (CSE across both).
struct jacobian_plan {
    std::vector<GiNaC::symbol> wrt; ///< the inputs differentiated by, in order
    std::vector<step> steps;        ///< derivative steps, in order of evaluation
    /// d(output i)/d(wrt j), in inputs, solution steps and derivative steps.
    std::vector<std::vector<GiNaC::ex>> entries;
};

/// The closed form prepared for code generation: solution steps (rewritten
/// for the engine input conventions), outputs, and the function's inputs in order.
struct plan {
    problem prob; ///< specialised
    derivation deriv;
    solution sol;
    std::vector<GiNaC::symbol> inputs; ///< function parameters, in order
    std::vector<std::string> input_meaning;
    std::vector<output_value> outputs;
    /// Engine conventions: each input symbol replaced by inverse inputs (mass -> inv_m,
    /// inertia entry -> inverse tensor entries), by symbol identity, never by name.
    std::map<GiNaC::ex, std::vector<GiNaC::symbol>, GiNaC::ex_is_less> replaced;
    std::map<GiNaC::ex, GiNaC::symbol, GiNaC::ex_is_less> inverse_of; ///< mass or planar inertia -> its inverse input
    std::map<GiNaC::ex, std::string, GiNaC::ex_is_less> meaning;      ///< of the inverse inputs
    std::map<std::size_t, mat3>
        inverse_tensor; ///< body -> its inverse inertia tensor in inputs (engine convention, 3-D)
    std::vector<group> input_groups, output_groups;
    /// Each output with the impulses set to zero, in inputs only: what a failed call
    /// returns (the state unchanged; impulses, approach velocity and energy lost 0).
    std::vector<GiNaC::ex> unchanged;
    bool has_jacobian = false;
    jacobian_plan jac; ///< when options::jacobian
};
plan make_plan(const problem &p, const options &o);

/// The derivatives of the plan's outputs by the inputs named (empty: every
/// input); throws option_error(jacobian) for a name that is not an input.
jacobian_plan plan_jacobian(const plan &pl, const std::vector<std::string> &wrt);

struct header {
    std::string text;
    op_counts formula, checks;
    std::vector<std::string> inputs, outputs;
};
header generate(const problem &p, const options &o);

/// A usable function name made from any text (a class or file stem): mangled to
/// a safe identifier, and kept clear of the names the header uses itself
/// ("n.json" gives n_impact, "9-ball.json" x_9_ball).
std::string default_function_name(const std::string &stem);

/// Writes text to path unless the file already holds exactly that text;
/// returns true when it wrote.
bool write_if_changed(const std::string &path, const std::string &text);

} // namespace impactgen::codegen
