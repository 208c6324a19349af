// make_sheet(): the variants of a problem (see exercises.hpp for the rules).
#include "exercises/detail.hpp"
#include "symbolic/contact_law.hpp"

#include "figure/figure.hpp"
#include "print/answer.hpp"
#include "print/title.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/named_systems.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>

namespace impactgen::exercises
{
using namespace GiNaC;

namespace
{

/// xorshift64*: the sheet's own generator, the same numbers on every platform.
struct generator {
    std::uint64_t state;
    explicit generator(std::uint64_t seed) : state(seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL)
    {
        if (state == 0)
            state = 1;
    }
    std::uint64_t next()
    {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        return state * 0x2545F4914F6CDD1DULL;
    }
    std::size_t below(std::size_t n) { return static_cast<std::size_t>((next() >> 11) % n); }
    numeric pick(const std::vector<numeric> &from) { return from[below(from.size())]; }
};

/// The number of one significant digit nearest to x (keeps its sign; 0 stays 0).
numeric one_digit(const numeric &x)
{
    if (x.is_zero())
        return 0;
    const double a = std::abs(x.to_double());
    int k = static_cast<int>(std::floor(std::log10(a)));
    long d = std::lround(a / std::pow(10.0, k));
    if (d >= 10) {
        d = 1;
        ++k;
    }
    if (d < 1)
        d = 1;
    const numeric r = k >= 0 ? numeric(d) * numeric(10).power(k) : numeric(d) / numeric(10).power(-k);
    return x.is_negative() ? -r : r;
}

/// A value of the problem as an exact number (the figure's illustrative values are decimals).
numeric exact(const ex &e)
{
    const ex v = e.evalf();
    if (is_a<numeric>(e) && ex_to<numeric>(e).is_rational())
        return ex_to<numeric>(e);
    if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real())
        return 0;
    return numeric(std::lround(ex_to<numeric>(v).to_double() * 1000), 1000);
}

bool has_symbols(const ex &e)
{
    return !is_a<numeric>(e.evalf());
}

const std::vector<numeric> &factors()
{
    static const std::vector<numeric> f = {numeric(1, 2), numeric(2, 3), 1, numeric(3, 2), 2};
    return f;
}

const std::vector<numeric> &restitutions()
{
    static const std::vector<numeric> e = {0, numeric(1, 4), numeric(1, 2), numeric(3, 4), 1};
    return e;
}

const std::vector<numeric> &frictions()
{
    static const std::vector<numeric> mu = {
        numeric(1, 10), numeric(1, 5), numeric(1, 4), numeric(1, 3), numeric(1, 2), numeric(3, 4), 1};
    return mu;
}

/// A short fraction: what a person writes down (denominator and numerator bounded).
bool short_fraction(const ex &e, long max_denominator)
{
    if (!is_a<numeric>(e) || !ex_to<numeric>(e).is_rational())
        return false;
    const numeric &q = ex_to<numeric>(e);
    return q.denom() <= max_denominator && abs(q.numer()) <= numeric(99999);
}

struct solved {
    derivation d;
    regime_case c;
};

std::optional<solved> solve_numeric(const problem &q)
{
    try {
        validate(q);
        derivation d = derive(q);
        regime_case c = select_candidate(d, solve_impact(d));
        return solved{std::move(d), std::move(c)};
    } catch (const std::exception &) {
        return std::nullopt; // not an impact, no single regime: another draw
    }
}

ex normal_impulse(const solved &s)
{
    return impactgen::tidy(s.c.sol.expand_steps(s.c.sol.normal_impulse));
}

/// The problem's numbers as the variants start from them: its own, or for symbols the
/// figure's illustrative values made exact; numbered bodies named "body 1", "body 2".
problem numeric_base(const problem &base)
{
    problem p = base;
    // the figure's illustrative decimals made exact first, so that expressions in them
    // (a rod's m l^2/12) stay exact
    exmap values = figure::schematic_values(base);
    for (auto &kv : values)
        kv.second = exact(kv.second);
    // A named system class has a worked example (numbers for every symbol, velocities
    // included): the schematic values of its figure alone leave it at rest.
    for (const ex &eq : system_class_example_values(base.source))
        values[eq.lhs()] = exact(eq.rhs());
    auto put = [&](ex &x) {
        if (!values.empty())
            x = x.subs(values);
        if (has_symbols(x))
            x = 1;
        x = exact(x);
    };
    for_each_value(p, put);
    for (body &b : p.bodies)
        if (b.numbered) {
            b.name = b.label = "body " + b.name;
            b.numbered = false;
        }
    return p;
}

/// A new mass for a body of finite mass, its inertia scaled with it.
void draw_mass(body &b, generator &g)
{
    if (b.infinite_mass)
        return;
    const numeric m0 = ex_to<numeric>(b.mass), m = one_digit(m0 * g.pick(factors()));
    b.mass = m;
    for (auto &row : b.inertia)
        for (ex &x : row)
            x = ex_to<numeric>(x) * m / m0;
}

/// The body's velocity and spin times f.
void scale_motion(body &b, const numeric &f)
{
    for (int k = 0; k < 3; ++k) {
        b.velocity[k] = ex_to<numeric>(b.velocity[k]) * f;
        b.angular_velocity[k] = ex_to<numeric>(b.angular_velocity[k]) * f;
    }
}

/// A system's variant: new masses (inertias scaled with them), e and mu per contact, and every
/// velocity and spin scaled by one factor, which keeps the joints together before impact.
problem draw_system_values(const problem &p0, generator &g)
{
    problem q = p0;
    const numeric f = g.pick({numeric(1, 2), 1, 2});
    for (body &b : q.bodies) {
        draw_mass(b, g);
        scale_motion(b, f);
    }
    q.restitution = g.pick(restitutions());
    for (contact_spec &c : q.contacts) {
        if (c.own_restitution)
            c.restitution = g.pick(restitutions());
        if (!c.friction().is_zero())
            c.set_friction(g.pick(frictions()));
    }
    return q;
}

/// New masses, speeds, spins, e and mu for one variant (geometry kept).
problem draw_values(const problem &orig, const problem &p0, const std::string &regime, generator &g)
{
    if (p0.is_system())
        return draw_system_values(p0, g);
    problem q = p0;
    for (std::size_t i = 0; i < q.bodies.size(); ++i) {
        body &b = q.bodies[i];
        const body &o = orig.bodies[i];
        draw_mass(b, g);
        if (q.pivot_of(i)) { // a pinned body's motion is one: scaled as a whole, still about its pivot
            const numeric f = g.pick({numeric(1, 2), 1, 2});
            scale_motion(b, f);
            continue;
        }
        double speed = 0;
        for (int k = 0; k < 3; ++k) {
            const numeric v0 = ex_to<numeric>(b.velocity[k]);
            speed = std::max(speed, std::abs(v0.to_double()));
            b.velocity[k] = one_digit(v0 * g.pick(factors()));
        }
        if (b.particle)
            continue;
        // A spin given by a symbol gets a size from the speed and the lever |C - O|, and a sign.
        double lever = 0;
        for (int k = 0; k < 3; ++k)
            lever = std::max(lever, std::abs(ex_to<numeric>(b.position[k] - q.contact().point[k]).to_double()));
        for (int k = 0; k < 3; ++k) {
            const numeric w0 = ex_to<numeric>(b.angular_velocity[k]);
            if (!w0.is_zero())
                b.angular_velocity[k] = one_digit(w0 * g.pick(factors()));
            else if (has_symbols(o.angular_velocity[k]) && speed > 0 && lever > 0)
                b.angular_velocity[k] =
                    one_digit(numeric(std::lround(1000 * speed / lever), 1000) * g.pick(factors())) *
                    (g.below(2) ? 1 : -1);
        }
    }
    q.restitution = g.pick(restitutions());
    // With a coefficient of friction: sticking needs mu above a threshold, sliding below it, so mu is
    // drawn from that end.
    if (!q.contact().friction().is_zero()) {
        const std::vector<numeric> &all = frictions();
        const std::vector<numeric> high(all.begin() + 4, all.end()), low(all.begin(), all.begin() + 4);
        q.contact().set_friction(g.pick(regime == "stick" ? high : regime == "slide" ? low : all));
    }
    return q;
}

/// The velocity component that drives the approach: of a free movable body of the contact,
/// the non-zero one most nearly along the normal. false when there is none.
bool driving_slot(const problem &q, std::size_t &body_index, int &component)
{
    double best = 0;
    for (const std::size_t i : {q.contact().body1, q.contact().body2}) {
        if (q.immovable(i) || q.pivot_of(i))
            continue;
        for (int k = 0; k < q.dimension; ++k) {
            const double n = std::abs(exact(q.contact().normal[k]).to_double());
            if (!q.bodies[i].velocity[k].is_zero() && n > best + 1e-12) {
                best = n;
                body_index = i;
                component = k;
            }
        }
    }
    return best > 0;
}

/// Back-generation: the driving velocity chosen so that N is a number of one digit near its
/// value (N is linear in that velocity while the regime stays).
void back_generate(problem &q, generator &g)
{
    std::size_t i = 0;
    int k = 0;
    if (!driving_slot(q, i, k))
        return;
    const std::optional<solved> s0 = solve_numeric(q);
    if (!s0)
        return;
    problem q1 = q;
    const numeric x0 = ex_to<numeric>(q.bodies[i].velocity[k]);
    q1.bodies[i].velocity[k] = x0 + 1;
    const std::optional<solved> s1 = solve_numeric(q1);
    if (!s1 || s1->c.kind != s0->c.kind || s1->c.sign != s0->c.sign)
        return;
    const ex n0 = normal_impulse(*s0), n1 = normal_impulse(*s1);
    if (!is_a<numeric>(n0) || !is_a<numeric>(n1) || (n1 - n0).is_zero())
        return;
    const numeric target = one_digit(ex_to<numeric>(n0) * g.pick(factors()));
    const numeric x = x0 + (target - ex_to<numeric>(n0)) / ex_to<numeric>(n1 - n0);
    // a speed of at most two decimals (denominator dividing 100) within a factor 4 of the drawn one
    if (x.is_zero() || x.csgn() != x0.csgn() || !short_fraction(x, 100) || !irem(numeric(100), x.denom()).is_zero() ||
        abs(x) > abs(x0) * 4 || abs(x) * 4 < abs(x0))
        return;
    q.bodies[i].velocity[k] = x;
}

/// A variant solved: one contact through the candidate that holds, a system through its law.
std::optional<detail::outcome> outcome_of(const problem &q)
{
    if (q.is_system())
        return detail::system_outcome(q);
    const std::optional<solved> s = solve_numeric(q);
    if (!s)
        return std::nullopt;
    detail::outcome o;
    o.regime = regime_name(s->c.kind);
    o.key = o.regime + std::to_string(s->c.sign);
    o.asked = asked_quantities(s->d, s->c);
    o.answer = print::answer_json(s->d, s->c, false);
    return o;
}

/// The regime is the one asked for (a system: the set of regimes of the problem as given, when it
/// has one), and it stays the same with every mu a third larger or smaller (far from a boundary).
bool regime_kept(const problem &q, const detail::outcome &o, const std::string &regime, const std::string &key)
{
    if (!regime.empty() && regime != o.regime)
        return false;
    if (!key.empty() && key != o.key)
        return false;
    bool friction = false;
    for (const contact_spec &c : q.contacts)
        friction = friction || !c.friction().is_zero();
    if (!friction)
        return true;
    for (const numeric &f : {numeric(3, 4), numeric(4, 3)}) {
        problem near = q;
        for (contact_spec &c : near.contacts)
            if (!c.friction().is_zero())
                c.set_friction(ex_to<numeric>(c.friction()) * f);
        const std::optional<detail::outcome> t = outcome_of(near);
        if (!t || t->key != o.key)
            return false;
    }
    return true;
}

std::size_t digits(const numeric &n)
{
    std::ostringstream os;
    os << abs(n);
    return os.str().size();
}

/// How long the asked answers are to write: 0 when every one is a short fraction, else the
/// digits of their numerators and denominators (an irrational answer counts as 40 digits).
std::size_t answer_length(const detail::outcome &o)
{
    std::size_t len = 0;
    bool all_short = true;
    for (const quantity &a : o.asked) {
        all_short = all_short && short_fraction(a.exact, a.pointer == "/kinetic_energy/lost" ? 2000 : 200);
        if (is_a<numeric>(a.exact) && ex_to<numeric>(a.exact).is_rational()) {
            const numeric &q = ex_to<numeric>(a.exact);
            len += digits(q.numer()) + digits(q.denom());
        } else
            len += 40;
    }
    return all_short ? 0 : len + 1;
}

/// The regimes the problem can have: smooth without friction, else its candidates' kinds.
std::set<std::string> possible_regimes(const problem &p0)
{
    std::set<std::string> out;
    if (law_traits_of(p0).single_candidate)
        return {"smooth"};
    const derivation d = derive(p0);
    for (const regime_case &c : solve_impact(d).cases)
        out.insert(regime_name(c.kind));
    return out;
}

std::string two_digits(std::size_t k)
{
    return (k < 10 ? "0" : "") + std::to_string(k);
}

/// The search for the variants of one sheet: draws until one has short answers, the regime
/// asked for, and is new on the sheet. When the attempts or the sheet's work units run out first,
/// the variant with the shortest answers among those drawn serves (its answers are then given as
/// decimals); only when no draw kept the regime is the sheet refused. What is drawn depends on
/// counts only, never on the clock: options::seconds is a safety net that refuses the sheet.
struct variant_search {
    const problem &base;
    const problem &p0;
    const options &opt;
    generator &g;
    std::set<std::string> seen;
    std::chrono::steady_clock::time_point start;
    std::string set_key;    ///< a system: the key of the problem's own set of regimes, kept by every variant
    long units_left = 0;    ///< work units for draws past the 8 of each exercise
    long draw_cost = 1;     ///< draw_units(p0)
    int short_of_draws = 0; ///< exercises whose draws ran out before short answers

