// The rate-form plastic laws' consistent tangent (materials/tangent.hpp).
#include "pmpm/materials/tangent.hpp"

namespace pmpm {

Mat3 trial_stress(const ElasticConstants &el, const TangentKinematics &k, const TangentPoint &pt) {
  const Mat3 so3 = stress_to_tensor(pt.s_old);
  Mat3 de, dw;
  strain_and_spin(k.gm, de, dw);
  if (pt.eigen)
    for (int d = 0; d < 3; ++d) de(d, d) -= pt.eigen[d];
  return jaumann_rotate(so3, dw) + elastic_increment(el, de);
}

void plastic_piola_tangent(const ElasticConstants &el, const TangentKinematics &k,
                           const TangentPoint &pt, const ReturnDerivative &D, double *A) {
  const Mat3 so3 = stress_to_tensor(pt.s_old);
  piola_directions(
      [&](const MatN &dG) {
        const MatN dGm = k.Hi * dG * k.Hi;
        const double g[DIM * DIM] = {dGm(0, 0), dGm(0, 1), dGm(1, 0), dGm(1, 1)};
        Mat3 de, dw;
        strain_and_spin(g, de, dw);
        const Mat3 ds3 = D.apply(dw * so3 - so3 * dw + elastic_increment(el, de));
        MatN ds;
        ds << ds3(0, 0), ds3(0, 1), ds3(1, 0), ds3(1, 1);
        return k.rate_form_dP(dG, ds);
      },
      A);
}

} // namespace pmpm
