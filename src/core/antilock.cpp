#include "pmpm/core/antilock.hpp"
#include <algorithm>
#include <cmath>

namespace pmpm {

void fbar_groups(const ParticleView &P, const double origin[DIM], double h, const PetscInt lo[DIM],
                 const PetscInt hi[DIM], int nbody, std::vector<int> &group) {
  group.resize(P.n);
  const double invh = 1.0 / h;
  const PetscInt nx = hi[0] - lo[0];
  for (PetscInt p = 0; p < P.n; ++p) {
    const PetscInt i = static_cast<PetscInt>(std::floor((P.x[p * DIM] - origin[0]) * invh));
    const PetscInt j = static_cast<PetscInt>(std::floor((P.x[p * DIM + 1] - origin[1]) * invh));
    const bool in = i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1];
    group[p] = in ? static_cast<int>(((j - lo[1]) * nx + (i - lo[0])) * nbody + P.body[p]) : -1;
  }
}

double fbar_apply(const ParticleView &P, const std::vector<int> &group, std::vector<double> &sums,
                  double *dudx) {
  int ng = 0;
  for (PetscInt p = 0; p < P.n; ++p) ng = std::max(ng, group[p] + 1);
  sums.assign(2 * static_cast<size_t>(ng), 0.0);
  // dJ_p = det(I + L dt): the step's volume ratio; vol (already updated) / dJ_p is the old one
  auto step_ratio = [&](PetscInt p) {
    const double *du = dudx + p * DIM * DIM;
    return (1.0 + du[0]) * (1.0 + du[3]) - du[1] * du[2];
  };
  for (PetscInt p = 0; p < P.n; ++p) {
    if (group[p] < 0) continue;
    sums[2 * group[p]] += P.vol[p];
    sums[2 * group[p] + 1] += P.vol[p] / step_ratio(p);
  }
  double change = 0;
  for (PetscInt p = 0; p < P.n; ++p) {
    if (group[p] < 0) continue;
    const double dJ = step_ratio(p), dJbar = sums[2 * group[p]] / sums[2 * group[p] + 1];
    const double r = dJbar / dJ, s = std::sqrt(r);
    change = std::max(change, std::fabs(r - 1.0));
    double *du = dudx + p * DIM * DIM, *F = P.F + p * DIM * DIM;
    // I + du_bar = s (I + du)
    du[0] = s * (1.0 + du[0]) - 1.0;
    du[1] *= s;
    du[2] *= s;
    du[3] = s * (1.0 + du[3]) - 1.0;
    for (int k = 0; k < DIM * DIM; ++k) F[k] *= s;
    P.vol[p] *= r;
  }
  return change;
}

void fbar_pressure_shift(const ParticleView &P, const std::vector<int> &group,
                         std::vector<double> &sums, std::vector<double> &shift) {
  int ng = 0;
  for (PetscInt p = 0; p < P.n; ++p) ng = std::max(ng, group[p] + 1);
  sums.assign(2 * static_cast<size_t>(ng), 0.0);
  shift.assign(P.n, 0.0);
  auto pressure = [&](PetscInt p) {
    const double *s = P.stress + p * NSTRESS;
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

} // namespace pmpm
