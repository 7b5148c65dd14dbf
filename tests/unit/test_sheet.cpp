// Unit test of the 3D sheet's own mechanics (sheet.hpp), without the grid:
//  1. the law's three states (taut, wrinkled, slack) against their formulas (1e-12), and the
//     energy continuous where the state changes;
//  2. homogeneous deformations of a disc lattice: a rigid rotation strains nothing and gives no
//     force (1e-12); a stretch along x with z held gives b1 = s, b2 = 0, N1 = J s in every
//     triangle (the plane-strain chain's T = J eps) and an equibiaxial stretch N = J (1 + nu) s,
//     rotated or not; the points inside carry no net force (a homogeneous state is in
//     equilibrium; 1e-10 of a rim force);
//  3. forces = -grad energy by central differences on a randomly deformed disc, for the linear
//     law and for the tension-field law in a state with wrinkled triangles (step 1e-7, tolerance
//     1e-6 of the largest force: truncation (1e-7)^2 of the curvature, round-off 1e-16 / 1e-7);
//  2d. a partial update (the triangles one rank computes) equals the whole sheet's at the points
//     whose triangles it lists, bit for bit, and leaves the other triangles alone;
//  4. a flat circular sheet clamped at its rim under its own weight (Foppl-Hencky), relaxed with
//     kinetic damping: at q a / (E t) = 1e-4 (slopes about 0.03, where the small-slope theory
//     holds) the centre deflection is 0.653 a (q a / E t)^(1/3) for nu = 0.3 (Fichter 1997)
//     within 2 % on two lattices (ds = a / 8 and a / 16; measured +0.08 % and +0.10 %: the
//     lattice has converged there, the rest is the theory's and its 3-digit coefficient's);
//  5. the same sheet at the catenary scene's load (a = 10 m, q = 100 Pa, E t = 1e5 N/m: slopes
//     about 0.3, beyond Foppl-Hencky) against the membrane of revolution with the same law,
//     the chain of revolution (chain.hpp) of 400 segments relaxed alone (its own discretisation:
//     it matches the boundary-value problem to 4e-4 at 80 segments, test_membrane_axisymmetric):
//     the sag within 1 %, the centre strain (the mean of the centre's triangles) within 3 % and
//     the rim's radial strain (the two outer bands extrapolated to the rim, as the chain's
//     segments) within 3 %, at ds = a / 16 and a / 32, the sag's error falling with ds.
#include "check.hpp"
#include "chain_fixture.hpp"
#include "pmpm/contact/sheet.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {
using pmpm::Sheet;
using pmpm::SheetLaw;
using pmpm::SheetState;

// x = c + A (X - c) for a 3 x 3 row-major A.
void deform(Sheet &s, const double c[3], const double A[9]) {
  for (int i = 0; i < s.n; ++i)
    for (int d = 0; d < 3; ++d) {
      double y = c[d];
      for (int e = 0; e < 3; ++e) y += A[3 * d + e] * (s.x0[3 * i + e] - c[e]);
      s.x[3 * i + d] = y;
    }
}

// A rotation by angle a about the unit axis u (Rodrigues), row-major.
void rotation(const double u[3], double a, double R[9]) {
  const double c = std::cos(a), s = std::sin(a);
  const double K[9] = {0, -u[2], u[1], u[2], 0, -u[0], -u[1], u[0], 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      R[3 * i + j] = (i == j ? c : 0.0) + s * K[3 * i + j] + (1 - c) * u[i] * u[j];
    }
}

void matmul(const double A[9], const double B[9], double C[9]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      C[3 * i + j] = 0;
      for (int k = 0; k < 3; ++k) C[3 * i + j] += A[3 * i + k] * B[3 * k + j];
    }
}

double max_abs(const std::vector<double> &v) {
  double m = 0;
  for (double a : v) m = std::fmax(m, std::fabs(a));
  return m;
}

// A clamped disc of radius R about the origin (ring gap ds), linear law J, nu, weight q per area.
Sheet clamped_disc(double J, double nu, double q, double R, double ds) {
  Sheet s;
  const double c[3] = {0, 0, 0};
  s.J = J;
  s.nu = nu;
  s.area_weight = q;
  pmpm::sheet_disc(R, ds, c, s);
  return s;
}

