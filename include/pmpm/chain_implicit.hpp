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
// Distribution as in chain.hpp: every rank holds every point; the rank owning a point's cell
// computes its du (the others give 0; the caller sums over ranks, so every rank has every trial
// position, bit for bit alike) and adds its force and its rows of the tangent.
#pragma once
#include "pmpm/chain.hpp"
#include "pmpm/implicit_kernels.hpp"
#include <vector>

namespace pmpm {

// A chain's points on the grid at a load step's start.
struct ChainStencil {
  std::vector<char> mapped; // this rank owns the point's cell and the point is not pinned
  std::vector<char> moves;  // not pinned (the point's du is a column of the tangent)
  std::vector<Weights<UGIMPShape>> W;
};
// Returns how many points this rank maps.
int chain_stencil(const Chain &c, const GridView &G, const Grid &grid, ChainStencil &S);

// du of the points this rank maps (DIM per point; 0 for the others): sum_k w_ik mask_k U_k.
void chain_point_increment(const ChainStencil &S, const NodalView &U, const NodalView &mask,
                           double *du);

// The trial state of a chain from the points' increments (summed over ranks): positions, segment
// strains, tensions from copies of the committed law state, their tangents dT/deps, point forces.
struct ChainTrial {
  std::vector<double> x, eps, eps_p, alpha, T, dT, f;
};
void chain_trial(const Chain &c, const double *du, ChainTrial &t);

// R_k -= w_ik f_i for the points this rank maps (into the ghosted view).
void chain_internal_force(const ChainStencil &S, const ChainTrial &t, const NodalView &R);

// The rows of W^T K W at the nodes of the points this rank maps, into the node blocks. Returns
// the couplings that did not fit (a node outside the ghosted range or farther than the blocks'
// width from its row): 0 when the stencil width covers the chain (newton.cpp).
int chain_stiffness(const Chain &c, const ChainStencil &S, const ChainTrial &t,
                    const NodeBlocks &B);

} // namespace pmpm
