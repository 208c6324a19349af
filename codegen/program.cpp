#include "program.hpp"

#include "names/escape.hpp"

#include <algorithm>
#include <iterator>
#include <set>
#include <stdexcept>

namespace impactgen::codegen
{
using GiNaC::numeric;

int program::make(op o)
{
    o.owner = owner_;
    ops_.push_back(std::move(o));
    return static_cast<int>(ops_.size()) - 1;
}

int program::node(op::kind_t k, int a, int b)
{
    auto key = std::make_tuple(int(k), a, b);
    auto it = memo_.find(key);
    if (it != memo_.end())
        return it->second;
    op o;
    o.kind = k;
    o.a = a;
    o.b = b;
    int id = make(o);
    memo_[key] = id;
    return id;
}

int program::leaf(std::map<std::string, int> &index, const std::string &key, const op &o)
{
    auto it = index.find(key);
    if (it != index.end())
        return it->second;
    int id = make(o);
    index[key] = id;
    return id;
}

int program::input(const std::string &name)
{
    op o;
    o.kind = op::input;
    o.name = name;
    return leaf(inputs_, name, o);
}

int program::constant(const numeric &x)
{
    op o;
    o.kind = op::constant;
    o.value = x;
    return leaf(constants_, number_text(x), o);
}

int program::negate(int a)
{
    const op &x = at(a);
    if (x.kind == op::constant)
        return constant(-x.value);
    if (x.kind == op::neg)
        return x.a;
    return node(op::neg, a);
}

int program::square_root(int a)
{
    if (at(a).kind == op::constant && at(a).value.is_zero())
        return a;
    return node(op::sqrt_, a);
}

int program::trig(op::kind_t k, int a)
{
    return node(k, a);
}

int program::binary(op::kind_t k, int a, int b)
{
    const op &x = at(a);
    const op &y = at(b);
    const bool cx = x.kind == op::constant, cy = y.kind == op::constant;
    if (cx && cy) {
        switch (k) {
        case op::add:
            return constant(x.value + y.value);
        case op::sub:
            return constant(x.value - y.value);
        case op::mul:
            return constant(x.value * y.value);
        case op::div:
            if (y.value.is_zero())
                throw std::runtime_error("code generation: division by zero");
            return constant(x.value / y.value);
        default:
            break;
        }
    }
    if (k == op::add && cx && x.value.is_zero())
        return b;
    if ((k == op::add || k == op::sub) && cy && y.value.is_zero())
        return a;
    if (k == op::mul) {
        if ((cx && x.value.is_zero()) || (cy && y.value.is_zero()))
            return constant(0);
        if (cx && x.value == 1)
            return b;
        if (cy && y.value == 1)
            return a;
        if (cy && y.value == -1)
            return negate(a);
    }
    if (k == op::div && cy && y.value == 1)
        return a;
    if (k == op::add || k == op::mul)
        if (a > b)
            std::swap(a, b);
    return node(k, a, b);
}

int program::lower(const canonical_pool &pool, const scaled &s)
{
    if (s.node < 0)
        return constant(s.scale);
    numeric a = abs(s.scale);
    if (s.scale < 0 && a == 1 && pool.at(s.node).kind == cnode::add)
        return lower_add(pool, s.node, true); // -(x - y) as y - x
    int v = lower(pool, s.node);
    if (a != 1)
        v = binary(op::mul, v, constant(a));
    return s.scale < 0 ? negate(v) : v;
}

// A sum, starting from its first positive term so that it needs no negation
// unless every term is negative.
int program::lower_add(const canonical_pool &pool, int cid, bool negated)
{
    auto memo = lowered_neg_.find(cid);
    if (negated && memo != lowered_neg_.end())
        return memo->second;
    const cnode &n = pool.at(cid);
    std::vector<std::pair<numeric, int>> terms;
    for (auto &[c, t] : n.terms)
        terms.push_back({negated ? -c : c, t});
    numeric konst = negated ? -n.value : n.value;
    std::stable_partition(terms.begin(), terms.end(), [](const auto &t) { return t.first > 0; });
    int r = -1;
    bool all_negative = terms.front().first < 0;
    for (auto &[c, t] : terms) {
        int v = lower(pool, t);
        numeric a = abs(c);
        if (a != 1)
            v = binary(op::mul, v, constant(a));
        if (r < 0)
            r = v;
        else
            r = binary(all_negative || c > 0 ? op::add : op::sub, r, v);
    }
    if (all_negative) {
        if (!konst.is_zero())
            r = binary(op::sub, constant(konst), r);
        else
            r = negate(r);
    } else if (!konst.is_zero()) {
        r = binary(konst < 0 ? op::sub : op::add, r, constant(abs(konst)));
    }
    if (negated)
        lowered_neg_[cid] = r;
    return r;
}

int program::lower(const canonical_pool &pool, int cid)
{
    auto memo = lowered_.find(cid);
    if (memo != lowered_.end())
        return memo->second;
    const cnode &n = pool.at(cid);
    int r = -1;
    switch (n.kind) {
    case cnode::constant:
        r = constant(n.value);
        break;
    case cnode::input:
        r = input(n.name);
        break;
    case cnode::step: {
        auto it = step_op_.find(n.step_index);
        if (it == step_op_.end())
            throw std::logic_error("code generation: step " + n.name + " used before it is defined");
        r = it->second;
        break;
    }
    case cnode::sqrt_:
        r = square_root(lower(pool, n.arg));
        break;
    case cnode::cos_:
    case cnode::sin_:
        r = trig(n.kind == cnode::cos_ ? op::cos_ : op::sin_, lower(pool, n.arg));
        break;
    case cnode::add:
        r = lower_add(pool, cid, false);
        break;
    case cnode::mul: {
        int num = -1, den = -1;
        numeric a = abs(n.value);
        std::vector<std::pair<int, int>> factors = n.factors;
        std::sort(factors.begin(), factors.end());
        // A product lowered before with the same coefficient whose factors (exponents
        // included) are among these, the largest: this one is that times the rest
        // (m v'_x - N beside v'_x = (1/2) l^2 N / I_E: one multiplication, not three).
        const lowered_product *base = nullptr;
        for (const lowered_product &lp : products_)
            if (lp.coefficient == a && lp.factors.size() < factors.size() &&
                (!base || lp.factors.size() > base->factors.size()) &&
                std::includes(factors.begin(), factors.end(), lp.factors.begin(), lp.factors.end()))
                base = &lp;
        if (base) {
            std::vector<std::pair<int, int>> rest;
            std::set_difference(factors.begin(), factors.end(), base->factors.begin(), base->factors.end(),
                                std::back_inserter(rest));
            num = base->op_id;
            for (auto &[f, x] : rest) {
                int v = lower(pool, f);
                int &acc = x > 0 ? num : den;
                for (int k = 0; k < (x > 0 ? x : -x); ++k)
                    acc = acc < 0 ? v : binary(op::mul, acc, v);
            }
            r = den >= 0 ? binary(op::mul, num, reciprocal(den)) : num;
            products_.push_back({factors, a, r});
            if (n.value < 0)
                r = negate(r);
            break;
        }
        for (auto &[f, x] : n.factors) {
            int v = lower(pool, f);
            int &acc = x > 0 ? num : den;
            for (int k = 0; k < (x > 0 ? x : -x); ++k)
                acc = acc < 0 ? v : binary(op::mul, acc, v);
        }
        if (a.numer() != 1)
            num = num < 0 ? constant(a.numer()) : binary(op::mul, num, constant(a.numer()));
        if (a.denom() != 1) {
            // a rational coefficient p/q folds into one constant factor
            if (num < 0)
                num = constant(1 / numeric(a.denom()));
            else
                num = binary(op::mul, num, constant(1 / numeric(a.denom())));
        }
        if (den >= 0)
            r = num < 0 ? reciprocal(den) : binary(op::mul, num, reciprocal(den));
        else
            r = num < 0 ? constant(1) : num;
        // worth reusing when it took a multiplication (or a division) of its own
        int multiplicity = a == 1 ? 0 : 1;
        for (auto &[f, x] : factors)
            multiplicity += x > 0 ? x : -x;
        if (multiplicity >= 2 && at(r).kind != op::constant)
            products_.push_back({factors, a, r});
        if (n.value < 0)
            r = negate(r);
        break;
    }
    }
    lowered_[cid] = r;
    return r;
}

} // namespace impactgen::codegen
