// Everything one run holds: settings from the options database, the grid, the particles, the
// materials, the loads and boundary conditions, the run's progress, and its equilibrium solver
// (solver.hpp, which holds the solver's own state).
#pragma once
#include "pmpm/core/affine.hpp"
#include "pmpm/model/balance.hpp"
#include "pmpm/contact/chain.hpp"
#include "pmpm/core/degradation.hpp"
#include "pmpm/model/design.hpp"
#include "pmpm/model/geometry.hpp"
#include "pmpm/core/grid.hpp"
#include "pmpm/contact/interface.hpp"
#include "pmpm/contact/sheet.hpp"
#include "pmpm/materials/material.hpp"
#include "pmpm/core/particles.hpp"
#include "pmpm/model/solver.hpp"
#include "pmpm/core/transfers.hpp"
#include <memory>
#include <string>
#include <vector>

namespace pmpm {

enum class Damping { None = 0, Local = 1, Kinetic = 2, Both = 3, Fire = 4 };
inline constexpr const char *DampingNames[] = {"none", "local",   "kinetic",  "both",
                                               "fire", "Damping", "DAMPING_", nullptr};
enum class InertiaScaling { None = 0, WaveSpeed = 1 };
inline constexpr const char *InertiaScalingNames[] = {"none", "wave_speed", "InertiaScaling",
                                                      "INERTIA_", nullptr};
// -fbar_pressure: the internal force's pressure under F-bar, the particle's own or its group's
enum class FbarPressure { Particle = 0, Cell = 1 };
inline constexpr const char *FbarPressureNames[] = {"particle", "cell", "FbarPressure",
                                                    "FBAR_PRESSURE_", nullptr};

// Options every scene accepts (the interface contract in docs/user-guide.md).
struct Settings {
  std::string scene;
  double h = 0;     // -cell_size
  PetscInt ppc = 2; // -ppc, particles per cell per direction
  ShapeKind shape = ShapeKind::UGIMP;
  double cfl = 0.5; // -cfl, 0 < F <= 1
  PetscInt max_steps = 200000;
  std::string output_dir;
  bool quiet = false;
  PetscInt output_every = 0;
  double tol = 1e-6;                  // -tol, unbalanced-force ratio for convergence
  Damping damping = Damping::Kinetic; // docs/benchmarks/run.md: 0.38x the steps of local damping
  double damping_alpha = 0.8;
  // -damping fire (relaxation.cpp): FIRE's mixing at a restart, its decay factor per step, and
  // the steps after a restart before it decays (Bitzek et al. 2006: 0.1, 0.99, 5)
  double fire_alpha = 0.1, fire_decay = 0.99;
  PetscInt fire_delay = 5;
  double chain_pic = -1; // -chain_pic: PIC fraction of the chains' points (< 0: -pic)
  // -relax_history FILE: every -relax_history_every steps one CSV row (stage, step, ratio, kinetic
  // energy, resets, the node of the largest unbalanced force): where and how a relaxation stalls
  std::string relax_history;
  PetscInt relax_history_every = 100;
  PetscInt ramp_steps = 0;
  double pic = 0.05; // a little PIC damps the FLIP velocity noise the grid cannot see
  Transfer transfer = Transfer::Flip; // -transfer apic: affine transfers (affine.hpp)
  InertiaScaling inertia = InertiaScaling::WaveSpeed;
  double gdir[DIM] = {0.0, -1.0};
  double gdir_z = 0.0; // -dim 3: gravity's z component (the incline's azimuth; 0: in the plane)
  double progress_seconds = 2.0;
  bool dynamic = false; // -dynamic: no damping, no convergence test (run max_steps)
  bool musl = false;    // -musl: recompute nodal velocities from updated particle momenta
  bool fbar = false;    // -fbar: cell-averaged volume change per step (antilock.hpp)
  FbarPressure fbar_pressure = FbarPressure::Particle; // -fbar_pressure (antilock.hpp)
  // checkpoint.hpp: write the state every K steps (0: never) and after every stage; resume
  PetscInt checkpoint_every = 0;
  bool checkpoint_stage_end = false;
  std::string restart;                       // -restart FILE (empty: a fresh run)
  std::string solver = "relaxation";         // -solver: a name of the solver table (solver.hpp)
  Geometry geometry = Geometry::PlaneStrain; // -geometry (geometry.hpp)
  // -dim 3: the 2D scene extruded over -depth along z (extrude.hpp); 2: plane strain as before
  PetscInt dim = 2;
  double depth = 0;
};

struct MaterialEntry {
  std::string name;
  std::unique_ptr<Material> model;
  ElasticConstants el;
  double gamma = 0;   // unit weight (N/m^3): the load
  double density = 0; // inertial density (kg/m^3), possibly scaled
};

// What a stage changes, for the solver's load path (newton.cpp): stage 0 applies the loads from
// zero; a shrinkage stage imposes an eigenstrain (Simulation::stage_shrink) at full load; a void
// removes particles; anything else (a pressure raised, a support moved) is `Other`.
enum class StageChange { Loads = 0, Shrink = 1, Void = 2, Other = 3 };
inline constexpr const char *StageChangeNames[] = {
    "the loads", "a shrinkage", "a void (particles removed)", "loads or supports", nullptr};

struct Simulation;

// A scene: named geometry, materials, boundary conditions and results (pTatin-style table).
class Scene {
public:
  virtual ~Scene() = default;
  // Read the scene's options; set the box (origin, ncell), face BCs and material names.
  virtual PetscErrorCode setup(Simulation &sim) = 0;
  // The particles whose centres lie in this rank's cells.
  virtual PetscErrorCode generate(Simulation &sim, ParticleList &out) = 0;
  // Scene-specific results, as "key": value pairs appended to the summary's results object.
  virtual PetscErrorCode results(Simulation &sim, std::string &json) = 0;
  // Called once before the first step (step 0: a scene may set initial velocities there) and
  // after every step (rank-collective); for scenes that record a time history.
  virtual PetscErrorCode monitor(Simulation &) { return 0; }
  // The design answers (design.hpp) of the state results() reported, and the allowable the
  // checked one is compared with; called after results. Default: no design answers.
  virtual PetscErrorCode design(Simulation &, DesignRecord &) { return 0; }
  virtual bool has_design() const { return false; } // known after setup
  // Extra files (profiles); called after results, rank-collective.
  virtual PetscErrorCode write_files(Simulation &) { return 0; }
  // Stages after stage 0 (the loads' equilibrium): how many, what each changes before it is
  // relaxed, and what is recorded after (rank-collective). Scenes without stages have none.
  virtual PetscInt stages() const { return 0; }
  virtual PetscErrorCode begin_stage(Simulation &, PetscInt) { return 0; }
  virtual PetscErrorCode end_stage(Simulation &, PetscInt) { return 0; }
  // What stage k changes (known after setup): stage 0 the loads; by default a later stage is
  // `Other`, which only relaxation can follow.
  virtual StageChange stage_change(PetscInt k) const {
    return k == 0 ? StageChange::Loads : StageChange::Other;
  }
  // -dim 3 (extrude.hpp): the scene runs extruded along z (its results read any dimension).
  virtual bool extrudes() const { return false; }
  // -dim 3: the scene's membrane chains become strips of 3D sheet (extrude.hpp) and its results
  // read them as sheets.
  virtual bool extrudes_chains() const { return false; }
  // -dim 3: whether an extruded particle centred at x (3 coordinates) is kept; a scene whose 3D
  // body is not a prism (the round column) drops the others. Default: every particle.
  virtual bool keeps_extruded(const double[3]) const { return true; }
  // -dim 3: the material of an extruded particle centred at x, given its plane particle's (a
  // zone bounded in z, or round in plan). Default: the plane's.
  virtual int extruded_material(const double[3], int mat) const { return mat; }
  // -dim 3: whether an extruded particle centred at x (3 coordinates) carries its plane
  // particle's surface load (a load that is round in plan: the circular footing). Default: yes.
  virtual bool extruded_loaded(const double[3]) const { return true; }
  // -dim 3: the height at z of a point at height y of the plane at x, and dy'/dy there in
  // *stretch (a scene whose surface rises along z: the cover's -cover_deck_grade_z stretches its
  // waste and lifts what lies on it). Default: the plane's height, no stretch.
  virtual double extruded_height(double /*x*/, double y, double /*z*/, double *stretch) const {
    *stretch = 1;
    return y;
  }
  // True when the later stages have no meaning any more (a footing that collapsed).
  virtual bool finished() const { return false; }
  // Checkpoint and restart (checkpoint.hpp): the scene's own state that changes during a run
  // (time histories, references, stage records) into and out of the checkpoint's /scene group,
  // with the helpers of checkpoint.hpp; rank-collective. Default: nothing to save. checkpoint_read
  // runs after setup and generate, and replaces what they and monitor's step 0 left.
  virtual PetscErrorCode checkpoint_write(Simulation &, PetscViewer) { return 0; }
  virtual PetscErrorCode checkpoint_read(Simulation &, PetscViewer) { return 0; }
};

// The scene table (src/scenes/registry.cpp): one entry per scene, in -help's order.
struct SceneEntry {
  const char *name;                 // -scene's value; the scene's options are -<name>_*
  std::unique_ptr<Scene> (*make)(); // the factory
  const char *description;          // one line: -help, docs/options.md
};
const std::vector<SceneEntry> &Scenes();
std::string SceneList();       // the names joined by ", " (error messages, help texts)
std::string ExtrudingScenes(); // those that run under -dim 3 (Scene::extrudes), likewise
// The scene of that name, or null.
std::unique_ptr<Scene> make_scene(const std::string &name);

struct RunState {
  PetscInt step = 0;       // steps over all stages
  PetscInt stage_step = 0; // steps of the current stage
  double time = 0;
  double dt = 0;
  double max_speed = 0;
  double ratio = 1e300; // unbalanced-force ratio
  double kinetic = 0;   // particle kinetic energy
  bool converged = false;
  double wall_seconds = 0;  // all stages
  double stage_seconds = 0; // the current stage
  PetscInt migrations = 0;
  double local_unbalanced = 0;               // this rank's largest nodal unbalanced force
  double local_unbalanced_at[3] = {0, 0, 0}; // and its node (x, y; z in 3D)
  bool stop_stage = false;   // set by a scene's monitor: end the stage unconverged (a collapse)
  bool all_converged = true; // every stage so far converged
  // Stages that ended at their step cap out of equilibrium (not a collapse the scene asked for,
  // nor a -dynamic run, which has no equilibrium to reach): no verdict from such a run.
  std::vector<int> capped_stages;

