// Emission of a straight-line program (program.hpp): emit_cpp and decimal_literal; the
// lowering of canonical trees into the program is program.cpp.
#include "program.hpp"

#include "names/escape.hpp"

#include <algorithm>
#include <iterator>
#include <set>
#include <stdexcept>

namespace impactgen::codegen
{
using GiNaC::numeric;

// ---------------------------------------------------------------------------
// Emission

namespace
{

struct printer {
    const program &prog;
    const std::vector<bool> &materialised;
    const std::vector<int> &refs;
    const std::map<int, std::string> &var;
    op_counts *counts;
    bool plain = false; ///< numbers as in mathematics (1/2), for the formula comments; else T(1) / T(2)

    bool inline_recip(int id) const
    {
        const op &o = prog.at(id);
        return o.kind == op::div && prog.at(o.a).kind == op::constant && prog.at(o.a).value == 1 &&
               !materialised[static_cast<std::size_t>(id)] && refs[static_cast<std::size_t>(id)] == 1;
    }

    // precedence: 1 = additive, 2 = multiplicative, 3 = unary, 4 = atom
    std::string text(int id, int &prec, bool top = false) const
    {
        const op &o = prog.at(id);
        if (!top && (materialised[static_cast<std::size_t>(id)] || o.kind == op::input)) {
            prec = 4;
            return o.kind == op::input ? o.name : var.at(id);
        }
        switch (o.kind) {
        case op::input:
            prec = 4;
            return o.name;
        case op::constant:
            prec = plain && !o.value.is_integer() ? 1 : 4;
            return plain ? number_text(o.value) : literal(o.value);
        case op::neg: {
            int p;
            std::string s = text(o.a, p);
            prec = 3;
            return "-" + (p < 3 ? "(" + s + ")" : s);
        }
        case op::sqrt_: {
            int p;
            std::string s = text(o.a, p);
            ++counts->sqrt;
            prec = 4;
            return "sqrt(" + s + ")";
        }
        case op::cos_:
        case op::sin_: {
            int p;
            std::string s = text(o.a, p);
            ++counts->trig;
            prec = 4;
            return (o.kind == op::cos_ ? "cos(" : "sin(") + s + ")";
        }
        case op::add:
        case op::sub: {
            int pa, pb;
            std::string sa = text(o.a, pa), sb = text(o.b, pb);
            ++counts->add;
            prec = 1;
            if (o.kind == op::sub && pb <= 1)
                sb = "(" + sb + ")";
            return sa + (o.kind == op::add ? " + " : " - ") + sb;
        }
        case op::mul:
        case op::div: {
            int a = o.a, b = o.b;
            bool as_div = o.kind == op::div;
            if (o.kind == op::mul) {
                if (inline_recip(a) && !inline_recip(b))
                    std::swap(a, b);
                if (inline_recip(b)) {
                    as_div = true;
                    b = prog.at(b).b;
                }
            }
            int pa, pb;
            std::string sa = text(a, pa), sb = text(b, pb);
            if (as_div)
                ++counts->div;
            else
                ++counts->mul;
            prec = 2;
            if (pa < 2)
                sa = "(" + sa + ")";
            if (pb < 2 || (as_div && pb == 2))
                sb = "(" + sb + ")";
            return sa + (as_div ? " / " : " * ") + sb;
        }
        }
        return "?";
    }

