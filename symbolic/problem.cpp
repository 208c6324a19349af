#include "problem.hpp"

#include "decide.hpp"
#include "law_reader.hpp"
#include "names/escape.hpp"
#include "system_input.hpp"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace impactgen
{
using namespace GiNaC;

namespace
{

std::map<std::string, symbol> &symbol_registry()
{
    static std::map<std::string, symbol> registry;
    return registry;
}

// "v_t1" -> "v_{t1}", "m1" -> "m_{1}", "omega" stays (GiNaC prints Greek names itself).
std::string default_tex(const std::string &name)
{
    if (name == "omicron" || name == "Omicron") // GiNaC would write \omicron, which LaTeX lacks
        return name == "omicron" ? "o" : "O";
    auto us = name.find('_');
    if (us != std::string::npos && us + 1 < name.size()) {
        // one subscript: later underscores are printed, not a second subscript (v_ball_x_0)
        std::string sub;
        for (char c : name.substr(us + 1))
            sub += c == '_' ? std::string("\\_") : std::string(1, c);
        return name.substr(0, us) + "_{" + sub + "}";
    }
    std::size_t d = name.size();
    while (d > 0 && std::isdigit(static_cast<unsigned char>(name[d - 1])))
        --d;
    if (d > 0 && d < name.size())
        return name.substr(0, d) + "_{" + name.substr(d) + "}";
    return "";
}

bool is_ident_start(char c)
{
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool is_ident_char(char c)
{
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// Exact value of a decimal literal: 0.8 -> 4/5, 1e-3 -> 1/1000.
numeric exact_decimal(const std::string &lit, const std::string &where)
{
    std::string mant = lit, expo;
    auto epos = lit.find_first_of("eE");
    if (epos != std::string::npos) {
        mant = lit.substr(0, epos);
        expo = lit.substr(epos + 1);
    }
    bool negative = false;
    if (!mant.empty() && (mant[0] == '-' || mant[0] == '+')) {
        negative = mant[0] == '-';
        mant.erase(0, 1);
    }
    std::string digits;
    long scale = 0;
    bool seen_point = false;
    for (char c : mant) {
        if (c == '.') {
            seen_point = true;
            continue;
        }
        if (!std::isdigit(static_cast<unsigned char>(c)))
            throw input_error(where + ": \"" + names::display_text(lit) + "\" is not a number");
        digits += c;
        if (seen_point)
            --scale;
    }
    if (digits.empty())
        throw input_error(where + ": \"" + names::display_text(lit) + "\" is not a number");
    // A number below 10^-400 in magnitude underflows (it is not infinite): said so, apart.
    auto too_small = [&]() {
        return input_error(
            where + ": " + names::display_text(lit) +
            " is too small: its magnitude is below 10^-400, the smallest non-zero number read (write 0 for zero)");
    };
    if (!expo.empty()) {
        // The exponent's sign, then its digits without leading zeros (1e-000003 is 1e-3).
        std::string sign, body = expo;
        if (body[0] == '-' || body[0] == '+') {
            sign = body.substr(0, 1);
            body.erase(0, 1);
        }
        if (body.empty() || body.find_first_not_of("0123456789") != std::string::npos)
            throw input_error(where + ": \"" + names::display_text(lit) + "\" is not a number");
        body.erase(0, std::min(body.find_first_not_of('0'), body.size() - 1));
        expo = (sign == "-" ? "-" : "") + body;
        if (expo.size() > 6) {
            if (digits.find_first_not_of('0') == std::string::npos)
                return numeric(0); // 0e-9999999 is 0
            if (expo[0] == '-')
                throw too_small();
            throw input_error(where + ": the exponent of " + names::display_text(lit) +
                              " is out of range (non-finite number)");
        }
        scale += std::stol(expo);
    }
    if (digits.size() > limits::expression_length)
        throw input_error(where + ": a number of " + std::to_string(digits.size()) + " digits; at most " +
                          std::to_string(limits::expression_length) + " are read");
    // The magnitude is about 10^(scale + significant digits): 0.47 with 420 digits is fine.
    const std::size_t first = digits.find_first_not_of('0');
    const long magnitude = first == std::string::npos ? 0 : scale + static_cast<long>(digits.size() - first);
    // The value lies in [10^(magnitude - 1), 10^magnitude): below 10^-400 when magnitude <= -400.
    if (magnitude <= -400)
        throw too_small();
    if (magnitude > 400)
        throw input_error(where + ": " + names::display_text(lit) +
                          " is out of the range of double (non-finite number)");
    numeric value(digits.c_str());
    value *= pow(numeric(10), numeric(scale));
    return negative ? -value : value;
}

// Rewrites decimal literals inside an expression string as exact rationals
// and registers every identifier as a shared symbol; returns the rewritten text.
const std::string reserved_prefix = "impactgen_number_";

// The limits on one character of an expression: nesting depth, runs of signs, ASCII only.
void check_character(char c, const std::string &where, int &depth, int &signs)
{
    if (c == '(') {
        if (++depth > limits::expression_depth)
            throw input_error(where + ": parentheses nested deeper than " + std::to_string(limits::expression_depth) +
                              " levels");
    } else if (c == ')') {
        --depth;
    }
    if (c == '+' || c == '-') {
        if (++signs > limits::sign_run)
            throw input_error(where + ": more than " + std::to_string(limits::sign_run) +
                              " signs in a row (+ or -) in the expression");
    } else if (!std::isspace(static_cast<unsigned char>(c))) {
        signs = 0;
    }
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f)
        throw input_error(where + ": the expression contains the byte " + names::display_text(std::string(1, c)) +
                          " (expressions are ASCII: numbers, symbols, + - * / ^ ( ) and functions)");
}

// An identifier at i: a known function called, a constant, or a symbol registered; appended to out, returns its end.
std::size_t identifier_token(const std::string &s, std::size_t i, symtab &table, const std::string &where,
                             std::string &out)
{
    static const std::set<std::string> functions = {"sqrt", "sin", "cos", "tan", "asin", "acos", "atan",
                                                    "exp",  "log", "abs", "pow", "sinh", "cosh", "tanh"};
    std::size_t j = i;
    while (j < s.size() && is_ident_char(s[j]))
        ++j;
    std::string id = s.substr(i, j - i);
    std::size_t k = j;
    while (k < s.size() && std::isspace(static_cast<unsigned char>(s[k])))
        ++k;
    bool call = k < s.size() && s[k] == '(';
    std::string lower = id;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (lower == "inf" || lower == "infinity" || lower == "nan")
        throw input_error(
            where + ": \"" + names::display_text(s) +
            "\" is not a finite value (an infinite mass is written as the whole value: \"mass\": \"inf\")");
    if (id.rfind(reserved_prefix, 0) == 0)
        throw input_error(where + ": names starting with \"" + reserved_prefix + "\" are reserved");
    if (call) {
        if (!functions.count(id))
            throw input_error(where + ": unknown function \"" + id + "\" in \"" + names::display_text(s) + "\"");
        std::size_t a = k + 1;
        while (a < s.size() && std::isspace(static_cast<unsigned char>(s[a])))
            ++a;
        if (a >= s.size() || s[a] == ')')
            throw input_error(where + ": the function " + id + "() needs an argument");
    } else if (id == "I") {
        throw input_error(where + ": \"I\" is the imaginary unit in expressions; name the symbol otherwise (e.g. I1)");
    } else if (id != "Pi" && id != "Euler" && id != "Catalan") {
        table[id] = symbol_named(id);
    }
    out += id;
    return j;
}

// A decimal literal at i, replaced by a placeholder symbol for its exact value; returns its end.
std::size_t number_token(const std::string &s, std::size_t i, symtab &table, const std::string &where, lst &numbers,
                         std::string &out)
{
    std::size_t j = i;
    while (j < s.size() && (std::isdigit(static_cast<unsigned char>(s[j])) || s[j] == '.'))
        ++j;
    if (j < s.size() && (s[j] == 'e' || s[j] == 'E')) {
        std::size_t k = j + 1;
        if (k < s.size() && (s[k] == '+' || s[k] == '-'))
            ++k;
        if (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) {
            j = k;
            while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j])))
                ++j;
        }
    }
    // One number: at most one decimal point, and not run into a name or another number
    // ("0.3.1", "0..3", "1e2e3", "2x" are refused, never read as something else).
    const std::string token = s.substr(i, j - i);
    if (std::count(token.begin(), token.end(), '.') > 1 || (j < s.size() && (is_ident_char(s[j]) || s[j] == '.')))
        throw input_error(where + ": malformed number in \"" + names::display_text(s) +
                          "\" (a number has at most one decimal point and an exponent like 1e-3, "
                          "and a product is written with *)");
    // A placeholder symbol: GiNaC's parser would evaluate 2^(2^40) eagerly.
    std::string name = reserved_prefix + std::to_string(numbers.nops());
    symbol placeholder(name);
    table[name] = placeholder;
    numbers.append(placeholder == exact_decimal(s.substr(i, j - i), where));
    out += name;
    return j;
}

