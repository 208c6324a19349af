// jacobian/<class> and autodiff/<class>: the generated <name>_jacobian (double) against
// forward-mode autodiff (Eigen's AutoDiffScalar, one derivative per input, fixed size) of
// the same generated function <name>; the headers with a Jacobian are generated at build
// time into the build directory (bench/CMakeLists.txt), in namespace impactgen::bench_jacobian.
#pragma once

#include <string>
#include <vector>

/// Registers jacobian/<cls> and autodiff/<cls> on these inputs (rows[i][j]: input j of
/// impact i, in the order of the class's input names) for the classes built with a
/// Jacobian: noncentral-3d, noncentral-3d-engine (1/m and I^-1 given) and planar. First,
/// once and untimed, checks that autodiff's values and derivatives equal the Jacobian's
/// on every row; aborts with a message when they do not. The rows must outlive the run.
void register_jacobian_benchmarks(const std::string& cls, const std::vector<std::vector<double>>& rows);
