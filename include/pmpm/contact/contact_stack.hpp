// Multi-velocity contact of a stack of bodies at one grid node: Bardenhagen et al. (2001)
// ("An improved contact algorithm for the material point method and application to stress
// propagation in granular material", CMES 2:509-522) generalised from two bodies to a stack.
//
// Setting. At one node nb bodies (1 <= nb <= 8) are stacked along the unit normal n (2D): body 0
// lowest, body k+1 above body k (e.g. waste, a geomembrane chain, cover soil). Body k has nodal
// mass m_k > 0 and a trial velocity v_k computed on its own. Face k lies between bodies k and
// k+1. With t = (-n_y, n_x): vn_k = v_k . n, vt_k = v_k . t.
//
// Normal (no interpenetration). Face k carries the normal impulse N_k (> 0 compression: -N_k on
// body k along n, +N_k on body k+1), so vn_k' = vn_k + (N_{k-1} - N_k) / m_k (N_{-1} = N_{nb-1} =
// 0). The new normal velocities are the mass-weighted projection of the trial ones onto
//   Contact faces:        vn_k' <= vn_{k+1}'  (N_k >= 0, N_k (vn_{k+1}' - vn_k') = 0: separation
//                         is free)
//   Bonded, Paper faces:  vn_k' == vn_{k+1}'  (bilateral: they never separate, N_k of any sign)
// i.e. min sum_k m_k (vn_k' - vn_k)^2 / 2 under these constraints. Solved exactly: bodies joined by
// bilateral faces form blocks, then pool-adjacent-violators (weights m) over the blocks: adjacent
// blocks merge while the lower one's velocity exceeds the upper one's; a block moves with
// sum m vn / sum m. Inside a final block N_k = sum_{i = first .. k} m_i (vn_i - vn_i') (>= 0 at
// Contact faces by the KKT conditions; < 0 is tension, possible at Paper and Bonded faces). Faces
// between blocks are not in contact: N_k = 0.
//
// Tangential (Coulomb friction with maximal dissipation). Face k carries S_k (+S_k on body k along
// t, -S_k on body k+1), vt_k' = vt_k + (S_k - S_{k-1}) / m_k, with |S_k| <= C_k:
//   C_k = infinity                            Bonded
//   C_k = mu_k max(N_k, 0) + adhesion_k       Paper and Contact faces in contact
//   C_k = 0                                   faces not in contact (free)
// The S_k minimise the kinetic energy sum_k m_k vt_k'^2 / 2 over the box: a strictly convex QP
// whose KKT conditions are Coulomb's law: |S_k| < C_k -> the face sticks (vt_k' = vt_{k+1}'),
// S_k = +C_k -> vt_{k+1}' >= vt_k', S_k = -C_k -> vt_{k+1}' <= vt_k'. Solved exactly by
// enumerating the faces' states (stick, slip at +C, slip at -C; C = 0 faces are free, Bonded faces
// stick) over the independent groups between free faces: stuck faces join bodies into clusters
// moving with (sum m vt + S_top - S_bottom) / sum m; a state is accepted when every stuck face's
// impulse is within its capacity and every slipping face's impulse opposes the sliding (up to the
// round-off of the computed quantities, estimated per cluster, so that a light body between heavy
// ones, e.g. a geomembrane of 1e-6 their mass, is handled exactly). The first consistent state is
// taken (stick before slip at ties). Should round-off leave no state consistent, projected
// Gauss-Seidel on the S_k is used instead (reported through `fallback`).
//
// Total momentum is conserved (every impulse acts with opposite signs on two bodies) and the
// kinetic energy does not increase (both steps are projections that keep zero impulse feasible).
// Pure functions on plain arrays: no PETSc, no MPI.
#pragma once

