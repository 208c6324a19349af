// A fast evaluation of a friction class's closed form (symbolic/friction.hpp) with CLN
// long floats, for tests/codegen/friction.cpp: independent of the generated headers (no
// code or root finder of codegen/) and of select_regime's exact path (no substitution).
//
// Once per class, every expression the test needs -- each case's conditions, the angle
// equation g(c_d, s_d) of a 3-D slide without closed form, and the outputs (velocities,
// angular velocities, impulses, approach velocity, energy lost, pivot impulses) -- is
// compiled into one flat program: a list of nodes over GiNaC's add, mul, power (integer
// and half-integer exponents), numbers and symbols, each step of the closed form compiled
// once and every shared subexpression a single node (a DAG, in topological order).
//
// Per sample the program runs on CLN long floats of 256 bits (cln::float_format(60): 77
// digits), the inputs converted exactly from the doubles. Beside its value each node
// carries a bound on its absolute error, propagated by the rules of running error
// analysis (sum of the arguments' errors plus a rounding of 4 ulps per operation;
// |x y - x' y'| <= |x| e_y + |y| e_x + e_x e_y; 1/x and sqrt(x) only when x is clear of 0).
// A condition's sign is taken from its value only when |value| > 1e20 times that bound
// (the bound being some 1e-75 of the size of the terms, that asks for |value| above
// about 1e-55 of them; a value exactly 0, a condition on its boundary, is never decided);
// otherwise the sample is "too close" and the caller decides it another way
// (select_regime, exactly).
//
// The 3-D slide without closed form: g is a trigonometric polynomial of degree 2 in the
// sliding angle phi (d = cos phi e_t + sin phi e_b). Its five coefficients come from g at
// the five angles phi0 + 2 pi k / 5 (a discrete Fourier transform, exact for degree 2);
// with t = tan((phi - phi0) / 2) the equation is a quartic in t (phi0 fixed and generic,
// so a root at t = infinity, phi = phi0 + pi, does not happen but with probability 0: it
// is reported as too close). All four roots are found by Aberth's method in complex
// doubles, each polished by Newton's method in complex long floats; a root is real when
// its imaginary part is within its error bound (|p| over |p'|), complex when far beyond
// it, and any two roots closer than 1e5 times their bounds (a double root: two sliding
// directions merge) make the sample too close. Each real root gives a slide candidate,
// its angle's error carried into the conditions.
#pragma once

#include "symbolic/decide.hpp"
#include "symbolic/friction.hpp"

#include <cln/cln.h>
#include <ginac/ginac.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace cln_closed_form {

using GiNaC::ex;

/// The double x as a long float of the format, exactly (CLN's double floats have no
/// subnormals: those are scaled into range first).
inline cln::cl_F exactly(double x, cln::float_format_t format)
{
    if (x != 0 && std::fabs(x) < 1e-290)
        return cln::scale_float(cln::cl_float(cln::cl_DF(std::ldexp(x, 200)), format), -200);
    return cln::cl_float(cln::cl_DF(x), format);
}

/// A flat program over GiNaC expressions, evaluated in CLN long floats with error bounds.
class program {
public:
    explicit program(long decimal_digits = 60) : format_(cln::float_format(decimal_digits))
    {
        const cln::cl_F one = cln::cl_float(1, format_);
        bits_ = static_cast<int>(cln::float_digits(one));
        unit_ = 4 * std::ldexp(1.0, 1 - bits_); // 4 ulps per operation (CLN rounds to nearest)
        zero_ = cln::cl_float(0, format_);
    }
    cln::float_format_t format() const { return format_; }
    int bits() const { return bits_; }
    /// The rounding error of one operation, relative to its result.
    double unit() const { return unit_; }

