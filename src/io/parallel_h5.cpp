#include "pmpm/io/parallel_h5.hpp"

namespace pmpm {

PetscErrorCode WriteRowsCollective(MPI_Comm comm, hid_t loc, const char *name, PetscInt nlocal,
                                   int bs, const double *data, bool flat) {
  PetscFunctionBeginUser;
  long long n = nlocal, off = 0, total = 0;
  PetscCallMPI(MPI_Exscan(&n, &off, 1, MPI_LONG_LONG, MPI_SUM, comm));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) off = 0; // MPI_Exscan leaves rank 0's result undefined
  PetscCallMPI(MPI_Allreduce(&n, &total, 1, MPI_LONG_LONG, MPI_SUM, comm));
  const int rank2 = bs > 1 && !flat ? 2 : 1;
  const hsize_t w = flat ? static_cast<hsize_t>(bs) : 1; // values per row of a 1-D dataset
  const hsize_t dims[2] = {static_cast<hsize_t>(total) * w, static_cast<hsize_t>(bs)};
  const hsize_t start[2] = {static_cast<hsize_t>(off) * w, 0};
  const hsize_t count[2] = {static_cast<hsize_t>(n) * w, static_cast<hsize_t>(bs)};
  const hsize_t mdim = static_cast<hsize_t>(n) * bs;

  // our one-line error below, not HDF5's error stack
  H5E_auto2_t efn;
  void *edata;
  H5Eget_auto2(H5E_DEFAULT, &efn, &edata);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  herr_t err = 0;
  const hid_t space = H5Screate_simple(rank2, dims, nullptr);
  const hid_t mem = H5Screate_simple(1, &mdim, nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  const hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  err |= H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER) < 0;
  err |= H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE) < 0;
  const hid_t dset =
      H5Dcreate2(loc, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (n > 0)
    err |= H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr) < 0;
  else {
    err |= H5Sselect_none(space) < 0;
    err |= H5Sselect_none(mem) < 0;
  }
  // an empty dataset has no storage to write to (a scene of chains alone has no particles)
  if (dset >= 0 && total > 0) err |= H5Dwrite(dset, H5T_NATIVE_DOUBLE, mem, space, dxpl, data) < 0;
  if (dset >= 0) H5Dclose(dset);
  H5Pclose(dxpl);
  H5Pclose(dcpl);
  H5Sclose(mem);
  H5Sclose(space);
  H5Eset_auto2(H5E_DEFAULT, efn, edata);
  int bad = (err || space < 0 || mem < 0 || dset < 0) ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm));
  PetscCheck(!bad, comm, PETSC_ERR_FILE_WRITE,
             "HDF5 could not write dataset %s (%lld rows of %d values): disk full or the output "
             "directory's file system refused MPI-IO",
             name, total, bs);
  PetscFunctionReturn(0);
}

} // namespace pmpm
