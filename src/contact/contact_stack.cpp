// Multi-velocity contact of a stack of bodies at one node (see contact_stack.hpp for the maths).
#include "pmpm/contact/contact_stack.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pmpm {

namespace {

constexpr int kMax = kStackMaxBodies;
// Round-off allowance of the consistency checks, relative to the magnitudes of the terms summed
// (a few hundred ulps: sums of at most 8 terms, a division, a difference).
constexpr double kTau = 256 * std::numeric_limits<double>::epsilon();

bool bonded(double cap) {
  return std::isinf(cap);
}
bool free_face(double cap) {
  return !(cap > 0);
}

// One state of the group of bodies b0 .. b1 (faces b0 .. b1-1, none free; the faces bounding the
// group carry no impulse). Slipping faces get S = +-cap; stuck faces join bodies into clusters
// moving with (sum m vt + S_top - S_bottom) / sum m, whose internal impulses follow from the
// momentum balance of the bodies below them. Writes S and the new velocities w; returns whether
// every stuck face is within its capacity and every slipping face opposes its sliding, each up to
// the round-off of the quantities compared (estimated from the magnitudes summed).
bool evaluate(int b0, int b1, const double *m, const double *vt, const double *cap,
              const FaceState *st, double *S, double *w) {
  for (int k = b0; k < b1; ++k)
    if (st[k] != FaceState::Stick) S[k] = st[k] == FaceState::SlipPlus ? cap[k] : -cap[k];
  double v_below = 0, e_below = 0; // the cluster below: velocity and its round-off estimate
  for (int a = b0; a <= b1;) {
    int b = a;
    while (b < b1 && st[b] == FaceState::Stick) ++b;
    const double s_bot = a > b0 ? S[a - 1] : 0.0, s_top = b < b1 ? S[b] : 0.0;
    double V, e;
    if (a == b) {
      V = vt[a] + (s_top - s_bot) / m[a];
      e = kTau * (std::fabs(vt[a]) + (std::fabs(s_top) + std::fabs(s_bot)) / m[a]);
    } else {
      double M = 0, P = 0, A = 0;
      for (int i = a; i <= b; ++i) {
        M += m[i];
        P += m[i] * vt[i];
        A += m[i] * std::fabs(vt[i]);
      }
      V = (P + s_top - s_bot) / M;
      e = kTau * (A + std::fabs(s_top) + std::fabs(s_bot)) / M;
      // stuck faces inside: S_k = S_bottom + sum_{i = a .. k} m_i (V - vt_i)
      double s = s_bot, mag = std::fabs(s_bot), mass = 0;
      for (int k = a; k < b; ++k) {
        s += m[k] * (V - vt[k]);
        mag += m[k] * (std::fabs(V) + std::fabs(vt[k]));
        mass += m[k];
        S[k] = s;
        if (bonded(cap[k])) continue;
        if (std::fabs(s) > cap[k] + kTau * (mag + cap[k]) + e * mass) return false;
        S[k] = std::clamp(s, -cap[k], cap[k]); // within round-off of the capacity
      }
    }
    if (a > b0) { // face a-1 slips: its impulse on the lower body must oppose the sliding
      const double rel = V - v_below, tol = e + e_below;
      if (st[a - 1] == FaceState::SlipPlus ? rel < -tol : rel > tol) return false;
    }
    for (int i = a; i <= b; ++i) w[i] = V;
    v_below = V;
    e_below = e;
    a = b + 1;
  }
  return true;
}

// Enumerates the states of the group b0 .. b1: bonded faces stick, the others stick or slip at
// +-cap (stick first, so ties go to stick). Returns false if none is consistent.
bool solve_group(int b0, int b1, const double *m, const double *vt, const double *cap,
                 FaceState *st, double *S, double *w) {
  int free3[kMax], nt = 0, digit[kMax] = {0};
  for (int k = b0; k < b1; ++k) {
    st[k] = FaceState::Stick;
    if (!bonded(cap[k])) free3[nt++] = k;
  }
  constexpr FaceState option[3] = {FaceState::Stick, FaceState::SlipPlus, FaceState::SlipMinus};
  for (;;) {
    for (int j = 0; j < nt; ++j) st[free3[j]] = option[digit[j]];
    if (evaluate(b0, b1, m, vt, cap, st, S, w)) return true;
    int j = 0;
    while (j < nt && ++digit[j] == 3) digit[j++] = 0;
    if (j == nt) return false;
  }
}

} // namespace