    // Declarations, before compiling: what each symbol stands for.
    /// The next input slot (begin() takes the inputs in this order).
    void input(const GiNaC::symbol& s)
    {
        const int i = push(op::input, {}, static_cast<int>(inputs_.size()));
        cache_.emplace(s, i);
        inputs_.push_back(i);
    }
    /// A step of the closed form: s stands for value (compiled when first used).
    void define(const GiNaC::symbol& s, const ex& value) { defined_.emplace(s, value); }
    /// The cosine and sine of the sliding angle (set_angle gives their values).
    void angle(const GiNaC::symbol& c, const GiNaC::symbol& s)
    {
        if (angle_c_ < 0) {
            angle_c_ = push(op::angle_c, {});
            angle_s_ = push(op::angle_s, {});
        }
        cache_.emplace(c, angle_c_);
        cache_.emplace(s, angle_s_);
    }

    /// The node computing e (every subexpression compiled once).
    int compile(const ex& e)
    {
        const auto it = cache_.find(e);
        if (it != cache_.end())
            return it->second;
        int r = -1;
        if (GiNaC::is_a<GiNaC::symbol>(e)) {
            const auto d = defined_.find(e);
            if (d == defined_.end())
                throw std::runtime_error("cln_closed_form: a symbol without value: " + to_text(e));
            r = compile(d->second);
        } else if (GiNaC::is_a<GiNaC::numeric>(e)) {
            r = constant(GiNaC::ex_to<GiNaC::numeric>(e));
        } else if (impactgen::is_constant(e)) {
            // sqrt(2), Pi, ...: a float at 30 digits more than the program's
            const long saved = GiNaC::Digits;
            GiNaC::Digits = static_cast<long>(bits_ * 0.30103) + 30;
            const ex v = e.evalf();
            GiNaC::Digits = saved;
            if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
                throw std::runtime_error("cln_closed_form: a constant that is not a real number: " + to_text(e));
            r = constant(GiNaC::ex_to<GiNaC::numeric>(v));
        } else if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
            std::vector<int> args;
            for (std::size_t i = 0; i < e.nops(); ++i)
                args.push_back(compile(e.op(i)));
            r = push(GiNaC::is_a<GiNaC::add>(e) ? op::add : op::mul, args);
        } else if (GiNaC::is_a<GiNaC::power>(e)) {
            const ex k = e.op(1);
            if (!GiNaC::is_a<GiNaC::numeric>(k))
                throw std::runtime_error("cln_closed_form: a power with a symbolic exponent: " + to_text(e));
            const GiNaC::numeric q = GiNaC::ex_to<GiNaC::numeric>(k);
            const int base = compile(e.op(0));
            if (q.is_integer()) {
                r = push(op::power, {base}, q.to_int());
            } else if ((2 * q).is_integer()) { // x^(k/2) = sqrt(x)^k
                const int k2 = (2 * q).to_int();
                if (k2 == 1) {
                    r = push(op::sqrt, {base});
                } else {
                    const int root = compile(GiNaC::pow(e.op(0), GiNaC::numeric(1, 2))); // one sqrt per base
                    r = push(op::power, {root}, k2);
                }
            } else {
                throw std::runtime_error("cln_closed_form: an exponent other than n or n/2: " + to_text(e));
            }
        } else {
            throw std::runtime_error("cln_closed_form: an expression it cannot evaluate: " + to_text(e));
        }
        cache_.emplace(e, r);
        return r;
    }

    /// The nodes the targets need (themselves included), in the order to compute them.
    std::vector<int> schedule(const std::vector<int>& targets) const
    {
        std::vector<char> need(nodes_.size(), 0);
        std::vector<int> todo = targets;
        while (!todo.empty()) {
            const int i = todo.back();
            todo.pop_back();
            if (need[static_cast<std::size_t>(i)])
                continue;
            need[static_cast<std::size_t>(i)] = 1;
            for (int a : nodes_[static_cast<std::size_t>(i)].args)
                todo.push_back(a);
        }
        std::vector<int> order;
        for (std::size_t i = 0; i < nodes_.size(); ++i)
            if (need[i] && computed(nodes_[i].kind))
                order.push_back(static_cast<int>(i));
        return order; // children are compiled before their parents
    }
    bool depends_on_angle(int i) const { return nodes_[static_cast<std::size_t>(i)].angle; }
    std::size_t size() const { return nodes_.size(); }

    // Evaluation.
    /// A new sample: the inputs, exactly (every double is a long float).
    void begin(const double* x)
    {
        sample_ = ++clock_;
        angle_stamp_ = ++clock_;
        for (std::size_t k = 0; k < inputs_.size(); ++k) {
            const std::size_t i = static_cast<std::size_t>(inputs_[k]);
            if (!std::isfinite(x[k]))
                throw std::runtime_error("cln_closed_form: a non-finite input");
            val_[i] = exactly(x[k], format_);
            mag_[i] = std::fabs(x[k]);
            err_[i] = 0;
        }
    }
    /// The sliding angle's cosine and sine, each within err.
    void set_angle(const cln::cl_F& c, const cln::cl_F& s, double err)
    {
        angle_stamp_ = ++clock_;
        if (angle_c_ < 0)
            return;
        set(angle_c_, c, err);
        set(angle_s_, s, err);
    }
    /// Computes the nodes of a schedule that are not yet computed for this sample (angle).
    void run(const std::vector<int>& order)
    {
        for (int i : order) {
            long& st = stamp_[static_cast<std::size_t>(i)];
            const long want = nodes_[static_cast<std::size_t>(i)].angle ? angle_stamp_ : sample_;
            if (st != want) {
                evaluate(i);
                st = want;
            }
        }
    }
    const cln::cl_F& value(int i) const { return val_[static_cast<std::size_t>(i)]; }
    double magnitude(int i) const { return mag_[static_cast<std::size_t>(i)]; }
    /// A bound on |value - exact value| (infinity: unknown).
    double error(int i) const { return err_[static_cast<std::size_t>(i)]; }
    /// +1 or -1 when |value| > margin times its error bound, else 0 (too close to call).
    int sign(int i, double margin) const
    {
        const double m = magnitude(i), e = error(i);
        if (!(e < inf) || !(m > margin * e))
            return 0;
        return cln::minusp(value(i)) ? -1 : 1;
    }

