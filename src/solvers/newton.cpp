// The implicit quasi-static solver (-solver newton): load steps, each a PETSc SNES solve for the
// nodal displacement increment on a DMDA of its own, the residual and the consistent tangent
// assembled from the particles by the kernels of implicit_kernels.cpp.
//
// Choices:
//  - Unknowns: du at every grid node. Held dofs (box faces, held_dofs) and nodes without particle
//    support (mass <= kSmallCut x the largest nodal mass: empty cells and the tiniest "small
//    cuts") are removed by an identity row and column scaled by the largest P-wave modulus:
//    R = k du, so du = 0 there and the matrix stays non-singular (and symmetric where the
//    tangent is). Their du is masked out of the kinematics, so rows and columns agree.
//  - Loads: the explicit P2G's nodal external force (gravity by the shape's weights, tractions at
//    the blocks' faces) at the particles' positions at the step's start, times the load factor.
//  - The grid moves with the body within a load step (implicit_kernels.hpp); after a step the
//    particles carry the increment (x += sum S_i du_i, F, V, stress) and the grid is reset.
//    Relaxation's equilibrium is on the reset grid, so after the last load step Newton takes
//    equilibrium steps at full load until relaxation's unbalanced-force ratio (StaticResidual) is
//    <= -tol. An equilibrium step solves the reset grid's residual itself, its particles moving
//    over the fixed grid, with that motion's term in the tangent (reset_internal_force,
//    particle_reset_stiffness): on the moved grid instead, each step removed a fixed share of the
//    residual (landfill at h = 0.25 mm, one load step: 11 equilibrium steps, 4 now).
//  - Membrane chains bonded on both faces are more internal force on the same du
//    (chain_implicit.hpp); the stencil is then one node wider. Stages run on a LoadPath (stage 0
//    ramps the loads, a shrinkage stage its eigenstrain at full load, a void stage releases the
//    removed particles' forces at full load; Scene::stage_change; a moving-support stage imposes
//    the supports' displacement at full load, SupportMotion in solver.hpp).
//  - Prescribed supports (Simulation::prescribed) are Dirichlet dofs: identity rows and columns
//    like held dofs, R = kref (du - ubar), but their du enters the kinematics (kinL). The force
//    on them is the residual's rows before that replacement (SupportReaction).
//  - A load step whose solve fails is halved (-newton_max_cuts in a row); one failing at the last
//    halving ends the stage not converged (relaxation's capped stage: a collapse), never an
//    answer.
//  - Default linear solver: in 2D a direct LU by MUMPS (any rank count; PETSc's own LU is
//    serial), in 3D GMRES with BoomerAMG (an LU's fill grows too fast: kIterativeRtol); the line
//    search bt; every -snes_/-ksp_/-pc_ option overrides them.
//  - -dim 3: the same solve on the 3D grid (every function below that takes a D); membrane sheets
//    are refused (CheckSupported).
#include "pmpm/util/options.hpp"
#include "pmpm/model/solver.hpp"
#include "pmpm/solvers/chain_implicit.hpp"
#include "pmpm/step/cycle.hpp"
#include "pmpm/core/degradation.hpp"
#include "pmpm/solvers/implicit_kernels.hpp"
#include "pmpm/step/stress_update.hpp"
#include <petscsnes.h>
#include <algorithm>
#include <cmath>
#include <cstring>

namespace pmpm {

// The solver's state: its options, the SNES on its DMDA, the trial state of the current load
// step, and its work over the run (the summary's "newton" member).
struct NewtonSolver final : EquilibriumSolver {
  const char *name() const override { return "newton"; }
  PetscErrorCode setup(Simulation &sim) override;
  PetscErrorCode solve_stage(Simulation &sim) override;
  std::string report() const override {
    return "\"newton\": {\"load_steps\": " + std::to_string(solved_steps) +
           ", \"nonlinear_iterations\": " + std::to_string(newton_its) +
           ", \"linear_iterations\": " + std::to_string(linear_its) +
           ", \"halvings\": " + std::to_string(halvings) + "},\n  ";
  }
  PetscErrorCode destroy() override;
  // bonded chains and interfaces only (CheckSupported)
  bool supports(SolverFeature f) const override {
    return f != SolverFeature::FrictionalFaces && f != SolverFeature::Axisymmetric;
  }
  // MUMPS reads its -mat_mumps_* options at the first factorisation
  bool reads_later(const char *option) const override {
    return !std::strncmp(option, "mat_mumps_", 10);
  }

  Simulation *sim = nullptr;
  PetscInt solved_steps = 0, newton_its = 0, linear_its = 0; // over the run
  PetscInt halvings = 0; // failed load steps retried at half the increment, over the run
  DM da = nullptr;
  SNES snes = nullptr;
  Mat J = nullptr;
  Vec U = nullptr, R = nullptr, fext = nullptr, maskG = nullptr;
  Vec R0 = nullptr;   // a void stage's residual at its start (the removed particles' forces)
  double release = 0; // the share of R0 still held by the load path (1 - t: LoadPath)
  Vec Uloc = nullptr, Rloc = nullptr, maskL = nullptr;
  // Moving supports (Simulation::prescribed, SupportMotion): Dirichlet dofs whose increment ubar
  // is imposed. kinL: the dofs whose du enters the kinematics, the free ones and these (maskL
  // with no supports); pdof: per owned dof its entry of Simulation::prescribed or -1.
  Vec kinL = nullptr;
  std::vector<PetscInt> pdof;
  std::vector<double> ubar;       // per owned dof: the load step's prescribed increment (m)
  std::vector<double> support_du; // per prescribed entry: the stage's displacement (m)
  double reaction[3] = {};        // the last residual's weighted support force (this rank)
  // the solve's nodes (D = sim.set.dim of them used): ghosted start and size, owned ones
  PetscInt gs[3] = {}, gm[3] = {}, s[3] = {}, m[3] = {};
  PetscInt load_steps = 10, max_cuts = 6, max_equilibrium = 30;
  double cell_fraction = 0; // -newton_cell_fraction: largest |du| / h of a load step (0: off)
  double small_cut = 1e-9;  // -newton_small_cut: a node below this share of the largest nodal
                            // mass is held (its stiffness would be of the order of this share
                            // squared: a small cut that only adds round-off to the solve)
  double frac = 0;          // the last solve's max |du| / h over the free dofs
  bool atol_given = false;  // -snes_atol given: keep it; else set per step from the load
  bool rtol_given = false;  // -snes_rtol given: every solve keeps it
  double rtol = 1e-10;      // a load step's relative tolerance (-snes_rtol)
  double lambda = 0;        // load factor of the current solve
  double t_stage = 0;       // wall time at the stage's start (the progress lines' ETA)
  double shrink = 0;        // the current load step's share of the stage's shrinkage
  double kref = 1;          // diagonal of held and unsupported dofs (Pa: the stiffness scale)
  PetscInt width = 2;       // the solve's stencil width (the shape's support)
  std::vector<double> G, Gm, Fnew, snew, epsp, Pk, blocks;
  std::vector<double> eigen; // the load step's eigenstrain increment, 3 per particle (or empty)
  bool reset = false;        // an equilibrium step: the residual of the reset grid
                             // (implicit_kernels.hpp), with the particles' increments up
  std::vector<double> up;
  int outside = 0; // the last residual's particles whose trial support left the ghost nodes
  // membrane chains (chain_implicit.hpp): per chain its stencils and trial state at the step's
  // start, and the points' increments of all chains (summed over ranks)
  std::vector<ChainStencil> cst;
  std::vector<ChainTrial> ctr;
  std::vector<double> cdu;
  // the DMDA's global numbering (ownership ranges, per rank its first row): the projected chain
  // coupling reaches nodes beyond the ghosts (chain_implicit.hpp)
  std::vector<PetscInt> xs, ys, roff;
  PetscInt global_dof(PetscInt i, PetscInt j, int d) const {
    const int px = static_cast<int>(xs.size()) - 1, py = static_cast<int>(ys.size()) - 1;
    int rx = 0, ry = 0;
    while (rx + 1 < px && i >= xs[rx + 1]) ++rx;
    while (ry + 1 < py && j >= ys[ry + 1]) ++ry;
    const PetscInt lx = xs[rx + 1] - xs[rx];
    return roff[ry * px + rx] + ((j - ys[ry]) * lx + (i - xs[rx])) * DIM + d;
  }
};

namespace {
PetscLogEvent ev_residual, ev_jacobian, ev_solve, ev_commit;

// A node with less mass than this share of the largest nodal mass is held (its stiffness would be
// of the order of this share squared: a small cut that only adds round-off to the solve).
// Without -snes_atol, a load step's solve stops when |R|_2 <= kAtolShare x -tol x |f_ext|_2 (well
// inside relaxation's criterion, which the equilibrium steps then check on the reset grid).
constexpr double kAtolShare = 1e-3;
// Without -snes_rtol, an equilibrium step's solve stops when it has reduced its residual (the reset
// grid's) by this factor, and the next step linearizes again at the committed positions: the
// tangent's reset-grid term is linearized at the step's start, so it loses accuracy as the trial
// positions move away, and a fresh step converges faster than more iterations (landfill, 1 load
// step, h = 0.25 mm: 16 Newton iterations in all with 1e-4, 10 with 2e-2, 9 with 0.1; at
// h = 0.125 mm 9 with 0.3, 0.1 or 0.02).
constexpr double kEquilibriumRtol = 0.1;
// Newton iterations a solve may take before it counts as failed (and its load step is halved),
// unless -snes_max_it is given: PETSc's 50. With 15 the footing at 1.15 q_u reported its collapse
// later (63 s against 55 s: its load steps near the limit need more, so they were halved more
// often) and the footing at 1.05 q_u failed earlier.
constexpr PetscInt kMaxIterations = 50;
// -dim 3's default linear solver: GMRES preconditioned by BoomerAMG (pmpm's defaults below) to
// this relative tolerance. A 3D LU fills in: on the quarter circular footing at h = B/8 (11,271
// dofs, 24,576 particles) each MUMPS factorisation took 13.5 s (60 s with METIS ordering, 169 s
// with AMF) against 0.6 s for a BoomerAMG solve; at 1e-8 the Newton iterations are those of the
// LU (4 in the first load step, 14-15 linear iterations each), at 1e-6 also, with 10 each.
constexpr double kIterativeRtol = 1e-8;

// The solve's ghosted nodes, over the explicit grid of dimension D (D = 2, 3: the functions
// below that take a D run the solve in that dimension, -dim).
template <int D> NodalViewT<D> LocalView(const NewtonSolver &ns, double *data) {
  const GridT<D> &g = ns.sim->template grid_of<D>();
  NodalViewT<D> v;
  v.h = g.h;
  for (int d = 0; d < D; ++d) {
    v.origin[d] = g.origin[d];
    v.gs[d] = ns.gs[d];
    v.gm[d] = ns.gm[d];
  }
  v.data = data;
  return v;
}

// gw = lambda g in D dimensions (GravityDirection, cycle.hpp).
template <int D> void Gravity(const Simulation &sim, double lambda, double gw[D]) {
  GravityDirection<D>(sim, gw);
  for (int d = 0; d < D; ++d) gw[d] *= lambda;
}

// du (ghosted) to the trial state of every particle: G, F_new, trial stress and plastic strain
// (copies; the committed state is untouched), and P.
template <class Shape, int D>
PetscErrorCode TrialState(NewtonSolver &ns, Vec U, const ParticleView &P) {
  Simulation &sim = *ns.sim;
  const double *u, *mk;
  PetscFunctionBeginUser;
  const size_t n = static_cast<size_t>(P.n);
  ns.G.resize(n * D * D);
  ns.Fnew.resize(n * D * D);
  ns.Pk.resize(n * D * D);
  ns.snew.assign(P.stress, P.stress + n * NStress<D>);
  ns.epsp.assign(P.eps_p, P.eps_p + n);
  PetscCall(DMGlobalToLocal(ns.da, U, INSERT_VALUES, ns.Uloc));
  PetscCall(VecGetArrayRead(ns.Uloc, &u));
  PetscCall(VecGetArrayRead(ns.kinL, &mk));
  if (ns.reset) ns.up.resize(n * D); // the equilibrium step's trial positions need u_p
  implicit_gradient<Shape, D>(P, LocalView<D>(ns, const_cast<double *>(u)),
                              LocalView<D>(ns, const_cast<double *>(mk)), ns.G.data(),
                              ns.reset ? ns.up.data() : nullptr);
  if constexpr (D == 2) { // the chains' points: the owners' increments, summed so every rank
    size_t off = 0;       // has all (membrane chains are 2D)
    for (const ChainStencil &S : ns.cst) {
      chain_point_increment(S, LocalView<D>(ns, const_cast<double *>(u)),
                            LocalView<D>(ns, const_cast<double *>(mk)), ns.cdu.data() + off);
      off += S.mapped.size() * DIM;
    }
  }
  PetscCall(VecRestoreArrayRead(ns.kinL, &mk));
  PetscCall(VecRestoreArrayRead(ns.Uloc, &u));
  if (!ns.cst.empty()) {
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, ns.cdu.data(), static_cast<int>(ns.cdu.size()),
                               MPI_DOUBLE, MPI_SUM, sim.comm));
    size_t off = 0;
    for (size_t k = 0; k < sim.chains.size(); ++k) {
      chain_trial(sim.chains[k], ns.cst[k], ns.cdu.data() + off, ns.ctr[k]);
      off += static_cast<size_t>(sim.chains[k].n) * DIM;
    }
  }
  implicit_deformation<D>(P.n, ns.G.data(), P.F, ns.Fnew.data());
  ns.Gm.resize(n * D * D);
  implicit_midpoint_gradient<D>(P.n, ns.G.data(), ns.Gm.data());
  const double *eigen = ns.eigen.empty() ? nullptr : ns.eigen.data();
  UpdateStresses(sim, ns.Gm.data(), ns.Fnew.data(), ns.snew.data(), ns.epsp.data(), eigen);
  implicit_piola<D>(P.n, ns.G.data(), ns.snew.data(), ns.Pk.data());
  PetscFunctionReturn(0);
}

