// Setup of a run: the common options, the scene, the materials, the grid and the particles.
#include "pmpm/util/options.hpp"
#include "pmpm/model/simulation.hpp"
#include "pmpm/materials/registry.hpp"
#include "pmpm/model/extrude.hpp"
#include "pmpm/model/prerun.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstring>

namespace pmpm {

namespace {

// The options blocks' groups, in -help's order (PetscOptionsObject: the block's, for the
// readers' macros). The run: scene, discretisation, step cap and output.
PetscErrorCode RunOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, Settings &s) {
  char scene[64] = "", dir[PETSC_MAX_PATH_LEN] = "";
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  const std::string scenes = SceneList();
  PetscCall(PetscOptionsString("-scene", ("Scene: " + scenes).c_str(), nullptr, scene, scene,
                               sizeof(scene), &set));
  PmpmCheckInput(set, comm, PETSC_ERR_USER_INPUT,
                 "No scene given: pass -options_file options/<scene>.opts or -scene NAME (%s)",
                 scenes.c_str());
  s.scene = scene;
  PetscCall(PmpmOptionsReal("-cell_size", "Cell size h (m), > 0", nullptr, s.h, &s.h, nullptr));
  PetscCall(PmpmOptionsInt("-ppc", "Particles per cell per direction, 1..8", nullptr, s.ppc, &s.ppc,
                           nullptr));
  PetscCall(PmpmOptionsEnum("-shape",
                            "Shape functions: mpm (linear), pmpm (uGIMP: blocks of fixed size) or "
                            "cpgimp (blocks stretched "
                            "with F's diagonal, up to one cell in half-size)",
                            nullptr, ShapeKindNames, (PetscEnum)s.shape, (PetscEnum *)&s.shape,
                            nullptr));
  PetscCall(PmpmOptionsReal("-cfl", "Time-step factor on h / max(c + |v|), 0 < F <= 1", nullptr,
                            s.cfl, &s.cfl, nullptr));
  PetscCall(
      PmpmOptionsInt("-max_steps", "Step cap, >= 1", nullptr, s.max_steps, &s.max_steps, nullptr));
  PetscCall(PetscOptionsString("-output_dir", "Output directory (default output/<scene>)", nullptr,
                               dir, dir, sizeof(dir), &set));
  PmpmCheckInput(!set || dir[0], comm, PETSC_ERR_USER_INPUT,
                 "-output_dir is empty: give a directory (default output/<scene>)");
  s.output_dir = set ? std::string(dir) : "output/" + s.scene;
  PetscBool quiet = s.quiet ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscOptionsBool("-quiet", "No progress lines", nullptr, quiet, &quiet, nullptr));
  s.quiet = quiet;
  PetscCall(PmpmOptionsInt("-output_every",
                           "Also write a particle time series every K steps (0: "
                           "final state only)",
                           nullptr, s.output_every, &s.output_every, nullptr));
  PetscFunctionReturn(0);
}

// The relaxation: convergence, damping, history, load ramp.
PetscErrorCode RelaxationOptions(PetscOptionItems *PetscOptionsObject, Settings &s) {
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PmpmOptionsReal("-tol", "Convergence: unbalanced-force ratio max|f|/mean|f_ext|, > 0",
                            nullptr, s.tol, &s.tol, nullptr));
  PetscCall(PmpmOptionsEnum("-damping",
                            "Dynamic-relaxation damping: kinetic (zero the velocities at each "
                            "peak of kinetic energy), local (Cundall), both, none, or fire "
                            "(velocities turned toward the force, zeroed when the forces' power "
                            "turns negative)",
                            nullptr, DampingNames, (PetscEnum)s.damping, (PetscEnum *)&s.damping,
                            nullptr));
  PetscCall(PmpmOptionsReal("-damping_alpha", "Local (Cundall) damping coefficient, 0 <= a < 1",
                            nullptr, s.damping_alpha, &s.damping_alpha, nullptr));
  PetscCall(PmpmOptionsReal("-fire_alpha",
                            "-damping fire: velocity mixing toward the force after a restart, "
                            "0 <= a < 1",
                            nullptr, s.fire_alpha, &s.fire_alpha, nullptr));
  PetscCall(PmpmOptionsReal("-fire_decay",
                            "-damping fire: factor on the mixing per step without a restart "
                            "(after -fire_delay steps), 0 < f <= 1",
                            nullptr, s.fire_decay, &s.fire_decay, nullptr));
  PetscCall(PmpmOptionsInt("-fire_delay",
                           "-damping fire: steps after a restart before the mixing decays, >= 0",
                           nullptr, s.fire_delay, &s.fire_delay, nullptr));
  char hist[PETSC_MAX_PATH_LEN] = "";
  PetscCall(PetscOptionsString("-relax_history",
                               "Write the relaxation's history (stage, step, unbalanced-force "
                               "ratio, kinetic energy, kinetic resets, node of the largest "
                               "unbalanced force) to this CSV file",
                               nullptr, hist, hist, sizeof(hist), &set));
  s.relax_history = set ? std::string(hist) : "";
  PetscCall(PmpmOptionsInt("-relax_history_every", "Steps between -relax_history rows, >= 1",
                           nullptr, s.relax_history_every, &s.relax_history_every, nullptr));
  PetscCall(PmpmOptionsInt("-ramp_steps", "Load ramp length in steps (0: full load at once)",
                           nullptr, s.ramp_steps, &s.ramp_steps, nullptr));
  PetscFunctionReturn(0);
}

