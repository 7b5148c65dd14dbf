// A geomembrane sheet in 3D (sheet.hpp): the lattice, the plane-stress Biot law and the internal
// point forces, plain functions over the sheet's arrays.
#include "pmpm/contact/sheet.hpp"
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace pmpm {

using Mat32 = Eigen::Matrix<double, 3, 2>;

SheetTensions sheet_tensions(SheetLaw law, double J, double nu, double b1, double b2) {
  SheetTensions t;
  t.N1 = J * (b1 + nu * b2);
  t.N2 = J * (b2 + nu * b1);
  if (law == SheetLaw::Linear || t.N2 >= 0.0) return t;
  if (b1 > 0.0) { // wrinkled: the uniaxial sheet, E t = J (1 - nu^2), along n1
    t.N1 = J * (1.0 - nu * nu) * b1;
    t.N2 = 0.0;
    t.state = SheetState::Wrinkled;
  } else {
    t.N1 = t.N2 = 0.0;
    t.state = SheetState::Slack;
  }
  return t;
}

double sheet_energy_density(SheetLaw law, double J, double nu, double b1, double b2) {
  const SheetTensions t = sheet_tensions(law, J, nu, b1, b2);
  switch (t.state) {
  case SheetState::Taut:
    return 0.5 * J * (b1 * b1 + 2.0 * nu * b1 * b2 + b2 * b2);
  case SheetState::Wrinkled:
    return 0.5 * J * (1.0 - nu * nu) * b1 * b1;
  case SheetState::Slack:
    break;
  }
  return 0.0;
}

void sheet_plastic_forces(double J, double nu, double yield_N, double hardening, const double B[3],
                          double Bp[3], double &alpha, double N[3]) {
  const double e11 = B[0] - Bp[0], e22 = B[1] - Bp[1], e12 = B[2] - Bp[2];
  N[0] = J * (e11 + nu * e22);
  N[1] = J * (e22 + nu * e11);
  N[2] = J * (1.0 - nu) * e12;
  const double r2 = std::sqrt(2.0);
  const double at = (N[0] + N[1]) / r2, bt = (N[1] - N[0]) / r2, ct = N[2];
  auto q_of = [&](double l) {
    const double a = at / (1 + 0.5 * J * (1 + nu) * l), k = 1 + 1.5 * J * (1 - nu) * l;
    const double b = bt / k, c = ct / k;
    return std::sqrt(0.5 * a * a + 1.5 * b * b + 3 * c * c);
  };
  const double Y = yield_N + hardening * alpha;
  const double q0 = q_of(0.0);
  if (q0 <= Y * (1 + 1e-12)) return; // elastic, or on the surface already
  // q(l) (1 - H l) - Y falls from q0 - Y > 0: bracket its root, then bisect to round-off
  auto g = [&](double l) { return q_of(l) * (1 - hardening * l) - Y; };
  double lo = 0, hi = (q0 - Y) / (J * std::fmin(1 + nu, 1 - nu) * std::fmax(Y, 1e-300 * J));
  while (g(hi) > 0) hi *= 2;
  for (int it = 0; it < 200 && hi - lo > 1e-16 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0 ? lo : hi) = mid;
  }
  const double l = hi;
  const double a = at / (1 + 0.5 * J * (1 + nu) * l), k = 1 + 1.5 * J * (1 - nu) * l;
  const double b = bt / k, c = ct / k;
  const double dpa = 0.5 * l * a, dpb = 1.5 * l * b;
  Bp[0] += (dpa - dpb) / r2;
  Bp[1] += (dpa + dpb) / r2;
  Bp[2] += 1.5 * l * c;
  alpha += l * q_of(l);
  // the forces of the new elastic strain (the returned a, b, c to round-off): the same bits as a
  // second call at these positions gives, so a restart recomputes them exactly
  const double f11 = B[0] - Bp[0], f22 = B[1] - Bp[1], f12 = B[2] - Bp[2];
  N[0] = J * (f11 + nu * f22);
  N[1] = J * (f22 + nu * f11);
  N[2] = J * (1.0 - nu) * f12;
}