private:
    enum class op { input, angle_c, angle_s, constant, add, mul, power, sqrt };
    struct node {
        op kind;
        std::vector<int> args;
        int k = 0;          ///< input slot, or the integer exponent
        bool angle = false; ///< depends on the sliding angle
    };
    static constexpr double inf = std::numeric_limits<double>::infinity();
    static bool computed(op k) { return k == op::add || k == op::mul || k == op::power || k == op::sqrt; }
    static std::string to_text(const ex& e)
    {
        std::ostringstream s;
        s << e;
        return s.str();
    }

    int push(op kind, std::vector<int> args, int k = 0)
    {
        node n{kind, std::move(args), k, kind == op::angle_c || kind == op::angle_s};
        for (int a : n.args)
            n.angle = n.angle || nodes_[static_cast<std::size_t>(a)].angle;
        nodes_.push_back(std::move(n));
        val_.push_back(zero_);
        mag_.push_back(0);
        err_.push_back(inf);
        stamp_.push_back(-1);
        return static_cast<int>(nodes_.size()) - 1;
    }
    int constant(const GiNaC::numeric& q)
    {
        if (!q.is_real())
            throw std::runtime_error("cln_closed_form: a complex number in the closed form");
        const int i = push(op::constant, {});
        const cln::cl_R r = cln::the<cln::cl_R>(q.to_cl_N());
        const cln::cl_F v = cln::cl_float(r, format_);
        double e = 0;
        if (q.is_rational()) {
            if (cln::rational(v) != cln::the<cln::cl_RA>(r))
                e = unit_ * std::fabs(cln::double_approx(v)); // rounded
        } else {
            // a float of GiNaC's, evaluated at Digits = 30 more than ours
            e = 1e-30 * std::ldexp(1.0, 1 - bits_) * std::fabs(cln::double_approx(v)) + unit_ * std::fabs(cln::double_approx(v));
        }
        set(i, v, e);
        return i;
    }
    void set(int i, const cln::cl_F& v, double e)
    {
        const std::size_t k = static_cast<std::size_t>(i);
        val_[k] = v;
        double m = 0;
        if (!cln::zerop(v)) {
            m = std::fabs(cln::double_approx(v));
            if (m == 0 || !(m < inf))
                e = inf; // beyond double's range: no bound kept
        }
        mag_[k] = m;
        err_[k] = e < inf ? e : inf; // NaN (0 times infinity) is no bound either
    }
    void invalid(int i) { set(i, zero_, inf); }

    void evaluate(int i)
    {
        const node& n = nodes_[static_cast<std::size_t>(i)];
        auto V = [&](int a) -> const cln::cl_F& { return val_[static_cast<std::size_t>(a)]; };
        auto M = [&](int a) { return mag_[static_cast<std::size_t>(a)]; };
        auto E = [&](int a) { return err_[static_cast<std::size_t>(a)]; };
        switch (n.kind) {
        case op::add: {
            cln::cl_F s = V(n.args[0]);
            double e = E(n.args[0]), terms = M(n.args[0]);
            for (std::size_t a = 1; a < n.args.size(); ++a) {
                s = s + V(n.args[a]);
                e += E(n.args[a]);
                terms += M(n.args[a]);
            }
            // each partial sum rounded: at most unit times the sum of the terms' sizes
            set(i, s, e + static_cast<double>(n.args.size() - 1) * unit_ * terms);
            return;
        }
        case op::mul: {
            cln::cl_F p = V(n.args[0]);
            double m = M(n.args[0]), e = E(n.args[0]);
            for (std::size_t a = 1; a < n.args.size(); ++a) {
                const double xm = M(n.args[a]), xe = E(n.args[a]);
                p = p * V(n.args[a]);
                e = m * xe + xm * e + e * xe + unit_ * m * xm;
                m *= xm;
            }
            set(i, p, e);
            return;
        }
        case op::power: {
            const int b = n.args[0];
            const int k = n.k < 0 ? -n.k : n.k;
            if (k == 0) {
                set(i, cln::cl_float(1, format_), 0);
                return;
            }
            cln::cl_F p = V(b);
            double m = M(b), e = E(b);
            for (int j = 1; j < k; ++j) {
                p = p * V(b);
                e = m * E(b) + M(b) * e + e * E(b) + unit_ * m * M(b);
                m *= M(b);
            }
            if (n.k > 0) {
                set(i, p, e);
                return;
            }
            // 1/p: |1/p - 1/p'| <= e / (|p| (|p| - e)) when p is clear of 0
            if (cln::zerop(p) || !(e < m)) {
                invalid(i);
                return;
            }
            set(i, cln::recip(p), e / (m * (m - e)) + unit_ / m);
            return;
        }
        case op::sqrt: {
            const int b = n.args[0];
            if (cln::zerop(V(b)) || cln::minusp(V(b)) || !(E(b) < M(b))) {
                invalid(i);
                return;
            }
            // |sqrt x - sqrt x'| = |x - x'| / (sqrt x + sqrt x') <= e / sqrt x
            const double r = std::sqrt(M(b));
            set(i, cln::sqrt(V(b)), E(b) / r + unit_ * r);
            return;
        }
        default: return; // inputs, constants, the angle: set elsewhere
        }
    }

    cln::float_format_t format_;
    int bits_ = 0;
    double unit_ = 0;
    cln::cl_F zero_;
    std::vector<node> nodes_;
    std::vector<cln::cl_F> val_;
    std::vector<double> mag_, err_;
    std::vector<long> stamp_;
    long clock_ = 0, sample_ = 0, angle_stamp_ = 0;
    std::vector<int> inputs_;
    int angle_c_ = -1, angle_s_ = -1;
    std::map<ex, int, GiNaC::ex_is_less> cache_;
    std::map<ex, ex, GiNaC::ex_is_less> defined_;
};

