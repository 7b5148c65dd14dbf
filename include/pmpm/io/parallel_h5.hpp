// Per-particle arrays to HDF5 from every rank at once: each rank writes its own rows of one
// dataset in a collective MPI-IO call, at the offset of the ranks before it. Nothing is gathered
// on one rank, and nothing is copied: PETSc's VecView would create a chunked dataset whose fill
// values HDF5 builds in a buffer as large as the chunk (up to the whole dataset, 32 B per
// particle for the stress) and keeps in its free lists afterwards (docs/benchmarks/memory.md).
#pragma once
#include <hdf5.h>
#include <petscsys.h>

namespace pmpm {

// Dataset `name` under loc (a file or group of a file opened for MPI-IO), contiguous, no fill:
// nlocal rows of bs values from this rank, shape (N) if bs == 1 or flat, else (N, bs).
PetscErrorCode WriteRowsCollective(MPI_Comm comm, hid_t loc, const char *name, PetscInt nlocal,
                                   int bs, const double *data, bool flat = false);

} // namespace pmpm
