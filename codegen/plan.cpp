// The plan of a generated solver: the problem specialised by the caller's
// options, its closed form rewritten for the engine input conventions, the
// function's inputs in order and its outputs. No C++ text is made here.
#include "codegen.hpp"
#include "text.hpp"

#include "names/escape.hpp"
#include "names/identifier.hpp"
#include "symbolic/contact_law.hpp"
#include "symbolic/decide.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>
#include <tuple>

namespace impactgen::codegen
{
using namespace GiNaC;

namespace
{

// Quantity suffix of a body: "1" -> "1", "ball" -> "_ball".
std::string suffix(const std::string &label)
{
    return label.size() == 1 ? label : "_" + names::mangle(label);
}

struct quantity {
    std::string name;
    ex *value;
    std::string meaning;
};

// A system's own quantities (after its bodies): per contact k its restitution e_ck (when
// its own), friction mu_ck (when Coulomb's), point O_x_ck and normal n_x_ck; per joint j
// its point J_x_jj; per pivot its point, as for one contact.
void system_quantities(problem &p, std::vector<quantity> &q)
{
    const int dim = p.dimension;
    const auto &ax = p.axes;
    for (std::size_t k = 0; k < p.contacts.size(); ++k) {
        contact_spec &c = p.contacts[k];
        const std::string s = "_c" + std::to_string(k), who = "contacts[" + std::to_string(k) + "]";
        if (c.own_restitution)
            q.push_back({"e" + s, &c.restitution, "coefficient of restitution of " + who + ", 0 <= e <= 1"});
        if (auto *law = std::get_if<coulomb>(&c.law))
            q.push_back({"mu" + s, &law->mu, "coefficient of friction of " + who + " (>= 0)"});
        for (int a = 0; a < dim; ++a)
            q.push_back({"O_" + ax[a] + s, &c.point[a], "point of " + who + ", " + ax[a]});
        for (int a = 0; a < dim; ++a)
            q.push_back({"n_" + ax[a] + s, &c.normal[a],
                         "normal of " + who + " (from its first body into its second, any length), " + ax[a]});
    }
    for (std::size_t j = 0; j < p.joints.size(); ++j)
        for (int a = 0; a < dim; ++a)
            q.push_back({"J_" + ax[a] + "_j" + std::to_string(j), &p.joints[j].point[a],
                         "point of joints[" + std::to_string(j) + "], " + ax[a]});
    for (pivot &pv : p.pivots)
        for (int a = 0; a < dim; ++a)
            q.push_back({"E_" + ax[a] + suffix(p.bodies[pv.body].label), &pv.point[a],
                         "pivot of " + p.bodies[pv.body].name + ", " + ax[a]});
}

// Every liftable quantity of the problem, in problem order; inertia entries
// (r <= c) stand for both symmetric entries.
std::vector<quantity> quantities(problem &p)
{
    std::vector<quantity> q;
    const int dim = p.dimension;
    const auto &ax = p.axes;
    q.push_back({"e", &p.restitution, "coefficient of restitution, 0 <= e <= 1"});
    for (body &b : p.bodies) {
        const std::string s = suffix(b.label), sub = s;
        if (!b.infinite_mass)
            q.push_back({"m" + s, &b.mass, "mass of " + b.name + " (> 0)"});
        if (!b.particle && !b.infinite_mass) {
            if (dim == 2)
                q.push_back(
                    {"I" + s, &b.inertia[2][2], "moment of inertia of " + b.name + " about its centre of mass (> 0)"});
            else
                for (int r = 0; r < 3; ++r)
                    for (int c = r; c < 3; ++c)
                        q.push_back(
                            {"I" + s + "_" + ax[r] + ax[c], &b.inertia[r][c],
                             "inertia tensor of " + b.name + " about its centre of mass, " + ax[r] + ax[c] + " entry"});
        }
        for (int c = 0; c < dim; ++c)
            q.push_back({"r_" + ax[c] + sub, &b.position[c],
                         "position of the centre of mass of " + b.name + " from the origin, " + ax[c]});
        for (int c = 0; c < dim; ++c)
            q.push_back({"v_" + ax[c] + sub, &b.velocity[c],
                         "velocity of the centre of mass of " + b.name + " before impact, " + ax[c]});
        for (int c = dim == 2 ? 2 : 0; c < 3; ++c)
            q.push_back({"w_" + ax[c] + sub, &b.angular_velocity[c],
                         "angular velocity of " + b.name + " before impact, " + ax[c]});
    }
    if (p.is_system()) {
        system_quantities(p, q);
        return q;
    }
    for (int c = 0; c < dim; ++c)
        q.push_back({"O_" + ax[c], &p.contact().point[c], "position of the contact point from the origin, " + ax[c]});
    for (int c = 0; c < dim; ++c)
        q.push_back(
            {"n_" + ax[c], &p.contact().normal[c], "contact normal (from body 1 into body 2, any length), " + ax[c]});
    for (pivot &pv : p.pivots)
        for (int c = 0; c < dim; ++c)
            q.push_back({"E_" + ax[c] + suffix(p.bodies[pv.body].label), &pv.point[c],
                         "position of the pivot of " + p.bodies[pv.body].name + " from the origin, " + ax[c]});
    return q;
}

void symmetrise(problem &p)
{
    for (body &b : p.bodies)
        for (int r = 0; r < 3; ++r)
            for (int c = r + 1; c < 3; ++c)
                b.inertia[c][r] = b.inertia[r][c];
}

std::string shown(const ex &e)
{
    std::ostringstream os;
    os << e;
    return names::display_text(os.str(), 120);
}

// Every solution value the emitter reads, rewritten by one substitution.
void rewrite_solution(solution &s, const ex &rel)
{
    for (step &st : s.steps)
        st.value = st.value.subs(rel);
    for (body_state &b : s.after)
        for (int c = 0; c < 3; ++c) {
            b.velocity[c] = b.velocity[c].subs(rel);
            b.angular_velocity[c] = b.angular_velocity[c].subs(rel);
        }
    for (vec3 &r : s.pivot_impulses)
        for (ex &c : r)
            c = c.subs(rel);
    s.normal_impulse = s.normal_impulse.subs(rel);
    s.energy_lost = s.energy_lost.subs(rel);
}

// A new input symbol standing for the inverse of `old` (never a registered
// symbol of the same name: a user's own symbol inv_m1 stays a different input).
symbol inverse_symbol(plan &pl, const ex &old, const std::string &meaning, bool reciprocal = true)
{
    symbol k("inv_" + ex_to<symbol>(old).get_name());
    pl.replaced[old].push_back(k);
    if (reciprocal) // old = 1/k (a mass, a planar inertia); not an entry of an inverse tensor
        pl.inverse_of[old] = k;
    pl.meaning[k] = meaning;
    return k;
}

// Engine convention for one planar body: I becomes 1/inv_I.
bool planar_inverse_inertia(plan &pl, const body &b, lst &subs)
{
    const ex &old = b.inertia[2][2];
    if (is_a<numeric>(old))
        return false;
    if (!is_a<symbol>(old))
        throw option_error(option_error::inverse_inertia, "the moment of inertia of " + names::display_text(b.name) +
                                                              " is neither a number nor a single symbol");
    symbol k = inverse_symbol(
        pl, old, "inverse moment of inertia 1/I of " + b.name + " about its centre of mass (>= 0; 0: rotation locked)");
    subs.append(old == 1 / k);
    return true;
}

// The inverse of one 3-D body's inertia tensor, filled block by block, with the inputs it takes.
struct tensor_inverter {
    plan &pl;
    const problem &q;
    const body &b;
    const mat3 &I;
    lst &subs;
    const std::string who;
    mat3 K = zero_mat();

