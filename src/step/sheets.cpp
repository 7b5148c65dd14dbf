// 3D sheets (sheet.hpp) in the explicit step under -dim 3: their points' mass, momentum and
// forces into the grid's nodes, the points moved by the owner of their cell and shared by one
// allreduce, their forces from the new positions, and their share of the step's report. Points
// may be pinned, or held in some components (rollers: the extruded catenary's free edges). A
// sheet is alone on the grid for now (the sheet and extruded catenary scenes): it is the grid's
// only body; its contact with bodies on its faces (contact_stack3) is the next step of issue 23.
#include "pmpm/step/step_hooks.hpp"
#include <cmath>

namespace pmpm {

namespace {
using G3 = GridDofT<3>;
constexpr int NS = UGIMPShape::NS, NN = Weights<UGIMPShape, 3>::NN;

bool Active(const Simulation &sim, const Load &) {
  return !sim.sheets.empty();
}

// The cell holding x (may lie outside the box).
void CellOf(const GridViewT<3> &G, const double *x, PetscInt c[3]) {
  for (int d = 0; d < 3; ++d) c[d] = static_cast<PetscInt>(std::floor((x[d] - G.origin[d]) / G.h));
}

// Point i's uGIMP weights: a square patch of the sheet one cell wide in its tangent plane, thin
// across it (the chain's one-cell blocks, chain.cpp, with the axis extents of the patch), kept
// inside the box.
void PointWeights(const Sheet &s, int i, const GridViewT<3> &G, Weights<UGIMPShape, 3> &W) {
  const double *x = &s.x[3 * static_cast<size_t>(i)], *n = &s.nrm[3 * static_cast<size_t>(i)];
  double lp[3];
  for (int d = 0; d < 3; ++d) {
    const double lo = x[d] - G.origin[d], hi = G.origin[d] + G.ncell[d] * G.h - x[d];
    const double l = std::fmax(1e-3 * G.h, 0.5 * G.h * std::sqrt(std::fmax(0.0, 1 - n[d] * n[d])));
    lp[d] = std::fmax(1e-6 * G.h, std::fmin(l, std::fmin(lo, hi)));
  }
  weights<UGIMPShape, 3>(x, lp, G.origin, G.h, W);
}

// 1a. The points this rank owns (not pinned): mass, momentum, internal force and weight into the
//     grid's body block.
void P2GSheet(const Sheet &s, const LoadT<3> &load, const GridT<3> &g, const GridViewT<3> &G) {
  Weights<UGIMPShape, 3> W;
  for (int i = 0; i < s.n; ++i) {
    const double *x = &s.x[3 * static_cast<size_t>(i)];
    PetscInt c[3];
    CellOf(G, x, c);
    if (s.pinned[i] || !g.owns_cell(c)) continue;
    PointWeights(s, i, G, W);
    const double m = s.mass[i], wt = load.factor * s.weight[i];
    // a held component's forces meet its support's reaction: none reach the grid
    double fext[3], fint[3];
    for (int d = 0; d < 3; ++d) {
      const bool hold = !s.held.empty() && (s.held[i] >> d & 1);
      fext[d] = hold ? 0.0 : wt * load.gdir[d];
      fint[d] = hold ? 0.0 : s.f[3 * i + d];
    }
    for (int k = 0; k < NN; ++k) {
      const double w = W.w[k];
      if (w == 0.0) continue;
      double *nb = G.node(W.base[0] + k % NS, W.base[1] + (k / NS) % NS, W.base[2] + k / (NS * NS));
      nb[G3::M] += w * m;
      for (int d = 0; d < 3; ++d) {
        nb[G3::P + d] += w * m * s.v[3 * i + d];
        nb[G3::F + d] += w * (fint[d] + fext[d]);
        nb[G3::FEXT + d] += w * fext[d];
      }
    }
  }
}

PetscErrorCode ParticlesToGrid(StepStateT<3> &S) {
  GridT<3> &g = S.sim.grid3;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.chain);
  PetscCall(GridWithLocal(g, false, [&](const GridViewT<3> &G) {
    for (const Sheet &s : S.sim.sheets) P2GSheet(s, S.load, g, G);
  }));
  PetscFunctionReturn(0);
}

// 5a. The owner of each point's cell moves it (the grid's velocity and acceleration at the point,
//     FLIP / PIC as the chains', -chain_pic); buf gets x, v and 1 for the points it owns, zeros
//     for the others.
void G2PSheet(const Sheet &s, const GridT<3> &g, const GridViewT<3> &G, double dt, double pic,
              std::vector<double> &buf) {
  Weights<UGIMPShape, 3> W;
  buf.assign(7 * static_cast<size_t>(s.n), 0.0);
  for (int i = 0; i < s.n; ++i) {
    const double *x = &s.x[3 * static_cast<size_t>(i)], *v = &s.v[3 * static_cast<size_t>(i)];
    PetscInt c[3];
    CellOf(G, x, c);
    if (!g.owns_cell(c)) continue;
    double *out = &buf[7 * static_cast<size_t>(i)];
    out[6] = 1.0;
    if (s.pinned[i]) {
      for (int d = 0; d < 3; ++d) out[d] = x[d];
      continue;
    }
    PointWeights(s, i, G, W);
    double vg[3] = {0, 0, 0}, ag[3] = {0, 0, 0};
    for (int k = 0; k < NN; ++k) {
      const double w = W.w[k];
      if (w == 0.0) continue;
      const double *nb =
          G.node(W.base[0] + k % NS, W.base[1] + (k / NS) % NS, W.base[2] + k / (NS * NS));
      for (int d = 0; d < 3; ++d) {
        vg[d] += w * nb[G3::P + d];
        ag[d] += w * nb[G3::F + d];
      }
    }
    for (int d = 0; d < 3; ++d) {
      out[d] = x[d] + dt * vg[d];
      out[3 + d] = (1.0 - pic) * (v[d] + dt * ag[d]) + pic * vg[d];
      if (!s.held.empty() && (s.held[i] >> d & 1)) { // a roller: this component stays
        out[d] = x[d];
        out[3 + d] = 0.0;
      }
    }
  }
}

PetscErrorCode GridToPoints(StepStateT<3> &S) {
  Simulation &sim = S.sim;
  GridT<3> &g = sim.grid3;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.chain);
  const double pic = sim.set.chain_pic < 0 ? S.pp.pic : sim.set.chain_pic;
  std::vector<double> &buf = sim.scratch.chain_buf;
  for (Sheet &s : sim.sheets) {
    PetscCall(
        GridWithLocal(g, false, [&](const GridViewT<3> &G) { G2PSheet(s, g, G, S.dt, pic, buf); }));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE,
                               MPI_SUM, sim.comm));
    int owners = 0;
    for (int i = 0; i < s.n; ++i) {
      const double *b = &buf[7 * static_cast<size_t>(i)];
      owners += b[6] == 1.0;
      for (int d = 0; d < 3; ++d) {
        s.x[3 * i + d] = b[d];
        s.v[3 * i + d] = b[3 + d];
      }
      PetscCheck(std::isfinite(b[0] + b[1] + b[2] + b[3] + b[4] + b[5]), sim.comm,
                 PETSC_ERR_NOT_CONVERGED,
                 "Instability at step %" PetscInt_FMT ": sheet point %d (initially at (%g, %g, %g) "
                 "m) has a non-finite position or velocity. Reduce -cfl (now %g) or raise "
                 "-damping_alpha.",
                 sim.run.step, i, s.x0[3 * i], s.x0[3 * i + 1], s.x0[3 * i + 2], sim.set.cfl);
    }
    PetscCheck(owners == s.n, sim.comm, PETSC_ERR_NOT_CONVERGED,
               "Instability at step %" PetscInt_FMT ": the sheet has %d of its %d points off the "
               "grid. Enlarge the grid or reduce -cfl (now %g).",
               sim.run.step, s.n - owners, s.n, sim.set.cfl);
    sheet_update_forces(s);
    sheet_normals(s);
  }
  PetscFunctionReturn(0);
}

