#include "codegen.hpp"

#include "names/escape.hpp"
#include "names/identifier.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

namespace impactgen::codegen {
using namespace GiNaC;

namespace {

// Names the emitted code itself uses inside the functions (keywords and
// reserved C++ names never come out of names::mangle).
const std::set<std::string>& reserved()
{
    static const std::set<std::string> r = {"out", "fail", "why", "T", "in", "detail", "check_sum", "ok", "status", "failed",
                                            "with_energy_lost", "impact_status", "op_count", "to_string", "finite", "all_finite",
                                            "min_of", "sqrt", "std", "i", "n", "r", "a"};
    return r;
}

std::string join(const std::vector<std::string>& v, const std::string& sep)
{
    std::string r;
    for (const std::string& s : v)
        r += (r.empty() ? "" : sep) + s;
    return r;
}

std::string counts_text(const op_counts& c)
{
    return std::to_string(c.add) + " add/sub, " + std::to_string(c.mul) + " mul, " + std::to_string(c.div) + " div, " +
           std::to_string(c.sqrt) + " sqrt";
}

std::string wrap_comment(const std::string& lhs, const std::string& rhs)
{
    // One formula per line; long right-hand sides continue on indented lines.
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

} // namespace

header generate(const problem& p, const options& o)
{
    if (!names::is_safe_identifier(o.name) || reserved().count(o.name))
        throw option_error(option_error::function_name,
                           "\"" + names::display_text(o.name) +
                               "\" is not a usable C++ identifier (letters, digits and single underscores, not a keyword or a "
                               "reserved name)");
    if (std::string why = names::namespace_problem(o.ns); !why.empty())
        throw option_error(option_error::name_space, "\"" + names::display_text(o.ns) + "\": " + why);
    plan pl = make_plan(p, o);
    const solution& s = pl.sol;
    const problem& q = pl.prob;

    // Every name the header declares comes from one scope (names/identifier.hpp):
    // the emitter's own names first, then inputs, steps and the locals derived
    // from outputs and inputs, so no user name can shadow or collide with another.
    names::identifier_scope scope, members;
    for (const std::string& r : reserved())
        if (names::is_safe_identifier(r))
            scope.reserve(r);
    for (const char* suffix : {"", "_result", "_checked", "_batch", "_input_count", "_output_count", "_input_names",
                               "_output_names", "_ops", "_to_array"})
        scope.reserve(o.name + suffix);
    std::map<ex, std::string, ex_is_less> input_ident; // input symbol -> C++ parameter
    std::vector<std::string> input_names;
    for (const symbol& x : pl.inputs) {
        input_names.push_back(scope.claim(x.get_name()));
        input_ident[x] = input_names.back();
    }
    for (output_value& ov : pl.outputs)
        ov.field = members.claim(ov.field);
    canonical_pool pool;
    pool.set_input_names(input_ident);
    program prog;
    std::map<int, std::string> names;
    for (std::size_t i = 0; i < s.steps.size(); ++i) {
        const step& st = s.steps[i];
        const std::string nm = scope.claim(st.sym.get_name());
        scaled v = pool.convert(st.value);
        pool.bind_step(st.sym, static_cast<int>(i), nm);
        prog.set_owner(nm);
        int id = prog.lower(pool, v);
        prog.set_step(static_cast<int>(i), id);
        if (!prog.is_leaf(id) && !names.count(id))
            names[id] = nm;
    }
    std::vector<std::pair<std::string, int>> outs, outs_local;
    std::map<std::string, std::string> local_of, out_ptr, in_ptr; // member -> local value / output pointer; input -> input pointer
    for (const output_value& ov : pl.outputs) {
        scaled v = pool.convert(ov.value);
        prog.set_owner(ov.field);
        outs.push_back({ov.field, prog.lower(pool, v)});
        local_of[ov.field] = scope.claim("o_" + ov.field);
        out_ptr[ov.field] = scope.claim("out_" + ov.field);
        outs_local.push_back({local_of[ov.field], outs.back().second});
    }
    for (const std::string& nm : input_names)
        in_ptr[nm] = scope.claim("in_" + nm);
    std::vector<std::string> all_taken = scope.names();
    // Validity checks, each right after the value it tests.
    std::vector<check> checks;
    auto add_check = [&](const ex& value, check::kind_t kind, const std::string& status, const std::string& comment) {
        if (is_a<numeric>(value))
            return; // constants were validated when the problem was read
        prog.set_owner("check");
        checks.push_back({kind, prog.lower(pool, pool.convert(value)), status, comment});
    };
    add_check(q.restitution, check::unit_interval, "invalid_restitution", "0 <= e <= 1");
    for (std::size_t i : {q.contact.body1, q.contact.body2}) {
        const body& b = q.bodies[i];
        if (b.infinite_mass)
            continue;
        auto inverse = [&](const ex& x) -> const symbol* {
            auto it = pl.inverse_of.find(x);
            return it == pl.inverse_of.end() ? nullptr : &it->second;
        };
        const symbol* inv_m = inverse(b.mass);
        add_check(inv_m ? ex(*inv_m) : b.mass, check::positive, "invalid_mass",
                  (inv_m ? "inverse mass of " : "mass of ") + b.name + " > 0, finite");
        if (!b.particle && q.dimension == 2) {
            const symbol* inv_I = inverse(b.inertia[2][2]);
            add_check(inv_I ? ex(*inv_I) : b.inertia[2][2], check::positive, "invalid_inertia",
                      (inv_I ? "inverse moment of inertia of " : "moment of inertia of ") + b.name + " > 0, finite");
        }
    }
    const bool has_k = s.find(step_role::contact_inverse_mass) != nullptr;
    for (const step& st : s.steps) {
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
        default: break;
        }
    }
    emitted em = emit_cpp(prog, outs, checks, names, all_taken);

