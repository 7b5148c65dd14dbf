// -dim 3: a 2D scene extruded along z (extrude.hpp).
#include "pmpm/model/extrude.hpp"
#include "pmpm/contact/interface.hpp"
#include "pmpm/contact/sheet_contact.hpp"
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
      {s.geometry != Geometry::PlaneStrain, "-geometry axisymmetric"},
      {!sim.model.chain_specs.empty() && !sim.scene->extrudes_chains(),
       "this scene's membrane chains (its results read them in the plane; -scene pullout "
       "extrudes its chain as a strip of 3D sheet)"},
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
// Chain c as a strip of 3D sheet across the whole depth (extrude.hpp): checked, built, its
// material, faces, pins and end force the chain's.
PetscErrorCode SheetOfChain(Simulation &sim, const Chain &c, int k, int nbody, Sheet &st) {
  PetscFunctionBeginUser;
  const double h = sim.set.h;
  const PetscInt nz = static_cast<PetscInt>(std::llround(sim.set.depth / h));
  bool level = c.n >= 2, rising = c.n >= 2; // x increasing: a line over the plan's x
  for (int i = 1; i < c.n; ++i) {
    level = level && c.x0[i * DIM + 1] == c.x0[1];
    rising = rising && c.x0[i * DIM] > c.x0[(i - 1) * DIM];
  }
  PmpmCheckInput(rising, sim.comm, PETSC_ERR_SUP,
                 "-dim 3: chain %s is extruded as a strip of 3D sheet, which needs its points' x "
                 "to increase along it (a line over the plan, level, sloped or bent)",
                 c.name.c_str());
  // uniaxial J = E t is the sheet's E t / (1 - nu^2) only when nu = 0
  PmpmCheckInput(c.stiffness == StiffnessKind::PlaneStrain || c.nu == 0, sim.comm, PETSC_ERR_SUP,
                 "-mat_%s_axial_stiffness uniaxial with -mat_%s_nu %g: a 3D sheet is biaxial "
                 "(J = E t / (1 - nu^2)); use plane_strain, or nu = 0",
                 c.material.c_str(), c.material.c_str(), c.nu);
  st = SheetMaterialOf(c);
  st.name = c.name;
  st.thickness = c.thickness;
  const double x0 = c.x0[0], len = c.x0[(c.n - 1) * DIM] - x0;
  const int nx = c.n, nzp = static_cast<int>(nz) + 1;
  if (level) // a level line: the rectangle (the lattice's x from its ends)
    sheet_rectangle(x0, len / (nx - 1), nx, 0.0, h, nzp, c.x0[1], st);
  else // sloped or bent (a cover over a side slope and its crest): the line swept along z
    sheet_strip(c.x0.data(), nx, 0.0, h, nzp, st); // (x, y) pairs: DIM == 2
  st.held.assign(st.n, 0);
  st.fend.assign(3 * static_cast<size_t>(st.n), 0.0);
  // a point on a box face with a roller or fixed condition is held normal to it (the z faces'
  // edge rows; a chain that runs from wall to wall, as a 3D cover's, on the x faces too)
  const double lo[3] = {sim.model.origin[0], 0, 0},
               hi[3] = {sim.model.origin[0] + sim.model.ncell[0] * h, 0, nz * h};
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < nzp; ++j) {
      const int p = i * nzp + j;
      st.pinned[p] = (i == 0 && c.pin[0]) || (i == nx - 1 && c.pin[1]);
      for (int d = 0; d < 3; d += 2) {
        const double X = st.x0[3 * static_cast<size_t>(p) + d];
        if ((X == lo[d] && sim.model.face[2 * d] != FaceBC::Free) ||
            (X == hi[d] && sim.model.face[2 * d + 1] != FaceBC::Free))
          st.held[p] |= static_cast<char>(1 << d);
      }
      if (i == nx - 1) { // the end force per unit width, over the column by the points' widths
        const double width = (j == 0 || j == nzp - 1) ? 0.5 * h : h;
        for (int d = 0; d < DIM; ++d) st.fend[3 * p + d] = c.end_force[d] * width;
      }
    }
  bool lifted = false; // the scene's height at each point's z (Scene::extruded_height)
  for (int p = 0; p < st.n; ++p) {
    double *X = &st.x0[3 * static_cast<size_t>(p)], stretch;
    const double y = sim.scene->extruded_height(X[0], X[1], X[2], &stretch);
    lifted = lifted || y != X[1];
    X[1] = y;
  }
  if (lifted) {
    st.x = st.x0;
    sheet_reference(st);
  }
  sheet_normals(st);
  st.up = st.nrm[1] >= 0 ? 1.0 : -1.0; // the body above is the one at larger y
  st.body = c.body;
  st.slot = nbody * GridDofT<3>::NDOF + k * SheetDof::NDOF;
  st.top = c.top;
  st.bottom = c.bottom;
  st.slip_top.assign(3 * static_cast<size_t>(st.n), 0.0);
  st.slip_bot = st.slip_top;
  st.p_top.assign(st.n, 0.0);
  st.p_bot = st.p_top;
  PetscFunctionReturn(0);
}

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
  if (!sim.chains.empty()) AssignBodies(sim, plane); // below / above the chains' lines
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
    for (PetscInt k = g.cell_lo[2] * sim.set.ppc; k < g.cell_hi[2] * sim.set.ppc; ++k) {
      ParticleInitT<3> p{};
      for (int d = 0; d < DIM; ++d) {
        p.x[d] = q.x[d];
        p.lp[d] = q.lp[d];
      }
      p.x[2] = g.origin[2] + (k + 0.5) * dz;
      p.lp[2] = 0.5 * dz;
      p.vol = q.vol * dz;
      double stretch = 1; // the scene's height at this z (Scene::extruded_height)
      p.x[1] = sim.scene->extruded_height(q.x[0], q.x[1], p.x[2], &stretch);
      if (stretch != 1) {
        p.vol *= stretch;
        p.lp[1] *= stretch;
      }
      PetscInt c[3];
      for (int d = 0; d < 3; ++d)
        c[d] = static_cast<PetscInt>(std::floor((p.x[d] - g.origin[d]) / h));
      if (!g.owns_cell(c)) continue;
      p.density = q.density;
      p.gamma = q.gamma;
      p.colour = q.colour;
      p.mat = q.mat;
      p.pid = q.pid * nz + k;
      p.body = q.body;
      // its plane particle's entry of sim.model.loads3, where the scene loads it
      p.load = q.load >= 0 && sim.scene->extruded_loaded(p.x) ? q.load : -1;
      const int mat = sim.scene->extruded_material(p.x, p.mat);
      if (mat != p.mat) { // its own material at its 3D position (a scene's zone)
        p.mat = mat;
        p.density = sim.model.mats[mat].density;
        p.gamma = sim.model.mats[mat].gamma;
      }
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
  // the scene's chains as strips of sheet between its bodies
  const int nchain = static_cast<int>(sim.chains.size());
  const int nbody = nchain > 0 ? 2 * nchain + 1 : 1;
  for (int k = 0; k < nchain; ++k) {
    Sheet st;
    PetscCall(SheetOfChain(sim, sim.chains[k], k, nbody, st));
    sim.sheets.push_back(std::move(st));
  }
  PetscCall(
      GridCreate<3>(sim.comm, sim.set.h, origin, ncell, nbody, nchain * SheetDof::NDOF, sim.grid3));
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
  sim.chains.clear(); // the sheets stand for them from here on
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
