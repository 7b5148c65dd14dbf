// Linear elastic (hypoelastic, Jaumann rate) and compressible neo-Hookean materials.
#pragma once
#include "pmpm/material.hpp"
#include <cmath>

namespace pmpm {

// Linear isotropic elasticity in rate form: sigma <- jaumann(sigma) + C : de.
// Exact for small strain; objective under large rotation.
class LinearElastic final : public Material {
public:
  explicit LinearElastic(const ElasticConstants &c) : c_(c) {}
  const char *model() const override { return "linear_elastic"; }
  double wave_modulus() const override { return c_.M(); }
  void update_stress(const StressBatch &b) const override {
    for (int k = 0; k < b.n; ++k) {
      const int p = b.idx[k];
      Mat3 de, dw;
      strain_and_spin(b.dudx + p * DIM * DIM, de, dw);
      const Mat3 s = jaumann_rotate(stress_to_tensor(b.stress + p * NSTRESS), dw);
      tensor_to_stress(s + elastic_increment(c_, de), b.stress + p * NSTRESS);
    }
  }

private:
  ElasticConstants c_;
};

// Compressible neo-Hookean: sigma = (mu (B - I) + lambda ln J I) / J, B = F F^T (plane strain,
// F_zz = 1). Hyperelastic, so the stress is a function of F alone: exact at any deformation.
inline Mat3 neo_hookean_stress(const ElasticConstants &c, const double *Fp) {
  Mat3 F = Mat3::Identity();
  for (int i = 0; i < DIM; ++i)
    for (int j = 0; j < DIM; ++j) F(i, j) = Fp[i * DIM + j];
  const double J = F.determinant();
  const Mat3 B = F * F.transpose();
  return (c.G() * (B - Mat3::Identity()) + c.lambda() * std::log(J) * Mat3::Identity()) / J;
}

class NeoHookean final : public Material {
public:
  explicit NeoHookean(const ElasticConstants &c) : c_(c) {}
  const char *model() const override { return "neo_hookean"; }
  double wave_modulus() const override { return c_.M(); }
  void update_stress(const StressBatch &b) const override {
    for (int k = 0; k < b.n; ++k) {
      const int p = b.idx[k];
      tensor_to_stress(neo_hookean_stress(c_, b.F + p * DIM * DIM), b.stress + p * NSTRESS);
    }
  }

private:
  ElasticConstants c_;
};

} // namespace pmpm
