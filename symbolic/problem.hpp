// The model of an impact: bodies, the contacts (each with its law), the joints to the
// fixed frame (pivots) and Newton's coefficient of restitution. Every quantity is a GiNaC expression,
// so the same model carries numbers (exact rationals) or symbols.
#pragma once

#include "json_value.hpp"
#include "restitution_law.hpp"
#include "vector_algebra.hpp"

#include <string>
#include <variant>
#include <vector>

namespace impactgen
{

/// What the problem reader accepts (anything larger is refused with a message
/// naming the key, before any work is done on it): every subcommand then
/// finishes in well under a second.
namespace limits
{
inline constexpr std::size_t file_bytes = 64 * 1024;   ///< a problem file or text
inline constexpr std::size_t expression_length = 1000; ///< characters of one expression string
inline constexpr int expression_depth = 32;            ///< nested parentheses in one expression
inline constexpr int sign_run = 3;                     ///< + or - signs in a row
inline constexpr std::size_t name_length = 64;         ///< bytes of a body name
inline constexpr std::size_t bodies = 64;              ///< bodies in one problem
inline constexpr std::size_t symbols = 64;             ///< distinct symbols in one problem
inline constexpr int exponent = 64;                    ///< |exponent| on a symbol or an expression (x^64)
inline constexpr std::size_t contacts = 64;            ///< contacts in one problem
inline constexpr std::size_t joints = 64;              ///< joints between bodies in one problem
} // namespace limits

/// The one symbol of a given name, shared by every problem in the process
/// (GiNaC compares symbols by identity, not by name).
GiNaC::symbol symbol_named(const std::string &name, const std::string &tex_name = "");

struct body {
    std::string name;
    std::string label;                  ///< short label used in symbol names ("1", "2", or the name)
    bool numbered = false;              ///< a named class's body 1 or 2 (prose says "body 1", not its name)
    bool infinite_mass = false;         ///< an immovable-by-impulse body (wall, ground, bat)
    ex mass = 0;                        ///< m > 0; unused when infinite_mass
    bool particle = true;               ///< no rotational inertia: angular velocity is left unchanged
    mat3 inertia = zero_mat();          ///< about the centre of mass, world axes; planar: only [2][2]
    vec3 position = zero_vec();         ///< centre of mass C
    vec3 velocity = zero_vec();         ///< of C, just before impact
    vec3 angular_velocity = zero_vec(); ///< planar: only [2]
    /// Velocity and angular velocity exactly zero before impact.
    bool at_rest() const
    {
        for (int a = 0; a < 3; ++a)
            if (!velocity[a].is_zero() || !angular_velocity[a].is_zero())
                return false;
        return true;
    }
};

struct pivot {
    std::size_t body = 0;    ///< index into problem::bodies
    vec3 point = zero_vec(); ///< the fixed point E
};

/// A joint between two bodies (format version 3): a pin in 2-D, a ball joint in 3-D. The two
/// bodies' material points at `point` move together after impact; the joint's impulse acts on
/// body 2 and its opposite on body 1.
struct joint {
    std::size_t body1 = 0, body2 = 1;
    vec3 point = zero_vec();
};

/// The laws a contact can obey. Each is a type; a law that needs more than these (another
/// restitution law, a friction law) is one more alternative of contact_law.
struct frictionless {
};
/// Coulomb's law: |P_t| <= mu P_n, P_t opposing the slip (format version 2).
struct coulomb {
    ex mu; ///< mu >= 0, a number or an expression
};
using contact_law = std::variant<frictionless, coulomb>;

struct contact_spec {
    std::size_t body1 = 0, body2 = 1; ///< A is on body 1, B on body 2
    vec3 point = zero_vec();          ///< the contact point O
    vec3 normal = zero_vec();         ///< from body 1 into body 2; any non-zero length
    contact_law law = frictionless{}; ///< the contact's law
    /// "friction": "inf" (format version 3): a perfectly rough contact, which never slips while it
    /// carries an impulse (law stays frictionless: friction() is 0 for it).
    bool rough = false;
    /// A `contacts` entry's own "restitution" (own_restitution), else the problem's.
    bool own_restitution = false;
    ex restitution = 0;
    /// How restitution is measured ("law": newton, poisson, energetic), a choice apart from `law`.
    restitution_law law_of_restitution = newton_restitution{};

