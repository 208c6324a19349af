// The Eigen friction reference for T = double, compiled once for the project's tests and
// benchmarks (numeric/friction_solver.hpp declares it extern when IMPACTGEN_NUMERIC_PREBUILT).
#include "numeric/friction_solver.hpp"

namespace impactgen::numeric
{
template friction_answer<double> solve_friction<double>(const problem<double> &, const friction_options<double> &);
template double kinetic_energy<double>(const problem<double> &, const std::vector<vec<double>> &,
                                       const std::vector<vec<double>> &);
template double kinetic_energy<double>(const problem<double> &);
} // namespace impactgen::numeric