/// The answer of the closed form for one sample.
struct answer {
    enum kind_t { ok, none, several, undecided } kind = undecided;
    std::size_t case_index = 0;                  ///< the case of friction_solution::cases that holds
    impactgen::regime regime = impactgen::regime::stick;
    std::vector<cln::cl_F> values;               ///< every output, in the caller's order
    std::vector<double> out, errors;             ///< the same as doubles, and a bound on each one's error
    std::string why;                             ///< undecided: what could not be decided
    int real_roots = -1;                         ///< a 3-D slide without closed form: real roots of g
};

/// Every case of a class's friction_solution, compiled; decides the regime of a sample.
class evaluator {
public:
    /// outputs_of(case) gives the outputs to compute for the case (in steps and inputs).
    evaluator(const impactgen::friction_solution& f, const std::vector<GiNaC::symbol>& inputs,
              const std::function<std::vector<ex>(const impactgen::regime_case&)>& outputs_of, long digits = 60)
        : p_(digits), f_(f)
    {
        for (const GiNaC::symbol& s : inputs)
            p_.input(s);
        for (const impactgen::regime_case& c : f.cases) {
            for (const impactgen::step& st : c.sol.steps)
                p_.define(st.sym, st.value);
            if (c.needs_angle)
                p_.angle(c.dir_c, c.dir_s);
        }
        for (const impactgen::regime_case& c : f.cases) {
            plan pl;
            pl.needs_angle = c.needs_angle;
            for (const impactgen::regime_condition& rc : c.conditions) {
                pl.conditions.push_back(p_.compile(rc.value));
                pl.meaning.push_back(rc.meaning);
            }
            pl.condition_order = p_.schedule(pl.conditions);
            for (const ex& o : outputs_of(c))
                pl.outputs.push_back(p_.compile(o));
            pl.output_order = p_.schedule(pl.outputs);
            if (c.needs_angle) {
                pl.g = p_.compile(c.angle_equation);
                pl.g_order = p_.schedule({pl.g});
            }
            plans_.push_back(std::move(pl));
        }
        // The angles: phi0 (generic), the five sample angles phi0 + 2 pi k / 5 and the
        // Fourier factors cos, sin of 2 pi k / 5 and 4 pi k / 5.
        const cln::float_format_t fmt = p_.format();
        const cln::cl_F phi0 = cln::cl_float(cln::cl_RA(7137) / 10000, fmt); // 0.7137 rad
        const cln::cl_F two_pi_5 = cln::pi(fmt) * cln::cl_float(cln::cl_RA(2) / 5, fmt);
        cos0_ = cln::cos(phi0);
        sin0_ = cln::sin(phi0);
        for (std::size_t k = 0; k < 5; ++k) {
            const cln::cl_F th = cln::cl_float(static_cast<int>(k), fmt) * two_pi_5;
            ck_[k] = cln::cos(phi0 + th);
            sk_[k] = cln::sin(phi0 + th);
            c1_[k] = cln::cos(th);
            s1_[k] = cln::sin(th);
            c2_[k] = cln::cos(th + th);
            s2_[k] = cln::sin(th + th);
        }
        for (int k = 0; k <= 8; ++k)
            small_[static_cast<std::size_t>(k)] = cln::cl_float(k, fmt);
    }

