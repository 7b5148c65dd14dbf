// The explicit step's phases (cycle.cpp) share one StepState; each optional physics (membrane
// chains, the colour interface, F-bar, an imposed eigenstrain, cpGIMP's support check) attaches
// to them as a StepHook, one file each in src/step/, listed in the order they run by StepHooks()
// (src/step/hooks.cpp). A hook's members run only in steps where it is active; a null member
// does nothing. Hooks run once per step, never per particle.
#pragma once
#include "pmpm/step/cycle.hpp"
#include "pmpm/util/log_event.hpp"
#include <cmath>
#include <vector>

namespace pmpm {

// The step's -log_view events (registered by LogRegister, cycle.cpp).
struct StepEvents {
  PetscLogEvent p2g = 0, l2g = 0, grid = 0, g2l = 0, g2p = 0, musl = 0, stress = 0, migrate = 0,
                iface = 0, chain = 0, contact = 0, fbar = 0, support = 0, sheet_share = 0,
                sheet_forces = 0; // inside Chain: the 3D sheets' allreduce and
                                  // triangles
};
extern StepEvents step_events;

// What the phases of one step share, in dimension D.
template <int D> struct StepStateT {
  Simulation &sim;
  const LoadT<D> &load;
  const double dt;
  StepReport &rep;
  GridStatsT<D> &grid_stats;        // rep.grid in 2D; the 3D step copies its own into rep
  G2PStatsT<D> &g2p_stats;          // rep.g2p in 2D; likewise
  ParticleView P;                   // this rank's particles, the whole step
  GridViewT<D> G;                   // the grid's global view during the grid update (phase 3)
  GridUpdateParamsT<D> gp;          // phase 3's parameters
  G2PParamsT<D> pp;                 // phase 5's parameters
  const double *pshift = nullptr;   // F-bar's group pressure for P2G's internal force, or null
  GridViewT<D> body;                // body 1's local view during G2P (the interface) ...
  const GridViewT<D> *G1 = nullptr; // ... which G2P reads through this, or null
  const double *eigen = nullptr; // the eigenstrain increment the stress update subtracts, or null
  StepStateT(Simulation &s, const LoadT<D> &l, double t, StepReport &r, GridStatsT<D> &gs,
             G2PStatsT<D> &ps)
      : sim(s), load(l), dt(t), rep(r), grid_stats(gs), g2p_stats(ps) {}
};
using StepState = StepStateT<DIM>;

// A hook's members for the phases 0-6 of a step in dimension D (null: nothing in that phase).
template <int D> struct HookPhasesT {
  PetscErrorCode (*before_p2g)(StepStateT<D> &);      // 0.
  PetscErrorCode (*p2g)(StepStateT<D> &);             // 1a, 1b: its own nodal values
  PetscErrorCode (*ghost_add)(StepStateT<D> &);       // 2: its grid's ghost sums (GhostAdd's event)
  PetscErrorCode (*after_ghost_add)(StepStateT<D> &); // 2b.
  PetscErrorCode (*grid_update)(StepStateT<D> &);     // 3a, 3b: after the nodal momentum balance
  PetscErrorCode (*ghost_scatter)(StepStateT<D> &);   // 4: its grid's ghosts (GhostScatter's event)
  PetscErrorCode (*before_g2p)(StepStateT<D> &);      // 5: what G2P reads (StepState::G1)
  PetscErrorCode (*after_g2p)(StepStateT<D> &);       // 5', 5a.
  PetscErrorCode (*stress)(StepStateT<D> &); // 6: before the materials (StressUpdate's event)
};

// An optional physics of the step. Its phases in 2D, and in 3D (-dim 3) where it has a 3D form: a
// hook active in a 3D step with a 2D member and no 3D one for a phase stops the run there.
struct StepHook {
  const char *name;
  bool (*active)(const Simulation &, const Load &);
  // reads or changes the velocity gradient between G2P and the stress update (the stress update
  // then cannot be fused into G2P's particle loop)
  bool reads_gradient;
  HookPhasesT<2> phases;  // 0-6 in 2D
  HookPhasesT<3> phases3; // 0-6 in 3D
  // after the phases, in both dimensions (the step's 2D state: its report and the simulation)
  PetscErrorCode (*reduce)(StepState &);     // 7: its share of the step's report
  PetscErrorCode (*after_step)(StepState &); // 8: after the migration
};
template <int D> const HookPhasesT<D> &Phases(const StepHook &h) {
  if constexpr (D == 3)
    return h.phases3;
  else
    return h.phases;
}

// Points that every rank holds (chains, sheets) into the step's report: their kinetic energy ke,
// wave speed c, largest squared speed v2 and load power pw, added once (on rank 0 for the power,
// which the budget sums over ranks).
inline void report_points(StepReport &rep, int rank, double ke, double c, double v2, double pw) {
  rep.g2p.kinetic += ke;
  rep.g2p.max_c = std::fmax(rep.g2p.max_c, c);
  rep.g2p.max_v = std::fmax(rep.g2p.max_v, std::sqrt(v2));
  rep.g2p.max_speed = rep.g2p.max_c + rep.g2p.max_v;
  if (rank == 0) rep.g2p.weight_power += pw;
}

// The stacked-body contact's counts and impulses of this step summed over ranks, with `per`
// (the chains' friction forces, or the 3D sheets' friction vectors) summed alongside; the run's
// record of them (sim.contact_stats, sim.contact_impulse) updated (src/step/chains.cpp).
PetscErrorCode ReduceContact(Simulation &sim, ContactStats &cs, std::vector<double> &per);

// The 3D sheets' forces and weight on the grid (src/step/sheets.cpp), for the static residual.
void p2g_sheets(const Simulation &sim, const LoadT<3> &load, const GridViewT<3> &G);

// Every hook, in the order the phases call them.
const std::vector<const StepHook *> &StepHooks();

// The hooks active in one step.
struct ActiveHooks {
  const StepHook *hook[8] = {};
  int n = 0;
  bool reads_gradient = false;
};
ActiveHooks ActiveStepHooks(const Simulation &sim, const Load &load);
// Call one of the after-phase members (reduce, after_step) of every active hook that has it, in
// order.
PetscErrorCode RunHooks(const ActiveHooks &h, PetscErrorCode (*StepHook::*member)(StepState &),
                        StepState &S);

} // namespace pmpm
