// Helpers shared by scenes: filling regions with regularly spaced particles, options checks and
// global reductions over particles.
#pragma once
#include "pmpm/model/simulation.hpp"
#include "pmpm/util/options.hpp"
#include <functional>

namespace pmpm {

// Which material (index) a point belongs to, or -1 for none.
using MaterialAt = std::function<int(const double x[DIM])>;

// ppc^DIM particles per cell at sub-cell centres, for the cells this rank owns, each assigned
// by `at`. Particle ids are rank-independent: (cell index * ppc^DIM + sub-index).
void FillRegular(const Simulation &sim, const MaterialAt &at, ParticleList &out);

// CheckCells (a length in whole cells): util/options.hpp.

// Uniaxial strain (1D columns): every particle's sigma_yy and u_y against exact functions of its
// initial height Y. Returns the volume-weighted relative L2 errors and, for each height in rows,
// the mean u_y (and its exact value) of the particles just below it (Y < row <= Y + l).
struct VerticalComparison {
  double stress_l2 = 0, displacement_l2 = 0;
  std::vector<double> row_u, row_u_exact;
};
PetscErrorCode CompareVertical(Simulation &sim, const std::function<double(double)> &sigma_yy,
                               const std::function<double(double)> &u_y,
                               const std::vector<double> &rows, VerticalComparison &out);

// Uniaxial strain: the exact volume ratio J = dy/dY under vertical stress sig (Pa, tension
// positive) for the material's law: exp(sig / M) for the hypoelastic Jaumann update, the root of
// lambda ln J + mu (J^2 - 1) = sig J for neo-Hookean (Newton from the hypoelastic value).
double UniaxialStrainJ(const MaterialEntry &m, double sig);

// Every rank's values concatenated on rank 0, in rank order (empty on the other ranks).
PetscErrorCode GatherToRoot(MPI_Comm comm, const std::vector<double> &mine,
                            std::vector<double> &all);

// Sum of values over all ranks.
PetscErrorCode SumAll(MPI_Comm comm, double *v, int n);

// The scenes' one membrane ("membrane", -mat_membrane_*): its thickness -membrane_thickness (m)
// read in its own options block titled `title`, and the check that it is > 0 (a scene whose
// membrane is optional checks it only when there is one).
PetscErrorCode MembraneThicknessOption(MPI_Comm comm, const char *title, double *t);
PetscErrorCode CheckMembraneThickness(MPI_Comm comm, double t);

} // namespace pmpm
