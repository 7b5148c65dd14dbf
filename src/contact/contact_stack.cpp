// Multi-velocity contact of a stack of bodies at one node (see contact_stack.hpp for the maths).
#include "pmpm/contact/contact_stack.hpp"
#include <Eigen/Dense>
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

// ---- Three dimensions: the friction cone (contact_stack.hpp) ----

namespace {
using Vec2 = Eigen::Vector2d;

Vec2 at(const double *a, int i) {
  return {a[2 * i], a[2 * i + 1]};
}

constexpr int kN = 2 * kMax; // the clusters' velocities, 2 per cluster (plain arrays: n <= 16)

// The clusters' energy sum_c M_c / 2 |W_c - V_c|^2 + sum_c C_c |W_{c+1} - W_c| (nc clusters, the
// sliding face c between clusters c and c + 1), its gradient g and Hessian H (may be null) where
// every jump is nonzero; false where one is not.
bool cone_energy(int nc, const double *M, const Vec2 *V, const double *C, const double *W,
                 double eps, double *phi, double *g, double (*H)[kN]) {
  const int n = 2 * nc;
  double e = 0;
  if (g) std::fill(g, g + n, 0.0);
  if (H)
    for (int i = 0; i < n; ++i) std::fill(H[i], H[i] + n, 0.0);
  for (int c = 0; c < nc; ++c)
    for (int q = 0; q < 2; ++q) {
      const double d = W[2 * c + q] - V[c][q];
      e += 0.5 * M[c] * d * d;
      if (g) g[2 * c + q] += M[c] * d;
      if (H) H[2 * c + q][2 * c + q] += M[c];
    }
  for (int c = 0; c + 1 < nc; ++c) {
    const double d[2] = {W[2 * c + 2] - W[2 * c], W[2 * c + 3] - W[2 * c + 1]};
    const double r =
        eps > 0 ? std::sqrt(d[0] * d[0] + d[1] * d[1] + eps * eps) : std::hypot(d[0], d[1]);
    if (!(r > 0)) return false;
    e += C[c] * r;
    const double u[2] = {d[0] / r, d[1] / r}; // |u| < 1 when smoothed
    for (int p = 0; p < 2; ++p) {
      if (g) {
        g[2 * c + p] -= C[c] * u[p];
        g[2 * c + 2 + p] += C[c] * u[p];
      }
      if (H)
        for (int q = 0; q < 2; ++q) {
          const double K = C[c] / r * ((p == q ? 1.0 : 0.0) - u[p] * u[q]);
          H[2 * c + p][2 * c + q] += K;
          H[2 * c + 2 + p][2 * c + 2 + q] += K;
          H[2 * c + p][2 * c + 2 + q] -= K;
          H[2 * c + 2 + p][2 * c + q] -= K;
        }
    }
  }
  *phi = e;
  return true;
}

// x = -H^-1 g for the symmetric positive definite n x n H (Cholesky in place); false if a pivot
// is not positive (round-off where a jump tends to zero: a state that wants to stick).
bool NewtonStep(double (*L)[kN], const double *g, int n, double *x) {
  for (int j = 0; j < n; ++j) {
    double d = L[j][j];
    for (int k = 0; k < j; ++k) d -= L[j][k] * L[j][k];
    if (!(d > 0)) return false;
    L[j][j] = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double a = L[i][j];
      for (int k = 0; k < j; ++k) a -= L[i][k] * L[j][k];
      L[i][j] = a / L[j][j];
    }
  }
  for (int i = 0; i < n; ++i) { // L y = -g
    double a = -g[i];
    for (int k = 0; k < i; ++k) a -= L[i][k] * x[k];
    x[i] = a / L[i][i];
  }
  for (int i = n - 1; i >= 0; --i) { // L^T x = y
    double a = x[i];
    for (int k = i + 1; k < n; ++k) a -= L[k][i] * x[k];
    x[i] = a / L[i][i];
  }
  return true;
}