// R = f_int(du) - lambda f_ext on free dofs, kref (du - ubar) on the others (ubar: a moving
// support's increment, else 0). The prescribed dofs' rows before that, -R weighted by their
// entries' weights, are the force the body puts on the supports (ns.reaction, this rank's).
template <class Shape, int D> PetscErrorCode Residual(NewtonSolver &ns, Vec U, Vec R) {
  ParticleView P;
  double *r;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(ns.sim->parts, P));
  PetscCall(TrialState<Shape, D>(ns, U, P));
  PetscCall(VecZeroEntries(ns.Rloc));
  PetscCall(VecGetArray(ns.Rloc, &r));
  if (ns.reset) {
    double gw[D];
    Gravity<D>(*ns.sim, ns.lambda, gw);
    ns.outside = reset_internal_force<Shape, D>(P, ns.G.data(), ns.snew.data(), ns.Pk.data(),
                                                ns.up.data(), gw, LocalView<D>(ns, r));
  } else
    implicit_internal_force<Shape, D>(P, ns.Pk.data(), LocalView<D>(ns, r));
  if constexpr (D == 2)
    for (size_t k = 0; k < ns.cst.size(); ++k)
      chain_internal_force(ns.cst[k], ns.ctr[k], LocalView<D>(ns, r));
  PetscCall(VecRestoreArray(ns.Rloc, &r));
  PetscCall(ParticlesRestoreView(ns.sim->parts, P));
  PetscCall(VecZeroEntries(R));
  PetscCall(DMLocalToGlobal(ns.da, ns.Rloc, ADD_VALUES, R));
  PetscCall(VecAXPY(R, -ns.lambda, ns.fext));
  if (ns.release != 0) PetscCall(VecAXPY(R, -ns.release, ns.R0)); // a void stage's path
  const double *u, *mk;
  PetscInt n;
  PetscCall(VecGetLocalSize(R, &n));
  PetscCall(VecGetArray(R, &r));
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArrayRead(ns.maskG, &mk));
  if (ns.pdof.empty()) {
    for (PetscInt q = 0; q < n; ++q)
      if (mk[q] == 0.0) r[q] = ns.kref * u[q];
  } else {
    const PrescribedVelocity &pv = ns.sim->prescribed;
    for (int d = 0; d < D; ++d) ns.reaction[d] = 0.0;
    for (PetscInt q = 0; q < n; ++q)
      if (ns.pdof[q] >= 0) ns.reaction[q % D] -= pv.weight[ns.pdof[q]] * r[q];
    for (PetscInt q = 0; q < n; ++q)
      if (mk[q] == 0.0) r[q] = ns.kref * (u[q] - ns.ubar[q]);
  }
  PetscCall(VecRestoreArrayRead(ns.maskG, &mk));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(VecRestoreArray(R, &r));
  PetscFunctionReturn(0);
}