  // The checkpointed scalars (checkpoint.cpp, /run attributes): f(name, field) for each. A new
  // checkpointed field is one line here; capped_stages is an array of /run, the local_* and
  // stop_stage are rebuilt by the next step.
  template <class F> PetscErrorCode checkpoint_fields(F &&f) {
    PetscFunctionBeginUser;
    PetscCall(f("step", step));
    PetscCall(f("stage_step", stage_step));
    PetscCall(f("time", time));
    PetscCall(f("dt", dt));
    PetscCall(f("max_speed", max_speed));
    PetscCall(f("ratio", ratio));
    PetscCall(f("kinetic", kinetic));
    PetscCall(f("converged", converged));
    PetscCall(f("all_converged", all_converged));
    PetscCall(f("wall_seconds", wall_seconds));
    PetscCall(f("stage_seconds", stage_seconds));
    PetscCall(f("migrations", migrations));
    PetscFunctionReturn(0);
  }
};

// The step's work arrays: refilled every step, never read across steps (nor checkpointed).
struct Scratch {
  std::vector<double> dudx;       // L dt per particle (G2P's velocity gradient times dt)
  std::vector<double> hoop;       // -geometry axisymmetric: hoop increment and stretch (2 each)
  std::vector<int> fbar_group;    // -fbar: each particle's cell and body
  std::vector<double> fbar_sums;  // -fbar: volumes per group
  std::vector<double> fbar_shift; // -fbar: group pressure less the particle's
  std::vector<double> eigen;      // the step's eigenstrain increments (3 per particle)
  std::vector<double> chain_buf;  // the chains' points packed for their allreduce
  std::vector<int> sheet_tris;    // the 3D sheets' triangles this rank computes (sheets.cpp)
  std::vector<char> sheet_near;   // the 3D sheets' points whose blocks reach this rank's nodes
};

// What the scene and the options define, read once at setup and not changed by the run (a
// stage's change is the scene's, through its begin_stage): the box, its faces, the materials, the
// membranes' specs, the surface loads, the interface's and the chains' contact parameters and
// the degrading zone.
struct Model {
  double origin[DIM] = {0, 0};
  PetscInt ncell[DIM] = {0, 0};
  // XMIN XMAX YMIN YMAX, then ZMIN ZMAX for -dim 3 (rollers unless -bc_zmin/-bc_zmax say)
  FaceBC face[6] = {FaceBC::Free, FaceBC::Free,   FaceBC::Free,
                    FaceBC::Free, FaceBC::Roller, FaceBC::Roller};
  // Traction (Pa) on the body's outermost particles toward each box face (free faces only).
  double face_traction[2 * DIM][DIM] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
  std::vector<MaterialEntry> mats;
  std::vector<ChainSpec> chain_specs; // membranes as chains (chain.hpp), bottom to top
  double chain_spacing = 0.25;        // -chain_spacing: point spacing in cells
  InterfaceParams iface;              // -interface_type, -interface_mu_top/bottom
  ContactParams contact;              // stacked-body contact at chain nodes
  std::vector<ParticleLoad> loads;    // surface loads, every rank alike (particles.hpp)
  // -dim 3: the same entries extruded (traction times the z spacing, tface and lp in 3D)
  std::vector<ParticleLoadT<3>> loads3;
  Shrinkage shrink; // the degrading zone (degradation.hpp)
};

struct Simulation {
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscMPIInt rank = 0, size = 1;
  Settings set;
  std::unique_ptr<Scene> scene;

