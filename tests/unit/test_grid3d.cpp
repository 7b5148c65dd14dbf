// The 3D grid and swarm (GridT<3>, ParticlesCreate<3>, ParticlesMigrate<3>) on any rank count and
// process grid (-da_processors_x/y/z), against a serial reference every rank computes alike:
//   a box of 8 x 6 x 9 cells (10 node planes along z, so 4 ranks along z keep the 2 node planes
//   a rank needs for stencil width 2), N random particles from one fixed seed, generated alike
//   on every rank and kept by the rank that owns their cell;
//   P2G of mass and momentum with uGIMP (p2g<UGIMPShape, 3>) into the ghosted local vector and the
//   ghost add (GridLocalToGlobalAdd): the owned nodes' mass and momentum equal the reference's
//   (p2g<UGIMPShape, 3> over all N particles into one whole-box array) to 1e-12 of the largest
//   nodal value; the mass on the owned nodes plus what each rank's particles spread to the ghost
//   nodes outside the box equals the particles' total to 1e-13 relative (partition of unity);
//   the ghost scatter (GridGlobalToLocal): every ghosted in-box node equals the reference, every
//   node outside the box is zero (some particles straddle the faces, so those nodes held sums);
//   the owned-nodes view of the global vector (GridGetGlobal; on one rank the `shared` shortcut's
//   view into the local array) addresses the nodes node(i, j, k) names;
//   migration: every particle moved by up to one cell per direction (a random displacement of
//   its own), ParticlesMigrate<3>: every particle id on exactly one rank (global count N, each id
//   counted once), on the rank owning its cell, every field as it was (compared exactly with the
//   values it was given, which are functions of its id); P2G again against the reference of the
//   moved particles.
// All of it twice on more than one rank: on PETSc's partition (or -da_processors_x/y/z), and on
// the same process grid with explicit, uneven node counts lx, ly, lz (GridCreate's px, py, pz).
// The differences from the reference are summation order only (a node sums up to a few hundred
// particles in another order on another partition): measured at most a few 1e-16 of the largest
// value; 1e-12 leaves room for other compilers, not for a lost or doubled particle (an error of
// one particle's share, >= 1e-4 of the largest value here).
#include "check.hpp"
#include "pmpm/core/grid.hpp"
#include "pmpm/core/particles.hpp"
#include "pmpm/core/transfers.hpp"
#include <algorithm>
#include <cmath>
#include <vector>

using namespace pmpm;

