// A lean plain-array 3D explicit MPM loop (issue 22): the same problem and the same arithmetic as
// pmpm's -dim 3 step on the extruded column, in one file, one thread, no PETSc, to measure how far
// pmpm's 3D step is from a plain loop, phase by phase (bench/lean3d.py runs both).
//
//   g++ -O3 -march=native -DNDEBUG -std=c++17 -o lean3d bench/lean3d.cpp
//   lean3d -cell_size 0.015625 -column_width 1 -depth 0.5 -ramp_steps 10 -max_steps 20
//
// The problem is generated as pmpm generates it (options/column.opts, src/scenes/column.cpp,
// src/model/extrude.cpp): cells of size h, the box nW x (nH + 2) x nD cells from the origin, ppc^2
// particles a plane cell (FillRegular: j, i, b, a loops), each extruded into ppc particles a z
// cell (z fastest), half-sizes dx / 2, volume dx^2 dz, mass density V with the inertia scaled to
// the wave speed (SetInertia: rho = M / c^2, c = sqrt(M / (gamma / 9.81))), weight gamma V.
// Faces: rollers on x and z, the base fixed, the top free. One step is src/step/cycle.cpp's, in
// its order, with the column's defaults (FLIP with -pic 0.05, kinetic damping, no local damping,
// -cfl 0.5):
//   P2G     the grid zeroed; uGIMP weights of each particle's block (UGIMPShape::eval1d, the
//           stencil trimmed to 2 nodes a direction where the block ends inside a cell, as
//           pmpm's); mass, momentum, force w f_body - V sigma . grad w, external force
//   grid    v = p / m, a = f / m, v += dt a on the box's nodes with mass, held dofs zeroed; the
//           unbalanced force (largest |f| over the free dofs, mean |f_ext|), the nodal kinetic
//           energy; the two ghost layers outside the box zeroed (pmpm's GhostScatter on 1 rank:
//           timed under "rest", as there)
//   G2P     v <- (1 - pic)(v + dt sum w a) + pic sum w v, x += dt sum w v, L = sum v (x) grad w,
//           dudx = L dt written, F <- (I + L dt) F, V = det F V0; the kinetic energy, the weight's
//           power, the largest wave speed and speed (the next dt), the J > 0 / finite / on-grid
//           checks
//   stress  linear elastic in Jaumann rate form on the 6 components: s + W s - s W + lambda
//           tr(de) I + 2 G de (de, W the symmetric and skew parts of dudx)
//   rest    kinetic damping (velocities zeroed when the particles' kinetic energy fell), the
//           next dt = cfl h / (max c + max |v|), the ghost layers
// Data: one std::vector per particle field with the field's D or D x D values together (pmpm's
// DMSwarm layout: each phase streams only the fields it needs, about 15 streams; one struct a
// particle would drag F through P2G and the stress through G2P, and an array per component
// would need ~40 streams); the grid one array of nodes, x fastest, two ghost layers a side as
// pmpm's DMDA, each node's values together (a P2G stencil row is then one run of memory).
// Particles in pmpm's order (plane particle by plane particle, z fastest): sorting them into the
// grid's cell order or putting the arrays on 2 MB pages changed the step by 5 % at most
// (measured while writing this: 96-99 against 101 ms a step at -node 8), so neither is done.
//
// Variants (same results to round-off; bench/lean3d.py times them beside the default):
//   -node 10  (default) pmpm's node, 10 values (M, P, F, FEXT), and its scalar arithmetic (P2G,
//             grid update and G2P in pmpm's order of operations; the stress update written out
//             on 6 components where pmpm multiplies 3 x 3 Eigen matrices): the same work as
//             plain loops
//   -node 8   8 values a node, one vector (64 bytes, 64-byte aligned): the external force kept as
//             one scalar, the sum of w x weight, gravity added to the force in the grid update
//             (pmpm scatters 3 external-force and 3 gravity components); a node then takes two
//             vector FMAs in P2G and two in G2P (the tensor-product factors taken a plane and a
//             row at a time)
//   -fuse     the stress update inside G2P (no dudx written and read back; pmpm fuses it in 2D)
//   -stencil27  3 x 3 x 3 nodes for every particle (zero weights added): the cost of blocks that
//             straddle cell faces in all three directions (the column's touch 10 on average)
// Output: one "key value" line each (read by bench/lean3d.py); -dump FILE writes the final state
// (ids as pmpm's, positions, velocities, stresses, F, volumes) for the check against pmpm.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>
#include <sys/resource.h>