  Model model; // what the scene and the options define

  Grid grid; // the 2D grid (-dim 3: the one the scene generates its plane section on)
  // -dim 3: the 3D grid the step runs on (extrude.hpp)
  GridT<3> grid3;
  // The grid a D-dimensional step runs on.
  template <int D> GridT<D> &grid_of() {
    if constexpr (D == 3)
      return grid3;
    else
      return grid;
  }
  Balance balance; // -balance: the partition by particle counts (balance.hpp)
  Particles parts;
  InterfaceGrid iface_grid;         // body 1's field, only when an interface is on
  std::vector<PetscInt> iface_idx;  // body-1 (colour 1) particles (this rank)
  InterfaceStats iface_stats;       // last step's counts (global)
  double iface_impulse[2] = {0, 0}; // normal impulse over the run: compression, tension
  std::vector<Chain> chains;        // every rank holds every point
  std::vector<Sheet> sheets;        // -dim 3: sheets of a lattice (sheet.hpp), whole on every rank
  ContactStats contact_stats;       // last step's (global)
  double contact_impulse[2] = {0, 0};    // chain faces' normal impulse over the run: +, -
  std::vector<double> wave_modulus;      // per material
  std::vector<std::vector<int>> mat_idx; // particles of each material (this rank)
  std::vector<PetscInt> traction_idx;    // particles carrying a surface load (this rank)
  Scratch scratch;                       // the step's work arrays
  // The next Step sums the particles' elastic energy in G2P when its stress update is fused
  // there (relaxation's energy check; StepReport's g2p.has_elastic says whether it did).
  bool step_energy = false;
  // Supports inside the box (transfers.hpp): nodal dofs at an imposed velocity, set by a scene,
  // and the weighted force the body put on them at the last step (global).
  PrescribedVelocity prescribed;
  double support_force[DIM] = {0, 0};
  // Stages (stages.cpp): the current one (0: the initial state under the loads), and what the
  // scene's begin_stage set for it: a shrinkage of the degrading zone applied over stage_ramp
  // steps (degradation.hpp).
  PetscInt stage = 0, nstages = 0;
  PetscInt stage_ramp = 0;
  double stage_shrink = 0;
  RunState run;
  PetscInt particles_setup = 0; // particles the scene generated (a checkpoint must match)
  // -restart: the stage loop resumes at `stage`, inside it (after run.stage_step steps) when
  // resume_in_stage, else at its start (the checkpoint was written after the previous stage)
  bool resume = false, resume_in_stage = false;
  // -solver's object (solver.hpp): made with the settings, set up after the particles,
  // destroyed with the run
  std::unique_ptr<EquilibriumSolver> solver;