std::string prepare_expression(const std::string &s, symtab &table, const std::string &where, lst &numbers)
{
    if (s.size() > limits::expression_length)
        throw input_error(where + ": the expression is " + std::to_string(s.size()) + " characters long; at most " +
                          std::to_string(limits::expression_length) + " are read");
    std::string out;
    std::size_t i = 0;
    int depth = 0, signs = 0;
    while (i < s.size()) {
        char c = s[i];
        check_character(c, where, depth, signs);
        if (is_ident_start(c)) {
            i = identifier_token(s, i, table, where, out);
        } else if (std::isdigit(static_cast<unsigned char>(c)) ||
                   (c == '.' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
            i = number_token(s, i, table, where, numbers, out);
        } else {
            out += c;
            ++i;
        }
    }
    return out;
}

// Every value is decided before it is used: real, within double range, and
// for a constant its sign known exactly (decide.hpp); otherwise refused.
// The largest |integer exponent| on a non-numeric base in e (x^(2^20) would make
// exact evaluation at a point, and any expansion, run without end).
numeric largest_exponent(const ex &e)
{
    numeric m = 0;
    if (is_a<power>(e) && !is_a<numeric>(e.op(0)) && is_a<numeric>(e.op(1)))
        m = abs(ex_to<numeric>(e.op(1)));
    for (std::size_t k = 0; k < e.nops(); ++k)
        m = std::max(m, largest_exponent(e.op(k)), [](const numeric &a, const numeric &b) { return a < b; });
    return m;
}

void check_value(const ex &e, const std::string &where)
{
    if (largest_exponent(e) > limits::exponent)
        throw input_error(where + ": an exponent larger than " + std::to_string(limits::exponent) +
                          " on a symbol or an expression (at most " + std::to_string(limits::exponent) + ")");
    if (e.has(I))
        throw input_error(where + ": the value is not real");
    if (is_constant(e)) {
        decision d = decide(e);
        if (d == decision::not_real || d == decision::out_of_range || d == decision::undecided)
            throw input_error(where + ": the value " + decision_text(d));
        // a plain number beyond double (1e308*10): exact, but no answer could be printed
        if (is_a<numeric>(e) && abs(ex_to<numeric>(e)) > numeric(DBL_MAX))
            throw input_error(where + ": the value " + decision_text(decision::out_of_range));
        return;
    }
    std::string why = constant_parts_problem(e);
    if (!why.empty())
        throw input_error(where + ": in the expression, a constant part: " + why);
}

std::string show(const ex &e)
{
    std::ostringstream os;
    os << e;
    // A rational too long to read (-1/10^400) as its sign, leading digits and power of ten.
    if (is_a<numeric>(e) && ex_to<numeric>(e).is_rational() && !e.is_zero() && os.str().size() > 40)
        return "about " + scientific_text(ex_to<numeric>(e), 6);
    return names::display_text(os.str(), 120);
}

// ---- reading the JSON format -------------------------------------------------

const json_value &require(const json_value &obj, const std::string &key, const std::string &where)
{
    const json_value *v = obj.find(key);
    if (!v)
        throw input_error(where + ": missing key \"" + key + "\"");
    return *v;
}

ex scalar(const json_value &v, const std::string &where)
{
    if (v.is_number() || v.is_string())
        return parse_value(v.text(), v.is_string(), where);
    throw input_error(where + ": expected a number or an expression string, got " + json_value::kind_name(v.type()));
}

vec3 vector_of(const json_value &v, int dim, const std::string &where)
{
    if (!v.is_array())
        throw input_error(where + ": expected a list of " + std::to_string(dim) + " values, got " +
                          json_value::kind_name(v.type()));
    if (static_cast<int>(v.items().size()) != dim)
        throw input_error(where + ": expected " + std::to_string(dim) + " components for a " + std::to_string(dim) +
                          "-D problem, got " + std::to_string(v.items().size()));
    vec3 r = zero_vec();
    for (int i = 0; i < dim; ++i)
        r[i] = scalar(v.items()[i], where + "[" + std::to_string(i) + "]");
    return r;
}

void warn_unknown_keys(const json_value &obj, std::initializer_list<const char *> known, const std::string &where,
                       std::vector<std::string> &warnings)
{
    for (const auto &m : obj.members()) {
        bool ok = false;
        for (const char *k : known)
            ok = ok || m.first == k;
        if (!ok)
            warnings.push_back(where + (where.empty() ? "" : ".") + names::display_text(m.first) +
                               ": unknown key, ignored");
    }
}

std::size_t body_index(const problem &p, const json_value &v, const std::string &where)
{
    if (!v.is_string())
        throw input_error(where + ": expected a body name (a string), got " + json_value::kind_name(v.type()));
    for (std::size_t i = 0; i < p.bodies.size(); ++i)
        if (p.bodies[i].name == v.text())
            return i;
    throw input_error(where + ": unknown body \"" + names::display_text(v.text()) + "\"");
}

} // namespace