namespace {

// 64-byte aligned storage for std::vector (a node of 8 doubles is then one cache line)
template <class T> struct Aligned {
  using value_type = T;
  Aligned() = default;
  template <class U> Aligned(const Aligned<U> &) {}
  T *allocate(size_t n) {
    void *p = std::aligned_alloc(64, ((n * sizeof(T) + 63) / 64) * 64);
    if (!p) throw std::bad_alloc();
    return static_cast<T *>(p);
  }
  void deallocate(T *p, size_t) { std::free(p); }
  template <class U> bool operator==(const Aligned<U> &) const { return true; }
  template <class U> bool operator!=(const Aligned<U> &) const { return false; }
};
template <class T> using vec = std::vector<T, Aligned<T>>;

struct Options {
  double h = 0.03125, width = -1, height = 1.0, depth = 0;
  int ppc = 2;
  double E = 1e7, nu = 0.3, gamma = 2e4;
  int ramp_steps = 500, max_steps = 20;
  double cfl = 0.5, pic = 0.05;
  int node = 10;
  bool fuse = false, full = false;
  std::string dump;
};

[[noreturn]] void die(const std::string &m) {
  std::fprintf(stderr, "lean3d: %s\n", m.c_str());
  std::exit(2);
}

Options parse(int argc, char **argv) {
  Options o;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    auto val = [&]() -> const char * {
      if (k + 1 >= argc) die(a + " needs a value");
      return argv[++k];
    };
    if (a == "-cell_size")
      o.h = std::atof(val());
    else if (a == "-column_width")
      o.width = std::atof(val());
    else if (a == "-column_height")
      o.height = std::atof(val());
    else if (a == "-depth")
      o.depth = std::atof(val());
    else if (a == "-ppc")
      o.ppc = std::atoi(val());
    else if (a == "-mat_column_E")
      o.E = std::atof(val());
    else if (a == "-mat_column_nu")
      o.nu = std::atof(val());
    else if (a == "-mat_column_gamma")
      o.gamma = std::atof(val());
    else if (a == "-ramp_steps")
      o.ramp_steps = std::atoi(val());
    else if (a == "-max_steps")
      o.max_steps = std::atoi(val());
    else if (a == "-cfl")
      o.cfl = std::atof(val());
    else if (a == "-pic")
      o.pic = std::atof(val());
    else if (a == "-node")
      o.node = std::atoi(val());
    else if (a == "-fuse")
      o.fuse = true;
    else if (a == "-stencil27")
      o.full = true;
    else if (a == "-dump")
      o.dump = val();
    else
      die("unknown option " + a);
  }
  if (o.width <= 0) o.width = 4 * o.h; // the column's default width: 4 cells
  if (!(o.depth > 0)) die("-depth D (m) is required");
  if (o.node != 8 && o.node != 10) die("-node is 8 or 10");
  return o;
}

// a length in whole cells (pmpm's CheckCells)
int cells(double len, double h, const char *what) {
  const double r = len / h;
  const long n = std::lround(r);
  if (n < 1 || std::fabs(r - n) > 1e-9 * r)
    die(std::string(what) + " is not a whole number of cells");
  return static_cast<int>(n);
}

// ---- the problem -------------------------------------------------------------------------------

struct Material {
  double M, lam, G2, density;
};

struct Particles {
  long n = 0;
  vec<double> x, x0, v, lp, F, stress, dudx; // 3, 3, 3, 3, 9, 6, 9 a particle
  vec<double> mass, vol, vol0, weight;       // 1 a particle
  vec<int> mat;                              // material index
  vec<long> pid;                             // pmpm's id (only for -dump)
};

constexpr int G0 = 2; // ghost layers a side (pmpm's DMDA stencil width)

struct Grid {
  double h = 0, invh = 0, origin[3] = {0, 0, 0};
  int ncell[3] = {0, 0, 0};
  long gm[3] = {0, 0, 0}; // ghosted nodes a direction
  int nd = 10;            // doubles a node
  vec<double> data;
  double *node(long i, long j, long k) {
    return data.data() + (((k + G0) * gm[1] + (j + G0)) * gm[0] + (i + G0)) * nd;
  }
  long row() const { return gm[0] * nd; }
  long plane() const { return gm[1] * gm[0] * nd; }
};

// held dofs of a box face: 0 free, 1 roller (the normal dof), 2 fixed (all)
// XMIN, XMAX, YMIN, YMAX, ZMIN, ZMAX as the column's: rollers, fixed base, free top, rollers
constexpr int kFace[6] = {1, 1, 2, 0, 1, 1};

