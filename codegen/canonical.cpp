#include "canonical.hpp"

#include "symbolic/decide.hpp"

#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>

namespace impactgen::codegen
{
using namespace GiNaC;

void canonical_pool::bind_step(const symbol &sym, int index, const std::string &name)
{
    cnode n;
    n.kind = cnode::step;
    n.step_index = index;
    n.name = name;
    n.key = "$" + name;
    step_syms_[sym] = intern(std::move(n));
}

int canonical_pool::intern(cnode n)
{
    auto it = by_key_.find(n.key);
    if (it != by_key_.end())
        return it->second;
    int id = static_cast<int>(nodes_.size());
    by_key_.emplace(n.key, id);
    nodes_.push_back(std::move(n));
    return id;
}

int canonical_pool::node_of(const scaled &s)
{
    if (s.node < 0) {
        cnode n;
        n.kind = cnode::constant;
        n.value = s.scale;
        n.key = "#" + number_text(s.scale);
        return intern(std::move(n));
    }
    if (s.scale == 1)
        return s.node;
    cnode m;
    m.kind = cnode::mul;
    m.value = s.scale;
    const cnode &inner = at(s.node);
    if (inner.kind == cnode::mul) {
        m.value *= inner.value;
        m.factors = inner.factors;
    } else
        m.factors = {{s.node, 1}};
    m.key = "[" + number_text(m.value) + ":";
    for (auto &f : m.factors)
        m.key += at(f.first).key + "^" + std::to_string(f.second) + ";";
    m.key += "]";
    return intern(std::move(m));
}

namespace
{

// The value of a constant to 40 digits (Digits restored even when evalf throws).
ex value_to_40_digits(const ex &e)
{
    const long saved = Digits;
    Digits = 40;
    ex v;
    try {
        v = e.evalf();
    } catch (...) {
        Digits = saved;
        throw;
    }
    Digits = saved;
    return v;
}

// The error for an expression C++ arithmetic cannot express, naming its functions.
[[noreturn]] void cannot_express(const ex &e)
{
    // A function of symbols: name the functions, in a stable order (GiNaC's own
    // printing of e changes with its term order from run to run).
    std::set<std::string> functions;
    for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<function>(*it))
            functions.insert(ex_to<function>(*it).get_name());
    std::string list;
    for (const std::string &f : functions)
        list += (list.empty() ? "" : ", ") + f;
    throw std::runtime_error("code generation: cannot express " +
                             (list.empty() ? std::string("this expression") : list) +
                             " of symbols in C++ arithmetic (only +, -, *, /, integer powers, sqrt, cos and sin)");
}

} // namespace

// A symbol: a bound step or a named input.
scaled canonical_pool::convert_symbol(const ex &e)
{
    auto it = step_syms_.find(e);
    if (it != step_syms_.end())
        return {1, it->second};
    cnode n;
    n.kind = cnode::input;
    auto known = input_names_.find(e);
    if (known == input_names_.end())
        throw std::logic_error("code generation: symbol " + ex_to<symbol>(e).get_name() + " is not an input");
    n.name = known->second;
    n.key = n.name;
    return {1, intern(std::move(n))};
}

// A sum: its terms' nodes with exact coefficients, signed so the first coefficient is positive.
scaled canonical_pool::convert_sum(expr::tree &t, int id)
{
    std::map<int, numeric> coeff;
    numeric constant = 0;
    for (const expr::term &tm : t.at(id).terms) {
        // A term with a constant that is not a number is valued whole (2*Pi, not 2 times Pi's value).
        const ex &rest = t.at(tm.rest).value;
        scaled s;
        if (!is_a<numeric>(rest) && is_constant(rest)) {
            s = convert(t, t.of(tm.coefficient * rest));
        } else {
            s = convert(t, tm.rest);
            s.scale *= tm.coefficient;
        }
        if (s.node < 0) {
            constant += s.scale;
            continue;
        }
        const cnode &tn = at(s.node);
        if (tn.kind == cnode::add) {
            for (auto &[c, term_id] : tn.terms)
                coeff[term_id] += s.scale * c;
            constant += s.scale * tn.value;
        } else {
            coeff[s.node] += s.scale;
        }
    }
    std::vector<std::pair<numeric, int>> terms;
    for (auto &[node_id, c] : coeff)
        if (!c.is_zero())
            terms.push_back({c, node_id});
    if (terms.empty())
        return {constant, -1};
    if (terms.size() == 1 && constant.is_zero())
        return {terms[0].first, terms[0].second};
    std::sort(terms.begin(), terms.end(),
              [&](const auto &a, const auto &b) { return at(a.second).key < at(b.second).key; });
    numeric sign = terms[0].first < 0 ? -1 : 1;
    cnode n;
    n.kind = cnode::add;
    n.value = sign * constant;
    for (auto &term : terms)
        n.terms.push_back({sign * term.first, term.second});
    n.key = "(";
    for (auto &[c, node_id] : n.terms)
        n.key += number_text(c) + "*" + at(node_id).key + ";";
    n.key += "|" + number_text(n.value) + ")";
    return {sign, intern(std::move(n))};
}

