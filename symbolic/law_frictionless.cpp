// The smooth contact (contact_law frictionless; the hooks of contact_law.hpp): the impulse
// along the normal alone, no equation beside the smooth impact's (derivation.cpp), and one
// unconditioned candidate, the closed form of solution.cpp.
#include "contact_law.hpp"
#include "friction.hpp"

namespace impactgen
{

law_traits traits(const frictionless &, const problem &)
{
    law_traits t;
    t.tangential_impulse = false;
    t.single_candidate = true;
    t.process = false; // one candidate: Newton's, Poisson's and the energetic law agree without friction
    t.jacobian = jacobian_route::closed_form;
    return t;
}

void add_law_equations(const frictionless &, derivation &) {}

impact_solution solve_law(const frictionless &, const derivation &d)
{
    impact_solution s;
    s.mu = 0;
    s.n_hat = d.n_hat;
    s.e_t = d.e_t;
    s.e_b = d.e_b;
    regime_case c;
    c.kind = regime::smooth;
    c.name = "smooth";
    c.sol = solve(d);
    s.shared = c.sol;
    for (int a = 0; a < 3; ++a) {
        c.impulse[a] = c.sol.normal_impulse * d.n_hat[a];
        c.tangential_impulse[a] = 0;
        c.direction[a] = 0;
    }
    c.tangential_scalar = 0;
    c.sliding_speed = 0;
    s.cases.push_back(c);
    return s;
}

} // namespace impactgen