    static std::string literal(const numeric &x)
    {
        auto integer = [](const numeric &k) {
            // exact in T when |k| <= 2^53 (and written as an integer literal); otherwise via long double
            if (abs(k) <= numeric(9007199254740992LL))
                return "T(" + number_text(k) + ")";
            return "detail::constant<T>(IMPACTGEN_WIDE(" + number_text(k) + ".0))";
        };
        const numeric limit(9007199254740992LL); // 2^53
        if (x.is_integer() && abs(x) <= limit)
            return integer(x);
        if (x.is_rational() && abs(x.numer()) <= limit && x.denom() <= limit)
            return "(" + integer(x.numer()) + " / " + integer(x.denom()) + ")";
        // Any other number as one long double literal of 40 significant digits: never
        // T(huge) / T(huge), which overflows to inf/inf in double or float.
        return "detail::constant<T>(" + decimal_literal(x) + ")";
    }
};

} // namespace

std::string decimal_literal(const numeric &x)
{
    const long saved = GiNaC::Digits;
    GiNaC::Digits = 40;
    numeric v = x.is_rational() ? GiNaC::ex_to<numeric>(GiNaC::ex(x).evalf()) : x;
    GiNaC::Digits = saved;
    std::string t = number_text(v);
    for (char &c : t)
        if (c == 'E')
            c = 'e';
    if (t.find_first_of(".e") == std::string::npos)
        t += ".0";
    return "IMPACTGEN_WIDE(" + t + ")"; // a long double literal, or a double one in device code
}

namespace
{

// base, or base_2, base_3, ... when taken (never "__", which C++ reserves).
std::string unique_name(const std::set<std::string> &taken, const std::string &base)
{
    std::string nm = base;
    for (int k = 2; taken.count(nm); ++k)
        nm = base + (base.back() == '_' ? "" : "_") + std::to_string(k);
    return nm;
}

} // namespace

namespace
{

bool is_reciprocal(const program &prog, const op &o)
{
    return o.kind == op::div && prog.at(o.a).kind == op::constant && prog.at(o.a).value == 1;
}

void add_unique(std::vector<std::string> &v, const std::string &t)
{
    if (std::find(v.begin(), v.end(), t) == v.end())
        v.push_back(t);
}

void add_unique(std::vector<code_term> &v, const std::string &t, int precedence)
{
    if (std::none_of(v.begin(), v.end(), [&](const code_term &x) { return x.text == t; }))
        v.push_back({t, precedence});
}

// One emission of the program: which values are reached and named, which are
// implied finite by the outputs, which reciprocals share a division, then the
// code in program order with each check right after the value it tests.
class emitter
{
public:
    emitter(const program &prog, const std::vector<std::pair<std::string, int>> &outputs,
            const std::vector<check> &checks, const std::map<int, std::string> &names,
            const std::vector<std::string> &taken, const emit_options &options)
        : prog_(prog), outputs_(outputs), checks_(checks), names_(names), placement_(options.outputs),
          branchless_(options.branchless), share_divisions_(options.share_divisions),
          optional_output_(options.optional_output), energy_output_(options.energy_output), n_(prog.size()),
          reach_(n_, false), materialised_(n_, false), covered_(n_, false), needed_(n_, false), emitted_(n_, false),
          refs_(n_, 0), used_names_(taken.begin(), taken.end())
    {
        if (branchless_ && placement_ != output_placement::local)
            throw std::logic_error("code generation: a branchless form places its outputs as locals");
    }

    emitted run()
    {
        mark_reachable();
        mark_needed();
        name_materialised();
        mark_covered();
        if (branchless_)
            prefold_scaled_checks();
        if (branchless_ && share_divisions_)
            group_reciprocals();
        std::set<int> input_checked;
        for (const check &c : checks_)
            if (prog_.at(c.op_id).kind == op::input && input_checked.insert(c.op_id).second)
                emit_checks(c.op_id);
        emit_values();
        emit_outputs();
        if (branchless_)
            prune_implied_finite_terms();
        for (std::size_t i = 0; i < n_; ++i)
            if ((needed_[i] || reach_[i]) && prog_.at(static_cast<int>(i)).kind == op::input)
                out_.inputs_read.insert(prog_.at(static_cast<int>(i)).name);
        return out_;
    }

private:
    // Every op an output or a check needs, with the number of its uses.
    void mark_reachable()
    {
        std::vector<int> stack;
        auto root = [&](int id) {
            ++refs_[static_cast<std::size_t>(id)];
            stack.push_back(id);
        };
        for (auto &o : outputs_)
            root(o.second);
        for (auto &c : checks_)
            root(c.op_id);
        while (!stack.empty()) {
            int id = stack.back();
            stack.pop_back();
            if (reach_[static_cast<std::size_t>(id)])
                continue;
            reach_[static_cast<std::size_t>(id)] = true;
            const op &o = prog_.at(id);
            for (int c : {o.a, o.b})
                if (c >= 0) {
                    ++refs_[static_cast<std::size_t>(c)];
                    stack.push_back(c);
                }
        }
    }