namespace pmpm {

constexpr int kStackMaxBodies = 8;

enum class FaceType { Bonded = 0, Paper = 1, Contact = 2 };

// One face of a membrane (a chain's or a sheet's) against the body beside it: its type, Coulomb
// mu (or tan delta) and an adhesion (Pa).
struct MembraneFace {
  FaceType type = FaceType::Contact;
  double mu = 0.5;
  double adhesion = 0;
};

struct StackFace {
  FaceType type = FaceType::Contact;
  double mu = 0;       // Coulomb coefficient, >= 0
  double adhesion = 0; // adhesion impulse capacity (N s per unit thickness) = adhesion (Pa) *
                       // length * dt, >= 0, added to the friction capacity where in contact
};

// The face between two present bodies lo < hi at a node, among membranes (chains or 3D sheets:
// each with `body`, `top` and `bottom` MembraneFaces) for which counts(membrane) holds: the face of
// the membrane between them, or, where a membrane lies between but does not reach the node, the
// weaker of its two faces (the smaller mu and adhesion, the looser type); bonded where none lies
// between (two continuum bodies with no membrane between them are one body).
template <class Membranes, class Counts>
StackFace face_between_membranes(const Membranes &ms, int lo, int hi, Counts counts) {
  StackFace f;
  bool first = true;
  for (const auto &c : ms) {
    if (!counts(c) || c.body < lo || c.body > hi) continue;
    const MembraneFace *cand[2] = {nullptr, nullptr};
    if (c.body == lo)
      cand[0] = &c.top;
    else if (c.body == hi)
      cand[0] = &c.bottom;
    else {
      cand[0] = &c.top;
      cand[1] = &c.bottom;
    }
    for (const MembraneFace *cf : cand) {
      if (!cf) continue;
      if (first) {
        f.type = cf->type;
        f.mu = cf->mu;
        f.adhesion = cf->adhesion;
        first = false;
      } else {
        f.mu = cf->mu < f.mu ? cf->mu : f.mu;
        f.adhesion = cf->adhesion < f.adhesion ? cf->adhesion : f.adhesion;
        if (cf->type == FaceType::Contact || f.type == FaceType::Contact)
          f.type = FaceType::Contact;
        else if (cf->type == FaceType::Paper || f.type == FaceType::Paper)
          f.type = FaceType::Paper;
      }
    }
  }
  if (first) f.type = FaceType::Bonded;
  return f;
}

struct StackFaceResult {
  double normal = 0;     // normal impulse across the face, > 0 compression (pushes the lower body
                         // along -n, the upper along +n)
  double tangential = 0; // tangential impulse on the LOWER body along t (the upper gets minus it)
  bool contact = false;  // the faces are joined in the normal direction (in contact)
  bool slip = false;     // in contact and not stuck: the tangential impulse is at its capacity
                         // (capacity > 0) or the face is free (capacity 0, e.g. mu = 0)
};

// nb bodies (1 <= nb <= 8), masses m[nb] > 0, velocities v[2*nb] (in: trial, out: new),
// faces[nb-1], res[nb-1] (out). n: unit normal pointing from body 0 toward body nb-1;
// t = (-n[1], n[0]). A body whose velocity is unchanged keeps its input bits. If fallback is given
// it is set to whether the tangential solve needed the projected Gauss-Seidel fallback.
// Throws std::invalid_argument if nb is outside 1 .. 8.
void contact_stack(int nb, const double *m, double *v, const StackFace *faces, const double n[2],
                   StackFaceResult *res, bool *fallback = nullptr);

// Face states of the tangential solve.
enum class FaceState { Stick = 0, SlipPlus = 1, SlipMinus = 2, Free = 3 };

// The tangential step alone (exposed for testing): nb bodies, m[nb], vt[nb] (in: trial tangential
// velocities, out: new), cap[nb-1] the capacities C_k (std::numeric_limits<double>::infinity()
// for a bonded face, 0 for a free one), S[nb-1] (out) the impulses, state[nb-1] (out, may be
// null). Returns true if the enumeration found a consistent state, false if the projected
// Gauss-Seidel fallback was used.
bool stack_friction(int nb, const double *m, double *vt, const double *cap, double *S,
                    FaceState *state);

// The fallback alone (exposed for testing): projected Gauss-Seidel on the S_k, at most `sweeps`
// sweeps (stops earlier once no impulse changes beyond round-off). Same arguments as
// stack_friction; the states are read off the converged impulses.
void stack_friction_pgs(int nb, const double *m, double *vt, const double *cap, double *S,
                        FaceState *state, int sweeps);

// Three dimensions (the 3D sheet's faces): the same stack along a unit normal n (3 components);
// a body's tangential velocity vt_k is a vector in the plane normal to n, each face's friction
// impulse S_k a vector there too, and Coulomb's law a cone, |S_k| <= C_k. The normal step is the
// 2D kernel's, run on the normal components alone (scalar along n). The tangential step minimises
// the kinetic energy sum_k m_k |vt_k'|^2 / 2 over |S_k| <= C_k (maximal dissipation); its dual is
//   min_w  sum_k m_k / 2 |w_k - vt_k|^2 + sum_k C_k |w_{k+1} - w_k|,
// strictly convex, whose minimiser is Coulomb's law: a face sticks (w_k = w_{k+1}) while its
// impulse is inside the cone, and slides with S_k = C_k (w_{k+1} - w_k) / |w_{k+1} - w_k| on
// the lower body otherwise, the impulse along the sliding and opposing it. Solved by enumerating
// the faces' states (stick or slide; free faces split the stack as in 2D) with the fewest slides
// first: stuck faces join bodies into clusters, and the clusters' velocities minimise the smooth
// energy above with every sliding face's velocity jump nonzero, by Newton's method with a line
// search: first with the jumps smoothed, sqrt(|d|^2 + eps^2) with eps falling from a tenth to
// 1e-11 of the velocity scale (so that a jump may reverse on the way), then unsmoothed (a light
// sheet between heavy bodies is a small, well-posed system, not a slow iteration). A state is
// accepted when every sliding face's jump stays above 1e-12 of the velocity scale and every stuck
// face's impulse is inside its cone to 1e-12 of the momenta summed. Should none be, projected
// block Gauss-Seidel (each face's impulse projected on its disc) is used instead.
struct StackFaceResult3 {
  double normal = 0;                // as StackFaceResult
  double tangential[3] = {0, 0, 0}; // friction impulse on the LOWER body (the upper gets minus it)
  bool contact = false, slip = false;
};

// nb bodies (1 <= nb <= 8), masses m[nb] > 0, velocities v[3*nb] (in: trial, out: new),
// faces[nb-1], res[nb-1] (out); n the unit normal from body 0 toward body nb-1. A body whose
// velocity is unchanged keeps its input bits. fallback as in 2D. Throws std::invalid_argument if
// nb is outside 1 .. 8.
void contact_stack3(int nb, const double *m, double *v, const StackFace *faces, const double n[3],
                    StackFaceResult3 *res, bool *fallback = nullptr);

// The tangential step alone (exposed for testing): vt[2*nb] (in: trial tangential velocities in
// any orthonormal basis of the plane, out: new), cap[nb-1] as stack_friction's, S[2*nb-2] (out)
// the impulses on the lower bodies, state[nb-1] (out, may be null: Stick, SlipPlus for a sliding
// face, Free). Returns true if the enumeration found a consistent state, false if the fallback
// was used.
bool stack_friction_cone(int nb, const double *m, double *vt, const double *cap, double *S,
                         FaceState *state);
// The fallback alone: projected block Gauss-Seidel, at most `sweeps` sweeps.
void stack_friction_cone_pgs(int nb, const double *m, double *vt, const double *cap, double *S,
                             FaceState *state, int sweeps);

} // namespace pmpm