    op_counts unused_counts;
    // The branchless forms: one call (latency: a division each) and the batch loop
    // (throughput: reciprocals share divisions).
    emitted fast = emit_cpp(prog, outs_local, checks, names, all_taken, true);
    emitted batch = emit_cpp(prog, outs_local, checks, names, all_taken, true, true);
    (void)unused_counts;
    // Inputs the outputs do not depend on still count for the finiteness check.
    std::set<std::string> reached;
    for (std::size_t i = 0; i < prog.size(); ++i)
        if (prog.at(static_cast<int>(i)).kind == op::input)
            reached.insert(prog.at(static_cast<int>(i)).name);
    std::vector<std::string> sum_terms;
    for (const auto& [field, id] : outs)
        if (prog.at(id).kind != op::constant)
            sum_terms.push_back("out." + field);
    std::vector<std::string> unused_inputs;
    for (const std::string& nm : input_names)
        if (!reached.count(nm)) {
            sum_terms.push_back(nm);
            unused_inputs.push_back(nm);
        }

    // The terms of the finiteness check in the branchless form (o_<field> values).
    auto finite_terms = [&](const emitted& em_) {
        std::vector<std::string> t;
        for (const auto& [field, id] : outs)
            if (prog.at(id).kind != op::constant)
                t.push_back(local_of.at(field));
        for (const std::string& nm : unused_inputs)
            t.push_back(nm);
        for (const std::string& x : em_.finite_terms)
            if (std::find(t.begin(), t.end(), x) == t.end())
                t.push_back(x);
        return t;
    };
    const std::vector<std::string> fast_terms = finite_terms(fast), batch_terms = finite_terms(batch);