void setup(const Options &o, Grid &g, Particles &P, Material &mat) {
  const double h = o.h;
  const int nW = cells(o.width, h, "-column_width"), nH = cells(o.height, h, "-column_height");
  const int nD = cells(o.depth, h, "-depth");
  g.h = h;
  g.invh = 1.0 / h;
  g.ncell[0] = nW;
  g.ncell[1] = nH + 2;
  g.ncell[2] = nD;
  for (int d = 0; d < 3; ++d) g.gm[d] = g.ncell[d] + 1 + 2 * G0;
  g.data.assign(g.gm[0] * g.gm[1] * g.gm[2] * g.nd, 0.0);
  // the material (ElasticConstants, SetInertia with -inertia_scaling wavespeed, one material)
  const double E = o.E, nu = o.nu;
  mat.M = E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
  mat.lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  mat.G2 = 2.0 * (E / (2.0 * (1.0 + nu)));
  const double rho0 = o.gamma / 9.81, c = std::sqrt(mat.M / rho0);
  mat.density = mat.M / (c * c);
  // FillRegular over the plane, then each plane particle into ppc particles a z cell
  const int ppc = o.ppc;
  const double dx = h / ppc, dz = h / ppc;
  const long nz = static_cast<long>(nD) * ppc;
  long nplane = 0;
  for (int j = 0; j < g.ncell[1]; ++j)
    for (int i = 0; i < g.ncell[0]; ++i)
      for (int b = 0; b < ppc; ++b)
        for (int a = 0; a < ppc; ++a) {
          const double x = 0.0 + i * h + (a + 0.5) * dx, y = 0.0 + j * h + (b + 0.5) * dx;
          if (x < o.width && y < o.height) ++nplane;
        }
  const long n = nplane * nz;
  P.n = n;
  P.x.resize(3 * n);
  P.v.assign(3 * n, 0.0);
  P.lp.resize(3 * n);
  P.F.resize(9 * n);
  P.stress.assign(6 * n, 0.0);
  P.dudx.assign(o.fuse ? 0 : 9 * n, 0.0);
  P.mass.resize(n);
  P.vol.resize(n);
  P.vol0.resize(n);
  P.weight.resize(n);
  P.mat.assign(n, 0);
  P.pid.resize(n);
  long p = 0;
  for (int j = 0; j < g.ncell[1]; ++j)
    for (int i = 0; i < g.ncell[0]; ++i)
      for (int b = 0; b < ppc; ++b)
        for (int a = 0; a < ppc; ++a) {
          const double x = 0.0 + i * h + (a + 0.5) * dx, y = 0.0 + j * h + (b + 0.5) * dx;
          if (!(x < o.width && y < o.height)) continue;
          const long pid2 = ((static_cast<long>(j) * g.ncell[0] + i) * ppc + b) * ppc + a;
          const double vol = dx * dx * dz; // the plane's dx^2, times the z spacing
          for (long k = 0; k < nz; ++k, ++p) {
            P.x[3 * p] = x;
            P.x[3 * p + 1] = y;
            P.x[3 * p + 2] = 0.0 + (k + 0.5) * dz;
            P.lp[3 * p] = P.lp[3 * p + 1] = 0.5 * dx;
            P.lp[3 * p + 2] = 0.5 * dz;
            for (int q = 0; q < 9; ++q) P.F[9 * p + q] = q % 4 == 0 ? 1.0 : 0.0;
            P.mass[p] = mat.density * vol;
            P.vol[p] = P.vol0[p] = vol;
            P.weight[p] = o.gamma * vol;
            P.pid[p] = pid2 * nz + k;
          }
        }
  P.x0 = P.x;
}

// ---- uGIMP weights ----------------------------------------------------------------------------

// UGIMPShape::eval1d (include/pmpm/core/shape.hpp), written out: the block [xi - li, xi + li]
// (cell units) in the coordinates of its first cell, the three hats integrated piecewise,
// branch-free. Returns whether the block reaches into the next cell (3 nodes, else 2).
inline bool eval1d(double xi, double li, int &base, double w[3], double dw[3]) {
  const double lo = xi - li;
  base = static_cast<int>(std::floor(lo));
  const double a = lo - base, b = a + 2.0 * li, inv = 0.5 / li;
  const double c = b < 1.0 ? b : 1.0;
  const double e = b > 1.0 ? b - 1.0 : 0.0;
  const double half = 0.5 * (c * c - a * a), e2 = 0.5 * e * e;
  const double I0 = (c - a) - half, I1 = half + (e - e2), I2 = e2;
  const double N0b = 1.0 - c, N1b = c - e, N2b = e;
  w[0] = I0 * inv;
  w[1] = I1 * inv;
  w[2] = I2 * inv;
  dw[0] = (N0b - (1.0 - a)) * inv;
  dw[1] = (N1b - a) * inv;
  dw[2] = N2b * inv;
  return e > 0.0; // the third weight and gradient are zero otherwise (pmpm trims them)
}

struct Stencil {
  double w[3][3], dw[3][3]; // per direction: weights, gradients per metre
  int n[3];                 // nodes a direction: 2, or 3 where the block reaches the next cell
  long off;                 // offset of the first node (doubles)
};

