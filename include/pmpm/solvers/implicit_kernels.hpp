// The kernels of the implicit (Newton) solver, plain functions over particle arrays and ghosted
// nodal arrays of DIM values per node; newton.cpp wraps them in PETSc's SNES.
//
// One load step is updated-Lagrangian on a grid that moves with the body during the step (the
// finite-element view of implicit MPM, Guilkey and Weiss 2003, Charlton et al. 2017): particles
// keep the weights S_i and gradients grad S_i of their positions x^n at the step's start, and the
// unknown is the nodal displacement increment du. Per particle
//   G = sum_i du_i (x) grad S_i           (increment gradient w.r.t. x^n)
//   f = I + G,  J = det f,  F = f F^n     (the explicit step's F <- (I + L dt) F)
//   G_m = (I + G/2)^-1 G                  (the gradient over the step's midpoint configuration)
//   sigma' = the material's update with dudx = G_m and F (evaluated on copies, committed only
//            after the step converged; G_m makes the rate-form update second order in the step)
//   P = J sigma' f^-T                     (first Piola stress relative to the step's start)
// and the internal force is f_int,i = sum_p V_p^n P_p grad S_i(x_p^n): exactly the Cauchy
// force sum_p V_p sigma_p grad_x S_i on the moved grid. At du = 0 it is the explicit P2G's
// internal force, so equilibrium at the start of a step is relaxation's equilibrium.
#pragma once
#include "pmpm/materials/material.hpp"
#include "pmpm/core/particles.hpp"
#include "pmpm/core/shape.hpp"

