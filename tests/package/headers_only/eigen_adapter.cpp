// The Eigen adapter from the header-only component: Eigen is the user's own
// dependency (found and linked by this project, not by impactgen::headers).
#include "generated/noncentral_3d.hpp"
#include "impactgen/eigen.hpp"

#include <Eigen/Core>
#include <cstdio>

int main()
{
    std::printf("impactgen/eigen.hpp compiles with Eigen %d.%d.%d\n", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION,
                EIGEN_MINOR_VERSION);
    return 0;
}