symbol symbol_named(const std::string &name, const std::string &tex_name)
{
    auto &reg = symbol_registry();
    auto it = reg.find(name);
    if (it != reg.end())
        return it->second;
    std::string tex = tex_name.empty() ? default_tex(name) : tex_name;
    symbol s = tex.empty() ? symbol(name) : symbol(name, tex);
    reg.emplace(name, s);
    return s;
}

ex parse_value(const std::string &text, bool is_string, const std::string &where)
{
    ex value;
    if (!is_string) {
        value = exact_decimal(text, where);
    } else {
        std::string t = text;
        if (t.find_first_not_of(" \t") == std::string::npos)
            throw input_error(where + ": empty expression");
        symtab table;
        lst numbers;
        std::string prepared = prepare_expression(t, table, where, numbers);
        parser reader(table, true);
        try {
            ex shape = reader(prepared);
            exmap values;
            for (const ex &rel : numbers)
                values[rel.lhs()] = rel.rhs();
            if (log10_magnitude_bound(shape, values) > 400)
                throw input_error(
                    where + ": \"" + names::display_text(text) +
                    "\" is beyond what is read: its magnitude, or a part's, is above 10^400 or below 10^-400");
            value = shape.subs(values);
        } catch (const input_error &) {
            throw;
        } catch (const std::exception &e) {
            std::string why = e.what();
            why = why.substr(0, why.find('\n'));
            // GiNaC quotes the rewritten text (decimals as exact symbols): not the user's, so not shown
            if (why.find("Illegal number syntax") != std::string::npos)
                why = "a number is malformed";
            throw input_error(where + ": cannot read the expression \"" + names::display_text(text) + "\" (" +
                              names::display_text(why) + ")");
        }
    }
    check_value(value, where);
    return value;
}