// 7. Their kinetic energy, speeds and load power from the points every rank holds (added once).
PetscErrorCode Reductions(StepState &S) {
  Simulation &sim = S.sim;
  StepReport &rep = S.rep;
  PetscFunctionBeginUser;
  double ke = 0, v2 = 0, c = 0, pw = 0;
  const double gz = sim.set.gdir_z;
  for (const Sheet &s : sim.sheets) {
    c = std::fmax(c, s.wave_speed());
    for (int i = 0; i < s.n; ++i) {
      const double *v = &s.v[3 * static_cast<size_t>(i)];
      const double s2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      ke += 0.5 * s.mass[i] * s2;
      v2 = std::fmax(v2, s2);
      // at full weight: the budget multiplies by the load factor (relaxation.cpp, LoadWork)
      pw += s.weight[i] * (S.load.gdir[0] * v[0] + S.load.gdir[1] * v[1] + gz * v[2]);
    }
  }
  report_points(rep, sim.rank, ke, c, v2, pw);
  PetscFunctionReturn(0);
}
} // namespace

// The sheets' forces and weight on the 3D grid, for the static residual (cycle.cpp).
void p2g_sheets(const Simulation &sim, const LoadT<3> &load, const GridViewT<3> &G) {
  for (const Sheet &s : sim.sheets) P2GSheet(s, load, sim.grid3, G);
}

extern const StepHook sheet_hook = [] {
  StepHook h{};
  h.name = "sheets";
  h.active = Active;
  h.phases3.p2g = ParticlesToGrid;
  h.phases3.after_g2p = GridToPoints;
  h.reduce = Reductions;
  return h;
}();

} // namespace pmpm
