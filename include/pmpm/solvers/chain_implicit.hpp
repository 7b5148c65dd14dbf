// Membrane chains (chain.hpp) under the implicit solver (-solver newton), every face bonded.
//
// Bonded, the stacked bodies and the sheet share one displacement field, so a chain is more
// internal force on the load step's unknown du (implicit_kernels.hpp). Per point i, from its
// position x_i^n at the step's start and its uGIMP weights there (the thin block p2g_chain maps):
//   du_i = sum_k w_ik du_k                    (held and unsupported dofs masked out)
//   x_i  = x_i^n + du_i,  eps_s = l_s / l0_s - 1,  T_s = law(eps_s; committed eps_p, alpha)
//   f_i  = T_i tau_i - T_{i-1} tau_{i-1}      (as chain_update_tension)
//   R_k += -w_ik f_i                          (R = f_int - f_ext: the sheet's pull acts on the
//   body)
// and the tangent is W^T K W with K the two-node bar of each segment s (n its unit vector, l its
// trial length): K_s = dT/deps / l0 n n^T + T / l (I - n n^T) on (+, -; -, +), dT/deps the law's
// consistent tangent (0 where a tension-only sheet is slack). Pinned points are not mapped (their
// du is 0 and their force is the support's reaction, as under relaxation).
//
// Under -chain_strain_projection the tension is T_s = law((P e)_s), P the projection of chain.hpp
// (ChainProjection) frozen at the step's start with the stencils (relaxation takes it at the
// current positions; the reset between steps catches up, as for the weights). P is linear in the
// chord strains, so the bar's material term becomes a coupling of every pair of segments that
// share a projection node I:
//   K_pq = sum_I (1/M_I) a_I^p (b_I^q)^T,  a_I^p = sum_k dT_k w_Ik s_kp n_k,
//                                          b_I^q = sum_j w_Ij s_jq n_j,
// s_kp = -1, +1 for p = k, k + 1 (e_k's derivative is s_kp n_k / l0_k): with a linear law it is
// the Hessian of J/2 sum_k l0_k e_k (P e)_k, symmetric. The geometric term T_s / l (I - n n^T)
// stays per segment with the projected T_s. Neighbouring segments' midpoints share nodes up to 3
// cells apart, so this coupling reaches about 7 nodes, beyond the solve's stencil and ghost nodes:
// newton.cpp adds it with global indices, its columns through masked weights every rank holds.
//
// Distribution as in chain.hpp: every rank holds every point; the rank owning a point's cell
// computes its du (the others give 0; the caller sums over ranks, so every rank has every trial
// position, bit for bit alike) and adds its force and its rows of the tangent.
#pragma once
#include "pmpm/contact/chain.hpp"
#include "pmpm/solvers/implicit_kernels.hpp"
#include <vector>

namespace pmpm {

// A chain's points on the grid at a load step's start.
struct ChainStencil {
  std::vector<char> mapped; // this rank owns the point's cell and the point is not pinned
  std::vector<char> moves;  // not pinned (the point's du is a column of the tangent)
  std::vector<Weights<UGIMPShape>> W;
  // -chain_strain_projection: the projection at the step's start, its nodes' segments (node
  // I's entries [nstart[I], nstart[I + 1]) of nseg, nent: the segment and its entry in proj), and
  // every point's weights times the dof mask (NN x DIM per point, from its owner, summed over
  // ranks: chain_stencil_mask).
  bool project = false;
  ChainProjection proj;
  std::vector<int> nstart, nseg, nent;
  std::vector<double> wm;
};
// Returns how many points this rank maps.
int chain_stencil(const Chain &c, const GridView &G, const Grid &grid, ChainStencil &S);

// The weights times the mask of the points this rank maps into S.wm (zeros for the others; the
// caller sums S.wm over ranks).
void chain_stencil_mask(ChainStencil &S, const NodalView &mask);

// du of the points this rank maps (DIM per point; 0 for the others): sum_k w_ik mask_k U_k.
void chain_point_increment(const ChainStencil &S, const NodalView &U, const NodalView &mask,
                           double *du);

// The trial state of a chain from the points' increments (summed over ranks): positions, segment
// strains, tensions from copies of the committed law state, their tangents dT/deps, point forces.
struct ChainTrial {
  std::vector<double> x, eps, eps_p, alpha, T, dT, f;
};
void chain_trial(const Chain &c, const ChainStencil &S, const double *du, ChainTrial &t);

// R_k -= w_ik f_i for the points this rank maps (into the ghosted view).
void chain_internal_force(const ChainStencil &S, const ChainTrial &t, const NodalView &R);

// The rows of W^T K W at the nodes of the points this rank maps, into the node blocks. Returns
// the couplings that did not fit (a node outside the ghosted range or farther than the blocks'
// width from its row): 0 when the stencil width covers the chain (newton.cpp).
// Under -chain_strain_projection only the geometric term (the material term is
// chain_projected_coupling's).
int chain_stiffness(const Chain &c, const ChainStencil &S, const ChainTrial &t,
                    const NodeBlocks &B);

// A grid dof of a sparse vector: node (i, j), component d, value v.
struct ChainDofValue {
  PetscInt i, j;
  int d;
  double v;
};
// Projection node I's term of the material tangent (-chain_strain_projection): the tangent gains
// a b^T / M_I, a over the rows of the points this rank maps (their weights, dofs not masked), b
// over the columns of every moving point (S.wm). Returns M_I; a is empty when no point of this
// rank reaches I.
double chain_projected_coupling(const Chain &c, const ChainStencil &S, const ChainTrial &t, int I,
                                std::vector<ChainDofValue> &a, std::vector<ChainDofValue> &b);

} // namespace pmpm