  // The checkpointed scalars of the run beside RunState's and Balance's (checkpoint.cpp, /run
  // attributes): f(name, field) for each, before the solver's own state ...
  template <class F> PetscErrorCode checkpoint_fields(F &&f) {
    PetscFunctionBeginUser;
    PetscCall(f("stage_ramp", stage_ramp));
    PetscCall(f("stage_shrink", stage_shrink));
    PetscCall(run.checkpoint_fields(f));
    PetscCall(balance.checkpoint_fields(f));
    PetscFunctionReturn(0);
  }
  // ... and after it.
  template <class F> PetscErrorCode checkpoint_totals(F &&f) {
    PetscFunctionBeginUser;
    PetscCall(f("iface_impulse_compression", iface_impulse[0]));
    PetscCall(f("iface_impulse_tension", iface_impulse[1]));
    PetscCall(f("contact_impulse_compression", contact_impulse[0]));
    PetscCall(f("contact_impulse_tension", contact_impulse[1]));
    PetscFunctionReturn(0);
  }
};

// Setup steps SimulationSetup and -dim 3's extrusion (extrude.cpp) share. The face tractions
// (-bc_*_traction) onto the particles at the body's extreme toward each loaded face (the extreme
// is reduced over sim.comm); the surface loads as a table every rank holds alike (sim.model.loads,
// in particle-id order, each particle keeping its entry's index), gathered over comm (a list every
// rank holds whole, as extrusion's plane: PETSC_COMM_SELF).
PetscErrorCode ApplyFaceTractions(Simulation &sim, ParticleList &init);
PetscErrorCode BuildLoadTable(Simulation &sim, ParticleList &init, MPI_Comm comm);

// Setup: options, scene, materials, grid, particles.
PetscErrorCode SimulationSetup(Simulation &sim);
PetscErrorCode SimulationDestroy(Simulation &sim);
// Rebuild the per-rank particle index lists (after a migration).
PetscErrorCode SimulationIndexParticles(Simulation &sim);
// Read a material's options (prefix -mat_<name>_) into an entry.
PetscErrorCode MaterialFromOptions(MPI_Comm comm, const std::string &name, MaterialEntry &m);

} // namespace pmpm