// One state of the group b0 .. b1 (faces b0 .. b1-1, none free; slide[k] for the faces that
// slide, bonded ones never do): the clusters' velocities by Newton's method, then the impulses
// (sliding faces C u, stuck ones from the bodies' momentum balance below them) and the bodies'
// velocities from the impulses (momentum conserved to round-off). Returns whether every sliding
// jump stays away from zero and every stuck impulse is inside its cone, up to round-off.
bool evaluate_cone(int b0, int b1, const double *m, const double *vt, const double *cap,
                   const bool *slide, double *S, double *w) {
  int first[kMax], last[kMax], nc = 0;
  double M[kMax], C[kMax], scale = 0;
  Vec2 V[kMax];
  for (int a = b0; a <= b1; ++nc) {
    int b = a;
    while (b < b1 && !slide[b]) ++b;
    first[nc] = a;
    last[nc] = b;
    M[nc] = 0;
    Vec2 P = Vec2::Zero();
    for (int i = a; i <= b; ++i) {
      M[nc] += m[i];
      P += m[i] * at(vt, i);
      scale = std::fmax(scale, at(vt, i).norm());
    }
    V[nc] = P / M[nc];
    if (b < b1) C[nc] = cap[b];
    a = b + 1;
  }
  double W[kN];
  for (int c = 0; c < nc; ++c) {
    W[2 * c] = V[c][0];
    W[2 * c + 1] = V[c][1];
  }
  double capmax = 0, mmin = M[0];
  for (int c = 0; c < nc; ++c) {
    if (c + 1 < nc) capmax = std::fmax(capmax, C[c]);
    mmin = std::fmin(mmin, M[c]);
  }
  scale = std::fmax(scale, capmax / mmin); // a velocity scale of the problem
  const double tiny = 1e-12 * scale;       // a sliding jump below this wants to stick
  double gscale = capmax;                  // the gradient's scale: momenta and capacities
  for (int c = 0; c < nc; ++c) gscale = std::fmax(gscale, M[c] * scale);
  auto jump = [&](int c) {
    return std::hypot(W[2 * c + 2] - W[2 * c], W[2 * c + 3] - W[2 * c + 1]);
  };
  // Newton's method with a line search on the energy, its jumps |d| smoothed to
  // sqrt(|d|^2 + eps^2) (eps > 0: smooth everywhere, so a jump may reverse on the way), the last
  // pass unsmoothed (eps = 0), where no jump may more than halve along itself in one step: there
  // the energy has a kink at a zero jump that the Newton model does not see (no curvature along
  // the jump), and a step across it is rejected ever more finely by the line search.
  const int n = 2 * nc;
  auto newton = [&](double eps, int max_it) {
    for (int it = 0; it < max_it; ++it) {
      double phi, g[kN], H[kN][kN], dx[kN], W1[kN];
      if (!cone_energy(nc, M, V, C, W, eps, &phi, g, H) || !NewtonStep(H, g, n, dx)) return false;
      double slope = 0, step = 0, gmax = 0, tmax = 1;
      for (int i = 0; i < n; ++i) {
        slope += g[i] * dx[i];
        gmax = std::fmax(gmax, std::fabs(g[i]));
      }
      for (int c = 0; c + 1 < nc && eps == 0; ++c) {
        const double d0 = W[2 * c + 2] - W[2 * c], d1 = W[2 * c + 3] - W[2 * c + 1];
        const double along =
            ((dx[2 * c + 2] - dx[2 * c]) * d0 + (dx[2 * c + 3] - dx[2 * c + 1]) * d1) /
            std::hypot(d0, d1);
        if (along < 0) tmax = std::fmin(tmax, 0.5 * std::hypot(d0, d1) / -along);
      }
      // near the minimum the decrease a step buys is below the energy's round-off, which the
      // line search cannot see: there the Newton step is taken whole
      const bool resolved = -slope > 1e-12 * std::fabs(phi);
      double t = tmax;
      for (int ls = 0; ls < 60 && resolved; ++ls, t *= 0.5) {
        for (int i = 0; i < n; ++i) W1[i] = W[i] + t * dx[i];
        double phi1;
        if (cone_energy(nc, M, V, C, W1, eps, &phi1, nullptr, nullptr) &&
            phi1 <= phi + 1e-4 * t * slope)
          break;
      }
      for (int i = 0; i < n; ++i) {
        W[i] += t * dx[i];
        step = std::max(step, std::fabs(t * dx[i])); // NaN-propagating, unlike fmax
      }
      if (!std::isfinite(step + W[0])) return false;
      // converged: smoothed, to within a thousandth of eps; unsmoothed, a step below round-off
      // where the gradient (before it) was at round-off too (a stall against a kink has steps as
      // small and a gradient of the size of C)
      if (eps > 0 ? step <= 1e-3 * eps
                  : step <= 4 * std::numeric_limits<double>::epsilon() * scale &&
                        gmax <= 1e-12 * gscale)
        return true;
    }
    return false;
  };
  if (nc > 1) {
    for (double eps = 0.1 * scale; eps > 1e-12 * scale; eps *= 1e-2)
      if (!newton(eps, 50)) return false;
    if (!newton(0.0, 100)) return false;
    for (int c = 0; c + 1 < nc; ++c)
      if (jump(c) <= tiny) return false;
  }
  // the impulses: sliding faces C u; stuck ones up each cluster from the face below it
  Vec2 below = Vec2::Zero();
  for (int c = 0; c < nc; ++c) {
    const Vec2 Wc(W[2 * c], W[2 * c + 1]);
    Vec2 s = below;
    double mag = below.norm();
    for (int k = first[c]; k < last[c]; ++k) {
      s += m[k] * (Wc - at(vt, k));
      mag += m[k] * (Wc.norm() + at(vt, k).norm());
      if (!bonded(cap[k])) {
        const double r = s.norm();
        if (r > cap[k] + 1e-12 * (mag + cap[k])) return false;
        // (within that allowance it is kept as it is: scaled onto the cone, the bodies it joins
        // would part by the excess over their mass)
      }
      S[2 * k] = s[0];
      S[2 * k + 1] = s[1];
    }
    if (c + 1 < nc) {
      const Vec2 d = Vec2(W[2 * c + 2], W[2 * c + 3]) - Wc, u = d / d.norm();
      const int k = last[c];
      S[2 * k] = C[c] * u[0];
      S[2 * k + 1] = C[c] * u[1];
      below = C[c] * u;
    }
  }
  for (int i = b0; i <= b1; ++i)
    for (int d = 0; d < 2; ++d)
      w[2 * i + d] = vt[2 * i + d] +
                     ((i < b1 ? S[2 * i + d] : 0.0) - (i > b0 ? S[2 * (i - 1) + d] : 0.0)) / m[i];
  return true;
}