    // The name of an entry by its axes, e.g. "xy".
    std::string entry(int r, int c) const { return q.axes[std::min(r, c)] + q.axes[std::max(r, c)]; }
    // The quantity an entry is, e.g. "I1_xy".
    std::string quantity_name(int r, int c) const { return "I" + suffix(b.label) + "_" + entry(r, c); }

    // A block of numbers: the inverse block exactly.
    void numbers_block(const std::vector<int> &axes, unsigned n)
    {
        matrix M(n, n);
        for (unsigned r = 0; r < n; ++r)
            for (unsigned c = 0; c < n; ++c)
                M(r, c) = I[axes[r]][axes[c]];
        matrix Minv = M.inverse();
        for (unsigned r = 0; r < n; ++r)
            for (unsigned c = 0; c < n; ++c)
                K[axes[r]][axes[c]] = tidy(Minv(r, c));
    }

    // A block of one symbol: inv_I = 1/I, shared by every entry (and body) it stands for.
    void one_symbol_block(const std::vector<int> &axes)
    {
        const int a = axes[0];
        const ex &old = I[a][a];
        if (!is_a<symbol>(old))
            throw option_error(option_error::inverse_inertia, "the inertia entry " + entry(a, a) + " of " + who +
                                                                  " is neither a number nor a single symbol");
        auto known = pl.inverse_of.find(old);
        if (known != pl.inverse_of.end()) {
            K[a][a] = known->second;
            return;
        }
        std::vector<std::string> where; // an isotropic tensor: one symbol on every diagonal entry
        for (int d = 0; d < 3; ++d)
            if (I[d][d].is_equal(old))
                where.push_back(entry(d, d));
        symbol k = inverse_symbol(pl, old,
                                  "inverse inertia tensor of " + b.name + " (world axes), " + join(where, ", ") +
                                      (where.size() > 1 ? " entries" : " entry") + " (= 1/" +
                                      ex_to<symbol>(old).get_name() + ")");
        subs.append(old == 1 / k);
        K[a][a] = k;
    }