// Relax the sheet under its weight (-y) with kinetic damping (velocities zeroed at each peak of
// the kinetic energy) until the largest unbalanced force at a free point is below tol of the
// largest point weight. Masses are the point areas (a fictitious density: the equilibrium does
// not depend on them). Returns the iterations taken.
int relax(Sheet &s, double tol, int max_it) {
  const double c = std::sqrt(s.J), wmax = max_abs(s.weight);
  double amin = 1e300;
  for (int i = 0; i < s.n; ++i) amin = std::fmin(amin, s.area[i]);
  const double dt = 0.3 * std::sqrt(amin) / c;
  double ke_old = 0;
  for (int it = 0; it < max_it; ++it) {
    pmpm::sheet_update_forces(s);
    double rmax = 0, ke = 0;
    for (int i = 0; i < s.n; ++i) {
      if (s.pinned[i]) continue;
      s.f[3 * i + 1] -= s.weight[i];
      for (int d = 0; d < 3; ++d) {
        rmax = std::fmax(rmax, std::fabs(s.f[3 * i + d]));
        s.v[3 * i + d] += dt * s.f[3 * i + d] / s.area[i];
        ke += 0.5 * s.area[i] * s.v[3 * i + d] * s.v[3 * i + d];
      }
    }
    if (rmax < tol * wmax) return it;
    if (ke < ke_old) {
      std::fill(s.v.begin(), s.v.end(), 0.0);
      ke = 0;
    }
    ke_old = ke;
    for (int i = 0; i < s.n; ++i)
      if (!s.pinned[i])
        for (int d = 0; d < 3; ++d) s.x[3 * i + d] += dt * s.v[3 * i + d];
  }
  return max_it;
}
} // namespace