namespace {

constexpr int D = 3;
constexpr int NS = NStress<3>;
constexpr PetscInt N = 3000;
constexpr double H = 0.25;
const double kOrigin[D] = {-0.5, 0.3, 1.1};
const PetscInt kCells[D] = {8, 6, 9};
constexpr double TOL_NODE = 1e-12, TOL_TOTAL = 1e-13;

// Every particle, as every rank generates it: position, half-size, mass, velocity and the other
// fields as functions of the id.
struct AllParticles {
  std::vector<double> x, x0, lp, v, mass, vol, vol0, weight, stress, F, eps_p, colour, moved;
  std::vector<PetscInt> mat, pid, body, load;
  AllParticles() {
    pmpm_test::Lcg rng(20261203);
    x.resize(N * D);
    lp.resize(N * D);
    v.resize(N * D);
    moved.resize(N * D);
    mass.resize(N);
    vol.resize(N);
    weight.resize(N);
    stress.resize(N * NS);
    F.resize(N * D * D);
    eps_p.resize(N);
    colour.resize(N);
    mat.resize(N);
    pid.resize(N);
    body.assign(N, 0);
    load.resize(N);
    for (PetscInt p = 0; p < N; ++p) {
      double V = 1;
      for (int d = 0; d < D; ++d) {
        // anywhere in the box: blocks near a face reach the ghost nodes outside it
        x[p * D + d] = kOrigin[d] + rng.uniform(0.0, kCells[d] * H);
        lp[p * D + d] = rng.uniform(0.1, 0.5) * H;
        v[p * D + d] = rng.uniform(-1.0, 1.0);
        V *= 2 * lp[p * D + d];
      }
      vol[p] = V;
      mass[p] = rng.uniform(0.5, 1.5) * V * 1800.0;
      weight[p] = 9.81 * mass[p];
      for (int s = 0; s < NS; ++s) stress[p * NS + s] = rng.uniform(-1e4, 1e4);
      for (int e = 0; e < D * D; ++e) F[p * D * D + e] = (e % 4 == 0 ? 1.0 : 0.0) + 1e-3 * e * p;
      eps_p[p] = 1e-6 * p;
      colour[p] = p % 2;
      mat[p] = p % 5;
      pid[p] = p;
      load[p] = p % 7 == 0 ? p / 7 : -1;
      // the displacement: up to one cell per direction; one that would leave the box is reversed
      for (int d = 0; d < D; ++d) {
        const double u = rng.uniform(-H, H), xd = x[p * D + d] + u;
        const double lo = kOrigin[d], hi = kOrigin[d] + kCells[d] * H;
        moved[p * D + d] = (xd >= lo && xd < hi) ? xd : x[p * D + d] - u;
      }
    }
    x0 = x;
    vol0 = vol;
  }
  ParticleView view(bool after_move) {
    ParticleView P;
    P.n = N;
    P.x = after_move ? moved.data() : x.data();
    P.x0 = x0.data();
    P.v = v.data();
    P.lp = lp.data();
    P.mass = mass.data();
    P.vol = vol.data();
    P.vol0 = vol0.data();
    P.weight = weight.data();
    P.stress = stress.data();
    P.F = F.data();
    P.eps_p = eps_p.data();
    P.colour = colour.data();
    P.mat = mat.data();
    P.pid = pid.data();
    P.body = body.data();
    P.load = load.data();
    return P;
  }
};

PetscInt CellOf(const double *x, int d) {
  return static_cast<PetscInt>(std::floor((x[d] - kOrigin[d]) / H));
}

// The reference: p2g over all particles into one array over the whole ghosted box.
struct Reference {
  std::vector<double> data;
  GridViewT<D> G;
  explicit Reference(const ParticleView &P) {
    G.h = H;
    size_t nn = 1;
    for (int d = 0; d < D; ++d) {
      G.origin[d] = kOrigin[d];
      G.ncell[d] = kCells[d];
      G.gs[d] = -2;
      G.gm[d] = kCells[d] + 5;
      nn *= G.gm[d];
    }
    data.assign(nn * GridDofT<D>::NDOF, 0.0);
    G.data = data.data();
    p2g<UGIMPShape, D>(P, LoadT<D>{}, G);
  }
};

bool InBox(const PetscInt *n) {
  for (int d = 0; d < D; ++d)
    if (n[d] < 0 || n[d] > kCells[d]) return false;
  return true;
}

// The largest |mass| and |momentum component| of the reference (the scales of the tolerance).
void Scales(const Reference &R, double &mmax, double &pmax) {
  mmax = pmax = 0;
  for (size_t k = 0; k < R.data.size(); k += GridDofT<D>::NDOF) {
    mmax = std::max(mmax, std::fabs(R.data[k + GridDofT<D>::M]));
    for (int d = 0; d < D; ++d) pmax = std::max(pmax, std::fabs(R.data[k + GridDofT<D>::P + d]));
  }
}

// p2g of this rank's swarm, the ghost add and the scatter, each checked against the reference.
// Returns the largest relative nodal difference seen (for the log).
PetscErrorCode CheckP2G(GridT<D> &g, Particles &parts, const Reference &R, double total_mass,
                        const char *when, double &worst) {
  PetscFunctionBeginUser;
  MPI_Comm comm = PetscObjectComm((PetscObject)g.da);
  double mmax, pmax;
  Scales(R, mmax, pmax);
  using Dof = GridDofT<D>;
  ParticleView P;
  GridViewT<D> L;
  PetscCall(ParticlesGetView(parts, P));
  PetscCall(GridGetLocal(g, true, L));
  p2g<UGIMPShape, D>(P, LoadT<D>{}, L);
  PetscCall(ParticlesRestoreView(parts, P));
  // this rank's spill: its sums on the ghost nodes outside the box (the ghost add drops them)
  double spill = 0;
  for (PetscInt k = L.gs[2]; k < L.gs[2] + L.gm[2]; ++k)
    for (PetscInt j = L.gs[1]; j < L.gs[1] + L.gm[1]; ++j)
      for (PetscInt i = L.gs[0]; i < L.gs[0] + L.gm[0]; ++i) {
        const PetscInt n[D] = {i, j, k};
        if (!InBox(n)) spill += L.node(n)[Dof::M];
      }
  PetscCall(GridRestoreLocal(g, L));
  PetscCall(GridLocalToGlobalAdd(g));

  // the owned nodes against the reference
  GridViewT<D> O;
  PetscCall(GridGetGlobal(g, O));
  double owned = 0, dm = 0, dp = 0;
  for (PetscInt k = g.s[2]; k < g.s[2] + g.m[2]; ++k)
    for (PetscInt j = g.s[1]; j < g.s[1] + g.m[1]; ++j)
      for (PetscInt i = g.s[0]; i < g.s[0] + g.m[0]; ++i) {
        const PetscInt n[D] = {i, j, k};
        const double *a = O.node(i, j, k), *r = R.G.node(n);
        CHECK(O.node(n) == a);
        owned += a[Dof::M];
        dm = std::max(dm, std::fabs(a[Dof::M] - r[Dof::M]));
        for (int d = 0; d < D; ++d) dp = std::max(dp, std::fabs(a[Dof::P + d] - r[Dof::P + d]));
      }
  PetscCall(GridRestoreGlobal(g, O));
  CHECK_CLOSE(dm, 0.0, TOL_NODE * mmax);
  CHECK_CLOSE(dp, 0.0, TOL_NODE * pmax);
  double sums[2] = {owned, spill}, all[2];
  PetscCallMPI(MPI_Allreduce(sums, all, 2, MPI_DOUBLE, MPI_SUM, comm));
  CHECK_CLOSE(all[0] + all[1], total_mass, TOL_TOTAL * total_mass);
  CHECK(all[1] > 1e-3 * total_mass); // particles straddle the faces: the zeroing below is tested

  // the scatter: ghosted in-box nodes as the reference, out-of-box nodes zero
  PetscCall(GridGlobalToLocal(g));
  PetscCall(GridGetLocal(g, false, L));
  double dg = 0, outside = 0;
  for (PetscInt k = L.gs[2]; k < L.gs[2] + L.gm[2]; ++k)
    for (PetscInt j = L.gs[1]; j < L.gs[1] + L.gm[1]; ++j)
      for (PetscInt i = L.gs[0]; i < L.gs[0] + L.gm[0]; ++i) {
        const PetscInt n[D] = {i, j, k};
        const double *a = L.node(n), *r = R.G.node(n);
        if (!InBox(n)) {
          for (int c = 0; c < Dof::NDOF; ++c) outside = std::max(outside, std::fabs(a[c]));
          continue;
        }
        dg = std::max(dg, std::fabs(a[Dof::M] - r[Dof::M]) / mmax);
        for (int d = 0; d < D; ++d)
          dg = std::max(dg, std::fabs(a[Dof::P + d] - r[Dof::P + d]) / pmax);
      }
  PetscCall(GridRestoreLocal(g, L));
  CHECK_CLOSE(dg, 0.0, TOL_NODE);
  CHECK(outside == 0.0);
  double mine[3] = {dm / mmax, dp / pmax, dg}, w[3];
  PetscCallMPI(MPI_Allreduce(mine, w, 3, MPI_DOUBLE, MPI_MAX, comm));
  worst = std::max({w[0], w[1], w[2]});
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0)
    std::printf("%s: P2G mass %.6g (particles %.6g, relative difference %.2g), owned nodes against "
                "the reference: mass %.2g, momentum %.2g, after the scatter %.2g (of the largest "
                "value)\n",
                when, all[0] + all[1], total_mass, (all[0] + all[1] - total_mass) / total_mass,
                w[0], w[1], w[2]);
  PetscFunctionReturn(0);
}

