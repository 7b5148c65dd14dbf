#include "pmpm/particles.hpp"
#include <algorithm>
#include <cstring>
#include <malloc.h>

namespace pmpm {

namespace {
struct FieldSpec {
  const char *name;
  int bs;
  PetscDataType type;
};
// Every field but the coordinates (registered by DMSwarm itself for the PIC type).
constexpr FieldSpec kFields[] = {
    {"x0", DIM, PETSC_REAL},   {"v", DIM, PETSC_REAL},          {"lp", DIM, PETSC_REAL},
    {"mass", 1, PETSC_REAL},   {"vol", 1, PETSC_REAL},          {"vol0", 1, PETSC_REAL},
    {"weight", 1, PETSC_REAL}, {"stress", NSTRESS, PETSC_REAL}, {"F", DIM *DIM, PETSC_REAL},
    {"eps_p", 1, PETSC_REAL},  {"colour", 1, PETSC_REAL},       {"mat", 1, PETSC_INT},
    {"pid", 1, PETSC_INT},     {"body", 1, PETSC_INT},          {"load", 1, PETSC_INT},
};
constexpr PetscInt kBuffer = 1000; // DMSwarm reallocation slack (docs/developer-guide.md)
} // namespace

PetscErrorCode ParticlesCreate(Grid &g, Particles &P) {
  PetscFunctionBeginUser;
  PetscCall(DMCreate(PetscObjectComm((PetscObject)g.da), &P.sw));
  PetscCall(PetscObjectSetName((PetscObject)P.sw, "particles"));
  PetscCall(DMSetType(P.sw, DMSWARM));
  PetscCall(DMSetDimension(P.sw, DIM));
  PetscCall(DMSwarmSetType(P.sw, DMSWARM_PIC));
  PetscCall(DMSwarmSetCellDM(P.sw, g.da));
  PetscCall(DMSwarmInitializeFieldRegister(P.sw));
  for (const auto &f : kFields)
    PetscCall(DMSwarmRegisterPetscDatatypeField(P.sw, f.name, f.bs, f.type));
  // APIC only: 32 bytes a particle that FLIP runs do not pay
  if (P.affine)
    PetscCall(DMSwarmRegisterPetscDatatypeField(P.sw, kAffineField, DIM * DIM, PETSC_REAL));
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

PetscErrorCode ParticlesAdd(Particles &P, ParticleList &init) {
  PetscFunctionBeginUser;
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
      const ParticleInit &q = init.front();
      const double vol = q.vol;
      for (int d = 0; d < DIM; ++d) {
        v.x[p * DIM + d] = q.x[d];
        v.x0[p * DIM + d] = q.x[d];
        v.v[p * DIM + d] = 0.0;
        v.lp[p * DIM + d] = q.lp[d];
        for (int e = 0; e < DIM; ++e) v.F[(p * DIM + d) * DIM + e] = d == e ? 1.0 : 0.0;
        if (v.B)
          for (int e = 0; e < DIM; ++e) v.B[(p * DIM + d) * DIM + e] = 0.0;
      }
      v.mass[p] = q.density * vol;
      v.vol[p] = vol;
      v.vol0[p] = vol;
      v.weight[p] = q.gamma * vol;
      for (int s = 0; s < NSTRESS; ++s) v.stress[p * NSTRESS + s] = 0.0;
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

std::vector<ParticleFieldInfo> ParticlesFieldList(const Particles &P) {
  std::vector<ParticleFieldInfo> list = {{DMSwarmPICField_coor, DIM, false}};
  for (const auto &f : kFields) list.push_back({f.name, f.bs, f.type == PETSC_INT});
  if (P.affine) list.push_back({kAffineField, DIM * DIM, false});
  return list;
}

PetscErrorCode ParticlesGlobalCount(Particles &P, PetscInt *n) {
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetSize(P.sw, n));
  PetscFunctionReturn(0);
}

} // namespace pmpm