namespace pmpm {

// Ghosted nodal array with D values per node (a DMDA of D dofs), node (i, j) in global indices at
// data[((j - gs[1]) * gm[0] + (i - gs[0])) * D], in 3D node (i, j, k) at
// data[(((k - gs[2]) * gm[1] + (j - gs[1])) * gm[0] + (i - gs[0])) * D].
template <int D> struct NodalViewT {
  double h = 0;
  double origin[D] = {};
  PetscInt gs[D] = {}, gm[D] = {};
  double *data = nullptr;
  double *node(PetscInt i, PetscInt j) const {
    static_assert(D == 2, "node(i, j) is 2D");
    return data + ((j - gs[1]) * gm[0] + (i - gs[0])) * D;
  }
  double *node(PetscInt i, PetscInt j, PetscInt k) const {
    static_assert(D == 3, "node(i, j, k) is 3D");
    return data + (((k - gs[2]) * gm[1] + (j - gs[1])) * gm[0] + (i - gs[0])) * D;
  }
  // node k of a particle's weights (Weights' order: x fastest)
  template <class Shape> double *node(const Weights<Shape, D> &W, int k) const {
    constexpr int NS = Shape::NS;
    if constexpr (D == 2)
      return node(W.base[0] + k % NS, W.base[1] + k / NS);
    else
      return node(W.base[0] + k % NS, W.base[1] + (k / NS) % NS, W.base[2] + k / (NS * NS));
  }
};
using NodalView = NodalViewT<DIM>;

// G_p = sum_i (mask_i du_i) (x) grad S_i(x_p), row-major (G[a * D + j] = d du_a / d x_j);
// mask is 1 on free dofs and 0 on held or unsupported ones (their du does not deform anything).
// With up, also the particles' increments u_p = sum_i S_i(x_p) mask_i du_i (D values each).
// D = 2 or 3, as the kernels below that take a D.
template <class Shape, int D = DIM>
void implicit_gradient(const ParticleView &P, const NodalViewT<D> &U, const NodalViewT<D> &mask,
                       double *G, double *up = nullptr);

// Trial kinematics for the material batch: F_new = (I + G) F^n per particle. These three work
// per particle in D = 2 or 3 dimensions (G, F, P: D x D row-major; stresses NStress<D>).
template <int D = DIM>
void implicit_deformation(PetscInt n, const double *G, const double *F, double *Fnew);

// The midpoint increment gradient Gm = (I + G/2)^-1 G = G (I + G/2)^-1 per particle: the gradient
// of du with respect to the step's midpoint configuration x^n + du/2 (Hughes and Winget 1980).
template <int D = DIM> void implicit_midpoint_gradient(PetscInt n, const double *G, double *Gm);

// P = J sigma' f^-T (D x D, row-major; in 2D the in-plane block) from G and the trial Cauchy
// stress.
template <int D = DIM>
void implicit_piola(PetscInt n, const double *G, const double *stress, double *Pk);

// R_i += V_p^n P_p grad S_i(x_p) (into the ghosted view; sum the ghosts across ranks after).
template <class Shape, int D = DIM>
void implicit_internal_force(const ParticleView &P, const double *Pk, const NodalViewT<D> &R);

// Equilibrium steps at full load solve on the reset grid, where relaxation's criterion is checked
// (newton.cpp): the particles' trial positions x' = x^n + u_p move across the fixed grid, and
//   R_i = sum_p [V^n J sigma'_p grad S_i(x'_p) - lambda w_p g (S_i(x'_p) - S_i(x^n_p))]
//         - lambda f_ext,i
// (w_p the particle's weight, g the gravity direction, f_ext at x^n; tractions and chains stay at
// x^n). Its tangent is the moved grid's plus, linearized at x^n (particle_reset_stiffness),
//   dR_ia / du_mc += sum_p V^n J sigma'_ab (d2S_i/dx_b dx_c S_m + dS_i/dx_c dS_m/dx_b)
//                    - lambda w_p g_a dS_i/dx_c S_m:
// the quadrature moving over the grid, of the order of |sigma| / E of the material stiffness.
// Without it the equilibrium steps converge by a fixed factor (0.22 on the seed landfill, whose
// soft zone carries a stress of that order of its modulus).

// The reset grid's residual (above) into the ghosted view R, without the load at x^n; gw = lambda
// g. A particle whose support at x' leaves the view (it moved across a rank's ghost layer) adds
// its moved-grid force V^n P grad S_i(x^n) instead; returns how many did.
template <class Shape, int D = DIM>
int reset_internal_force(const ParticleView &P, const double *G, const double *stress,
                         const double *Pk, const double *u, const double *gw,
                         const NodalViewT<D> &R);

// Add the reset grid's term (above) to one particle's stiffness K (particle_stiffness' layout):
// W and H the weights and their second derivatives at x^n, V = V^n, G and stress the particle's
// increment gradient and trial Cauchy stress, weight = w_p, gw = lambda g.
template <class Shape, int D = DIM>
void particle_reset_stiffness(const Weights<Shape, D> &W, const double H[][NHess<D>], double V,
                              const double *G, const double *stress, double weight,
                              const double *gw, double *K);

// A = dP / dG (D^2 x D^2, A[(a D + j) D^2 + (b D + l)] = dP_aj / dG_bl) of one particle in D = 2
// or 3 dimensions, exact for its material's update: the law's own tangent
// (Material::piola_tangent, piola_tangent3 in 3D; the laws'
// formulas in materials/tangent.hpp). s_old: committed stress; s_new: the stress at G (after the
// update); Fn: committed F; eps_p: committed equivalent plastic strain (plastic models only).
// eigen (3 values xx yy zz, or null): the step's eigenstrain increment (degradation.hpp), which
// the rate-form update subtracts from sym(G): a stress-free strain, so it moves the plastic
// models' trial stress (and so their return) but adds no term of its own.
template <int D = DIM>
inline void piola_tangent(const Material &m, const double *G, const double *s_old,
                          const double *s_new, const double *Fn, double eps_p, double *A,
                          const double *eigen = nullptr) {
  TangentPoint pt;
  pt.G = G;
  pt.s_old = s_old;
  pt.s_new = s_new;
  pt.Fn = Fn;
  pt.eps_p = eps_p;
  pt.eigen = eigen;
  if constexpr (D == 3)
    m.piola_tangent3(pt, A);
  else
    m.piola_tangent(pt, A);
}

// One particle's stiffness over its support: the NN nodes of weights() (node k at base +
// (k % NS, k / NS[, k / NS^2])); K[(k D + a) (NN D) + (m D + b)] = V sum_jl dS_k/dx_j A_ajbl
// dS_m/dx_l.
template <class Shape, int D = DIM>
void particle_stiffness(const Weights<Shape, D> &W, double V, const double *A, double *K);

// The tangent gathered per node before it goes into the matrix (one insertion per node row
// instead of one per particle): for every ghosted node, the D x D blocks coupling it to its
// (2w + 1)^D neighbours, w the stencil width; block (row node (i, j), column node (i + di, j + dj))
// at block(i, j, di, dj) (3D: block(i, j, k, di, dj, dk)), entry (a, b) at [a * D + b].
template <int D> struct NodeBlocksT {
  PetscInt gs[D] = {}, gm[D] = {};
  int w = 0;
  double *data = nullptr;
  double *block(PetscInt i, PetscInt j, int di, int dj) const {
    static_assert(D == 2, "block(i, j, di, dj) is 2D");
    const int nb = 2 * w + 1;
    return data +
           (((j - gs[1]) * gm[0] + (i - gs[0])) * nb * nb + (dj + w) * nb + (di + w)) * D * D;
  }
  double *block(PetscInt i, PetscInt j, PetscInt k, int di, int dj, int dk) const {
    static_assert(D == 3, "block(i, j, k, di, dj, dk) is 3D");
    const int nb = 2 * w + 1;
    const PetscInt n = ((k - gs[2]) * gm[1] + (j - gs[1])) * gm[0] + (i - gs[0]);
    return data + ((n * nb + (dk + w)) * nb * nb + (dj + w) * nb + (di + w)) * D * D;
  }
};
using NodeBlocks = NodeBlocksT<DIM>;

// Add one particle's stiffness (particle_stiffness' layout) into the node blocks.
template <class Shape, int D = DIM>
void add_particle_blocks(const Weights<Shape, D> &W, const double *K, const NodeBlocksT<D> &B);

} // namespace pmpm
