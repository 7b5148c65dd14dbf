// Reading numbers from the options database, and the options files before PETSc reads them.
//
// PETSc's PetscOptionsReal/RealArray/Int take "inf", "nan" and overflowing values such as 1e400
// (which become inf), ignore values beyond an array's length, and refuse text that is not a number
// without naming the option ("Input string abc has no numeric value"). The wrappers below check
// the option's text first and refuse, naming the option and quoting its help (which states the
// allowed range): text that is not a number or not an integer, several values where one is read,
// more values than the array holds, a missing value, and every non-finite value. What they accept
// is then read by PETSc's own call (listed by -help, marked used), so valid values are read bit
// for bit as before.
#pragma once
#include <petscsys.h>
#include <string>

namespace pmpm {

PetscErrorCode OptionReal(PetscOptionItems *items, const char opt[], const char text[],
                          const char man[], PetscReal current, PetscReal *value, PetscBool *set);
PetscErrorCode OptionRealArray(PetscOptionItems *items, const char opt[], const char text[],
                               const char man[], PetscReal value[], PetscInt *n, PetscBool *set);
// An enum option's value must be one of its list's names (PETSc's own refusal is a generic
// PETSC_ERR_USER); the names are listed.
PetscErrorCode OptionEnum(PetscOptionItems *items, const char opt[], const char text[],
                          const char man[], const char *const *list, PetscEnum current,
                          PetscEnum *value, PetscBool *set);
PetscErrorCode OptionInt(PetscOptionItems *items, const char opt[], const char text[],
                         const char man[], PetscInt current, PetscInt *value, PetscBool *set);

// The options files named on the command line (-options_file F) and, through their own
// -options_file lines, the files they include, checked as PETSc would read them, before it does
// (PETSc's errors there come as a 17-line traceback from every rank, and a file that includes
// itself recurses until the stack overflows). Returns "" or the one-line reason, naming the file:
// missing or unreadable, a directory, -options_file without a file, a line that is not one option
// (and its value), an include cycle or includes nested deeper than 16.
std::string CheckOptionsFiles(int argc, char **argv);

// True under -help: the run lists every options block and runs nothing (PETSc's convention), so
// the checks of the values read are skipped (an incomplete scene's defaults need not be valid).
bool ListingHelp();

} // namespace pmpm

// A check of the input (as PetscCheck), skipped under -help (ListingHelp).
#define PmpmCheckInput(cond, comm, err, ...)                                                       \
  PetscCheck((cond) || pmpm::ListingHelp(), comm, err, __VA_ARGS__)

namespace pmpm { // A length must be a positive whole number of cells (so faces fall on grid lines).
PetscErrorCode CheckCells(MPI_Comm comm, const char *option, double length, double h,
                          PetscInt *cells);

} // namespace pmpm

// Inside a PetscOptionsBegin/End block, as PetscOptionsReal/RealArray/Int.
#define PmpmOptionsReal(a, b, c, d, e, f) pmpm::OptionReal(PetscOptionsObject, a, b, c, d, e, f)
#define PmpmOptionsRealArray(a, b, c, d, e, f)                                                     \
  pmpm::OptionRealArray(PetscOptionsObject, a, b, c, d, e, f)
#define PmpmOptionsInt(a, b, c, d, e, f) pmpm::OptionInt(PetscOptionsObject, a, b, c, d, e, f)
#define PmpmOptionsEnum(a, b, c, d, e, f, g)                                                       \
  pmpm::OptionEnum(PetscOptionsObject, a, b, c, d, e, f, g)