std::vector<symbol> problem::parameters() const
{
    exset found;
    auto collect = [&](const ex &e) {
        for (const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
            if (is_a<symbol>(*it))
                found.insert(*it);
    };
    auto collect_v = [&](const vec3 &v) {
        for (const ex &e : v)
            collect(e);
    };
    collect(restitution);
    for (const body &b : bodies) {
        if (!b.infinite_mass)
            collect(b.mass);
        for (const auto &row : b.inertia)
            collect_v(row);
        collect_v(b.position);
        collect_v(b.velocity);
        collect_v(b.angular_velocity);
    }
    for (const contact_spec &c : contacts) {
        collect_v(c.point);
        collect_v(c.normal);
        collect(c.friction());
        if (c.own_restitution)
            collect(c.restitution);
    }
    for (const pivot &pv : pivots)
        collect_v(pv.point);
    for (const joint &j : joints)
        collect_v(j.point);
    std::vector<symbol> r;
    for (const ex &e : found)
        r.push_back(ex_to<symbol>(e));
    std::sort(r.begin(), r.end(), [](const symbol &a, const symbol &b) { return a.get_name() < b.get_name(); });
    return r;
}

std::string display_name(const body &b)
{
    bool digits =
        !b.name.empty() && std::all_of(b.name.begin(), b.name.end(), [](unsigned char c) { return std::isdigit(c); });
    return digits ? "body " + b.name : b.name;
}

vec3 point_velocity(const body &b, const vec3 &q)
{
    return point_velocity(b, b.velocity, b.angular_velocity, q);
}

vec3 point_velocity(const body &b, const vec3 &v, const vec3 &w, const vec3 &q)
{
    return b.particle && !b.infinite_mass ? v : v + cross(w, q - b.position);
}

const pivot *problem::pivot_of(std::size_t b) const
{
    for (const pivot &pv : pivots)
        if (pv.body == b)
            return &pv;
    return nullptr;
}

bool problem::immovable(std::size_t b) const
{
    return bodies[b].infinite_mass || (bodies[b].particle && pivot_of(b) != nullptr);
}

namespace
{

// The decided sign of a value or a quantity derived from values; refuses
// what is not real, out of range or cannot be decided (decide.hpp).
decision decided(const ex &e, const std::string &where, const std::string &what)
{
    decision d = decide(e);
    if (d == decision::not_real || d == decision::out_of_range || d == decision::undecided)
        throw input_error(where + ": " + what + " " + decision_text(d));
    return d;
}

bool negative_or_zero(decision d)
{
    return d == decision::negative || d == decision::zero;
}

// Zero exactly: decided for constants, identically zero after expansion for symbols.
bool vanishes(const ex &e, const std::string &where, const std::string &what)
{
    decision d = decided(e, where, what);
    if (d == decision::symbolic)
        return identically_zero(e);
    return d == decision::zero;
}

} // namespace

void validate(const problem &p)
{
    if (p.dimension != 2 && p.dimension != 3)
        throw input_error("dimension: must be 2 or 3");
    if (p.bodies.size() < 2)
        throw input_error("bodies: an impact needs two bodies, got " + std::to_string(p.bodies.size()));
    const bool system = p.is_system();
    if (decided(p.restitution, "restitution", "e") == decision::negative ||
        decided(1 - p.restitution, "restitution", "1 - e") == decision::negative)
        throw input_error("restitution: e must lie in [0, 1], got " + show(p.restitution));
    if (!system && decided(p.contact().friction(), "contact.friction", "mu") == decision::negative)
        throw input_error("contact.friction: the coefficient of friction mu must be >= 0, got " +
                          show(p.contact().friction()));
    std::set<std::string> seen;
    for (std::size_t i = 0; i < p.bodies.size(); ++i) {
        const body &b = p.bodies[i];
        std::string where = "bodies[" + std::to_string(i) + "] (\"" + names::display_text(b.name) + "\")";
        if (!seen.insert(b.name).second)
            throw input_error("bodies[" + std::to_string(i) + "].name: repeated body \"" + names::display_text(b.name) +
                              "\"");
        if (!b.infinite_mass && negative_or_zero(decided(b.mass, where + ".mass", "the mass")))
            throw input_error(where + ".mass: must be > 0 (or \"inf\"), got " + show(b.mass));
        if (b.particle)
            continue;
        // Symmetric positive-definite (Sylvester: leading principal minors > 0).
        for (int r = 0; r < 3; ++r)
            for (int c = r + 1; c < 3; ++c)
                if (!vanishes(b.inertia[r][c] - b.inertia[c][r], where + ".inertia", "the asymmetry of the tensor"))
                    throw input_error(where + ".inertia: not symmetric (entry [" + std::to_string(r) + "][" +
                                      std::to_string(c) + "] is " + show(b.inertia[r][c]) + ", [" + std::to_string(c) +
                                      "][" + std::to_string(r) + "] is " + show(b.inertia[c][r]) + ")");
        const mat3 &J = b.inertia;
        std::vector<ex> minors;
        if (p.dimension == 2) {
            minors = {J[2][2]};
        } else {
            minors = {J[0][0], J[0][0] * J[1][1] - J[0][1] * J[1][0], det(J)};
        }
        for (const ex &m : minors)
            if (negative_or_zero(decided(m, where + ".inertia", "a leading principal minor")))
                throw input_error(where + ".inertia: not positive-definite" +
                                  std::string(p.dimension == 2 ? " (must be > 0, or 0 for a particle)" : ""));
    }
    const contact_spec &c = p.contact();
    if (!system) {
        if (c.body1 >= p.bodies.size() || c.body2 >= p.bodies.size())
            throw input_error("contact.bodies: unknown body");
        if (c.body1 == c.body2)
            throw input_error("contact.bodies: repeated body \"" + names::display_text(p.bodies[c.body1].name) +
                              "\" (a body cannot strike itself)");
        if (vanishes(dot(c.normal, c.normal), "contact.normal", "|n|^2"))
            throw input_error("contact.normal: the normal must not be zero");
    }
    std::set<std::size_t> pinned;
    for (std::size_t k = 0; k < p.pivots.size(); ++k) {
        const pivot &pv = p.pivots[k];
        std::string where = "pivots[" + std::to_string(k) + "]";
        if (pv.body >= p.bodies.size())
            throw input_error(where + ".body: unknown body");
        const body &b = p.bodies[pv.body];
        const std::string bname = names::display_text(b.name);
        if (!pinned.insert(pv.body).second)
            throw input_error(where + ".body: body \"" + bname +
                              "\" has a second pivot; the pivot impulses would be statically indeterminate "
                              "(at most one pivot per body)");
        if (b.infinite_mass)
            throw input_error(where + ".body: body \"" + bname +
                              "\" has infinite mass; a pivot on it takes no part in the impact");
        // The pivot point E of the body must be at rest: v + w x (E - C) = 0.
        vec3 vE = point_velocity(b, pv.point);
        for (int i = 0; i < 3; ++i)
            if (!vanishes(vE[i], where, "the velocity of the pivot point"))
                throw input_error(where + ": the pivot point of body \"" + bname +
                                  "\" moves before impact (v + w x (E - C) has component " + p.axes[i] + " = " +
                                  show(tidy(vE[i])) + "); a pivot is a fixed point");
    }
    if (system) {
        validate_system(p);
        return;
    }
    std::size_t b1 = c.body1, b2 = c.body2;
    if (p.immovable(b1) && p.immovable(b2))
        throw input_error("contact.bodies: neither \"" + names::display_text(p.bodies[b1].name) + "\" nor \"" +
                          names::display_text(p.bodies[b2].name) +
                          "\" can move (infinite mass or pinned particle): no impulse can act");
    // Approach: (v_B - v_A) . n < 0 is an impact; >= 0 separates or rests.
    const body &A = p.bodies[b1];
    const body &B = p.bodies[b2];
    vec3 vA = point_velocity(A, c.point);
    vec3 vB = point_velocity(B, c.point);
    ex approach = tidy(dot(vB - vA, c.normal));
    decision d = decided(approach, "contact", "the normal velocity of approach (v_B - v_A).n");
    if (d == decision::zero || d == decision::positive)
        throw input_error(std::string("contact: not an impact: the contact points ") +
                          (d == decision::zero ? "rest relative to each other" : "separate") +
                          " along the normal ((v_B - v_A).n = " + show(approach) + " >= 0)");
}

// A body's "inertia": a number in 2-D; in 3-D a 3x3 nested list or [Ixx, Iyy, Izz]; 0 or all
// zeros for a particle.
void read_inertia(const json_value &in, int d, const std::string &where, body &b)
{
    const std::string w = where + ".inertia";
    if (d == 2) {
        ex I = scalar(in, w);
        const decision sign = decided(I, w, "the moment of inertia");
        if (sign == decision::negative)
            throw input_error(w + ": not positive-definite (must be > 0, or 0 for a particle)");
        if (sign != decision::zero) {
            b.particle = false;
            b.inertia[2][2] = I;
        }
    } else if (!in.is_array()) {
        ex I = scalar(in, w);
        if (!I.is_zero())
            throw input_error(w + ": a 3-D inertia is a 3x3 nested list or [Ixx, Iyy, Izz] (0 for a particle)");
    } else if (in.items().size() == 3 && !in.items()[0].is_array()) {
        for (int k = 0; k < 3; ++k)
            b.inertia[k][k] = scalar(in.items()[k], w + "[" + std::to_string(k) + "]");
        b.particle = false;
    } else if (in.items().size() == 3) {
        for (int r = 0; r < 3; ++r)
            b.inertia[r] = vector_of(in.items()[r], 3, w + "[" + std::to_string(r) + "]");
        b.particle = false;
    } else {
        throw input_error(w + ": a 3-D inertia is a 3x3 nested list or [Ixx, Iyy, Izz], got a list of " +
                          std::to_string(in.items().size()));
    }
    if (!b.particle) {
        bool all_zero = true;
        for (const auto &row : b.inertia)
            for (const ex &e : row)
                all_zero = all_zero && e.is_zero();
        b.particle = all_zero;
    }
}

// One element of "bodies" (index i), in dimension d.
body read_body(const json_value &jb, std::size_t i, int d, std::vector<std::string> &warnings)
{
    std::string where = "bodies[" + std::to_string(i) + "]";
    if (!jb.is_object())
        throw input_error(where + ": expected an object, got " + json_value::kind_name(jb.type()));
    warn_unknown_keys(jb, {"name", "mass", "inertia", "position", "velocity", "angular_velocity"}, where, warnings);
    body b;
    const json_value &name = require(jb, "name", where);
    if (!name.is_string() || name.text().empty())
        throw input_error(where + ".name: expected a non-empty string");
    if (name.text().size() > limits::name_length)
        throw input_error(where + ".name: longer than " + std::to_string(limits::name_length) + " bytes");
    for (char ch : name.text())
        if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f)
            throw input_error(where + ".name: \"" + names::display_text(name.text()) +
                              "\" contains a control character (names are printed in documents and code)");
    b.name = b.label = name.text();
    where += " (\"" + names::display_text(b.name) + "\")";
    const json_value &mass = require(jb, "mass", where);
    std::string lower = mass.text();
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (mass.is_string() && (lower == "inf" || lower == "infinity" || lower == "+inf")) {
        b.infinite_mass = true;
    } else {
        b.mass = scalar(mass, where + ".mass");
    }
    if (const json_value *in = jb.find("inertia"))
        read_inertia(*in, d, where, b);
    b.position = vector_of(require(jb, "position", where), d, where + ".position");
    b.velocity = vector_of(require(jb, "velocity", where), d, where + ".velocity");
    if (const json_value *w = jb.find("angular_velocity")) {
        if (d == 2)
            b.angular_velocity[2] = scalar(*w, where + ".angular_velocity");
        else
            b.angular_velocity = vector_of(*w, 3, where + ".angular_velocity");
    }
    return b;
}