PetscErrorCode FormResidual(SNES, Vec U, Vec R, void *ctx) {
  NewtonSolver &ns = *static_cast<NewtonSolver *>(ctx);
  const bool linear = ns.sim->set.shape == ShapeKind::Linear;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_residual, 0, 0, 0, 0));
  if (ns.sim->set.dim == 3)
    PetscCall(linear ? Residual<LinearShape, 3>(ns, U, R) : Residual<UGIMPShape, 3>(ns, U, R));
  else
    PetscCall(linear ? Residual<LinearShape, 2>(ns, U, R) : Residual<UGIMPShape, 2>(ns, U, R));
  PetscCall(PetscLogEventEnd(ev_residual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// Each particle's consistent stiffness at the trial state of U (with the reset grid's term in an
// equilibrium step), gathered per node pair into NB (add_particle_blocks); then the membrane
// chains' bar stiffness. NB's storage is ns.blocks.
template <class Shape, int D>
PetscErrorCode ParticleBlocks(NewtonSolver &ns, Vec U, NodeBlocksT<D> &NB) {
  constexpr int NN = Weights<Shape, D>::NN, ND = NN * D, NS = NStress<D>;
  Simulation &sim = *ns.sim;
  const GridT<D> &g = sim.template grid_of<D>();
  ParticleView P;
  Weights<Shape, D> W;
  double A[D * D * D * D], K[ND * ND], H[NN][NHess<D>], gw[D];
  PetscFunctionBeginUser;
  Gravity<D>(sim, ns.lambda, gw);
  NB.w = ns.width;
  size_t nb = 1, nodes = 1; // blocks per node, ghosted nodes
  for (int d = 0; d < D; ++d) {
    NB.gs[d] = ns.gs[d];
    NB.gm[d] = ns.gm[d];
    nb *= static_cast<size_t>(2 * NB.w + 1);
    nodes *= static_cast<size_t>(ns.gm[d]);
  }
  ns.blocks.assign(nodes * nb * D * D, 0.0);
  NB.data = ns.blocks.data();
  PetscCall(ParticlesGetView(sim.parts, P));
  PetscCall(TrialState<Shape, D>(ns, U, P));
  for (PetscInt p = 0; p < P.n; ++p) {
    const PetscInt mat = P.mat[p];
    piola_tangent<D>(*sim.model.mats[mat].model, &ns.G[p * D * D], P.stress + p * NS,
                     &ns.snew[p * NS], P.F + p * D * D, P.eps_p[p], A,
                     ns.eigen.empty() ? nullptr : &ns.eigen[3 * p]);
    weights<Shape>(P.x + p * D, P.lp + p * D, g.origin, g.h, W);
    particle_stiffness<Shape, D>(W, P.vol[p], A, K);
    if (ns.reset) {
      weight_hessians<Shape, D>(P.x + p * D, P.lp + p * D, g.origin, g.h, H);
      particle_reset_stiffness<Shape, D>(W, H, P.vol[p], &ns.G[p * D * D], &ns.snew[p * NS],
                                         P.weight[p], gw, K);
    }
    add_particle_blocks<Shape, D>(W, K, NB);
  }
  PetscCall(ParticlesRestoreView(sim.parts, P));
  int missed = 0;
  if constexpr (D == 2)
    for (size_t k = 0; k < ns.cst.size(); ++k)
      missed += chain_stiffness(sim.chains[k], ns.cst[k], ns.ctr[k], NB);
  // the stencil width covers a chain whose neighbouring points lie within a cell of each other
  PetscCheck(missed == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB,
             "-solver newton: %d couplings of a membrane chain reach beyond the stencil width %d "
             "(its points more than a cell apart?): raise -newton_load_steps",
             missed, (int)ns.width);
  PetscFunctionReturn(0);
}

// -chain_strain_projection: the material term couples segments sharing a projection node, up to
// about 7 nodes apart, beyond the stencil: added with global indices (the matrix takes new
// nonzeros), rows over the free dofs.
PetscErrorCode ProjectedChainCoupling(NewtonSolver &ns, Mat B) {
  Simulation &sim = *ns.sim;
  std::vector<ChainDofValue> pa, pb;
  std::vector<PetscInt> gr, gc;
  std::vector<double> gv;
  const double *mk;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(ns.maskL, &mk));
  const NodalView ML = LocalView<DIM>(ns, const_cast<double *>(mk));
  for (size_t k = 0; k < ns.cst.size(); ++k) {
    const ChainStencil &S = ns.cst[k];
    if (!S.project) continue;
    for (int I = 0; I + 1 < static_cast<int>(S.nstart.size()); ++I) {
      const double M = chain_projected_coupling(sim.chains[k], S, ns.ctr[k], I, pa, pb);
      gr.clear();
      gc.clear();
      gv.clear();
      std::vector<double> av;
      for (const ChainDofValue &e : pa)
        if (ML.node(e.i, e.j)[e.d] != 0.0) {
          gr.push_back(ns.global_dof(e.i, e.j, e.d));
          av.push_back(e.v / M);
        }
      if (gr.empty() || pb.empty()) continue;
      for (const ChainDofValue &e : pb) gc.push_back(ns.global_dof(e.i, e.j, e.d));
      for (double x : av)
        for (const ChainDofValue &e : pb) gv.push_back(x * e.v);
      PetscCall(MatSetValues(B, static_cast<PetscInt>(gr.size()), gr.data(),
                             static_cast<PetscInt>(gc.size()), gc.data(), gv.data(), ADD_VALUES));
    }
  }
  PetscCall(VecRestoreArrayRead(ns.maskL, &mk));
  PetscFunctionReturn(0);
}

// Calls f(n, q) for the nodes of the box [lo, lo + size) (D of the three values used), x fastest:
// n the node's D indices (n[2] = 0 in 2D), q its position in that order.
template <int D, class F> void ForNodes(const PetscInt *lo, const PetscInt *size, F &&f) {
  const PetscInt klo = D == 3 ? lo[2] : 0, khi = D == 3 ? lo[2] + size[2] : 1;
  PetscInt q = 0;
  for (PetscInt k = klo; k < khi; ++k)
    for (PetscInt j = lo[1]; j < lo[1] + size[1]; ++j)
      for (PetscInt i = lo[0]; i < lo[0] + size[0]; ++i) {
        const PetscInt n[3] = {i, j, k};
        f(n, q++);
      }
}

// Node n (three indices, n[2] unused in 2D) of a nodal view, and the block of node n with its
// neighbour n + dn.
template <int D> double *NodeAt(const NodalViewT<D> &v, const PetscInt *n) {
  if constexpr (D == 2)
    return v.node(n[0], n[1]);
  else
    return v.node(n[0], n[1], n[2]);
}
template <int D> const double *BlockAt(const NodeBlocksT<D> &B, const PetscInt *n, const int *dn) {
  if constexpr (D == 2)
    return B.block(n[0], n[1], dn[0], dn[1]);
  else
    return B.block(n[0], n[1], n[2], dn[0], dn[1], dn[2]);
}

// NB into the matrix: one insertion per node row over its free dofs, the columns its free
// neighbours' dofs (held and unsupported dofs have neither).
template <int D> PetscErrorCode InsertBlocks(NewtonSolver &ns, const NodeBlocksT<D> &NB, Mat B) {
  const int w = NB.w,
            nb = D == 3 ? (2 * w + 1) * (2 * w + 1) * (2 * w + 1) : (2 * w + 1) * (2 * w + 1);
  const int wz = D == 3 ? w : 0;
  const double *mk;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(ns.maskL, &mk));
  const NodalViewT<D> M = LocalView<D>(ns, const_cast<double *>(mk));
  std::vector<MatStencil> rows(D), cols(static_cast<size_t>(nb) * D);
  std::vector<double> vals(static_cast<size_t>(D) * nb * D);
  std::vector<const double *> src(static_cast<size_t>(nb) * D);
  std::vector<int> ra(D), cb(static_cast<size_t>(nb) * D);
  PetscErrorCode ierr = 0;
  ForNodes<D>(ns.gs, ns.gm, [&](const PetscInt *n, PetscInt) {
    if (ierr) return;
    int nr = 0, nc = 0;
    const double *mn = NodeAt<D>(M, n);
    for (int a = 0; a < D; ++a)
      if (mn[a] != 0.0) {
        rows[nr] = MatStencil{n[2], n[1], n[0], a};
        ra[nr++] = a;
      }
    if (nr == 0) return;
    bool any = false;
    for (int dk = -wz; dk <= wz; ++dk)
      for (int dj = -w; dj <= w; ++dj)
        for (int di = -w; di <= w; ++di) {
          const int dn[3] = {di, dj, dk};
          const PetscInt nn[3] = {n[0] + di, n[1] + dj, n[2] + dk};
          bool inside = true;
          for (int d = 0; d < D; ++d)
            inside = inside && nn[d] >= ns.gs[d] && nn[d] < ns.gs[d] + ns.gm[d];
          if (!inside) continue;
          const double *b = BlockAt<D>(NB, n, dn), *mm = NodeAt<D>(M, nn);
          for (int c = 0; c < D; ++c)
            if (mm[c] != 0.0) {
              cols[nc] = MatStencil{nn[2], nn[1], nn[0], c};
              src[nc] = b;
              cb[nc++] = c;
              for (int r = 0; r < nr; ++r) any = any || b[ra[r] * D + c] != 0.0;
            }
        }
    if (!any) return; // no particle of this rank couples this node
    for (int r = 0; r < nr; ++r)
      for (int c = 0; c < nc; ++c) vals[r * nc + c] = src[c][ra[r] * D + cb[c]];
    ierr = MatSetValuesStencil(B, nr, rows.data(), nc, cols.data(), vals.data(), ADD_VALUES);
  });
  PetscCall(ierr);
  PetscCall(VecRestoreArrayRead(ns.maskL, &mk));
  PetscFunctionReturn(0);
}

// kref on the diagonal of the owned dofs that are not free (held, prescribed, unsupported).
template <int D> PetscErrorCode HeldDiagonal(NewtonSolver &ns, Mat B) {
  const double *mk;
  PetscErrorCode ierr = 0;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(ns.maskG, &mk));
  ForNodes<D>(ns.s, ns.m, [&](const PetscInt *n, PetscInt q) {
    for (int a = 0; a < D && !ierr; ++a)
      if (mk[q * D + a] == 0.0) {
        MatStencil st{n[2], n[1], n[0], a};
        ierr = MatSetValuesStencil(B, 1, &st, 1, &st, &ns.kref, ADD_VALUES);
      }
  });
  PetscCall(ierr);
  PetscCall(VecRestoreArrayRead(ns.maskG, &mk));
  PetscFunctionReturn(0);
}