// The method: transfers, inertia, gravity, dynamics, MUSL, F-bar.
PetscErrorCode MethodOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, Settings &s) {
  PetscBool set = PETSC_FALSE, dynamic = s.dynamic ? PETSC_TRUE : PETSC_FALSE,
            musl = s.musl ? PETSC_TRUE : PETSC_FALSE, fbar = s.fbar ? PETSC_TRUE : PETSC_FALSE;
  PetscInt ng = DIM;
  PetscFunctionBeginUser;
  PetscCall(PmpmOptionsReal("-pic", "PIC fraction of the particle velocity update, 0..1", nullptr,
                            s.pic, &s.pic, nullptr));
  PetscCall(PmpmOptionsEnum(
      "-transfer",
      "Particle-grid velocity transfer: flip (FLIP blended with -pic PIC) or "
      "apic (affine PIC: keeps angular momentum; -pic unused; not with -musl)",
      nullptr, TransferNames, (PetscEnum)s.transfer, (PetscEnum *)&s.transfer, nullptr));
  PetscCall(PmpmOptionsEnum("-inertia_scaling",
                            "Inertial density per material: none (given densities) or "
                            "wave_speed (equal wave speed in every material; loads unchanged)",
                            nullptr, InertiaScalingNames, (PetscEnum)s.inertia,
                            (PetscEnum *)&s.inertia, nullptr));
  PetscCall(PmpmOptionsRealArray("-gravity_dir", "Gravity direction (normalised), gx,gy", nullptr,
                                 s.gdir, &ng, &set));
  PmpmCheckInput(!set || ng == DIM, comm, PETSC_ERR_USER_INPUT,
                 "-gravity_dir needs %d components, got %" PetscInt_FMT, DIM, ng);
  PetscCall(PmpmOptionsReal("-progress_interval", "Seconds between progress lines", nullptr,
                            s.progress_seconds, &s.progress_seconds, nullptr));
  PetscCall(PetscOptionsBool("-dynamic", "Undamped dynamics: no damping, run to -max_steps",
                             nullptr, dynamic, &dynamic, nullptr));
  s.dynamic = dynamic;
  PetscCall(PetscOptionsBool("-musl",
                             "Modified update (MUSL): nodal velocities for the kinematics "
                             "are re-mapped from the updated particle momenta (false: USL)",
                             nullptr, musl, &musl, nullptr));
  s.musl = musl;
  PetscCall(PetscOptionsBool("-fbar",
                             "Anti-locking: each step's volume change averaged over the particles "
                             "of one body in one cell (F-bar)",
                             nullptr, fbar, &fbar, nullptr));
  s.fbar = fbar;
  PetscCall(PmpmOptionsEnum("-fbar_pressure",
                            "F-bar's internal force: particle (each particle's own pressure) or "
                            "cell (the volume-averaged pressure of its cell and body, conjugate "
                            "to the averaged volume change: B-bar; needed for dilatant flow)",
                            nullptr, FbarPressureNames, (PetscEnum)s.fbar_pressure,
                            (PetscEnum *)&s.fbar_pressure, nullptr));
  PmpmCheckInput(s.fbar || s.fbar_pressure == FbarPressure::Particle, comm, PETSC_ERR_USER_INPUT,
                 "-fbar_pressure cell acts on F-bar's groups: add -fbar, or set -fbar_pressure "
                 "particle to run without F-bar");
  PetscFunctionReturn(0);
}

// Checkpoint and restart; *restart_given: -restart was given (perhaps empty).
PetscErrorCode CheckpointOptions(PetscOptionItems *PetscOptionsObject, Settings &s,
                                 PetscBool *restart_given) {
  PetscBool &set = *restart_given;
  PetscFunctionBeginUser;
  PetscBool stage_end = s.checkpoint_stage_end ? PETSC_TRUE : PETSC_FALSE;
  char restart[PETSC_MAX_PATH_LEN] = "";
  PetscCall(PmpmOptionsInt("-checkpoint_every",
                           "Write the complete state to <output_dir>/checkpoint_<step>.h5 every "
                           "K steps, K >= 0 (0: never)",
                           nullptr, s.checkpoint_every, &s.checkpoint_every, nullptr));
  PetscCall(PetscOptionsBool("-checkpoint_at_stage_end",
                             "Write the complete state to <output_dir>/checkpoint_<step>.h5 after "
                             "every stage",
                             nullptr, stage_end, &stage_end, nullptr));
  s.checkpoint_stage_end = stage_end;
  PetscCall(PetscOptionsString("-restart",
                               "Resume from a checkpoint file (same options files as the run "
                               "that wrote it; any rank count)",
                               nullptr, restart, restart, sizeof(restart), &set));
  s.restart = set ? std::string(restart) : "";
  PetscFunctionReturn(0);
}

// The solver table's entry and the geometry.
PetscErrorCode SolverOptions(PetscOptionItems *PetscOptionsObject, Settings &s) {
  PetscFunctionBeginUser;
  PetscEnum solver = PetscEnum(0); // the table's index (the default: its first entry)
  for (size_t k = 0; k < Solvers().size(); ++k)
    if (s.solver == Solvers()[k].name) solver = PetscEnum(k);
  PetscCall(PmpmOptionsEnum("-solver", SolverHelp().c_str(), nullptr, SolverEnumNames(), solver,
                            &solver, nullptr));
  s.solver = Solvers()[(size_t)solver].name;
  PetscCall(PmpmOptionsEnum("-geometry",
                            "2D geometry: plane_strain, or axisymmetric (x the radius r >= 0, y "
                            "the axis; quantities per radian; relaxation only; chains are sheets "
                            "of revolution)",
                            nullptr, GeometryNames, (PetscEnum)s.geometry, (PetscEnum *)&s.geometry,
                            nullptr));
  PetscCall(PmpmOptionsInt("-dim",
                           "Dimension: 2 (the scene's plane) or 3 (the scene extruded along z "
                           "over -depth; relaxation only; extrude.hpp)",
                           nullptr, s.dim, &s.dim, nullptr));
  PetscCall(PmpmOptionsReal("-depth",
                            "-dim 3: the depth (m) the 2D scene is extruded over along z, a whole "
                            "number of cells (z faces: -bc_zmin, -bc_zmax)",
                            nullptr, s.depth, &s.depth, nullptr));
  PetscFunctionReturn(0);
}

