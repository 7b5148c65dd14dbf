// -geometry axisymmetric at setup: the refusals, the axis, the radius weights (geometry.hpp).
#include "pmpm/model/geometry.hpp"
#include "pmpm/util/options.hpp"
#include "pmpm/model/simulation.hpp"
#include "pmpm/model/solver.hpp"

namespace pmpm {

PetscErrorCode GeometryCheck(Simulation &sim) {
  PetscFunctionBeginUser;
  if (sim.set.geometry != Geometry::Axisymmetric) PetscFunctionReturn(0);
  // Newton's tangent has no hoop terms (chains and F-bar do: chain.hpp, antilock.hpp)
  PmpmCheckInput(sim.solver->supports(SolverFeature::Axisymmetric), sim.comm, PETSC_ERR_SUP,
                 "-solver %s is not supported with -geometry axisymmetric (use -solver "
                 "relaxation)",
                 sim.set.solver.c_str());
  PmpmCheckInput(sim.model.origin[0] >= 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-geometry axisymmetric needs the grid at r = x >= 0: scene %s's box starts at "
                 "x = %g m (use -geometry plane_strain)",
                 sim.set.scene.c_str(), sim.model.origin[0]);
  PmpmCheckInput(sim.model.origin[0] > 0 || (sim.model.face_traction[XMIN][0] == 0 &&
                                             sim.model.face_traction[XMIN][1] == 0),
                 sim.comm, PETSC_ERR_ARG_INCOMP,
                 "-bc_xmin_traction acts on the axis r = 0 under -geometry axisymmetric: remove "
                 "it (the axis takes no load)");
  // the axis is a line of symmetry: v_r = 0 on its nodes
  if (sim.model.origin[0] == 0 && sim.model.face[XMIN] == FaceBC::Free)
    sim.model.face[XMIN] = FaceBC::Roller;
  sim.grid.axisymmetric = true;
  PetscFunctionReturn(0);
}

PetscErrorCode GeometryWeight(const Simulation &sim, ParticleList &init) {
  PetscFunctionBeginUser;
  if (sim.set.geometry != Geometry::Axisymmetric) PetscFunctionReturn(0);
  for (ParticleInit &q : init) {
    PetscCheck(q.x[0] > 0 && q.x[0] - q.lp[0] >= -1e-12 * sim.set.h, PETSC_COMM_SELF,
               PETSC_ERR_PLIB,
               "particle %" PetscInt_FMT " at r = %g (half-size %g) reaches r < 0 under "
               "-geometry axisymmetric",
               q.pid, q.x[0], q.lp[0]);
    q.vol *= q.x[0];
    // the face's radius: x_p for a face along r (the mean of r over it), x_p +- l for a face of
    // constant r
    const double rf = q.x[0] + q.tface[0];
    for (int d = 0; d < DIM; ++d) q.traction[d] *= rf;
  }
  PetscFunctionReturn(0);
}

} // namespace pmpm