// full: 3 nodes a direction always (the zeros added: the cost of a block straddling in 3D)
inline void stencil(const Grid &g, const double *x, const double *l, bool full, Stencil &S) {
  int base[3];
  for (int d = 0; d < 3; ++d) {
    const bool three =
        eval1d((x[d] - g.origin[d]) * g.invh, l[d] * g.invh, base[d], S.w[d], S.dw[d]);
    S.n[d] = three || full ? 3 : 2;
    for (int a = 0; a < 3; ++a) S.dw[d][a] *= g.invh;
  }
  S.off = (((base[2] + G0) * g.gm[1] + (base[1] + G0)) * g.gm[0] + (base[0] + G0)) * g.nd;
}

// ---- P2G ----------------------------------------------------------------------------------------

struct P2GIn {
  double m, mv[3], Vs[3][3], fb[3], wt; // mass, momentum, V sigma, body force, weight x factor
};

// One particle's block of n[0] x n[1] x n[2] nodes (loops of 2 or 3: GCC's code for them was
// faster than 8 kernels unrolled for each size: P2G 67-70 against 81-83 ms a step at 1 M). ND 10:
// M, P(3), F(3), FEXT(3), the body force in F and FEXT as pmpm's; ND 8: M, P(3), F(3), W (sum w x
// weight; the grid update adds gravity).
template <int ND>
__attribute__((always_inline)) inline void scatter(double *n0, long row, long plane,
                                                   const Stencil &S, const P2GIn &q) {
  const int NX = S.n[0], NY = S.n[1], NZ = S.n[2];
#pragma GCC unroll 3
  for (int c = 0; c < NZ; ++c)
#pragma GCC unroll 3
    for (int b = 0; b < NY; ++b) {
      const double wo = S.w[1][b] * S.w[2][c], go1 = S.dw[1][b] * S.w[2][c],
                   go2 = S.w[1][b] * S.dw[2][c];
      double *r = n0 + b * row + c * plane;
#pragma GCC unroll 3
      for (int a = 0; a < NX; ++a) {
        double *nd = r + a * ND;
        const double wa = S.w[0][a], w = wa * wo;
        const double g0 = S.dw[0][a] * wo, g1 = wa * go1, g2 = wa * go2;
        nd[0] += w * q.m;
        for (int d = 0; d < 3; ++d) nd[1 + d] += w * q.mv[d];
        for (int d = 0; d < 3; ++d) {
          const double t = q.Vs[d][0] * g0 + q.Vs[d][1] * g1 + q.Vs[d][2] * g2;
          if constexpr (ND == 10)
            nd[4 + d] += w * q.fb[d] - t;
          else
            nd[4 + d] -= t;
        }
        if constexpr (ND == 10)
          for (int d = 0; d < 3; ++d) nd[7 + d] += w * q.fb[d];
        else
          nd[7] += w * q.wt;
      }
    }
}

// -node 8: a node is one vector of 8 doubles (GCC's vector extension: one AVX-512 register, or
// two AVX2 ones), M, P(3), F(3), W. Node (a, b, c) gets w q_A + sum_e g_e q_Be with
// q_A = (m, m v, 0, 0, 0, weight) and q_Be = (0, 0, 0, 0, -V sigma_(., e), 0); the tensor-product
// factors are taken a plane and a row at a time, so a node costs two vector FMAs.
typedef double v8 __attribute__((vector_size(64)));

__attribute__((always_inline)) inline void scatter8(double *n0, long row, long plane,
                                                    const Stencil &S, v8 A, v8 B0, v8 B1, v8 B2) {
  const int NX = S.n[0], NY = S.n[1], NZ = S.n[2];
#pragma GCC unroll 3
  for (int c = 0; c < NZ; ++c) {
    const v8 X = S.w[2][c] * A + S.dw[2][c] * B2, Y = S.w[2][c] * B1, Z = S.w[2][c] * B0;
#pragma GCC unroll 3
    for (int b = 0; b < NY; ++b) {
      const v8 R = S.w[1][b] * X + S.dw[1][b] * Y, Q = S.w[1][b] * Z;
      v8 *r = reinterpret_cast<v8 *>(n0 + b * row + c * plane);
#pragma GCC unroll 3
      for (int a = 0; a < NX; ++a) r[a] += S.w[0][a] * R + S.dw[0][a] * Q;
    }
  }
}