    const program& code() const { return p_; }

    /// The regime of the sample x (the inputs in the order given), decided from the
    /// long-float values where they are clear of 0 by far more than their error bounds.
    answer solve(const double* x)
    {
        answer a;
        p_.begin(x);
        struct holding_case {
            std::size_t index;
            bool angle;
            cln::cl_F c, s;
            double err;
        };
        std::vector<holding_case> holding;
        bool undecided = false;
        for (std::size_t ci = 0; ci < plans_.size(); ++ci) {
            const plan& pl = plans_[ci];
            if (!pl.needs_angle) {
                const int h = holds(pl, a.why);
                if (h > 0)
                    holding.push_back({ci, false, cln::cl_F(), cln::cl_F(), 0});
                undecided = undecided || h == 0;
                continue;
            }
            std::vector<root> roots;
            if (!slide_angles(pl, roots, a.why)) {
                undecided = true;
                continue;
            }
            a.real_roots = static_cast<int>(roots.size());
            for (const root& r : roots) {
                p_.set_angle(r.c, r.s, r.err);
                const int h = holds(pl, a.why);
                if (h > 0)
                    holding.push_back({ci, true, r.c, r.s, r.err});
                undecided = undecided || h == 0;
            }
        }
        if (undecided) {
            a.kind = answer::undecided;
            return a;
        }
        if (holding.size() != 1) {
            a.kind = holding.empty() ? answer::none : answer::several;
            return a;
        }
        const holding_case& hc = holding[0];
        const plan& pl = plans_[hc.index];
        if (hc.angle)
            p_.set_angle(hc.c, hc.s, hc.err);
        p_.run(pl.output_order);
        a.kind = answer::ok;
        a.case_index = hc.index;
        a.regime = f_.cases[hc.index].kind;
        for (int o : pl.outputs) {
            a.values.push_back(p_.value(o));
            a.out.push_back(cln::double_approx(p_.value(o)));
            a.errors.push_back(p_.error(o));
        }
        return a;
    }

