// The solver table: one line per equilibrium solver (name, factory, one-line description).
// -solver's help, its allowed values, the error for an unknown one and docs/options.md all come
// from it.
#include "pmpm/model/solver.hpp"

namespace pmpm {

std::unique_ptr<EquilibriumSolver> make_relaxation_solver();
std::unique_ptr<EquilibriumSolver> make_newton_solver();

const std::vector<SolverEntry> &Solvers() {
  static const std::vector<SolverEntry> solvers = {
      {"relaxation", make_relaxation_solver, "explicit dynamic relaxation"},
      {"newton", make_newton_solver,
       "implicit load steps on PETSc SNES; -newton_*, -snes_*, -ksp_*, -pc_* options"},
  };
  return solvers;
}

std::string SolverHelp() {
  const auto &t = Solvers();
  std::string s = "Equilibrium solver: ";
  for (size_t k = 0; k < t.size(); ++k) {
    if (k > 0) s += k + 1 == t.size() ? " or " : ", ";
    s += std::string(t[k].name) + " (" + t[k].description + ")";
  }
  return s;
}

const char *const *SolverEnumNames() {
  static const std::vector<const char *> names = [] {
    std::vector<const char *> v;
    for (const SolverEntry &e : Solvers()) v.push_back(e.name);
    v.insert(v.end(), {"Solver", "SOLVER_", nullptr});
    return v;
  }();
  return names.data();
}

std::unique_ptr<EquilibriumSolver> make_solver(const std::string &name) {
  for (const SolverEntry &e : Solvers())
    if (name == e.name) return e.make();
  return nullptr;
}

} // namespace pmpm