template <int ND>
long p2g(Grid &g, const Particles &P, double factor, const double gdir[3], bool full) {
  std::memset(g.data.data(), 0, g.data.size() * sizeof(double));
  const long row = g.row(), plane = g.plane();
  double *data = g.data.data();
  long touched = 0;
  Stencil S;
  P2GIn q;
  for (long p = 0; p < P.n; ++p) {
    stencil(g, &P.x[3 * p], &P.lp[3 * p], full, S);
    const double m = P.mass[p], V = P.vol[p], *s = &P.stress[6 * p], *v = &P.v[3 * p];
    q.m = m;
    for (int d = 0; d < 3; ++d) q.mv[d] = m * v[d];
    // V sigma (xx yy zz xy yz xz)
    q.Vs[0][0] = V * s[0];
    q.Vs[1][1] = V * s[1];
    q.Vs[2][2] = V * s[2];
    q.Vs[0][1] = q.Vs[1][0] = V * s[3];
    q.Vs[1][2] = q.Vs[2][1] = V * s[4];
    q.Vs[0][2] = q.Vs[2][0] = V * s[5];
    for (int d = 0; d < 3; ++d) q.fb[d] = factor * P.weight[p] * gdir[d];
    q.wt = P.weight[p];
    double *n0 = data + S.off;
    if constexpr (ND == 8) {
      const v8 A = {m, q.mv[0], q.mv[1], q.mv[2], 0, 0, 0, q.wt};
      const v8 B0 = {0, 0, 0, 0, -q.Vs[0][0], -q.Vs[1][0], -q.Vs[2][0], 0};
      const v8 B1 = {0, 0, 0, 0, -q.Vs[0][1], -q.Vs[1][1], -q.Vs[2][1], 0};
      const v8 B2 = {0, 0, 0, 0, -q.Vs[0][2], -q.Vs[1][2], -q.Vs[2][2], 0};
      scatter8(n0, row, plane, S, A, B0, B1, B2);
    } else {
      scatter<ND>(n0, row, plane, S, q);
    }
    touched += S.n[0] * S.n[1] * S.n[2];
  }
  return touched;
}

// ---- grid update --------------------------------------------------------------------------------

struct GridStats {
  double max_unbalanced = 0, sum_ext = 0, n_ext = 0, kinetic = 0;
};

template <int ND> GridStats grid_update(Grid &g, double dt, double factor, const double gdir[3]) {
  GridStats st;
  const int *nc = g.ncell;
  for (long k = 0; k <= nc[2]; ++k)
    for (long j = 0; j <= nc[1]; ++j) {
      // held dofs of this row's nodes from the y and z faces; the x faces at its ends
      bool hrow[3] = {false, false, false};
      const long jk[2] = {j, k};
      for (int e = 1; e < 3; ++e)
        for (int side = 0; side < 2; ++side) {
          const int f = 2 * e + side;
          if (kFace[f] == 0 || jk[e - 1] != (side ? nc[e] : 0)) continue;
          if (kFace[f] == 2)
            hrow[0] = hrow[1] = hrow[2] = true;
          else
            hrow[e] = true;
        }
      double *nd = g.node(0, j, k);
      for (long i = 0; i <= nc[0]; ++i, nd += ND) {
        const double m = nd[0];
        if (m <= 0.0) continue;
        bool held[3] = {hrow[0], hrow[1], hrow[2]};
        for (int side = 0; side < 2; ++side) {
          const int f = side;
          if (kFace[f] == 0 || i != (side ? nc[0] : 0)) continue;
          if (kFace[f] == 2)
            held[0] = held[1] = held[2] = true;
          else
            held[0] = true;
        }
        double f[3], fext[3];
        for (int d = 0; d < 3; ++d) {
          if constexpr (ND == 10) {
            f[d] = nd[4 + d];
            fext[d] = nd[7 + d];
          } else {
            fext[d] = factor * gdir[d] * nd[7];
            f[d] = nd[4 + d] + fext[d];
          }
        }
        const double fext2 = fext[0] * fext[0] + fext[1] * fext[1] + fext[2] * fext[2];
        if (fext2 > 0.0) {
          st.sum_ext += std::sqrt(fext2);
          st.n_ext += 1.0;
        }
        double f2 = 0.0;
        for (int d = 0; d < 3; ++d)
          if (!held[d]) f2 += f[d] * f[d];
        const double fn = std::sqrt(f2);
        st.max_unbalanced = fn > st.max_unbalanced ? fn : st.max_unbalanced;
        for (int d = 0; d < 3; ++d) {
          if (held[d]) {
            nd[1 + d] = 0.0;
            nd[4 + d] = 0.0;
            continue;
          }
          double v = nd[1 + d] / m;
          const double a = f[d] / m;
          v += dt * a;
          nd[1 + d] = v;
          nd[4 + d] = a;
          st.kinetic += 0.5 * m * v * v;
        }
      }
    }
  return st;
}

// The nodes outside the box hold P2G's sums: G2P must read v = a = 0 there (pmpm's GhostScatter).
void zero_ghosts(Grid &g) {
  const long nx = g.gm[0], nd = g.nd;
  for (long k = -G0; k < g.gm[2] - G0; ++k)
    for (long j = -G0; j < g.gm[1] - G0; ++j) {
      double *row = g.node(-G0, j, k);
      if (k < 0 || k > g.ncell[2] || j < 0 || j > g.ncell[1]) {
        std::memset(row, 0, nx * nd * sizeof(double));
      } else {
        std::memset(row, 0, G0 * nd * sizeof(double));
        std::memset(row + (g.ncell[0] + 1 + G0) * nd, 0,
                    (nx - g.ncell[0] - 1 - G0) * nd * sizeof(double));
      }
    }
}

