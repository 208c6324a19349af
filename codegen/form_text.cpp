// The text helpers of the smooth header writer (form_text.hpp).
#include "form_text.hpp"
#include "runtime.hpp"
#include "text.hpp"

#include "names/escape.hpp"
#include "names/identifier.hpp"
#include "symbolic/decide.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace impactgen::codegen::form_text
{
std::string counts_text(const op_counts &c)
{
    return std::to_string(c.add) + " add/sub, " + std::to_string(c.mul) + " mul, " + std::to_string(c.div) + " div, " +
           std::to_string(c.sqrt) + " sqrt" + (c.trig ? ", " + std::to_string(c.trig) + " cos/sin" : std::string());
}

std::string wrap_comment(const std::string &lhs, const std::string &rhs)
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

// A balanced sum: finite unless some term is not (or it overflows, checked term by term).
std::string balanced_sum(const std::vector<std::string> &names)
{
    std::vector<code_term> level;
    for (const std::string &nm : names)
        level.push_back({nm, 4});
    auto operand = [](const code_term &x) { return parenthesised_in_sum(x.precedence) ? "(" + x.text + ")" : x.text; };
    while (level.size() > 1) {
        std::vector<code_term> next;
        for (std::size_t i = 0; i + 1 < level.size(); i += 2)
            next.push_back({operand(level[i]) + " + " + operand(level[i + 1]), 1});
        if (level.size() % 2)
            next.push_back(level.back());
        level = next;
    }
    return level.empty() ? std::string() : level[0].text;
}

// The sum of the terms, added in the order their values are ready (the two earliest
// first, like a Huffman tree): the terms known early (inputs, values before the
// impulse) are summed while the impulse is computed, and the flag waits for as few
// additions as possible after the last value. The optional term is added last, under
// with_energy_lost. Each side of the conditional converted to T (autodiff expression types).
std::string timed_sum(const std::vector<sum_term> &terms)
{
    struct node {
        std::string text;
        int ready;
        std::size_t order;
        int precedence;
    };
    std::vector<node> nodes;
    std::string optional;
    for (const sum_term &t : terms) {
        if (t.optional)
            optional = t.text;
        else
            nodes.push_back({t.text, t.ready, nodes.size(), t.precedence});
    }
    auto wrap = [](const node &x) { return parenthesised_in_sum(x.precedence) ? "(" + x.text + ")" : x.text; };
    std::size_t next = nodes.size();
    while (nodes.size() > 1) {
        auto earlier = [](const node &a, const node &b) {
            return a.ready != b.ready ? a.ready < b.ready : a.order < b.order;
        };
        std::sort(nodes.begin(), nodes.end(), earlier);
        node sum{wrap(nodes[0]) + " + " + wrap(nodes[1]), std::max(nodes[0].ready, nodes[1].ready) + 3, next++, 1};
        nodes.erase(nodes.begin(), nodes.begin() + 2);
        nodes.push_back(sum);
    }
    if (optional.empty())
        return nodes.empty() ? std::string() : "T(" + nodes[0].text + ")";
    if (nodes.empty())
        return "T(" + optional + ")";
    return "with_energy_lost ? T(" + wrap(nodes[0]) + " + " + optional + ") : T(" + nodes[0].text + ")";
}

// Minimums the flag of a branchless form takes (one per list of more than one term).
std::size_t mins(const emitted &em)
{
    std::size_t n = 0;
    for (const auto *v : {&em.positive_terms, &em.nonneg_terms, &em.normal_terms})
        n += v->empty() ? 0 : v->size() - 1;
    return n;
}

// Every check of a branchless form in one flag: signs through a min (which may drop a
// NaN: every value in a min is also in the sum), finiteness through one sum.
// The finiteness terms of a flag with positive terms: those ready well before the last
// values (early: summed and folded into the min while the impulse is computed) and the
// last values (late: within an add or two of each other as the estimate goes, summed as
// a balanced tree; the optional term with them).
std::pair<std::vector<sum_term>, std::vector<sum_term>> split_by_time(const std::vector<sum_term> &finite_terms)
{
    int last = 0;
    for (const sum_term &t : finite_terms)
        if (!t.optional)
            last = std::max(last, t.ready);
    std::vector<sum_term> early, late;
    for (const sum_term &t : finite_terms)
        if (t.optional || t.ready + 7 > last)
            late.push_back({t.text, last, t.optional});
        else
            early.push_back(t);
    return {early, late};
}

// The multiply-adds (x * 0 folded into the min) and the comparisons of a flag.
std::pair<std::size_t, std::size_t> flag_counts(const emitted &form, const std::vector<sum_term> &finite_terms)
{
    std::size_t fmas = 0, tests = 0;
    if (!form.positive_terms.empty()) {
        const auto [early, late] = split_by_time(finite_terms);
        fmas = (early.empty() ? 0 : 1) + (late.empty() ? 0 : 1);
    }
    tests += !form.positive_terms.empty() || !finite_terms.empty();
    tests += !form.nonneg_terms.empty();
    tests += !form.normal_terms.empty();
    return {fmas, tests};
}

std::string ok_flag(const std::string &ind, const emitted &form, const std::vector<sum_term> &finite_terms, bool scalar)
{
    std::vector<std::string> parts;
    std::string last_part; // the part that waits for the last values: tested last
    // Each argument converted to T: with an autodiff T, T(1) - e is an expression type
    // that would not deduce.
    // A balanced tree of mins of two: its depth is the logarithm of the number of terms, not
    // the number (the flag waits for fewer dependent mins).
    auto min_of = [](const std::vector<std::string> &v) {
        if (v.size() == 1)
            return v[0];
        std::vector<std::string> level;
        for (const std::string &x : v)
            level.push_back("T(" + x + ")");
        while (level.size() > 1) {
            std::vector<std::string> next;
            for (std::size_t i = 0; i + 1 < level.size(); i += 2)
                next.push_back("detail::min_of(" + level[i] + ", " + level[i + 1] + ")");
            if (level.size() % 2)
                next.push_back(level.back());
            level = next;
        }
        return level[0];
    };
    // The sums converted to T too: with an autodiff T a sum of values is an expression
    // type, and finite(x) would deduce it (AutoDiffScalar<CwiseBinaryOp<...>>: no T(0)).
    if (!form.positive_terms.empty()) {
        const std::string m =
            form.positive_terms.size() == 1 ? "T(" + form.positive_terms[0] + ")" : min_of(form.positive_terms);
        // With the finiteness in the same comparison: x * 0 is +-0 when x is finite
        // (min + 0 = min) and NaN when not (NaN > 0 fails). The terms ready before the
        // last ones (inputs, values before the impulse) are summed and folded into the
        // min while the impulse is computed; after the last values the flag waits for
        // their sum and one multiply-add, instead of the whole sum, a subtraction, a
        // comparison and a flag of its own. (Written min + x * 0: g++ 12 contracts it
        // into one fma, x * 0 + min not.)
        const auto [early, late] = split_by_time(finite_terms);
        auto wrapped = [](const std::string &x) { return x.find('?') != std::string::npos ? "T(" + x + ")" : x; };
        std::string folded = m;
        if (!early.empty())
            folded = "T(" + folded + " + " + wrapped(timed_sum(early)) + " * T(0))";
        if (!late.empty())
            folded = "T(" + folded + " + " + wrapped(timed_sum(late)) + " * T(0))";
        last_part = "(" + folded + " > T(0))";
    }
    if (!form.nonneg_terms.empty())
        parts.push_back("(" + min_of(form.nonneg_terms) + " >= T(0))");
    if (!form.normal_terms.empty())
        parts.push_back("(" + min_of(form.normal_terms) + " >= detail::smallest_normal<T>())");
    if (!finite_terms.empty() && form.positive_terms.empty())
        last_part = "detail::finite(" + timed_sum(finite_terms) + ")";
    if (!last_part.empty())
        parts.push_back(last_part);
    std::string text;
    if (!form.check_comments.empty() || form.shares_reciprocals) {
        std::string what = names::comment_text(join(form.check_comments, "; "));
        if (form.shares_reciprocals)
            what += std::string(what.empty() ? "" : "; ") + "shared reciprocals in range";
        text += ind + "// checks: " + what + "; every value finite\n";
    }
    if (scalar) {
        // The scalar forms: the parts joined by &&, which the compiler may test with a
        // branch each (the earlier parts decided before the last values are there;
        // predicted, they cost less than folding the comparisons into one flag).
        text += ind + "const bool ok = " +
                (parts.empty() ? std::string("true") : join(parts, " &&\n" + ind + "                ")) + ";\n";
        return text;
    }
    // The batch loop: folded as unsigned so that no branch is implied (the loop
    // vectorises) and clang's -Wbitwise-instead-of-logical has nothing to say.
    for (std::string &part : parts)
        part = "static_cast<unsigned>" + (part.front() == '(' ? part : "(" + part + ")");
    text += ind + "const bool ok = " +
            (parts.empty() ? std::string("true") : "(" + join(parts, " &\n" + ind + "                 ") + ") != 0u") +
            ";\n";
    return text;
}

// The options of a branchless form (fast, batch, Jacobian): one flag, outputs as locals.
emit_options branchless_form(bool share_divisions, int optional_output)
{
    emit_options o;
    o.outputs = output_placement::local;
    o.branchless = true;
    o.share_divisions = share_divisions;
    o.optional_output = optional_output;
    return o;
}

namespace
{
// The blocks of a symmetric tensor: axes coupled by a non-zero entry share a block. Each
// block lists its axes in order; the blocks in the order of their first axis.
std::vector<std::vector<std::size_t>> tensor_blocks(const mat3 &J)
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
    std::vector<std::vector<std::size_t>> blocks;
    for (int first = 0; first < 3; ++first) {
        std::vector<std::size_t> a;
        for (std::size_t k = 0; k < 3; ++k)
            if (block_of[k] == first)
                a.push_back(k);
        if (!a.empty())
            blocks.push_back(a);
    }
    return blocks;
}
} // namespace

