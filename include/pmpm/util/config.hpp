// Compile-time dimension and the small fixed-size types every kernel uses.
//
// The kernels (shape.hpp, affine.hpp, grid.hpp's GridViewT, transfers.hpp) are templates on the
// dimension D (2 or 3); DIM is the dimension the driver (Simulation, the DMDA, DMSwarm, the
// scenes) runs today, and the kernels' D = DIM instantiation is its 2D path (developer guide,
// "Dimensions").
#pragma once
#include <Eigen/Dense>
#include <cstdint>

namespace pmpm {

inline constexpr int DIM = 2; // the driver's dimension (plane strain)

// Cauchy stress components stored per particle: 2D xx yy zz xy (plane strain keeps sigma_zz),
// 3D xx yy zz xy yz xz. The 2D layout is the 3D one's first four entries.
template <int D> inline constexpr int NStress = D == 2 ? 4 : 6;
inline constexpr int NSTRESS = NStress<DIM>;

// Storage slot of the stress component (a, b), a, b < 3 (symmetric).
constexpr int stress_slot(int a, int b) {
  return a == b ? a : (a + b == 1 ? 3 : (a + b == 3 ? 4 : 5));
}

using VecN = Eigen::Matrix<double, DIM, 1>;
using MatN = Eigen::Matrix<double, DIM, DIM>;
using Mat3 = Eigen::Matrix3d;

// Stress storage <-> full 3x3 tensor; in 2D the out-of-plane shears are zero.
template <int D = DIM> inline Mat3 stress_to_tensor(const double *s) {
  static_assert(D == 2 || D == 3, "2D or 3D");
  Mat3 t;
  if constexpr (D == 2)
    t << s[0], s[3], 0.0, s[3], s[1], 0.0, 0.0, 0.0, s[2];
  else
    t << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  return t;
}
template <int D = DIM> inline void tensor_to_stress(const Mat3 &t, double *s) {
  static_assert(D == 2 || D == 3, "2D or 3D");
  s[0] = t(0, 0);
  s[1] = t(1, 1);
  s[2] = t(2, 2);
  s[3] = 0.5 * (t(0, 1) + t(1, 0));
  if constexpr (D == 3) {
    s[4] = 0.5 * (t(1, 2) + t(2, 1));
    s[5] = 0.5 * (t(0, 2) + t(2, 0));
  }
}

} // namespace pmpm
