#include "pmpm/core/particles.hpp"
#include "pmpm/core/particle_records.hpp"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <malloc.h>

namespace pmpm {

namespace {
// Values per particle of a field: 1, D, D*D or NStress<D> (Per), in dimension dim.
enum class Per { One, Dim, DimDim, Stress };
int BlockSize(Per per, int dim) {
  switch (per) {
  case Per::Dim:
    return dim;
  case Per::DimDim:
    return dim * dim;
  case Per::Stress:
    return dim == 3 ? NStress<3> : NStress<2>;
  default:
    return 1;
  }
}
struct FieldSpec {
  const char *name;
  Per per;
  PetscDataType type;
};
// Every field but the coordinates (registered by DMSwarm itself for the PIC type).
constexpr FieldSpec kFields[] = {
    {"x0", Per::Dim, PETSC_REAL},     {"v", Per::Dim, PETSC_REAL},
    {"lp", Per::Dim, PETSC_REAL},     {"mass", Per::One, PETSC_REAL},
    {"vol", Per::One, PETSC_REAL},    {"vol0", Per::One, PETSC_REAL},
    {"weight", Per::One, PETSC_REAL}, {"stress", Per::Stress, PETSC_REAL},
    {"F", Per::DimDim, PETSC_REAL},   {"eps_p", Per::One, PETSC_REAL},
    {"colour", Per::One, PETSC_REAL}, {"mat", Per::One, PETSC_INT},
    {"pid", Per::One, PETSC_INT},     {"body", Per::One, PETSC_INT},
    {"load", Per::One, PETSC_INT},
};
constexpr PetscInt kBuffer = 1000; // DMSwarm reallocation slack (docs/developer-guide.md)
} // namespace

template <int D> PetscErrorCode ParticlesCreate(GridT<D> &g, Particles &P) {
  PetscFunctionBeginUser;
  P.dim = D;
  PetscCall(DMCreate(PetscObjectComm((PetscObject)g.da), &P.sw));
  PetscCall(PetscObjectSetName((PetscObject)P.sw, "particles"));
  PetscCall(DMSetType(P.sw, DMSWARM));
  PetscCall(DMSetDimension(P.sw, D));
  PetscCall(DMSwarmSetType(P.sw, DMSWARM_PIC));
  PetscCall(DMSwarmSetCellDM(P.sw, g.da));
  PetscCall(DMSwarmInitializeFieldRegister(P.sw));
  for (const auto &f : kFields)
    PetscCall(DMSwarmRegisterPetscDatatypeField(P.sw, f.name, BlockSize(f.per, D), f.type));
  // APIC only: 32 bytes a particle (2D) that FLIP runs do not pay
  if (P.affine) PetscCall(DMSwarmRegisterPetscDatatypeField(P.sw, kAffineField, D * D, PETSC_REAL));
  PetscCall(DMSwarmFinalizeFieldRegister(P.sw));
  PetscCall(DMSwarmSetLocalSizes(P.sw, 0, kBuffer));
  PetscFunctionReturn(0);
}

PetscErrorCode ParticlesDestroy(Particles &P) {
  PetscFunctionBeginUser;
  PetscCall(DMDestroy(&P.sw));
  PetscFunctionReturn(0);
}

PetscErrorCode ParticlesGetView(Particles &P, ParticleView &v) {
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(P.sw, &v.n));
  PetscCall(DMSwarmGetField(P.sw, DMSwarmPICField_coor, nullptr, nullptr, (void **)&v.x));
  double **reals[] = {&v.x0,     &v.v,      &v.lp, &v.mass,  &v.vol,   &v.vol0,
                      &v.weight, &v.stress, &v.F,  &v.eps_p, &v.colour};
  for (int k = 0; k < 11; ++k)
    PetscCall(DMSwarmGetField(P.sw, kFields[k].name, nullptr, nullptr, (void **)reals[k]));
  PetscCall(DMSwarmGetField(P.sw, "mat", nullptr, nullptr, (void **)&v.mat));
  PetscCall(DMSwarmGetField(P.sw, "pid", nullptr, nullptr, (void **)&v.pid));
  PetscCall(DMSwarmGetField(P.sw, "body", nullptr, nullptr, (void **)&v.body));
  PetscCall(DMSwarmGetField(P.sw, "load", nullptr, nullptr, (void **)&v.load));
  if (P.affine) PetscCall(DMSwarmGetField(P.sw, kAffineField, nullptr, nullptr, (void **)&v.B));
  PetscFunctionReturn(0);
}

