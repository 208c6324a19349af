// The Eigen friction reference for T = float, compiled once for the project's tests and
// benchmarks (numeric/friction_solver.hpp declares it extern when IMPACTGEN_NUMERIC_PREBUILT).
#include "numeric/friction_solver.hpp"

namespace impactgen::numeric
{
template friction_answer<float> solve_friction<float>(const problem<float> &, const friction_options<float> &);
template float kinetic_energy<float>(const problem<float> &, const std::vector<vec<float>> &,
                                     const std::vector<vec<float>> &);
template float kinetic_energy<float>(const problem<float> &);
} // namespace impactgen::numeric