// Enumerates the states of the group b0 .. b1 by the number of sliding faces (none first: ties
// go to stick), each count in the faces' order. Returns false if none is consistent.
bool solve_cone_group(int b0, int b1, const double *m, const double *vt, const double *cap,
                      bool *slide, double *S, double *w) {
  int fr[kMax], nf = 0;
  for (int k = b0; k < b1; ++k) {
    slide[k] = false;
    if (!bonded(cap[k])) fr[nf++] = k;
  }
  for (int ns = 0; ns <= nf; ++ns)
    for (unsigned mask = 0; mask < (1u << nf); ++mask) {
      if (__builtin_popcount(mask) != ns) continue;
      for (int j = 0; j < nf; ++j) slide[fr[j]] = mask >> j & 1;
      if (evaluate_cone(b0, b1, m, vt, cap, slide, S, w)) return true;
    }
  return false;
}
} // namespace

void stack_friction_cone_pgs(int nb, const double *m, double *vt, const double *cap, double *S,
                             FaceState *state, int sweeps) {
  double w[2 * kMax], scale = 0;
  for (int i = 0; i < nb; ++i) {
    w[2 * i] = vt[2 * i];
    w[2 * i + 1] = vt[2 * i + 1];
    scale += m[i] * at(vt, i).norm();
  }
  for (int k = 0; k < 2 * (nb - 1); ++k) S[k] = 0;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    double change = 0;
    for (int k = 0; k < nb - 1; ++k) {
      if (free_face(cap[k])) continue;
      // the impulse that equalises the two velocities, then projected onto the disc
      const Vec2 d = (at(w, k + 1) - at(w, k)) / (1 / m[k] + 1 / m[k + 1]);
      Vec2 s = at(S, k) + d;
      if (!bonded(cap[k]) && s.norm() > cap[k]) s *= cap[k] / s.norm();
      const Vec2 ds = s - at(S, k);
      for (int q = 0; q < 2; ++q) {
        w[2 * k + q] += ds[q] / m[k];
        w[2 * k + 2 + q] -= ds[q] / m[k + 1];
        S[2 * k + q] = s[q];
      }
      change = std::fmax(change, ds.norm());
    }
    if (change <= kTau * scale) break;
  }
  for (int i = 0; i < nb; ++i) // from the impulses: conserves momentum to round-off
    for (int q = 0; q < 2; ++q)
      vt[2 * i + q] +=
          ((i < nb - 1 ? S[2 * i + q] : 0.0) - (i > 0 ? S[2 * (i - 1) + q] : 0.0)) / m[i];
  if (state)
    for (int k = 0; k < nb - 1; ++k)
      state[k] = free_face(cap[k])                                            ? FaceState::Free
                 : !bonded(cap[k]) && at(S, k).norm() >= cap[k] * (1 - 1e-12) ? FaceState::SlipPlus
                                                                              : FaceState::Stick;
}