    // A larger block that mixes numbers (or expressions) and symbols: refused, with the reason.
    [[noreturn]] void refuse_mixed_block(const std::vector<int> &axes, unsigned n) const
    {
        std::string block_axes;
        for (int a : axes)
            block_axes += q.axes[static_cast<std::size_t>(a)];
        std::vector<std::string> numbers, names, exprs;
        for (std::size_t r = 0; r < n; ++r)
            for (std::size_t c = r; c < n; ++c) {
                const ex &x = I[axes[r]][axes[c]];
                if (is_constant(x)) {
                    numbers.push_back(entry(axes[r], axes[c]) + " = " + shown(x));
                    names.push_back(quantity_name(axes[r], axes[c]));
                } else if (!is_a<symbol>(x)) {
                    exprs.push_back(entry(axes[r], axes[c]));
                }
            }
        if (!exprs.empty())
            throw option_error(option_error::inverse_inertia,
                               "the inertia entry " + exprs[0] + " of " + who +
                                   " is not a single symbol (the entries of a tensor whose axes " + block_axes +
                                   " are coupled are replaced by its inverse's entries, one input each)");
        throw option_error(option_error::inverse_inertia,
                           "the inertia tensor of " + who + " couples the axes " + block_axes +
                               " (non-zero off-diagonal entries), and in that block numbers (" + join(numbers, ", ") +
                               ") stand beside symbols: the entries of the inverse there depend on both, so they are "
                               "neither inputs nor numbers. Make every entry of the block a symbol (name " +
                               join(names, ", ") + " in --params) or a number");
    }