void sheet_disc(double R, double ds, const double c[3], Sheet &s) {
  const int K = std::max(1, static_cast<int>(std::ceil(R / ds - 1e-9)));
  std::vector<int> first(K + 2, 0); // ring k's points are [first[k], first[k + 1])
  for (int k = 0; k <= K; ++k) first[k + 1] = first[k] + (k == 0 ? 1 : 6 * k);
  s.n = first[K + 1];
  s.x0.assign(3 * static_cast<size_t>(s.n), 0.0);
  s.pinned.assign(s.n, 0);
  for (int k = 0; k <= K; ++k) {
    const int m = first[k + 1] - first[k];
    const double r = R * k / K;
    for (int j = 0; j < m; ++j) {
      const double th = 2.0 * M_PI * j / m;
      double *X = &s.x0[3 * static_cast<size_t>(first[k] + j)];
      X[0] = c[0] + r * std::cos(th);
      X[1] = c[1];
      X[2] = c[2] + r * std::sin(th);
      s.pinned[first[k] + j] = k == K;
    }
  }
  // ring k - 1 to ring k: walk both rings by angle, each triangle advancing one of them
  s.tri.clear();
  for (int k = 1; k <= K; ++k) {
    const int na = first[k] - first[k - 1], nb = first[k + 1] - first[k];
    int i = 0, j = 0;
    while (i < na || j < nb) {
      const double ta = static_cast<double>(i + 1) / na, tb = static_cast<double>(j + 1) / nb;
      const int A = first[k - 1] + i % na, B = first[k] + j % nb;
      if (i < na && (j == nb || ta < tb)) {
        const int A1 = first[k - 1] + (i + 1) % na;
        if (A1 != A) s.tri.insert(s.tri.end(), {A, B, A1});
        ++i;
      } else {
        s.tri.insert(s.tri.end(), {A, B, first[k] + (j + 1) % nb});
        ++j;
      }
    }
  }
  s.nt = static_cast<int>(s.tri.size()) / 3;
  s.x = s.x0;
  s.v.assign(s.x0.size(), 0.0);
  s.f.assign(s.x0.size(), 0.0);
  sheet_reference(s);
}

namespace {
// The lattice's triangles and the rest of a new sheet: point (i, j) numbered i nz + j, each
// square split along its diagonal, the diagonals alternating square by square; x = x0, v = 0,
// the reference.
void lattice_triangles(int nx, int nz, Sheet &s) {
  s.pinned.assign(s.n, 0);
  s.tri.clear();
  for (int i = 0; i + 1 < nx; ++i)
    for (int j = 0; j + 1 < nz; ++j) {
      const int a = i * nz + j, b = a + nz, c = a + 1, d = b + 1; // (i,j) (i+1,j) (i,j+1) (i+1,j+1)
      if ((i + j) % 2 == 0)
        s.tri.insert(s.tri.end(), {a, b, d, a, d, c});
      else
        s.tri.insert(s.tri.end(), {a, b, c, b, d, c});
    }
  s.nt = static_cast<int>(s.tri.size()) / 3;
  s.x = s.x0;
  s.v.assign(s.x0.size(), 0.0);
  s.f.assign(s.x0.size(), 0.0);
  sheet_reference(s);
}
} // namespace

void sheet_rectangle(double x0, double dx, int nx, double z0, double dz, int nz, double y,
                     Sheet &s) {
  s.n = nx * nz;
  s.x0.assign(3 * static_cast<size_t>(s.n), 0.0);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < nz; ++j) {
      double *X = &s.x0[3 * static_cast<size_t>(i * nz + j)];
      X[0] = x0 + i * dx;
      X[1] = y;
      X[2] = z0 + j * dz;
    }
  lattice_triangles(nx, nz, s);
}

void sheet_strip(const double *xy, int nx, double z0, double dz, int nz, Sheet &s) {
  s.n = nx * nz;
  s.x0.assign(3 * static_cast<size_t>(s.n), 0.0);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < nz; ++j) {
      double *X = &s.x0[3 * static_cast<size_t>(i * nz + j)];
      X[0] = xy[2 * i];
      X[1] = xy[2 * i + 1];
      X[2] = z0 + j * dz;
    }
  lattice_triangles(nx, nz, s);
}

void sheet_lay(Sheet &s) {
  s.x0 = s.x;
  sheet_reference(s);
  std::fill(s.bp.begin(), s.bp.end(), 0.0);
  std::fill(s.alpha.begin(), s.alpha.end(), 0.0);
  std::fill(s.slip_top.begin(), s.slip_top.end(), 0.0);
  std::fill(s.slip_bot.begin(), s.slip_bot.end(), 0.0);
  sheet_update_forces(s);
}