    /// Coulomb's coefficient of the law, 0 for a frictionless contact.
    ex friction() const
    {
        const coulomb *c = std::get_if<coulomb>(&law);
        return c ? c->mu : ex(0);
    }
    /// The law for a coefficient of friction: frictionless when mu is identically 0, else Coulomb's.
    void set_friction(const ex &mu) { law = mu.is_zero() ? contact_law(frictionless{}) : contact_law(coulomb{mu}); }
};

struct problem {
    std::string source;      ///< named class or file it came from
    std::string title;       ///< "title" of the file (a person's words), or "" (documents then name the source)
    std::string description; ///< "description" of the file, or ""
    int dimension = 3;       ///< 2 (planar) or 3
    ex restitution = 0;
    std::vector<body> bodies;
    /// The contacts that act in the impact, in the file's order. The reader accepts one today
    /// (a file's `contact`, or `contacts` with one entry); several at once are the Systems issue.
    std::vector<contact_spec> contacts{contact_spec{}};
    /// The joints to the fixed frame (pins in 2-D, ball joints in 3-D).
    std::vector<pivot> pivots;
    /// The joints between bodies (format version 3).
    std::vector<joint> joints;
    /// "impacts": "sequential": the contacts act one at a time (format version 3).
    bool sequential = false;
    std::array<std::string, 3> axes{"x", "y", "z"}; ///< names of the world axes in printed symbols
    std::string units;                 ///< "" (none given) or "SI": the unit system of every number (prose only)
    std::vector<std::string> warnings; ///< e.g. keys that were ignored
    /// A named class's figure (symbolic/named_classes.cpp, named_systems.cpp): `illustrated`, and
    /// the number to draw each of its symbols with, given where the class puts the symbol in a
    /// quantity (illustrate()); a symbol without one is drawn by the quantity it is in (a spin 0,
    /// an inertia entry 1 on the diagonal and 0 off it, anything else 1). A problem file is not
    /// illustrated: its figure places every symbol by the quantity it is in (figure/values.cpp).
    bool illustrated = false;
    GiNaC::exmap illustrative;

    /// The contact of a one-contact problem (every problem the reader accepts today).
    contact_spec &contact() { return contacts.front(); }
    const contact_spec &contact() const { return contacts.front(); }
    /// The figure's value of a quantity that is one symbol (anything else: nothing to give).
    void illustrate(const ex &quantity, double value)
    {
        if (GiNaC::is_a<GiNaC::symbol>(quantity))
            illustrative[quantity] = GiNaC::numeric(value);
    }
    /// Every symbol the problem's values contain, sorted by name.
    std::vector<GiNaC::symbol> parameters() const;
    bool is_numeric() const { return parameters().empty(); }
    /// A system (format version 3): several contacts, joints, sequential impacts or a perfectly
    /// rough contact. Systems are solved by symbolic/system.hpp; every other problem by the
    /// one-contact pipeline, unchanged.
    bool is_system() const
    {
        bool rough = false;
        for (const contact_spec &c : contacts)
            rough = rough || c.rough;
        return contacts.size() > 1 || !joints.empty() || sequential || rough;
    }
    /// Newton's e of contact k: its own, else the problem's.
    ex restitution_of(std::size_t k) const
    {
        return contacts[k].own_restitution ? contacts[k].restitution : restitution;
    }
    /// The pivot of a body, or nullptr.
    const pivot *pivot_of(std::size_t body) const;
    /// True when the impulse cannot move the body (infinite mass, or a pinned particle).
    bool immovable(std::size_t body) const;
};

/// Checks everything the problem format requires that can be decided for the
/// values at hand (numbers are checked exactly; symbols are assumed valid).
/// Throws input_error naming the key.
void validate(const problem &p);

/// Reads a problem in the format of shared/problem-format.md; validates it.
problem read_problem(const std::string &json_text, const std::string &source);
problem load_problem_file(const std::string &path);

/// Parses one value of the problem format (a JSON number's text or an
/// expression string) into an exact expression; `where` names the key.
ex parse_value(const std::string &text, bool is_string, const std::string &where);

/// The body as prose names it: "body 1" for the named classes' numbered bodies, else its name.
std::string display_name(const body &b);

/// Velocity of a point q of body b: v + w x (q - C); a particle is a point,
/// so its spin does not move it (its velocity is v everywhere).
vec3 point_velocity(const body &b, const vec3 &q);
vec3 point_velocity(const body &b, const vec3 &v, const vec3 &w, const vec3 &q);

/// Calls put(ex &) on every value of the problem a number can stand for: the restitution, each
/// body's mass, position, velocity, spin and inertia, each contact's point, normal, friction
/// coefficient and restitution, each pivot's and joint's point.
template <typename Put> void for_each_value(problem &p, Put &&put)
{
    put(p.restitution);
    for (body &b : p.bodies) {
        put(b.mass);
        for (int r = 0; r < 3; ++r) {
            put(b.position[r]);
            put(b.velocity[r]);
            put(b.angular_velocity[r]);
            for (int c = 0; c < 3; ++c)
                put(b.inertia[r][c]);
        }
    }
    for (contact_spec &c : p.contacts) {
        for (int r = 0; r < 3; ++r) {
            put(c.point[r]);
            put(c.normal[r]);
        }
        ex mu = c.friction();
        put(mu);
        c.set_friction(mu);
        put(c.restitution);
    }
    for (pivot &pv : p.pivots)
        for (int r = 0; r < 3; ++r)
            put(pv.point[r]);
    for (joint &j : p.joints)
        for (int r = 0; r < 3; ++r)
            put(j.point[r]);
}

/// The problem with every symbol replaced (symbol == value list).
problem substitute(const problem &p, const GiNaC::ex &symbol_values);

} // namespace impactgen