// The consistent tangent: each particle's stiffness gathered per node, the chains' couplings,
// then one insertion per node row over its free, supported dofs; kref on the diagonal of the
// others.
template <class Shape, int D> PetscErrorCode Tangent(NewtonSolver &ns, Vec U, Mat B) {
  NodeBlocksT<D> NB;
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(B));
  PetscCall(ParticleBlocks<Shape, D>(ns, U, NB));
  if constexpr (D == 2) PetscCall(ProjectedChainCoupling(ns, B));
  PetscCall(InsertBlocks<D>(ns, NB, B));
  PetscCall(HeldDiagonal<D>(ns, B));
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode FormJacobian(SNES, Vec U, Mat Jac, Mat B, void *ctx) {
  NewtonSolver &ns = *static_cast<NewtonSolver *>(ctx);
  PetscFunctionBeginUser;
  const bool linear = ns.sim->set.shape == ShapeKind::Linear;
  PetscCall(PetscLogEventBegin(ev_jacobian, 0, 0, 0, 0));
  if (ns.sim->set.dim == 3)
    PetscCall(linear ? Tangent<LinearShape, 3>(ns, U, B) : Tangent<UGIMPShape, 3>(ns, U, B));
  else
    PetscCall(linear ? Tangent<LinearShape, 2>(ns, U, B) : Tangent<UGIMPShape, 2>(ns, U, B));
  if (Jac != B) { // -snes_mf_operator and the like
    PetscCall(MatAssemblyBegin(Jac, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(Jac, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(PetscLogEventEnd(ev_jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// The grid's cells per direction (three values; 0 along z in 2D).
template <int D> void GridCells(Simulation &sim, PetscInt ncell[3]) {
  const GridT<D> &g = sim.template grid_of<D>();
  for (int d = 0; d < 3; ++d) ncell[d] = d < D ? g.ncell[d] : 0;
}

// The entry of Simulation::prescribed that holds dof d of node n (D indices), or -1.
template <int D> PetscInt PrescribedEntry(Simulation &sim, const PetscInt *n, int d) {
  const std::vector<PetscInt> &key = sim.prescribed.key;
  if (key.empty()) return -1;
  PetscInt ncell[3];
  GridCells<D>(sim, ncell);
  for (int e = 0; e < D; ++e)
    if (n[e] < 0 || n[e] > ncell[e]) return -1;
  const PetscInt k = PrescribedKey<D>(n, d, ncell);
  const auto it = std::lower_bound(key.begin(), key.end(), k);
  return it != key.end() && *it == k ? static_cast<PetscInt>(it - key.begin()) : -1;
}

// The kinematic mask kinL: the free dofs (maskL) and the prescribed ones, whose du is imposed.
template <int D> PetscErrorCode KinematicMask(NewtonSolver &ns) {
  double *k;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(ns.maskL, ns.kinL));
  if (ns.sim->prescribed.empty()) PetscFunctionReturn(0);
  PetscCall(VecGetArray(ns.kinL, &k));
  ForNodes<D>(ns.gs, ns.gm, [&](const PetscInt *n, PetscInt q) {
    for (int a = 0; a < D; ++a)
      if (PrescribedEntry<D>(*ns.sim, n, a) >= 0) k[q * D + a] = 1.0;
  });
  PetscCall(VecRestoreArray(ns.kinL, &k));
  PetscFunctionReturn(0);
}

// The unit load (explicit P2G's external force at the current positions) and the dof masks: a
// dof is free when its node has support and neither a box face nor a prescribed support holds it.
template <int D> PetscErrorCode Loads(NewtonSolver &ns) {
  using Dof = GridDofT<D>;
  Simulation &sim = *ns.sim;
  GridT<D> &g = sim.template grid_of<D>();
  GridViewT<D> G;
  ParticleView P;
  LoadT<D> load; // factor 1
  double *f, *mk;
  PetscFunctionBeginUser;
  GravityDirection<D>(sim, load.gdir);
  PetscCall(ParticlesGetView(sim.parts, P));
  PetscCall(GridGetLocal(g, true, G));
  if (sim.set.shape == ShapeKind::Linear)
    StaticForces<LinearShape, D>(sim, P, load, G);
  else
    StaticForces<UGIMPShape, D>(sim, P, load, G);
  // the chains' weight and end loads, and their mass (support), into their bodies' blocks
  if constexpr (D == 2)
    for (const Chain &c : sim.chains) p2g_chain(c, load, G, g);
  PetscCall(GridRestoreLocal(g, G));
  PetscCall(ParticlesRestoreView(sim.parts, P));
  PetscCall(GridLocalToGlobalAdd(g));
  PetscCall(GridGetGlobal(g, G));
  // bonded bodies move as one: a node's mass and load are the sums over its bodies
  auto body_sum = [&](const double *node, int dof) {
    double v = 0;
    for (int b = 0; b < G.nbody; ++b) v += node[b * Dof::NDOF + dof];
    return v;
  };
  double mmax = 0;
  ForNodes<D>(ns.s, ns.m, [&](const PetscInt *n, PetscInt) {
    mmax = std::fmax(mmax, body_sum(G.node(n), Dof::M));
  });
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mmax, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
  PetscCall(VecGetArray(ns.fext, &f));
  PetscCall(VecGetArray(ns.maskG, &mk));
  const bool moving = !sim.prescribed.empty();
  size_t owned = D;
  for (int d = 0; d < D; ++d) owned *= static_cast<size_t>(ns.m[d]);
  ns.pdof.assign(moving ? owned : 0, -1);
  PetscInt ncell[3];
  GridCells<D>(sim, ncell);
  ForNodes<D>(ns.s, ns.m, [&](const PetscInt *n, PetscInt nq) {
    const double *node = G.node(n);
    const PetscInt q = nq * D;
    bool held[D];
    held_dofs<D>(n, ncell, sim.model.face, held);
    const bool supported = body_sum(node, Dof::M) > ns.small_cut * mmax;
    for (int a = 0; a < D; ++a) {
      f[q + a] = body_sum(node, Dof::FEXT + a);
      if (moving) ns.pdof[q + a] = PrescribedEntry<D>(sim, n, a);
      mk[q + a] = supported && !held[a] && !(moving && ns.pdof[q + a] >= 0) ? 1.0 : 0.0;
    }
  });
  PetscCall(VecRestoreArray(ns.maskG, &mk));
  PetscCall(VecRestoreArray(ns.fext, &f));
  PetscCall(GridRestoreGlobal(g, G));
  PetscCall(VecSet(ns.maskL, 0.0)); // ghosts beyond the box stay 0: never free
  PetscCall(DMGlobalToLocal(ns.da, ns.maskG, INSERT_VALUES, ns.maskL));
  PetscCall(KinematicMask<D>(ns));
  PetscFunctionReturn(0);
}

// The converged increment into the particles: x += sum S_i du_i, F, V = det(F) V0, stress and
// plastic strain (the materials' own update with dudx = G_m, the midpoint gradient), velocity 0;
// migration if needed.
template <class Shape, int D> PetscErrorCode Commit(NewtonSolver &ns) {
  constexpr int NN = Weights<Shape, D>::NN;
  Simulation &sim = *ns.sim;
  ParticleView P;
  Weights<Shape, D> W;
  const double *u, *mk;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(sim.parts, P));
  PetscCall(TrialState<Shape, D>(ns, ns.U, P)); // G and F_new of the converged du; Uloc holds du
  PetscCall(VecGetArrayRead(ns.Uloc, &u));
  PetscCall(VecGetArrayRead(ns.kinL, &mk));
  const NodalViewT<D> Uv = LocalView<D>(ns, const_cast<double *>(u)),
                      Mv = LocalView<D>(ns, const_cast<double *>(mk));
  const GridT<D> &g = sim.template grid_of<D>();
  double hi[D];
  for (int d = 0; d < D; ++d) hi[d] = g.origin[d] + g.ncell[d] * g.h;
  double bad[5] = {0, 0, 0, 0, 0}; // count, pid, x, y, z
  PetscInt left = 0;
  for (PetscInt p = 0; p < P.n; ++p) {
    weights<Shape>(P.x + p * D, P.lp + p * D, g.origin, g.h, W);
    double dx[D] = {};
    for (int k = 0; k < NN; ++k) {
      const double *mn = Mv.node(W, k), *un = Uv.node(W, k);
      for (int a = 0; a < D; ++a) dx[a] += W.w[k] * mn[a] * un[a];
    }
    double *x = P.x + p * D, *F = P.F + p * D * D;
    for (int a = 0; a < D; ++a) {
      x[a] += dx[a];
      P.v[p * D + a] = 0.0;
    }
    for (int q = 0; q < D * D; ++q) F[q] = ns.Fnew[p * D * D + q];
    const double J = det_of<D>(F);
    double xs = x[0] + x[1];
    if constexpr (D == 3) xs += x[2];
    P.vol[p] = J * P.vol0[p];
    bool inside = true;
    for (int d = 0; d < D; ++d) inside = inside && x[d] >= g.origin[d] && x[d] < hi[d];
    if (!(J > 0.0) || !std::isfinite(xs) || !inside) {
      if (bad[0]++ == 0) {
        bad[1] = static_cast<double>(P.pid[p]);
        for (int d = 0; d < D; ++d) bad[2 + d] = x[d];
      }
      continue;
    }
    PetscInt cell[D];
    for (int d = 0; d < D; ++d) cell[d] = static_cast<PetscInt>((x[d] - g.origin[d]) / g.h);
    if (!g.owns_cell(cell)) ++left;
  }
  PetscCall(VecRestoreArrayRead(ns.kinL, &mk));
  PetscCall(VecRestoreArrayRead(ns.Uloc, &u));
  // the committed update, in place
  UpdateStresses(sim, ns.Gm.data(), P.F, P.stress, P.eps_p,
                 ns.eigen.empty() ? nullptr : ns.eigen.data());
  PetscCall(ParticlesRestoreView(sim.parts, P));
  // the chains: the trial positions of the converged du (alike on every rank), then the law's
  // committed state and the tensions from them
  for (size_t k = 0; k < sim.chains.size(); ++k) {
    Chain &c = sim.chains[k];
    c.x = ns.ctr[k].x;
    chain_update_tension(c);
  }
  struct {
    double v;
    int rank;
  } loc = {bad[0], sim.rank}, glob;
  PetscCallMPI(MPI_Allreduce(&loc, &glob, 1, MPI_DOUBLE_INT, MPI_MAXLOC, sim.comm));
  if (glob.v > 0) {
    PetscCallMPI(MPI_Bcast(bad, 5, MPI_DOUBLE, glob.rank, sim.comm));
    char where[96];
    if (D == 3)
      PetscCall(PetscSNPrintf(where, sizeof where, "(%g, %g, %g)", bad[2], bad[3], bad[4]));
    else
      PetscCall(PetscSNPrintf(where, sizeof where, "(%g, %g)", bad[2], bad[3]));
    SETERRQ(sim.comm, PETSC_ERR_NOT_CONVERGED,
            "-solver newton: load step %" PetscInt_FMT " (load factor %g) moved particle %.0f "
            "off the grid or inverted it (x = %s m). Raise -newton_load_steps (now "
            "%" PetscInt_FMT ") or enlarge the grid.",
            ns.solved_steps + 1, ns.lambda, bad[1], where, ns.load_steps);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &left, 1, MPIU_INT, MPI_SUM, sim.comm));
  if (left > 0) PetscCall(Migrate(sim));
  PetscFunctionReturn(0);
}

// The chains' stencils at the load step's start; every point must be mapped by one rank or pinned.
// (Membrane chains are 2D: -dim 3 has none.)
PetscErrorCode ChainStencils(NewtonSolver &ns) {
  Simulation &sim = *ns.sim;
  PetscFunctionBeginUser;
  if (sim.set.dim == 3) PetscFunctionReturn(0);
  ns.cst.resize(sim.chains.size());
  ns.ctr.resize(sim.chains.size());
  size_t npts = 0;
  GridView G; // the grid's geometry only
  G.h = sim.grid.h;
  for (int d = 0; d < DIM; ++d) {
    G.origin[d] = sim.grid.origin[d];
    G.ncell[d] = sim.grid.ncell[d];
  }
  std::vector<int> count(sim.chains.size()), expect(sim.chains.size());
  const double *mk;
  PetscCall(VecGetArrayRead(ns.maskL, &mk));
  for (size_t k = 0; k < sim.chains.size(); ++k) {
    const Chain &c = sim.chains[k];
    count[k] = chain_stencil(c, G, sim.grid, ns.cst[k]);
    expect[k] = c.n - (c.pin[0] ? 1 : 0) - (c.pin[1] ? 1 : 0);
    npts += static_cast<size_t>(c.n) * DIM;
    if (ns.cst[k].project)
      chain_stencil_mask(ns.cst[k], LocalView<DIM>(ns, const_cast<double *>(mk)));
  }
  PetscCall(VecRestoreArrayRead(ns.maskL, &mk));
  for (ChainStencil &S : ns.cst) // every rank needs every point's masked weights (columns)
    if (S.project)
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, S.wm.data(), static_cast<int>(S.wm.size()),
                                 MPI_DOUBLE, MPI_SUM, sim.comm));
  ns.cdu.assign(npts, 0.0);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, count.data(), static_cast<int>(count.size()), MPI_INT,
                             MPI_SUM, sim.comm));
  for (size_t k = 0; k < sim.chains.size(); ++k)
    PetscCheck(count[k] == expect[k], sim.comm, PETSC_ERR_NOT_CONVERGED,
               "-solver newton: chain %s has %d of its %d free points off the grid: enlarge the "
               "grid",
               sim.chains[k].name.c_str(), expect[k] - count[k], expect[k]);
  PetscFunctionReturn(0);
}

