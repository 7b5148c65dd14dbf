// The rate-form plastic laws' consistent tangent (materials/tangent.hpp), in 2D and 3D.
#include "pmpm/materials/tangent.hpp"

namespace pmpm {

template <int D>
Mat3 trial_stress(const ElasticConstants &el, const TangentKinematicsT<D> &k,
                  const TangentPoint &pt) {
  const Mat3 so3 = stress_to_tensor<D>(pt.s_old);
  Mat3 de, dw;
  strain_and_spin<D>(k.gm, de, dw);
  if (pt.eigen)
    for (int d = 0; d < 3; ++d) de(d, d) -= pt.eigen[d];
  return jaumann_rotate(so3, dw) + elastic_increment(el, de);
}

template <int D>
void plastic_piola_tangent(const ElasticConstants &el, const TangentKinematicsT<D> &k,
                           const TangentPoint &pt, const ReturnDerivative &R, double *A) {
  const Mat3 so3 = stress_to_tensor<D>(pt.s_old);
  piola_directions<D>(
      [&](const MatD<D> &dG) {
        const MatD<D> dGm = k.Hi * dG * k.Hi;
        double g[D * D];
        for (int i = 0; i < D; ++i)
          for (int j = 0; j < D; ++j) g[i * D + j] = dGm(i, j);
        Mat3 de, dw;
        strain_and_spin<D>(g, de, dw);
        const Mat3 ds3 = R.apply(dw * so3 - so3 * dw + elastic_increment(el, de));
        const MatD<D> ds = ds3.topLeftCorner<D, D>();
        return k.rate_form_dP(dG, ds);
      },
      A);
}

template Mat3 trial_stress<2>(const ElasticConstants &, const TangentKinematicsT<2> &,
                              const TangentPoint &);
template Mat3 trial_stress<3>(const ElasticConstants &, const TangentKinematicsT<3> &,
                              const TangentPoint &);
template void plastic_piola_tangent<2>(const ElasticConstants &, const TangentKinematicsT<2> &,
                                       const TangentPoint &, const ReturnDerivative &, double *);
template void plastic_piola_tangent<3>(const ElasticConstants &, const TangentKinematicsT<3> &,
                                       const TangentPoint &, const ReturnDerivative &, double *);

} // namespace pmpm