void sheet_reference(Sheet &s) {
  s.a0.assign(s.nt, 0.0);
  s.dinv.assign(4 * static_cast<size_t>(s.nt), 0.0);
  s.basis.assign(6 * static_cast<size_t>(s.nt), 0.0);
  s.area.assign(s.n, 0.0);
  for (int t = 0; t < s.nt; ++t) {
    const int *v = &s.tri[3 * static_cast<size_t>(t)];
    const Eigen::Map<const Eigen::Vector3d> X0(&s.x0[3 * v[0]]), X1(&s.x0[3 * v[1]]),
        X2(&s.x0[3 * v[2]]);
    const Eigen::Vector3d d1 = X1 - X0, d2 = X2 - X0;
    const Eigen::Vector3d e1 = d1.normalized(), e2 = d1.cross(d2).normalized().cross(e1);
    Eigen::Matrix2d D;
    D << d1.dot(e1), d2.dot(e1), d1.dot(e2), d2.dot(e2);
    const Eigen::Matrix2d Di = D.inverse();
    s.a0[t] = 0.5 * std::fabs(D.determinant());
    for (int q = 0; q < 4; ++q) s.dinv[4 * static_cast<size_t>(t) + q] = Di(q / 2, q % 2);
    for (int d = 0; d < 3; ++d) {
      s.basis[6 * static_cast<size_t>(t) + d] = e1[d];
      s.basis[6 * static_cast<size_t>(t) + 3 + d] = e2[d];
    }
    for (int a = 0; a < 3; ++a) s.area[v[a]] += s.a0[t] / 3.0;
  }
  s.mass.resize(s.n);
  s.weight.resize(s.n);
  for (int i = 0; i < s.n; ++i) {
    s.mass[i] = s.area_mass * s.area[i];
    s.weight[i] = s.area_weight * s.area[i];
  }
  s.biot.assign(3 * static_cast<size_t>(s.nt), 0.0);
  s.b.assign(2 * static_cast<size_t>(s.nt), 0.0);
  s.N.assign(2 * static_cast<size_t>(s.nt), 0.0);
  s.state.assign(s.nt, SheetState::Taut);
  s.tens.assign(3 * static_cast<size_t>(s.nt), 0.0);
  s.P.assign(6 * static_cast<size_t>(s.nt), 0.0);
  s.fresh.assign(s.nt, 1); // the plastic state (none yet) is every triangle's latest
  if (s.law == SheetLaw::Elastoplastic) {
    s.bp.assign(3 * static_cast<size_t>(s.nt), 0.0);
    s.alpha.assign(s.nt, 0.0);
  }
}

namespace {
// Triangle t's deformation gradient over its reference basis (3 x 2).
Mat32 Deformation(const Sheet &s, int t) {
  const int *v = &s.tri[3 * static_cast<size_t>(t)];
  const Eigen::Map<const Eigen::Vector3d> x0(&s.x[3 * v[0]]), x1(&s.x[3 * v[1]]),
      x2(&s.x[3 * v[2]]);
  Mat32 E;
  E.col(0) = x1 - x0;
  E.col(1) = x2 - x0;
  const Eigen::Map<const Eigen::Matrix<double, 2, 2, Eigen::RowMajor>> Di(
      &s.dinv[4 * static_cast<size_t>(t)]);
  return E * Di;
}

// The principal stretches l1 >= l2 of a triangle's F and their reference directions n1, n2.
struct Stretches {
  double l1, l2;
  Eigen::Vector2d n1, n2;
};
Stretches PrincipalStretches(const Mat32 &F) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig;
  eig.computeDirect(F.transpose() * F);
  // ascending eigenvalues: column 1 is the larger stretch
  return {std::sqrt(std::fmax(eig.eigenvalues()[1], 0.0)),
          std::sqrt(std::fmax(eig.eigenvalues()[0], 0.0)), eig.eigenvectors().col(1),
          eig.eigenvectors().col(0)};
}
} // namespace