// The largest displacement increment of a free dof, in cells.
PetscErrorCode IncrementInCells(NewtonSolver &ns, double *frac) {
  const double *u, *mk;
  PetscInt n;
  double mx = 0;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(ns.U, &n));
  PetscCall(VecGetArrayRead(ns.U, &u));
  PetscCall(VecGetArrayRead(ns.maskG, &mk));
  for (PetscInt q = 0; q < n; ++q) mx = std::fmax(mx, mk[q] * std::fabs(u[q]));
  PetscCall(VecRestoreArrayRead(ns.maskG, &mk));
  PetscCall(VecRestoreArrayRead(ns.U, &u));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mx, 1, MPI_DOUBLE, MPI_MAX, ns.sim->comm));
  *frac = mx / ns.sim->grid.h;
  PetscFunctionReturn(0);
}

// A stage's load path, parametrised by t from 0 to 1 over its load steps: the load factor on f_ext
// and the share of the stage's change imposed by t (Scene::stage_change). Stage 0 ramps the loads
// from zero; a shrinkage stage holds them at full and imposes its eigenstrain in proportion to t
// (each load step its share, in the trial stress update and in the commit: a stress-free strain,
// so the tangent has no term of its own). A void stage (particles removed by the scene's
// begin_stage) holds the loads at full and releases the removed particles' forces: R0, the
// residual of the remaining particles at the stage's start (in equilibrium before the removal, so
// R0 is what the removed ones carried), is held back by the share 1 - t (R(du) - (1 - t) R0 = 0,
// solved by du = 0 at t = 0), the usual excavation path, which a failed step can halve. A
// moving-support stage (SupportMotion: the trapdoor's door) holds the loads at full and imposes
// the share t of the supports' displacement: each load step's increment (t1 - t0) of it on the
// prescribed dofs, Dirichlet rows kref (du - ubar) with du = ubar from the start.
struct LoadPath {
  bool ramp_loads = true;            // f_ext from 0 to full over the stage; else full throughout
  double shrink = 0;                 // the stage's volumetric shrinkage (Simulation::stage_shrink)
  bool release = false;              // a void stage: R0 released from 1 to 0 over the stage
  SupportMotion *supports = nullptr; // a moving-support stage: the scene that moves them
  double load(double t) const { return ramp_loads ? t : 1.0; }
};

// The load step's prescribed increments (ns.ubar: share dt of the stage's support displacement,
// 0 in equilibrium steps and other stages) and its initial guess: du = ubar on them, 0 elsewhere.
PetscErrorCode PrescribedIncrement(NewtonSolver &ns, double dt) {
  double *u;
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(ns.U));
  ns.ubar.assign(ns.pdof.size(), 0.0);
  if (ns.support_du.empty() || dt == 0.0) PetscFunctionReturn(0);
  PetscCall(VecGetArray(ns.U, &u));
  for (size_t q = 0; q < ns.pdof.size(); ++q)
    if (ns.pdof[q] >= 0) u[q] = ns.ubar[q] = dt * ns.support_du[ns.pdof[q]];
  PetscCall(VecRestoreArray(ns.U, &u));
  PetscFunctionReturn(0);
}