    /// For a disagreement's report: every candidate (each real root of g for a 3-D slide)
    /// with its conditions' values and error bounds.
    std::string describe(const double* x)
    {
        std::ostringstream t;
        t.precision(6);
        p_.begin(x);
        auto conditions = [&](const plan& pl) {
            p_.run(pl.condition_order);
            for (std::size_t k = 0; k < pl.conditions.size(); ++k)
                t << "    " << pl.meaning[k] << ": " << cln::double_approx(p_.value(pl.conditions[k])) << " (error bound "
                  << p_.error(pl.conditions[k]) << ")\n";
        };
        for (std::size_t ci = 0; ci < plans_.size(); ++ci) {
            const plan& pl = plans_[ci];
            t << "  " << f_.cases[ci].name << ":\n";
            if (!pl.needs_angle) {
                conditions(pl);
                continue;
            }
            std::vector<root> roots;
            std::string why;
            if (!slide_angles(pl, roots, why)) {
                t << "    " << why << "\n";
                continue;
            }
            for (const root& r : roots) {
                t << "   at the angle " << std::atan2(cln::double_approx(r.s), cln::double_approx(r.c)) << " rad (error bound "
                  << r.err << "):\n";
                p_.set_angle(r.c, r.s, r.err);
                conditions(pl);
            }
        }
        return t.str();
    }

    /// A condition's value must exceed this times its error bound to be decided.
    static constexpr double margin = 1e20;

private:
    struct plan {
        bool needs_angle = false;
        std::vector<int> conditions; ///< value > 0 or >= 0 (decided alike: a value is never exactly 0 here)
        std::vector<std::string> meaning;
        std::vector<int> condition_order, outputs, output_order;
        int g = -1;
        std::vector<int> g_order;
    };
    struct root {
        cln::cl_F c, s; ///< cos and sin of the sliding angle
        double err;     ///< a bound on the error of each
    };
    using cplx = std::complex<double>;

    // +1: the case holds; -1: a condition fails; 0: none fails but one cannot be decided.
    // (Every condition is decided by its value: a value within its error bound of 0 is
    // too close, strict or not -- exactly 0 cannot be told from a tiny value.)
    int holds(const plan& pl, std::string& why)
    {
        p_.run(pl.condition_order);
        int result = 1;
        for (std::size_t k = 0; k < pl.conditions.size(); ++k) {
            const int s = p_.sign(pl.conditions[k], margin);
            if (s < 0)
                return -1;
            if (s == 0) {
                result = 0;
                why = "the condition " + pl.meaning[k] + " is too close to its boundary";
            }
        }
        return result;
    }

