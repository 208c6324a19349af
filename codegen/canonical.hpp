// Canonical n-ary expression trees built from GiNaC expressions, independent
// of GiNaC's term order (which moves from run to run with address-space
// randomisation, see shared/measured-facts.md).
//
// Every node is hash-consed under a key computed from its children's keys;
// the operands of + and * are sorted by that key and a sum is normalised so
// that its first term has a positive coefficient (x - y and y - x share one
// node). Equal subexpressions therefore become one node whatever order GiNaC
// happened to print them in, and everything downstream (the straight-line
// program, the printed formulas) is byte-for-byte reproducible.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace impactgen::codegen
{

struct cnode {
    enum kind_t { constant, input, step, add, mul, sqrt_, cos_, sin_ } kind = constant;
    GiNaC::numeric value;                              ///< constant; add: constant term; mul: coefficient
    std::string name;                                  ///< input or step
    int step_index = -1;                               ///< step
    std::vector<std::pair<GiNaC::numeric, int>> terms; ///< add: coefficient * node
    std::vector<std::pair<int, int>> factors;          ///< mul: node ^ integer exponent
    int arg = -1;                                      ///< sqrt, cos, sin
    std::string key;                                   ///< canonical text, the sort and hash-consing key
};

/// scale * node; node == -1 means the constant `scale` alone.
struct scaled {
    GiNaC::numeric scale;
    int node = -1;
};

class canonical_pool
{
public:
    /// The C++ name of each input symbol (by GiNaC name); a symbol not listed is an error.
    void set_input_names(std::map<GiNaC::ex, std::string, GiNaC::ex_is_less> names) { input_names_ = std::move(names); }
    /// Occurrences of `sym` in later expressions refer to step `index`.
    void bind_step(const GiNaC::symbol &sym, int index, const std::string &name);
    /// Throws std::runtime_error for what C++ cannot express (functions other than cos and sin,
    /// complex numbers, powers other than integer and half-integer).
    scaled convert(const GiNaC::ex &e);
    /// scale * node as one node.
    int node_of(const scaled &s);

    const cnode &at(int id) const { return nodes_[static_cast<std::size_t>(id)]; }
    std::size_t size() const { return nodes_.size(); }

private:
    /// A symbol: a bound step or a named input.
    scaled convert_symbol(const GiNaC::ex &e);
    /// A sum: its terms' nodes with exact coefficients.
    scaled convert_sum(const GiNaC::ex &e);
    /// A product or power: its factors' nodes with integer exponents.
    scaled convert_product(const GiNaC::ex &e);
    /// cos or sin of an expression (a rod's angle): one node, evaluated by std::cos / std::sin.
    scaled convert_trig(const GiNaC::ex &e);
    int intern(cnode n);
    std::vector<cnode> nodes_;
    std::map<std::string, int> by_key_;
    std::map<std::string, std::pair<int, std::string>> steps_; ///< step symbol name -> index, name
    std::map<GiNaC::ex, int, GiNaC::ex_is_less> step_syms_;
    std::map<GiNaC::ex, std::string, GiNaC::ex_is_less> input_names_;
};

/// Text of an exact number, e.g. "4/5", "-3".
std::string number_text(const GiNaC::numeric &x);

} // namespace impactgen::codegen