    // Values the outputs need (through any operand). A reachable value that is not
    // needed only serves checks: it is computed as soon as its operands are.
    void mark_needed()
    {
        std::vector<int> stack;
        for (auto &o : outputs_)
            stack.push_back(o.second);
        while (!stack.empty()) {
            int id = stack.back();
            stack.pop_back();
            if (needed_[static_cast<std::size_t>(id)])
                continue;
            needed_[static_cast<std::size_t>(id)] = true;
            const op &o = prog_.at(id);
            for (int c : {o.a, o.b})
                if (c >= 0)
                    stack.push_back(c);
        }
    }

    bool check_only(int id) const
    {
        return reach_[static_cast<std::size_t>(id)] && !needed_[static_cast<std::size_t>(id)];
    }

    // Whether every named value the text of id refers to has been emitted.
    bool operands_emitted(int id) const
    {
        const op &o = prog_.at(id);
        for (int c : {o.a, o.b}) {
            if (c < 0 || prog_.is_leaf(c))
                continue;
            if (materialised_[static_cast<std::size_t>(c)] ? !emitted_[static_cast<std::size_t>(c)]
                                                           : !operands_emitted(c))
                return false;
        }
        return true;
    }

    // A variable for every named step, every value used twice and every checked value.
    void name_materialised()
    {
        std::set<int> checked;
        for (auto &c : checks_)
            checked.insert(c.op_id);
        std::map<std::string, int> part_counter;
        for (std::size_t i = 0; i < n_; ++i) {
            const int id = static_cast<int>(i);
            if (!reach_[i] || prog_.is_leaf(id))
                continue;
            const bool named = names_.count(id) > 0;
            if (!named && refs_[i] < 2 && !checked.count(id))
                continue;
            materialised_[i] = true;
            std::string nm;
            if (named) {
                nm = names_.at(id); // step names come unique from the caller's scope
            } else {
                const op &o = prog_.at(id);
                if (is_reciprocal(prog_, o) && (prog_.at(o.b).kind == op::input || var_.count(o.b)))
                    nm = "inv_" + (prog_.at(o.b).kind == op::input ? prog_.at(o.b).name : var_[o.b]);
                else
                    nm = o.owner + "_p" + std::to_string(++part_counter[o.owner]);
                nm = unique_name(used_names_, nm);
            }
            used_names_.insert(nm);
            var_[id] = nm;
        }
    }

    // Values whose finiteness follows from the finiteness of the outputs: an operand of
    // +, -, *, negation, sqrt, cos, sin, or the numerator of /, is finite when the result is
    // (inf and NaN propagate); a denominator is not (1/inf = 0). An optional output (left 0
    // when not requested) covers nothing.
    void mark_covered()
    {
        std::vector<int> stack;
        for (std::size_t k = 0; k < outputs_.size(); ++k)
            if (static_cast<int>(k) != optional_output_)
                stack.push_back(outputs_[k].second);
        while (!stack.empty()) {
            int id = stack.back();
            stack.pop_back();
            if (covered_[static_cast<std::size_t>(id)])
                continue;
            covered_[static_cast<std::size_t>(id)] = true;
            const op &o = prog_.at(id);
            if (o.a >= 0)
                stack.push_back(o.a);
            if (o.b >= 0 && o.kind != op::div)
                stack.push_back(o.b);
        }
    }

