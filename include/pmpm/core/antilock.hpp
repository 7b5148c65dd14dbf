// Anti-locking for plastic flow: F-bar, the volume change of a step averaged over each cell.
//
// Linear cells with four particles each carry four volume constraints per cell when the flow is
// isochoric (von Mises, Drucker-Prager at psi = 0); the mesh cannot deform without changing volume
// and locks: collapse loads overshoot (the strip footing, docs/method.md, section 2.6) and a thin
// cover layer bridges a void it should fall into. F-bar (de Souza Neto et al. 1996; for MPM, Coombs
// et al. 2018) replaces each particle's volume change over the step by its cell's:
//
//     dJ_bar = sum_p vol_p(new) / sum_p vol_p(old)    over the particles of one body in one cell
//     dF_bar = (dJ_bar / dJ_p)^(1/D) dF_p             (in D dimensions det scales with the D-th
//     power)
//
// so the increment's deviatoric part stays the particle's own and the volume is shared. The
// groups are the cells the particles sat in at the start of the step (all on the rank that owns
// the cell, so the average needs no communication) and one group per body: bodies on either side
// of a membrane chain share cells and must not share volume changes.
//
// The internal force -sum_p V_p sigma_p : grad S_ip still uses each particle's own pressure, so
// its power differs from the stress power by sum_p V_p (p_p - p_bar)(tr D_p - tr D_bar) over a
// group: nothing when the group's pressures agree (elastic and isochoric flow keep them equal),
// a source of energy when a dilatant return map sets them apart. The strip footing on c-phi soil
// with psi = phi heaves and flows at 0.8 of its capacity that way. -fbar_pressure cell replaces
// p_p by the group's volume-averaged p_bar in the force (B-bar's force, de Souza Neto et al.
// 2008, 15.3): the power is then exactly sum_p V_p s_p : D_p + p_bar sum_p V_p tr D_p, the
// stress power of the averaged volume change. It is not the default: on the slope cover
// (options/cover_slope.opts, psi = 0) it lets the thin cover creep at its surface and the
// geostatic stage ends its 30,000 steps at a ratio of 1e-2 (docs/anti-locking.md).
#pragma once
#include "pmpm/core/particles.hpp"
#include <vector>

namespace pmpm {

// In 3D (-dim 3) the exponent is 1/3, so the averaged volume change is shared by the three
// directions: an extruded plane-strain body under F-bar then takes a small out-of-plane strain
// its 2D run (exponent 1/2, in-plane only) does not, and the two differ within the discretisation
// error (the extruded strip footing: tests/test_dim3.py).

// The group of each particle at the start of the step: cell (i, j[, k]) among this rank's owned
// cells [lo, hi) and body b give (((k - lo2) * ny + (j - lo1)) * nx + (i - lo0)) * nbody + b; -1
// outside.
template <int D>
void fbar_groups(const ParticleView &P, const double origin[D], double h, const PetscInt lo[D],
                 const PetscInt hi[D], int nbody, std::vector<int> &group);

// Replace each particle's step increment dudx (L dt, D x D per particle) and its F and volume
// by the F-bar ones of its group. sums: scratch of 2 per group. Returns the largest
// |dJ_bar / dJ_p - 1| (how much the average changed a particle's volume step).
// hoop (-geometry axisymmetric, 2D: the hoop increment and stretch, 2 per particle): a step's
// volume ratio is then det(I + L dt) (1 + d_thth dt), and the in-plane increment and F take the
// whole correction (exponent 1/2): the hoop stretch is r / r0, the particle's position, which
// no average may change; the volumes are per radian, so the group's average is radius-weighted.
template <int D>
double fbar_apply(const ParticleView &P, const std::vector<int> &group, std::vector<double> &sums,
                  double *dudx, const double *hoop = nullptr);

// The internal force's pressure conjugate to F-bar's volume change: shift[p] = p_bar - p_p, with
// p_bar the volume average of p = tr(sigma) / 3 over the particle's group (0 outside a group).
template <int D>
void fbar_pressure_shift(const ParticleView &P, const std::vector<int> &group,
                         std::vector<double> &sums, std::vector<double> &shift);

} // namespace pmpm