// One contact object: the two bodies, the point, the normal, the law (Coulomb's with
// "friction") and, in a `contacts` entry, its own restitution. `where` names it in messages.
contact_spec read_contact(const json_value &jc, problem &p, const std::string &where, bool own_restitution)
{
    const int d = p.dimension;
    if (!jc.is_object())
        throw input_error(where + ": expected an object, got " + json_value::kind_name(jc.type()));
    if (own_restitution)
        warn_unknown_keys(jc, {"bodies", "point", "normal", "friction", "restitution", "law"}, where, p.warnings);
    else
        warn_unknown_keys(jc, {"bodies", "point", "normal", "friction", "law"}, where, p.warnings);
    contact_spec c;
    const json_value &cb = require(jc, "bodies", where);
    if (!cb.is_array() || cb.items().size() != 2)
        throw input_error(where + ".bodies: expected a list of the two bodies that touch");
    c.body1 = body_index(p, cb.items()[0], where + ".bodies[0]");
    c.body2 = body_index(p, cb.items()[1], where + ".bodies[1]");
    c.point = vector_of(require(jc, "point", where), d, where + ".point");
    c.normal = vector_of(require(jc, "normal", where), d, where + ".normal");
    read_law_of_restitution(jc, where, c);
    if (const json_value *jf = jc.find("friction")) {
        if (jf->is_string() && jf->text() == "inf") {
            c.rough = true; // a perfectly rough contact: symbolic/system.hpp solves it
            return c;
        }
        c.set_friction(scalar(*jf, where + ".friction"));
        // mu = 0 (exactly, however written) is the smooth impact, unchanged
        if (is_constant(c.friction()) && decide(c.friction()) == decision::zero)
            c.set_friction(0);
    }
    return c;
}

