// The canonical tree of expr/ (expr/tree.hpp, the one every printer reads) lowered
// to what C++ code needs: symbols become the C++ names of the inputs or the steps
// already computed, constants that are not rational (Pi, sqrt(2)/2 + 1) their
// values to 40 digits, half-integer powers square roots; what C++ arithmetic cannot
// express (a function of symbols, a complex number) is refused here.
//
// The lowered nodes are value-numbered under a key made of the C++ names (two
// symbols the printers write alike are two inputs here), and the operands of + and
// * are ordered by that key, a sum signed so that its first coefficient is
// positive (x - y and y - x share one node): the straight-line program and the
// emitted code depend on the C++ names, not on how a symbol prints.
#pragma once

#include "expr/tree.hpp"

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
    /// A node of the canonical tree.
    scaled convert(expr::tree &t, int id);
    /// A symbol: a bound step or a named input.
    scaled convert_symbol(const GiNaC::ex &e);
    /// A sum: its terms' nodes with exact coefficients.
    scaled convert_sum(expr::tree &t, int id);
    /// A product: its factors' nodes with integer exponents.
    scaled convert_product(expr::tree &t, int id);
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
inline std::string number_text(const GiNaC::numeric &x)
{
    return expr::number_text(x);
}

} // namespace impactgen::codegen