PetscErrorCode ParticlesRestoreView(Particles &P, ParticleView &v) {
  PetscFunctionBeginUser;
  PetscCall(DMSwarmRestoreField(P.sw, DMSwarmPICField_coor, nullptr, nullptr, (void **)&v.x));
  double **reals[] = {&v.x0,     &v.v,      &v.lp, &v.mass,  &v.vol,   &v.vol0,
                      &v.weight, &v.stress, &v.F,  &v.eps_p, &v.colour};
  for (int k = 0; k < 11; ++k)
    PetscCall(DMSwarmRestoreField(P.sw, kFields[k].name, nullptr, nullptr, (void **)reals[k]));
  PetscCall(DMSwarmRestoreField(P.sw, "mat", nullptr, nullptr, (void **)&v.mat));
  PetscCall(DMSwarmRestoreField(P.sw, "pid", nullptr, nullptr, (void **)&v.pid));
  PetscCall(DMSwarmRestoreField(P.sw, "body", nullptr, nullptr, (void **)&v.body));
  PetscCall(DMSwarmRestoreField(P.sw, "load", nullptr, nullptr, (void **)&v.load));
  if (P.affine) PetscCall(DMSwarmRestoreField(P.sw, kAffineField, nullptr, nullptr, (void **)&v.B));
  v = ParticleView{};
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode ParticlesAdd(Particles &P, ParticleListT<D> &init) {
  PetscFunctionBeginUser;
  PetscCheck(P.dim == D, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
             "ParticlesAdd: %dD particles into a %dD swarm", D, P.dim);
  constexpr int NS = NStress<D>;
  // Chunks of an eighth: eight reallocations of the swarm's fields (each copies one field at a
  // time), while the list's blocks are freed as the particles leave it.
  const PetscInt total = static_cast<PetscInt>(init.size());
  const PetscInt chunk = std::max<PetscInt>(total / 8 + 1, kBuffer);
  PetscInt n0;
  PetscCall(DMSwarmGetLocalSize(P.sw, &n0));
  while (!init.empty()) {
    const PetscInt n = std::min<PetscInt>(chunk, static_cast<PetscInt>(init.size()));
    PetscCall(DMSwarmSetLocalSizes(P.sw, n0 + n, kBuffer));
    ParticleView v;
    PetscCall(ParticlesGetView(P, v));
    for (PetscInt p = n0; p < n0 + n; ++p) {
      const ParticleInitT<D> &q = init.front();
      const double vol = q.vol;
      for (int d = 0; d < D; ++d) {
        v.x[p * D + d] = q.x[d];
        v.x0[p * D + d] = q.x[d];
        v.v[p * D + d] = 0.0;
        v.lp[p * D + d] = q.lp[d];
        for (int e = 0; e < D; ++e) v.F[(p * D + d) * D + e] = d == e ? 1.0 : 0.0;
        if (v.B)
          for (int e = 0; e < D; ++e) v.B[(p * D + d) * D + e] = 0.0;
      }
      v.mass[p] = q.density * vol;
      v.vol[p] = vol;
      v.vol0[p] = vol;
      v.weight[p] = q.gamma * vol;
      for (int s = 0; s < NS; ++s) v.stress[p * NS + s] = 0.0;
      v.eps_p[p] = 0.0;
      v.colour[p] = q.colour;
      v.mat[p] = q.mat;
      v.pid[p] = q.pid;
      v.body[p] = q.body;
      v.load[p] = q.load;
      init.pop_front();
    }
    PetscCall(ParticlesRestoreView(P, v));
    n0 += n;
    // the list's freed blocks lie below the heap's top: hand their pages back now, or the swarm's
    // next chunk comes on top of them
    malloc_trim(0);
  }
  init.shrink_to_fit();
  PetscFunctionReturn(0);
}

PetscErrorCode ParticlesMigrate(Particles &P) {
  PetscFunctionBeginUser;
  PetscCall(DMSwarmMigrate(P.sw, PETSC_TRUE));
  PetscFunctionReturn(0);
}

namespace {
// 3D migration by records: the particles outside g's owned cells leave the swarm (the rest keep
// their order), those inside the box go to the ranks owning their cells (RecordsRedistribute) and
// the arrivals are appended.
template <int D> PetscErrorCode MigrateByRecords(Particles &P, const GridT<D> &g) {
  PetscFunctionBeginUser;
  const std::vector<ParticleFieldInfo> fields = ParticlesFieldList(P);
  const PetscInt w = ParticleRecordWidth(P);
  PetscInt n;
  PetscCall(DMSwarmGetLocalSize(P.sw, &n));
  // which particles stay (centred in an owned cell), which leave (inside the box elsewhere)
  std::vector<char> keep(n, 1), send(n, 0);
  PetscInt nkeep = 0, nsend = 0;
  {
    double *x;
    PetscCall(DMSwarmGetField(P.sw, DMSwarmPICField_coor, nullptr, nullptr, (void **)&x));
    for (PetscInt p = 0; p < n; ++p) {
      PetscInt c[D];
      bool inside = true;
      for (int d = 0; d < D; ++d) {
        const double xi = (x[p * D + d] - g.origin[d]) / g.h;
        inside = inside && xi >= 0.0 && xi < static_cast<double>(g.ncell[d]);
        c[d] = inside ? static_cast<PetscInt>(std::floor(xi)) : 0;
      }
      keep[p] = inside && g.owns_cell(c);
      send[p] = inside && !keep[p];
      nkeep += keep[p];
      nsend += send[p];
    }
    PetscCall(DMSwarmRestoreField(P.sw, DMSwarmPICField_coor, nullptr, nullptr, (void **)&x));
  }
  // pack the leaving particles, compact the staying ones in place (field by field)
  std::vector<double> rec(static_cast<size_t>(nsend * w));
  PetscInt off = 0;
  for (const auto &f : fields) {
    void *data;
    PetscCall(DMSwarmGetField(P.sw, f.name, nullptr, nullptr, &data));
    PetscInt q = 0, k = 0;
    for (PetscInt p = 0; p < n; ++p) {
      if (send[p]) {
        for (PetscInt b = 0; b < f.bs; ++b)
          rec[k * w + off + b] =
              f.integer ? static_cast<double>(static_cast<PetscInt *>(data)[p * f.bs + b])
                        : static_cast<double *>(data)[p * f.bs + b];
        ++k;
      }
      if (keep[p]) {
        if (q != p) {
          if (f.integer)
            std::copy_n(static_cast<PetscInt *>(data) + p * f.bs, f.bs,
                        static_cast<PetscInt *>(data) + q * f.bs);
          else
            std::copy_n(static_cast<double *>(data) + p * f.bs, f.bs,
                        static_cast<double *>(data) + q * f.bs);
        }
        ++q;
      }
    }
    PetscCall(DMSwarmRestoreField(P.sw, f.name, nullptr, nullptr, &data));
    off += f.bs;
  }
  PetscCall(RecordsRedistribute(PetscObjectComm((PetscObject)P.sw), g, w, rec));
  const PetscInt nrecv = static_cast<PetscInt>(rec.size()) / w;
  PetscCall(DMSwarmSetLocalSizes(P.sw, nkeep + nrecv, kBuffer));
  off = 0;
  for (const auto &f : fields) {
    void *data;
    PetscCall(DMSwarmGetField(P.sw, f.name, nullptr, nullptr, &data));
    for (PetscInt k = 0; k < nrecv; ++k)
      for (PetscInt b = 0; b < f.bs; ++b) {
        const double v = rec[k * w + off + b];
        const PetscInt p = nkeep + k;
        if (f.integer)
          static_cast<PetscInt *>(data)[p * f.bs + b] = static_cast<PetscInt>(v);
        else
          static_cast<double *>(data)[p * f.bs + b] = v;
      }
    PetscCall(DMSwarmRestoreField(P.sw, f.name, nullptr, nullptr, &data));
    off += f.bs;
  }
  PetscFunctionReturn(0);
}
} // namespace

template <int D> PetscErrorCode ParticlesMigrate(Particles &P, const GridT<D> &g) {
  PetscFunctionBeginUser;
  PetscCheck(P.dim == D, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
             "ParticlesMigrate: a %dD swarm on a %dD grid", P.dim, D);
  if constexpr (D == 2)
    PetscCall(ParticlesMigrate(P));
  else
    PetscCall(MigrateByRecords(P, g));
  PetscFunctionReturn(0);
}

std::vector<ParticleFieldInfo> ParticlesFieldList(const Particles &P) {
  std::vector<ParticleFieldInfo> list = {{DMSwarmPICField_coor, P.dim, false}};
  for (const auto &f : kFields)
    list.push_back({f.name, BlockSize(f.per, P.dim), f.type == PETSC_INT});
  if (P.affine) list.push_back({kAffineField, P.dim * P.dim, false});
  return list;
}

PetscErrorCode ParticlesGlobalCount(Particles &P, PetscInt *n) {
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetSize(P.sw, n));
  PetscFunctionReturn(0);
}

template PetscErrorCode ParticlesCreate<2>(GridT<2> &, Particles &);
template PetscErrorCode ParticlesCreate<3>(GridT<3> &, Particles &);
template PetscErrorCode ParticlesAdd<2>(Particles &, ParticleListT<2> &);
template PetscErrorCode ParticlesAdd<3>(Particles &, ParticleListT<3> &);
template PetscErrorCode ParticlesMigrate<2>(Particles &, const GridT<2> &);
template PetscErrorCode ParticlesMigrate<3>(Particles &, const GridT<3> &);

} // namespace pmpm