    // Branchless batch: reciprocals of inputs that must be > 0 (masses, inertia) share
    // divisions, up to four per division (1/a = b / (a b)); the products must be normal
    // numbers (else the flag fails and the checked version computes the impact).
    void group_reciprocals()
    {
        std::vector<int> recips;
        for (std::size_t i = 0; i < n_; ++i) {
            const op &o = prog_.at(static_cast<int>(i));
            if (materialised_[i] && is_reciprocal(prog_, o) && prog_.at(o.b).kind == op::input &&
                std::any_of(checks_.begin(), checks_.end(),
                            [&](const check &c) { return c.op_id == o.b && c.kind == check::positive; }))
                recips.push_back(static_cast<int>(i));
        }
        for (std::size_t g = 0; g + 1 < recips.size(); g += 4) {
            std::vector<int> members(recips.begin() + static_cast<long>(g),
                                     recips.begin() + static_cast<long>(std::min(g + 4, recips.size())));
            group_at_[members[0]] = members;
            grouped_.insert(members.begin(), members.end());
            for (int id : members) // the product of the denominators is in the sum
                covered_[static_cast<std::size_t>(prog_.at(id).b)] = true;
        }
    }

    // Branchless: values the flag already proves > 0 (their positivity is among its terms).
    // x >= 0 (or NaN, or +inf) whenever those are > 0: a product whose factors of odd multiplicity
    // are (rounding keeps the sign of a product: r * g * r >= 0 for g >= 0), a sum or a
    // quotient of such, a constant >= 0. Depth-bounded: a value it cannot decide is not.
    bool nonnegative(int id, int depth) const
    {
        if (depth > 32)
            return false;
        if (proves_positive(id, depth + 1))
            return true;
        const op &o = prog_.at(id);
        switch (o.kind) {
        case op::constant:
            return o.value.is_real() && !o.value.is_negative();
        case op::add:
            return nonnegative(o.a, depth + 1) && nonnegative(o.b, depth + 1);
        // a / b for a, b >= 0: >= 0, +inf (b = 0) or NaN (0 / 0); never -0, as no rule
        // here gives -0 (a product's sign is that of its factors, +0 + +0 = +0).
        case op::div:
            return nonnegative(o.a, depth + 1) && nonnegative(o.b, depth + 1);
        case op::mul: {
            std::map<int, int> factors; // product tree flattened: factor -> multiplicity
            std::vector<int> stack{id};
            while (!stack.empty()) {
                const int f = stack.back();
                stack.pop_back();
                if (prog_.at(f).kind == op::mul && factors.size() < 64) {
                    stack.push_back(prog_.at(f).a);
                    stack.push_back(prog_.at(f).b);
                } else {
                    ++factors[f];
                }
            }
            for (const auto &[f, count] : factors)
                if (count % 2 && !nonnegative(f, depth + 1))
                    return false;
            return true;
        }
        default:
            return false;
        }
    }

    // x > 0 (or NaN, or +inf) whenever the flag's positive terms are > 0: one of them, a positive
    // constant, or a sum of such a value and a value >= 0 (the rounded sum of a >= 0 and
    // b > 0 is >= b). Not a product or quotient: they may underflow to 0.
    bool proves_positive(int id, int depth) const
    {
        if (depth > 32)
            return false;
        if (positive_ids_.count(id))
            return true;
        const op &o = prog_.at(id);
        if (o.kind == op::constant)
            return o.value.is_real() && o.value.is_positive();
        if (o.kind == op::add)
            return (proves_positive(o.a, depth + 1) && nonnegative(o.b, depth + 1)) ||
                   (proves_positive(o.b, depth + 1) && nonnegative(o.a, depth + 1));
        return false;
    }

    // (y, c) for a value id = c y of a value y and a positive constant c (a product of
    // two operands, one a constant), (id, 1) for any other; (-1, 0) for a constant.
    std::pair<int, numeric> scaled(int id) const
    {
        const op &o = prog_.at(id);
        if (o.kind == op::constant)
            return {-1, numeric(0)};
        if (o.kind == op::mul) {
            const op &a = prog_.at(o.a);
            const op &b = prog_.at(o.b);
            if (b.kind == op::constant && a.kind != op::constant && b.value.is_real() && b.value.is_positive())
                return {o.a, b.value};
            if (a.kind == op::constant && b.kind != op::constant && a.value.is_real() && a.value.is_positive())
                return {o.b, a.value};
        }
        return {id, numeric(1)};
    }