// ---- G2P and the stress update ------------------------------------------------------------------

template <int ND>
__attribute__((always_inline)) inline void gather(const double *n0, long row, long plane,
                                                  const Stencil &S, double vg[3], double ag[3],
                                                  double L[9]) {
  const int NX = S.n[0], NY = S.n[1], NZ = S.n[2];
#pragma GCC unroll 3
  for (int c = 0; c < NZ; ++c)
#pragma GCC unroll 3
    for (int b = 0; b < NY; ++b) {
      const double wo = S.w[1][b] * S.w[2][c], go1 = S.dw[1][b] * S.w[2][c],
                   go2 = S.w[1][b] * S.dw[2][c];
      const double *r = n0 + b * row + c * plane;
#pragma GCC unroll 3
      for (int a = 0; a < NX; ++a) {
        const double *nd = r + a * ND;
        const double wa = S.w[0][a], w = wa * wo;
        const double g[3] = {S.dw[0][a] * wo, wa * go1, wa * go2};
        for (int d = 0; d < 3; ++d) vg[d] += w * nd[1 + d];
        for (int d = 0; d < 3; ++d) ag[d] += w * nd[4 + d];
        for (int d = 0; d < 3; ++d)
          for (int e = 0; e < 3; ++e) L[d * 3 + e] += nd[1 + d] * g[e];
      }
    }
}

// -node 8: per row the x sums of w n and dw n (vectors), then acc += wo (w n), L_e += g_e n: the
// lanes of acc are (sum w m, v, a, W), L_e's lanes 1-3 the column e of L.
__attribute__((always_inline)) inline void
gather8(const double *n0, long row, long plane, const Stencil &S, v8 &acc, v8 &L0, v8 &L1, v8 &L2) {
  const int NX = S.n[0], NY = S.n[1], NZ = S.n[2];
#pragma GCC unroll 3
  for (int c = 0; c < NZ; ++c)
#pragma GCC unroll 3
    for (int b = 0; b < NY; ++b) {
      const v8 *r = reinterpret_cast<const v8 *>(n0 + b * row + c * plane);
      v8 sa = S.w[0][0] * r[0], sd = S.dw[0][0] * r[0];
#pragma GCC unroll 3
      for (int a = 1; a < NX; ++a) {
        sa += S.w[0][a] * r[a];
        sd += S.dw[0][a] * r[a];
      }
      const double wo = S.w[1][b] * S.w[2][c], go1 = S.dw[1][b] * S.w[2][c],
                   go2 = S.w[1][b] * S.dw[2][c];
      acc += wo * sa;
      L0 += wo * sd;
      L1 += go1 * sa;
      L2 += go2 * sa;
    }
}

// Linear elastic, Jaumann rate, on s = (xx yy zz xy yz xz) with g = L dt (row-major):
// s + W s - s W + lambda tr(g) I + 2G sym(g); W s - s W = Q + Q^T with Q = W s.
__attribute__((always_inline)) inline void elastic_jaumann(double lam, double G2, const double *g,
                                                           double *s) {
  const double w01 = 0.5 * (g[1] - g[3]), w02 = 0.5 * (g[2] - g[6]), w12 = 0.5 * (g[5] - g[7]);
  const double sxx = s[0], syy = s[1], szz = s[2], sxy = s[3], syz = s[4], sxz = s[5];
  const double q00 = w01 * sxy + w02 * sxz, q01 = w01 * syy + w02 * syz,
               q02 = w01 * syz + w02 * szz;
  const double q10 = -w01 * sxx + w12 * sxz, q11 = -w01 * sxy + w12 * syz,
               q12 = -w01 * sxz + w12 * szz;
  const double q20 = -w02 * sxx - w12 * sxy, q21 = -w02 * sxy - w12 * syy,
               q22 = -w02 * sxz - w12 * syz;
  const double ltr = lam * (g[0] + g[4] + g[8]);
  s[0] = sxx + 2.0 * q00 + ltr + G2 * g[0];
  s[1] = syy + 2.0 * q11 + ltr + G2 * g[4];
  s[2] = szz + 2.0 * q22 + ltr + G2 * g[8];
  s[3] = sxy + (q01 + q10) + G2 * (0.5 * (g[1] + g[3]));
  s[4] = syz + (q12 + q21) + G2 * (0.5 * (g[5] + g[7]));
  s[5] = sxz + (q02 + q20) + G2 * (0.5 * (g[2] + g[6]));
}

struct G2PStats {
  double c2max = 0, v2max = 0, kinetic = 0, weight_power = 0;
  long bad = 0;
};