    // ---- the header text
    const std::string R = o.name + "_result";
    std::ostringstream h;
    std::string command = "impactgen codegen " + o.source + " --name " + o.name + " --namespace " + o.ns;
    if (o.params_given)
        command += " --params " + join(o.params, ",");
    if (!o.set.empty()) {
        std::vector<std::string> kv;
        for (auto& [k, v] : o.set)
            kv.push_back(k + "=" + v);
        command += " --set " + join(kv, ",");
    }
    if (o.inverse_inertia)
        command += " --inverse-inertia";
    if (o.inverse_mass)
        command += " --inverse-mass";
    h << "// Generated by impactgen " << o.version << " from " << names::comment_text(o.source) << ". Do not edit: regenerate.\n";
    h << "//   " << names::comment_text(command) << "\n";
    h << "// Closed form of the smooth impact, specialised; plain C++17, no dependency, no allocation.\n";
    h << "// Arithmetic per call: " << counts_text(em.formula) << " (closed form);\n";
    h << "//   validity checks: " << counts_text(em.checks) << " + " << (sum_terms.empty() ? 0 : sum_terms.size() - 1)
      << " add (finiteness of the result), and comparisons;\n";
    auto mins = [](const emitted& em_) {
        std::size_t n = 0;
        for (const auto* v : {&em_.positive_terms, &em_.nonneg_terms, &em_.normal_terms})
            n += v->empty() ? 0 : v->size() - 1;
        return n;
    };
    h << "//   fast path (inputs that pass every check): " << counts_text(fast.formula) << " + " << (fast_terms.empty() ? 0 : fast_terms.size() - 1)
      << " add, " << mins(fast) << " min (checks), 1 branch;\n";
    h << "//   batch loop: " << counts_text(batch.formula) << " + " << (batch_terms.empty() ? 0 : batch_terms.size() - 1) << " add, "
      << mins(batch) << " min (checks) per impact, no branch.\n";
    h << "#pragma once\n\n";
    if (em.uses_sqrt)
        h << "#include <cmath>\n";
    if (!batch.normal_terms.empty())
        h << "#include <limits>\n";
    if (em.uses_sqrt || !batch.normal_terms.empty())
        h << "\n";
    const std::string guard = names::guard_macro("PREAMBLE", o.ns);
    h << "namespace " << o.ns << " {\n\n";
    h << "#ifndef " << guard << "\n#define " << guard << "\n";
    h << R"(/// Why a call computed no post-impact state (the result is then all zeros).
enum class impact_status : int {
    ok = 0,
    non_finite_input,    ///< an input is infinite or NaN
    invalid_mass,        ///< a mass (or inverse mass) is <= 0 or not finite
    invalid_inertia,     ///< an inertia (or its determinant) is <= 0 or not finite
    invalid_restitution, ///< e outside [0, 1]
    not_approaching,     ///< the contact points separate or rest: (v_B - v_A).n >= 0
    singular,            ///< the effective inverse mass k = w_1 + w_2 is not positive and finite
    overflow             ///< finite inputs whose result overflows
};

inline constexpr const char* to_string(impact_status s) noexcept
{
    switch (s) {
    case impact_status::ok: return "ok";
    case impact_status::non_finite_input: return "non-finite input";
    case impact_status::invalid_mass: return "invalid mass";
    case impact_status::invalid_inertia: return "invalid inertia";
    case impact_status::invalid_restitution: return "invalid restitution";
    case impact_status::not_approaching: return "not approaching";
    case impact_status::singular: return "singular effective mass";
    case impact_status::overflow: return "overflow";
    }
    return "?";
}

/// Floating-point operations of one call of a generated function.
struct op_count {
    int add, mul, div, sqrt;
};

namespace detail {
template <typename T> constexpr bool finite(T x) noexcept { return x - x == T(0); }
template <typename T, typename... U> constexpr bool all_finite(T x, U... y) noexcept
{
    return (finite(x) && ... && finite(y));
}
template <typename T> constexpr T min_of(T x) noexcept { return x; }
/// The smallest argument (a NaN argument may be dropped: callers test finiteness apart).
template <typename T, typename... U> constexpr T min_of(T x, T y, U... z) noexcept
{
    return min_of(y < x ? y : x, z...);
}
} // namespace detail
#if defined(__GNUC__)
#define IMPACTGEN_COLD __attribute__((noinline, cold)) // the slow path that classifies failures
#define IMPACTGEN_HOT __attribute__((always_inline))   // the fast path, inlined at each call
#else
#define IMPACTGEN_COLD
#define IMPACTGEN_HOT
#endif
#endif

)";
    // Result struct.
    h << "/// Post-impact state of " << o.name << " (units as the inputs).\n";
    h << "template <typename T> struct " << R << " {\n";
    for (const output_value& ov : pl.outputs)
        h << "    T " << ov.field << "; ///< " << names::comment_text(ov.meaning) << "\n";
    h << "};\n\n";

