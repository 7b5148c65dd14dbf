// The equilibrium solver of every stage (the stage loop, stages.cpp, calls it once per stage):
// an abstract interface and the table of its implementations (src/solvers/registry.cpp), from
// which -solver's help, its allowed values and docs/options.md come. Explicit dynamic relaxation
// (relaxation.cpp) and Newton load steps on PETSc SNES (newton.cpp) are the two entries; each
// holds its own state (relaxation's damping and energy budget, Newton's SNES and counters).
#pragma once
#include <petscviewer.h>
#include <memory>
#include <string>
#include <vector>

namespace pmpm {

struct Simulation;

// What the rest of the code may ask of a solver instead of comparing names.
enum class SolverFeature {
  FrictionalFaces = 0, // chains with slipping or separating faces, frictional interfaces
  Axisymmetric = 1,    // -geometry axisymmetric (hoop terms in the residual, not the tangent)
};

class EquilibriumSolver {
public:
  virtual ~EquilibriumSolver() = default;
  virtual const char *name() const = 0;
  // Read the solver's options and refuse, with a one-line error, what it cannot solve; under
  // -help only list its options. Called once the scene, materials and particles are set up.
  // Collective.
  virtual PetscErrorCode setup(Simulation &sim) = 0;
  // Equilibrium of the current stage (Simulation::stage), or its step cap; sets RunState's
  // converged, ratio, stage_step and stage_seconds and honours Simulation::resume. Collective.
  virtual PetscErrorCode solve_stage(Simulation &sim) = 0;
  // The solver's members of summary.json ("key": value,\n  each), "" for none.
  virtual std::string report() const { return ""; }
  // Free what setup created. Collective.
  virtual PetscErrorCode destroy() { return 0; }
  virtual bool supports(SolverFeature) const = 0;
  // An option the solver reads after setup (the unused-option check, main.cpp, skips it).
  virtual bool reads_later(const char * /*option without its dash*/) const { return false; }
  // Its state in a checkpoint's group `group` (checkpoint.cpp), and back; `ranks`: the rank
  // count that wrote it. Collective.
  virtual PetscErrorCode checkpoint_write(Simulation &, PetscViewer, const char * /*group*/) {
    return 0;
  }
  virtual PetscErrorCode checkpoint_read(Simulation &, PetscViewer, const char * /*group*/,
                                         const std::string & /*file*/, PetscInt /*ranks*/) {
    return 0;
  }
};

// A scene whose later stages move supports (the nodal dofs of Simulation::prescribed, such as the
// trapdoor's door) implements this beside Scene: a displacement-driven solver (Newton) imposes
// the stage's support displacement over its load steps instead of the velocities relaxation
// integrates step by step. Collective where it takes a Simulation.
class SupportMotion {
public:
  virtual ~SupportMotion() = default;
  // Whether stage k (>= 1) changes nothing but the supports' positions.
  virtual bool moves_supports(PetscInt k) const = 0;
  // Stage k's displacement of every entry of Simulation::prescribed over the stage (m), called
  // after begin_stage; from then on the solver drives the supports (their velocities are zero and
  // the scene's monitor leaves them alone).
  virtual PetscErrorCode support_displacement(Simulation &, PetscInt k,
                                              std::vector<double> &du) = 0;
  // The share t in (0, 1] of the stage's displacement imposed so far (after each converged step).
  virtual PetscErrorCode supports_moved(Simulation &, double t) = 0;
};

// The solver table: one entry per solver, in -help's order (the first is the default).
struct SolverEntry {
  const char *name;                             // -solver's value
  std::unique_ptr<EquilibriumSolver> (*make)(); // the factory
  const char *description;                      // -solver's help, docs/options.md
};
const std::vector<SolverEntry> &Solvers();
// -solver's help: "Equilibrium solver: NAME (DESCRIPTION), ... or NAME (DESCRIPTION)".
std::string SolverHelp();
// The names in PETSc's enum layout (names, type name, prefix, null) for PmpmOptionsEnum.
const char *const *SolverEnumNames();
// The solver of that name, or null.
std::unique_ptr<EquilibriumSolver> make_solver(const std::string &name);

} // namespace pmpm
