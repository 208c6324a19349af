// A straight-line program of binary floating-point operations, built from
// canonical trees with value numbering: every (operation, operand, operand)
// exists once, so common subexpressions are computed once. Products are
// folded left to right in canonical order, so shared leading factors are
// shared too; a division x / y is lowered as x * (1 / y), and the emitter
// prints it back as x / y unless 1 / y is used more than once (one division
// and several multiplications instead of several divisions).
#pragma once

#include "canonical.hpp"

#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace impactgen::codegen
{

struct op {
    enum kind_t { input, constant, add, sub, mul, div, neg, sqrt_, cos_, sin_ } kind = constant;
    int a = -1, b = -1;
    GiNaC::numeric value; ///< constant
    std::string name;     ///< input
    std::string owner;    ///< the step or output being lowered when this op was created
};

/// A number as a C++ long double literal of 40 significant digits ("1.5e-300L").
std::string decimal_literal(const GiNaC::numeric &x);

struct op_counts {
    int add = 0, mul = 0, div = 0, sqrt = 0;
    int trig = 0; ///< cos and sin (not in the header's op_count, whose four fields stay)
};

class program
{
public:
    /// The ops of the canonical node; step nodes resolve through set_step.
    int lower(const canonical_pool &pool, int cid);
    int lower(const canonical_pool &pool, const scaled &s);
    void set_step(int step_index, int op_id) { step_op_[step_index] = op_id; }
    void set_owner(const std::string &owner) { owner_ = owner; }

    int input(const std::string &name);
    int constant(const GiNaC::numeric &x);
    int binary(op::kind_t k, int a, int b);
    int negate(int a);
    int square_root(int a);
    /// cos or sin (kind op::cos_ or op::sin_) of a.
    int trig(op::kind_t k, int a);
    int reciprocal(int a) { return binary(op::div, constant(1), a); }

    const op &at(int id) const { return ops_[static_cast<std::size_t>(id)]; }
    std::size_t size() const { return ops_.size(); }
    bool is_leaf(int id) const { return at(id).kind == op::input || at(id).kind == op::constant; }

private:
    int make(op o);
    /// The op k(a, b), made once: the same operation on the same operands is one op.
    int node(op::kind_t k, int a, int b = -1);
    /// The leaf o under `key` in `index`, made once.
    int leaf(std::map<std::string, int> &index, const std::string &key, const op &o);
    int lower_add(const canonical_pool &pool, int cid, bool negated);
    std::map<int, int> lowered_neg_;
    std::vector<op> ops_;
    std::map<std::tuple<int, int, int>, int> memo_;
    std::map<std::string, int> inputs_, constants_;
    std::map<int, int> lowered_;
    std::map<int, int> step_op_;
    std::string owner_;
    /// Products lowered so far: their factors (node, exponent; sorted), |coefficient|
    /// and op (before any sign), for a later product whose factors include them.
    struct lowered_product {
        std::vector<std::pair<int, int>> factors;
        GiNaC::numeric coefficient;
        int op_id;
    };
    std::vector<lowered_product> products_;
};

/// What the emitted code checks and which status it returns when the check fails.
/// A checked value that nothing but checks uses (a principal minor, the squared
/// length of a declared-unit normal) is computed as soon as its operands are, so
/// its check comes before the values computed after them.
struct check {
    enum kind_t {
        positive,      ///< x > 0, finite
        unit_interval, ///< 0 <= x <= 1
        negative,      ///< x < 0
        normal_number, ///< x >= std::numeric_limits<T>::min(), finite: neither zero, denormal nor infinite
        near_one,      ///< |x - 1| <= unit_tolerance (the squared length of a unit vector rounded in float)
        nonnegative    ///< x >= 0, finite (an inverse mass or inertia of the engine convention: 0 is a static body)
    } kind;
    int op_id;
    std::string status; ///< enumerator of impact_status
    std::string comment;
};

/// The tolerance of check::near_one, 2^-17 (64 float epsilons, about 7.6e-6): a vector
/// normalised in float has |n.n - 1| of a few float epsilons, in any T the header is
/// instantiated with; a vector whose length is off by more than about 3.8e-6 fails.
/// As exact fractions: 1 - 2^-17 and 1 + 2^-17 (exact in float).
inline constexpr long unit_tolerance_denominator = 131072;

/// A C++ expression the emitter wrote, with the precedence of its top operation on the
/// printer's scale (1 a sum or difference, 2 a product or quotient, 3 a negation, 4 an atom: a
/// name, a number, a call), so that whoever combines it further puts parentheses by its
/// structure, never by reading its text.
struct code_term {
    std::string text;
    int precedence = 4;
};

/// True when a code term of this precedence takes parentheses as an operand of a sum the writers
/// build (a + b): it is itself a sum or a binary product or quotient.
inline bool parenthesised_in_sum(int precedence)
{
    return precedence <= 2;
}

struct emitted {
    std::string code;  ///< the function body, indented by 4
    op_counts formula; ///< arithmetic of the closed form
    op_counts checks;  ///< arithmetic spent on validity checks
    bool uses_sqrt = false;
    bool uses_trig = false; ///< cos or sin: the function needs `using std::cos; using std::sin;`
    // Branchless: the checks, for the caller to fold into one flag.
    std::vector<code_term> finite_terms;     ///< values that must be finite (tested in one sum)
    std::vector<std::string> positive_terms; ///< values that must be > 0 (their min)
    std::vector<std::string> nonneg_terms;   ///< values that must be >= 0 (their min)
    std::vector<std::string>
        normal_terms; ///< values that must be normal numbers (shared reciprocals' products, check::normal_number)
    bool shares_reciprocals = false;         ///< reciprocals share divisions (their products are among normal_terms)
    std::vector<std::string> check_comments; ///< what the checks mean, in order
    /// Every value the checked form computes, in order, as `name = expression`
    /// from the same printer as the code (numbers written as in mathematics):
    /// the header's formula comments, which therefore cannot disagree with the code.
    std::vector<std::pair<std::string, std::string>> assignments;
    /// The names the code declares (`const T name`: values, shared reciprocals, outputs
    /// placed as locals), in the order of the code.
    std::vector<std::string> declared;
    /// The inputs the code reads: those the outputs are computed from and those it checks.
    std::set<std::string> inputs_read;
};

/// How emit_cpp writes an output value v of field F.
enum class output_placement {
    result, ///< `out.F = v;`: into the caller's result struct (assignments name it out.F)
    local,  ///< `const T F = v;`: a new local
    assign  ///< `F = v;`: into a variable the caller declared
};

struct emit_options {
    output_placement outputs = output_placement::result;
    /// Checks accumulate into `ok` instead of returning (the fast form; the body of a
    /// vectorisable batch loop); outputs then must be placed as locals, and no
    /// assignments are listed.
    bool branchless = false;
    /// Branchless only: reciprocals of positive inputs share one division (fewer divisions
    /// for the throughput of a vectorised loop; a longer chain of latency).
    bool share_divisions = false;
    /// The index in outputs of a value the form may leave 0 instead of computing it
    /// (energy_lost under with_energy_lost = false), or -1: its finiteness then implies
    /// nothing about the values it is made of (they are checked in their own right).
    int optional_output = -1;
    /// The index in outputs of a value written `with_energy_lost ? v : T(0)` (the energy
    /// lost, computed only when the function's template parameter asks), or -1.
    int energy_output = -1;
};

/// Emits straight-line C++ for the outputs (field name, op), placed as the options say,
/// with the checks placed right after the values they test. `names` gives ops their
/// variable names (the solution's step names, unique). `taken` are the names already
/// declared (parameters, steps, the caller's locals): new names avoid them.
emitted emit_cpp(const program &prog, const std::vector<std::pair<std::string, int>> &outputs,
                 const std::vector<check> &checks, const std::map<int, std::string> &names,
                 const std::vector<std::string> &taken, const emit_options &options = {});

} // namespace impactgen::codegen
