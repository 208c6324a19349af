// Random valid problems and their mutations. The generator keeps a double
// value next to every value it writes, only to make sure the contact points
// approach ((v_B - v_A).n < 0) so that the seeds reach the solver; the checks
// never use these doubles (they read the problem with the project's reader).
// The hostile values and names are the ones a user, a script or a corrupted
// file can produce: expressions that are not real, not finite, not decidable
// or huge, wrong JSON types, names that would break C++, LaTeX or a one-line
// message, and structural damage (missing keys, repeated bodies, wrong
// dimension, vectors of the wrong length).
#include "mutate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace impactgen::fuzz {

namespace {

constexpr double pi = 3.14159265358979323846;

// Raw number tokens are written as strings with this prefix, then unquoted by serialise().
const std::string raw_prefix = "@@impactgen-fuzz-raw@@";

json raw(const std::string& token) { return raw_prefix + token; }

std::size_t pick(engine& rng, std::size_t n)
{
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
}

long between(engine& rng, long lo, long hi) { return std::uniform_int_distribution<long>(lo, hi)(rng); }

bool chance(engine& rng, double p) { return std::uniform_real_distribution<double>(0, 1)(rng) < p; }

template <typename T> const T& one_of(engine& rng, const std::vector<T>& items) { return items[pick(rng, items.size())]; }

// A value as written in the file, and its value as a double (for the approach test only).
struct value {
    json text;
    double v;
};

struct irrational {
    const char* text;
    double v;
};

const std::vector<irrational>& irrationals()
{
    static const std::vector<irrational> list = {
        {"sqrt(2)", std::sqrt(2.0)}, {"sqrt(3)", std::sqrt(3.0)}, {"sqrt(5)", std::sqrt(5.0)},
        {"Pi", pi},                {"exp(1)", std::exp(1.0)},   {"cos(1)", std::cos(1.0)},
        {"log(3)", std::log(3.0)},   {"atan(2)", std::atan(2.0)},
    };
    return list;
}

// A number in [lo, hi] written as an integer, a decimal, "p/q" or "p*X/q" with X irrational.
value number(engine& rng, double lo, double hi)
{
    double target = std::uniform_real_distribution<double>(lo, hi)(rng);
    switch (pick(rng, 8)) {
    case 0:
    case 1: {
        long k = std::lround(target);
        if (k < lo || k > hi)
            break;
        return {json(k), static_cast<double>(k)};
    }
    case 2:
    case 3: { // quarters and tenths: exact decimals
        double q = chance(rng, 0.5) ? 4 : 10;
        double x = std::round(target * q) / q;
        if (x < lo || x > hi)
            break;
        return {json(x), x};
    }
    case 4:
    case 5: {
        static const std::vector<long> dens = {3, 7, 9, 11, 12};
        long q = one_of(rng, dens), p = std::lround(target * static_cast<double>(q));
        double x = static_cast<double>(p) / static_cast<double>(q);
        if (x < lo || x > hi)
            break;
        return {json(std::to_string(p) + "/" + std::to_string(q)), x};
    }
    default: {
        static const std::vector<std::pair<const char*, double>> fixed = {
            {"1/3", 1.0 / 3}, {"sqrt(2)/2", std::sqrt(2.0) / 2}, {"Pi/4", pi / 4}, {"2*sqrt(3)", 2 * std::sqrt(3.0)},
            {"-sqrt(2)/2", -std::sqrt(2.0) / 2}, {"-1/3", -1.0 / 3}, {"3/2 - sqrt(2)", 1.5 - std::sqrt(2.0)}};
        if (chance(rng, 0.4)) {
            const auto& f = one_of(rng, fixed);
            if (f.second >= lo && f.second <= hi)
                return {json(f.first), f.second};
        }
        const irrational& x = one_of(rng, irrationals());
        long q = between(rng, 1, 4), p = std::lround(target * static_cast<double>(q) / x.v);
        double v = static_cast<double>(p) * x.v / static_cast<double>(q);
        if (p == 0 || v < lo || v > hi)
            break;
        std::string t = (p == 1 ? std::string() : p == -1 ? std::string("-") : std::to_string(p) + "*") + x.text;
        if (q != 1)
            t += "/" + std::to_string(q);
        return {json(t), v};
    }
    }
    long k = std::lround((lo + hi) / 2);
    return {json(k), static_cast<double>(k)};
}

using vec = std::array<double, 3>;

struct vector_value {
    json text = json::array();
    vec v{0, 0, 0};
};

vector_value random_vector(engine& rng, int dim, double lo, double hi)
{
    vector_value r;
    for (int c = 0; c < dim; ++c) {
        value x = number(rng, lo, hi);
        r.text.push_back(x.text);
        r.v[c] = x.v;
    }
    return r;
}

vector_value zero_vector(int dim)
{
    vector_value r;
    for (int c = 0; c < dim; ++c)
        r.text.push_back(0);
    return r;
}

vector_value random_normal(engine& rng, int dim)
{
    static const std::vector<std::vector<double>> planar = {{1, 0}, {0, 1}, {3, 4}, {-3, 4}, {1, 1}, {1, -2}, {5, 12}, {-1, 0}, {0.6, 0.8}};
    static const std::vector<std::vector<double>> spatial = {{1, 2, 2}, {0, 0, 1}, {2, -1, 2}, {1, 1, 1}, {0, -1, 0},
                                                             {2, 3, 6}, {1, 0, 0}, {0.3, -0.4, 1.2}, {4, 4, 7}};
    vector_value r;
    if (chance(rng, 0.15)) { // a unit normal written with square roots
        const double h = std::sqrt(2.0) / 2;
        if (dim == 2) {
            r.text = json::array({"sqrt(2)/2", "-sqrt(2)/2"});
            r.v = {h, -h, 0};
        } else {
            r.text = json::array({"sqrt(2)/2", 0, "sqrt(2)/2"});
            r.v = {h, 0, h};
        }
        return r;
    }
    if (chance(rng, 0.2)) { // random small integers, not all zero
        do {
            r = vector_value();
            for (int c = 0; c < dim; ++c) {
                long x = between(rng, -3, 3);
                r.text.push_back(x);
                r.v[c] = static_cast<double>(x);
            }
        } while (r.v[0] == 0 && r.v[1] == 0 && r.v[2] == 0);
        return r;
    }
    const auto& n = one_of(rng, dim == 2 ? planar : spatial);
    for (int c = 0; c < dim; ++c) {
        double x = n[static_cast<std::size_t>(c)];
        r.text.push_back(x == std::floor(x) ? json(static_cast<long>(x)) : json(x));
        r.v[c] = x;
    }
    return r;
}

enum class kind { particle, rigid, infinite, pinned_rigid, pinned_particle };

struct body_draft {
    kind k = kind::particle;
    json j;
    vec v{0, 0, 0}, w{0, 0, 0}, c{0, 0, 0};
};

vec cross(const vec& a, const vec& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Velocity of the contact point O of a body (a particle's spin does not move it).
vec point_velocity(const body_draft& b, const vec& o)
{
    if (b.k == kind::particle || b.k == kind::pinned_particle)
        return b.v;
    vec r{o[0] - b.c[0], o[1] - b.c[1], o[2] - b.c[2]};
    vec wr = cross(b.w, r);
    return {b.v[0] + wr[0], b.v[1] + wr[1], b.v[2] + wr[2]};
}

json inertia_of(engine& rng, int dim)
{
    if (dim == 2)
        return number(rng, 0.05, 3).text;
    if (chance(rng, 0.5)) {
        json d = json::array();
        for (int c = 0; c < 3; ++c)
            d.push_back(number(rng, 0.05, 3).text);
        return d;
    }
    // A^T A + d 1 with small integer A: symmetric positive-definite, exact.
    int a[3][3];
    for (auto& row : a)
        for (int& x : row)
            x = static_cast<int>(between(rng, -2, 2));
    double d = one_of(rng, std::vector<double>{0.5, 1, 2, 0.25});
    std::string factor = chance(rng, 0.2) ? one_of(rng, std::vector<std::string>{"sqrt(2)", "Pi", "1/3"}) : "";
    json m = json::array();
    for (int r = 0; r < 3; ++r) {
        json row = json::array();
        for (int c = 0; c < 3; ++c) {
            double x = (r == c) ? d : 0;
            for (int k = 0; k < 3; ++k)
                x += a[k][r] * a[k][c];
            json t = x == std::floor(x) ? json(static_cast<long>(x)) : json(x);
            if (!factor.empty())
                t = factor + "*" + t.dump();
            row.push_back(t);
        }
        m.push_back(row);
    }
    return m;
}

kind random_kind(engine& rng)
{
    static const std::vector<std::pair<kind, int>> weights = {
        {kind::particle, 3}, {kind::rigid, 5}, {kind::infinite, 2}, {kind::pinned_rigid, 2}, {kind::pinned_particle, 1}};
    int total = 0;
    for (const auto& w : weights)
        total += w.second;
    int x = static_cast<int>(between(rng, 0, total - 1));
    for (const auto& w : weights) {
        if (x < w.second)
            return w.first;
        x -= w.second;
    }
    return kind::rigid;
}

bool immovable(kind k) { return k == kind::infinite || k == kind::pinned_particle; }
bool pinned(kind k) { return k == kind::pinned_rigid || k == kind::pinned_particle; }

body_draft random_body(engine& rng, kind k, int dim, const std::string& name, json& pivots)
{
    body_draft b;
    b.k = k;
    b.j = json::object();
    b.j["name"] = name;
    b.j["mass"] = k == kind::infinite ? json("inf") : number(rng, 0.1, 10).text;
    if (k == kind::rigid || k == kind::pinned_rigid || (k == kind::infinite && chance(rng, 0.3)))
        b.j["inertia"] = inertia_of(rng, dim);
    else if (chance(rng, 0.15))
        b.j["inertia"] = dim == 3 && chance(rng, 0.5) ? json::array({0, 0, 0}) : json(0);
    vector_value c = random_vector(rng, dim, -2, 2);
    b.j["position"] = c.text;
    b.c = c.v;
    vector_value v = pinned(k) ? zero_vector(dim) : random_vector(rng, dim, -5, 5);
    b.j["velocity"] = v.text;
    b.v = v.v;
    bool spins = !pinned(k) && chance(rng, 0.6);
    if (spins || chance(rng, 0.5)) {
        if (dim == 2) {
            value w = spins ? number(rng, -3, 3) : value{json(0), 0};
            b.j["angular_velocity"] = w.text;
            b.w = {0, 0, w.v};
        } else {
            vector_value w = spins ? random_vector(rng, 3, -3, 3) : zero_vector(3);
            b.j["angular_velocity"] = w.text;
            b.w = w.v;
        }
    }
    if (pinned(k)) // at rest, so any point of it may be the pivot
        pivots.push_back(json{{"body", name}, {"point", random_vector(rng, dim, -2, 2).text}});
    return b;
}

} // namespace

json random_problem(engine& rng, bool* numbers_only)
{
    static const std::vector<std::string> names = {"ball", "rod", "wall", "puck", "block", "bat", "plate", "box", "floor", "cue", "A", "B"};
    for (;;) {
        const int dim = chance(rng, 0.5) ? 2 : 3;
        kind k1 = random_kind(rng), k2 = random_kind(rng);
        if ((immovable(k1) && immovable(k2)) || (pinned(k1) && pinned(k2)))
            continue;
        std::vector<std::string> pool = names;
        std::shuffle(pool.begin(), pool.end(), rng);
        json pivots = json::array();
        body_draft a = random_body(rng, k1, dim, pool[0], pivots);
        body_draft b = random_body(rng, k2, dim, pool[1], pivots);
        vector_value o = random_vector(rng, dim, -1, 1);
        vector_value n = random_normal(rng, dim);
        vec va = point_velocity(a, o.v), vb = point_velocity(b, o.v);
        double approach = 0, length = 0;
        for (int c = 0; c < 3; ++c) {
            approach += (vb[c] - va[c]) * n.v[c];
            length += n.v[c] * n.v[c];
        }
        approach /= std::sqrt(length);
        if (std::abs(approach) < 0.05) // too close to grazing to be sure of its sign from doubles
            continue;
        // Separating: the same pair with the bodies named the other way round approaches.
        if (approach > 0)
            std::swap(a, b);
        json p = json::object();
        if (chance(rng, 0.1))
            p["name"] = "fuzz seed";
        p["dimension"] = dim;
        static const std::vector<json> restitutions = {0, 1, 0.5, 0.8, "1/3", "sqrt(2)/2", 0.25, "2/3", 0.9};
        p["restitution"] = one_of(rng, restitutions);
        json bodies = json::array({a.j, b.j});
        if (chance(rng, 0.25)) { // a bystander that takes no part
            kind k = one_of(rng, std::vector<kind>{kind::particle, kind::rigid, kind::infinite});
            json unused = json::array();
            body_draft c = random_body(rng, k, dim, pool[2], unused);
            bodies.insert(bodies.begin() + static_cast<long>(pick(rng, 3)), c.j);
        } else if (chance(rng, 0.3)) {
            std::swap(bodies[0], bodies[1]);
        }
        p["bodies"] = bodies;
        p["contact"] = json{{"bodies", {a.j["name"], b.j["name"]}}, {"point", o.text}, {"normal", n.text}};
        if (!pivots.empty() || chance(rng, 0.1))
            p["pivots"] = pivots;
        if (numbers_only)
            *numbers_only = true;
        if (chance(rng, 0.08)) { // symbols: formulas, explain and codegen work, solve refuses
            if (numbers_only)
                *numbers_only = false;
            p["restitution"] = "e";
            for (json& body : p["bodies"])
                if (body["mass"] != "inf" && chance(rng, 0.6))
                    body["mass"] = "m_" + body["name"].get<std::string>();
        }
        return p;
    }
}

namespace {

std::string repeat(const std::string& s, int n)
{
    std::string r;
    for (int i = 0; i < n; ++i)
        r += s;
    return r;
}

std::string long_sum(engine& rng, std::size_t length, int distinct)
{
    std::string s;
    while (s.size() < length)
        s += (s.empty() ? "" : "+") + std::string("a") + std::to_string(between(rng, 0, distinct - 1));
    return s;
}

json hostile_value(engine& rng)
{
    switch (pick(rng, 46)) {
    case 0: return "sqrt(2)/2";
    case 1: return "-sqrt(2)/2";
    case 2: return "Pi";
    case 3: return "sqrt(2)-2";
    case 4: return "sin(1)^2+cos(1)^2-1";
    case 5: return "(-1)^(1/3)";
    case 6: return "sin()";
    case 7: return "exp(exp(1000))";
    case 8: return "1e308*10";
    case 9: return raw(one_of(rng, std::vector<std::string>{"1e400", "-1e400", "1e-400", "123456789012345678901234567890", "-0", "1E+2", "0.0000000000000000000001"}));
    case 10: return one_of(rng, std::vector<std::string>{"inf", "-inf", "Infinity", "INF"});
    case 11: return one_of(rng, std::vector<std::string>{"nan", "NaN"});
    case 12: return -1;
    case 13: return 0;
    case 14: return "";
    case 15: return repeat("(", 40) + "1" + repeat(")", 40);
    case 16: return repeat("-", 20) + "1";
    case 17: return long_sum(rng, 2000, 100);
    case 18: // symbols that collide with the closed form's step names, C++ keywords or the header's own names
        return one_of(rng, std::vector<std::string>{"u", "k", "N", "w_1", "class", "i", "x__y", "e", "m1", "T_lost", "int",
                                                    "_x", "Digits", "out", "in", "T", "new", "and", "not", "this", "std",
                                                    "detail", "with_energy_lost", "impact_status", "NULL", "x_", "__y"});
    case 19: return nullptr;
    case 20: return true;
    case 21: return json::array();
    case 22: return json::object();
    case 23: return std::string(5000, 'x');
    case 24: return "2^(2^40)";
    case 25: return "0^0";
    case 26: return "1/0";
    case 27: return "log(0)";
    case 28: return "sqrt(-1)";
    case 29: return "1/(sqrt(2)-sqrt(2))";
    case 30: return "tan(Pi/2)";
    case 31: return "(sqrt(2)+1)*(sqrt(2)-1)-1";
    case 32: return "10^(-300)";
    case 33: return raw(one_of(rng, std::vector<std::string>{"1e300", "1e-300", "2.2250738585072014e-308", "4.9e-324"}));
    case 34: return "x/x";
    case 35: return "abs(x)";
    case 36: return "exp(1000)";
    case 37: return one_of(rng, std::vector<std::string>{"2*/3", "((1)", "1)", "sqrt(2", "3 4", "1,5", "0x10", "1e", "\u00e9", "\t1"});
    case 38: return "asin(2)";
    case 40: return "cosh(700)*sinh(700)";
    default: // symbolic powers and products whose expansion or evaluation explodes
        return one_of(rng, std::vector<std::string>{"x^(10^6)", "x^1000000", "x^999999", "x^50000", "(a+b)^1000",
                                                    "(a+b+c+d+f+g+h+p+q)^12", "x^(-10^6)", "x^(1/1000000)",
                                                    "sqrt(x)^(10^6)", "exp(x)^100000", "sin(x)^100000",
                                                    "(x+y)^40*(x-y)^40", "x^(2^20)", "x^100*y^100*z^100"});
    }
}

json plausible_value(engine& rng)
{
    // Values that keep a problem valid more often than not: edges and extremes of the accepted range.
    static const std::vector<json> list = {0, 1, -1, 2, 0.5, "1/3", "1/1000000", "1000000", "10^(-12)", 1e-9,
                                           "sqrt(2)/2", "Pi", 1e6, "1/7", -3, 1};
    return one_of(rng, list);
}

std::string hostile_name(engine& rng)
{
    static const std::vector<std::string> names = {
        "ball\n#define private public\n//", "a b", "a-b", "class", "NULL", "", "*/", "/*", "\u540d\u524d",
        std::string("x\0y", 3), std::string(300, 'n'), std::string(64, 'q'), std::string(65, 'q'), "1", "2", "x",
        "e", "u", "N", "k", "m1", "\\", "\\end{document}", "$x$", "%", "?\?/", "\"", "'", "a\tb", "\u202e", "\xc3\x28",
        "main", "std", "impactgen", "operator", "__x", "_X", "__LINE__", "x.y", "a,b", "\u00e9t\u00e9", "\U0001F600",
        "$(rm -rf /)", "<script>", "~", "&", "ball ", " ball", "0x", "v_x_ball", "w_1", "impactgen_number_0"};
    return one_of(rng, names);
}

// Every node of the tree except the root.
void nodes(json& j, std::vector<json*>& all)
{
    if (j.is_object())
        for (auto& m : j.items()) {
            all.push_back(&m.value());
            nodes(m.value(), all);
        }
    else if (j.is_array())
        for (auto& x : j) {
            all.push_back(&x);
            nodes(x, all);
        }
}

void leaves(json& j, std::vector<json*>& all)
{
    std::vector<json*> every;
    nodes(j, every);
    for (json* x : every)
        if (x->is_primitive())
            all.push_back(x);
}

std::vector<json*> objects(json& j)
{
    std::vector<json*> all{&j}, r;
    nodes(j, all);
    for (json* x : all)
        if (x->is_object() && !x->empty())
            r.push_back(x);
    return r;
}

json* bodies_of(json& p)
{
    if (p.is_object() && p.contains("bodies") && p["bodies"].is_array() && !p["bodies"].empty())
        return &p["bodies"];
    return nullptr;
}

json negated(const json& x)
{
    if (x.is_number_integer())
        return -x.get<long long>();
    if (x.is_number())
        return -x.get<double>();
    if (x.is_string())
        return "-(" + x.get<std::string>() + ")";
    return x;
}

// Renames a body; references in contact and pivots follow unless `dangling`.
void rename_body(json& p, const std::string& from, const std::string& to, bool dangling)
{
    if (dangling)
        return;
    auto fix = [&](json& ref) {
        if (ref.is_string() && ref.get<std::string>() == from)
            ref = to;
    };
    if (p.contains("contact") && p["contact"].is_object() && p["contact"].contains("bodies") && p["contact"]["bodies"].is_array())
        for (json& ref : p["contact"]["bodies"])
            fix(ref);
    if (p.contains("pivots") && p["pivots"].is_array())
        for (json& pv : p["pivots"])
            if (pv.is_object() && pv.contains("body"))
                fix(pv["body"]);
}

std::string mutate_once(json& p, engine& rng)
{
    switch (pick(rng, 15)) {
    case 0:
    case 1:
    case 2: { // a leaf value becomes hostile
        std::vector<json*> all;
        leaves(p, all);
        if (all.empty())
            break;
        *all[pick(rng, all.size())] = hostile_value(rng);
        return "hostile value";
    }
    case 3: { // any node (a whole vector, body or object) becomes hostile
        std::vector<json*> all;
        nodes(p, all);
        if (all.empty())
            break;
        *all[pick(rng, all.size())] = hostile_value(rng);
        return "hostile node";
    }
    case 4:
    case 5: { // an edge value that often stays valid
        std::vector<json*> all;
        leaves(p, all);
        if (all.empty())
            break;
        *all[pick(rng, all.size())] = plausible_value(rng);
        return "edge value";
    }
    case 6:
    case 7: { // a hostile body name
        json* bodies = bodies_of(p);
        if (!bodies)
            break;
        json& b = (*bodies)[pick(rng, bodies->size())];
        if (!b.is_object())
            break;
        std::string old = b.contains("name") && b["name"].is_string() ? b["name"].get<std::string>() : "";
        std::string name = hostile_name(rng);
        b["name"] = name;
        rename_body(p, old, name, chance(rng, 0.15));
        return "hostile name";
    }
    case 8: { // a key is deleted
        std::vector<json*> objs = objects(p);
        if (objs.empty())
            break;
        json& o = *objs[pick(rng, objs.size())];
        auto it = o.begin();
        std::advance(it, static_cast<long>(pick(rng, o.size())));
        std::string key = it.key();
        o.erase(key);
        return "deleted key " + key;
    }
    case 9: { // a body is duplicated, under its own name or a new one
        json* bodies = bodies_of(p);
        if (!bodies)
            break;
        json copy = (*bodies)[pick(rng, bodies->size())];
        if (copy.is_object() && chance(rng, 0.5))
            copy["name"] = "copy" + std::to_string(bodies->size());
        bodies->push_back(copy);
        return "duplicated body";
    }
    case 10: { // contact bodies swapped; half the time the normal is turned round as well (same impact)
        if (!p.contains("contact") || !p["contact"].is_object())
            break;
        json& c = p["contact"];
        if (c.contains("bodies") && c["bodies"].is_array() && c["bodies"].size() >= 2)
            std::swap(c["bodies"][0], c["bodies"][1]);
        if (chance(rng, 0.5) && c.contains("normal") && c["normal"].is_array()) {
            for (json& x : c["normal"])
                x = negated(x);
            return "swapped contact bodies and normal";
        }
        return "swapped contact bodies";
    }
    case 11: { // the dimension changes
        static const std::vector<json> dims = {2, 3, 4, 0, 1, -2, 2.5, "2", raw("3.0"), raw("2e0"), nullptr};
        p["dimension"] = chance(rng, 0.5) && p.contains("dimension") && p["dimension"].is_number_integer()
                             ? json(5 - p["dimension"].get<long long>())
                             : one_of(rng, dims);
        return "dimension";
    }
    case 12: { // a vector gets shorter or longer
        std::vector<json*> all, arrays;
        nodes(p, all);
        for (json* x : all)
            if (x->is_array() && (x->empty() || x->front().is_primitive()))
                arrays.push_back(x);
        if (arrays.empty())
            break;
        json& a = *arrays[pick(rng, arrays.size())];
        if (!a.empty() && chance(rng, 0.5))
            a.erase(a.size() - 1);
        else
            a.push_back(chance(rng, 0.5) ? json(0) : plausible_value(rng));
        return "vector length";
    }
    case 13: { // a restitution law (format version 3), valid or not, now and then with friction
        if (!p.contains("contact") || !p["contact"].is_object())
            break;
        static const std::vector<json> laws = {"newton", "poisson", "energetic", "energetic", "poisson",
                                               "Poisson", "stronge", "", 3, nullptr, json::array()};
        p["contact"]["law"] = one_of(rng, laws);
        if (chance(rng, 0.6))
            p["contact"]["friction"] =
                one_of(rng, std::vector<json>{0, 0.2, 0.5, 1, 2, "1/3", "sqrt(2)/2", "inf", -1, "mu"});
        return "law";
    }
    default: { // a body's mass becomes infinite, or bodies change order
        json* bodies = bodies_of(p);
        if (!bodies)
            break;
        if (chance(rng, 0.5)) {
            json& b = (*bodies)[pick(rng, bodies->size())];
            if (b.is_object())
                b["mass"] = one_of(rng, std::vector<json>{"inf", "+inf", "Infinity", "-inf", "inf*2"});
            return "infinite mass";
        }
        std::shuffle(bodies->begin(), bodies->end(), rng);
        return "body order";
    }
    }
    return "no-op";
}

} // namespace

std::string mutate_tree(json& problem, engine& rng, int count)
{
    std::string what;
    for (int i = 0; i < count; ++i)
        what += (what.empty() ? "" : ", ") + mutate_once(problem, rng);
    return what;
}

std::string serialise(const json& problem, engine& rng)
{
    const int indent = chance(rng, 0.5) ? -1 : 2;
    const bool ascii = chance(rng, 0.3);
    std::string text = problem.dump(indent, ' ', ascii, json::error_handler_t::replace);
    const std::string quoted = "\"" + raw_prefix;
    for (std::size_t at = text.find(quoted); at != std::string::npos; at = text.find(quoted, at)) {
        std::size_t end = text.find('"', at + quoted.size());
        if (end == std::string::npos)
            break;
        std::string token = text.substr(at + quoted.size(), end - at - quoted.size());
        text.replace(at, end + 1 - at, token);
        at += token.size();
    }
    return text;
}

std::string mutate_bytes(std::string& text, engine& rng, int count)
{
    static const std::string inserts = std::string("\"\\{}[],:-+.eE0123456789 \n\t\xff\xc3\x80/*", 31) + std::string(1, '\0');
    std::string what;
    for (int i = 0; i < count; ++i) {
        std::size_t at = text.empty() ? 0 : pick(rng, text.size());
        std::string op;
        switch (pick(rng, 7)) {
        case 0:
            if (text.empty())
                break;
            text[at] = static_cast<char>(text[at] ^ (1 << pick(rng, 8)));
            op = "flip";
            break;
        case 1:
            text.erase(at, 1 + pick(rng, 16));
            op = "delete";
            break;
        case 2: {
            std::string bytes;
            for (std::size_t k = 0, n = 1 + pick(rng, 4); k < n; ++k)
                bytes += chance(rng, 0.8) ? inserts[pick(rng, inserts.size())] : static_cast<char>(pick(rng, 256));
            text.insert(at, bytes);
            op = "insert";
            break;
        }
        case 3:
            text.resize(at);
            op = "truncate";
            break;
        case 4: {
            std::size_t n = std::min<std::size_t>(text.size() - at, 1 + pick(rng, 64));
            text.insert(at, text.substr(at, n));
            op = "duplicate";
            break;
        }
        default: { // a digit becomes another digit: usually still a valid problem
            std::vector<std::size_t> digits;
            for (std::size_t k = 0; k < text.size(); ++k)
                if (text[k] >= '0' && text[k] <= '9')
                    digits.push_back(k);
            if (digits.empty())
                break;
            text[digits[pick(rng, digits.size())]] = static_cast<char>('0' + pick(rng, 10));
            op = "digit";
            break;
        }
        }
        if (!op.empty())
            what += (what.empty() ? "" : ", ") + op;
    }
    return what;
}

} // namespace impactgen::fuzz