// "contact" (one) or "contacts" (a list; one entry is solved today), never both. A
// `contacts` entry may carry its own "restitution", which replaces the top-level one.
void read_contacts(const json_value &root, problem &p, bool &restitution_given)
{
    const json_value *one = root.find("contact");
    const json_value *list = root.find("contacts");
    if (one && list)
        throw input_error("contacts: a file has \"contact\" (one) or \"contacts\" (a list), not both");
    if (!one && !list)
        throw input_error("problem: missing key \"contact\" (or \"contacts\")");
    if (one) {
        p.contacts = {read_contact(*one, p, "contact", false)};
        return;
    }
    if (!list->is_array())
        throw input_error(std::string("contacts: expected a list, got ") + json_value::kind_name(list->type()));
    if (list->items().empty())
        throw input_error("contacts: an impact needs at least one contact, got an empty list");
    refuse_process_laws_in_systems(*list);
    if (list->items().size() > limits::contacts)
        throw input_error("contacts: " + std::to_string(list->items().size()) + " contacts; at most " +
                          std::to_string(limits::contacts) + " are read");
    p.contacts.clear();
    restitution_given = true;
    for (std::size_t k = 0; k < list->items().size(); ++k) {
        const json_value &jc = list->items()[k];
        const std::string where = "contacts[" + std::to_string(k) + "]";
        p.contacts.push_back(read_contact(jc, p, where, true));
        const json_value *je = jc.find("restitution");
        if (je) {
            p.contacts.back().own_restitution = true;
            p.contacts.back().restitution = scalar(*je, where + ".restitution");
        }
        restitution_given = restitution_given && je;
    }
    // One contact of its own restitution: the one-contact pipeline reads the problem's.
    if (p.contacts.size() == 1 && p.contacts[0].own_restitution)
        p.restitution = p.contacts[0].restitution;
}

