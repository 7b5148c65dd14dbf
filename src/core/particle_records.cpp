#include "pmpm/core/particle_records.hpp"
#include <algorithm>

namespace pmpm {

PetscInt ParticleRecordWidth(const Particles &P) {
  PetscInt w = 0;
  for (const auto &f : ParticlesFieldList(P)) w += f.bs;
  return w;
}

PetscErrorCode ParticlesPack(Particles &P, std::vector<double> &rec) {
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(P.sw, &n));
  const PetscInt w = ParticleRecordWidth(P);
  rec.assign(static_cast<size_t>(n * w), 0.0);
  PetscInt off = 0;
  for (const auto &f : ParticlesFieldList(P)) {
    void *data;
    PetscInt bs;
    PetscDataType type;
    PetscCall(DMSwarmGetField(P.sw, f.name, &bs, &type, &data));
    for (PetscInt p = 0; p < n; ++p)
      for (PetscInt b = 0; b < f.bs; ++b)
        rec[p * w + off + b] =
            f.integer ? static_cast<double>(static_cast<PetscInt *>(data)[p * f.bs + b])
                      : static_cast<double *>(data)[p * f.bs + b];
    PetscCall(DMSwarmRestoreField(P.sw, f.name, &bs, &type, &data));
    off += f.bs;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ParticlesUnpack(Particles &P, const std::vector<double> &rec) {
  PetscFunctionBeginUser;
  const PetscInt w = ParticleRecordWidth(P);
  const PetscInt n = static_cast<PetscInt>(rec.size()) / w;
  PetscCall(DMSwarmSetLocalSizes(P.sw, n, 1000));
  PetscInt off = 0;
  for (const auto &f : ParticlesFieldList(P)) {
    void *data;
    PetscInt bs;
    PetscDataType type;
    PetscCall(DMSwarmGetField(P.sw, f.name, &bs, &type, &data));
    for (PetscInt p = 0; p < n; ++p)
      for (PetscInt b = 0; b < f.bs; ++b) {
        const double x = rec[p * w + off + b];
        if (f.integer)
          static_cast<PetscInt *>(data)[p * f.bs + b] = static_cast<PetscInt>(x);
        else
          static_cast<double *>(data)[p * f.bs + b] = x;
      }
    PetscCall(DMSwarmRestoreField(P.sw, f.name, &bs, &type, &data));
    off += f.bs;
  }
  PetscFunctionReturn(0);
}

template <int D>
PetscErrorCode RecordsRedistribute(MPI_Comm comm, const GridT<D> &g, PetscInt w,
                                   std::vector<double> &rec) {
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  // every rank's owned cells, [lo, hi) per direction
  std::vector<PetscInt> box(2 * D * size);
  PetscInt mine[2 * D];
  for (int d = 0; d < D; ++d) {
    mine[2 * d] = g.cell_lo[d];
    mine[2 * d + 1] = g.cell_hi[d];
  }
  PetscCallMPI(MPI_Allgather(mine, 2 * D, MPIU_INT, box.data(), 2 * D, MPIU_INT, comm));
  auto owns = [&](int r, const PetscInt *c) {
    for (int d = 0; d < D; ++d)
      if (c[d] < box[2 * D * r + 2 * d] || c[d] >= box[2 * D * r + 2 * d + 1]) return false;
    return true;
  };
  const size_t n = rec.size() / w;
  std::vector<int> dest(n), scount(size, 0), rcount(size), sdisp(size), rdisp(size);
  for (size_t p = 0; p < n; ++p) {
    PetscInt c[D];
    for (int d = 0; d < D; ++d) {
      c[d] = static_cast<PetscInt>((rec[p * w + d] - g.origin[d]) / g.h);
      c[d] = std::min(std::max(c[d], (PetscInt)0), g.ncell[d] - 1);
    }
    int r = 0;
    while (r < size && !owns(r, c)) ++r;
    PetscCheck(r < size, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no rank owns cell (%d, %d, %d)",
               (int)c[0], (int)c[1], D == 3 ? (int)c[D - 1] : 0);
    dest[p] = r;
    scount[r] += static_cast<int>(w);
  }
  PetscCallMPI(MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, comm));
  int st = 0, rt = 0;
  for (int r = 0; r < size; ++r) {
    sdisp[r] = st;
    rdisp[r] = rt;
    st += scount[r];
    rt += rcount[r];
  }
  std::vector<double> send(static_cast<size_t>(st)), recv(static_cast<size_t>(rt));
  std::vector<int> at(sdisp);
  for (size_t p = 0; p < n; ++p) {
    std::copy(rec.begin() + p * w, rec.begin() + (p + 1) * w, send.begin() + at[dest[p]]);
    at[dest[p]] += static_cast<int>(w);
  }
  PetscCallMPI(MPI_Alltoallv(send.data(), scount.data(), sdisp.data(), MPI_DOUBLE, recv.data(),
                             rcount.data(), rdisp.data(), MPI_DOUBLE, comm));
  rec.swap(recv);
  PetscFunctionReturn(0);
}

template PetscErrorCode RecordsRedistribute<2>(MPI_Comm, const GridT<2> &, PetscInt,
                                               std::vector<double> &);
template PetscErrorCode RecordsRedistribute<3>(MPI_Comm, const GridT<3> &, PetscInt,
                                               std::vector<double> &);

} // namespace pmpm