// One load step from t0 to t1 on the path, from the committed state: SNES solve, then commit.
// Returns the SNES reason (the state is committed only when it is positive) and, under
// -newton_cell_fraction with `limit`, whether the converged step was rejected for moving the body
// more than that fraction of a cell (not committed either).
PetscErrorCode LoadStep(NewtonSolver &ns, const LoadPath &path, double t0, double t1, bool limit,
                        bool equilibrium, SNESConvergedReason *reason, bool *rejected) {
  Simulation &sim = *ns.sim;
  PetscInt its = 0, lits = 0;
  const double lambda = path.load(t1);
  PetscFunctionBeginUser;
  *rejected = false;
  PetscCall(ns.sim->set.dim == 3 ? Loads<3>(ns) : Loads<2>(ns));
  PetscCall(ChainStencils(ns));
  ns.lambda = lambda;
  ns.release = path.release ? 1.0 - t1 : 0.0;
  ns.shrink = path.shrink * (t1 - t0);
  ns.eigen.clear();
  if (ns.shrink != 0) { // this step's share of the eigenstrain, per particle (3: xx yy zz)
    ParticleView P;
    PetscCall(ParticlesGetView(sim.parts, P));
    if (sim.set.dim == 3)
      shrinkage_increment<3>(P, sim.model.shrink, ns.shrink, ns.eigen);
    else
      shrinkage_increment<DIM>(P, sim.model.shrink, ns.shrink, ns.eigen);
    PetscCall(ParticlesRestoreView(sim.parts, P));
  }
  double atol = PETSC_DEFAULT;
  if (!ns.atol_given) {
    PetscCall(VecNorm(ns.fext, NORM_2, &atol));
    atol *= kAtolShare * sim.set.tol * lambda;
  }
  const double rtol = equilibrium && !ns.rtol_given ? kEquilibriumRtol : ns.rtol;
  ns.reset = equilibrium; // relaxation's criterion is checked on the reset grid: solve there
  PetscCall(SNESSetTolerances(ns.snes, atol, rtol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(PrescribedIncrement(ns, equilibrium || !path.supports ? 0.0 : t1 - t0));
  PetscCall(PetscLogEventBegin(ev_solve, 0, 0, 0, 0));
  PetscCall(SNESSolve(ns.snes, nullptr, ns.U));
  PetscCall(PetscLogEventEnd(ev_solve, 0, 0, 0, 0));
  if (ns.reset) { // particles whose trial support left their rank's ghost nodes: say so
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ns.outside, 1, MPI_INT, MPI_SUM, sim.comm));
    if (ns.outside > 0 && !sim.set.quiet)
      PetscCall(PetscPrintf(sim.comm,
                            "  equilibrium step: %d particles moved past their rank's ghost nodes "
                            "and kept the moved grid's force in this step\n",
                            ns.outside));
  }
  ns.reset = false;
  ns.outside = 0;
  PetscCall(SNESGetConvergedReason(ns.snes, reason));
  PetscCall(SNESGetIterationNumber(ns.snes, &its));
  PetscCall(SNESGetLinearSolveIterations(ns.snes, &lits));
  ns.newton_its += its;
  ns.linear_its += lits;
  if (*reason == SNES_DIVERGED_LINEAR_SOLVE) {
    // a failed factorisation (MUMPS: a zero pivot) leaves the factor's error state behind, and
    // MUMPS then skips every later factorisation: start the next solve from a fresh one
    KSP ksp;
    PC pc;
    PetscCall(SNESGetKSP(ns.snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCReset(pc));
  }
  if (*reason <= 0) PetscFunctionReturn(0);
  PetscCall(IncrementInCells(ns, &ns.frac));
  if (limit && ns.cell_fraction > 0 && ns.frac > ns.cell_fraction) {
    *rejected = true;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(ev_commit, 0, 0, 0, 0));
  const bool linear = sim.set.shape == ShapeKind::Linear;
  if (sim.set.dim == 3)
    PetscCall(linear ? Commit<LinearShape, 3>(ns) : Commit<UGIMPShape, 3>(ns));
  else
    PetscCall(linear ? Commit<LinearShape, 2>(ns) : Commit<UGIMPShape, 2>(ns));
  PetscCall(PetscLogEventEnd(ev_commit, 0, 0, 0, 0));
  ++ns.solved_steps;
  ++sim.run.step;
  ++sim.run.stage_step;
  if (!equilibrium) sim.run.time = t1; // pseudo-time: the stage's path parameter
  if (!equilibrium && path.supports) PetscCall(path.supports->supports_moved(sim, t1));
  if (!sim.set.quiet) {
    double rn;
    PetscCall(SNESGetFunctionNorm(ns.snes, &rn));
    PetscCall(PetscPrintf(sim.comm,
                          "  load step %4" PetscInt_FMT "  %s %.4f  Newton its %2" PetscInt_FMT
                          "  linear its %3" PetscInt_FMT "  |R| %.3e  max|du|/h %.2e  (%s)",
                          ns.solved_steps, path.ramp_loads ? "load" : "stage", t1, its, lits, rn,
                          ns.frac, SNESConvergedReasons[*reason]));
    // the load steps' ETA: the stage's time so far over the path covered (the equilibrium steps
    // that follow are cheaper: one Newton iteration each)
    const double spent = MPI_Wtime() - ns.t_stage;
    if (!equilibrium && t1 < 1.0)
      PetscCall(PetscPrintf(sim.comm, "  load steps ETA %.0f s", spent * (1.0 - t1) / t1));
    PetscCall(PetscPrintf(sim.comm, "\n"));
  }
  PetscCall(sim.scene->monitor(sim));
  PetscFunctionReturn(0);
}

// The force the body puts on the prescribed supports at the committed state, weighted by their
// entries (Simulation::support_force, as relaxation's grid update reports it): minus the residual's
// prescribed rows at full load and du = 0. That is the residual of the last converged step on the
// reset grid (the commit moved the particles where its trial state put them), whose free rows
// relaxation's criterion checked.
PetscErrorCode SupportReaction(NewtonSolver &ns) {
  Simulation &sim = *ns.sim;
  PetscFunctionBeginUser;
  if (sim.prescribed.empty()) PetscFunctionReturn(0);
  PetscCall(ns.sim->set.dim == 3 ? Loads<3>(ns) : Loads<2>(ns));
  PetscCall(ChainStencils(ns));
  ns.lambda = 1.0;
  ns.release = 0.0;
  ns.eigen.clear();
  ns.reset = false;
  PetscCall(PrescribedIncrement(ns, 0.0));
  PetscCall(FormResidual(ns.snes, ns.U, ns.R, &ns));
  double force[3];
  PetscCallMPI(MPI_Allreduce(ns.reaction, force, sim.set.dim, MPI_DOUBLE, MPI_SUM, sim.comm));
  for (int d = 0; d < DIM; ++d) sim.support_force[d] = force[d]; // the report's x and y
  PetscFunctionReturn(0);
}

// A void stage's R0 (LoadPath): the residual at full load and du = 0 of the particles that remain.
PetscErrorCode ReleaseStart(NewtonSolver &ns) {
  PetscFunctionBeginUser;
  PetscCall(ns.sim->set.dim == 3 ? Loads<3>(ns) : Loads<2>(ns));
  PetscCall(ChainStencils(ns));
  ns.lambda = 1.0;
  ns.release = 0.0;
  ns.eigen.clear();
  ns.reset = false;
  PetscCall(PrescribedIncrement(ns, 0.0));
  PetscCall(FormResidual(ns.snes, ns.U, ns.R0, &ns));
  PetscFunctionReturn(0);
}

// What Newton cannot solve yet: a clear error, never a silent wrong answer.
PetscErrorCode CheckSupported(Simulation &sim, NewtonSolver & /*ns*/) {
  const char *fix = "; use -solver relaxation";
  PetscFunctionBeginUser;
  // -dim 3: the sheets' contact and stiffness are not in the residual and tangent yet
  PetscCheck(sim.sheets.empty(), sim.comm, PETSC_ERR_SUP,
             "-solver newton does not solve 3D sheets yet (-dim 3 with a membrane, here sheet "
             "%s)%s",
             sim.sheets.empty() ? "" : sim.sheets[0].name.c_str(), fix);
  // membrane chains: bonded on both faces, the bodies and the sheet then share one field
  for (const Chain &c : sim.chains)
    PetscCheck(c.top.type == FaceType::Bonded && c.bottom.type == FaceType::Bonded, sim.comm,
               PETSC_ERR_SUP,
               "-solver newton solves membrane chains bonded on both faces only: chain %s has "
               "%s / %s faces (-chain_%s_interface, default from -interface_type, else contact); "
               "add -chain_%s_interface bonded, or for slip and separation%s",
               c.name.c_str(), FaceTypeNames[(int)c.top.type], FaceTypeNames[(int)c.bottom.type],
               c.name.c_str(), c.name.c_str(), fix);
  // without chains -interface_type is the colour-1 body's interface
  PetscCheck(!sim.chains.empty() || sim.model.iface.type == InterfaceType::Bonded, sim.comm,
             PETSC_ERR_SUP,
             "-solver newton does not support frictional interfaces (-interface_type %s) yet%s",
             InterfaceTypeNames[(int)sim.model.iface.type], fix);
  // stages: stage 0's loads, shrinkage, void and moving-support stages have a load path
  // (Newton's LoadPath)
  const auto *motion = dynamic_cast<const SupportMotion *>(sim.scene.get());
  for (PetscInt k = 1; k <= sim.scene->stages(); ++k) {
    const StageChange ch = sim.scene->stage_change(k);
    PetscCheck(ch == StageChange::Shrink || ch == StageChange::Void ||
                   (motion && motion->moves_supports(k)),
               sim.comm, PETSC_ERR_SUP,
               "-solver newton runs stage 0, shrinkage and void stages only (and a scene's "
               "moving supports): stage %d of scene %s changes %s%s",
               (int)k, sim.set.scene.c_str(), StageChangeNames[(int)ch], fix);
  }
  // a prescribed support under a membrane chain: the chains' projected columns do not take it
  PetscCheck(sim.prescribed.empty() || sim.chains.empty(), sim.comm, PETSC_ERR_SUP,
             "-solver newton does not support prescribed supports with membrane chains yet%s", fix);
  // a direction no box face holds (and no support inside the box) is a rigid translation: the
  // matrix is singular and every load step's linear solve fails, so say it before the run
  const int D = static_cast<int>(sim.set.dim);
  for (int d = 0; d < D && sim.prescribed.empty(); ++d) {
    bool held = false;
    for (int f = 0; f < 2 * D; ++f)
      held = held || sim.model.face[f] == FaceBC::Fixed ||
             (sim.model.face[f] == FaceBC::Roller && f / 2 == d);
    PmpmCheckInput(held, sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-solver newton: no box face holds the %c direction, a rigid translation the "
                   "implicit solve cannot fix (its matrix is singular): put -bc_%cmin or "
                   "-bc_%cmax on roller (a symmetry plane) or fixed",
                   "xyz"[d], "xyz"[d], "xyz"[d]);
  }
  PetscCheck(!sim.set.dynamic, sim.comm, PETSC_ERR_SUP,
             "-solver newton is quasi-static: -dynamic needs -solver relaxation");
  PetscCheck(!sim.set.fbar, sim.comm, PETSC_ERR_SUP, "-solver newton does not support -fbar yet%s",
             fix);
  PetscCheck(sim.set.shape != ShapeKind::CPGIMP, sim.comm, PETSC_ERR_SUP,
             "-solver newton does not support -shape cpgimp yet (its blocks change within a load "
             "step): use -shape pmpm or mpm with it%s",
             fix);
  PetscCheck(sim.set.restart.empty() && sim.set.checkpoint_every == 0, sim.comm, PETSC_ERR_SUP,
             "-solver newton does not support -restart or -checkpoint_every yet%s", fix);
  for (size_t k = 0; k < sim.model.mats.size(); ++k) {
    const Material &m = *sim.model.mats[k].model;
    PetscCheck(m.has_tangent(), sim.comm, PETSC_ERR_SUP,
               "-solver newton does not support -mat_%s_model %s yet (it has no consistent "
               "tangent)%s",
               sim.model.mats[k].name.c_str(), m.model(), fix);
  }
  PetscFunctionReturn(0);
}
} // namespace

// With -pc_type hypre (BoomerAMG), pmpm's defaults for its matrices, each still a PETSc option:
// HMIS coarsening, ext+i interpolation of at most 4 entries per row, and one level of aggressive
// coarsening. BoomerAMG's own (Falgout, classical) build a heavy hierarchy for uGIMP's 5 x 5-node
// couplings (50 nonzeros per row): the landfill at h = 0.125 mm, one load step, GMRES to 1e-6,
// takes 25.9 s with them and 13.0 s with these (118 linear iterations against 75, each cheaper, and
// a 2x cheaper setup); without aggressive coarsening 19.3 s, two levels of it 15.8 s, P_max 2
// 15.9 s, strong threshold 0.5 16.0 s, nodal coarsening 26.8 s (bench/newton.py).
// hypre_default: BoomerAMG is the default preconditioner (3D), so the defaults apply unless
// -pc_type names another.
PetscErrorCode BoomerAMGDefaults(bool hypre_default) {
  char pc[64] = "", type[64] = "";
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-pc_type", pc, sizeof pc, nullptr));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-pc_hypre_type", type, sizeof type, nullptr));
  const bool hypre = pc[0] ? std::strcmp(pc, "hypre") == 0 : hypre_default;
  if (!hypre || (type[0] && std::strcmp(type, "boomeramg") != 0)) PetscFunctionReturn(0);
  const char *const defaults[][2] = {{"-pc_hypre_boomeramg_coarsen_type", "HMIS"},
                                     {"-pc_hypre_boomeramg_interp_type", "ext+i"},
                                     {"-pc_hypre_boomeramg_P_max", "4"},
                                     {"-pc_hypre_boomeramg_agg_nl", "1"}};
  for (const auto &d : defaults) {
    PetscCall(PetscOptionsHasName(nullptr, nullptr, d[0], &set));
    if (!set) PetscCall(PetscOptionsSetValue(nullptr, d[0], d[1]));
  }
  PetscFunctionReturn(0);
}