// Optional "title" and "description": a person's words for the problem.
std::string read_text(const json_value &root, const char *key)
{
    const json_value *v = root.find(key);
    if (!v)
        return "";
    if (!v->is_string())
        throw input_error(std::string(key) + ": expected a string, got " + json_value::kind_name(v->type()));
    for (char ch : v->text())
        if ((static_cast<unsigned char>(ch) < 0x20 && ch != '\n') || ch == 0x7f)
            throw input_error(std::string(key) + ": contains a control character (it is printed in documents)");
    if (v->text().size() > 2000)
        throw input_error(std::string(key) + ": longer than 2000 bytes");
    return v->text();
}

// "impacts": simultaneous (the default) or sequential.
void read_impacts(const json_value &root, problem &p)
{
    if (const json_value *i = root.find("impacts")) {
        if (!i->is_string() || (i->text() != "simultaneous" && i->text() != "sequential"))
            throw input_error("impacts: expected \"simultaneous\" or \"sequential\"");
        p.sequential = i->text() == "sequential";
    }
}

// "pivots" (optional): fixed pins (2-D) or ball joints (3-D).
void read_pivots(const json_value &root, problem &p)
{
    const int d = p.dimension;
    if (const json_value *jp = root.find("pivots")) {
        if (!jp->is_array())
            throw input_error(std::string("pivots: expected a list, got ") + json_value::kind_name(jp->type()));
        for (std::size_t k = 0; k < jp->items().size(); ++k) {
            const json_value &jv = jp->items()[k];
            std::string where = "pivots[" + std::to_string(k) + "]";
            if (!jv.is_object())
                throw input_error(where + ": expected an object, got " + json_value::kind_name(jv.type()));
            warn_unknown_keys(jv, {"body", "point"}, where, p.warnings);
            pivot pv;
            pv.body = body_index(p, require(jv, "body", where), where + ".body");
            pv.point = vector_of(require(jv, "point", where), d, where + ".point");
            p.pivots.push_back(pv);
        }
    }
}

