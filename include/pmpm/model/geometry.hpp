// The 2D geometry of a run (-geometry): plane strain (the default) or axisymmetric.
//
// Axisymmetric (docs/method.md, section 9): x is the radius r >= 0, y the axis z, and every
// extensive quantity is per radian of the ring a particle sweeps about the axis. A scene's
// particles keep their plane-strain description (area A, unit weight, face tractions per unit
// length); the run multiplies each by the radius once, at setup (GeometryWeight):
//   volume  V = A r_p (so the mass rho A r_p and the weight gamma A r_p, both conserved),
//   face load t L r_f (r_f the loaded face's radius: exact for a face of constant r, and for a
//   face along r, whose centre r_p is the mean of r over it),
// and the kernels (transfers.cpp) add what the ring's hoop direction brings, per particle:
//   internal force, r component:  -V_p sigma_thth N_I(x_p) / r_p        (p2g)
//   hoop strain increment:         d_thth dt = dt sum_I v_rI N_I(x_p) / r_p  (g2p)
//   hoop stretch:                  F_thth = r_p / r_p0, volume V = det(F_2x2) F_thth V_0.
// The stress component plane strain keeps at zero strain (sigma_zz, index 2 of the stored stress)
// is the hoop stress sigma_thth, driven by that strain; the stored stress is (rr, zz, thth, rz).
//
// The axis: no particle is centred on it (the grid starts at r >= 0 and particles lie inside it,
// so r_p > 0 always; g2p stops a run whose particle reaches r <= 0), and the nodes on r = 0 hold
// v_r = 0: a free xmin face at r = 0 becomes a roller (GeometryCheck).
#pragma once
#include "pmpm/core/particles.hpp"
#include <petscsys.h>

namespace pmpm {

enum class Geometry { PlaneStrain = 0, Axisymmetric = 1 };
inline constexpr const char *GeometryNames[] = {"plane_strain", "axisymmetric", "Geometry",
                                                "GEOMETRY_", nullptr};

struct Simulation;

// After the scene's setup and the face options: what axisymmetric runs refuse (-solver newton,
// membrane chains, -fbar, a grid reaching r < 0), the roller on the axis, and the grid's flag that
// selects the kernels' axisymmetric variants. Nothing in plane strain.
PetscErrorCode GeometryCheck(Simulation &sim);

// The scene's particles weighted by their radius (axisymmetric only; see above): volume, and the
// surface loads by their face's radius. Before the load table is built and the particles are added.
PetscErrorCode GeometryWeight(const Simulation &sim, ParticleList &init);

} // namespace pmpm