    // A larger block of distinct symbols, each standing for its entry only: its inverse's entries as inputs.
    void symbols_block(const std::vector<int> &axes, unsigned n)
    {
        problem copy = q;
        const std::vector<quantity> all = quantities(copy);
        for (std::size_t r = 0; r < n; ++r)
            for (std::size_t c = r; c < n; ++c) {
                const int ar = axes[r], ac = axes[c];
                const ex &old = I[ar][ac];
                const std::string own = quantity_name(ar, ac);
                for (const quantity &other : all)
                    if (other.name != own && other.value->has(old))
                        throw option_error(option_error::inverse_inertia,
                                           "the symbol " + names::display_text(ex_to<symbol>(old).get_name()) +
                                               " is the inertia entry " + entry(ar, ac) + " of " + who +
                                               " and also appears in " + names::display_text(other.name) +
                                               ": the inverse tensor's entry that replaces it "
                                               "cannot stand for it there (give that quantity its own symbol)");
                K[ar][ac] = K[ac][ar] = inverse_symbol(
                    pl, old, "inverse inertia tensor of " + b.name + " (world axes), " + entry(ar, ac) + " entry",
                    false);
            }
    }
};

// The blocks of a tensor: axes joined by a non-zero off-diagonal entry share a block.
void inertia_blocks(const mat3 &I, int (&block_of)[3])
{
    for (int r = 0; r < 3; ++r)
        for (int c = r + 1; c < 3; ++c)
            if (!tidy(I[r][c]).is_zero()) {
                const int from = block_of[c], to = block_of[r];
                for (int &x : block_of)
                    if (x == from)
                        x = to;
            }
}

// The angular response steps g = K t rewritten with the inverse tensor K; the determinant step dropped.
void rewrite_angular_response(plan &pl, std::size_t i, const mat3 &K)
{
    const problem &q = pl.prob;
    const body &b = q.bodies[i];
    solution &s = pl.sol;
    vec3 tau = cross(q.contact().point - b.position, pl.deriv.n_hat);
    vec3 t;
    for (int c = 0; c < 3; ++c) {
        const step *ts = s.find(step_role::lever_arm, i, c);
        t[c] = ts ? ex(ts->sym) : tau[c].normal();
    }
    vec3 g = mul(K, t);
    for (int c = 0; c < 3; ++c) {
        step *gs = s.find(step_role::angular_response, i, c);
        if (gs) {
            gs->value = g[c];
            continue;
        }
        // No step: the component was too simple to name: zero (r x n has no component
        // there, and the tensor does not couple it), or t_c / I_cc with I_cc a number
        // (a block of one number: K_cc t_c is the same value). Otherwise the rewrite cannot hold.
        bool fixed_row = true;
        for (int a = 0; a < 3; ++a)
            fixed_row = fixed_row && is_constant(K[c][a]);
        if (!fixed_row && !g[c].expand().is_zero())
            throw std::logic_error("inverse inertia: no angular response step for body " + std::to_string(i));
    }
    s.steps.erase(
        std::remove_if(s.steps.begin(), s.steps.end(),
                       [&](const step &st) { return st.role == step_role::inertia_determinant && st.body == i; }),
        s.steps.end());
}

// Engine convention for one 3-D body: g = inv_I (r x n) with the inverse tensor's
// entries as inputs; the determinant step is no longer needed.
//
// The tensor falls into blocks of axes coupled by non-zero off-diagonal entries (a
// diagonal tensor: three blocks of one axis each), and its inverse has the same
// blocks. A block of numbers is inverted exactly here; a block of one symbol I gets
// the input inv_I = 1/I (and I becomes 1/inv_I wherever else it appears; an
// isotropic ["I", "I", "I"] has one input); a larger block of symbols takes its
// inverse's entries as inputs, one per entry. Refused, with the reason: an entry that
// is an expression; a larger block that mixes numbers and symbols (the inverse's
// entries there are neither numbers nor inputs: they depend on the numbers and the
// symbols together); a symbol of a larger block that stands for two entries or
// appears anywhere else in the problem (its inverse entry cannot stand for it there).
bool tensor_inverse_inertia(plan &pl, std::size_t i, lst &subs)
{
    const problem &q = pl.prob;
    const body &b = q.bodies[i];
    const mat3 &I = b.inertia;
    bool symbolic = false;
    for (auto &row : I)
        for (auto &c : row)
            symbolic = symbolic || !is_constant(c);
    if (!symbolic)
        return false; // a known tensor is inverted exactly at generation time
    const std::string who = names::display_text(b.name);
    tensor_inverter T{pl, q, b, I, subs, who};

    // Blocks: axes joined by a non-zero off-diagonal entry.
    int block_of[3] = {0, 1, 2};
    inertia_blocks(I, block_of);
    for (int first = 0; first < 3; ++first) {
        std::vector<int> axes;
        for (int a = 0; a < 3; ++a)
            if (block_of[a] == first)
                axes.push_back(a);
        if (axes.empty())
            continue;
        const unsigned n = static_cast<unsigned>(axes.size());
        bool constant = true, all_symbols = true;
        for (int r : axes)
            for (int c : axes) {
                constant = constant && is_constant(I[r][c]);
                all_symbols = all_symbols && is_a<symbol>(I[r][c]);
            }
        if (constant) {
            T.numbers_block(axes, n);
            continue;
        }
        if (n == 1) {
            T.one_symbol_block(axes);
            continue;
        }
        if (!all_symbols)
            T.refuse_mixed_block(axes, n);
        T.symbols_block(axes, n);
    }
    pl.inverse_tensor[i] = T.K;
    rewrite_angular_response(pl, i, T.K);
    return true;
}

void apply_inverse_inertia(plan &pl)
{
    const problem &q = pl.prob;
    bool any = false;
    lst subs;
    for (std::size_t i : {q.contact().body1, q.contact().body2}) {
        const body &b = q.bodies[i];
        if (b.particle || b.infinite_mass || q.pivot_of(i))
            continue;
        any = (q.dimension == 2 ? planar_inverse_inertia(pl, b, subs) : tensor_inverse_inertia(pl, i, subs)) || any;
    }
    if (!any)
        throw option_error(option_error::inverse_inertia,
                           "no free rigid body with a symbolic inertia takes part in the contact");
    if (subs.nops() > 0)
        rewrite_solution(pl.sol, subs);
}

void apply_inverse_mass(plan &pl)
{
    const problem &q = pl.prob;
    lst subs;
    for (std::size_t i : {q.contact().body1, q.contact().body2}) {
        const body &b = q.bodies[i];
        if (b.infinite_mass || is_a<numeric>(b.mass))
            continue;
        if (!is_a<symbol>(b.mass))
            throw option_error(option_error::inverse_mass, "the mass of " + names::display_text(b.name) +
                                                               " is neither a number nor a single symbol");
        symbol im =
            inverse_symbol(pl, b.mass, "inverse mass 1/m of " + b.name + " (>= 0; 0: a static or kinematic body)");
        subs.append(b.mass == 1 / im);
    }
    if (subs.nops() == 0)
        throw option_error(option_error::inverse_mass, "no body in the contact has a symbolic mass");
    rewrite_solution(pl.sol, subs);
}

// Inputs in order: the parameters as given, else first appearance in the
// problem; a symbol replaced by its inverse(s) is replaced in place.
void order_inputs(plan &pl, const options &o)
{
    problem q = pl.prob;
    std::vector<quantity> all = quantities(q);
    std::map<ex, std::string, ex_is_less> meaning;
    for (const quantity &x : all) {
        if (!is_a<symbol>(*x.value))
            continue;
        const bool normal = x.value >= &q.contact().normal[0] && x.value <= &q.contact().normal[2];
        if (normal && o.unit_normal) // the promise --unit-normal makes, in the parameter's documentation
            meaning.emplace(*x.value, "contact normal, a unit vector (from body 1 into body 2; |n.n - 1| <= 2^-17), " +
                                          q.axes[static_cast<std::size_t>(x.value - &q.contact().normal[0])]);
        else
            meaning.emplace(*x.value, x.meaning);
    }
    std::vector<ex> order;
    if (o.params_given) {
        for (const std::string &nm : o.params)
            order.push_back(symbol_named(nm));
    } else {
        exset seen;
        for (const quantity &x : all) {
            std::vector<ex> found;
            for (const_preorder_iterator it = x.value->preorder_begin(); it != x.value->preorder_end(); ++it)
                if (is_a<symbol>(*it) && seen.insert(*it).second)
                    found.push_back(*it);
            std::sort(found.begin(), found.end(), [](const ex &a, const ex &b) {
                return ex_to<symbol>(a).get_name() < ex_to<symbol>(b).get_name();
            });
            order.insert(order.end(), found.begin(), found.end());
        }
    }
    exset done;
    for (const ex &x0 : order) {
        auto r = pl.replaced.find(x0);
        std::vector<symbol> syms = r == pl.replaced.end() ? std::vector<symbol>{ex_to<symbol>(x0)} : r->second;
        for (const symbol &x : syms) {
            if (!done.insert(x).second)
                continue;
            pl.inputs.push_back(x);
            if (auto m = pl.meaning.find(x); m != pl.meaning.end()) {
                pl.input_meaning.push_back(m->second);
            } else if (auto m2 = meaning.find(x); m2 != meaning.end()) {
                pl.input_meaning.push_back(m2->second);
            } else {
                std::vector<std::string> where;
                for (const quantity &qq : all)
                    if (qq.value->has(x))
                        where.push_back(qq.name);
                pl.input_meaning.push_back("appears in " + join(where, ", "));
            }
        }
    }
}

// The post-impact state of the bodies in contact, then impulses and energy.
void plan_outputs(plan &pl)
{
    const problem &q = pl.prob;
    const solution &s = pl.sol;
    const auto &ax = q.axes;
    const int dim = q.dimension;
    for (std::size_t i : {q.contact().body1, q.contact().body2}) {
        const body &b = q.bodies[i];
        if (b.infinite_mass)
            continue;
        const std::string sub = suffix(b.label);
        for (int c = 0; c < dim; ++c)
            pl.outputs.push_back({output_value::velocity, i, c, "v_" + ax[c] + sub, s.after[i].velocity[c],
                                  "velocity of the centre of mass of " + b.name + " after impact, " + ax[c]});
        if (!b.particle)
            for (int c = dim == 2 ? 2 : 0; c < 3; ++c)
                pl.outputs.push_back({output_value::angular_velocity, i, c, "w_" + ax[c] + sub,
                                      s.after[i].angular_velocity[c],
                                      "angular velocity of " + b.name + " after impact, " + ax[c]});
    }
    // N is the impulse along the unit normal (as `impactgen solve` reports it), whatever |n| was given.
    pl.outputs.push_back({output_value::normal_impulse, 0, 0, "normal_impulse", s.normal_impulse,
                          "normal impulse, integral of N dt >= 0 along the unit normal: on " +
                              q.bodies[q.contact().body2].name + " along +n, on " + q.bodies[q.contact().body1].name +
                              " along -n"});
    for (std::size_t k = 0; k < q.pivots.size(); ++k)
        for (int c = 0; c < dim; ++c)
            pl.outputs.push_back({output_value::pivot_impulse, k, c,
                                  "R_" + ax[c] + suffix(q.bodies[q.pivots[k].body].label), s.pivot_impulses[k][c],
                                  "impulse of the pivot on " + q.bodies[q.pivots[k].body].name + ", " + ax[c]});
    const step *u_step = s.find(step_role::approach_velocity);
    const ex u = u_step ? ex(u_step->sym) : ex(0);
    pl.outputs.push_back({output_value::approach_velocity, 0, 0, "approach_velocity", u,
                          "(v_B - v_A).n before impact along the unit normal (< 0)"});
    pl.outputs.push_back({output_value::energy_lost, 0, 0, "energy_lost", s.energy_lost,
                          "kinetic energy lost, T - T' (bodies of finite mass)"});
}

// The values given for symbols, folded in.
problem set_values(const problem &p, const options &o, std::set<std::string> &given)
{
    std::set<std::string> symbols;
    for (const symbol &s : p.parameters())
        symbols.insert(s.get_name());
    lst values;
    std::set<std::string> seen;
    for (const auto &[name, text] : o.set) {
        if (!seen.insert(name).second)
            throw option_error(option_error::set, names::display_text(name) + " is given two values");
        if (!symbols.count(name))
            throw option_error(
                option_error::set,
                names::display_text(name) + ": the problem has no symbol " + names::display_text(name) +
                    (symbols.empty()
                         ? " (it has none)"
                         : " (its symbols: " + names::display_text(join({symbols.begin(), symbols.end()}, ", "), 160) +
                               ")"));
        bool is_number = !text.empty() &&
                         (std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '-' || text[0] == '.') &&
                         text.find_first_not_of("0123456789.eE+-") == std::string::npos;
        try {
            values.append(symbol_named(name) == parse_value(text, !is_number, "the value of " + name));
        } catch (const input_error &e) {
            throw option_error(option_error::set, e.what());
        }
        given.insert(name);
    }
    return values.nops() > 0 ? substitute(p, values) : p;
}

// A numeric quantity named in the parameter list becomes a symbol of that name.
void lift_quantity(problem &q, const std::string &name, const std::set<std::string> &now)
{
    bool lifted = false;
    for (quantity &x : quantities(q))
        if (x.name == name) {
            if (!is_a<numeric>(*x.value))
                throw option_error(option_error::params, "the quantity " + name + " is the expression " +
                                                             shown(*x.value) + "; name its symbols instead");
            *x.value = symbol_named(name);
            lifted = true;
        }
    if (!lifted) {
        std::vector<std::string> numeric_names;
        for (const auto &[n, v] : quantity_names(q))
            if (is_a<numeric>(v))
                numeric_names.push_back(n);
        throw option_error(
            option_error::params,
            names::display_text(name) + " is neither a symbol of the problem" +
                (now.empty() ? "" : " (" + names::display_text(join({now.begin(), now.end()}, ", "), 160) + ")") +
                " nor a numeric quantity of it (" + names::display_text(join(numeric_names, ", "), 400) + ")");
    }
    symmetrise(q);
}

// The vectors and tensors among the inputs and outputs (views for adapters): a
// group whose entries are all input symbols or numbers, with at least one input.
void plan_groups(plan &pl)
{
    const problem &q = pl.prob;
    const int dim = q.dimension;
    exset inputs(pl.inputs.begin(), pl.inputs.end());
    auto add_input = [&](const std::string &name, int rows, int cols, std::vector<ex> entries,
                         const std::string &meaning) {
        bool any = false;
        for (const ex &x : entries) {
            if (!is_a<numeric>(x) && !inputs.count(x))
                return;
            any = any || inputs.count(x);
        }
        if (any && entries.size() > 1)
            pl.input_groups.push_back({name, rows, cols, std::move(entries), {}, meaning});
    };
    auto vec = [&](const vec3 &v, int from = 0) {
        std::vector<ex> r;
        for (int c = from; c < (from == 0 ? dim : 3); ++c)
            r.push_back(v[c]);
        return r;
    };
    for (std::size_t i : {q.contact().body1, q.contact().body2}) {
        const body &b = q.bodies[i];
        const std::string s = suffix(b.label);
        if (!b.infinite_mass && !b.particle && dim == 3) {
            auto inv = pl.inverse_tensor.find(i);
            const mat3 &J = inv == pl.inverse_tensor.end() ? b.inertia : inv->second;
            std::vector<ex> entries;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    entries.push_back(J[r][c]);
            add_input((inv == pl.inverse_tensor.end() ? "I" : "inv_I") + s, 3, 3, entries,
                      (inv == pl.inverse_tensor.end() ? "inertia tensor of " : "inverse inertia tensor of ") + b.name);
        }
        add_input("r" + s, dim, 1, vec(b.position), "position of the centre of mass of " + b.name + " from the origin");
        add_input("v" + s, dim, 1, vec(b.velocity), "velocity of the centre of mass of " + b.name + " before impact");
        if (dim == 3)
            add_input("w" + s, 3, 1, vec(b.angular_velocity), "angular velocity of " + b.name + " before impact");
    }
    add_input("O", dim, 1, vec(q.contact().point), "position of the contact point from the origin");
    add_input("n", dim, 1, vec(q.contact().normal), "contact normal");
    for (const pivot &pv : q.pivots)
        add_input("E" + suffix(q.bodies[pv.body].label), dim, 1, vec(pv.point),
                  "position of the pivot of " + q.bodies[pv.body].name + " from the origin");

    // Outputs: every component of a vector is an output, or there is no group.
    std::map<std::tuple<int, std::size_t>, std::vector<std::size_t>> found;
    for (std::size_t k = 0; k < pl.outputs.size(); ++k) {
        const output_value &ov = pl.outputs[k];
        if (ov.kind == output_value::velocity || ov.kind == output_value::angular_velocity ||
            ov.kind == output_value::pivot_impulse)
            found[{static_cast<int>(ov.kind), ov.index}].push_back(k);
    }
    for (const auto &[key, ks] : found) {
        const auto kind = static_cast<output_value::kind_t>(std::get<0>(key));
        const std::size_t i = std::get<1>(key);
        if (ks.size() < 2)
            continue;
        const std::string who =
            kind == output_value::pivot_impulse ? q.bodies[q.pivots[i].body].name : q.bodies[i].name;
        const std::string s =
            suffix(kind == output_value::pivot_impulse ? q.bodies[q.pivots[i].body].label : q.bodies[i].label);
        const std::string name = (kind == output_value::velocity           ? "v"
                                  : kind == output_value::angular_velocity ? "w"
                                                                           : "R") +
                                 s;
        const std::string meaning =
            kind == output_value::velocity           ? "velocity of the centre of mass of " + who + " after impact"
            : kind == output_value::angular_velocity ? "angular velocity of " + who + " after impact"
                                                     : "impulse of the pivot on " + who;
        pl.output_groups.push_back({name, static_cast<int>(ks.size()), 1, {}, ks, meaning});
    }
    std::stable_sort(pl.output_groups.begin(), pl.output_groups.end(),
                     [](const group &a, const group &b) { return a.outputs.front() < b.outputs.front(); });
}

// What a failed call returns: each output with the impulses zero, in inputs only.
void plan_unchanged(plan &pl)
{
    const solution &s = pl.sol;
    lst zero;
    for (const step &st : s.steps)
        if (st.role == step_role::normal_impulse)
            zero.append(st.sym == 0);
    for (const output_value &ov : pl.outputs) {
        ex v = 0;
        if (ov.kind == output_value::velocity || ov.kind == output_value::angular_velocity) {
            v = ov.value.subs(zero);
            // Steps left (none in practice: every change is a multiple of N) in inputs.
            for (auto st = s.steps.rbegin(); st != s.steps.rend(); ++st)
                if (v.has(st->sym))
                    v = v.subs(st->sym == st->value);
            for (const step &st : s.steps)
                if (v.has(st.sym))
                    throw std::logic_error("codegen: the unchanged state of " + ov.field + " still uses the step " +
                                           st.sym.get_name());
        }
        pl.unchanged.push_back(v);
    }
}

// --unit-normal: the normal's inputs are promised to be a unit vector (the header
// checks them: invalid_normal). A constant normal must have length 1 (then the
// option changes nothing); one of another length is refused.
void check_unit_normal(const problem &q)
{
    const vec3 &n = q.contact().normal;
    const ex nn = tidy(dot(n, n));
    if (!is_constant(nn))
        return;
    const decision d = decide(nn - 1);
    if (d == decision::zero)
        return;
    std::string text = "(" + shown(n[0]) + ", " + shown(n[1]) + (q.dimension == 3 ? ", " + shown(n[2]) : "") + ")";
    if (d == decision::positive || d == decision::negative)
        throw option_error(
            option_error::unit_normal,
            "the contact normal " + text + " is a constant of length " + shown(sqrt(nn)) +
                ", not 1 (--unit-normal declares the normal a unit vector; without it the header normalises "
                "this normal itself)");
    throw option_error(option_error::unit_normal,
                       "whether the contact normal " + text + " has length 1 " + decision_text(d));
}

} // namespace

void order_plan_inputs(plan &pl, const options &o)
{
    order_inputs(pl, o);
}

const char *option_error::option_name(option o)
{
    switch (o) {
    case set:
        return "set";
    case params:
        return "params";
    case inverse_inertia:
        return "inverse-inertia";
    case inverse_mass:
        return "inverse-mass";
    case function_name:
        return "name";
    case name_space:
        return "namespace";
    case unit_normal:
        return "unit-normal";
    case jacobian:
        return "jacobian";
    case wrt:
        return "wrt";
    case rows:
        return "rows";
    }
    return "?";
}

std::vector<std::pair<std::string, ex>> quantity_names(const problem &p)
{
    problem q = p;
    std::vector<std::pair<std::string, ex>> r;
    for (const quantity &x : quantities(q))
        r.push_back({x.name, *x.value});
    return r;
}

problem specialise(const problem &p, const options &o)
{
    std::set<std::string> given;
    problem q = set_values(p, o, given);
    if (!o.params_given)
        return q;
    std::set<std::string> now;
    for (const symbol &s : q.parameters())
        now.insert(s.get_name());
    std::set<std::string> wanted;
    for (const std::string &name : o.params) {
        if (!wanted.insert(name).second)
            throw option_error(option_error::params, names::display_text(name) + " is named twice");
        if (given.count(name))
            throw option_error(option_error::params, names::display_text(name) + " is also given a value");
        if (!now.count(name))
            lift_quantity(q, name, now);
    }
    for (const symbol &s : q.parameters())
        if (!wanted.count(s.get_name()))
            throw option_error(option_error::params,
                               "symbol " + s.get_name() + " is neither a parameter nor given a value", s.get_name());
    return q;
}

plan make_plan(const problem &p, const options &o)
{
    plan pl;
    pl.prob = specialise(p, o);
    if ((o.jacobian || !o.wrt.empty()) && law_traits_of(pl.prob).jacobian != jacobian_route::closed_form)
        throw option_error(option_error::jacobian, "Jacobians are not offered for problems with friction (the regime "
                                                   "selection makes the impact map piecewise)");
    if (o.unit_normal)
        check_unit_normal(pl.prob);
    derive_options how;
    how.unit_normal = o.unit_normal;
    pl.deriv = derive(pl.prob, how);
    pl.sol = solve(pl.deriv);
    if (o.inverse_inertia)
        apply_inverse_inertia(pl);
    if (o.inverse_mass)
        apply_inverse_mass(pl);
    order_inputs(pl, o);
    plan_outputs(pl);
    plan_groups(pl);
    plan_unchanged(pl);
    if (o.jacobian || !o.wrt.empty()) {
        pl.jac = plan_jacobian(pl, o.wrt);
        pl.has_jacobian = true;
    }
    return pl;
}

} // namespace impactgen::codegen
