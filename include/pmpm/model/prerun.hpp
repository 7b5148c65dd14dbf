// What can be checked before the run is checked before it, each failure one line naming the
// option (printed once when every rank meets it, main.cpp): an -output_dir that cannot be
// created or written (instead of a page of HDF5 diagnostics after the whole run), and a run that
// needs more memory than its nodes have (instead of an allocation failing deep in PETSc).
#pragma once
#include "pmpm/model/simulation.hpp"
#include <string>

namespace pmpm {

// -output_dir: an existing directory must be writable; otherwise its nearest existing ancestor
// must be a writable directory (probed by creating and removing a temporary directory there).
// Nothing is left behind. Rank-collective (rank 0 probes).
PetscErrorCode CheckOutputDir(MPI_Comm comm, const std::string &dir);

// Memory. The estimate (bytes):
//   grid:      nodes x values per node x 8 x 2 (the local, ghosted, and the global vector), plus
//              the coordinates and PETSc's index maps (kGridBytesPerNode), plus the interface
//              grid's two vectors when an interface is on;
//   particles: count x kParticleBytes (the swarm's fields, DMSwarm's own, and the setup's
//              transient while the swarm grows; the run's scratch is smaller).
// Compared per node (ranks sharing memory, MPI_COMM_TYPE_SHARED) with -memory_limit, by default
// the node's MemAvailable (/proc/meminfo), or its cgroup's remaining limit if lower.
struct MemoryCheck {
  double limit_gib = 0; // -memory_limit: GiB per node (0: what the node has available)
};
PetscErrorCode MemoryFromOptions(MPI_Comm comm, MemoryCheck &m);
// Before the grid is created: the grid alone (every rank an even share of the nodes).
PetscErrorCode CheckMemoryGrid(Simulation &sim, const MemoryCheck &m, int nd, bool iface);
// After the scene generated this rank's nlocal particles, before the swarm holds them: the grid
// (this rank's ghosted nodes) and the particles.
PetscErrorCode CheckMemoryParticles(Simulation &sim, const MemoryCheck &m, PetscInt nlocal);

// -dim 3 (extrude.hpp), with nz cells along z: before the 3D grid is created (nlocal = 0) the
// grid alone; after the extrusion, this rank's ghosted nodes and its nlocal particles.
PetscErrorCode CheckMemoryExtruded(Simulation &sim, const MemoryCheck &m, PetscInt nz,
                                   PetscInt nlocal);

// A process grid given with -da_processors_x/y (/z in 3D) that leaves a rank fewer than two nodes
// in a direction (the stencil width), or does not multiply to the rank count (PETSc would fail on
// some ranks only, deep in DMSetUp). Before the grid of dimension D with ncell cells is created.
PetscErrorCode CheckProcessGrid(Simulation &sim, int D, const PetscInt *ncell);

// With chains, a particle's body is 2 k, k the number of chains below its centre (a chain's
// height at x by linear interpolation of its points, held level beyond its ends): the plane's
// particles in 2D (simulation.cpp) and before their extrusion under -dim 3 (extrude.cpp).
void AssignBodies(const Simulation &sim, ParticleList &init);

} // namespace pmpm