    // The real roots of g on the circle, as cos and sin of the angle with error bounds.
    // False (why says it) when they cannot be told apart or counted.
    bool slide_angles(const plan& pl, std::vector<root>& roots, std::string& why)
    {
        const double u = p_.unit();
        // g at the five angles
        std::array<cln::cl_F, 5> g;
        double gerr = 0, gsize = 0;
        for (int k = 0; k < 5; ++k) {
            p_.set_angle(ck_[k], sk_[k], u);
            p_.run(pl.g_order);
            g[k] = p_.value(pl.g);
            gerr += p_.error(pl.g);
            gsize += p_.magnitude(pl.g);
        }
        if (!(gerr < std::numeric_limits<double>::infinity())) {
            why = "the sliding equation cannot be evaluated";
            return false;
        }
        // g(phi0 + th) = a0 + a1 cos th + b1 sin th + a2 cos 2th + b2 sin 2th
        cln::cl_F a0 = g[0], a1 = g[0] * c1_[0], b1 = g[0] * s1_[0], a2 = g[0] * c2_[0], b2 = g[0] * s2_[0];
        for (int k = 1; k < 5; ++k) {
            a0 = a0 + g[k];
            a1 = a1 + g[k] * c1_[k];
            b1 = b1 + g[k] * s1_[k];
            a2 = a2 + g[k] * c2_[k];
            b2 = b2 + g[k] * s2_[k];
        }
        const cln::cl_F& two = small_[2], four = small_[4], six = small_[6], five = small_[5];
        a0 = a0 / five;
        a1 = two * a1 / five;
        b1 = two * b1 / five;
        a2 = two * a2 / five;
        b2 = two * b2 / five;
        // each coefficient within (2/5) sum |error of g_k| plus the rounding of the sums
        const double ce = 0.4 * gerr + 16 * u * gsize;
        // t = tan(th / 2): (1 + t^2)^2 g is the quartic q4 t^4 + ... + q0
        std::array<cln::cl_F, 5> q = {a0 + a1 + a2, two * b1 + four * b2, two * a0 - six * a2, two * b1 - four * b2, a0 - a1 + a2};
        std::array<double, 5> qm{}, qe{};
        double Q = 0, QE = 0;
        for (int i = 0; i < 5; ++i) {
            qm[i] = std::fabs(cln::double_approx(q[static_cast<std::size_t>(i)]));
            qe[i] = 9 * ce + 16 * u * 6 * gsize; // |multipliers| <= 8, plus rounding
            Q = std::max(Q, qm[i]);
            QE = std::max(QE, qe[i]);
        }
        if (!(Q > margin * QE)) {
            why = "the sliding equation vanishes for every direction, within its rounding";
            return false;
        }
        if (!(qm[4] > 1e-20 * Q)) {
            why = "a root of the sliding equation at phi0 + pi (t infinite)";
            return false;
        }
        // Aberth's method in complex doubles, on the monic quartic.
        std::array<double, 4> b{};
        for (int i = 0; i < 4; ++i)
            b[static_cast<std::size_t>(i)] = cln::double_approx(q[static_cast<std::size_t>(i)] / q[4]);
        double R = 0; // Fujiwara's bound on the roots
        for (int i = 0; i < 4; ++i)
            R = std::max(R, std::pow(std::fabs(b[static_cast<std::size_t>(i)]) * (i == 0 ? 0.5 : 1.0), 1.0 / (4 - i)));
        R = 2 * std::max(R, 1e-300);
        std::array<cplx, 4> z;
        for (int k = 0; k < 4; ++k)
            z[static_cast<std::size_t>(k)] = std::polar(R, 0.4 + 1.5707963267948966 * k);
        for (int it = 0; it < 500; ++it) {
            double largest = 0;
            for (std::size_t k = 0; k < 4; ++k) {
                cplx pv = 1, dp = 0;
                for (int i = 3; i >= 0; --i) {
                    dp = dp * z[k] + pv;
                    pv = pv * z[k] + b[static_cast<std::size_t>(i)];
                }
                if (pv == cplx(0))
                    continue;
                cplx sum = 0;
                for (std::size_t j = 0; j < 4; ++j)
                    if (j != k)
                        sum += 1.0 / (z[k] - z[j] + cplx(1e-300));
                const cplx ratio = pv / dp;
                const cplx w = ratio / (1.0 - ratio * sum);
                if (std::isfinite(w.real()) && std::isfinite(w.imag())) {
                    z[k] -= w;
                    largest = std::max(largest, std::abs(w) / (1 + std::abs(z[k])));
                } else {
                    z[k] += cplx(1e-3 * R, 1e-3 * R); // off a stationary point
                    largest = 1;
                }
            }
            if (largest < 1e-14)
                break;
        }
        // Newton's method in complex long floats on the quartic itself, then each root's
        // error bound: (the error of p at z) / |p'(z)|, doubled, plus the last step.
        const cln::float_format_t fmt = p_.format();
        struct polished {
            cln::cl_F re, im;
            double re_d, im_d, bound;
        };
        std::vector<polished> all;
        for (std::size_t k = 0; k < 4; ++k) {
            cln::cl_F re = exactly(z[k].real(), fmt), im = exactly(z[k].imag(), fmt);
            // the error of p at a point of size zm: the coefficients' errors plus rounding
            auto p_error = [&](double zm) {
                double perr = 0, psize = 0, zi = 1;
                for (std::size_t i = 0; i < 5; ++i) {
                    perr += qe[i] * zi;
                    psize += qm[i] * zi;
                    zi *= zm;
                }
                return perr + 16 * u * psize;
            };
            double step = std::numeric_limits<double>::infinity(), noise = 0;
            bool converged = false;
            for (int it = 0; it < 16 && !converged; ++it) {
                cln::cl_F pr = q[4], pim = cln::cl_float(0, fmt), dr = cln::cl_float(0, fmt), di = dr;
                for (int i = 3; i >= 0; --i) {
                    const cln::cl_F ndr = dr * re - di * im + pr, ndi = dr * im + di * re + pim;
                    dr = ndr;
                    di = ndi;
                    const cln::cl_F npr = pr * re - pim * im + q[static_cast<std::size_t>(i)], npi = pr * im + pim * re;
                    pr = npr;
                    pim = npi;
                }
                const cln::cl_F den = dr * dr + di * di;
                if (cln::zerop(den))
                    break;
                const double zm = std::hypot(cln::double_approx(re), cln::double_approx(im));
                const double dpm = std::sqrt(cln::double_approx(den));
                noise = p_error(zm) / dpm; // how far the root may be from here, to first order
                const cln::cl_F wr = (pr * dr + pim * di) / den, wi = (pim * dr - pr * di) / den;
                re = re - wr;
                im = im - wi;
                step = std::hypot(cln::double_approx(wr), cln::double_approx(wi));
                // done when the step is below the rounding of z, or below what p's error
                // leaves undetermined anyway
                converged = step <= std::max(std::ldexp(1.0, 8 - p_.bits()) * (1 + zm), noise);
            }
            if (!converged || !(noise < std::numeric_limits<double>::infinity())) {
                why = "Newton's method does not converge on a root of the sliding equation";
                return false;
            }
            const double bound = 2 * noise + step;
            all.push_back({re, im, cln::double_approx(re), cln::double_approx(im), bound});
        }
        // Distinct roots (a double root is two sliding directions merging: too close), then
        // real (imaginary part within the bound: its conjugate, another root, would lie
        // within twice that) or complex (far beyond it).
        for (std::size_t i = 0; i < all.size(); ++i)
            for (std::size_t j = i + 1; j < all.size(); ++j)
                if (!(std::hypot(all[i].re_d - all[j].re_d, all[i].im_d - all[j].im_d) > 1e5 * std::max(all[i].bound, all[j].bound))) {
                    why = "two roots of the sliding equation too close to tell apart";
                    return false;
                }
        for (const polished& r : all) {
            const double im = std::fabs(r.im_d);
            if (im > 1e4 * r.bound)
                continue; // complex
            if (!(im <= 1e2 * r.bound) || !(r.bound < 1e-10)) {
                why = "a root of the sliding equation neither clearly real nor clearly complex";
                return false;
            }
            // t real: cos and sin of phi = phi0 + 2 atan t
            const cln::cl_F& t = r.re;
            const cln::cl_F t2 = t * t, den = small_[1] + t2;
            const cln::cl_F ct = (small_[1] - t2) / den, st = small_[2] * t / den;
            const double td = r.re_d;
            const double angle_err = (2 * r.bound) / (1 + td * td) + 16 * u;
            roots.push_back({cos0_ * ct - sin0_ * st, sin0_ * ct + cos0_ * st, angle_err});
        }
        return true;
    }

    program p_;
    impactgen::friction_solution f_;
    std::vector<plan> plans_;
    cln::cl_F cos0_, sin0_;
    std::array<cln::cl_F, 5> ck_, sk_, c1_, s1_, c2_, s2_;
    std::array<cln::cl_F, 9> small_; ///< 0, 1, ..., 8 as long floats
};

} // namespace cln_closed_form
