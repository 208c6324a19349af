#include "tree.hpp"

#include "print.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace impactgen::expr
{
using namespace GiNaC;

std::string number_text(const numeric &x)
{
    std::ostringstream os;
    os << x;
    return os.str();
}

int tree::of(const ex &e)
{
    auto it = by_value_.find(e);
    return it != by_value_.end() ? it->second : build(e);
}

int tree::build(const ex &e)
{
    const int id = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    by_value_.emplace(e, id);
    node &n = nodes_.back(); // a deque keeps references through later nodes
    n.value = e;
    if (is_a<numeric>(e)) {
        n.k = kind::number;
    } else if (is_a<symbol>(e)) {
        n.k = kind::symbol;
    } else if (is_a<constant>(e)) {
        n.k = kind::constant;
    } else if (is_a<add>(e)) {
        n.k = kind::sum;
        build_sum(id);
    } else if (is_a<mul>(e) || is_a<power>(e)) {
        n.k = kind::product;
    } else if (is_a<function>(e)) {
        n.k = kind::function;
        for (std::size_t i = 0; i < e.nops(); ++i) {
            const int arg = of(e.op(i));
            n.args.push_back(arg);
        }
    }
    return id;
}

namespace
{

// The sign that makes a sum canonical, from its terms in order: more positive than
// negative terms; on a tie, the number (1 - e²), else the term of the longest text
// (then the first in order) positive: m (v′ - v), e - 1.
int sum_sign(const tree &t, const std::vector<term> &terms)
{
    int balance = 0;
    const term *lead = nullptr;
    for (const term &tm : terms) {
        balance += tm.negative ? -1 : 1;
        if (!lead || tm.key.size() > lead->key.size())
            lead = &tm;
    }
    if (balance != 0)
        return balance > 0 ? 1 : -1;
    if (!terms.empty() && t.at(terms.front().rest).value.is_equal(1))
        return terms.front().negative ? -1 : 1;
    return !lead || !lead->negative ? 1 : -1;
}

} // namespace

void tree::build_sum(int id)
{
    const ex e = at(id).value;
    std::vector<term> terms;
    for (std::size_t i = 0; i < e.nops(); ++i) {
        const ex &t = e.op(i);
        term tm;
        tm.coefficient = 1;
        ex rest = 1;
        if (is_a<numeric>(t)) {
            tm.coefficient = ex_to<numeric>(t);
        } else if (is_a<mul>(t)) {
            for (std::size_t k = 0; k < t.nops(); ++k)
                if (is_a<numeric>(t.op(k)))
                    tm.coefficient *= ex_to<numeric>(t.op(k));
                else
                    rest *= t.op(k);
        } else {
            rest = t;
        }
        tm.rest = of(rest);
        // rest may be written with a sign of its own (a canonical inner sum).
        const printed r = key(tm.rest, true);
        const bool rest_negative = r.negative && !r.s.empty() && r.s[0] == '-';
        tm.key = rest_negative ? r.s.substr(1) : r.s;
        tm.negative = tm.coefficient.is_negative() != rest_negative;
        terms.push_back(tm);
    }
    // Numbers first ("1 + e"), otherwise by text; equal texts by coefficient.
    std::sort(terms.begin(), terms.end(), [this](const term &a, const term &b) {
        const bool an = at(a.rest).value.is_equal(1), bn = at(b.rest).value.is_equal(1);
        if (an != bn)
            return an;
        if (a.key != b.key)
            return a.key < b.key;
        if (a.negative != b.negative)
            return b.negative;
        return abs(a.coefficient) < abs(b.coefficient);
    });
    const int sign = sum_sign(*this, terms);
    // Written with the positive terms first, each group in order.
    std::stable_partition(terms.begin(), terms.end(), [](const term &tm) { return !tm.negative; });
    for (term &tm : terms)
        tm.body = of(at(tm.rest).value * abs(tm.coefficient));
    node &n = at_mutable(id);
    n.terms = std::move(terms);
    n.sign = sign;
}

product_form tree::make_product(const ex &e)
{
    product_form pf;
    auto add_factor = [&](ex base, ex exponent) {
        const bool negative_exp = is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_negative();
        if (negative_exp)
            exponent = -exponent;
        if (is_a<add>(base) && is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_integer() &&
            at(of(base)).sign < 0) {
            base = -base;
            if (ex_to<numeric>(exponent).is_odd())
                pf.coefficient = -pf.coefficient;
        }
        factor f;
        f.base = of(base);
        f.exponent = exponent;
        f.exponent_node = of(exponent);
        f.key = factor_key(f);
        (negative_exp ? pf.denominator : pf.numerator).push_back(f);
    };
    auto visit = [&](const ex &f) {
        if (is_a<numeric>(f))
            pf.coefficient *= ex_to<numeric>(f);
        else if (is_a<power>(f))
            add_factor(f.op(0), f.op(1));
        else
            add_factor(f, 1);
    };
    if (is_a<mul>(e))
        for (std::size_t i = 0; i < e.nops(); ++i)
            visit(e.op(i));
    else
        visit(e);
    auto by_key = [](const factor &a, const factor &b) { return a.key < b.key; };
    std::sort(pf.numerator.begin(), pf.numerator.end(), by_key);
    std::sort(pf.denominator.begin(), pf.denominator.end(), by_key);
    return pf;
}

const product_form &tree::product(int id)
{
    if (!at(id).product) {
        product_form pf = make_product(at(id).value);
        at_mutable(id).product = std::move(pf);
    }
    return *at(id).product;
}

void tree::remember(int id, bool as_product, const printed &p)
{
    (as_product ? at_mutable(id).product_text : at_mutable(id).text) = p;
}

printed tree::key(int id, bool as_product)
{
    try {
        return as_product ? print_product(*this, id, syntax::text) : print(*this, id, syntax::text);
    } catch (const std::invalid_argument &) {
        std::ostringstream os; // not printable: the printer reports it when asked
        os << at(id).value;
        return {os.str(), p_atom, false};
    }
}

std::string tree::factor_key(const factor &f)
{
    if (f.exponent.is_equal(1))
        return key(f.base, false).s;
    try {
        return print_factor(*this, f, syntax::text).s;
    } catch (const std::invalid_argument &) {
        return key(f.base, false).s + "^" + key(f.exponent_node, false).s;
    }
}

namespace
{
tree &the_shared_tree()
{
    static tree t;
    return t;
}
int shared_scopes = 0;
} // namespace

shared_tree::shared_tree()
{
    if (shared_scopes++ == 0 && the_shared_tree().size() > 100000)
        the_shared_tree() = tree{};
}

shared_tree::~shared_tree()
{
    --shared_scopes;
}

tree &shared_tree::get() const
{
    return the_shared_tree();
}

} // namespace impactgen::expr