int main() {
  const double J = 2.0e5, nu = 0.3, Et = J * (1 - nu * nu);

  // 1. the law's states
  {
    using pmpm::sheet_tensions;
    auto T = sheet_tensions(SheetLaw::TensionField, J, nu, 0.02, 0.01); // taut
    CHECK(T.state == SheetState::Taut);
    CHECK_CLOSE(T.N1, J * (0.02 + nu * 0.01), 1e-12 * J);
    CHECK_CLOSE(T.N2, J * (0.01 + nu * 0.02), 1e-12 * J);
    T = sheet_tensions(SheetLaw::TensionField, J, nu, 0.02, -0.01); // N2 < 0: wrinkled
    CHECK(T.state == SheetState::Wrinkled);
    CHECK_CLOSE(T.N1, Et * 0.02, 1e-12 * J);
    CHECK_CLOSE(T.N2, 0.0, 1e-12 * J);
    T = sheet_tensions(SheetLaw::TensionField, J, nu, -0.001, -0.01); // slack
    CHECK(T.state == SheetState::Slack);
    CHECK_CLOSE(T.N1, 0.0, 0.0);
    T = sheet_tensions(SheetLaw::Linear, J, nu, 0.02, -0.01); // the linear law compresses
    CHECK(T.state == SheetState::Taut && T.N2 < 0);
    // the energy across taut / wrinkled (b2 = -nu b1) and wrinkled / slack (b1 = 0)
    const double b1 = 0.013, e = 1e-9;
    CHECK_CLOSE(pmpm::sheet_energy_density(SheetLaw::TensionField, J, nu, b1, -nu * b1 + e),
                pmpm::sheet_energy_density(SheetLaw::TensionField, J, nu, b1, -nu * b1 - e),
                1e-6 * J * b1 * b1);
    CHECK_CLOSE(pmpm::sheet_energy_density(SheetLaw::TensionField, J, nu, e, -0.01), 0.0, 1e-12);
  }

  // 2. homogeneous deformations of a disc (3 rings)
  {
    Sheet s;
    const double c[3] = {1.0, 2.0, 3.0};
    s.J = J;
    s.nu = nu;
    pmpm::sheet_disc(1.5, 0.5, c, s);
    CHECK(s.n == 1 + 6 + 12 + 18);
    CHECK(s.nt == 6 * 9); // 6 K^2 triangles
    double area = 0;
    for (double a : s.a0) area += a;
    // the inscribed polygon: 18 sides around the rim
    CHECK_CLOSE(area, 0.5 * 18 * 1.5 * 1.5 * std::sin(2 * M_PI / 18), 1e-12);
    const double u[3] = {0.36, 0.48, 0.8}, stretch = 0.04;
    double R[9], A[9], Q[9];
    rotation(u, 0.7, R);
    deform(s, c, R);
    pmpm::sheet_update_forces(s);
    CHECK(max_abs(s.b) < 1e-12);
    CHECK(max_abs(s.f) < 1e-12 * J);
    // stretch along x, z held, then rotated: b1 = s, b2 = 0, N1 = J s
    const double Sx[9] = {1 + stretch, 0, 0, 0, 1, 0, 0, 0, 1};
    matmul(R, Sx, A);
    deform(s, c, A);
    pmpm::sheet_update_forces(s);
    double fin = 0, frim = 0;
    for (int t = 0; t < s.nt; ++t) {
      CHECK_CLOSE(s.b[2 * t], stretch, 1e-12);
      CHECK_CLOSE(s.b[2 * t + 1], 0.0, 1e-12);
      CHECK_CLOSE(s.N[2 * t], J * stretch, 1e-9 * J);
      CHECK_CLOSE(s.N[2 * t + 1], nu * J * stretch, 1e-9 * J);
      const double ex[3] = {1, 0, 0};
      CHECK_CLOSE(pmpm::sheet_strain_along(s, t, ex), stretch, 1e-12);
    }
    for (int i = 0; i < s.n; ++i)
      for (int d = 0; d < 3; ++d)
        (s.pinned[i] ? frim : fin) = std::fmax(s.pinned[i] ? frim : fin, std::fabs(s.f[3 * i + d]));
    CHECK(frim > 0.01 * J * stretch);
    CHECK(fin < 1e-10 * frim);
    // equibiaxial, rotated: N = J (1 + nu) s in every direction
    const double Sb[9] = {1 + stretch, 0, 0, 0, 1, 0, 0, 0, 1 + stretch};
    matmul(R, Sb, Q);
    deform(s, c, Q);
    pmpm::sheet_update_forces(s);
    for (int t = 0; t < s.nt; ++t) {
      CHECK_CLOSE(s.N[2 * t], J * (1 + nu) * stretch, 1e-9 * J);
      CHECK_CLOSE(s.N[2 * t + 1], J * (1 + nu) * stretch, 1e-9 * J);
    }
    fin = 0;
    for (int i = 0; i < s.n; ++i)
      if (!s.pinned[i])
        for (int d = 0; d < 3; ++d) fin = std::fmax(fin, std::fabs(s.f[3 * i + d]));
    CHECK(fin < 1e-10 * frim);
  }

  // 2b. the rectangle lattice (sheet_rectangle): 4 x 3 points, its area, and a rotated uniaxial
  //     stretch strains every triangle alike, with no net force at its inner points and the
  //     point values (sheet_point_principal) the triangles'
  {
    Sheet s;
    s.J = J;
    s.nu = nu;
    pmpm::sheet_rectangle(0.5, 0.25, 4, -1.0, 0.5, 3, 2.0, s);
    CHECK(s.n == 12 && s.nt == 2 * 3 * 2);
    double area = 0;
    for (double a : s.a0) area += a;
    CHECK_CLOSE(area, 0.75 * 1.0, 1e-12);
    CHECK_CLOSE(s.x0[3 * 7], 0.5 + 2 * 0.25, 1e-15); // point (i, j) = (2, 1) is i nz + j
    CHECK_CLOSE(s.x0[3 * 7 + 2], -1.0 + 0.5, 1e-15);
    const double c[3] = {0.5, 2.0, -1.0}, u[3] = {0.6, 0.0, 0.8}, stretch = 0.03;
    double R[9], A[9];
    rotation(u, 0.4, R);
    const double Sx[9] = {1 + stretch, 0, 0, 0, 1, 0, 0, 0, 1};
    matmul(R, Sx, A);
    deform(s, c, A);
    pmpm::sheet_update_forces(s);
    for (int t = 0; t < s.nt; ++t) {
      CHECK_CLOSE(s.b[2 * t], stretch, 1e-12);
      CHECK_CLOSE(s.N[2 * t], J * stretch, 1e-9 * J);
    }
    for (int i : {4, 7}) // the inner points (1, 1) and (2, 1)
      for (int d = 0; d < 3; ++d) CHECK(std::fabs(s.f[3 * i + d]) < 1e-10 * J * stretch);
    std::vector<double> e, N;
    pmpm::sheet_point_principal(s, e, N);
    for (int i = 0; i < s.n; ++i) {
      CHECK_CLOSE(e[2 * i], stretch, 1e-12);
      CHECK_CLOSE(e[2 * i + 1], 0.0, 1e-12);
      CHECK_CLOSE(N[2 * i + 1], nu * J * stretch, 1e-9 * J);
    }
    const pmpm::PeakPrincipal p = pmpm::sheet_peak_principal(s);
    CHECK_CLOSE(p.strain1, stretch, 1e-12);
    CHECK_CLOSE(p.triangle_strain1, stretch, 1e-12);
  }

  // 2c. the elastoplastic sheet (sheet_plastic_forces): plane-stress von Mises on the forces with
  //     linear hardening, at a point and through the lattice
  {
    const double Ny = 0.01 * J, H = 0.2 * J, ey = Ny / (J * (1 + nu)); // equibiaxial yield strain
    // equibiaxial strain past yield: N = Ny + H alpha, e_p = alpha / 2 each way, so
    // N (1 + J (1 + nu) / (2 H)) = J (1 + nu) (e + Ny / (2 H)); in 7 unequal increments
    double Bp[3] = {0, 0, 0}, alpha = 0, N[3];
    for (const double e : {0.5 * ey, 1.3 * ey, 2 * ey, 2.1 * ey, 3.7 * ey, 5 * ey, 8 * ey}) {
      const double B[3] = {e, e, 0};
      pmpm::sheet_plastic_forces(J, nu, Ny, H, B, Bp, alpha, N);
      const double k = J * (1 + nu),
                   want = e <= ey ? k * e : (k * e + k * Ny / (2 * H)) / (1 + k / (2 * H));
      CHECK_CLOSE(N[0], want, 1e-10 * J * ey);
      CHECK_CLOSE(N[1], want, 1e-10 * J * ey);
      CHECK_CLOSE(N[2], 0.0, 1e-12 * J * ey);
      CHECK_CLOSE(alpha, e <= ey ? 0.0 : (want - Ny) / H, 1e-9 * ey);
    }
    // the same strain again: on the yield surface, nothing changes (bit for bit)
    {
      const double B[3] = {8 * ey, 8 * ey, 0}, Bp0[3] = {Bp[0], Bp[1], Bp[2]}, a0 = alpha;
      pmpm::sheet_plastic_forces(J, nu, Ny, H, B, Bp, alpha, N);
      CHECK(Bp[0] == Bp0[0] && Bp[1] == Bp0[1] && Bp[2] == Bp0[2] && alpha == a0);
      // unloading by d: elastic, N falls by J (1 + nu) d, the plastic state kept
      const double d = 0.5 * ey, B2[3] = {8 * ey - d, 8 * ey - d, 0}, N0 = N[0];
      pmpm::sheet_plastic_forces(J, nu, Ny, H, B2, Bp, alpha, N);
      CHECK_CLOSE(N[0], N0 - J * (1 + nu) * d, 1e-10 * J * ey);
      CHECK(Bp[0] == Bp0[0] && alpha == a0);
    }
    // perfectly plastic (H = 0): equibiaxial plateau N = Ny; pure shear plateau N12 = Ny / sqrt 3
    double P2[3] = {0, 0, 0}, a2 = 0;
    for (int i = 1; i <= 6; ++i) {
      const double B[3] = {i * ey, i * ey, 0};
      pmpm::sheet_plastic_forces(J, nu, Ny, 0.0, B, P2, a2, N);
      CHECK_CLOSE(N[0], std::fmin(i, 1) * Ny, 1e-10 * Ny);
    }
    double P3[3] = {0, 0, 0}, a3 = 0;
    const double gy = Ny / std::sqrt(3.0) / (J * (1 - nu)); // shear yield (tensor strain)
    for (int i = 1; i <= 6; ++i) {
      const double B[3] = {0, 0, 0.5 * i * gy};
      pmpm::sheet_plastic_forces(J, nu, Ny, 0.0, B, P3, a3, N);
      CHECK_CLOSE(N[2], std::fmin(0.5 * i, 1.0) * Ny / std::sqrt(3.0), 1e-10 * Ny);
      CHECK_CLOSE(N[0], 0.0, 1e-12 * Ny);
      CHECK_CLOSE(N[1], 0.0, 1e-12 * Ny);
    }
    // through the lattice: an equibiaxial stretch past yield, rotated in space, gives every
    // triangle the point's answer and no net force at the inner points; the same positions
    // again change nothing
    Sheet s;
    s.law = SheetLaw::Elastoplastic;
    s.J = J;
    s.nu = nu;
    s.yield_N = Ny;
    s.hardening = H;
    pmpm::sheet_rectangle(0.0, 0.5, 4, 0.0, 0.5, 4, 0.0, s);
    const double c[3] = {0.75, 0, 0.75}, u[3] = {0.0, 0.6, 0.8}, e = 4 * ey;
    double R[9], A[9];
    rotation(u, 0.9, R);
    const double Sb[9] = {1 + e, 0, 0, 0, 1, 0, 0, 0, 1 + e};
    matmul(R, Sb, A);
    deform(s, c, A);
    pmpm::sheet_update_forces(s);
    const double k = J * (1 + nu), want = (k * e + k * Ny / (2 * H)) / (1 + k / (2 * H));
    for (int t = 0; t < s.nt; ++t) {
      CHECK_CLOSE(s.N[2 * t], want, 1e-9 * J * ey);
      CHECK_CLOSE(s.N[2 * t + 1], want, 1e-9 * J * ey);
    }
    for (int i : {5, 6, 9, 10}) // the inner points
      for (int d = 0; d < 3; ++d) CHECK(std::fabs(s.f[3 * i + d]) < 1e-10 * J * e);
    const std::vector<double> f0 = s.f, bp0 = s.bp;
    pmpm::sheet_update_forces(s);
    CHECK(s.f == f0 && s.bp == bp0);
  }

  // 2d. a partial update (one rank's triangles under MPI, src/step/sheets.cpp): listing the
  //     triangles at some points gives those points the whole sheet's forces and normals bit for
  //     bit, computes only the listed triangles (the others' plastic state untouched, not fresh),
  //     and sheet_sum_forces over the completed arrays gives every point's whole-sheet force
  {
    Sheet s;
    const double c[3] = {0, 0, 0};
    s.law = SheetLaw::Elastoplastic;
    s.J = J;
    s.nu = nu;
    s.yield_N = 0.002 * J;
    s.hardening = 0.1 * J;
    pmpm::sheet_disc(1.0, 0.25, c, s);
    pmpm_test::Lcg rng(11);
    for (int i = 0; i < s.n; ++i) {
      const double *X = &s.x0[3 * i];
      s.x[3 * i] = 1.02 * X[0] + rng.uniform(-2e-3, 2e-3);
      s.x[3 * i + 1] = 0.1 * X[0] * X[0] + rng.uniform(-2e-3, 2e-3);
      s.x[3 * i + 2] = 1.01 * X[2] + rng.uniform(-2e-3, 2e-3);
    }
    Sheet whole = s;
    pmpm::sheet_update_forces(whole);
    pmpm::sheet_normals(whole);
    std::vector<char> mine(s.n, 0); // the points at x > 0.2: "this rank's"
    for (int i = 0; i < s.n; ++i) mine[i] = s.x0[3 * i] > 0.2;
    std::vector<int> tris;
    for (int t = 0; t < s.nt; ++t) {
      const int *v = &s.tri[3 * t];
      if (mine[v[0]] || mine[v[1]] || mine[v[2]]) tris.push_back(t);
    }
    CHECK(tris.size() > 10 && static_cast<int>(tris.size()) < s.nt - 10);
    pmpm::sheet_update_forces(s, tris);
    pmpm::sheet_normals(s, tris);
    bool same = true;
    for (int i = 0; i < s.n; ++i)
      for (int d = 0; d < 3 && mine[i]; ++d)
        same = same && s.f[3 * i + d] == whole.f[3 * i + d] &&
               s.nrm[3 * i + d] == whole.nrm[3 * i + d];
    CHECK(same);
    int yielded = 0, fresh = 0, untouched = 0;
    for (int t = 0; t < s.nt; ++t) {
      yielded += whole.alpha[t] > 0;
      fresh += s.fresh[t];
      untouched += !s.fresh[t] && s.alpha[t] == 0.0 && s.N[2 * t] == 0.0;
    }
    CHECK(yielded > 10); // the plastic state matters here
    CHECK(fresh == static_cast<int>(tris.size()) && untouched == s.nt - fresh);
    // complete the others as SheetsComplete does (their arrays from where they were computed)
    Sheet done = s;
    for (int t = 0; t < s.nt; ++t) {
      if (done.fresh[t]) continue;
      for (int k = 0; k < 6; ++k) done.P[6 * t + k] = whole.P[6 * t + k];
      done.alpha[t] = whole.alpha[t];
    }
    pmpm::sheet_sum_forces(done);
    CHECK(done.f == whole.f);
  }

  // 3. forces = -grad U
  for (SheetLaw law : {SheetLaw::Linear, SheetLaw::TensionField}) {
    Sheet s;
    const double c[3] = {0, 0, 0};
    s.J = J;
    s.nu = nu;
    s.law = law;
    pmpm::sheet_disc(1.0, 0.5, c, s);
    // stretched 3 % along x, shortened 2 % along z (wrinkles under the tension-field law), bent
    // and perturbed
    pmpm_test::Lcg rng(7 + static_cast<int>(law));
    for (int i = 0; i < s.n; ++i) {
      const double *X = &s.x0[3 * i];
      s.x[3 * i] = 1.03 * X[0] + rng.uniform(-2e-3, 2e-3);
      s.x[3 * i + 1] = 0.1 * (X[0] * X[0] + 0.5 * X[2] * X[2]) + rng.uniform(-2e-3, 2e-3);
      s.x[3 * i + 2] = 0.98 * X[2] + rng.uniform(-2e-3, 2e-3);
    }
    pmpm::sheet_update_forces(s);
    const std::vector<double> f = s.f;
    int wrinkled = 0;
    for (SheetState st : s.state) wrinkled += st == SheetState::Wrinkled;
    if (law == SheetLaw::TensionField) CHECK(wrinkled > 0);
    const double fmax = max_abs(f), step = 1e-7;
    for (size_t q = 0; q < s.x.size(); ++q) {
      const double x = s.x[q];
      s.x[q] = x + step;
      const double up = pmpm::sheet_energy(s);
      s.x[q] = x - step;
      const double dn = pmpm::sheet_energy(s);
      s.x[q] = x;
      CHECK_CLOSE(f[q], -(up - dn) / (2 * step), 1e-6 * fmax);
    }
  }

  // 4. Foppl-Hencky: a = 1 m, q a / E t = 1e-4
  {
    const double a = 1.0, load = 1e-4 * Et / a, w_fh = 0.653 * a * std::cbrt(1e-4);
    double err[2];
    int k = 0;
    for (double ds : {a / 8, a / 16}) {
      Sheet s = clamped_disc(J, nu, load, a, ds);
      const int it = relax(s, 1e-9, 2000000);
      CHECK(it < 2000000);
      const double w0 = -s.x[1];
      err[k] = w0 / w_fh - 1;
      std::printf("Foppl-Hencky, ds = a/%g: %d points, %d iterations, w0 = %.6g m (%.6g), error "
                  "%+.3e\n",
                  a / ds, s.n, it, w0, w_fh, err[k]);
      CHECK(std::fabs(err[k]) < 0.02);
      ++k;
    }
  }
  // 5. against the chain of revolution
  {
    const double a = 10.0, q = 100.0, Et5 = 1e5, J5 = Et5 / (1 - nu * nu);
    // the chain: points from the axis to the rim along x (= r), the rim pinned, the axis point
    // kept on the axis; masses fictitious (R + l0) l0, weights per radian q R l
    const int ns = 160;
    std::vector<double> pts;
    for (int i = 0; i <= ns; ++i) pts.insert(pts.end(), {a * i / ns, 0.0});
    pmpm::Chain ch = pmpm_test::make_chain(pts, J5, nu, 0);
    const double l0 = a / ns, dt = 0.3 * l0 / std::sqrt(J5);
    std::vector<double> m(ch.n), w(ch.n), v(2 * ch.n, 0.0);
    for (int i = 0; i < ch.n; ++i) {
      const double len = (i == 0 || i == ns) ? 0.5 * l0 : l0, R = a * i / ns;
      m[i] = (R + l0) * len;
      w[i] = q * R * len;
    }
    double ke_old = 0;
    int it = 0;
    for (; it < 5000000; ++it) {
      pmpm::chain_update_tension(ch);
      double rmax = 0, ke = 0;
      for (int i = 0; i < ns; ++i) {
        ch.f[2 * i + 1] -= w[i];
        if (i == 0) ch.f[0] = 0; // on the axis
        for (int d = 0; d < 2; ++d) {
          rmax = std::fmax(rmax, std::fabs(ch.f[2 * i + d]));
          v[2 * i + d] += dt * ch.f[2 * i + d] / m[i];
          ke += 0.5 * m[i] * v[2 * i + d] * v[2 * i + d];
        }
      }
      if (rmax < 1e-8 * q * a * l0) break;
      if (ke < ke_old) {
        std::fill(v.begin(), v.end(), 0.0);
        ke = 0;
      }
      ke_old = ke;
      for (int i = 0; i < ns; ++i)
        for (int d = 0; d < 2; ++d) ch.x[2 * i + d] += dt * v[2 * i + d];
    }
    CHECK(it < 5000000);
    const double sag_ref = -ch.x[1], eps_c_ref = ch.eps[0],
                 eps_r_ref = 1.5 * ch.eps[ns - 1] - 0.5 * ch.eps[ns - 2];
    std::printf("chain of revolution (%d segments, %d iterations): sag %.6g m, centre strain "
                "%.6g, rim strain %.6g\n",
                ns, it, sag_ref, eps_c_ref, eps_r_ref);
    double err_old = 1;
    for (double ds : {a / 16, a / 32}) {
      Sheet s = clamped_disc(J5, nu, q, a, ds);
      const double c[3] = {0, 0, 0};
      const int its = relax(s, 1e-9, 4000000);
      CHECK(its < 4000000);
      const pmpm::SheetDiscStrains st = pmpm::sheet_disc_strains(s, c, a, ds);
      const double sag = -s.x[1], eps_c = st.centre, eps_r = st.rim;
      const double err = sag / sag_ref - 1;
      std::printf("sheet ds = a/%g: %d points, %d iterations; sag %.6g m (%+.2e), centre strain "
                  "%.6g (%+.2e), rim strain %.6g (%+.2e)\n",
                  a / ds, s.n, its, sag, err, eps_c, eps_c / eps_c_ref - 1, eps_r,
                  eps_r / eps_r_ref - 1);
      CHECK(std::fabs(err) < 0.01);
      CHECK(std::fabs(eps_c / eps_c_ref - 1) < 0.03);
      CHECK(std::fabs(eps_r / eps_r_ref - 1) < 0.03);
      CHECK(std::fabs(eps_c / eps_c_ref - 1) < err_old);
      err_old = std::fabs(eps_c / eps_c_ref - 1);
    }
  }
  return pmpm_test::report("test_sheet");
}