bool stack_friction_cone(int nb, const double *m, double *vt, const double *cap, double *S,
                         FaceState *state) {
  bool slide[kMax] = {};
  double w[2 * kMax];
  int b0 = 0;
  for (int k = 0; k < nb; ++k) {
    if (k < nb - 1 && !free_face(cap[k])) continue;
    if (k < nb - 1) S[2 * k] = S[2 * k + 1] = 0;
    if (!solve_cone_group(b0, k, m, vt, cap, slide, S, w)) {
      stack_friction_cone_pgs(nb, m, vt, cap, S, state, 200000);
      return false;
    }
    b0 = k + 1;
  }
  for (int i = 0; i < 2 * nb; ++i) vt[i] = w[i];
  if (state)
    for (int k = 0; k < nb - 1; ++k)
      state[k] = free_face(cap[k]) ? FaceState::Free
                 : slide[k]        ? FaceState::SlipPlus
                                   : FaceState::Stick;
  return true;
}

void contact_stack3(int nb, const double *m, double *v, const StackFace *faces, const double n[3],
                    StackFaceResult3 *res, bool *fallback) {
  if (fallback) *fallback = false;
  if (nb < 1 || nb > kMax) throw std::invalid_argument("pmpm::contact_stack3: nb must be 1 .. 8");
  if (nb == 1) return;
  // an orthonormal basis t1, t2 of the plane normal to n
  const Eigen::Vector3d N(n[0], n[1], n[2]), t1 = N.unitOrthogonal(), t2 = N.cross(t1);
  double vn[kMax], wn[kMax], vt[2 * kMax], wt[2 * kMax];
  for (int i = 0; i < nb; ++i) {
    const Eigen::Vector3d x(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    vn[i] = x.dot(N);
    vt[2 * i] = x.dot(t1);
    vt[2 * i + 1] = x.dot(t2);
  }
  // the normal step is the 2D kernel's on the normal components alone (no tangential motion,
  // no friction): one implementation of the stack's normal contact for both dimensions
  {
    double v2[2 * kMax];
    StackFace f2[kMax];
    StackFaceResult r2[kMax];
    for (int i = 0; i < nb; ++i) {
      v2[2 * i] = 0;
      v2[2 * i + 1] = vn[i];
    }
    for (int k = 0; k + 1 < nb; ++k) f2[k] = {faces[k].type, 0.0, 0.0};
    const double n2[2] = {0, 1};
    contact_stack(nb, m, v2, f2, n2, r2);
    for (int i = 0; i < nb; ++i) wn[i] = v2[2 * i + 1];
    for (int k = 0; k + 1 < nb; ++k) {
      res[k].normal = r2[k].normal;
      res[k].contact = r2[k].contact;
    }
  }
  double cap[kMax], S[2 * kMax];
  FaceState st[kMax];
  for (int k = 0; k < nb - 1; ++k) {
    const StackFace &f = faces[k];
    cap[k] = f.type == FaceType::Bonded ? std::numeric_limits<double>::infinity()
             : res[k].contact           ? f.mu * std::max(res[k].normal, 0.0) + f.adhesion
                                        : 0.0;
  }
  for (int i = 0; i < 2 * nb; ++i) wt[i] = vt[i];
  const bool exact = stack_friction_cone(nb, m, wt, cap, S, st);
  if (fallback) *fallback = !exact;
  for (int k = 0; k < nb - 1; ++k) {
    const Eigen::Vector3d s = S[2 * k] * t1 + S[2 * k + 1] * t2;
    for (int d = 0; d < 3; ++d) res[k].tangential[d] = s[d];
    res[k].slip = res[k].contact && st[k] != FaceState::Stick;
  }
  for (int i = 0; i < nb; ++i)
    if (wn[i] != vn[i] || wt[2 * i] != vt[2 * i] || wt[2 * i + 1] != vt[2 * i + 1]) {
      const Eigen::Vector3d x = wn[i] * N + wt[2 * i] * t1 + wt[2 * i + 1] * t2;
      for (int d = 0; d < 3; ++d) v[3 * i + d] = x[d];
    }
}

} // namespace pmpm
