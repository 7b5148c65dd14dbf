// Material points in a DMSwarm (PIC type, the grid's DMDA as cell DM). This file and grid.hpp
// are the only places that talk to PETSc's DM objects; kernels see ParticleView.
#pragma once
#include "pmpm/config.hpp"
#include "pmpm/grid.hpp"
#include <petscdmswarm.h>
#include <vector>

namespace pmpm {

// Raw per-particle arrays (each field is contiguous; block size in the comment).
struct ParticleView {
  PetscInt n = 0;
  double *x = nullptr;        // DIM, current position
  double *x0 = nullptr;       // DIM, initial position
  double *v = nullptr;        // DIM, velocity
  double *lp = nullptr;       // DIM, initial half-size (PMPM block)
  double *mass = nullptr;     // 1, inertial mass (may be scaled; never the load)
  double *vol = nullptr;      // 1, current volume (area per unit thickness)
  double *vol0 = nullptr;     // 1, initial volume
  double *weight = nullptr;   // 1, body force magnitude gamma * V0 (conserved)
  double *traction = nullptr; // DIM, surface force on the particle's face (per unit thickness)
  double *tface = nullptr;    // DIM, initial offset from the centre to the loaded face's centre
  double *stress = nullptr;   // NSTRESS, Cauchy stress xx yy zz xy
  double *F = nullptr;        // DIM*DIM, deformation gradient, row-major
  double *eps_p = nullptr;    // 1, equivalent plastic strain
  double *colour = nullptr;   // 1, interface colour (1 on the geomembrane)
  PetscInt *mat = nullptr;    // 1, material index
  PetscInt *pid = nullptr;    // 1, global particle id (rank-independent)
  PetscInt *body = nullptr;   // 1, body on the grid (0 without chains; chain.hpp)
  double *B = nullptr;        // DIM*DIM, APIC affine matrix, row-major (affine.hpp); null
                              // unless the swarm has it (-transfer apic)
};

// One particle as a scene creates it.
struct ParticleInit {
  double x[DIM];
  double lp[DIM];
  double vol;
  double density; // inertial density after any inertia scaling
  double gamma;   // unit weight (N/m^3)
  double traction[DIM];
  double tface[DIM];
  double colour;
  PetscInt mat;
  PetscInt pid;
  PetscInt body = 0;
};

struct Particles {
  DM sw = nullptr;
  bool affine = false; // set before ParticlesCreate: register the APIC matrix B (-transfer apic)
};

PetscErrorCode ParticlesCreate(Grid &g, Particles &P);
PetscErrorCode ParticlesDestroy(Particles &P);
// Add the particles this rank owns (they must lie in this rank's cells).
PetscErrorCode ParticlesAdd(Particles &P, const std::vector<ParticleInit> &init);
PetscErrorCode ParticlesGetView(Particles &P, ParticleView &v);
PetscErrorCode ParticlesRestoreView(Particles &P, ParticleView &v);
// Move particles to the ranks owning their cells (only call when some left).
PetscErrorCode ParticlesMigrate(Particles &P);
PetscErrorCode ParticlesGlobalCount(Particles &P, PetscInt *n);

// Every per-particle field, the coordinates first: its DMSwarm name, values per particle, and
// whether it holds integers (PETSC_INT) rather than reals. A checkpoint saves them all. The
// affine matrix "B" is in the list only when the swarm has it (P.affine).
struct ParticleFieldInfo {
  const char *name;
  int bs;
  bool integer;
};
std::vector<ParticleFieldInfo> ParticlesFieldList(const Particles &P);
inline constexpr const char *kAffineField = "B";

} // namespace pmpm