namespace {
// The -newton_* options, each checked against its range.
PetscErrorCode ReadOptions(NewtonSolver &ns, Simulation &sim) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(sim.comm, "newton_", "Implicit solver (-solver newton)", nullptr);
  PetscCall(PmpmOptionsInt("-load_steps",
                           "Load steps from zero to the full load, 1..100000 (the fewest "
                           "under -newton_cell_fraction; a step whose solve fails is halved up "
                           "to -newton_max_cuts times)",
                           nullptr, ns.load_steps, &ns.load_steps, nullptr));
  PetscCall(PmpmOptionsInt("-max_cuts",
                           "Halvings in a row of a failed load step below the nominal one, 0..30 "
                           "(a step failing at the last ends the stage NOT converged: a collapse)",
                           nullptr, ns.max_cuts, &ns.max_cuts, nullptr));
  PetscCall(PmpmOptionsInt("-equilibrium_steps",
                           "Most equilibrium steps at full load on the reset grid to reach -tol, "
                           "0..1000",
                           nullptr, ns.max_equilibrium, &ns.max_equilibrium, nullptr));
  PetscCall(PmpmOptionsReal("-cell_fraction",
                            "Adaptive load steps: the largest displacement increment of a step "
                            "in cells, 0 <= f <= 1 (0: off, the -newton_load_steps equal steps)",
                            nullptr, ns.cell_fraction, &ns.cell_fraction, nullptr));
  PetscCall(PmpmOptionsReal("-small_cut",
                            "Nodes with less than this share of the largest nodal mass are held "
                            "(du = 0: the small-cut nodes), 0 <= s < 0.1",
                            nullptr, ns.small_cut, &ns.small_cut, nullptr));
  PetscOptionsEnd();
  PetscCheck(ns.small_cut >= 0 && ns.small_cut < 0.1, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-newton_small_cut must be in [0, 0.1) (got %g)", ns.small_cut);
  PetscCheck(ns.cell_fraction >= 0 && ns.cell_fraction <= 1, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-newton_cell_fraction must be in [0, 1] (got %g; 0: off)", ns.cell_fraction);
  PetscCheck(ns.load_steps >= 1 && ns.load_steps <= 100000, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-newton_load_steps must be in 1..100000 (got %" PetscInt_FMT ")", ns.load_steps);
  PetscCheck(ns.max_cuts >= 0 && ns.max_cuts <= 30, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-newton_max_cuts must be in 0..30 (got %" PetscInt_FMT ")", ns.max_cuts);
  PetscCheck(
      ns.max_equilibrium >= 0 && ns.max_equilibrium <= 1000, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
      "-newton_equilibrium_steps must be in 0..1000 (got %" PetscInt_FMT ")", ns.max_equilibrium);
  PetscFunctionReturn(0);
}

// The solve's DMDA: the explicit grid's nodes and partition (2D or 3D, -dim), D dofs, a box
// stencil as wide as the shape's support (uGIMP: 3 nodes per direction, so couplings reach 2
// nodes; a chain couples the nodes of neighbouring points up to a cell apart, one node farther);
// its matrix (not under -help), its global numbering (global_dof, 2D chains) and the solver's
// vectors.
template <int D> PetscErrorCode CreateGrid(NewtonSolver &ns, Simulation &sim, bool help) {
  PetscInt M, N, Pz, px, py, pz;
  const PetscInt *lx, *ly, *lz;
  const DM gda = sim.template grid_of<D>().da;
  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(gda, nullptr, &M, &N, &Pz, &px, &py, &pz, nullptr, nullptr, nullptr,
                        nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(gda, &lx, &ly, &lz));
  PetscInt width = sim.set.shape == ShapeKind::Linear ? LinearShape::NS - 1 : UGIMPShape::NS - 1;
  if (!sim.chains.empty()) width = UGIMPShape::NS;
  ns.width = width;
  if constexpr (D == 3)
    PetscCall(DMDACreate3d(sim.comm, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED,
                           DMDA_STENCIL_BOX, M, N, Pz, px, py, pz, D, width, lx, ly, lz, &ns.da));
  else
    PetscCall(DMDACreate2d(sim.comm, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED, DMDA_STENCIL_BOX, M,
                           N, px, py, D, width, lx, ly, &ns.da));
  PetscCall(DMSetUp(ns.da));
  PetscCall(DMDAGetCorners(ns.da, &ns.s[0], &ns.s[1], &ns.s[2], &ns.m[0], &ns.m[1], &ns.m[2]));
  PetscCall(
      DMDAGetGhostCorners(ns.da, &ns.gs[0], &ns.gs[1], &ns.gs[2], &ns.gm[0], &ns.gm[1], &ns.gm[2]));
  if (!help) PetscCall(DMCreateMatrix(ns.da, &ns.J)); // -help: the options only, no matrix
  bool project = false;
  for (const Chain &c : sim.chains) project = project || c.strain_projection;
  if (!help && project) { // the projected chain coupling reaches beyond the stencil
    PetscCall(MatSetOption(ns.J, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_FALSE));
    PetscCall(MatSetOption(ns.J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  }
  const PetscInt *ox, *oy;
  PetscCall(DMDAGetOwnershipRanges(ns.da, &ox, &oy, nullptr));
  ns.xs.assign(px + 1, 0);
  ns.ys.assign(py + 1, 0);
  for (PetscInt r = 0; r < px; ++r) ns.xs[r + 1] = ns.xs[r] + ox[r];
  for (PetscInt r = 0; r < py; ++r) ns.ys[r + 1] = ns.ys[r] + oy[r];
  ns.roff.assign(px * py + 1, 0);
  for (PetscInt r = 0; r < px * py; ++r)
    ns.roff[r + 1] = ns.roff[r] + ox[r % px] * oy[r / px] * DIM;
  PetscCall(DMCreateGlobalVector(ns.da, &ns.U));
  PetscCall(VecDuplicate(ns.U, &ns.R));
  PetscCall(VecDuplicate(ns.U, &ns.fext));
  PetscCall(VecDuplicate(ns.U, &ns.maskG));
  PetscCall(VecDuplicate(ns.U, &ns.R0));
  PetscCall(DMCreateLocalVector(ns.da, &ns.Uloc));
  PetscCall(VecDuplicate(ns.Uloc, &ns.Rloc));
  PetscCall(VecDuplicate(ns.Uloc, &ns.maskL));
  PetscCall(VecDuplicate(ns.Uloc, &ns.kinL));
  PetscFunctionReturn(0);
}

// The SNES on the DMDA: Newton with the bt line search, MUMPS LU (3D: GMRES and BoomerAMG), pmpm's
// BoomerAMG defaults; then
// every -snes_/-ksp_/-pc_ option, and which tolerances the user gave.
PetscErrorCode CreateSNES(NewtonSolver &ns, Simulation &sim) {
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(SNESCreate(sim.comm, &ns.snes));
  PetscCall(SNESSetDM(ns.snes, ns.da));
  PetscCall(SNESSetFunction(ns.snes, ns.R, FormResidual, &ns));
  PetscCall(SNESSetJacobian(ns.snes, ns.J, ns.J, FormJacobian, &ns));
  PetscCall(SNESSetType(ns.snes, SNESNEWTONLS));
  SNESLineSearch ls;
  PetscCall(SNESGetLineSearch(ns.snes, &ls));
  // bt: backtracking with the Armijo condition, one residual per trial length, the full step
  // whenever it decreases |R| enough (the quadratic rate near equilibrium); l2 spends extra
  // residuals on every iteration, basic has no fallback but the load step's halving
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBT));
  PetscCall(SNESSetTolerances(ns.snes, PETSC_DEFAULT, 1e-10, PETSC_DEFAULT, kMaxIterations,
                              PETSC_DEFAULT));
  KSP ksp;
  PC pc;
  PetscCall(SNESGetKSP(ns.snes, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  const bool iterative = sim.set.dim == 3;
  if (iterative) { // kIterativeRtol
    PetscCall(KSPSetType(ksp, KSPGMRES));
    PetscCall(KSPSetTolerances(ksp, kIterativeRtol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
    PetscCall(PCSetType(pc, PCHYPRE));
    PetscCall(PCHYPRESetType(pc, "boomeramg"));
  } else {
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(PCSetType(pc, PCLU));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  }
  PetscCall(BoomerAMGDefaults(iterative));
  PetscCall(SNESSetFromOptions(ns.snes));
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-snes_atol", &set));
  ns.atol_given = set;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-snes_rtol", &set));
  ns.rtol_given = set;
  PetscCall(SNESGetTolerances(ns.snes, nullptr, &ns.rtol, nullptr, nullptr, nullptr));
  // read by SNESSolve, after main's unused-option check: mark them used here
  for (const char *o : {"-snes_test_jacobian", "-snes_test_jacobian_view", "-snes_converged_reason",
                        "-ksp_converged_reason"})
    PetscCall(PetscOptionsHasName(nullptr, nullptr, o, &set));
  PetscFunctionReturn(0);
}
} // namespace

// Read the -newton_* options, refuse what Newton cannot solve yet (chains in contact, frictional
// interfaces, stages without a load path, materials without a consistent tangent, ...) with a
// clear error, and create the SNES on its own DMDA (DIM dofs per node, box stencil as wide as the
// shape's support) with every -snes_/-ksp_/-pc_ option applied. With -help only lists the
// options.
PetscErrorCode NewtonSolver::setup(Simulation &sim) {
  PetscBool help = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  this->sim = &sim;
  PetscCall(ReadOptions(*this, sim));
  if (!help) PetscCall(CheckSupported(sim, *this));
  if (!ev_residual) {
    PetscClassId cls;
    PetscCall(PetscClassIdRegister("pmpm newton", &cls));
    PetscCall(PetscLogEventRegister("NewtonResidual", cls, &ev_residual));
    PetscCall(PetscLogEventRegister("NewtonJacobian", cls, &ev_jacobian));
    PetscCall(PetscLogEventRegister("NewtonSolve", cls, &ev_solve));
    PetscCall(PetscLogEventRegister("NewtonCommit", cls, &ev_commit));
  }
  for (const auto &m : sim.model.mats) kref = std::fmax(kref, m.model->wave_modulus());
  // under -help the grid is the 2D one whatever -dim says (SimulationSetup): no solve follows
  if (sim.set.dim == 3 && !help)
    PetscCall(CreateGrid<3>(*this, sim, help));
  else
    PetscCall(CreateGrid<2>(*this, sim, help));
  PetscCall(CreateSNES(*this, sim));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonSolver::destroy() {
  NewtonSolver *ns = this;
  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(&ns->snes));
  PetscCall(MatDestroy(&ns->J));
  for (Vec *v : {&ns->U, &ns->R, &ns->fext, &ns->maskG, &ns->R0, &ns->Uloc, &ns->Rloc, &ns->maskL,
                 &ns->kinL})
    PetscCall(VecDestroy(v));
  PetscCall(DMDestroy(&ns->da));
  PetscFunctionReturn(0);
}

namespace {
// The current stage's load path, from what the scene says it changes (Scene::stage_change; a
// scene may also move supports, SupportMotion), and what the progress line calls it. CheckSupported
// refused the other changes; a scene's begin_stage may not switch a chain's faces from bonded
// either.
PetscErrorCode StagePath(NewtonSolver &ns, LoadPath &path, const char **what) {
  Simulation &sim = *ns.sim;
  PetscFunctionBeginUser;
  const StageChange change = sim.scene->stage_change(sim.stage);
  auto *motion = dynamic_cast<SupportMotion *>(sim.scene.get());
  const bool moving =
      change == StageChange::Other && sim.stage > 0 && motion && motion->moves_supports(sim.stage);
  PetscCheck(change == StageChange::Loads || change == StageChange::Shrink ||
                 change == StageChange::Void || moving,
             sim.comm, PETSC_ERR_SUP, "-solver newton: stage %d changes %s; use -solver relaxation",
             (int)sim.stage, StageChangeNames[(int)change]);
  for (const Chain &c : sim.chains)
    PetscCheck(c.top.type == FaceType::Bonded && c.bottom.type == FaceType::Bonded, sim.comm,
               PETSC_ERR_SUP,
               "-solver newton: stage %d runs chain %s with %s / %s faces (bonded only); use "
               "-solver relaxation",
               (int)sim.stage, c.name.c_str(), FaceTypeNames[(int)c.top.type],
               FaceTypeNames[(int)c.bottom.type]);
  path.ramp_loads = change == StageChange::Loads;
  path.shrink = change == StageChange::Shrink ? sim.stage_shrink : 0.0;
  path.release = change == StageChange::Void;
  path.supports = moving ? motion : nullptr;
  ns.support_du.clear();
  if (moving) PetscCall(motion->support_displacement(sim, sim.stage, ns.support_du));
  *what = path.ramp_loads ? "the loads from zero"
          : path.release  ? "a void's forces released at full load"
          : moving        ? "supports moved at full load"
                          : "shrinkage at full load";
  PetscFunctionReturn(0);
}

// A stage that cannot go on (a load step failed at the last halving, or an equilibrium step
// failed) ends as relaxation's capped stage: not converged, the last committed state.
PetscErrorCode Collapse(NewtonSolver &ns, const LoadPath &path, double t, double target,
                        SNESConvergedReason reason, bool equilibrium) {
  Simulation &sim = *ns.sim;
  RunState &run = sim.run;
  const Settings &s = sim.set;
  PetscFunctionBeginUser;
  PetscCall(StaticResidual(sim, s.shape, &run.ratio));
  run.converged = false;
  run.stage_seconds = MPI_Wtime() - ns.t_stage;
  run.wall_seconds += run.stage_seconds;
  if (s.quiet) PetscFunctionReturn(0);
  if (equilibrium)
    PetscCall(PetscPrintf(sim.comm,
                          "NOT converged: stage %d's equilibrium step at full load did not "
                          "converge (SNES: %s) with unbalanced-force ratio %.3e > %g (%.2f "
                          "s): the stage cannot reach equilibrium (a collapse). See "
                          "-snes_converged_reason -snes_monitor.\n",
                          (int)sim.stage, SNESConvergedReasons[reason], run.ratio, s.tol,
                          run.stage_seconds));
  else
    PetscCall(PetscPrintf(
        sim.comm,
        "NOT converged: stage %d stopped at %s %.6g with unbalanced-force ratio %.3e > %g "
        "(%.2f s): the load step to %.6g did not converge (SNES: %s) at %" PetscInt_FMT
        " halvings of the nominal step (-newton_max_cuts), so the stage finds no "
        "equilibrium beyond %.6g of its path: a collapse, unless more halvings "
        "(-newton_max_cuts) or load steps (-newton_load_steps) carry it further.\n",
        (int)sim.stage, path.ramp_loads ? "load factor" : "stage fraction", t, run.ratio, s.tol,
        run.stage_seconds, target, SNESConvergedReasons[reason], ns.max_cuts, t));
  PetscFunctionReturn(0);
}

// The stage's load steps from t = 0 to 1 on its path. A step whose solve fails (SNES diverged,
// the line search failed, or its iteration cap) is retried at half the increment, up to
// -newton_max_cuts halvings below the nominal step in a row; each converged step doubles the
// increment back toward the nominal one. A step that fails at the smallest increment ends the
// stage out of equilibrium (Collapse). Under -newton_cell_fraction f the first step sizes them
// all: from the unloaded state its increment is the load's alone, |du| / h per unit load (later
// steps also carry the grid reset's correction, which does not shrink with them), so the step
// count is ceil(that / f), the first step redone when it moved more than f cells. Returns the
// halvings and whether the stage collapsed.
PetscErrorCode LoadSteps(NewtonSolver &ns, const LoadPath &path, PetscInt *total_cuts,
                         bool *collapsed) {
  Simulation &sim = *ns.sim;
  const Settings &s = sim.set;
  PetscFunctionBeginUser;
  double nominal = 1.0 / double(ns.load_steps);
  double t = 0; // the path parameter: the load factor in stage 0
  PetscInt cuts = 0;
  bool sized = ns.cell_fraction <= 0;
  *total_cuts = 0;
  *collapsed = false;
  while (t < 1.0 - 1e-12) {
    const double dl = nominal * std::ldexp(1.0, -static_cast<int>(cuts));
    const double target = std::fmin(1.0, t + dl);
    SNESConvergedReason reason;
    bool rejected;
    PetscCall(LoadStep(ns, path, t, target, !sized, false, &reason, &rejected));
    if (!sized && reason > 0) {
      sized = true;
      const double steps = std::ceil(ns.frac / (ns.cell_fraction * target) * (1 - 1e-12));
      nominal = std::fmin(nominal, 1.0 / std::fmax(steps, 1.0));
      if (!s.quiet)
        PetscCall(PetscPrintf(sim.comm,
                              "  -newton_cell_fraction %g: %.0f load steps (the first moved "
                              "%.3g cells per unit load)%s\n",
                              ns.cell_fraction, 1.0 / nominal, ns.frac / target,
                              rejected ? "; first step redone" : ""));
      cuts = 0;
      if (rejected) continue;
    }
    if (reason <= 0) {
      if (cuts >= ns.max_cuts) {
        PetscCall(Collapse(ns, path, t, target, reason, false));
        *collapsed = true;
        PetscFunctionReturn(0);
      }
      ++cuts;
      ++*total_cuts;
      ++ns.halvings;
      if (!s.quiet)
        PetscCall(PetscPrintf(sim.comm, "  load step to %.6g failed (%s): step halved to %.4g\n",
                              target, SNESConvergedReasons[reason],
                              nominal * std::ldexp(1.0, -static_cast<int>(cuts))));
      continue;
    }
    t = target;
    if (cuts > 0) --cuts; // back toward the nominal step after a cut
  }
  PetscFunctionReturn(0);
}

// Equilibrium steps on the reset grid at full load until relaxation's criterion holds (at most
// -newton_equilibrium_steps); one that fails ends the stage out of equilibrium (Collapse).
PetscErrorCode EquilibriumSteps(NewtonSolver &ns, const LoadPath &path, bool *collapsed) {
  Simulation &sim = *ns.sim;
  RunState &run = sim.run;
  const Settings &s = sim.set;
  PetscFunctionBeginUser;
  *collapsed = false;
  PetscCall(StaticResidual(sim, s.shape, &run.ratio));
  if (!s.quiet)
    PetscCall(PetscPrintf(sim.comm,
                          "  after the load steps: unbalanced-force ratio %.3e (-tol %g)\n",
                          run.ratio, s.tol));
  for (PetscInt k = 0; k < ns.max_equilibrium && !(run.ratio <= s.tol); ++k) {
    SNESConvergedReason reason;
    bool rejected;
    PetscCall(LoadStep(ns, path, 1.0, 1.0, false, true, &reason, &rejected));
    if (reason <= 0) {
      PetscCall(Collapse(ns, path, 1.0, 1.0, reason, true));
      *collapsed = true;
      PetscFunctionReturn(0);
    }
    PetscCall(StaticResidual(sim, s.shape, &run.ratio));
    if (!s.quiet)
      PetscCall(PetscPrintf(sim.comm,
                            "  equilibrium step %" PetscInt_FMT ": unbalanced-force ratio %.3e "
                            "(-tol %g)\n",
                            k + 1, run.ratio, s.tol));
  }
  PetscFunctionReturn(0);
}
} // namespace

// Equilibrium of the current stage by load steps (-newton_load_steps), then equilibrium steps at
// full load until the unbalanced-force ratio of relaxation (StaticResidual) is <= -tol; with
// moving supports, the force on them at the end (Simulation::support_force).
PetscErrorCode NewtonSolver::solve_stage(Simulation &sim) {
  NewtonSolver &ns = *this;
  RunState &run = sim.run;
  const Settings &s = sim.set;
  PetscFunctionBeginUser;
  sim.resume = false;
  run.stop_stage = false;
  run.converged = false;
  run.stage_step = 0;
  ns.t_stage = MPI_Wtime();
  LoadPath path;
  const char *what = "";
  PetscCall(StagePath(ns, path, &what));
  if (!s.quiet)
    PetscCall(PetscPrintf(sim.comm,
                          "pmpm %s: %" PetscInt_FMT " x %" PetscInt_FMT " cells, h = %g m, shape "
                          "%s, -solver newton: %" PetscInt_FMT " load steps, tolerance %g; stage "
                          "%d: %s%s\n",
                          s.scene.c_str(), sim.model.ncell[0], sim.model.ncell[1], s.h,
                          ShapeKindNames[(int)s.shape], ns.load_steps, s.tol, (int)sim.stage, what,
                          path.ramp_loads ? "" : " (stage fraction per step)"));
  if (path.release) PetscCall(ReleaseStart(ns));
  PetscInt cuts = 0;
  bool collapsed = false;
  PetscCall(LoadSteps(ns, path, &cuts, &collapsed));
  if (!collapsed) PetscCall(EquilibriumSteps(ns, path, &collapsed));
  if (!collapsed) {
    run.converged = run.ratio <= s.tol;
    run.stage_seconds = MPI_Wtime() - ns.t_stage;
    run.wall_seconds += run.stage_seconds;
    if (!s.quiet)
      PetscCall(PetscPrintf(sim.comm,
                            "%s: unbalanced-force ratio %.3e %s %g after %" PetscInt_FMT
                            " load steps (%" PetscInt_FMT " in all, %" PetscInt_FMT
                            " halved), %" PetscInt_FMT " Newton and %" PetscInt_FMT
                            " linear iterations (%.2f s)\n",
                            run.converged ? "converged" : "NOT converged", run.ratio,
                            run.converged ? "<=" : ">", s.tol, run.stage_step, ns.solved_steps,
                            cuts, ns.newton_its, ns.linear_its, run.stage_seconds));
  }
  PetscCall(SupportReaction(ns));
  PetscFunctionReturn(0);
}

std::unique_ptr<EquilibriumSolver> make_newton_solver() {
  return std::make_unique<NewtonSolver>();
}

} // namespace pmpm
