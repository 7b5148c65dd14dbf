// Waste degradation as an imposed volumetric shrinkage (an eigenstrain) of a zone of waste.
//
// Degrading waste loses volume; pmpm imposes that loss as an eigenstrain e* on the particles of
// the degrading materials inside a zone, and the stress sees the strain increment minus it
// (material.hpp, StressBatch::eigen), so plasticity and the cover's response follow. The mass
// (and so the load) is kept: the waste's own weight does not change as it shrinks.
//
// Two modes, for a volumetric shrinkage e_v of a particle:
//   vertical:  e*_yy = -e_v                (collapse of voids in the waste fabric)
//   isotropic: e*_xx = e*_yy = e*_zz = -e_v / 3
// Under uniaxial strain (a wide layer on rollers) with its weight unchanged, the vertical
// stress is unchanged, so the height ratio is exp(-e_v) for the vertical mode and
// exp(-(1 + nu) / (1 - nu) e_v / 3) for the isotropic one (rate form, logarithmic strain;
// tests/closed_forms.py uniaxial_strain_shrinkage; the lateral restraint turns the isotropic
// eigenstrain's lateral parts into vertical settlement through Poisson's effect).
//
// Grading: e_v at a particle = amount * gx(X) * gy(Y), from its initial position: gx is 1 over
// [x_lo, x_hi] and falls linearly to 0 over `taper` on either side; gy varies linearly from
// grade_bottom at y_lo to grade_top at y_hi (1 and 1: uniform).
#pragma once
#include "pmpm/core/particles.hpp"
#include <vector>

namespace pmpm {

enum class ShrinkMode { Vertical = 0, Isotropic = 1 };
inline constexpr const char *ShrinkModeNames[] = {"vertical", "isotropic", "ShrinkMode", "SHRINK_",
                                                  nullptr};

struct Shrinkage {
  ShrinkMode mode = ShrinkMode::Vertical;
  double x_lo = -1e300, x_hi = 1e300, taper = 0; // zone in x (m)
  double y_lo = -1e300, y_hi = 1e300;            // zone in y (m)
  double grade_bottom = 1, grade_top = 1;        // factors at y_lo and y_hi
  std::vector<char> degrades;                    // per material: 1 if it shrinks
  // 3D: a zone round in plan in place of the x range when radius > 0: full within radius of
  // (cx, cz), falling linearly to 0 over taper beyond it
  double cx = 0, cz = 0, radius = 0;
};

// The zone's grade (0..1 times the grading factors) at an initial position X.
double shrinkage_grade(const Shrinkage &s, const double X[DIM]);
// The same at a 3D initial position: the x range's (a prism along z), or a round zone's.
double shrinkage_grade3(const Shrinkage &s, const double X[3]);

// The eigenstrain increment of this step for every particle (3 per particle: xx, yy, zz) for a
// volumetric shrinkage `amount` of the zone at full grade. Returns this rank's power of the
// eigenstrain on the current stresses, sum_p V_p sigma_p : (-de*_p) (J/m; J in 3D), for the
// energy budget of the relaxation. D = 2, 3: the particles' layout (positions of D, NStress<D>
// stresses); in 3D the zone is a prism along z (graded by the initial x and y) or round in plan
// (shrinkage_grade3).
template <int D>
double shrinkage_increment(const ParticleView &P, const Shrinkage &s, double amount,
                           std::vector<double> &eigen);

} // namespace pmpm
