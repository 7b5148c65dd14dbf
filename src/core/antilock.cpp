#include "pmpm/core/antilock.hpp"
#include <algorithm>
#include <cmath>

namespace pmpm {

template <int D>
void fbar_groups(const ParticleView &P, const double origin[D], double h, const PetscInt lo[D],
                 const PetscInt hi[D], int nbody, std::vector<int> &group) {
  group.resize(P.n);
  const double invh = 1.0 / h;
  for (PetscInt p = 0; p < P.n; ++p) {
    bool in = true;
    PetscInt cell = 0; // ((k - lo2) * ny + (j - lo1)) * nx + (i - lo0)
    for (int d = D - 1; d >= 0; --d) {
      const PetscInt c = static_cast<PetscInt>(std::floor((P.x[p * D + d] - origin[d]) * invh));
      in = in && c >= lo[d] && c < hi[d];
      cell = cell * (hi[d] - lo[d]) + (c - lo[d]);
    }
    group[p] = in ? static_cast<int>(cell * nbody + P.body[p]) : -1;
  }
}

namespace {
// det(I + du): a step's volume ratio, du = L dt (D x D, row-major).
template <int D> double step_ratio(const double *du) {
  if constexpr (D == 2)
    return (1.0 + du[0]) * (1.0 + du[3]) - du[1] * du[2];
  else {
    const double a = 1.0 + du[0], e = 1.0 + du[4], i = 1.0 + du[8];
    return a * (e * i - du[5] * du[7]) - du[1] * (du[3] * i - du[5] * du[6]) +
           du[2] * (du[3] * du[7] - e * du[6]);
  }
}
} // namespace

template <int D>
double fbar_apply(const ParticleView &P, const std::vector<int> &group, std::vector<double> &sums,
                  double *dudx, const double *hoop) {
  constexpr int DD = D * D;
  int ng = 0;
  for (PetscInt p = 0; p < P.n; ++p) ng = std::max(ng, group[p] + 1);
  sums.assign(2 * static_cast<size_t>(ng), 0.0);
  // dJ_p = det(I + L dt): the step's volume ratio; vol (already updated) / dJ_p is the old one
  for (PetscInt p = 0; p < P.n; ++p) {
    if (group[p] < 0) continue;
    const double dJ =
        hoop ? step_ratio<D>(dudx + p * DD) * (1.0 + hoop[2 * p]) : step_ratio<D>(dudx + p * DD);
    sums[2 * group[p]] += P.vol[p];
    sums[2 * group[p] + 1] += P.vol[p] / dJ;
  }
  double change = 0;
  for (PetscInt p = 0; p < P.n; ++p) {
    if (group[p] < 0) continue;
    double *du = dudx + p * DD, *F = P.F + p * DD;
    const double dJ = hoop ? step_ratio<D>(du) * (1.0 + hoop[2 * p]) : step_ratio<D>(du),
                 dJbar = sums[2 * group[p]] / sums[2 * group[p] + 1];
    const double r = dJbar / dJ, s = D == 2 ? std::sqrt(r) : std::cbrt(r);
    change = std::max(change, std::fabs(r - 1.0));
    // I + du_bar = s (I + du)
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b)
        du[a * D + b] = a == b ? s * (1.0 + du[a * D + b]) - 1.0 : s * du[a * D + b];
    for (int k = 0; k < DD; ++k) F[k] *= s;
    P.vol[p] *= r;
  }
  return change;
}

template <int D>
void fbar_pressure_shift(const ParticleView &P, const std::vector<int> &group,
                         std::vector<double> &sums, std::vector<double> &shift) {
  int ng = 0;
  for (PetscInt p = 0; p < P.n; ++p) ng = std::max(ng, group[p] + 1);
  sums.assign(2 * static_cast<size_t>(ng), 0.0);
  shift.assign(P.n, 0.0);
  auto pressure = [&](PetscInt p) { // xx, yy, zz lead both layouts
    const double *s = P.stress + p * NStress<D>;
    return (s[0] + s[1] + s[2]) / 3.0;
  };
  for (PetscInt p = 0; p < P.n; ++p) {
    if (group[p] < 0) continue;
    sums[2 * group[p]] += P.vol[p] * pressure(p);
    sums[2 * group[p] + 1] += P.vol[p];
  }
  for (PetscInt p = 0; p < P.n; ++p)
    if (group[p] >= 0) shift[p] = sums[2 * group[p]] / sums[2 * group[p] + 1] - pressure(p);
}

#define PMPM_FBAR(D)                                                                               \
  template void fbar_groups<D>(const ParticleView &, const double[D], double, const PetscInt[D],   \
                               const PetscInt[D], int, std::vector<int> &);                        \
  template double fbar_apply<D>(const ParticleView &, const std::vector<int> &,                    \
                                std::vector<double> &, double *, const double *);                  \
  template void fbar_pressure_shift<D>(const ParticleView &, const std::vector<int> &,             \
                                       std::vector<double> &, std::vector<double> &);
PMPM_FBAR(2)
PMPM_FBAR(3)
#undef PMPM_FBAR

} // namespace pmpm