namespace {
using RowMat32 = Eigen::Matrix<double, 3, 2, Eigen::RowMajor>;

// Triangle t's corner forces -A0 P g_a added to its points, P its stored tension (TriangleState).
void AddCornerForces(Sheet &s, int t) {
  const double *pt = &s.P[6 * static_cast<size_t>(t)];
  if (pt[0] == 0.0 && pt[1] == 0.0 && pt[2] == 0.0 && pt[3] == 0.0 && pt[4] == 0.0 && pt[5] == 0.0)
    return; // slack: nothing
  const Mat32 P = Eigen::Map<const RowMat32>(pt);
  const Eigen::Map<const Eigen::Matrix<double, 2, 2, Eigen::RowMajor>> Di(
      &s.dinv[4 * static_cast<size_t>(t)]);
  const Eigen::Vector2d g1 = Di.row(0).transpose(), g2 = Di.row(1).transpose(), g0 = -(g1 + g2);
  const Eigen::Vector2d *g[3] = {&g0, &g1, &g2};
  const int *v = &s.tri[3 * static_cast<size_t>(t)];
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d fa = -s.a0[t] * (P * *g[a]);
    for (int d = 0; d < 3; ++d) s.f[3 * v[a] + d] += fa[d];
  }
}

// Triangle t's strains, forces' tensor, principal tensions, state and the first Piola-Kirchhoff
// tension P (s.P) from the current positions; an elastoplastic triangle's plastic state advances.
void TriangleState(Sheet &s, int t) {
  Eigen::Map<RowMat32> Pt(&s.P[6 * static_cast<size_t>(t)]);
  const Mat32 F = Deformation(s, t);
  const Stretches st = PrincipalStretches(F);
  const double l1 = st.l1, l2 = st.l2;
  const Eigen::Vector2d &n1 = st.n1, &n2 = st.n2;
  const Eigen::Matrix2d B = (l1 - 1.0) * n1 * n1.transpose() + (l2 - 1.0) * n2 * n2.transpose();
  double *bt = &s.biot[3 * static_cast<size_t>(t)], *tt = &s.tens[3 * static_cast<size_t>(t)];
  bt[0] = B(0, 0);
  bt[1] = B(1, 1);
  bt[2] = B(0, 1);
  s.b[2 * t] = l1 - 1.0;
  s.b[2 * t + 1] = l2 - 1.0;
  if (s.law == SheetLaw::Elastoplastic) { // the forces from the plastic state (not coaxial)
    sheet_plastic_forces(s.J, s.nu, s.yield_N, s.hardening, bt, &s.bp[3 * static_cast<size_t>(t)],
                         s.alpha[t], tt);
    Eigen::Matrix2d Tm;
    Tm << tt[0], tt[2], tt[2], tt[1];
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig;
    eig.computeDirect(Tm);
    s.N[2 * t] = eig.eigenvalues()[1];
    s.N[2 * t + 1] = eig.eigenvalues()[0];
    s.state[t] = SheetState::Taut;
    // P = R T with R = F U^-1 the rotation
    const Eigen::Matrix2d Uinv = n1 * n1.transpose() / l1 + n2 * n2.transpose() / l2;
    const Mat32 P = F * Uinv * Tm;
    Pt = P;
    return;
  }
  const SheetTensions T = sheet_tensions(s.law, s.J, s.nu, l1 - 1.0, l2 - 1.0);
  s.N[2 * t] = T.N1;
  s.N[2 * t + 1] = T.N2;
  s.state[t] = T.state;
  const Eigen::Matrix2d Tm = T.N1 * n1 * n1.transpose() + T.N2 * n2 * n2.transpose();
  tt[0] = Tm(0, 0);
  tt[1] = Tm(1, 1);
  tt[2] = Tm(0, 1);
  if (T.N1 == 0.0 && T.N2 == 0.0) {
    Pt.setZero();
    return;
  }
  // P = F U^-1 T_B (the Biot tension rotated into place); l_i > 0 wherever a tension acts
  const Mat32 P =
      F * (T.N1 / l1 * n1 * n1.transpose() + (T.N2 != 0.0 ? T.N2 / l2 : 0.0) * n2 * n2.transpose());
  Pt = P;
}
} // namespace

void sheet_update_forces(Sheet &s) {
  for (int t = 0; t < s.nt; ++t) TriangleState(s, t);
  std::fill(s.f.begin(), s.f.end(), 0.0);
  for (int t = 0; t < s.nt; ++t) AddCornerForces(s, t);
  std::fill(s.fresh.begin(), s.fresh.end(), 1);
}

void sheet_update_forces(Sheet &s, const std::vector<int> &tris) {
  std::fill(s.fresh.begin(), s.fresh.end(), 0);
  for (const int t : tris) {
    TriangleState(s, t);
    s.fresh[t] = 1;
  }
  std::fill(s.f.begin(), s.f.end(), 0.0);
  for (const int t : tris) AddCornerForces(s, t);
}

