// Material points in a DMSwarm (PIC type, the grid's DMDA as cell DM). This file and grid.hpp
// are the only places that talk to PETSc's DM objects; kernels see ParticleView.
#pragma once
#include "pmpm/util/config.hpp"
#include "pmpm/core/grid.hpp"
#include <deque>
#include <petscdmswarm.h>
#include <vector>

namespace pmpm {

// Raw per-particle arrays (each field is contiguous; block size in the comment, DIM standing for
// the swarm's dimension D and NSTRESS for NStress<D>).
struct ParticleView {
  PetscInt n = 0;
  double *x = nullptr;      // DIM, current position
  double *x0 = nullptr;     // DIM, initial position
  double *v = nullptr;      // DIM, velocity
  double *lp = nullptr;     // DIM, initial half-size (PMPM block)
  double *mass = nullptr;   // 1, inertial mass (may be scaled; never the load)
  double *vol = nullptr;    // 1, current volume (area per unit thickness)
  double *vol0 = nullptr;   // 1, initial volume
  double *weight = nullptr; // 1, body force magnitude gamma * V0 (conserved)
  double *stress = nullptr; // NSTRESS, Cauchy stress xx yy zz xy
  double *F = nullptr;      // DIM*DIM, deformation gradient, row-major
  double *eps_p = nullptr;  // 1, equivalent plastic strain
  double *colour = nullptr; // 1, interface colour (1 on the geomembrane)
  PetscInt *mat = nullptr;  // 1, material index
  PetscInt *pid = nullptr;  // 1, global particle id (rank-independent)
  PetscInt *body = nullptr; // 1, body on the grid (0 without chains; chain.hpp)
  PetscInt *load = nullptr; // 1, the particle's entry in the run's ParticleLoad table, or -1
  double *B = nullptr;      // DIM*DIM, APIC affine matrix, row-major (affine.hpp); null
                            // unless the swarm has it (-transfer apic)
};

// A surface load on one particle. Few particles carry one (a loaded face's outermost row), so
// the loads are a table every rank holds alike, in particle-id order, and a particle carries
// only its entry's index: 4 bytes instead of 32 per particle (docs/benchmarks/memory.md).
template <int D> struct ParticleLoadT {
  double traction[D]; // force on the particle's face (per unit thickness in 2D)
  double tface[D];    // initial offset from the centre to the loaded face's centre
  double lp[D];       // the particle's initial half-size (a scene rescales by face length)
};
using ParticleLoad = ParticleLoadT<DIM>;

// One particle as a scene creates it.
template <int D> struct ParticleInitT {
  double x[D];
  double lp[D];
  double vol;
  double density; // inertial density after any inertia scaling
  double gamma;   // unit weight (N/m^3)
  double traction[D];
  double tface[D];
  double colour;
  PetscInt mat;
  PetscInt pid;
  PetscInt body = 0;
  PetscInt load = -1; // set by SimulationSetup from traction (ParticleLoad)
};
using ParticleInit = ParticleInitT<DIM>;

// The particles a scene generates, before they enter the swarm. A deque, not a vector: it never
// reallocates while a scene fills it (a vector's doubling held up to 2 x 112 B per particle), and
// ParticlesAdd frees it block by block as the swarm grows, so the two never coexist in full
// (docs/benchmarks/memory.md).
template <int D> using ParticleListT = std::deque<ParticleInitT<D>>;
using ParticleList = ParticleListT<DIM>;

// The swarm of a grid of dimension dim (2 or 3; set by ParticlesCreate): fields of D (position,
// x0, v, lp), D*D (F, B) and NStress<D> (stress) values per particle.
struct Particles {
  DM sw = nullptr;
  bool affine = false; // set before ParticlesCreate: register the APIC matrix B (-transfer apic)
  int dim = DIM;
};

// Create the swarm with g's DMDA as its cell DM (destroy the swarm before the grid).
template <int D> PetscErrorCode ParticlesCreate(GridT<D> &g, Particles &P);
PetscErrorCode ParticlesDestroy(Particles &P);
// Add the particles this rank owns (they must lie in this rank's cells), consuming init: it is
// empty on return. The swarm grows in chunks while init shrinks, so peak memory is about the
// swarm's, not the swarm's plus the list's.
template <int D> PetscErrorCode ParticlesAdd(Particles &P, ParticleListT<D> &init);
// Any dimension: the arrays hold P.dim-sized blocks (ParticleView).
PetscErrorCode ParticlesGetView(Particles &P, ParticleView &v);
PetscErrorCode ParticlesRestoreView(Particles &P, ParticleView &v);
// Move particles to the ranks owning their cells (only call when some left). 2D: DMSwarm's PIC
// migrate, which drops particles outside the box and reaches only the neighbouring ranks.
PetscErrorCode ParticlesMigrate(Particles &P);
// The same on grid g in any dimension. 2D: the call above. 3D (DMSwarm 3.18's PIC point location
// is broken in 3D): each particle that left is sent to the rank owning its cell (owned-cell boxes
// of every rank, RecordsRedistribute: any rank, not only neighbours; collective), particles
// outside the box are dropped as DMSwarm drops them, and the staying particles keep their order,
// the arrivals after them in the senders' rank order.
template <int D> PetscErrorCode ParticlesMigrate(Particles &P, const GridT<D> &g);
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