// Every local particle on this rank's cells with the fields it was given (x: at or after the
// move); each id counted into seen.
PetscErrorCode CheckSwarm(GridT<D> &g, Particles &parts, const AllParticles &A, bool after_move,
                          std::vector<PetscInt> &seen) {
  PetscFunctionBeginUser;
  ParticleView P;
  PetscCall(ParticlesGetView(parts, P));
  PetscInt bad_cell = 0, bad_field = 0;
  const std::vector<double> &X = after_move ? A.moved : A.x;
  for (PetscInt q = 0; q < P.n; ++q) {
    const PetscInt p = P.pid[q];
    if (p < 0 || p >= N) {
      ++bad_field;
      continue;
    }
    ++seen[p];
    PetscInt c[D];
    for (int d = 0; d < D; ++d) c[d] = CellOf(P.x + q * D, d);
    if (!g.owns_cell(c)) ++bad_cell;
    bool ok = P.mass[q] == A.mass[p] && P.vol[q] == A.vol[p] && P.vol0[q] == A.vol0[p] &&
              P.weight[q] == A.weight[p] && P.eps_p[q] == A.eps_p[p] &&
              P.colour[q] == A.colour[p] && P.mat[q] == A.mat[p] && P.body[q] == A.body[p] &&
              P.load[q] == A.load[p];
    for (int d = 0; d < D; ++d)
      ok = ok && P.x[q * D + d] == X[p * D + d] && P.x0[q * D + d] == A.x0[p * D + d] &&
           P.v[q * D + d] == A.v[p * D + d] && P.lp[q * D + d] == A.lp[p * D + d];
    for (int s = 0; s < NS; ++s) ok = ok && P.stress[q * NS + s] == A.stress[p * NS + s];
    for (int e = 0; e < D * D; ++e) ok = ok && P.F[q * D * D + e] == A.F[p * D * D + e];
    if (!ok) ++bad_field;
  }
  PetscCall(ParticlesRestoreView(parts, P));
  CHECK(bad_cell == 0);
  CHECK(bad_field == 0);
  PetscFunctionReturn(0);
}

