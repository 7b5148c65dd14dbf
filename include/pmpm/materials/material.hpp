// The material interface: one batched stress update per material per step.
//
// A material receives, for each of its particles, the velocity gradient times dt (the
// increment of the displacement gradient in the current configuration, a dim x dim matrix),
// the updated deformation gradient F, and updates the particle's Cauchy stress (xx yy zz xy in
// 2D, xx yy zz xy yz xz in 3D: NStress, config.hpp; tension positive) and its internal state
// (equivalent plastic strain). Rate-form models use
// the Jaumann rate for objectivity; hyperelastic models compute the stress from F directly.
#pragma once
#include "pmpm/util/config.hpp"
#include <memory>
#include <string>
#include <vector>

namespace pmpm {

// Plain views over particle arrays; idx lists the particles this material owns.
struct StressBatch {
  int dim = 2;                  // the run's dimension (2: plane strain or axisymmetric; 3)
  int n = 0;                    // number of particles in idx
  const int *idx = nullptr;     // particle indices
  const double *dudx = nullptr; // dim*dim per particle: L*dt, row-major (dv_i/dx_j)
  const double *F = nullptr;    // dim*dim per particle: deformation gradient after the step
  double *stress = nullptr;     // NStress<dim> per particle
  double *eps_p = nullptr;      // 1 per particle: accumulated equivalent plastic strain
  // Optional eigenstrain increment (waste degradation, degradation.hpp): 3 per particle (xx,
  // yy, zz); the stress sees de - de*. Rate-form models only (Material::rate_form).
  const double *eigen = nullptr;
  // -geometry axisymmetric (geometry.hpp): 2 per particle, the hoop strain increment d_thth dt
  // (the stress's zz component is then the hoop stress) and the hoop stretch F_thth = r / r0;
  // null in plane strain (zero strain, F_zz = 1).
  const double *hoop = nullptr;
};

struct ElasticConstants {
  double E = 0, nu = 0;
  double G() const { return E / (2.0 * (1.0 + nu)); }
  double K() const { return E / (3.0 * (1.0 - 2.0 * nu)); }
  double lambda() const { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
  // constrained (P-wave) modulus M = lambda + 2G
  double M() const { return E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
};

// Elastic energy of a particle of volume V under stress s (xx, yy, zz, xy): V s : C^-1 : s / 2
// (plane strain, s_zz kept). One expression for relaxation's energy check (ElasticEnergy) and
// for G2P, which sums it on the steps that check (G2PParams::energy): the same sums bit for bit.
// In 3D (D = 3) the shears yz and xz add to xy's term.
template <int D = DIM>
inline double elastic_energy(double E, double nu, double V, const double *s) {
  const double sq = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
  const double cross = s[0] * s[1] + s[1] * s[2] + s[2] * s[0];
  double shear = s[3] * s[3];
  if constexpr (D == 3) shear += s[4] * s[4] + s[5] * s[5];
  return V * ((sq - 2 * nu * cross) + 2 * (1 + nu) * shear) / (2 * E);
}

// One particle's state at which -solver newton differentiates the update (piola_tangent,
// implicit_kernels.hpp): the step's increment gradient G (DIM x DIM, row-major; the rate-form
// update reads its midpoint gradient (I + G/2)^-1 G), the committed stress s_old, the stress s_new
// at G (after the update), the committed F (Fn) and eps_p, and the step's eigenstrain increment
// (3 values xx yy zz, or null; StressBatch::eigen).
struct TangentPoint {
  const double *G = nullptr, *s_old = nullptr, *s_new = nullptr, *Fn = nullptr;
  double eps_p = 0;
  const double *eigen = nullptr;
};

class Material {
public:
  virtual ~Material() = default;
  virtual const char *model() const = 0;
  // P-wave modulus that bounds the wave speed (for the stable time step and inertia scaling).
  virtual double wave_modulus() const = 0;
  // True when the model can yield: scenes report plastic state only for these.
  virtual bool plastic() const { return false; }
  // plastic flow that changes volume (Drucker-Prager with psi > 0)
  virtual bool dilatant() const { return false; }
  // True when the stress is updated from strain increments (an eigenstrain can be imposed).
  virtual bool rate_form() const { return true; }
  virtual void update_stress(const StressBatch &b) const = 0;
  // Linear elasticity in rate form (LinearElastic): its Lame constant lambda and 2G, so G2P can
  // update the stress in its own particle loop (elastic_rate_update, elastic.hpp). False for
  // every other model.
  virtual bool linear_elastic_rate(double & /*lambda*/, double & /*G2*/) const { return false; }
  // -solver newton: true when the model has a consistent tangent (piola_tangent below); false:
  // -solver newton refuses it.
  virtual bool has_tangent() const { return false; }
  // The consistent tangent A = dP / dG (DIM^2 x DIM^2, A[(a DIM + j) DIM^2 + (b DIM + l)] =
  // dP_aj / dG_bl) of one particle at pt, P = J sigma' f^-T (implicit_kernels.hpp): exact for this
  // model's update_stress as -solver newton calls it. Called only when has_tangent().
  virtual void piola_tangent(const TangentPoint & /*pt*/, double * /*A*/) const {}
  // The same in 3D (G and F 3 x 3, the stresses xx yy zz xy yz xz, A 9 x 9).
  virtual void piola_tangent3(const TangentPoint & /*pt*/, double * /*A*/) const {}
};

// Small-strain increment and spin from L*dt (D x D, row-major; 3x3, in 2D zz rows/cols zero).
template <int D = DIM> inline void strain_and_spin(const double *dudx, Mat3 &de, Mat3 &dw) {
  Mat3 g = Mat3::Zero();
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) g(i, j) = dudx[i * D + j];
  de = 0.5 * (g + g.transpose());
  dw = 0.5 * (g - g.transpose());
}

// Jaumann rotation of a stress over the step: sigma + dw sigma - sigma dw.
inline Mat3 jaumann_rotate(const Mat3 &s, const Mat3 &dw) {
  return s + dw * s - s * dw;
}

// Isotropic linear elastic increment: lambda tr(de) I + 2 G de.
inline Mat3 elastic_increment(const ElasticConstants &c, const Mat3 &de) {
  return c.lambda() * de.trace() * Mat3::Identity() + 2.0 * c.G() * de;
}

// The rate-form elastoplastic update shared by the plastic models: elastic predictor (Jaumann-
// rotated old stress + C : de) and a return map ret(Mat3 &sigma, double &eps_p) per particle.
// D: the dimension (StressBatch::dim); Hoop: the axisymmetric hoop strain increment
// (StressBatch::hoop, 2D only) in de's zz entry.
template <int D, bool Hoop, class Return>
inline void predictor_corrector_loop(const StressBatch &b, const ElasticConstants &el,
                                     Return &ret) {
  constexpr int NS = NStress<D>;
  for (int k = 0; k < b.n; ++k) {
    const int p = b.idx[k];
    Mat3 de, dw;
    strain_and_spin<D>(b.dudx + p * D * D, de, dw);
    if (Hoop) de(2, 2) = b.hoop[2 * p];
    if (b.eigen)
      for (int d = 0; d < 3; ++d) de(d, d) -= b.eigen[3 * p + d];
    Mat3 s = jaumann_rotate(stress_to_tensor<D>(b.stress + p * NS), dw) + elastic_increment(el, de);
    double ep = b.eps_p ? b.eps_p[p] : 0.0;
    ret(s, ep);
    if (b.eps_p) b.eps_p[p] = ep;
    tensor_to_stress<D>(s, b.stress + p * NS);
  }
}
// The dimension and the geometry chosen once per batch, not per particle.
template <class Return>
inline void predictor_corrector(const StressBatch &b, const ElasticConstants &el, Return &&ret) {
  if (b.dim == 3)
    predictor_corrector_loop<3, false>(b, el, ret);
  else if (b.hoop)
    predictor_corrector_loop<2, true>(b, el, ret);
  else
    predictor_corrector_loop<2, false>(b, el, ret);
}

} // namespace pmpm