    // Formula block.
    h << "// Formulas (impactgen's closed form; n the unit normal from body 1 into body 2,\n";
    h << "// s_1 = -1, s_2 = +1; r_i = O - C_i for a free body, O - E for a body pinned at E):\n";
    h << "//   w_i  = 1/m_i + (r_i x n) . g_i,  g_i = I_i^{-1} (r_i x n)  (free rigid body; 1/m_i for a particle;\n";
    h << "//          pinned: (r_i x n) . g_i with I_E = I_C + m (|d|^2 1 - d d^T), d = C - E)\n";
    h << "//   u    = (v_B - v_A) . n,  v_A = v_C1 + w_1 x (O - C_1)        (u < 0: the contact points approach)\n";
    h << "//   k    = w_1 + w_2,  N = -(1 + e) u / k                          (impulse per unit normal)\n";
    h << "//   v'_i = v_i + s_i N n / m_i (pinned: w' x (C - E)),  w'_i = w_i + s_i N g_i\n";
    h << "//   T_lost = -sum_i (s_i N a_i + N^2 w_i / 2),  a_i = v_{contact point of i} . n\n";
    if (o.inverse_inertia && q.dimension == 2)
        h << "// Input convention: inverse moments of inertia inv_I = 1/I (as physics engines store them).\n";
    else if (o.inverse_inertia)
        h << "// Input convention: inverse inertia tensors inv_I (as physics engines store them), so g_i = inv_I_i (r_i x n).\n";
    if (o.inverse_mass)
        h << "// Input convention: inverse masses inv_m = 1/m.\n";
    h << "// This problem, step by step, as the code below computes it:\n";
    for (const auto& [lhs, rhs] : em.assignments)
        h << wrap_comment(lhs, rhs);

    // A balanced sum: finite unless some term is not (or it overflows, checked term by term).
    auto balanced_sum = [](std::vector<std::string> level) {
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
    };
    // Every check of the branchless form in one flag: signs through a min (which may drop a
    // NaN: every value in a min is also in the sum), finiteness through one sum.
    auto ok_flag = [&](const std::string& ind, const emitted& batch, const std::vector<std::string>& fast_terms) {
        std::vector<std::string> parts;
        auto min_of = [](const std::vector<std::string>& v) {
            return v.size() == 1 ? v[0] : "detail::min_of(" + join(v, ", ") + ")";
        };
        if (!batch.positive_terms.empty())
            parts.push_back("(" + min_of(batch.positive_terms) + " > T(0))");
        if (!batch.nonneg_terms.empty())
            parts.push_back("(" + min_of(batch.nonneg_terms) + " >= T(0))");
        if (!batch.normal_terms.empty())
            parts.push_back("(" + min_of(batch.normal_terms) + " >= std::numeric_limits<T>::min())");
        if (!fast_terms.empty())
            parts.push_back("detail::finite(" + balanced_sum(fast_terms) + ")");
        std::string text;
        if (!batch.check_comments.empty() || !batch.normal_terms.empty()) {
            std::string what = names::comment_text(join(batch.check_comments, "; "));
            if (!batch.normal_terms.empty())
                what += std::string(what.empty() ? "" : "; ") + "shared reciprocals in range";
            text += ind + "// checks: " + what + "; every value finite\n";
        }
        // Folded as unsigned so that no branch is implied and clang's
        // -Wbitwise-instead-of-logical has nothing to say.
        for (std::string& part : parts)
            part = "static_cast<unsigned>" + (part.front() == '(' ? part : "(" + part + ")");
        text += ind + "const bool ok = " +
                (parts.empty() ? std::string("true")
                               : "(" + join(parts, " &\n" + ind + "                 ") + ") != 0u") +
                ";\n";
        return text;
    };

    // energy_lost on request: with_energy_lost = false leaves it 0 (not computed, not checked).
    auto energy_optional = [](const std::string& code, const std::string& lhs) {
        std::istringstream lines(code);
        std::string line, r;
        while (std::getline(lines, line)) {
            if (line.rfind(lhs, 0) == 0 && line.size() > lhs.size() && line.back() == ';') {
                std::string rhs = line.substr(lhs.size(), line.size() - lhs.size() - 1);
                if (rhs.find(' ') != std::string::npos)
                    rhs = "(" + rhs + ")";
                line = lhs + "with_energy_lost ? " + rhs + " : T(0);";
            }
            r += line + "\n";
        }
        return r;
    };
    const std::string tparams = "template <typename T, bool with_energy_lost = true>\n";

