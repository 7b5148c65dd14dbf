// Particles as flat records, for moving them between partitions: every swarm field of a particle
// (ParticlesFieldList order, the coordinates first, integers as doubles), w values per particle.
// A restart on another rank count and a rebalance during the run both pack (or read) records,
// send each to the rank owning its cell, and unpack them into the swarm.
#pragma once
#include "pmpm/core/grid.hpp"
#include "pmpm/core/particles.hpp"
#include <vector>

namespace pmpm {

// Values per record.
PetscInt ParticleRecordWidth(const Particles &P);
// This rank's particles, in swarm order.
PetscErrorCode ParticlesPack(Particles &P, std::vector<double> &rec);
// Replace this rank's particles by the records (in their order).
PetscErrorCode ParticlesUnpack(Particles &P, const std::vector<double> &rec);
// Send each record to the rank owning its cell on grid g (records of width w, the D coordinates
// first; a record outside the box goes to the owner of the nearest cell); rec becomes this rank's
// records, in rank order of their senders. Collective.
template <int D>
PetscErrorCode RecordsRedistribute(MPI_Comm comm, const GridT<D> &g, PetscInt w,
                                   std::vector<double> &rec);

} // namespace pmpm