// The leading principal minors that make a symmetric tensor positive definite, block by
// block: axes coupled by non-zero off-diagonal entries form a block (a diagonal tensor is
// three blocks of one entry), and the tensor is positive definite when each block is. Per
// block its leading minors of order 1 and 2, and of order 3 for a block of all three axes
// when with_determinant (else the caller checks its determinant step). Minors of blocks,
// not of the whole tensor: no product of entries of different blocks, whose range float
// may not hold (a diagonal I = 1e13 would give 1e39).
std::vector<std::pair<ex, std::string>> positive_definite_minors(const mat3 &J, const std::array<std::string, 3> &axes,
                                                                 bool with_determinant)
{
    std::vector<std::pair<ex, std::string>> minors;
    for (const std::vector<std::size_t> &a : tensor_blocks(J)) {
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

std::vector<std::pair<ex, std::string>> positive_semidefinite_minors(const mat3 &J,
                                                                     const std::array<std::string, 3> &axes)
{
    std::vector<std::pair<ex, std::string>> minors;
    for (const std::vector<std::size_t> &a : tensor_blocks(J)) {
        for (std::size_t x : a)
            minors.push_back({J[x][x], axes[x] + axes[x] + " entry >= 0, finite"});
        for (std::size_t i = 0; i < a.size(); ++i)
            for (std::size_t j = i + 1; j < a.size(); ++j) {
                const std::size_t x = a[i], y = a[j];
                minors.push_back({J[x][x] * J[y][y] - J[x][y] * J[y][x], "minor " + axes[x] + axes[x] + " " + axes[y] +
                                                                             axes[y] + " - " + axes[x] + axes[y] +
                                                                             "^2 >= 0, finite"});
            }
        if (a.size() == 3)
            minors.push_back({det(J), "determinant >= 0, finite"});
    }
    return minors;
}

// The command that regenerates a header, as its banner writes it.
std::string command_line(const options &o)
{
    std::string command = "impactgen codegen " + o.source + " --name " + o.name + " --namespace " + o.ns;
    if (o.params_given)
        command += " --params " + join(o.params, ",");
    if (!o.set.empty()) {
        std::vector<std::string> kv;
        for (auto &[k, v] : o.set)
            kv.push_back(k + "=" + v);
        command += " --set " + join(kv, ",");
    }
    if (o.inverse_inertia)
        command += " --inverse-inertia";
    if (o.inverse_mass)
        command += " --inverse-mass";
    if (o.unit_normal)
        command += " --unit-normal";
    if (!o.wrt.empty())
        command += " --wrt " + join(o.wrt, ",");
    else if (o.jacobian)
        command += " --jacobian";
    return command;
}

// The function name and the namespace of a header, refused with option_error when unusable.
void check_names(const options &o)
{
    if (!names::is_safe_identifier(o.name) || reserved().count(o.name) || o.name.back() == '_')
        throw option_error(
            option_error::function_name,
            "\"" + names::display_text(o.name) +
                "\" is not a usable C++ identifier (letters, digits and single underscores, not ending in one; "
                "not a keyword or a reserved name)");
    if (std::string why = names::namespace_problem(o.ns); !why.empty())
        throw option_error(option_error::name_space, "\"" + names::display_text(o.ns) + "\": " + why);
}

} // namespace impactgen::codegen::form_text
