// -dim 3: a 2D scene extruded along z (extrude.hpp).
#include "pmpm/model/extrude.hpp"
#include "pmpm/contact/interface.hpp"
#include "pmpm/model/balance.hpp"
#include "pmpm/util/options.hpp"
#include <cmath>

namespace pmpm {

PetscErrorCode ExtrusionCheck(Simulation &sim) {
  const Settings &s = sim.set;
  PetscFunctionBeginUser;
  if (s.dim == 2) {
    PmpmCheckInput(s.depth == 0, sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-depth %g is for -dim 3 (the run is 2D: -dim 2)", s.depth);
    PetscFunctionReturn(0);
  }
  PmpmCheckInput(sim.scene->extrudes(), sim.comm, PETSC_ERR_SUP,
                 "-dim 3: -scene %s has no 3D form yet (its results read the plane); scenes "
                 "that extrude: %s",
                 s.scene.c_str(), ExtrudingScenes().c_str());
  // each refusal names what to change
  const struct {
    bool refused;
    const char *what;
  } refusals[] = {
      {s.solver != "relaxation", "-solver newton (use -solver relaxation)"},
      {s.geometry != Geometry::PlaneStrain, "-geometry axisymmetric"},
      {!sim.model.chain_specs.empty(), "membrane chains"},
  };
  for (const auto &r : refusals)
    PmpmCheckInput(!r.refused, sim.comm, PETSC_ERR_SUP, "-dim 3 does not run %s yet", r.what);
  PetscFunctionReturn(0); // -depth in whole cells: ExtrudedGridAndParticles, which comes next
}

PetscErrorCode ExtrudeLoads(Simulation &sim) {
  PetscFunctionBeginUser;
  const double dz = sim.set.h / sim.set.ppc;
  sim.model.loads3.resize(sim.model.loads.size());
  for (size_t k = 0; k < sim.model.loads.size(); ++k) {
    const ParticleLoad &L = sim.model.loads[k];
    ParticleLoadT<3> &L3 = sim.model.loads3[k];
    for (int d = 0; d < DIM; ++d) {
      L3.traction[d] = L.traction[d] * dz;
      L3.tface[d] = L.tface[d];
      L3.lp[d] = L.lp[d];
    }
    L3.traction[2] = L3.tface[2] = 0;
    L3.lp[2] = 0.5 * dz;
  }
  PetscFunctionReturn(0);
}

namespace {
// The 2D scene's particles over the whole plane: the plane's grid is the box's cells, with no DM
// (FillRegular and the scenes read its owned cells).
PetscErrorCode GeneratePlane(Simulation &sim, ParticleList &plane) {
  Grid &g = sim.grid;
  PetscFunctionBeginUser;
  g.h = sim.set.h;
  for (int d = 0; d < DIM; ++d) {
    g.origin[d] = sim.model.origin[d];
    g.ncell[d] = sim.model.ncell[d];
    g.cell_lo[d] = 0;
    g.cell_hi[d] = sim.model.ncell[d];
  }
  PetscCall(sim.scene->generate(sim, plane));
  // the plane's surface loads (per unit depth), a table every rank builds from its whole plane,
  // then each entry for a particle of z spacing dz: the force times dz, the face and the
  // half-size with their z components
  PetscCall(ApplyFaceTractions(sim, plane));
  PetscCall(BuildLoadTable(sim, plane, PETSC_COMM_SELF));
  PetscCall(ExtrudeLoads(sim));
  PetscFunctionReturn(0);
}

// The plane's particles extruded into the z cells this rank owns, each kept only where this rank
// owns its (x, y) cell too.
void Extrude(const Simulation &sim, const ParticleList &plane, ParticleListT<3> &out) {
  const GridT<3> &g = sim.grid3;
  const double h = sim.set.h, dz = h / sim.set.ppc;
  const PetscInt nz = g.ncell[2] * sim.set.ppc; // particles along z
  for (const ParticleInit &q : plane) {
    PetscInt c[3];
    for (int d = 0; d < DIM; ++d)
      c[d] = static_cast<PetscInt>(std::floor((q.x[d] - g.origin[d]) / h));
    c[2] = g.cell_lo[2];
    if (!g.owns_cell(c)) continue;
    for (PetscInt k = g.cell_lo[2] * sim.set.ppc; k < g.cell_hi[2] * sim.set.ppc; ++k) {
      ParticleInitT<3> p{};
      for (int d = 0; d < DIM; ++d) {
        p.x[d] = q.x[d];
        p.lp[d] = q.lp[d];
      }
      p.x[2] = g.origin[2] + (k + 0.5) * dz;
      p.lp[2] = 0.5 * dz;
      p.vol = q.vol * dz;
      p.density = q.density;
      p.gamma = q.gamma;
      p.colour = q.colour;
      p.mat = q.mat;
      p.pid = q.pid * nz + k;
      p.body = q.body;
      p.load = q.load; // its plane particle's entry of sim.model.loads3
      if (sim.scene->keeps_extruded(p.x)) out.push_back(p);
    }
  }
}
} // namespace

PetscErrorCode ExtrudedGridAndParticles(Simulation &sim, const MemoryCheck &mem) {
  PetscFunctionBeginUser;
  double origin[3] = {sim.model.origin[0], sim.model.origin[1], 0.0};
  PetscInt ncell[3] = {sim.model.ncell[0], sim.model.ncell[1], 0};
  PetscCall(CheckCells(sim.comm, "-depth", sim.set.depth, sim.set.h, &ncell[2]));
  PetscCall(CheckProcessGrid(sim, 3, ncell));
  PetscCall(CheckMemoryExtruded(sim, mem, ncell[2], 0));
  PetscCall(GridCreate<3>(sim.comm, sim.set.h, origin, ncell, 1, 0, sim.grid3));
  sim.parts.affine = sim.set.transfer == Transfer::Apic; // APIC's B (affine.hpp)
  PetscCall(ParticlesCreate(sim.grid3, sim.parts));
  {
    ParticleList plane;
    PetscCall(GeneratePlane(sim, plane));
    PetscCall(BalanceSetupExtruded(sim, plane)); // -balance setup: lx, ly from the plane
    // ids: 2D id x (z cells x ppc) + z index, within PetscInt's range
    double top = 0;
    for (const ParticleInit &q : plane) top = std::fmax(top, static_cast<double>(q.pid));
    const double nz = static_cast<double>(ncell[2] * sim.set.ppc);
    PmpmCheckInput((top + 1) * nz <= static_cast<double>(PETSC_MAX_INT), sim.comm,
                   PETSC_ERR_ARG_OUTOFRANGE,
                   "-dim 3: %.0f particle ids (the plane's %.0f x %.0f along z) exceed PetscInt's "
                   "range; reduce -depth or use a PETSc built with 64-bit indices",
                   (top + 1) * nz, top + 1, nz);
    ParticleListT<3> init;
    Extrude(sim, plane, init);
    plane.clear();
    PetscCall(CheckMemoryExtruded(sim, mem, ncell[2], static_cast<PetscInt>(init.size())));
    PetscCall(ParticlesAdd(sim.parts, init));
  }
  // the colour interface's body grid, beside the 3D grid as balanced (interface.hpp)
  if (sim.model.iface.type != InterfaceType::Bonded)
    PetscCall(InterfaceGridCreate(sim.grid3, sim.iface_grid));
  PetscCall(SimulationIndexParticles(sim));
  PetscInt n;
  PetscCall(ParticlesGlobalCount(sim.parts, &n));
  sim.particles_setup = n;
  PetscCheck(n > 0 || !sim.sheets.empty(), sim.comm, PETSC_ERR_USER_INPUT,
             "the scene produced no particles: check the geometry options against -cell_size");
  PetscFunctionReturn(0);
}

} // namespace pmpm