// The values read, checked (after the block: -help lists every option first).
PetscErrorCode CheckSettings(MPI_Comm comm, Settings &s, PetscBool restart_given) {
  const PetscBool set = restart_given;
  PetscFunctionBeginUser;
  PmpmCheckInput(s.h > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-cell_size must be > 0 (got %g)", s.h);
  PmpmCheckInput(s.dim == 2 || s.dim == 3, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-dim must be 2 or 3 (got %" PetscInt_FMT ")", s.dim);
  if (!(s.h > 0)) s.h = 1; // -help without a cell size: the scenes' lengths in cells stay finite
  PmpmCheckInput(s.ppc >= 1 && s.ppc <= 8, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-ppc must be in 1..8 (got %" PetscInt_FMT ")", s.ppc);
  PmpmCheckInput(s.cfl > 0 && s.cfl <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-cfl must be in (0, 1] (got %g): above 1 the explicit step is unstable", s.cfl);
  PmpmCheckInput(s.max_steps >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-max_steps must be >= 1");
  PmpmCheckInput(s.tol > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-tol must be > 0 (got %g)", s.tol);
  PmpmCheckInput(s.damping_alpha >= 0 && s.damping_alpha < 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-damping_alpha must be in [0, 1) (got %g)", s.damping_alpha);
  PmpmCheckInput(s.fire_alpha >= 0 && s.fire_alpha < 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-fire_alpha must be in [0, 1) (got %g)", s.fire_alpha);
  PmpmCheckInput(s.fire_decay > 0 && s.fire_decay <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-fire_decay must be in (0, 1] (got %g)", s.fire_decay);
  PmpmCheckInput(s.fire_delay >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-fire_delay must be >= 0 (got %" PetscInt_FMT ")", s.fire_delay);
  PmpmCheckInput(s.relax_history_every >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-relax_history_every must be >= 1 (got %" PetscInt_FMT ")",
                 s.relax_history_every);
  PmpmCheckInput(s.ramp_steps >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-ramp_steps must be >= 0");
  PmpmCheckInput(s.pic >= 0 && s.pic <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-pic must be in [0, 1] (got %g)", s.pic);
  // MUSL's second P2G and its kinematics from the remapped velocity would need the affine term
  // and break the angular momentum argument of affine.hpp (positions would not move by v_p)
  PmpmCheckInput(
      !(s.musl && s.transfer == Transfer::Apic), comm, PETSC_ERR_SUP,
      "-transfer apic is not supported with -musl (use USL: -musl 0, or -transfer flip)");
  PmpmCheckInput(s.output_every >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-output_every must be >= 0");
  PmpmCheckInput(s.checkpoint_every >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-checkpoint_every must be >= 0 steps (got %" PetscInt_FMT "; 0: never)",
                 s.checkpoint_every);
  PmpmCheckInput(!set || !s.restart.empty(), comm, PETSC_ERR_USER_INPUT,
                 "-restart needs a checkpoint file (<output_dir>/checkpoint_<step>.h5)");
  PmpmCheckInput(s.progress_seconds >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-progress_interval must be >= 0 seconds (got %g)", s.progress_seconds);
  const double gn = std::hypot(s.gdir[0], s.gdir[1]);
  PmpmCheckInput(gn > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-gravity_dir must be non-zero");
  for (int d = 0; d < DIM; ++d) s.gdir[d] /= gn;
  if (s.dynamic) s.damping = Damping::None;
  PetscFunctionReturn(0);
}

PetscErrorCode SettingsFromOptions(MPI_Comm comm, Settings &s) {
  PetscBool restart_given = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "pmpm: quasi-static MPM (every scene)", nullptr);
  PetscCall(RunOptions(PetscOptionsObject, comm, s));
  PetscCall(RelaxationOptions(PetscOptionsObject, s));
  PetscCall(MethodOptions(PetscOptionsObject, comm, s));
  PetscCall(CheckpointOptions(PetscOptionsObject, s, &restart_given));
  PetscCall(SolverOptions(PetscOptionsObject, s));
  PetscOptionsEnd();
  PetscCall(CheckSettings(comm, s, restart_given));
  PetscFunctionReturn(0);
}

constexpr double kMaxUnitWeight = 1e12; // N/m^3 (gamma) and kg/m^3 (density)
// A material faster than this (sqrt(M / density), m/s; steel's P wave is 6e3 m/s) is a typo
// in -mat_<name>_E or its density: its time step would be absurdly small.
constexpr double kMaxWaveSpeed = 1e6;

} // namespace

// A material: its law (-mat_<name>_model, from the law table materials/registry.hpp), the options
// every material has, then its law's own; under -help every law's, so that all are listed.
PetscErrorCode MaterialFromOptions(MPI_Comm comm, const std::string &name, MaterialEntry &m) {
  const std::string prefix = "mat_" + name + "_";
  const std::vector<MaterialLaw> &laws = MaterialLaws();
  PetscEnum model = (PetscEnum)0;
  PetscBool hasE = PETSC_FALSE, hasnu = PETSC_FALSE;
  PetscFunctionBeginUser;
  m.name = name;
  m.density = 0;
  std::vector<std::unique_ptr<LawOptions>> law_options;
  for (const MaterialLaw &l : laws) law_options.push_back(l.options());
  const bool help = ListingHelp();
  PetscOptionsBegin(comm, prefix.c_str(), ("Material " + name).c_str(), nullptr);
  PetscCall(PmpmOptionsEnum("-model", "Constitutive model (the material laws: pmpm -help)", nullptr,
                            MaterialLawNames(), model, &model, nullptr));
  PetscCall(PmpmOptionsReal("-E", "Young's modulus (Pa), > 0", nullptr, m.el.E, &m.el.E, &hasE));
  PetscCall(
      PmpmOptionsReal("-nu", "Poisson's ratio, -1 < nu < 0.5", nullptr, m.el.nu, &m.el.nu, &hasnu));
  PetscCall(PmpmOptionsReal("-gamma", "Unit weight (N/m^3), the body force, >= 0", nullptr, m.gamma,
                            &m.gamma, nullptr));
  PetscCall(PmpmOptionsReal("-density",
                            "Inertial density (kg/m^3), > 0; ignored under "
                            "-inertia_scaling wave_speed",
                            nullptr, m.density, &m.density, nullptr));
  for (size_t k = 0; k < laws.size(); ++k)
    if (k == (size_t)model || help) PetscCall(law_options[k]->read(PetscOptionsObject));
  PetscOptionsEnd();
  PmpmCheckInput(hasE, comm, PETSC_ERR_USER_INPUT, "-%sE is required (Young's modulus in Pa)",
                 prefix.c_str());
  PmpmCheckInput(hasnu, comm, PETSC_ERR_USER_INPUT, "-%snu is required (Poisson's ratio)",
                 prefix.c_str());
  // Sane ranges: the stiffest solids are near 1e12 Pa, the landfill's scaled model loads its soil
  // with gamma = 1.5e9 N/m^3 (options/landfill.opts); beyond these a value is a typo, and it
  // would show only as a vanishing time step or an instability at step 1.
  PmpmCheckInput(m.el.E > 0 && m.el.E <= kMaxModulus, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%sE must be in (0, %g] Pa (got %g)", prefix.c_str(), kMaxModulus, m.el.E);
  PmpmCheckInput(m.el.nu > -1 && m.el.nu < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%snu must be in (-1, 0.5) (got %g)", prefix.c_str(), m.el.nu);
  PmpmCheckInput(m.gamma >= 0 && m.gamma <= kMaxUnitWeight, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%sgamma must be in [0, %g] N/m^3 (got %g)", prefix.c_str(), kMaxUnitWeight,
                 m.gamma);
  PmpmCheckInput(m.density >= 0 && m.density <= kMaxUnitWeight, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%sdensity must be in (0, %g] kg/m^3 (got %g)", prefix.c_str(), kMaxUnitWeight,
                 m.density);
  PetscCall(law_options[model]->make(comm, prefix, m.el, m.model));
  PetscFunctionReturn(0);
}

PetscErrorCode SimulationIndexParticles(Simulation &sim) {
  ParticleView P;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(sim.parts, P));
  for (auto &l : sim.mat_idx) l.clear();
  sim.traction_idx.clear();
  sim.iface_idx.clear();
  for (PetscInt p = 0; p < P.n; ++p) {
    if (P.colour[p] > 0.5) sim.iface_idx.push_back(p);
    sim.mat_idx[P.mat[p]].push_back(static_cast<int>(p));
    if (P.load[p] >= 0) sim.traction_idx.push_back(p);
  }
  sim.scratch.dudx.resize(static_cast<size_t>(P.n) * sim.parts.dim * sim.parts.dim);
  if (sim.set.geometry == Geometry::Axisymmetric)
    sim.scratch.hoop.resize(static_cast<size_t>(P.n) * 2);
  PetscCall(ParticlesRestoreView(sim.parts, P));
  PetscFunctionReturn(0);
}

namespace {
const char *const kFaceNames[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};

// Box-face boundary conditions: the scene's defaults, overridable per face.
PetscErrorCode BoundaryFromOptions(Simulation &sim) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(sim.comm, "bc_", "Boundary conditions per box face (defaults: the scene's)",
                    nullptr);
  for (int f = 0; f < 2 * DIM; ++f) {
    char opt[32], topt[32], help[160];
    snprintf(opt, sizeof(opt), "-%s", kFaceNames[f]);
    snprintf(topt, sizeof(topt), "-%s_traction", kFaceNames[f]);
    PetscCall(PmpmOptionsEnum(opt, "Face condition: free, roller (normal velocity 0), fixed",
                              nullptr, FaceBCNames, (PetscEnum)sim.model.face[f],
                              (PetscEnum *)&sim.model.face[f], nullptr));
    snprintf(help, sizeof(help),
             "Traction tx,ty (Pa) on the body's outermost particles toward the %s face "
             "(dead load, ramped with the loads; the face must be free)",
             kFaceNames[f]);
    PetscInt n = DIM;
    PetscBool set = PETSC_FALSE;
    PetscCall(PmpmOptionsRealArray(topt, help, nullptr, sim.model.face_traction[f], &n, &set));
    PmpmCheckInput(!set || n == DIM, sim.comm, PETSC_ERR_USER_INPUT,
                   "-bc_%s_traction needs %d components, got %" PetscInt_FMT, kFaceNames[f], DIM,
                   n);
  }
  for (int f = 2 * DIM; f < 6; ++f) { // -dim 3's z faces: conditions only
    char opt[32], help[160];
    snprintf(opt, sizeof(opt), "-%s", kFaceNames[f]);
    snprintf(help, sizeof(help),
             "-dim 3: the %s face's condition: free, roller (normal velocity 0; the default: "
             "plane strain), fixed",
             kFaceNames[f]);
    PetscCall(PmpmOptionsEnum(opt, help, nullptr, FaceBCNames, (PetscEnum)sim.model.face[f],
                              (PetscEnum *)&sim.model.face[f], nullptr));
  }
  PetscOptionsEnd();
  for (int f = 0; f < 2 * DIM; ++f)
    PmpmCheckInput(sim.model.face[f] == FaceBC::Free ||
                       (sim.model.face_traction[f][0] == 0 && sim.model.face_traction[f][1] == 0),
                   sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-bc_%s_traction needs -bc_%s free (a held face takes no traction)",
                   kFaceNames[f], kFaceNames[f]);
  PetscFunctionReturn(0);
}

} // namespace

// A face traction loads the particles whose blocks reach the body's extreme toward that face:
// force t * (the block's face length), applied at the block's face (tface, see p2g_traction).
PetscErrorCode ApplyFaceTractions(Simulation &sim, ParticleList &init) {
  PetscFunctionBeginUser;
  for (int f = 0; f < 2 * DIM; ++f) {
    const double *t = sim.model.face_traction[f];
    if (t[0] == 0 && t[1] == 0) continue;
    const int d = f / 2, o = 1 - d;
    const double sgn = f % 2 ? 1.0 : -1.0; // outward along d
    double ext = -1e300;
    for (const auto &q : init) ext = std::fmax(ext, sgn * (q.x[d] + sgn * q.lp[d]));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ext, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
    for (auto &q : init)
      if (sgn * (q.x[d] + sgn * q.lp[d]) > ext - 1e-9 * sim.set.h) {
        for (int e = 0; e < DIM; ++e) q.traction[e] += t[e] * 2.0 * q.lp[o];
        q.tface[d] = sgn * q.lp[d];
      }
  }
  PetscFunctionReturn(0);
}
// The surface loads as a table every rank holds alike: the loaded particles of every rank, in
// particle-id order (so the table does not depend on the rank count); each particle keeps its
// entry's index.
PetscErrorCode BuildLoadTable(Simulation &sim, ParticleList &init, MPI_Comm comm) {
  constexpr int W = 1 + 3 * DIM; // pid, traction, tface, lp
  std::vector<double> mine;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  for (const auto &q : init)
    if (q.traction[0] != 0.0 || q.traction[1] != 0.0) {
      mine.push_back(static_cast<double>(q.pid));
      for (int d = 0; d < DIM; ++d) mine.push_back(q.traction[d]);
      for (int d = 0; d < DIM; ++d) mine.push_back(q.tface[d]);
      for (int d = 0; d < DIM; ++d) mine.push_back(q.lp[d]);
    }
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(size), displs(size, 0);
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm));
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<double> all(static_cast<size_t>(displs.back() + counts.back()));
  PetscCallMPI(MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                              MPI_DOUBLE, comm));
  const size_t nl = all.size() / W;
  std::vector<size_t> order(nl);
  for (size_t k = 0; k < nl; ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return all[a * W] < all[b * W]; });
  sim.model.loads.resize(nl);
  std::vector<PetscInt> pids(nl);
  for (size_t k = 0; k < nl; ++k) {
    const double *r = &all[order[k] * W];
    pids[k] = static_cast<PetscInt>(r[0]);
    for (int d = 0; d < DIM; ++d) {
      sim.model.loads[k].traction[d] = r[1 + d];
      sim.model.loads[k].tface[d] = r[1 + DIM + d];
      sim.model.loads[k].lp[d] = r[1 + 2 * DIM + d];
    }
  }
  for (auto &q : init)
    if (q.traction[0] != 0.0 || q.traction[1] != 0.0)
      q.load = std::lower_bound(pids.begin(), pids.end(), q.pid) - pids.begin();
  PetscFunctionReturn(0);
}

void AssignBodies(const Simulation &sim, ParticleList &init) {
  for (auto &q : init) {
    int below = 0;
    for (const Chain &c : sim.chains) {
      const double *X = c.x.data();
      double y;
      if (q.x[0] <= X[0])
        y = X[1];
      else if (q.x[0] >= X[(c.n - 1) * DIM])
        y = X[(c.n - 1) * DIM + 1];
      else {
        int k = 0;
        while (X[(k + 1) * DIM] < q.x[0]) ++k;
        const double r = (q.x[0] - X[k * DIM]) / (X[(k + 1) * DIM] - X[k * DIM]);
        y = X[k * DIM + 1] + r * (X[(k + 1) * DIM + 1] - X[k * DIM + 1]);
      }
      below += q.x[1] > y;
    }
    q.body = 2 * below;
  }
}

namespace {
// The solver's options, what it cannot solve, its own objects; under -help every solver's
// options (the chosen one's first, then the table's order).
PetscErrorCode SolverSetup(Simulation &sim, bool help) {
  PetscFunctionBeginUser;
  PetscCall(sim.solver->setup(sim));
  for (const SolverEntry &e : Solvers())
    if (help && sim.set.solver != e.name) {
      std::unique_ptr<EquilibriumSolver> other = e.make();
      PetscCall(other->setup(sim));
      PetscCall(other->destroy());
    }
  PetscFunctionReturn(0);
}
// -help without a scene: the scenes and the material laws (the options of no scene follow).
PetscErrorCode ListScenesAndLaws(MPI_Comm comm) {
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(comm, "Scenes (-scene NAME; -scene NAME -help lists its options):\n"));
  for (const SceneEntry &e : Scenes())
    PetscCall(PetscPrintf(comm, "  %-10s %s\n", e.name, e.description));
  PetscCall(PetscPrintf(comm, "Material laws (-mat_<name>_model LAW):\n"));
  for (const MaterialLaw &l : MaterialLaws())
    PetscCall(PetscPrintf(comm, "  %-15s %s\n", l.name, l.description));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckFbarDilatancy(const Simulation &sim) {
  PetscFunctionBeginUser;
  // F-bar with the particles' own pressures is unstable under dilatant flow (the c-phi footing
  // heaves and flows at 0.8 of its capacity; README, "Anti-locking"): refused, not run.
  for (auto &m : sim.model.mats)
    PmpmCheckInput(
        !(sim.set.fbar && sim.set.fbar_pressure == FbarPressure::Particle && m.model->dilatant()),
        sim.comm, PETSC_ERR_USER_INPUT,
        "-fbar with the dilatant material %s (-mat_%s_dilation_angle > 0) needs "
        "-fbar_pressure cell: with each particle's own pressure F-bar is unstable under "
        "dilatant flow (docs/anti-locking.md)",
        m.name.c_str(), m.name.c_str());
  PetscFunctionReturn(0);
}

// *cmax: the fastest material's wave speed (at the given or default densities).
PetscErrorCode SetInertia(Simulation &sim, double *cmax) {
  PetscFunctionBeginUser;
  // Inertia: either the given densities, or one wave speed for all materials (the fastest
  // physical one), which equalises the relaxation rate of stiff and soft layers. Loads come from
  // gamma only, so the equilibrium is unchanged.
  for (auto &m : sim.model.mats) {
    if (sim.set.inertia == InertiaScaling::None) {
      PmpmCheckInput(m.density > 0, sim.comm, PETSC_ERR_USER_INPUT,
                     "-mat_%s_density is required (> 0) with -inertia_scaling none",
                     m.name.c_str());
    } else if (m.density <= 0) {
      m.density = m.gamma > 0 ? m.gamma / 9.81 : 1000.0;
    }
    const double c = std::sqrt(m.model->wave_modulus() / m.density);
    PmpmCheckInput(
        c <= kMaxWaveSpeed, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
        "-mat_%s_E %g Pa over the density %g kg/m^3 (-mat_%s_density, or -mat_%s_gamma / "
        "9.81) gives a wave speed of %g m/s, above %g m/s: the time step would be %g s "
        "(-cfl x -cell_size / wave speed); check -mat_%s_E and its density",
        m.name.c_str(), m.el.E, m.density, m.name.c_str(), m.name.c_str(), c, kMaxWaveSpeed,
        sim.set.cfl * sim.set.h / c, m.name.c_str());
    *cmax = std::fmax(*cmax, c);
  }
  sim.wave_modulus.clear();
  for (auto &m : sim.model.mats) {
    if (sim.set.inertia == InertiaScaling::WaveSpeed)
      m.density = m.model->wave_modulus() / (*cmax * *cmax);
    sim.wave_modulus.push_back(m.model->wave_modulus());
  }
  sim.mat_idx.assign(sim.model.mats.size(), {});
  PetscFunctionReturn(0);
}

// *type_set: -interface_type was given (the chains' faces default to it).
PetscErrorCode InterfaceFromOptions(Simulation &sim, PetscBool *type_set) {
  PetscFunctionBeginUser;
  // Interface between colour-1 particles and the rest (skipped entirely when bonded).
  PetscOptionsBegin(sim.comm, "interface_", "Interface of the colour-1 body (geomembrane)",
                    nullptr);
  PetscCall(PmpmOptionsEnum("-type",
                            "bonded (one velocity field), paper (Coulomb friction-slip of "
                            "section 3.2), contact (Bardenhagen multi-velocity friction); "
                            "for a chain, the default of -chain_<name>_interface (contact)",
                            nullptr, InterfaceTypeNames, (PetscEnum)sim.model.iface.type,
                            (PetscEnum *)&sim.model.iface.type, type_set));
  // each type's own normals unless asked otherwise: the paper's cells, Bardenhagen's gradient
  sim.model.iface.normals = sim.model.iface.type == InterfaceType::Contact
                                ? InterfaceNormals::Particles
                                : InterfaceNormals::Cells;
  PetscCall(PmpmOptionsEnum("-normals",
                            "cells (the paper's central differences of cell-average colour; "
                            "default of paper) or particles (sum of V c grad S over body 1; "
                            "default of contact)",
                            nullptr, InterfaceNormalsNames, (PetscEnum)sim.model.iface.normals,
                            (PetscEnum *)&sim.model.iface.normals, nullptr));
  PetscCall(PmpmOptionsReal("-mu_top", "Friction coefficient on the body's upper face, >= 0",
                            nullptr, sim.model.iface.mu_top, &sim.model.iface.mu_top, nullptr));
  PetscCall(PmpmOptionsReal("-mu_bottom", "Friction coefficient on the body's lower face, >= 0",
                            nullptr, sim.model.iface.mu_bottom, &sim.model.iface.mu_bottom,
                            nullptr));
  PetscCall(PmpmOptionsReal("-tail_share",
                            "Below this share of a node's mass a body takes the common "
                            "acceleration there and keeps its relative velocity, 0 <= s < 0.5",
                            nullptr, sim.model.iface.tail_share, &sim.model.iface.tail_share,
                            nullptr));
  PetscOptionsEnd();
  PetscCheck(sim.model.iface.tail_share >= 0 && sim.model.iface.tail_share < 0.5, sim.comm,
             PETSC_ERR_ARG_OUTOFRANGE, "-interface_tail_share must be in [0, 0.5) (got %g)",
             sim.model.iface.tail_share);
  PetscCheck(sim.model.iface.mu_top >= 0 && sim.model.iface.mu_bottom >= 0, sim.comm,
             PETSC_ERR_ARG_OUTOFRANGE, "-interface_mu_top and -interface_mu_bottom must be >= 0");
  PetscCheck(!(sim.set.musl && sim.model.iface.type != InterfaceType::Bonded), sim.comm,
             PETSC_ERR_SUP, "-musl is not supported with -interface_type %s (use USL: -musl 0)",
             InterfaceTypeNames[(int)sim.model.iface.type]);
  for (int d = 0; d < DIM; ++d) sim.model.iface.up[d] = -sim.set.gdir[d];
  for (int f = 0; f < 2 * DIM; ++f) sim.model.iface.face[f] = sim.model.face[f];
  PetscFunctionReturn(0);
}

// The chains' options and the chains made from the scene's specs (cmax: the continuum's fastest
// wave speed, for their inertia; under -help a chain's unchecked defaults may stop it).
PetscErrorCode ChainsFromOptions(Simulation &sim, PetscBool help, PetscBool type_set, double cmax) {
  PetscFunctionBeginUser;
  // Membrane chains: each a body between the material below and above it (chain.hpp).
  // chains follow -inertia_scaling unless told otherwise: a sheet given the continuum's wave
  // speed is heavy and nearly weightless, which relaxation does not mind but which floats off
  // its support in dynamics (incline: 98 of 114 contact nodes separated by step 100)
  PetscBool strain_projection = PETSC_TRUE;
  PetscBool chain_scaling = sim.set.inertia == InertiaScaling::WaveSpeed ? PETSC_TRUE : PETSC_FALSE;
  PetscOptionsBegin(sim.comm, nullptr, "Membrane chains: mass, strain, contact", nullptr);
  PetscCall(PetscOptionsBool("-chain_inertia_scaling",
                             "Set each chain's mass so its axial wave speed is the fastest "
                             "continuum material's, as -inertia_scaling wave_speed does for "
                             "materials (the load is unchanged); default: on under "
                             "-inertia_scaling wave_speed",
                             nullptr, chain_scaling, &chain_scaling, nullptr));
  PetscCall(PetscOptionsBool("-chain_strain_projection",
                             "Each chain segment's strain is the projection of the chord strains "
                             "on the grid's nodes (removes the cell-period strain a sheet bending "
                             "on the grid's interpolation carries); 0: each segment's chord strain",
                             nullptr, strain_projection, &strain_projection, nullptr));
  PetscCall(PmpmOptionsReal("-chain_tail_share",
                            "A sheet with less than this share of a node's mass and no body on "
                            "one side of it there (or only bodies below -interface_tail_share) "
                            "moves with the bodies at the node, 0 <= s < 0.5",
                            nullptr, sim.model.contact.chain_tail_share,
                            &sim.model.contact.chain_tail_share, nullptr));
  PetscCall(PmpmOptionsReal("-chain_pic",
                            "PIC fraction of the chains' point velocity update, 0..1 (default: "
                            "-pic)",
                            nullptr, sim.set.chain_pic, &sim.set.chain_pic, nullptr));
  PetscOptionsEnd();
  if (sim.set.chain_pic < 0) sim.set.chain_pic = sim.set.pic;
  PetscCheck(sim.set.chain_pic <= 1, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-chain_pic must be in [0, 1] (got %g)", sim.set.chain_pic);
  PetscCheck(sim.model.contact.chain_tail_share >= 0 && sim.model.contact.chain_tail_share < 0.5,
             sim.comm, PETSC_ERR_ARG_OUTOFRANGE, "-chain_tail_share must be in [0, 0.5) (got %g)",
             sim.model.contact.chain_tail_share);
  PetscCheck(sim.model.chain_spacing >= 0.05 && sim.model.chain_spacing <= 1, sim.comm,
             PETSC_ERR_ARG_OUTOFRANGE, "-chain_spacing must be in [0.05, 1] cells (got %g)",
             sim.model.chain_spacing);
  const int nchain = static_cast<int>(sim.model.chain_specs.size());
  PetscCheck(nchain <= 3, sim.comm, PETSC_ERR_SUP, "at most 3 chains per scene (got %d)", nchain);
  PetscCheck(!(sim.set.musl && nchain > 0), sim.comm, PETSC_ERR_SUP,
             "-musl is not supported with membrane chains (use USL: -musl 0)");
  const int nbody = nchain > 0 ? 2 * nchain + 1 : 1;
  sim.chains.resize(nchain);
  for (int k = 0; k < nchain; ++k) {
    Chain &c = sim.chains[k];
    c.body = 2 * k + 1;
    c.slot = nbody * GridDof::NDOF + k * ChainDof::NDOF;
    // faces default to the -interface_* options; a chain is in contact unless told otherwise
    const FaceType ft = type_set ? static_cast<FaceType>(sim.model.iface.type) : FaceType::Contact;
    c.top.type = c.bottom.type = ft;
    c.top.mu = sim.model.iface.mu_top;
    c.bottom.mu = sim.model.iface.mu_bottom;
    // -help: a chain's unchecked defaults may stop it; its options are listed up to there
    const PetscErrorCode chain_err =
        ChainCreate(sim.comm, sim.model.chain_specs[k], sim.model.chain_spacing * sim.set.h, c);
    if (help && chain_err) continue;
    PetscCall(chain_err);
    // inertia: the sheet's axial wave no faster than the continuum's (its load is unchanged)
    if (chain_scaling && cmax > 0) c.line_mass = c.law.J / (cmax * cmax);
    c.strain_projection = strain_projection;
    c.axisymmetric = sim.set.geometry == Geometry::Axisymmetric;
    PmpmCheckInput(
        !c.axisymmetric || (!c.law.plastic() && c.stiffness == StiffnessKind::PlaneStrain),
        sim.comm, PETSC_ERR_SUP,
        "-geometry axisymmetric: chain %s needs -mat_%s_law linear or tension_only "
        "(got %s) and -mat_%s_axial_stiffness plane_strain (the sheet's biaxial "
        "plane-stress law; chain.hpp)",
        c.name.c_str(), c.material.c_str(), MembraneLawNames[c.law.kind], c.material.c_str());
    c.grid_h = sim.set.h;
    for (int d = 0; d < DIM; ++d) {
      c.grid_origin[d] = sim.model.origin[d];
      c.grid_ncell[d] = sim.model.ncell[d];
    }
    chain_update_tension(c);
  }
  sim.model.contact.tail_share = sim.model.iface.tail_share;
  for (int f = 0; f < 2 * DIM; ++f) sim.model.contact.face[f] = sim.model.face[f];
  PetscFunctionReturn(0);
}

// The grid (its memory checked first), the particles the scene generates (balanced), their
// tractions, weights, bodies and loads (not under -help).
PetscErrorCode GridAndParticles(Simulation &sim, const MemoryCheck &mem, int nbody, int nchain) {
  PetscFunctionBeginUser;
  const bool iface = sim.model.iface.type != InterfaceType::Bonded && nchain == 0;
  PetscCall(CheckProcessGrid(sim, DIM, sim.model.ncell));
  PetscCall(CheckMemoryGrid(sim, mem, nbody * GridDof::NDOF + nchain * ChainDof::NDOF, iface));
  PetscCall(GridCreate(sim.comm, sim.set.h, sim.model.origin, sim.model.ncell, nbody,
                       nchain * ChainDof::NDOF, sim.grid));
  if (iface) PetscCall(InterfaceGridCreate(sim.grid, sim.iface_grid));
  sim.parts.affine = sim.set.transfer == Transfer::Apic;
  PetscCall(ParticlesCreate(sim.grid, sim.parts));
  ParticleList init;
  PetscCall(sim.scene->generate(sim, init));
  PetscCall(BalanceSetup(sim, init)); // may recreate the grid and generate init again
  PetscCall(CheckMemoryParticles(sim, mem, (PetscInt)init.size()));
  PetscCall(ApplyFaceTractions(sim, init));
  PetscCall(GeometryWeight(sim, init));
  if (nchain > 0) AssignBodies(sim, init);
  PetscCall(BuildLoadTable(sim, init, sim.comm));
  // The PMPM support spans at most two cells per direction: 0 < l <= h/2.
  for (const auto &q : init)
    for (int d = 0; d < DIM; ++d)
      PetscCheck(q.lp[d] > 0 && q.lp[d] <= 0.5 * sim.set.h * (1 + 1e-12), PETSC_COMM_SELF,
                 PETSC_ERR_PLIB, "particle %" PetscInt_FMT " half-size %g outside (0, h/2]", q.pid,
                 q.lp[d]);
  PetscCall(ParticlesAdd(sim.parts, init));
  PetscCall(SimulationIndexParticles(sim));
  PetscInt n;
  PetscCall(ParticlesGlobalCount(sim.parts, &n));
  sim.particles_setup = n;
  PetscCheck(n > 0 || nchain > 0, sim.comm, PETSC_ERR_USER_INPUT,
             "the scene produced no particles: check the geometry options against -cell_size");
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SimulationSetup(Simulation &sim) {
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(sim.comm, &sim.rank));
  PetscCallMPI(MPI_Comm_size(sim.comm, &sim.size));
  PetscCall(SettingsFromOptions(sim.comm, sim.set));
  sim.solver = make_solver(sim.set.solver); // the scene's setup may ask it what it supports
  PetscBool help = PETSC_FALSE; // -help lists the options and runs nothing: nothing to check
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (!help) PetscCall(CheckOutputDir(sim.comm, sim.set.output_dir));
  MemoryCheck mem;
  PetscCall(MemoryFromOptions(sim.comm, mem));
  sim.scene = make_scene(sim.set.scene);
  PetscCheck(sim.scene || (help && sim.set.scene.empty()), sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-scene %s is unknown; allowed: %s", sim.set.scene.c_str(), SceneList().c_str());
  if (!sim.scene) PetscCall(ListScenesAndLaws(sim.comm)); // -help without a scene
  PetscOptionsBegin(sim.comm, nullptr, "Membrane chains", nullptr);
  PetscCall(PmpmOptionsReal("-chain_spacing", "Chain point spacing in cells, 0.05..1", nullptr,
                            sim.model.chain_spacing, &sim.model.chain_spacing, nullptr));
  PetscOptionsEnd();
  if (sim.scene) PetscCall(sim.scene->setup(sim));
  PetscCall(BoundaryFromOptions(sim));
  PetscCall(GeometryCheck(sim));
  PetscCheck(!sim.model.mats.empty() || !sim.model.chain_specs.empty() || !sim.sheets.empty() ||
                 help,
             sim.comm, PETSC_ERR_PLIB, "scene defined no material");
  PetscCall(CheckFbarDilatancy(sim));

  double cmax = 0; // the fastest material's wave speed
  PetscCall(SetInertia(sim, &cmax));

  PetscBool type_set = PETSC_FALSE; // -interface_type given
  PetscCall(InterfaceFromOptions(sim, &type_set));

  PetscCall(ChainsFromOptions(sim, help, type_set, cmax));
  const int nchain = static_cast<int>(sim.chains.size());
  const int nbody = nchain > 0 ? 2 * nchain + 1 : 1;

  PetscCall(BalanceFromOptions(sim.comm, sim.balance));
  if (help) { // -help: the grid's and Newton's options need a grid, whatever box the scene's
    // (unchecked) defaults give; no particles
    for (int d = 0; d < DIM; ++d)
      sim.model.ncell[d] =
          std::min<PetscInt>(std::max<PetscInt>(sim.model.ncell[d], 4 * sim.size), 256);
    PetscCall(GridCreate(sim.comm, sim.set.h > 0 ? sim.set.h : 1.0, sim.model.origin,
                         sim.model.ncell, nbody, nchain * ChainDof::NDOF, sim.grid));
    PetscCall(SolverSetup(sim, true));
    PetscFunctionReturn(0);
  }
  PetscCall(ExtrusionCheck(sim));
  if (sim.set.dim == 3)
    PetscCall(ExtrudedGridAndParticles(sim, mem));
  else
    PetscCall(GridAndParticles(sim, mem, nbody, nchain));
  PetscCall(SolverSetup(sim, false));
  // Step 0: monitor() also sees the initial state, where scenes may set an initial velocity field.
  PetscCall(sim.scene->monitor(sim));
  PetscFunctionReturn(0);
}

PetscErrorCode SimulationDestroy(Simulation &sim) {
  PetscFunctionBeginUser;
  if (sim.solver) PetscCall(sim.solver->destroy());
  sim.solver.reset();
  PetscCall(ParticlesDestroy(sim.parts)); // the swarm holds a bare pointer to the DMDA
  PetscCall(InterfaceGridDestroy(sim.iface_grid));
  PetscCall(GridDestroy(sim.grid));
  PetscCall(GridDestroy(sim.grid3));
  PetscFunctionReturn(0);
}

} // namespace pmpm