template <int ND, bool Fuse>
G2PStats g2p(const Grid &g, Particles &P, const Material *mats, double dt, double pic,
             const double gdir[3], bool full) {
  G2PStats st;
  const long row = g.row(), plane = g.plane();
  const double *data = g.data.data();
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = g.origin[d];
    hi[d] = g.origin[d] + g.ncell[d] * g.h;
  }
  double c2max = 0, v2max = 0, kinetic = 0, wpow = 0;
  long bad = 0;
  Stencil S;
  for (long p = 0; p < P.n; ++p) {
    double *x = &P.x[3 * p], *v = &P.v[3 * p];
    stencil(g, x, &P.lp[3 * p], full, S);
    double vg[3] = {0, 0, 0}, ag[3] = {0, 0, 0}, L[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    const double *n0 = data + S.off;
    if constexpr (ND == 8) {
      v8 acc = {}, L0 = {}, L1 = {}, L2 = {};
      gather8(n0, row, plane, S, acc, L0, L1, L2);
      for (int d = 0; d < 3; ++d) {
        vg[d] = acc[1 + d];
        ag[d] = acc[4 + d];
        L[3 * d] = L0[1 + d];
        L[3 * d + 1] = L1[1 + d];
        L[3 * d + 2] = L2[1 + d];
      }
    } else {
      gather<ND>(n0, row, plane, S, vg, ag, L);
    }
    for (int d = 0; d < 3; ++d) v[d] = (1.0 - pic) * (v[d] + dt * ag[d]) + pic * vg[d];
    for (int d = 0; d < 3; ++d) x[d] += dt * vg[d];
    double du[9];
    for (int k = 0; k < 9; ++k) du[k] = L[k] * dt;
    const Material &mt = mats[P.mat[p]];
    if constexpr (Fuse)
      elastic_jaumann(mt.lam, mt.G2, du, &P.stress[6 * p]);
    else
      for (int k = 0; k < 9; ++k) P.dudx[9 * p + k] = du[k];
    // F <- (I + du) F
    double *F = &P.F[9 * p], F0[9];
    for (int k = 0; k < 9; ++k) F0[k] = F[k];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double t = (i == 0 ? 1.0 + du[i * 3] : du[i * 3]) * F0[j];
        for (int k = 1; k < 3; ++k)
          t += (i == k ? 1.0 + du[i * 3 + k] : du[i * 3 + k]) * F0[k * 3 + j];
        F[i * 3 + j] = t;
      }
    const double J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
                     F[2] * (F[3] * F[7] - F[4] * F[6]);
    P.vol[p] = J * P.vol0[p];
    const double speed2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    kinetic += 0.5 * P.mass[p] * speed2;
    wpow += P.weight[p] * (gdir[0] * v[0] + gdir[1] * v[1] + gdir[2] * v[2]);
    const double xv = x[0] + x[1] + x[2] + v[0] + v[1] + v[2];
    const bool on = x[0] >= lo[0] && x[0] < hi[0] && x[1] >= lo[1] && x[1] < hi[1] &&
                    x[2] >= lo[2] && x[2] < hi[2];
    if (!(J > 0.0) || !std::isfinite(J) || !std::isfinite(xv) || !on) {
      ++bad;
      continue;
    }
    const double c2 = mt.M * P.vol[p] / P.mass[p];
    c2max = c2 > c2max ? c2 : c2max;
    v2max = speed2 > v2max ? speed2 : v2max;
  }
  st.c2max = c2max;
  st.v2max = v2max;
  st.kinetic = kinetic;
  st.weight_power = wpow;
  st.bad = bad;
  return st;
}

void stress_update(Particles &P, const Material *mats) {
  const double *du = P.dudx.data();
  double *s = P.stress.data();
  const int *mat = P.mat.data();
  for (long p = 0; p < P.n; ++p) {
    const Material &mt = mats[mat[p]];
    elastic_jaumann(mt.lam, mt.G2, du + 9 * p, s + 6 * p);
  }
}

// ---- the relaxation loop ------------------------------------------------------------------------

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