    /// Another draw for this exercise: its first 8, then while the attempts and the units last.
    bool may_draw(int attempt)
    {
        if (opt.seconds > 0 &&
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > opt.seconds) {
            std::ostringstream s;
            s << opt.seconds;
            throw input_error("exercises: the search for variants ran past its safety net of " + s.str() +
                              " s (options::seconds); no sheet is given, since a shorter search would "
                              "give other variants than the same seed gives elsewhere");
        }
        if (attempt >= opt.attempts)
            return false;
        if (attempt < 8)
            return true;
        if (units_left < draw_cost)
            return false;
        units_left -= draw_cost;
        return true;
    }

    /// The exercise of a kept problem: the problem file read back is the exercise, so what a
    /// student is given is what is solved.
    std::optional<exercise> make(const problem &q, int k) const
    {
        exercise ex;
        ex.prob =
            read_problem(problem_json(q).dump(2), "problems/" + two_digits(static_cast<std::size_t>(k)) + ".json");
        const std::optional<detail::outcome> r = outcome_of(ex.prob);
        if (!r)
            return std::nullopt;
        ex.regime = r->regime;
        ex.asked = r->asked;
        ex.answer = r->answer;
        return ex;
    }

    exercise next(int k, const std::string &title)
    {
        std::optional<problem> fallback;
        std::string fallback_key;
        std::size_t fallback_length = 0;
        int attempt = 0;
        for (; may_draw(attempt); ++attempt) {
            if (opt.before_draw)
                opt.before_draw();
            problem q = draw_values(base, p0, opt.regime, g);
            q.units = base.units.empty() ? "SI" : base.units;
            if (!q.is_system())
                back_generate(q, g);
            q.title = "Exercise " + std::to_string(k) + ": " + title;
            q.description.clear();
            const std::optional<detail::outcome> s = outcome_of(q);
            if (!s || !regime_kept(q, *s, opt.regime, set_key))
                continue;
            problem untitled = q;
            untitled.title.clear();
            const std::string key = problem_json(untitled).dump();
            if (seen.count(key))
                continue;
            const std::size_t length = answer_length(*s);
            if (length == 0) {
                if (std::optional<exercise> ex = make(q, k)) {
                    seen.insert(key);
                    return std::move(*ex);
                }
            } else if (!fallback || length < fallback_length) {
                fallback = q;
                fallback_key = key;
                fallback_length = length;
            }
        }
        ++short_of_draws;
        if (fallback)
            if (std::optional<exercise> ex = make(*fallback, k)) {
                seen.insert(fallback_key);
                return std::move(*ex);
            }
        throw input_error("exercises: no variant " +
                          std::string(opt.regime.empty() ? "" : "with regime " + opt.regime + " ") + "found in " +
                          std::to_string(attempt) + " draws for exercise " + std::to_string(k) +
                          " (every draw left the regime or was not an impact; try another --seed)");
    }
};

} // namespace