    // Branchless: value id (text x) must be finite: a term of the one sum.
    void add_finite(int id, const std::string &x, int precedence)
    {
        add_unique(out_.finite_terms, x, precedence);
        finite_id_.emplace(x, id);
    }

    // Branchless: a term of the finiteness sum whose value is an operand of another term's
    // value (through +, -, *, negation, sqrt, a numerator, as mark_covered), however deep, is
    // finite when that one is: it leaves the sum (a minor of an inertia tensor that its
    // determinant is computed from, a diagonal entry of a minor). Each term left out has one
    // above it in the sum, as the values form a DAG.
    void prune_implied_finite_terms()
    {
        std::vector<bool> below(n_, false);
        std::vector<int> stack;
        auto operands = [&](int id) {
            const op &o = prog_.at(id);
            if (o.a >= 0)
                stack.push_back(o.a);
            if (o.b >= 0 && o.kind != op::div)
                stack.push_back(o.b);
        };
        for (const code_term &t : out_.finite_terms)
            if (auto f = finite_id_.find(t.text); f != finite_id_.end())
                operands(f->second);
        while (!stack.empty()) {
            const int id = stack.back();
            stack.pop_back();
            if (below[static_cast<std::size_t>(id)])
                continue;
            below[static_cast<std::size_t>(id)] = true;
            operands(id);
        }
        std::vector<code_term> kept;
        for (const code_term &t : out_.finite_terms) {
            auto f = finite_id_.find(t.text);
            if (f == finite_id_.end() || !below[static_cast<std::size_t>(f->second)])
                kept.push_back(t);
        }
        out_.finite_terms = kept;
    }

    // Branchless: the checks of value id folded into the lists the one flag is made of
    // (signs through a min, finiteness through one sum).
    void fold_check(const check &c, int id, const std::string &x, int p)
    {
        if (c.kind == check::positive && proves_positive(id, 0)) {
            // x > 0 follows from the positive terms before it (k = w_1 + w_2 of
            // reciprocals > 0 and squares): no term of the min; its finiteness as any other.
            if (!covered_[static_cast<std::size_t>(id)])
                add_finite(id, x, p);
            out_.check_comments.push_back(c.comment);
            return;
        }
        if (c.kind == check::positive) {
            positive_ids_.insert(id);
            // x > 0 and finite <=> 1/x > 0 and finite x: when 1/x is computed anyway,
            // test 1/x > 0 (1/inf = 0 fails it; 1/NaN is NaN) and let x go.
            int rid = -1;
            for (std::size_t k = 0; k < n_ && rid < 0; ++k) {
                const op &o = prog_.at(static_cast<int>(k));
                if (materialised_[k] && is_reciprocal(prog_, o) && o.b == id)
                    rid = static_cast<int>(k);
            }
            if (rid >= 0) {
                positive_ids_.insert(rid);
                add_unique(out_.positive_terms, var_.at(rid));
                if (!covered_[static_cast<std::size_t>(rid)])
                    add_finite(rid, var_.at(rid), 4);
                out_.check_comments.push_back(c.comment);
                return;
            }
        }
        switch (c.kind) {
        case check::positive:
            add_unique(out_.positive_terms, x);
            break;
        case check::negative:
            add_unique(out_.positive_terms, "-" + (p < 3 ? "(" + x + ")" : x));
            break;
        case check::unit_interval:
            add_unique(out_.nonneg_terms, x);
            add_unique(out_.nonneg_terms, "T(1) - " + (p < 2 ? "(" + x + ")" : x));
            break;
        case check::normal_number:
            add_unique(out_.normal_terms, x);
            break;
        case check::nonnegative:
            add_unique(out_.nonneg_terms, x);
            break;
        case check::near_one:
            add_unique(out_.nonneg_terms, (p < 2 ? "(" + x + ")" : x) + " - " + unit_bound(-1));
            add_unique(out_.nonneg_terms, unit_bound(+1) + " - " + (p < 2 ? "(" + x + ")" : x));
            break;
        }
        // (unless the finiteness of the outputs implies it)
        if (!covered_[static_cast<std::size_t>(id)])
            add_finite(id, x, p);
        out_.check_comments.push_back(c.comment);
    }