PetscErrorCode CheckIds(MPI_Comm comm, std::vector<PetscInt> &seen, const char *when) {
  PetscFunctionBeginUser;
  std::vector<PetscInt> all(N);
  PetscCallMPI(MPI_Allreduce(seen.data(), all.data(), (int)N, MPIU_INT, MPI_SUM, comm));
  PetscInt once = 0;
  for (PetscInt p = 0; p < N; ++p) once += all[p] == 1;
  CHECK(once == N); // every id on exactly one rank
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0)
    std::printf("%s: %d of %d particle ids on exactly one rank\n", when, (int)once, (int)N);
  std::fill(seen.begin(), seen.end(), 0);
  PetscFunctionReturn(0);
}

// Everything on grid g (created by the caller).
PetscErrorCode RunOn(GridT<D> &g);

// The grid of PETSc's partition (or -da_processors_x/y/z), then the same process grid with
// explicit node counts lx, ly, lz (balance.hpp's path): one node moved from the first slab to the
// last along every split direction whose first slab has nodes to spare.
PetscErrorCode Run() {
  PetscFunctionBeginUser;
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscInt p[D];
  std::vector<PetscInt> l[D];
  {
    GridT<D> g;
    PetscCall(GridCreate(comm, H, kOrigin, kCells, 1, 0, g));
    const PetscInt *r[D];
    PetscCall(DMDAGetInfo(g.da, nullptr, nullptr, nullptr, nullptr, &p[0], &p[1], &p[2], nullptr,
                          nullptr, nullptr, nullptr, nullptr, nullptr));
    PetscCall(DMDAGetOwnershipRanges(g.da, &r[0], &r[1], &r[2]));
    for (int d = 0; d < D; ++d) l[d].assign(r[d], r[d] + p[d]);
    PetscCall(RunOn(g));
    PetscCall(GridDestroy(g));
  }
  bool uneven = false;
  for (int d = 0; d < D; ++d)
    if (p[d] > 1 && l[d][0] > 2) {
      --l[d][0];
      ++l[d][p[d] - 1];
      uneven = true;
    }
  if (!uneven) PetscFunctionReturn(0);
  GridT<D> g;
  PetscCall(GridCreate(comm, H, kOrigin, kCells, 1, 0, g, p[0], p[1], l[0].data(), l[1].data(),
                       p[2], l[2].data()));
  const PetscInt *r[D];
  PetscCall(DMDAGetOwnershipRanges(g.da, &r[0], &r[1], &r[2]));
  for (int d = 0; d < D; ++d) CHECK(std::equal(l[d].begin(), l[d].end(), r[d]));
  if (rank == 0)
    std::printf("explicit node counts: first slabs %d, %d, %d nodes\n", (int)l[0][0], (int)l[1][0],
                (int)l[2][0]);
  PetscCall(RunOn(g));
  PetscCall(GridDestroy(g));
  PetscFunctionReturn(0);
}

