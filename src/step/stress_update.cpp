// The stress update of every particle, one batch per material (stress_update.hpp).
#include "pmpm/step/stress_update.hpp"

namespace pmpm {

void UpdateStresses(Simulation &sim, const double *dudx, const double *F, double *stress,
                    double *eps_p, const double *eigen) {
  for (size_t m = 0; m < sim.model.mats.size(); ++m) {
    StressBatch b;
    b.dim = sim.parts.dim;
    b.n = static_cast<int>(sim.mat_idx[m].size());
    if (b.n == 0) continue;
    b.idx = sim.mat_idx[m].data();
    b.dudx = dudx;
    b.F = F;
    b.stress = stress;
    b.eps_p = eps_p;
    b.eigen = eigen;
    b.hoop = sim.scratch.hoop.empty() ? nullptr : sim.scratch.hoop.data(); // -geometry axisymmetric
    sim.model.mats[m].model->update_stress(b);
  }
}

} // namespace pmpm