    // Branchless: a check x > 0 of a value only that check uses, x = c_x y, where z = c_z y
    // (constants with 2^-20 <= c_x / c_z <= 1) has its reciprocal computed anyway (a
    // centroidal inertia m l^2/12 beside the pivot's m l^2/3): 1/z > 0 and finite (z
    // finite) imply z >= 1/max, so x ~ (c_x / c_z) z > 0 without underflow (2^-20/max is
    // above the smallest denormal of float, double and long double) and x <= z finite.
    // The flag tests 1/z and x is not computed at all; its comment comes with 1/z.
    void prefold_scaled_checks()
    {
        for (const check &c : checks_) {
            const int x = c.op_id;
            const auto xi = static_cast<std::size_t>(x);
            if (c.kind != check::positive || prog_.at(x).kind == op::input || !check_only(x) || refs_[xi] != 1)
                continue;
            const auto [y, cx] = scaled(x);
            if (y < 0 || y == x)
                continue;
            int rid = -1;
            for (std::size_t k = 0; k < n_; ++k) {
                const op &o = prog_.at(static_cast<int>(k));
                if (!materialised_[k] || !is_reciprocal(prog_, o))
                    continue;
                if (o.b == x) { // 1/x itself: fold_check's own rule
                    rid = -1;
                    break;
                }
                const auto [yz, cz] = scaled(o.b);
                if (rid < 0 && yz == y && cz.is_positive() && cx / cz <= 1 && cx / cz >= numeric(1, 1 << 20))
                    rid = static_cast<int>(k);
            }
            if (rid < 0)
                continue;
            positive_ids_.insert(x);
            positive_ids_.insert(prog_.at(rid).b);
            positive_ids_.insert(rid);
            add_unique(out_.positive_terms, var_.at(rid));
            if (!covered_[static_cast<std::size_t>(rid)])
                add_finite(rid, var_.at(rid), 4);
            prefolded_comments_[rid].push_back(c.comment);
            reach_[xi] = false;
            materialised_[xi] = false;
        }
    }

    void emit_checks(int id)
    {
        auto pre = prefolded_comments_.find(id);
        if (pre != prefolded_comments_.end())
            for (const std::string &comment : pre->second)
                out_.check_comments.push_back(comment);
        for (const check &c : checks_) {
            if (c.op_id != id)
                continue;
            int p;
            std::string x = printer_().text(id, p);
            if (branchless_) {
                fold_check(c, id, x, p);
                continue;
            }
            std::string cond;
            switch (c.kind) {
            case check::positive:
                cond = x + " > T(0) && detail::finite(" + x + ")";
                break;
            case check::unit_interval:
                cond = x + " >= T(0) && " + x + " <= T(1)";
                break;
            case check::nonnegative:
                cond = x + " >= T(0) && detail::finite(" + x + ")";
                break;
            case check::negative:
                cond = x + " < T(0)";
                break;
            case check::normal_number:
                cond = x + " >= detail::smallest_normal<T>() && detail::finite(" + x + ")";
                break;
            case check::near_one:
                cond = x + " >= " + unit_bound(-1) + " && " + x + " <= " + unit_bound(+1);
                break;
            }
            out_.code += "    if (!(" + cond + ")) // " + names::comment_text(c.comment) + "\n";
            out_.code += "        return fail(impact_status::" + c.status + ");\n";
        }
    }

    // 1 - 2^-17 or 1 + 2^-17, the bounds of check::near_one, exact in float.
    static std::string unit_bound(int sign)
    {
        const long d = unit_tolerance_denominator;
        return "(T(" + std::to_string(d + sign) + ") / T(" + std::to_string(d) + "))";
    }