void stack_friction_pgs(int nb, const double *m, double *vt, const double *cap, double *S,
                        FaceState *state, int sweeps) {
  double w[kMax], scale = 0;
  for (int i = 0; i < nb; ++i) {
    w[i] = vt[i];
    scale += m[i] * std::fabs(vt[i]);
  }
  for (int k = 0; k < nb - 1; ++k) S[k] = 0;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    double change = 0;
    for (int k = 0; k < nb - 1; ++k) {
      if (free_face(cap[k])) continue;
      // the impulse that equalises the two velocities, then projected onto [-cap, cap]
      const double d = (w[k + 1] - w[k]) / (1 / m[k] + 1 / m[k + 1]);
      const double s = bonded(cap[k]) ? S[k] + d : std::clamp(S[k] + d, -cap[k], cap[k]);
      const double ds = s - S[k];
      w[k] += ds / m[k];
      w[k + 1] -= ds / m[k + 1];
      S[k] = s;
      change = std::max(change, std::fabs(ds));
    }
    if (change <= kTau * scale) break;
  }
  for (int i = 0; i < nb; ++i) // from the impulses: conserves momentum to round-off
    vt[i] += ((i < nb - 1 ? S[i] : 0.0) - (i > 0 ? S[i - 1] : 0.0)) / m[i];
  if (state)
    for (int k = 0; k < nb - 1; ++k) {
      if (free_face(cap[k]))
        state[k] = FaceState::Free;
      else if (!bonded(cap[k]) && std::fabs(S[k]) >= cap[k] * (1 - 1e-12))
        state[k] = S[k] > 0 ? FaceState::SlipPlus : FaceState::SlipMinus;
      else
        state[k] = FaceState::Stick;
    }
}

bool stack_friction(int nb, const double *m, double *vt, const double *cap, double *S,
                    FaceState *state) {
  FaceState st[kMax];
  double w[kMax];
  int b0 = 0;
  // free faces (capacity 0) carry no impulse and split the stack into independent groups
  for (int k = 0; k < nb; ++k) {
    if (k < nb - 1 && !free_face(cap[k])) continue;
    if (k < nb - 1) {
      st[k] = FaceState::Free;
      S[k] = 0;
    }
    if (!solve_group(b0, k, m, vt, cap, st, S, w)) {
      stack_friction_pgs(nb, m, vt, cap, S, state, 200000);
      return false;
    }
    b0 = k + 1;
  }
  for (int i = 0; i < nb; ++i) vt[i] = w[i];
  if (state)
    for (int k = 0; k < nb - 1; ++k) state[k] = st[k];
  return true;
}

void contact_stack(int nb, const double *m, double *v, const StackFace *faces, const double n[2],
                   StackFaceResult *res, bool *fallback) {
  if (fallback) *fallback = false;
  if (nb < 1 || nb > kMax) throw std::invalid_argument("pmpm::contact_stack: nb must be 1 .. 8");
  if (nb == 1) return;
  const double t[2] = {-n[1], n[0]};
  double vn[kMax], vt[kMax], wn[kMax], wt[kMax];
  for (int i = 0; i < nb; ++i) {
    vn[i] = v[2 * i] * n[0] + v[2 * i + 1] * n[1];
    vt[i] = v[2 * i] * t[0] + v[2 * i + 1] * t[1];
  }

  // Normal: blocks joined by bilateral faces, then pool-adjacent-violators over the blocks.
  int first[kMax], last[kMax], nblk = 0;
  double M[kMax], P[kMax], V[kMax];
  for (int i = 0; i < nb;) {
    int j = i;
    double mass = m[i], mom = m[i] * vn[i];
    while (j < nb - 1 && faces[j].type != FaceType::Contact) {
      ++j;
      mass += m[j];
      mom += m[j] * vn[j];
    }
    first[nblk] = i;
    last[nblk] = j;
    M[nblk] = mass;
    P[nblk] = mom;
    V[nblk] = i == j ? vn[i] : mom / mass;
    ++nblk;
    while (nblk >= 2 && V[nblk - 2] > V[nblk - 1]) { // the lower block runs into the upper one
      const int b = nblk - 2;
      last[b] = last[b + 1];
      M[b] += M[b + 1];
      P[b] += P[b + 1];
      V[b] = P[b] / M[b];
      --nblk;
    }
    i = j + 1;
  }
  for (int b = 0; b < nblk; ++b) {
    double N = 0;
    for (int k = first[b]; k <= last[b]; ++k) {
      wn[k] = V[b];
      if (k == nb - 1) break;
      N += m[k] * (vn[k] - V[b]);
      res[k].contact = k < last[b];
      res[k].normal = k < last[b] ? N : 0.0;
    }
  }

  // Tangential: the friction box QP over the capacities.
  double cap[kMax], S[kMax];
  FaceState st[kMax];
  for (int k = 0; k < nb - 1; ++k) {
    const StackFace &f = faces[k];
    cap[k] = f.type == FaceType::Bonded ? std::numeric_limits<double>::infinity()
             : res[k].contact           ? f.mu * std::max(res[k].normal, 0.0) + f.adhesion
                                        : 0.0;
  }
  for (int i = 0; i < nb; ++i) wt[i] = vt[i];
  const bool exact = stack_friction(nb, m, wt, cap, S, st);
  if (fallback) *fallback = !exact;
  for (int k = 0; k < nb - 1; ++k) {
    res[k].tangential = S[k];
    res[k].slip = res[k].contact && st[k] != FaceState::Stick;
  }

  for (int i = 0; i < nb; ++i)
    if (wn[i] != vn[i] || wt[i] != vt[i]) {
      v[2 * i] = wn[i] * n[0] + wt[i] * t[0];
      v[2 * i + 1] = wn[i] * n[1] + wt[i] * t[1];
    }
}

} // namespace pmpm