    // The checked version: each check right after the value it tests, with its own status.
    std::string params;
    for (const std::string& nm : input_names)
        params += "T " + nm + ", ";
    const std::string checked = o.name + "_checked";
    h << "\nnamespace detail {\n";
    h << "/// " << o.name << " with each check right after the value it tests: the status of the\n";
    h << "/// inputs that fail the fast path of " << o.name << " (every member of out is then zero).\n";
    h << tparams << "IMPACTGEN_COLD inline impact_status " << checked << "(" << params << R << "<T>& out) noexcept\n{\n";
    if (em.uses_sqrt)
        h << "    using std::sqrt;\n";
    h << "    auto fail = [&](impact_status why) noexcept {\n";
    h << "        out = " << R << "<T>{};\n";
    if (input_names.empty())
        h << "        return why;\n";
    else
        h << "        return detail::all_finite(" << join(input_names, ", ") << ") ? why : impact_status::non_finite_input;\n";
    h << "    };\n";
    h << "    (void)fail; // a fully numeric problem may have no check left\n";
    h << energy_optional(em.code, "    out.energy_lost = ");
    if (!sum_terms.empty()) {
        h << "    const T check_sum = " << balanced_sum(sum_terms) << ";\n";
        h << "    if (!detail::finite(check_sum) && !detail::all_finite(" << join(sum_terms, ", ") << "))\n";
        h << "        return fail(impact_status::overflow);\n";
    }
    h << "    return impact_status::ok;\n}\n} // namespace detail\n\n";

    // The function: every check folded into one flag, one branch.
    h << "/// Post-impact state for the inputs below; returns impact_status::ok, or why not\n";
    h << "/// (then every member of out is zero). T: float, double, long double or alike.\n";
    h << "/// The checks do not branch one by one: they are folded into one flag, and only\n";
    h << "/// inputs that fail one of them take the slow path (detail::" << checked << ") that\n";
    h << "/// says which check failed. with_energy_lost = false: out.energy_lost is left 0,\n";
    h << "/// neither computed nor checked (the rest is the same).\n";
    for (std::size_t i = 0; i < input_names.size(); ++i)
        h << "///   " << input_names[i] << ": " << names::comment_text(pl.input_meaning[i]) << "\n";
    h << tparams << "IMPACTGEN_HOT inline impact_status " << o.name << "(" << params << R << "<T>& out) noexcept\n{\n";
    if (em.uses_sqrt)
        h << "    using std::sqrt;\n";
    h << energy_optional(fast.code, "    const T " + local_of.at("energy_lost") + " = ");
    h << ok_flag("    ", fast, fast_terms);
    h << "    if (!ok) // some check failed (or a value is not finite): find which\n";
    h << "        return detail::" << checked << "<T, with_energy_lost>(";
    for (const std::string& nm : input_names)
        h << nm << ", ";
    h << "out);\n";
    for (const output_value& ov : pl.outputs)
        h << "    out." << ov.field << " = " << local_of.at(ov.field) << ";\n";
    h << "    return impact_status::ok;\n}\n\n";