    // `    const T name = text;` with its comment, and name among the declared.
    void declare(const std::string &name, const std::string &text, const std::string &comment = "")
    {
        out_.code += "    const T " + name + " = " + text + ";" + comment + "\n";
        out_.declared.push_back(name);
    }

    std::string fresh(const std::string &base)
    {
        std::string nm = unique_name(used_names_, base);
        used_names_.insert(nm);
        return nm;
    }

    // Pairs (a, b) -> q = a b; then r = 1 / (q_1 q_2), s_1 = q_2 r = 1/q_1, s_2 = q_1 r = 1/q_2.
    void emit_group(const std::vector<int> &members)
    {
        std::string &code = out_.code;
        out_.shares_reciprocals = true;
        auto den = [&](int id) { return prog_.at(prog_.at(id).b).name; };
        std::string list;
        for (int id : members)
            list += (list.empty() ? "" : ", ") + ("1/" + den(id));
        code += "    // one division for " + list + "\n";
        std::vector<std::vector<int>> pairs;
        for (std::size_t j = 0; j < members.size(); j += 2)
            pairs.push_back(std::vector<int>(members.begin() + static_cast<long>(j),
                                             members.begin() + static_cast<long>(std::min(j + 2, members.size()))));
        std::vector<std::string> q;
        for (const auto &pair : pairs) {
            if (pair.size() == 1) {
                q.push_back(den(pair[0]));
                continue;
            }
            std::string nm = fresh("rcp_q" + std::to_string(q.size() + 1));
            declare(nm, den(pair[0]) + " * " + den(pair[1]));
            ++out_.formula.mul;
            out_.normal_terms.push_back(nm);
            q.push_back(nm);
        }
        std::vector<std::string> s;
        if (q.size() == 1) {
            std::string r = fresh("rcp_r");
            declare(r, "T(1) / " + q[0]);
            ++out_.formula.div;
            out_.finite_terms.push_back({q[0], 4});
            s.push_back(r);
        } else {
            std::string pq = fresh("rcp_p"), r = fresh("rcp_r"), s1 = fresh("rcp_s1"), s2 = fresh("rcp_s2");
            declare(pq, q[0] + " * " + q[1]);
            declare(r, "T(1) / " + pq);
            declare(s1, q[1] + " * " + r, " // 1/" + q[0]);
            declare(s2, q[0] + " * " + r, " // 1/" + q[1]);
            out_.formula.mul += 3;
            ++out_.formula.div;
            out_.normal_terms.push_back(pq);
            out_.finite_terms.push_back({pq, 4});
            s = {s1, s2};
        }
        for (std::size_t j = 0; j < pairs.size(); ++j) {
            if (pairs[j].size() == 1) {
                declare(var_[pairs[j][0]], s[j]);
                continue;
            }
            declare(var_[pairs[j][0]], den(pairs[j][1]) + " * " + s[j]);
            declare(var_[pairs[j][1]], den(pairs[j][0]) + " * " + s[j]);
            out_.formula.mul += 2;
        }
        for (int id : members) {
            emitted_[static_cast<std::size_t>(id)] = true;
            emit_checks(id);
        }
    }

    void emit_value(int id)
    {
        int p;
        declare(var_[id], printer_().text(id, p, true));
        if (!branchless_)
            out_.assignments.push_back({var_[id], math_().text(id, p, true)});
        emitted_[static_cast<std::size_t>(id)] = true;
        emit_checks(id);
    }

    // The values only checks use, each as soon as its operands are there (so that a
    // check of the inputs, such as a principal minor of an inertia tensor, comes
    // before the values that would fail on them).
    void emit_ready_check_values()
    {
        for (bool progress = true; progress;) {
            progress = false;
            for (auto it = pending_.begin(); it != pending_.end();) {
                if (operands_emitted(*it)) {
                    const int id = *it;
                    it = pending_.erase(it);
                    emit_value(id);
                    progress = true;
                } else {
                    ++it;
                }
            }
        }
    }