PetscErrorCode RunOn(GridT<D> &g) {
  PetscFunctionBeginUser;
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscMPIInt rank, size;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscInt px, py, pz;
  PetscCall(DMDAGetInfo(g.da, nullptr, nullptr, nullptr, nullptr, &px, &py, &pz, nullptr, nullptr,
                        nullptr, nullptr, nullptr, nullptr));
  CHECK(px * py * pz == size);
  CHECK(g.shared == (size == 1));
  if (rank == 0)
    std::printf("grid %d x %d x %d cells on %d ranks, process grid %d x %d x %d\n", (int)kCells[0],
                (int)kCells[1], (int)kCells[2], size, (int)px, (int)py, (int)pz);

  AllParticles A;
  double total_mass = 0;
  for (PetscInt p = 0; p < N; ++p) total_mass += A.mass[p];

  // this rank's particles: those centred in its cells
  Particles parts;
  PetscCall(ParticlesCreate(g, parts));
  CHECK(parts.dim == 3);
  ParticleListT<D> init;
  for (PetscInt p = 0; p < N; ++p) {
    PetscInt c[D];
    for (int d = 0; d < D; ++d) c[d] = CellOf(&A.x[p * D], d);
    if (!g.owns_cell(c)) continue;
    ParticleInitT<D> q{};
    for (int d = 0; d < D; ++d) {
      q.x[d] = A.x[p * D + d];
      q.lp[d] = A.lp[p * D + d];
    }
    q.vol = A.vol[p];
    q.density = A.mass[p] / A.vol[p];
    q.gamma = 0;
    q.colour = A.colour[p];
    q.mat = A.mat[p];
    q.pid = p;
    q.load = A.load[p];
    init.push_back(q);
  }
  PetscCall(ParticlesAdd(parts, init));
  // the fields ParticlesAdd sets from its own rule (mass = density vol, v = 0, F = I, stress = 0)
  // are overwritten with the generated values, so the checks below compare exactly
  {
    ParticleView P;
    PetscCall(ParticlesGetView(parts, P));
    for (PetscInt q = 0; q < P.n; ++q) {
      const PetscInt p = P.pid[q];
      P.mass[q] = A.mass[p];
      P.weight[q] = A.weight[p];
      P.eps_p[q] = A.eps_p[p];
      for (int d = 0; d < D; ++d) P.v[q * D + d] = A.v[p * D + d];
      for (int s = 0; s < NS; ++s) P.stress[q * NS + s] = A.stress[p * NS + s];
      for (int e = 0; e < D * D; ++e) P.F[q * D * D + e] = A.F[p * D * D + e];
    }
    PetscCall(ParticlesRestoreView(parts, P));
  }
  PetscInt nglobal;
  PetscCall(ParticlesGlobalCount(parts, &nglobal));
  CHECK(nglobal == N);
  std::vector<PetscInt> seen(N, 0);
  PetscCall(CheckSwarm(g, parts, A, false, seen));
  PetscCall(CheckIds(comm, seen, "created"));

  double worst;
  {
    Reference R(A.view(false));
    PetscCall(CheckP2G(g, parts, R, total_mass, "created", worst));
  }

  // move every particle, migrate
  PetscInt left = 0;
  {
    ParticleView P;
    PetscCall(ParticlesGetView(parts, P));
    for (PetscInt q = 0; q < P.n; ++q) {
      PetscInt c[D];
      for (int d = 0; d < D; ++d) {
        P.x[q * D + d] = A.moved[P.pid[q] * D + d];
        c[d] = CellOf(P.x + q * D, d);
      }
      left += !g.owns_cell(c);
    }
    PetscCall(ParticlesRestoreView(parts, P));
  }
  PetscInt left_all;
  PetscCallMPI(MPI_Allreduce(&left, &left_all, 1, MPIU_INT, MPI_SUM, comm));
  if (size > 1) CHECK(left_all > 0); // the migration has something to move
  PetscCall(ParticlesMigrate(parts, g));
  PetscCall(ParticlesGlobalCount(parts, &nglobal));
  CHECK(nglobal == N);
  PetscCall(CheckSwarm(g, parts, A, true, seen));
  if (rank == 0) std::printf("moved: %d particles left their rank's cells\n", (int)left_all);
  PetscCall(CheckIds(comm, seen, "migrated"));
  {
    Reference R(A.view(true));
    double w2;
    PetscCall(CheckP2G(g, parts, R, total_mass, "migrated", w2));
    worst = std::max(worst, w2);
  }
  PetscCall(ParticlesDestroy(parts));
  PetscFunctionReturn(0);
}

} // namespace

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscCall(Run());
  int fails = pmpm_test::failures(), all;
  MPI_Allreduce(&fails, &all, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) std::printf("grid3d: %d failures on all ranks\n", all);
  const int rc = pmpm_test::report("grid3d");
  PetscCall(PetscFinalize());
  return all ? EXIT_FAILURE : rc;
}
