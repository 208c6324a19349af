// The Eigen friction reference for T = long double, compiled once for the project's tests and
// benchmarks (numeric/friction_solver.hpp declares it extern when IMPACTGEN_NUMERIC_PREBUILT).
#include "numeric/friction_solver.hpp"

namespace impactgen::numeric
{
template friction_answer<long double> solve_friction<long double>(const problem<long double> &,
                                                                  const friction_options<long double> &);
template long double kinetic_energy<long double>(const problem<long double> &, const std::vector<vec<long double>> &,
                                                 const std::vector<vec<long double>> &);
template long double kinetic_energy<long double>(const problem<long double> &);
} // namespace impactgen::numeric