void sheet_sum_forces(Sheet &s) {
  std::fill(s.f.begin(), s.f.end(), 0.0);
  for (int t = 0; t < s.nt; ++t) AddCornerForces(s, t);
  std::fill(s.fresh.begin(), s.fresh.end(), 1);
}

double sheet_energy(const Sheet &s) {
  double U = 0;
  if (s.law == SheetLaw::Elastoplastic) { // the elastic part, from the last forces computed
    for (int t = 0; t < s.nt; ++t) {
      const double *B = &s.biot[3 * static_cast<size_t>(t)], *P = &s.bp[3 * static_cast<size_t>(t)],
                   *N = &s.tens[3 * static_cast<size_t>(t)];
      U += 0.5 * s.a0[t] * (N[0] * (B[0] - P[0]) + N[1] * (B[1] - P[1]) + 2 * N[2] * (B[2] - P[2]));
    }
    return U;
  }
  for (int t = 0; t < s.nt; ++t) {
    const Stretches st = PrincipalStretches(Deformation(s, t));
    U += s.a0[t] * sheet_energy_density(s.law, s.J, s.nu, st.l1 - 1.0, st.l2 - 1.0);
  }
  return U;
}

namespace {
void AddTriangleNormal(Sheet &s, int t) {
  const int *v = &s.tri[3 * static_cast<size_t>(t)];
  const Eigen::Map<const Eigen::Vector3d> x0(&s.x[3 * v[0]]), x1(&s.x[3 * v[1]]),
      x2(&s.x[3 * v[2]]);
  Eigen::Vector3d n = (x1 - x0).cross(x2 - x0); // twice the area times the unit normal
  if (n[1] < 0) n = -n;                         // pointing up (+y): the lattice's order varies
  for (int a = 0; a < 3; ++a)
    for (int d = 0; d < 3; ++d) s.nrm[3 * v[a] + d] += n[d];
}
void NormaliseNormals(Sheet &s) {
  for (int i = 0; i < s.n; ++i) {
    double *n = &s.nrm[3 * static_cast<size_t>(i)];
    const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int d = 0; d < 3; ++d) n[d] = l > 0 ? n[d] / l : (d == 1 ? 1.0 : 0.0);
  }
}
} // namespace

void sheet_normals(Sheet &s) {
  s.nrm.assign(3 * static_cast<size_t>(s.n), 0.0);
  for (int t = 0; t < s.nt; ++t) AddTriangleNormal(s, t);
  NormaliseNormals(s);
}

void sheet_normals(Sheet &s, const std::vector<int> &tris) {
  s.nrm.assign(3 * static_cast<size_t>(s.n), 0.0);
  for (const int t : tris) AddTriangleNormal(s, t);
  NormaliseNormals(s);
}

SheetDiscStrains sheet_disc_strains(const Sheet &s, const double c[3], double R, double dr) {
  double ec = 0, nc = 0, band[2] = {0, 0}, wb[2] = {0, 0};
  for (int t = 0; t < s.nt; ++t) {
    const int *v = &s.tri[3 * static_cast<size_t>(t)];
    double X[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) X[d] += (s.x0[3 * v[k] + d] - c[d]) / 3;
    const double r = std::hypot(X[0], X[2]);
    if (v[0] == 0 || v[1] == 0 || v[2] == 0) { // point 0 is the centre
      ec += 0.5 * (s.b[2 * t] + s.b[2 * t + 1]);
      nc += 1;
    }
    const int k = r > R - dr ? 0 : r > R - 2 * dr ? 1 : -1;
    if (k < 0) continue;
    const double dir[3] = {X[0] / r, 0.0, X[2] / r};
    band[k] += s.a0[t] * sheet_strain_along(s, t, dir);
    wb[k] += s.a0[t];
  }
  SheetDiscStrains out;
  out.centre = nc > 0 ? ec / nc : 0.0;
  out.rim = wb[0] > 0 && wb[1] > 0 ? 1.5 * band[0] / wb[0] - 0.5 * band[1] / wb[1] : 0.0;
  return out;
}

