#include "pmpm/scenes/scene_util.hpp"
#include "pmpm/materials/elastic.hpp"
#include "pmpm/util/options.hpp"
#include <cmath>
#include <cstring>
#include <memory>

namespace pmpm {

void FillRegular(const Simulation &sim, const MaterialAt &at, ParticleList &out) {
  const double h = sim.set.h;
  const PetscInt ppc = sim.set.ppc;
  const double dx = h / ppc;
  const Grid &g = sim.grid;
  for (PetscInt j = g.cell_lo[1]; j < g.cell_hi[1]; ++j)
    for (PetscInt i = g.cell_lo[0]; i < g.cell_hi[0]; ++i)
      for (PetscInt b = 0; b < ppc; ++b)
        for (PetscInt a = 0; a < ppc; ++a) {
          ParticleInit q{};
          q.x[0] = sim.model.origin[0] + i * h + (a + 0.5) * dx;
          q.x[1] = sim.model.origin[1] + j * h + (b + 0.5) * dx;
          const int m = at(q.x);
          if (m < 0) continue;
          q.lp[0] = q.lp[1] = 0.5 * dx;
          q.vol = dx * dx;
          q.mat = m;
          q.density = sim.model.mats[m].density;
          q.gamma = sim.model.mats[m].gamma;
          q.pid = ((j * sim.model.ncell[0] + i) * ppc + b) * ppc + a;
          out.push_back(q);
        }
}

PetscErrorCode CompareVertical(Simulation &sim, const std::function<double(double)> &sigma_yy,
                               const std::function<double(double)> &u_y,
                               const std::vector<double> &rows, VerticalComparison &out) {
  ParticleView P;
  PetscFunctionBeginUser;
  const size_t nr = rows.size();
  // sums: stress err^2 V, stress^2 V, disp err^2 V, disp^2 V, then per row: u, u_exact, count
  std::vector<double> s(4 + 3 * nr, 0.0);
  const double tol = 1e-9 * (rows.empty() ? 1.0 : std::fabs(rows.back()));
  PetscCall(ParticlesGetView(sim.parts, P));
  const int D = sim.parts.dim, NS = D == 3 ? NStress<3> : NSTRESS; // -dim 3: extruded
  for (PetscInt p = 0; p < P.n; ++p) {
    const double Y = P.x0[p * D + 1], V0 = P.vol0[p], l = P.lp[p * D + 1];
    const double u = P.x[p * D + 1] - Y, ue = u_y(Y);
    const double se = sigma_yy(Y), sy = P.stress[p * NS + 1];
    s[0] += (sy - se) * (sy - se) * V0;
    s[1] += se * se * V0;
    s[2] += (u - ue) * (u - ue) * V0;
    s[3] += ue * ue * V0;
    for (size_t r = 0; r < nr; ++r)
      if (Y < rows[r] && Y + l > rows[r] - tol) {
        s[4 + 3 * r] += u;
        s[5 + 3 * r] += ue;
        s[6 + 3 * r] += 1;
      }
  }
  PetscCall(ParticlesRestoreView(sim.parts, P));
  PetscCall(SumAll(sim.comm, s.data(), static_cast<int>(s.size())));
  out.stress_l2 = std::sqrt(s[0] / s[1]);
  out.displacement_l2 = std::sqrt(s[2] / s[3]);
  out.row_u.assign(nr, 0.0);
  out.row_u_exact.assign(nr, 0.0);
  for (size_t r = 0; r < nr; ++r) {
    out.row_u[r] = s[4 + 3 * r] / s[6 + 3 * r];
    out.row_u_exact[r] = s[5 + 3 * r] / s[6 + 3 * r];
  }
  PetscFunctionReturn(0);
}

double UniaxialStrainJ(const MaterialEntry &m, double sig) {
  const ElasticConstants &c = m.el;
  double J = std::exp(sig / c.M());
  if (std::strcmp(m.model->model(), NeoHookean::kName) != 0) return J;
  for (int it = 0; it < 60; ++it) { // Newton on g(J) = lambda ln J + mu (J^2 - 1) - sig J
    const double g = c.lambda() * std::log(J) + c.G() * (J * J - 1) - sig * J;
    const double dg = c.lambda() / J + 2 * c.G() * J - sig;
    const double step = g / dg;
    J -= step;
    if (std::fabs(step) < 1e-15 * J) break;
  }
  return J;
}

PetscErrorCode GatherToRoot(MPI_Comm comm, const std::vector<double> &mine,
                            std::vector<double> &all) {
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(size), displs(size, 0);
  PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm));
  int total = 0;
  if (rank == 0)
    for (int r = 0; r < size; ++r) {
      displs[r] = total;
      total += counts[r];
    }
  all.assign(rank == 0 ? total : 0, 0.0);
  PetscCallMPI(MPI_Gatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                           MPI_DOUBLE, 0, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode SumAll(MPI_Comm comm, double *v, int n) {
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode MembraneThicknessOption(MPI_Comm comm, const char *title, double *t) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "membrane_", title, nullptr);
  PetscCall(
      PmpmOptionsReal("-thickness", "Membrane thickness t (m), > 0", nullptr, *t, t, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode CheckMembraneThickness(MPI_Comm comm, double t) {
  PetscFunctionBeginUser;
  PmpmCheckInput(t > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-membrane_thickness must be > 0 (got %g)",
                 t);
  PetscFunctionReturn(0);
}

} // namespace pmpm
