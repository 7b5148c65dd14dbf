// Compile-time dimension and the small fixed-size types every kernel uses.
#pragma once
#include <Eigen/Dense>
#include <cstdint>

namespace pmpm {

inline constexpr int DIM = 2;     // plane strain; 3D is a new constant, not a rewrite
inline constexpr int NSTRESS = 4; // Cauchy stress components stored per particle: xx yy zz xy

using VecN = Eigen::Matrix<double, DIM, 1>;
using MatN = Eigen::Matrix<double, DIM, DIM>;
using Mat3 = Eigen::Matrix3d;

// Stress storage <-> full 3x3 tensor (plane strain keeps sigma_zz).
inline Mat3 stress_to_tensor(const double *s) {
  Mat3 t;
  t << s[0], s[3], 0.0, s[3], s[1], 0.0, 0.0, 0.0, s[2];
  return t;
}
inline void tensor_to_stress(const Mat3 &t, double *s) {
  s[0] = t(0, 0);
  s[1] = t(1, 1);
  s[2] = t(2, 2);
  s[3] = 0.5 * (t(0, 1) + t(1, 0));
}

} // namespace pmpm