    // The materialised values in program order, each followed by its checks; the
    // values only checks use as soon as they can be computed.
    void emit_values()
    {
        for (std::size_t i = 0; i < n_; ++i)
            if (materialised_[i] && check_only(static_cast<int>(i)) && !grouped_.count(static_cast<int>(i)))
                pending_.push_back(static_cast<int>(i));
        emit_ready_check_values();
        for (std::size_t i = 0; i < n_; ++i) {
            const int id = static_cast<int>(i);
            if (reach_[i] && prog_.at(id).kind == op::sqrt_)
                out_.uses_sqrt = true;
            if (reach_[i] && (prog_.at(id).kind == op::cos_ || prog_.at(id).kind == op::sin_))
                out_.uses_trig = true;
            if (!materialised_[i] || grouped_.count(id) || check_only(id)) {
                if (group_at_.count(id)) {
                    emit_group(group_at_[id]);
                    emit_ready_check_values();
                }
                continue;
            }
            emit_value(id);
            emit_ready_check_values();
        }
        for (std::size_t i = 0; i < n_; ++i)
            if (materialised_[i] && !emitted_[i] && !grouped_.count(static_cast<int>(i)))
                throw std::logic_error("code generation: a checked value was never emitted");
    }

    // The outputs as placed: `out.F = v;`, `const T F = v;` or `F = v;`, the energy
    // output as `with_energy_lost ? v : T(0)`.
    void emit_outputs()
    {
        for (std::size_t k = 0; k < outputs_.size(); ++k) {
            const auto &[field, id] = outputs_[k];
            int p;
            std::string v = printer_().text(id, p);
            if (static_cast<int>(k) == energy_output_)
                v = (parenthesised_in_sum(p) ? "with_energy_lost ? (" + v + ")" : "with_energy_lost ? " + v) +
                    " : T(0)";
            switch (placement_) {
            case output_placement::result:
                out_.code += "    out." + field + " = " + v + ";\n";
                break;
            case output_placement::local:
                declare(field, v);
                break;
            case output_placement::assign:
                out_.code += "    " + field + " = " + v + ";\n";
                break;
            }
            if (!branchless_)
                out_.assignments.push_back(
                    {placement_ == output_placement::result ? "out." + field : field, math_().text(id, p)});
        }
    }

    printer printer_() { return printer{prog_, materialised_, refs_, var_, &out_.formula}; }
    printer math_()
    {
        return printer{prog_, materialised_, refs_, var_, &uncounted_, true};
    } // numbers as in mathematics

    const program &prog_;
    const std::vector<std::pair<std::string, int>> &outputs_;
    const std::vector<check> &checks_;
    const std::map<int, std::string> &names_;
    const output_placement placement_;
    const bool branchless_, share_divisions_;
    const int optional_output_, energy_output_;
    const std::size_t n_;
    std::vector<bool> reach_, materialised_, covered_, needed_, emitted_;
    std::vector<int> refs_;
    std::map<int, std::vector<std::string>> prefolded_comments_; ///< 1/z -> the checks it stands for
    std::set<std::string> used_names_;
    std::map<int, std::string> var_;
    std::map<int, std::vector<int>> group_at_; // first member -> members
    std::set<int> grouped_;
    std::set<int> positive_ids_;           // branchless: values the flag proves > 0 (fold_check)
    std::map<std::string, int> finite_id_; // branchless: a term of the finiteness sum -> its value
    std::vector<int> pending_;             // values only checks use, not yet emitted, in program order
    emitted out_;
    op_counts uncounted_;
};

} // namespace

emitted emit_cpp(const program &prog, const std::vector<std::pair<std::string, int>> &outputs,
                 const std::vector<check> &checks, const std::map<int, std::string> &names,
                 const std::vector<std::string> &taken, const emit_options &options)
{
    return emitter(prog, outputs, checks, names, taken, options).run();
}

} // namespace impactgen::codegen
