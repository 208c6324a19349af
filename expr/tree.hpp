// The one canonical form of an expression, read by every printer (print/canonical:
// text, LaTeX, parser, MathML) and by code generation (codegen/canonical lowers it
// to C++ names and value numbers).
//
// GiNaC orders the operands of sums and products by hash, and hashes depend on
// addresses: the same expression prints in different orders from run to run. The
// tree is built once from a GiNaC expression and fixes, node by node:
//   kind       number, symbol, constant (Pi), function, sum, product, other;
//   order      the terms of a sum and the factors of a product sorted by their own
//              text form (expr::print in syntax::text, the order key);
//   sign       a sum raised to an integer power is kept with its canonical sign
//              (more positive terms than negative; on a tie the number, then the
//              longest term, positive) and the sign moved to the coefficient, so
//              (a - b)/(c - d) and (b - a)/(d - c) are one form;
//   sharing    every GiNaC expression is one node (hash-consed by structure), so a
//              subexpression's form and text are computed once.
// A product is read as number * numerator / denominator, every exponent positive.
// The tree never throws: what no printer can print (a matrix, a complex number) is
// refused by the printer that meets it, and code generation refuses what C++
// arithmetic cannot express.
#pragma once

#include <ginac/ginac.h>

#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace impactgen::expr
{

enum class kind { number, symbol, constant, function, sum, product, other };

/// base^exponent, exponent > 0: a factor of a numerator or a denominator.
struct factor {
    int base = -1;
    GiNaC::ex exponent;     ///< positive
    int exponent_node = -1; ///< the node of exponent
    std::string key;        ///< its text form: the order of the factors
};

/// A term of a sum: coefficient * rest.
struct term {
    GiNaC::numeric coefficient; ///< with its sign
    int rest = -1;              ///< the term without its number (the node of 1 for a number)
    int body = -1;              ///< rest * |coefficient|, read as a product: the term without its sign
    bool negative = false;      ///< the sign the term is written with
    std::string key;            ///< the text form of rest without a sign: the order of the terms
};

/// A node read as a product: coefficient * numerator / denominator.
struct product_form {
    GiNaC::numeric coefficient = 1; ///< with the signs moved out of the sums
    std::vector<factor> numerator, denominator;
};

// Binding strength of a printed form: a sum binds loosest.
enum prec { p_sum = 0, p_product = 1, p_power = 2, p_atom = 3 };

struct printed {
    std::string s;
    prec level = p_atom;
    bool negative = false; ///< starts with a minus sign
};

struct node {
    kind k = kind::other;
    GiNaC::ex value;                     ///< the expression the node stands for
    std::vector<int> args;               ///< function: its arguments
    std::vector<term> terms;             ///< sum: in the order written (positive terms first, each group in order)
    int sign = 1;                        ///< sum: -1 when its canonical form is its negative
    std::optional<product_form> product; ///< read as a product, once asked
    std::optional<printed> text, product_text; ///< the text forms, once asked
};

class tree
{
public:
    /// The node of e, built with its operands when new.
    int of(const GiNaC::ex &e);
    const node &at(int id) const { return nodes_[static_cast<std::size_t>(id)]; }
    std::size_t size() const { return nodes_.size(); }
    /// The node read as a product (a product node's own form; a symbol is a product of one).
    const product_form &product(int id);
    /// The order key: the node's text form (a printer's error becomes GiNaC's text,
    /// for the printer to report when it prints the node).
    printed key(int id, bool as_product);
    /// Keeps a node's text form (the printer's, in syntax::text).
    void remember(int id, bool as_product, const printed &p);

private:
    int build(const GiNaC::ex &e);
    void build_sum(int id);
    product_form make_product(const GiNaC::ex &e);
    std::string factor_key(const factor &f);
    node &at_mutable(int id) { return nodes_[static_cast<std::size_t>(id)]; }
    std::deque<node> nodes_;
    std::map<GiNaC::ex, int, GiNaC::ex_is_less> by_value_;
};

/// The tree every printer and code generation share in this process, held for the length of a
/// scope: node ids stay valid while any scope holds it (scopes nest: a conversion may print or
/// convert again), and it forgets its nodes when it has grown past a bound and the first scope
/// opens.
class shared_tree
{
public:
    shared_tree();
    ~shared_tree();
    shared_tree(const shared_tree &) = delete;
    shared_tree &operator=(const shared_tree &) = delete;
    tree &get() const;
};

/// Text of an exact number, e.g. "4/5", "-3".
std::string number_text(const GiNaC::numeric &x);

} // namespace impactgen::expr
