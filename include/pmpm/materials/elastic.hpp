// Linear elastic (hypoelastic, Jaumann rate) and compressible neo-Hookean materials.
#pragma once
#include "pmpm/materials/material.hpp"
#include <petscsys.h>
#include <cmath>
#include <memory>
#include <string>

namespace pmpm {

// The linear elastic rate update of one particle (LinearElastic::update_stress without an
// eigenstrain): g = L dt, row-major. Plane strain written out (the same algebra as jaumann_rotate
// + elastic_increment on 3x3 tensors, without the temporaries): with spin
// w = (du/dy - dv/dx)/2, sxx += 2 w sxy, syy -= 2 w sxy, sxy += w (syy - sxx), szz unchanged;
// then + C : de. G2P calls it too, fused into its particle loop (transfers.hpp, G2PParams).
inline void elastic_rate_update(double lam, double G2, const double g[DIM * DIM], double exx,
                                double eyy, double ezz, double *s) {
  const double exy = 0.5 * (g[1] + g[2]), w = 0.5 * (g[1] - g[2]);
  const double sxx = s[0], syy = s[1], sxy = s[3], ltr = lam * (exx + eyy + ezz);
  s[0] = sxx + 2.0 * w * sxy + ltr + G2 * exx;
  s[1] = syy - 2.0 * w * sxy + ltr + G2 * eyy;
  s[2] += ltr + G2 * ezz;
  s[3] = sxy + w * (syy - sxx) + G2 * exy;
}

// The same in 3D, written out on the six components (xx yy zz xy yz xz): with the spin
// W = (g - g^T) / 2 and Q = W s, the Jaumann term W s - s W is Q + Q^T; then + C : de with
// de = sym(g) less the eigenstrain (exx, eyy, ezz given). The plastic models' predictor-corrector
// on 3x3 tensors did the same algebra 6.5x slower (docs/benchmarks/lean3d.md). With g's and s's
// out-of-plane terms zero it is the 2D update term by term.
inline void elastic_rate_update3(double lam, double G2, const double g[9], double exx, double eyy,
                                 double ezz, double *s) {
  const double wxy = 0.5 * (g[1] - g[3]), wyz = 0.5 * (g[5] - g[7]), wxz = 0.5 * (g[2] - g[6]);
  const double exy = 0.5 * (g[1] + g[3]), eyz = 0.5 * (g[5] + g[7]), exz = 0.5 * (g[2] + g[6]);
  const double sxx = s[0], syy = s[1], szz = s[2], sxy = s[3], syz = s[4], sxz = s[5];
  const double ltr = lam * (exx + eyy + ezz);
  s[0] = sxx + 2.0 * wxy * sxy + 2.0 * wxz * sxz + ltr + G2 * exx;
  s[1] = syy - 2.0 * wxy * sxy + 2.0 * wyz * syz + ltr + G2 * eyy;
  s[2] = szz - 2.0 * wxz * sxz - 2.0 * wyz * syz + ltr + G2 * ezz;
  s[3] = sxy + wxy * (syy - sxx) + wxz * syz + wyz * sxz + G2 * exy;
  s[4] = syz + wyz * (szz - syy) - wxy * sxz - wxz * sxy + G2 * eyz;
  s[5] = sxz + wxz * (szz - sxx) + wxy * syz - wyz * sxy + G2 * exz;
}

// Linear isotropic elasticity in rate form: sigma <- jaumann(sigma) + C : de.
// Exact for small strain; objective under large rotation.
class LinearElastic final : public Material {
public:
  static constexpr const char *kName = "linear_elastic";
  static constexpr bool kRateForm = true, kPlastic = false;
  struct Options {}; // -E and -nu only (every material's)
  static PetscErrorCode ReadOptions(PetscOptionItems *, Options &) { return 0; }
  static PetscErrorCode Create(MPI_Comm comm, const std::string &prefix, const ElasticConstants &el,
                               const Options &o, std::unique_ptr<Material> &model);
  explicit LinearElastic(const ElasticConstants &c) : c_(c) {}
  const char *model() const override { return kName; }
  bool rate_form() const override { return kRateForm; }
  bool plastic() const override { return kPlastic; }
  bool has_tangent() const override { return true; }
  void piola_tangent(const TangentPoint &pt, double *A) const override { tangent<DIM>(pt, A); }
  void piola_tangent3(const TangentPoint &pt, double *A) const override { tangent<3>(pt, A); }
  double wave_modulus() const override { return c_.M(); }
  bool linear_elastic_rate(double &lam, double &G2) const override {
    lam = c_.lambda();
    G2 = 2.0 * c_.G();
    return true;
  }
  void update_stress(const StressBatch &b) const override {
    if (b.dim == 3)
      update3(b);
    else if (b.hoop) // the geometry once per batch (geometry.hpp)
      update<true>(b);
    else
      update<false>(b);
  }

private:
  // the consistent tangent in D dimensions (piola_tangent, piola_tangent3)
  template <int D> void tangent(const TangentPoint &pt, double *A) const;
  template <bool Hoop> void update(const StressBatch &b) const {
    const double lam = c_.lambda(), G2 = 2.0 * c_.G();
    for (int k = 0; k < b.n; ++k) {
      const int p = b.idx[k];
      const double *g = b.dudx + p * DIM * DIM;
      double *s = b.stress + p * NSTRESS;
      double exx = g[0], eyy = g[3], ezz = Hoop ? b.hoop[2 * p] : 0;
      if (b.eigen) {
        exx -= b.eigen[3 * p];
        eyy -= b.eigen[3 * p + 1];
        ezz -= b.eigen[3 * p + 2];
      }
      elastic_rate_update(lam, G2, g, exx, eyy, ezz, s);
    }
  }
  void update3(const StressBatch &b) const {
    const double lam = c_.lambda(), G2 = 2.0 * c_.G();
    for (int k = 0; k < b.n; ++k) {
      const int p = b.idx[k];
      const double *g = b.dudx + p * 9;
      double exx = g[0], eyy = g[4], ezz = g[8];
      if (b.eigen) {
        exx -= b.eigen[3 * p];
        eyy -= b.eigen[3 * p + 1];
        ezz -= b.eigen[3 * p + 2];
      }
      elastic_rate_update3(lam, G2, g, exx, eyy, ezz, b.stress + p * NStress<3>);
    }
  }
  ElasticConstants c_;
};

// Compressible neo-Hookean: sigma = (mu (B - I) + lambda ln J I) / J, B = F F^T (3D: F is D x D,
// row-major; plane strain, F_zz = 1; axisymmetric, F_zz = F_thth = r / r0). Hyperelastic, so the
// stress is a function of F alone: exact at any deformation.
template <int D = DIM>
inline Mat3 neo_hookean_stress(const ElasticConstants &c, const double *Fp, double Fzz = 1.0) {
  Mat3 F = Mat3::Identity();
  F(2, 2) = Fzz;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) F(i, j) = Fp[i * D + j];
  const double J = F.determinant();
  const Mat3 B = F * F.transpose();
  return (c.G() * (B - Mat3::Identity()) + c.lambda() * std::log(J) * Mat3::Identity()) / J;
}