problem read_problem(const std::string &text, const std::string &source)
{
    if (text.size() > limits::file_bytes)
        throw input_error("problem: the text is " + std::to_string(text.size()) + " bytes; at most " +
                          std::to_string(limits::file_bytes) + " are read");
    json_value root = json_value::parse(text);
    if (!root.is_object())
        throw input_error(std::string("problem: expected a JSON object, got ") + json_value::kind_name(root.type()));
    problem p;
    p.source = source;
    warn_unknown_keys(root,
                      {"dimension", "restitution", "bodies", "contact", "contacts", "pivots", "joints", "impacts",
                       "name", "title", "description", "units"},
                      "", p.warnings);
    p.title = read_text(root, "title");
    p.description = read_text(root, "description");
    read_impacts(root, p);
    if (const json_value *u = root.find("units")) {
        // Optional: the unit system of every number, for the prose of explain
        // (kg, m, s, N·s, J). Only "SI" is known; the values are not converted.
        if (!u->is_string() || u->text() != "SI")
            throw input_error(
                "units: the only unit system known is \"SI\" (kg, m, s), got " +
                (u->is_string() ? "\"" + names::display_text(u->text()) + "\"" : json_value::kind_name(u->type())));
        p.units = "SI";
    }

    const json_value &dim = require(root, "dimension", "problem");
    if (!dim.is_number() || (dim.text() != "2" && dim.text() != "3"))
        throw input_error("dimension: must be 2 or 3, got " +
                          (dim.text().empty() ? json_value::kind_name(dim.type()) : dim.text()));
    p.dimension = dim.text() == "2" ? 2 : 3;
    const int d = p.dimension;
    const json_value *top_e = root.find("restitution");
    if (top_e)
        p.restitution = scalar(*top_e, "restitution");

    const json_value &bodies = require(root, "bodies", "problem");
    if (!bodies.is_array())
        throw input_error(std::string("bodies: expected a list, got ") + json_value::kind_name(bodies.type()));
    if (bodies.items().size() > limits::bodies)
        throw input_error("bodies: " + std::to_string(bodies.items().size()) + " bodies; at most " +
                          std::to_string(limits::bodies) + " are read");
    for (std::size_t i = 0; i < bodies.items().size(); ++i)
        p.bodies.push_back(read_body(bodies.items()[i], i, d, p.warnings));
    if (p.bodies.size() < 2)
        throw input_error("bodies: an impact needs two bodies, got " + std::to_string(p.bodies.size()));
    {
        std::set<std::string> seen;
        for (std::size_t i = 0; i < p.bodies.size(); ++i)
            if (!seen.insert(p.bodies[i].name).second)
                throw input_error("bodies[" + std::to_string(i) + "].name: repeated body \"" +
                                  names::display_text(p.bodies[i].name) + "\"");
    }

    bool own_e = false;
    read_contacts(root, p, own_e);
    if (!top_e && !own_e)
        throw input_error("problem: missing key \"restitution\" (at the top level or in every contact)");
    read_pivots(root, p);
    read_joints(root, p);
    const std::size_t symbols = p.parameters().size();
    if (symbols > limits::symbols)
        throw input_error("problem: " + std::to_string(symbols) + " distinct symbols; at most " +
                          std::to_string(limits::symbols) + " are read");
    validate(p);
    check_law_of_restitution(p);
    return p;
}

problem load_problem_file(const std::string &path)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw input_error(names::display_text(path) + ": not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw input_error(names::display_text(path) + ": cannot open the problem file");
    std::string text(limits::file_bytes + 1, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    std::ostringstream ss;
    ss << text;
    try {
        return read_problem(ss.str(), path);
    } catch (const input_error &e) {
        throw input_error(names::display_text(path) + ": " + e.what());
    }
}

namespace detail
{
std::size_t body_index_of(const problem &p, const json_value &v, const std::string &where)
{
    return body_index(p, v, where);
}
vec3 read_vector(const json_value &v, int dim, const std::string &where)
{
    return vector_of(v, dim, where);
}
const json_value &required(const json_value &obj, const std::string &key, const std::string &where)
{
    return require(obj, key, where);
}
decision decided_sign(const ex &e, const std::string &where, const std::string &what)
{
    return decided(e, where, what);
}
bool is_zero_exactly(const ex &e, const std::string &where, const std::string &what)
{
    return vanishes(e, where, what);
}
std::string show_value(const ex &e)
{
    return show(e);
}
} // namespace detail

problem substitute(const problem &p, const ex &values)
{
    problem q = p;
    for_each_value(q, [&](ex &x) { x = x.subs(values); });
    return q;
}

} // namespace impactgen