// A product: its factors' nodes with integer exponents (half-integer ones through sqrt).
scaled canonical_pool::convert_product(expr::tree &t, int id)
{
    const expr::product_form &pf = t.product(id);
    numeric coeff = pf.coefficient;
    std::map<int, int> expo;
    auto take = [&](const scaled &f, int k) {
        if (f.scale.is_zero() && k < 0)
            throw std::runtime_error("code generation: division by zero");
        coeff *= pow(f.scale, numeric(k)); // exact for integer k
        if (f.node < 0)
            return;
        const cnode &fn = at(f.node);
        if (fn.kind == cnode::mul) {
            coeff *= pow(fn.value, numeric(k));
            for (auto &[node_id, x] : fn.factors)
                expo[node_id] += x * k;
        } else {
            expo[f.node] += k;
        }
    };
    auto factor = [&](const expr::factor &f, int sign) {
        if (!is_a<numeric>(f.exponent) || !ex_to<numeric>(f.exponent).is_rational())
            throw std::runtime_error("code generation: power with a non-rational exponent");
        const numeric q = ex_to<numeric>(f.exponent);
        if (q.is_integer()) {
            take(convert(t, f.base), sign * q.to_int());
            return;
        }
        if (q.denom() != 2)
            throw std::runtime_error("code generation: only integer and half-integer powers are supported");
        // b^(p/2) = sqrt(b)^p
        cnode s;
        s.kind = cnode::sqrt_;
        s.arg = node_of(convert(t, f.base));
        s.key = "sqrt(" + at(s.arg).key + ")";
        take({1, intern(std::move(s))}, sign * q.numer().to_int());
    };
    for (const expr::factor &f : pf.numerator)
        factor(f, 1);
    for (const expr::factor &f : pf.denominator)
        factor(f, -1);
    std::vector<std::pair<int, int>> factors;
    for (auto &[node_id, x] : expo)
        if (x != 0)
            factors.push_back({node_id, x});
    if (factors.empty() || coeff.is_zero())
        return {coeff, -1};
    if (factors.size() == 1 && factors[0].second == 1)
        return {coeff, factors[0].first};
    std::sort(factors.begin(), factors.end(),
              [&](const auto &a, const auto &b) { return at(a.first).key < at(b.first).key; });
    cnode n;
    n.kind = cnode::mul;
    n.value = 1;
    n.factors = std::move(factors);
    n.key = "[1:";
    for (auto &f : n.factors)
        n.key += at(f.first).key + "^" + std::to_string(f.second) + ";";
    n.key += "]";
    return {coeff, intern(std::move(n))};
}

scaled canonical_pool::convert_trig(const ex &e)
{
    const std::string f = ex_to<function>(e).get_name();
    if ((f != "cos" && f != "sin") || e.nops() != 1)
        cannot_express(e);
    cnode n;
    n.kind = f == "cos" ? cnode::cos_ : cnode::sin_;
    n.arg = node_of(convert(e.op(0)));
    n.key = f + "(" + at(n.arg).key + ")";
    return {1, intern(std::move(n))};
}

scaled canonical_pool::convert(const ex &e)
{
    const expr::shared_tree shared;
    expr::tree &t = shared.get();
    return convert(t, t.of(e));
}

scaled canonical_pool::convert(expr::tree &t, int id)
{
    const expr::node &n = t.at(id);
    // A constant that is not a rational (Pi, sqrt(2)/2 + 1, cos(1)) becomes its value
    // to 40 digits: a literal good for long double, exact to every digit of double.
    if (n.k != expr::kind::number && is_constant(n.value)) {
        ex v = value_to_40_digits(n.value);
        if (is_a<numeric>(v) && ex_to<numeric>(v).is_real())
            return {ex_to<numeric>(v), -1};
    }
    switch (n.k) {
    case expr::kind::number: {
        const numeric &x = ex_to<numeric>(n.value);
        if (!x.is_real())
            throw std::runtime_error("code generation: complex number " + number_text(x));
        return {x, -1};
    }
    case expr::kind::symbol:
        return convert_symbol(n.value);
    case expr::kind::sum:
        return convert_sum(t, id);
    case expr::kind::product:
        return convert_product(t, id);
    case expr::kind::function:
        return convert_trig(n.value);
    default:
        cannot_express(n.value);
    }
}

} // namespace impactgen::codegen