template <int ND, bool Fuse> int run(const Options &o) {
  Grid g;
  g.nd = ND;
  Particles P;
  Material mat;
  const auto t_setup = Clock::now();
  setup(o, g, P, mat);
  const double setup_s = seconds(t_setup, Clock::now());
  const double gdir[3] = {0.0, -1.0, 0.0};
  // the first step from the particles' wave speeds (InitialWaveSpeed), then from the last step's
  double c0 = 0;
  for (long p = 0; p < P.n; ++p) c0 = std::fmax(c0, std::sqrt(mat.M * P.vol[p] / P.mass[p]));
  double dt = o.cfl * o.h / c0, time = 0, kinetic_prev = 0, ratio = 0;
  long resets = 0, touched = 0;
  double tp[5] = {0, 0, 0, 0, 0}; // P2G, GridUpdate, G2P, StressUpdate, rest
  const auto t_loop = Clock::now();
  for (int k = 1; k <= o.max_steps; ++k) {
    const double factor = o.ramp_steps > 0 ? std::fmin(1.0, double(k) / o.ramp_steps) : 1.0;
    const auto t0 = Clock::now();
    touched = p2g<ND>(g, P, factor, gdir, o.full);
    const auto t1 = Clock::now();
    const GridStats gs = grid_update<ND>(g, dt, factor, gdir);
    const auto t2 = Clock::now();
    zero_ghosts(g);
    const auto t3 = Clock::now();
    const G2PStats ps = g2p<ND, Fuse>(g, P, &mat, dt, o.pic, gdir, o.full);
    const auto t4 = Clock::now();
    if (!Fuse) stress_update(P, &mat);
    const auto t5 = Clock::now();
    if (ps.bad > 0) die("a particle went bad at step " + std::to_string(k));
    time += dt;
    const double mean_ext = gs.n_ext > 0 ? gs.sum_ext / gs.n_ext : 0.0;
    ratio = mean_ext > 0 ? gs.max_unbalanced / mean_ext : 0.0;
    if (ps.kinetic < kinetic_prev) { // kinetic damping (relaxation.cpp, Damp)
      std::fill(P.v.begin(), P.v.end(), 0.0);
      kinetic_prev = 0;
      ++resets;
    } else {
      kinetic_prev = ps.kinetic;
    }
    dt = o.cfl * o.h / (std::sqrt(ps.c2max) + std::sqrt(ps.v2max));
    const auto t6 = Clock::now();
    tp[0] += seconds(t0, t1);
    tp[1] += seconds(t1, t2);
    tp[2] += seconds(t3, t4);
    tp[3] += seconds(t4, t5);
    tp[4] += seconds(t2, t3) + seconds(t5, t6);
  }
  const double loop_s = seconds(t_loop, Clock::now());
  double syy = 0, uy = 0;
  for (long p = 0; p < P.n; ++p) {
    syy += P.stress[6 * p + 1];
    uy += P.x[3 * p + 1] - P.x0[3 * p + 1];
  }
  const int steps = o.max_steps;
  std::printf("variant node%d%s%s\n", ND, Fuse ? "_fused" : "", o.full ? "_stencil27" : "");
  std::printf("particles %ld\n", P.n);
  std::printf("cells %d %d %d\n", g.ncell[0], g.ncell[1], g.ncell[2]);
  std::printf("steps %d\n", steps);
  std::printf("setup_s %.6f\n", setup_s);
  std::printf("loop_s %.6f\n", loop_s);
  std::printf("step_ms %.4f\n", loop_s / steps * 1e3);
  const char *names[5] = {"P2G", "GridUpdate", "G2P", "StressUpdate", "rest"};
  for (int q = 0; q < 5; ++q) std::printf("phase_ms %s %.4f\n", names[q], tp[q] / steps * 1e3);
  std::printf("Mupdates_per_s %.4f\n", P.n * double(steps) / loop_s / 1e6);
  std::printf("nodes_per_particle %.4f\n", double(touched) / P.n); // the last step's P2G
  std::printf("time %.17g\n", time);
  std::printf("unbalanced_ratio %.17g\n", ratio);
  std::printf("kinetic_resets %ld\n", resets);
  std::printf("mean_stress_yy %.17g\n", syy / P.n);
  std::printf("mean_uy %.17g\n", uy / P.n);
  rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  std::printf("peak_rss_kb %ld\n", ru.ru_maxrss);
  if (!o.dump.empty()) { // n, then per particle: id, x(3), v(3), stress(6), F(9), vol (doubles)
    FILE *f = std::fopen(o.dump.c_str(), "wb");
    if (!f) die("cannot write " + o.dump);
    const int64_t n = P.n;
    std::fwrite(&n, sizeof n, 1, f);
    std::vector<double> row(23);
    for (long p = 0; p < P.n; ++p) {
      row[0] = static_cast<double>(P.pid[p]);
      for (int d = 0; d < 3; ++d) row[1 + d] = P.x[3 * p + d];
      for (int d = 0; d < 3; ++d) row[4 + d] = P.v[3 * p + d];
      for (int d = 0; d < 6; ++d) row[7 + d] = P.stress[6 * p + d];
      for (int d = 0; d < 9; ++d) row[13 + d] = P.F[9 * p + d];
      row[22] = P.vol[p];
      std::fwrite(row.data(), sizeof(double), row.size(), f);
    }
    std::fclose(f);
  }
  return 0;
}

} // namespace

int main(int argc, char **argv) {
  const Options o = parse(argc, argv);
  if (o.node == 10) return o.fuse ? run<10, true>(o) : run<10, false>(o);
  return o.fuse ? run<8, true>(o) : run<8, false>(o);
}