namespace {
// Triangle t's in-plane strain and tension tensors (in e1, e2) and their reference basis Q.
void TriangleTensors(const Sheet &s, int t, Eigen::Matrix2d &B, Eigen::Matrix2d &T, Mat32 &Q) {
  const double *bt = &s.biot[3 * static_cast<size_t>(t)], *e = &s.basis[6 * static_cast<size_t>(t)];
  B << bt[0], bt[2], bt[2], bt[1];
  const double *tt = &s.tens[3 * static_cast<size_t>(t)];
  T << tt[0], tt[2], tt[2], tt[1];
  Q.col(0) = Eigen::Vector3d(e[0], e[1], e[2]);
  Q.col(1) = Eigen::Vector3d(e[3], e[4], e[5]);
}

// The principal values (major first) of a 3D tensor A in the plane normal to n.
Eigen::Vector2d InPlanePrincipal(const Eigen::Matrix3d &A, const Eigen::Vector3d &n) {
  const Eigen::Vector3d u = n.unitOrthogonal(), w = n.cross(u);
  Mat32 P;
  P.col(0) = u;
  P.col(1) = w;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig;
  eig.computeDirect(P.transpose() * A * P);
  return {eig.eigenvalues()[1], eig.eigenvalues()[0]};
}
} // namespace

void sheet_point_principal(const Sheet &s, std::vector<double> &strain,
                           std::vector<double> &tension) {
  std::vector<Eigen::Matrix3d> E(s.n, Eigen::Matrix3d::Zero()), T(s.n, Eigen::Matrix3d::Zero());
  std::vector<Eigen::Vector3d> nrm(s.n, Eigen::Vector3d::Zero());
  std::vector<double> w(s.n, 0.0);
  for (int t = 0; t < s.nt; ++t) {
    Eigen::Matrix2d B, N;
    Mat32 Q;
    TriangleTensors(s, t, B, N, Q);
    const Eigen::Matrix3d B3 = Q * B * Q.transpose(), N3 = Q * N * Q.transpose();
    const Eigen::Vector3d n = Q.col(0).cross(Q.col(1));
    for (int a = 0; a < 3; ++a) {
      const int i = s.tri[3 * static_cast<size_t>(t) + a];
      E[i] += s.a0[t] * B3;
      T[i] += s.a0[t] * N3;
      // the triangles' normals in one orientation (the lattice's corner order varies)
      nrm[i] += (n.dot(nrm[i]) < 0 ? -s.a0[t] : s.a0[t]) * n;
      w[i] += s.a0[t];
    }
  }
  strain.assign(2 * static_cast<size_t>(s.n), 0.0);
  tension.assign(2 * static_cast<size_t>(s.n), 0.0);
  for (int i = 0; i < s.n; ++i) {
    if (!(w[i] > 0)) continue;
    const Eigen::Vector3d n = nrm[i].normalized();
    const Eigen::Vector2d e = InPlanePrincipal(E[i] / w[i], n),
                          N = InPlanePrincipal(T[i] / w[i], n);
    strain[2 * i] = e[0];
    strain[2 * i + 1] = e[1];
    tension[2 * i] = N[0];
    tension[2 * i + 1] = N[1];
  }
}

void sheet_major_direction(const Sheet &s, int t, double dir[3]) {
  Eigen::Matrix2d B, N;
  Mat32 Q;
  TriangleTensors(s, t, B, N, Q);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig;
  eig.computeDirect(B);
  const Eigen::Vector3d d = Q * eig.eigenvectors().col(1);
  for (int k = 0; k < 3; ++k) dir[k] = d[k];
}

PeakPrincipal sheet_peak_principal(const Sheet &s) {
  PeakPrincipal p;
  std::vector<double> e, N;
  sheet_point_principal(s, e, N);
  for (int i = 0; i < s.n; ++i)
    if (p.point < 0 || e[2 * i] > p.strain1) {
      p.point = i;
      p.strain1 = e[2 * i];
    }
  for (int t = 0; t < s.nt; ++t)
    p.triangle_strain1 = t == 0 ? s.b[0] : std::fmax(p.triangle_strain1, s.b[2 * t]);
  if (p.point < 0) return p;
  const int i = p.point;
  p.strain2 = e[2 * i + 1];
  p.tension1 = N[2 * i];
  p.tension2 = N[2 * i + 1];
  for (int d = 0; d < 3; ++d) p.x[d] = s.x[3 * i + d];
  return p;
}

double sheet_strain_along(const Sheet &s, int t, const double d[3]) {
  const double *e = &s.basis[6 * static_cast<size_t>(t)], *B = &s.biot[3 * static_cast<size_t>(t)];
  const double u = d[0] * e[0] + d[1] * e[1] + d[2] * e[2],
               w = d[0] * e[3] + d[1] * e[4] + d[2] * e[5];
  return B[0] * u * u + 2.0 * B[2] * u * w + B[1] * w * w;
}

} // namespace pmpm