class NeoHookean final : public Material {
public:
  static constexpr const char *kName = "neo_hookean";
  static constexpr bool kRateForm = false, kPlastic = false; // the stress is a function of F
  struct Options {};                                         // -E and -nu only (every material's)
  static PetscErrorCode ReadOptions(PetscOptionItems *, Options &) { return 0; }
  static PetscErrorCode Create(MPI_Comm comm, const std::string &prefix, const ElasticConstants &el,
                               const Options &o, std::unique_ptr<Material> &model);
  explicit NeoHookean(const ElasticConstants &c) : c_(c) {}
  const char *model() const override { return kName; }
  bool has_tangent() const override { return true; }
  void piola_tangent(const TangentPoint &pt, double *A) const override { tangent<DIM>(pt, A); }
  void piola_tangent3(const TangentPoint &pt, double *A) const override { tangent<3>(pt, A); }
  double wave_modulus() const override { return c_.M(); }
  bool rate_form() const override { return kRateForm; }
  bool plastic() const override { return kPlastic; }
  void update_stress(const StressBatch &b) const override {
    if (b.dim == 3) {
      for (int k = 0; k < b.n; ++k) {
        const int p = b.idx[k];
        tensor_to_stress<3>(neo_hookean_stress<3>(c_, b.F + p * 9), b.stress + p * NStress<3>);
      }
    } else if (b.hoop) { // the geometry once per batch: F_zz = F_thth (geometry.hpp)
      for (int k = 0; k < b.n; ++k) {
        const int p = b.idx[k];
        tensor_to_stress(neo_hookean_stress(c_, b.F + p * DIM * DIM, b.hoop[2 * p + 1]),
                         b.stress + p * NSTRESS);
      }
    } else {
      for (int k = 0; k < b.n; ++k) {
        const int p = b.idx[k];
        tensor_to_stress(neo_hookean_stress(c_, b.F + p * DIM * DIM), b.stress + p * NSTRESS);
      }
    }
  }

private:
  // the consistent tangent in D dimensions (piola_tangent, piola_tangent3)
  template <int D> void tangent(const TangentPoint &pt, double *A) const;
  ElasticConstants c_;
};

} // namespace pmpm