    // Array form, names, counts.
    h << "/// The same with the inputs in an array, in the order of " << o.name << "_input_names.\n";
    h << tparams << "IMPACTGEN_HOT inline impact_status " << o.name << "(const T* in, " << R << "<T>& out) noexcept\n{\n";
    if (input_names.empty())
        h << "    (void)in;\n";
    h << "    return " << o.name << "<T, with_energy_lost>(";
    for (std::size_t i = 0; i < input_names.size(); ++i)
        h << "in[" << i << "], ";
    h << "out);\n}\n\n";
    // Batch form over arrays (structure of arrays), branchless so that it vectorises.
    h << "/// The same over n impacts in structure-of-arrays form: in[j][i] is input j\n";
    h << "/// (order of " << o.name << "_input_names) of impact i, out[j][i] output j. The arrays\n";
    h << "/// must not overlap. A first pass computes every impact without branches (it\n";
    h << "/// vectorises); if any impact failed a check, a second pass redoes those one by\n";
    h << "/// one for their status (their outputs are zero).\n";
    std::size_t energy_index = pl.outputs.size();
    for (std::size_t j = 0; j < pl.outputs.size(); ++j)
        if (pl.outputs[j].kind == output_value::energy_lost)
            energy_index = j;
    if (energy_index < pl.outputs.size())
        h << "/// with_energy_lost = false: energy_lost is neither computed nor checked, and out[" << energy_index
          << "] is not written (it may be null).\n";
    h << tparams << "inline void " << o.name << "_batch(long n, const T* const* in, T* const* out, impact_status* status) noexcept\n{\n";
    if (input_names.empty())
        h << "    (void)in;\n";
    for (std::size_t j = 0; j < input_names.size(); ++j)
        h << "    const T* const " << in_ptr.at(input_names[j]) << " = in[" << j << "];\n";
    for (std::size_t j = 0; j < pl.outputs.size(); ++j)
        h << "    T* const " << out_ptr.at(pl.outputs[j].field) << " = out[" << j << "];\n";
    h << "    unsigned failed = 0; // any impact that failed a check (the second pass is skipped when none did)\n";
    h << "#if defined(__GNUC__) && !defined(__clang__)\n#pragma GCC ivdep\n#endif\n";
    h << "    for (long i = 0; i < n; ++i) {\n";
    for (const std::string& nm : input_names)
        h << "        const T " << nm << " = " << in_ptr.at(nm) << "[i];\n";
    {
        std::istringstream lines(energy_optional(batch.code, "    const T " + local_of.at("energy_lost") + " = ") + ok_flag("    ", batch, batch_terms));
        std::string line;
        while (std::getline(lines, line))
            h << "    " << line << "\n";
    }
    // Stored unconditionally: the second pass overwrites the outputs of failed impacts.
    for (const output_value& ov : pl.outputs)
        h << (ov.kind == output_value::energy_lost ? "        if constexpr (with_energy_lost)\n    " : "") << "        " << out_ptr.at(ov.field)
          << "[i] = " << local_of.at(ov.field) << ";\n";
    h << "        status[i] = ok ? impact_status::ok : impact_status::overflow; // refined below\n";
    h << "        failed |= static_cast<unsigned>(!ok);\n";
    h << "    }\n";
    h << "    if (failed == 0)\n";
    h << "        return;\n";
    h << "    for (long i = 0; i < n; ++i)\n";
    h << "        if (status[i] != impact_status::ok) {\n";
    h << "            " << R << "<T> r;\n";
    h << "            status[i] = detail::" << checked << "<T, with_energy_lost>(";
    for (const std::string& nm : input_names)
        h << in_ptr.at(nm) << "[i], ";
    h << "r);\n";
    for (const output_value& ov : pl.outputs)
        h << (ov.kind == output_value::energy_lost ? "            if constexpr (with_energy_lost)\n    " : "") << "            " << out_ptr.at(ov.field)
          << "[i] = r." << ov.field << ";\n";
    h << "        }\n";
    h << "}\n\n";
    h << "inline constexpr int " << o.name << "_input_count = " << input_names.size() << ";\n";
    h << "inline constexpr int " << o.name << "_output_count = " << pl.outputs.size() << ";\n";
    h << "inline constexpr const char* " << o.name << "_input_names[] = {";
    for (const std::string& nm : input_names)
        h << names::cpp_string_literal(nm) << ", ";
    h << "nullptr};\n";
    h << "inline constexpr const char* " << o.name << "_output_names[] = {";
    for (const output_value& ov : pl.outputs)
        h << names::cpp_string_literal(ov.field) << ", ";
    h << "nullptr};\n";
    h << "/// Arithmetic of the closed form per call (validity checks not included).\n";
    h << "inline constexpr op_count " << o.name << "_ops{" << em.formula.add << ", " << em.formula.mul << ", "
      << em.formula.div << ", " << em.formula.sqrt << "};\n\n";
    h << "/// The members of r in the order of " << o.name << "_output_names.\n";
    h << "template <typename T> inline void " << o.name << "_to_array(const " << R << "<T>& r, T* a) noexcept\n{\n";
    for (std::size_t i = 0; i < pl.outputs.size(); ++i)
        h << "    a[" << i << "] = r." << pl.outputs[i].field << ";\n";
    h << "}\n\n} // namespace " << o.ns << "\n";

    header out;
    out.text = h.str();
    out.formula = em.formula;
    out.checks = em.checks;
    out.inputs = input_names;
    for (const output_value& ov : pl.outputs)
        out.outputs.push_back(ov.field);
    (void)unused_inputs;
    return out;
}

bool write_if_changed(const std::string& path, const std::string& text)
{
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw input_error(names::display_text(path) + ": not a regular file (the header is written only to a regular file or "
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
