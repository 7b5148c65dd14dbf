// Membrane chains under -solver newton (chain_implicit.hpp): plain kernels over the points.
#include "pmpm/solvers/chain_implicit.hpp"
#include <cmath>

namespace pmpm {

int chain_stencil(const Chain &c, const GridView &G, const Grid &grid, ChainStencil &S) {
  S.mapped.assign(c.n, 0);
  S.moves.assign(c.n, 1);
  S.W.resize(c.n);
  int mapped = 0;
  for (int i = 0; i < c.n; ++i) {
    S.mapped[i] = chain_point_weights(c, i, G, grid, S.W[i]);
    S.moves[i] = !((i == 0 && c.pin[0]) || (i == c.n - 1 && c.pin[1]));
    mapped += S.mapped[i];
  }
  S.project = c.strain_projection;
  if (S.project) {
    chain_projection(c, c.x.data(), S.proj);
    const int nn = static_cast<int>(S.proj.mass.size()), ns = c.n - 1;
    S.nstart.assign(nn + 1, 0);
    for (int q = 0; q < S.proj.start[ns]; ++q) ++S.nstart[S.proj.node[q] + 1];
    for (int I = 0; I < nn; ++I) S.nstart[I + 1] += S.nstart[I];
    S.nseg.assign(S.proj.start[ns], 0);
    S.nent.assign(S.proj.start[ns], 0);
    std::vector<int> fill(S.nstart.begin(), S.nstart.end() - 1);
    for (int k = 0; k < ns; ++k)
      for (int q = S.proj.start[k]; q < S.proj.start[k + 1]; ++q) {
        const int at = fill[S.proj.node[q]]++;
        S.nseg[at] = k;
        S.nent[at] = q;
      }
    S.wm.assign(static_cast<size_t>(c.n) * UGIMPShape::NS * UGIMPShape::NS * DIM, 0.0);
  }
  return mapped;
}

void chain_stencil_mask(ChainStencil &S, const NodalView &mask) {
  constexpr int NS = UGIMPShape::NS, NN = NS * NS;
  const int n = static_cast<int>(S.mapped.size());
  S.wm.assign(static_cast<size_t>(n) * NN * DIM, 0.0);
  for (int i = 0; i < n; ++i) {
    if (!S.mapped[i]) continue;
    const Weights<UGIMPShape> &W = S.W[i];
    for (int k = 0; k < NN; ++k) {
      if (W.w[k] == 0.0) continue;
      const double *m = mask.node(W.base[0] + k % NS, W.base[1] + k / NS);
      for (int e = 0; e < DIM; ++e)
        S.wm[(static_cast<size_t>(i) * NN + k) * DIM + e] = W.w[k] * m[e];
    }
  }
}

void chain_point_increment(const ChainStencil &S, const NodalView &U, const NodalView &mask,
                           double *du) {
  constexpr int NS = UGIMPShape::NS, NN = NS * NS;
  const int n = static_cast<int>(S.mapped.size());
  for (int i = 0; i < n; ++i) {
    double d[DIM] = {0, 0};
    if (S.mapped[i]) {
      const Weights<UGIMPShape> &W = S.W[i];
      for (int k = 0; k < NN; ++k) {
        if (W.w[k] == 0.0) continue;
        const PetscInt a = W.base[0] + k % NS, b = W.base[1] + k / NS;
        const double *u = U.node(a, b), *m = mask.node(a, b);
        for (int e = 0; e < DIM; ++e) d[e] += W.w[k] * m[e] * u[e];
      }
    }
    for (int e = 0; e < DIM; ++e) du[i * DIM + e] = d[e];
  }
}

void chain_trial(const Chain &c, const ChainStencil &S, const double *du, ChainTrial &t) {
  const int n = c.n, ns = n - 1;
  t.x.resize(static_cast<size_t>(n) * DIM);
  for (size_t q = 0; q < t.x.size(); ++q) t.x[q] = c.x[q] + du[q];
  t.eps.assign(ns, 0.0);
  t.eps_p.assign(c.eps_p.begin(), c.eps_p.end());
  t.alpha.assign(c.alpha.begin(), c.alpha.end());
  t.T.assign(ns, 0.0);
  t.dT.assign(ns, 0.0);
  t.f.assign(static_cast<size_t>(n) * DIM, 0.0);
  for (int k = 0; k < ns; ++k) {
    const double dx = t.x[(k + 1) * DIM] - t.x[k * DIM],
                 dy = t.x[(k + 1) * DIM + 1] - t.x[k * DIM + 1];
    t.eps[k] = std::hypot(dx, dy) / c.l0[k] - 1.0;
  }
  if (S.project) chain_project(c, S.proj, t.eps.data(), t.eps.data());
  for (int k = 0; k < ns; ++k) {
    const double dx = t.x[(k + 1) * DIM] - t.x[k * DIM],
                 dy = t.x[(k + 1) * DIM + 1] - t.x[k * DIM + 1], l = std::hypot(dx, dy);
    bool slack = false;
    t.dT[k] = c.law.tangent(t.eps[k], c.eps_p[k], c.alpha[k]);
    t.T[k] = c.law.tension(t.eps[k], t.eps_p[k], t.alpha[k], slack);
    const double fx = t.T[k] * dx / l, fy = t.T[k] * dy / l;
    t.f[k * DIM] += fx;
    t.f[k * DIM + 1] += fy;
    t.f[(k + 1) * DIM] -= fx;
    t.f[(k + 1) * DIM + 1] -= fy;
  }
}

void chain_internal_force(const ChainStencil &S, const ChainTrial &t, const NodalView &R) {
  constexpr int NS = UGIMPShape::NS, NN = NS * NS;
  const int n = static_cast<int>(S.mapped.size());
  for (int i = 0; i < n; ++i) {
    if (!S.mapped[i]) continue;
    const Weights<UGIMPShape> &W = S.W[i];
    for (int k = 0; k < NN; ++k) {
      if (W.w[k] == 0.0) continue;
      double *r = R.node(W.base[0] + k % NS, W.base[1] + k / NS);
      for (int e = 0; e < DIM; ++e) r[e] -= W.w[k] * t.f[i * DIM + e];
    }
  }
}

int chain_stiffness(const Chain &c, const ChainStencil &S, const ChainTrial &t,
                    const NodeBlocks &B) {
  constexpr int NS = UGIMPShape::NS, NN = NS * NS;
  int missed = 0;
  auto inside = [&](PetscInt a, PetscInt b) {
    return a >= B.gs[0] && a < B.gs[0] + B.gm[0] && b >= B.gs[1] && b < B.gs[1] + B.gm[1];
  };
  for (int s = 0; s + 1 < c.n; ++s) {
    const int pts[2] = {s, s + 1};
    if (!S.mapped[s] && !S.mapped[s + 1]) continue;
    const double dx = t.x[(s + 1) * DIM] - t.x[s * DIM],
                 dy = t.x[(s + 1) * DIM + 1] - t.x[s * DIM + 1], l = std::hypot(dx, dy);
    const double n[DIM] = {dx / l, dy / l}, kg = t.T[s] / l;
    const double km = S.project ? 0.0 : t.dT[s] / c.l0[s]; // projected: chain_projected_coupling
    double K[DIM * DIM];
    for (int a = 0; a < DIM; ++a)
      for (int b = 0; b < DIM; ++b)
        K[a * DIM + b] = km * n[a] * n[b] + kg * ((a == b ? 1.0 : 0.0) - n[a] * n[b]);
    for (int pi = 0; pi < 2; ++pi) {
      const int p = pts[pi];
      if (!S.mapped[p]) continue;
      const Weights<UGIMPShape> &Wp = S.W[p];
      for (int qi = 0; qi < 2; ++qi) {
        const int q = pts[qi];
        if (!S.moves[q]) continue;
        const Weights<UGIMPShape> &Wq = S.W[q];
        const double sign = p == q ? 1.0 : -1.0;
        for (int k = 0; k < NN; ++k) {
          if (Wp.w[k] == 0.0) continue;
          const PetscInt i = Wp.base[0] + k % NS, j = Wp.base[1] + k / NS;
          for (int m = 0; m < NN; ++m) {
            if (Wq.w[m] == 0.0) continue;
            const PetscInt ii = Wq.base[0] + m % NS, jj = Wq.base[1] + m / NS;
            const PetscInt di = ii - i, dj = jj - j;
            if (!inside(i, j) || !inside(ii, jj) || std::abs(di) > B.w || std::abs(dj) > B.w) {
              ++missed;
              continue;
            }
            double *blk = B.block(i, j, static_cast<int>(di), static_cast<int>(dj));
            const double w = sign * Wp.w[k] * Wq.w[m];
            for (int q2 = 0; q2 < DIM * DIM; ++q2) blk[q2] += w * K[q2];
          }
        }
      }
    }
  }
  return missed;
}

namespace {
void add_dof(std::vector<ChainDofValue> &v, PetscInt i, PetscInt j, int d, double x) {
  for (ChainDofValue &e : v)
    if (e.i == i && e.j == j && e.d == d) {
      e.v += x;
      return;
    }
  v.push_back(ChainDofValue{i, j, d, x});
}
} // namespace

double chain_projected_coupling(const Chain &, const ChainStencil &S, const ChainTrial &t, int I,
                                std::vector<ChainDofValue> &a, std::vector<ChainDofValue> &b) {
  constexpr int NS = UGIMPShape::NS, NN = NS * NS;
  a.clear();
  b.clear();
  for (int e = S.nstart[I]; e < S.nstart[I + 1]; ++e) {
    const int k = S.nseg[e];
    const double w = S.proj.w[S.nent[e]];
    const double dx = t.x[(k + 1) * DIM] - t.x[k * DIM],
                 dy = t.x[(k + 1) * DIM + 1] - t.x[k * DIM + 1], l = std::hypot(dx, dy);
    const double n[DIM] = {dx / l, dy / l};
    for (int end = 0; end < 2; ++end) {
      const int p = k + end;
      const double s = end == 0 ? -1.0 : 1.0;
      const Weights<UGIMPShape> &W = S.W[p];
      if (S.mapped[p] && t.dT[k] != 0.0)
        for (int m = 0; m < NN; ++m) {
          if (W.w[m] == 0.0) continue;
          for (int d = 0; d < DIM; ++d)
            add_dof(a, W.base[0] + m % NS, W.base[1] + m / NS, d, W.w[m] * t.dT[k] * w * s * n[d]);
        }
      if (S.moves[p])
        for (int m = 0; m < NN; ++m) {
          if (W.w[m] == 0.0) continue;
          for (int d = 0; d < DIM; ++d) {
            const double wm = S.wm[(static_cast<size_t>(p) * NN + m) * DIM + d];
            if (wm != 0.0) add_dof(b, W.base[0] + m % NS, W.base[1] + m / NS, d, wm * w * s * n[d]);
          }
        }
    }
  }
  return S.proj.mass[I];
}

} // namespace pmpm