int draw_units(const problem &p)
{
    // Measured (impactgen exercises, --count 10, a loaded 2-core machine): a system's draw about
    // 1 ms, one contact's 1 to 4 ms, with friction 4 to 5 ms, in 3-D with friction (its slide
    // solved through an angle equation) 10 to 85 ms.
    if (p.is_system())
        return 1;
    if (law_traits_of(p).single_candidate)
        return 3;
    return p.dimension == 3 ? 100 : 6;
}

sheet make_sheet(const problem &base, const options &opt)
{
    if (opt.count < 1 || opt.count > 99)
        throw input_error("--count: " + std::to_string(opt.count) + " exercises asked; a sheet has 1 to 99");
    if (!opt.regime.empty() && opt.regime != "smooth" && opt.regime != "stick" && opt.regime != "slide")
        throw input_error("--regime: \"" + opt.regime + "\" is not a regime (smooth, stick or slide)");
    if (base.is_system() && !opt.regime.empty())
        throw input_error("--regime " + opt.regime +
                          ": a system's variants keep the set of regimes of the problem as "
                          "given (each contact's own); --regime is for one contact");
    const problem p0 = numeric_base(base);
    if (!opt.regime.empty()) {
        const std::set<std::string> can = possible_regimes(p0);
        if (!can.count(opt.regime)) {
            std::string list;
            for (const std::string &r : can)
                list += (list.empty() ? "" : ", ") + r;
            throw input_error(
                "--regime " + opt.regime + ": this problem cannot have it (" +
                (law_traits_of(p0).single_candidate ? "it has no friction; its regime is " : "its regimes are ") +
                list + ")");
        }
    }
    sheet out;
    // the problem's title, else a person's name for it (never a path)
    out.title = !base.title.empty() ? base.title : print::class_name_in_words(base.source);
    if (out.title.empty())
        out.title = print::source_stem(base.source);
    out.units = true;
    generator g(opt.seed);
    variant_search search{base, p0, opt, g, {}, std::chrono::steady_clock::now(), {}, 0, draw_units(p0), 0};
    search.units_left = opt.units > 0 ? opt.units : sheet_units;
    if (base.is_system())
        if (const std::optional<detail::outcome> own = outcome_of(p0))
            search.set_key = own->key;
    for (int k = 1; k <= opt.count; ++k)
        out.exercises.push_back(search.next(k, out.title));
    out.short_of_draws = search.short_of_draws;
    out.units = out.exercises.front().prob.units == "SI";
    return out;
}

} // namespace impactgen::exercises
