// Unit tests of the transfer kernels (transfers.hpp) on plain arrays, no PETSc objects:
//   grid_update: Cundall damping law, boundary faces (held dofs), unbalanced-force and load stats;
//                prescribed nodal velocities (supports inside the box) and the force they hold;
//   g2p_kinematics: stable-step wave speed, exact reproduction of a linear velocity field,
//                   escape / instability flags and the left-rank count;
//   g2p_velocity: FLIP / PIC blend; the interface body's field G1 for particles of colour 1;
//   p2g: conservation of mass, momentum, forces (and their first moments), particle subsets;
//   MUSL: p2g_momentum + grid_velocity.
#include "check.hpp"
#include "pmpm/core/transfers.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

using namespace pmpm;

namespace {

// The sequence these tests were written with (pmpm_test::Lcg).
struct Lcg : pmpm_test::Lcg {
  Lcg() : pmpm_test::Lcg(0x9E3779B97F4A7C15ull) {}
};

// A ghosted grid of nodes -2 .. n + 2 in both directions over a std::vector.
struct TestGrid {
  std::vector<double> data;
  GridView G;
  TestGrid(PetscInt n, double h, double ox, double oy) {
    G.h = h;
    G.origin[0] = ox;
    G.origin[1] = oy;
    for (int d = 0; d < DIM; ++d) {
      G.ncell[d] = n;
      G.gs[d] = -2;
      G.gm[d] = n + 5;
    }
    data.assign(static_cast<size_t>(G.gm[0] * G.gm[1] * GridDof::NDOF), 0.0);
    G.data = data.data();
  }
  double xnode(PetscInt i, int d) const { return G.origin[d] + i * G.h; }
  template <class F> void for_nodes(F f) const {
    for (PetscInt j = G.gs[1]; j < G.gs[1] + G.gm[1]; ++j)
      for (PetscInt i = G.gs[0]; i < G.gs[0] + G.gm[0]; ++i) f(i, j, G.node(i, j));
  }
};

// Particle arrays over std::vectors.
struct TestParticles {
  std::vector<double> x, x0, v, lp, mass, vol, vol0, weight, stress, F, eps_p, colour;
  std::vector<PetscInt> mat, pid, load;
  ParticleView P; // points into the vectors above: never copy a TestParticles
  TestParticles(const TestParticles &) = delete;
  TestParticles &operator=(const TestParticles &) = delete;
  explicit TestParticles(PetscInt n) {
    x.assign(n * DIM, 0.0);
    x0.assign(n * DIM, 0.0);
    v.assign(n * DIM, 0.0);
    lp.assign(n * DIM, 0.0);
    mass.assign(n, 1.0);
    vol.assign(n, 1.0);
    vol0.assign(n, 1.0);
    weight.assign(n, 0.0);
    stress.assign(n * NSTRESS, 0.0);
    F.assign(n * DIM * DIM, 0.0);
    for (PetscInt p = 0; p < n; ++p) F[p * 4] = F[p * 4 + 3] = 1.0;
    eps_p.assign(n, 0.0);
    colour.assign(n, 0.0);
    mat.assign(n, 0);
    pid.assign(n, 0);
    load.assign(n, -1);
    for (PetscInt p = 0; p < n; ++p) pid[p] = 100 + p;
    P.n = n;
    P.x = x.data();
    P.x0 = x0.data();
    P.v = v.data();
    P.lp = lp.data();
    P.mass = mass.data();
    P.vol = vol.data();
    P.vol0 = vol0.data();
    P.weight = weight.data();
    P.stress = stress.data();
    P.F = F.data();
    P.eps_p = eps_p.data();
    P.colour = colour.data();
    P.mat = mat.data();
    P.pid = pid.data();
    P.load = load.data();
  }
};

// Random particles centred in [lo, hi) cells of the grid, half-sizes in (0.05 h, h/2].
void random_particles(Lcg &r, const TestGrid &T, TestParticles &TP, double lo, double hi) {
  const GridView &G = T.G;
  for (PetscInt p = 0; p < TP.P.n; ++p) {
    for (int d = 0; d < DIM; ++d) {
      TP.x[p * DIM + d] = G.origin[d] + r.uniform(lo, hi) * G.h;
      TP.lp[p * DIM + d] = r.uniform(0.05, 0.5) * G.h;
      TP.v[p * DIM + d] = r.uniform(-2.0, 2.0);
    }
    TP.mass[p] = r.uniform(0.5, 2.0);
    TP.vol0[p] = r.uniform(0.5, 1.5) * G.h * G.h;
    TP.vol[p] = TP.vol0[p] * r.uniform(0.9, 1.1);
    TP.weight[p] = r.uniform(1.0, 20.0);
    for (int s = 0; s < NSTRESS; ++s) TP.stress[p * NSTRESS + s] = r.uniform(-1e3, 1e3);
  }
}

Grid whole_grid(const GridView &G) {
  Grid g; // DM stays null: g2p_kinematics only reads cell_lo / cell_hi
  g.h = G.h;
  for (int d = 0; d < DIM; ++d) {
    g.origin[d] = G.origin[d];
    g.ncell[d] = G.ncell[d];
    g.cell_lo[d] = 0;
    g.cell_hi[d] = G.ncell[d];
  }
  return g;
}

// g2p_kinematics on the bulk field only (no interface body field G1).
template <class Shape>
void kinematics(const ParticleView &P, const GridView &G, const Grid &g, const G2PParams &prm,
                const double *wave_modulus, double *dudx, G2PStats &st) {
  g2p_kinematics<Shape>(P, G, nullptr, g, prm, wave_modulus, dudx, st);
}

double sgn(double v) {
  return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
}

// ---------------------------------------------------------------------------------------------
// grid_update

struct NodeIn {
  double m, p[DIM], f[DIM], fext[DIM];
};

void set_node(double *node, const NodeIn &in) {
  node[GridDof::M] = in.m;
  for (int d = 0; d < DIM; ++d) {
    node[GridDof::P + d] = in.p[d];
    node[GridDof::F + d] = in.f[d];
    node[GridDof::FEXT + d] = in.fext[d];
  }
}

// Expected Cundall update of one free dof: a = (f - alpha |f| sign(v)) / m, v_new = v + dt a.
void expected_dof(double m, double p, double f, double alpha, double dt, double &v_new, double &a) {
  const double v = p / m;
  a = (f - alpha * std::fabs(f) * sgn(v)) / m;
  v_new = v + dt * a;
}

void test_damping_law() {
  const double dt = 0.01, m = 2.5;
  const double alphas[] = {0.0, 0.3, 0.8};
  // momenta and forces of both signs, and v = 0 in one component
  const double ps[][DIM] = {{1.0, -2.0}, {-3.0, 0.5}, {0.0, 4.0}, {2.0, 0.0}};
  const double fs[][DIM] = {{5.0, 7.0}, {-6.0, 3.0}, {2.0, -8.0}, {-4.0, -1.0}};
  for (double alpha : alphas)
    for (const auto &p : ps)
      for (const auto &f : fs) {
        TestGrid T(4, 0.5, 0.0, 0.0);
        set_node(T.G.node(2, 2), {m, {p[0], p[1]}, {f[0], f[1]}, {0.0, 0.0}});
        GridUpdateParams prm;
        prm.dt = dt;
        prm.damping_alpha = alpha;
        GridStats st;
        grid_update(T.G, prm, st);
        const double *node = T.G.node(2, 2);
        double ke = 0.0;
        for (int d = 0; d < DIM; ++d) {
          double v_new, a;
          expected_dof(m, p[d], f[d], alpha, dt, v_new, a);
          CHECK_CLOSE(node[GridDof::P + d], v_new, 1e-14);
          CHECK_CLOSE(node[GridDof::F + d], a, 1e-14);
          ke += 0.5 * m * v_new * v_new;
        }
        CHECK_CLOSE(node[GridDof::M], m, 0.0);
        CHECK_CLOSE(st.kinetic, ke, 1e-13);
        CHECK_CLOSE(st.max_unbalanced, std::hypot(f[0], f[1]), 1e-14 * std::hypot(f[0], f[1]));
        CHECK_CLOSE(st.n_ext, 0.0, 0.0);
      }
  // A damped dof opposing the motion: |f| alpha reduces the force along v (v > 0, f > 0 gives
  // (1 - alpha) f), and increases it against v (v > 0, f < 0 gives (1 + alpha) f).
  {
    TestGrid T(4, 0.5, 0.0, 0.0);
    set_node(T.G.node(1, 3), {2.0, {2.0, 2.0}, {10.0, -10.0}, {0.0, 0.0}});
    GridUpdateParams prm;
    prm.dt = 1.0;
    prm.damping_alpha = 0.25;
    GridStats st;
    grid_update(T.G, prm, st);
    CHECK_CLOSE(T.G.node(1, 3)[GridDof::F + 0], 0.75 * 10.0 / 2.0, 1e-14);
    CHECK_CLOSE(T.G.node(1, 3)[GridDof::F + 1], -1.25 * 10.0 / 2.0, 1e-14);
  }
}

// Faces: node (i, j) on one or two faces, each face free, roller or fixed.
void test_faces() {
  const PetscInt n = 4;
  const FaceBC kinds[] = {FaceBC::Free, FaceBC::Roller, FaceBC::Fixed};
  // nodes: interior, on each face, a corner
  const PetscInt nodes[][2] = {{2, 2}, {0, 2}, {n, 1}, {3, 0}, {1, n}, {0, 0}, {n, n}};
  const double m = 1.5, dt = 0.1;
  const NodeIn in = {m, {0.6, -0.9}, {3.0, -40.0}, {0.0, -2.0}};
  for (const auto &ij : nodes)
    for (FaceBC kx0 : kinds)
      for (FaceBC ky0 : kinds) {
        // apply kx0 to both x faces and ky0 to both y faces
        GridUpdateParams prm;
        prm.dt = dt;
        prm.face[XMIN] = prm.face[XMAX] = kx0;
        prm.face[YMIN] = prm.face[YMAX] = ky0;
        TestGrid T(n, 0.5, 0.0, 0.0);
        set_node(T.G.node(ij[0], ij[1]), in);
        GridStats st;
        grid_update(T.G, prm, st);
        // expected held dofs, from the geometry (independent of held_dofs())
        const bool onx = ij[0] == 0 || ij[0] == n, ony = ij[1] == 0 || ij[1] == n;
        bool held[DIM] = {false, false};
        if (onx && kx0 == FaceBC::Fixed) held[0] = held[1] = true;
        if (onx && kx0 == FaceBC::Roller) held[0] = true;
        if (ony && ky0 == FaceBC::Fixed) held[0] = held[1] = true;
        if (ony && ky0 == FaceBC::Roller) held[1] = true;
        bool held_k[DIM];
        held_dofs(ij[0], ij[1], T.G.ncell, prm.face, held_k);
        CHECK(held_k[0] == held[0] && held_k[1] == held[1]);
        const double *node = T.G.node(ij[0], ij[1]);
        double maxf = 0.0, ke = 0.0;
        for (int d = 0; d < DIM; ++d) {
          if (held[d]) {
            CHECK_CLOSE(node[GridDof::P + d], 0.0, 0.0);
            CHECK_CLOSE(node[GridDof::F + d], 0.0, 0.0);
          } else {
            double v_new, a;
            expected_dof(m, in.p[d], in.f[d], 0.0, dt, v_new, a);
            CHECK_CLOSE(node[GridDof::P + d], v_new, 1e-14);
            CHECK_CLOSE(node[GridDof::F + d], a, 1e-14);
            maxf += in.f[d] * in.f[d]; // |f| over the free dofs
            ke += 0.5 * m * v_new * v_new;
          }
        }
        // the unbalanced force only counts free dofs (the y force, 40, is the large one)
        CHECK_CLOSE(st.max_unbalanced, std::sqrt(maxf), 1e-14 * std::sqrt(maxf));
        CHECK_CLOSE(st.kinetic, ke, 1e-14);
        // the external load counts whatever the support
        CHECK_CLOSE(st.n_ext, 1.0, 0.0);
        CHECK_CLOSE(st.sum_ext, 2.0, 0.0);
      }
}

// sum_ext / n_ext: nodes with mass and a non-zero external force; massless nodes are skipped.
void test_load_stats() {
  TestGrid T(6, 0.25, 1.0, -2.0);
  set_node(T.G.node(1, 1), {1.0, {0, 0}, {0, 0}, {3.0, 4.0}});    // |fext| = 5
  set_node(T.G.node(2, 5), {2.0, {0, 0}, {1, 1}, {0.0, -1.5}});   // 1.5
  set_node(T.G.node(4, 4), {0.5, {1, 1}, {2, 0}, {0.0, 0.0}});    // no load
  set_node(T.G.node(3, 3), {0.0, {0, 0}, {0, 0}, {10.0, 0.0}});   // no mass: skipped
  set_node(T.G.node(6, 2), {1.0, {0, 0}, {50, 50}, {-6.0, 8.0}}); // on XMAX (fixed): 10
  GridUpdateParams prm;
  prm.dt = 0.1;
  prm.face[XMAX] = FaceBC::Fixed;
  GridStats st;
  grid_update(T.G, prm, st);
  CHECK_CLOSE(st.n_ext, 3.0, 0.0);
  CHECK_CLOSE(st.sum_ext, 16.5, 1e-14);
  // massless node untouched
  const double *e = T.G.node(3, 3);
  CHECK(e[GridDof::M] == 0.0 && e[GridDof::P] == 0.0 && e[GridDof::F] == 0.0 &&
        e[GridDof::FEXT] == 10.0);
  // max |f| (free dofs) over nodes with mass: |(1, 1)| at (2, 5) < 2 at (4, 4); the fixed
  // node's 50 does not count
  CHECK_CLOSE(st.max_unbalanced, 2.0, 0.0);
}

// Prescribed dofs (PrescribedVelocity): the velocity is imposed, a = (v_prescribed - p/m) / dt,
// the dof leaves the unbalanced force, and the stats carry sum weight f and -sum f v_prescribed.
// Keys are given unsorted and with a duplicate (the first entry wins); a massless node is skipped.
void test_prescribed() {
  const PetscInt n = 6;
  TestGrid T(n, 0.25, 0.0, 0.0);
  set_node(T.G.node(2, 1), {2.0, {1.0, -3.0}, {4.0, -6.0}, {0.0, -1.0}}); // both dofs
  set_node(T.G.node(3, 1), {1.0, {0.2, 0.0}, {0.5, 100.0}, {0.0, 0.0}});  // y only
  set_node(T.G.node(4, 4), {0.5, {0.0, 0.0}, {1.0, 0.0}, {0.0, 0.0}});    // free
  set_node(T.G.node(3, 3), {0.0, {0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}});    // massless
  PrescribedVelocity pv;
  auto add = [&](PetscInt i, PetscInt j, int d, double v, double w) {
    pv.key.push_back(PrescribedKey(i, j, d, T.G.ncell));
    pv.v.push_back(v);
    pv.weight.push_back(w);
  };
  add(3, 3, 0, 9.0, 1.0);
  add(3, 1, 1, 0.0, 0.0);
  add(2, 1, 1, -0.25, 0.5);
  add(2, 1, 0, 0.5, 1.0);
  add(2, 1, 0, 7.0, 1.0); // duplicate: dropped
  PrescribedVelocitySort(pv);
  CHECK(pv.key.size() == 4 && std::is_sorted(pv.key.begin(), pv.key.end()));
  const double dt = 0.1;
  GridUpdateParams prm;
  prm.dt = dt;
  prm.prescribed = &pv;
  GridStats st;
  grid_update(T.G, prm, st);
  const double *a = T.G.node(2, 1), *b = T.G.node(3, 1);
  CHECK_CLOSE(a[GridDof::P + 0], 0.5, 0.0);
  CHECK_CLOSE(a[GridDof::P + 1], -0.25, 0.0);
  CHECK_CLOSE(a[GridDof::F + 0], (0.5 - 0.5) / dt, 1e-14);
  CHECK_CLOSE(a[GridDof::F + 1], (-0.25 + 1.5) / dt, 1e-13);
  CHECK_CLOSE(b[GridDof::P + 1], 0.0, 0.0);
  CHECK_CLOSE(b[GridDof::F + 1], 0.0, 0.0);
  CHECK_CLOSE(b[GridDof::P + 0], 0.2 + dt * 0.5, 1e-14); // the free dof: v + dt f / m
  CHECK_CLOSE(st.support_force[0], 1.0 * 4.0, 1e-14);
  CHECK_CLOSE(st.support_force[1], 0.5 * -6.0 + 0.0 * 100.0, 1e-14);
  CHECK_CLOSE(st.support_power, -(4.0 * 0.5 + -6.0 * -0.25 + 100.0 * 0.0), 1e-14);
  // free dofs only: (3, 1)'s x force 0.5 < (4, 4)'s 1; the prescribed 100 and |(4, -6)| do not
  // count
  CHECK_CLOSE(st.max_unbalanced, 1.0, 0.0);
  const double *e = T.G.node(3, 3);
  CHECK(e[GridDof::P] == 0.0 && e[GridDof::F] == 0.0);
  // MUSL's velocity pass imposes the same velocities
  set_node(T.G.node(2, 1), {2.0, {1.0, -3.0}, {0.0, 0.0}, {0.0, 0.0}});
  const FaceBC free_faces[2 * DIM] = {FaceBC::Free, FaceBC::Free, FaceBC::Free, FaceBC::Free};
  grid_velocity(T.G, free_faces, &pv);
  CHECK_CLOSE(T.G.node(2, 1)[GridDof::P + 0], 0.5, 0.0);
  CHECK_CLOSE(T.G.node(2, 1)[GridDof::P + 1], -0.25, 0.0);
}

// ---------------------------------------------------------------------------------------------
// g2p_kinematics

// Write v(x) = A x + b into the P slots (or another slot pair) of every (ghosted) node.
void linear_field(TestGrid &T, const double A[DIM][DIM], const double b[DIM],
                  int slot = GridDof::P) {
  T.for_nodes([&](PetscInt i, PetscInt j, double *node) {
    const double xn[DIM] = {T.xnode(i, 0), T.xnode(j, 1)};
    node[GridDof::M] = 1.0;
    for (int d = 0; d < DIM; ++d) node[slot + d] = A[d][0] * xn[0] + A[d][1] * xn[1] + b[d];
  });
}

double lin(const double A[DIM][DIM], const double b[DIM], const double *x, int d) {
  return A[d][0] * x[0] + A[d][1] * x[1] + b[d];
}

// Stable step: max_p sqrt(M V / m) + max_p |v| (a bound on max_p (c_p + |v_p|) that needs two
// roots per step), V the updated volume.
void test_wave_speed() {
  TestGrid T(8, 0.5, -1.0, 2.0);
  // a dilating field so that V differs from V0 (J = det(I + A dt) != 1)
  const double A[DIM][DIM] = {{0.5, 0.1}, {-0.2, 0.3}}, b[DIM] = {0.1, -0.2};
  const double dt = 0.1;
  const double M[2] = {4.0e6, 9.0e6};
  for (int winner = 0; winner < 2; ++winner) {
    linear_field(T, A, b);
    TestParticles TP(2);
    const double xs[2][DIM] = {{0.3, 3.1}, {1.4, 4.2}};
    for (int p = 0; p < 2; ++p) {
      TP.mat[p] = p;
      TP.x[p * DIM] = xs[p][0];
      TP.x[p * DIM + 1] = xs[p][1];
      TP.lp[p * DIM] = TP.lp[p * DIM + 1] = 0.2;
      TP.vol0[p] = TP.vol[p] = 0.16;
      TP.F[p * 4 + 1] = 0.05 * (p + 1); // non-identity F
    }
    // masses chosen so that either material gives the larger speed
    TP.mass[0] = winner == 0 ? 100.0 : 400.0;
    TP.mass[1] = winner == 0 ? 800.0 : 200.0;
    TP.v[0] = 3.0;
    TP.v[1] = -4.0; // |v| = 5
    TP.v[2] = 0.0;
    TP.v[3] = 1.0;
    std::vector<double> dudx(2 * DIM * DIM);
    G2PParams prm;
    prm.dt = dt;
    G2PStats st;
    const Grid g = whole_grid(T.G);
    kinematics<LinearShape>(TP.P, T.G, g, prm, M, dudx.data(), st);
    const double J = (1 + A[0][0] * dt) * (1 + A[1][1] * dt) - A[0][1] * dt * A[1][0] * dt;
    double c[2], vmax = 0;
    for (int p = 0; p < 2; ++p) {
      // V = J V0 with det F0 = 1 (F0 is a shear)
      CHECK_CLOSE(TP.vol[p], J * 0.16, 1e-14);
      vmax = std::fmax(vmax, std::hypot(TP.v[p * DIM], TP.v[p * DIM + 1]));
      c[p] = std::sqrt(M[p] * J * 0.16 / TP.mass[p]);
    }
    CHECK(c[winner] > c[1 - winner] * 1.05); // the cases really differ
    CHECK_CLOSE(st.max_speed, c[winner] + vmax, 1e-12 * c[winner]);
    CHECK_CLOSE(st.kinetic, 0.5 * TP.mass[0] * 25.0 + 0.5 * TP.mass[1] * 1.0, 1e-10);
    CHECK(st.bad == 0 && st.left_rank == 0);
  }
}

// A linear nodal velocity field is reproduced exactly (both shapes are linearly complete).
template <class Shape> void test_linear_field(Lcg &r) {
  TestGrid T(10, 0.3, -0.7, 1.1);
  const double A[DIM][DIM] = {{0.8, -0.35}, {0.45, -0.6}}, b[DIM] = {0.25, -0.15};
  linear_field(T, A, b);
  const PetscInt n = 200;
  TestParticles TP(n);
  random_particles(r, T, TP, 1.0, 9.0);
  for (PetscInt p = 0; p < n; ++p) {
    double *F = &TP.F[p * 4];
    F[0] = r.uniform(0.9, 1.1);
    F[1] = r.uniform(-0.1, 0.1);
    F[2] = r.uniform(-0.1, 0.1);
    F[3] = r.uniform(0.9, 1.1);
  }
  const std::vector<double> x_old = TP.x, F_old = TP.F;
  const double dt = 0.05;
  const double M[1] = {1e6};
  std::vector<double> dudx(n * DIM * DIM);
  G2PParams prm;
  prm.dt = dt;
  G2PStats st;
  const Grid g = whole_grid(T.G);
  kinematics<Shape>(TP.P, T.G, g, prm, M, dudx.data(), st);
  CHECK(st.bad == 0 && st.left_rank == 0);
  double err_du = 0, err_x = 0, err_F = 0, err_V = 0;
  for (PetscInt p = 0; p < n; ++p) {
    const double *xo = &x_old[p * DIM], *Fo = &F_old[p * 4];
    for (int d = 0; d < DIM; ++d) {
      const double xn = xo[d] + dt * (A[d][0] * xo[0] + A[d][1] * xo[1] + b[d]);
      err_x = std::max(err_x, std::fabs(TP.x[p * DIM + d] - xn));
      for (int e = 0; e < DIM; ++e) {
        err_du = std::max(err_du, std::fabs(dudx[p * 4 + d * DIM + e] - A[d][e] * dt));
        // ((I + A dt) F0)_de
        const double Fn = Fo[d * DIM + e] + dt * (A[d][0] * Fo[e] + A[d][1] * Fo[DIM + e]);
        err_F = std::max(err_F, std::fabs(TP.F[p * 4 + d * DIM + e] - Fn));
      }
    }
    const double *Fn = &TP.F[p * 4];
    err_V = std::max(err_V, std::fabs(TP.vol[p] - (Fn[0] * Fn[3] - Fn[1] * Fn[2]) * TP.vol0[p]));
  }
  // dudx sums nine nodal velocities (O(1) m/s) times gradients (O(1/h)) times dt: round-off
  // ~ 1e-15 * 10 / h * dt ~ 1e-15; 1e-12 is loose but six orders below any formula error.
  CHECK_CLOSE(err_du, 0.0, 1e-12);
  CHECK_CLOSE(err_x, 0.0, 1e-12);
  CHECK_CLOSE(err_F, 0.0, 1e-12);
  // V ~ 0.1 m^2: relative round-off of a 2x2 determinant
  CHECK_CLOSE(err_V, 0.0, 1e-14);
}

// Off the grid, J <= 0, and leaving the rank's cells.
void test_flags() {
  const PetscInt n = 8;
  const double h = 0.5;
  TestGrid T(n, h, 0.0, 0.0);
  const double dt = 0.1;
  const double M[1] = {1e6};
  // uniform velocity (+10, 0): a particle moves 1 m = 2 cells in x
  {
    const double A[DIM][DIM] = {{0, 0}, {0, 0}}, b[DIM] = {10.0, 0.0};
    linear_field(T, A, b);
    TestParticles TP(4);
    const double xs[4][DIM] = {{0.6, 1.0},  // cell 1 -> cell 3: stays in rank cells [0, 4)
                               {3.7, 2.0},  // -> 4.7 (> hi = 4): off the grid
                               {1.6, 3.0},  // cell 3 -> cell 5: left the rank
                               {3.1, 0.4}}; // -> 4.1: off the grid, second
    for (int p = 0; p < 4; ++p) {
      TP.x[p * DIM] = xs[p][0];
      TP.x[p * DIM + 1] = xs[p][1];
      TP.lp[p * DIM] = TP.lp[p * DIM + 1] = 0.25 * h;
    }
    TP.pid[1] = 42;
    TP.pid[3] = 43;
    Grid g = whole_grid(T.G);
    g.cell_hi[0] = 4; // this "rank" owns the cells x in [0, 2) m
    std::vector<double> dudx(4 * DIM * DIM);
    G2PParams prm;
    prm.dt = dt;
    G2PStats st;
    kinematics<UGIMPShape>(TP.P, T.G, g, prm, M, dudx.data(), st);
    CHECK(st.bad == 2);
    CHECK(st.bad_pid == 42);
    CHECK_CLOSE(st.bad_x[0], 4.7, 1e-14);
    CHECK_CLOSE(st.bad_x[1], 2.0, 1e-14);
    CHECK(std::strstr(st.bad_what, "left the grid") != nullptr);
    CHECK(st.left_rank == 1); // only particle 2 (bad particles are not counted)
  }
  // only one particle off the grid (the brief's case), no rank change
  {
    const double A[DIM][DIM] = {{0, 0}, {0, 0}}, b[DIM] = {0.0, -10.0};
    linear_field(T, A, b);
    TestParticles TP(3);
    const double xs[3][DIM] = {{1.0, 2.5}, {2.0, 0.7}, {3.0, 1.5}};
    for (int p = 0; p < 3; ++p) {
      TP.x[p * DIM] = xs[p][0];
      TP.x[p * DIM + 1] = xs[p][1];
      TP.lp[p * DIM] = TP.lp[p * DIM + 1] = 0.5 * h;
    }
    const Grid g = whole_grid(T.G);
    std::vector<double> dudx(3 * DIM * DIM);
    G2PParams prm;
    prm.dt = dt;
    G2PStats st;
    kinematics<LinearShape>(TP.P, T.G, g, prm, M, dudx.data(), st);
    CHECK(st.bad == 1);
    CHECK(st.bad_pid == 101);
    CHECK_CLOSE(st.bad_x[1], -0.3, 1e-14);
    CHECK(st.left_rank == 0);
  }
  // J <= 0: A dt = diag(-2, 0) flips the x axis
  {
    const double A[DIM][DIM] = {{-20.0, 0}, {0, 0}}, b[DIM] = {40.0, 0.0}; // v = 0 at x = 2
    linear_field(T, A, b);
    TestParticles TP(2);
    const double xs[4] = {2.0, 2.0, 2.1, 3.0}; // both stay on the grid (x -> 2, 1.9)
    for (int k = 0; k < 4; ++k) {
      TP.x[k] = xs[k];
      TP.lp[k] = 0.2;
    }
    TP.pid[1] = 7;
    const Grid g = whole_grid(T.G);
    std::vector<double> dudx(2 * DIM * DIM);
    G2PParams prm;
    prm.dt = dt;
    G2PStats st;
    kinematics<UGIMPShape>(TP.P, T.G, g, prm, M, dudx.data(), st);
    CHECK(st.bad == 2);
    CHECK(st.bad_pid == 100);
    CHECK(std::strstr(st.bad_what, "J") != nullptr);
    CHECK_CLOSE(TP.vol[1], -TP.vol0[1], 1e-14);
  }
}

// g2p_velocity (FLIP with a PIC blend) and the interface body's field G1: with linear nodal
// velocity and acceleration fields both are interpolated exactly, so
//   v_new = (1 - pic) (v + dt a(x_p)) + pic v(x_p),
// where particles of colour 1 read G1 and the others G0 (G1 null: everyone reads G0).
template <class Shape> void test_g2p_velocity_and_interface(Lcg &r) {
  TestGrid T0(10, 0.3, -0.7, 1.1), T1(10, 0.3, -0.7, 1.1);
  const double A[2][DIM][DIM] = {{{0.8, -0.35}, {0.45, -0.6}}, {{-0.3, 0.2}, {0.1, 0.5}}};
  const double b[2][DIM] = {{0.25, -0.15}, {-0.4, 0.3}};
  const double C[2][DIM][DIM] = {{{2.0, 1.0}, {-1.5, 0.5}}, {{-1.0, 3.0}, {0.5, -2.0}}};
  const double e[2][DIM] = {{-3.0, 1.0}, {4.0, -2.0}};
  TestGrid *T[2] = {&T0, &T1};
  for (int g = 0; g < 2; ++g) {
    linear_field(*T[g], A[g], b[g], GridDof::P);
    linear_field(*T[g], C[g], e[g], GridDof::F);
  }
  const PetscInt n = 100;
  TestParticles TP(n);
  random_particles(r, T0, TP, 1.0, 9.0);
  for (PetscInt p = 0; p < n; ++p) TP.colour[p] = double(p % 2);
  const std::vector<double> v_old = TP.v;
  const double dt = 0.02;
  for (int with_g1 = 0; with_g1 < 2; ++with_g1)
    for (double pic : {0.0, 0.3, 1.0}) {
      std::copy(v_old.begin(), v_old.end(), TP.v.begin());
      G2PParams prm;
      prm.dt = dt;
      prm.pic = pic;
      g2p_velocity<Shape>(TP.P, T0.G, with_g1 ? &T1.G : nullptr, prm);
      double err = 0;
      for (PetscInt p = 0; p < n; ++p) {
        const int g = with_g1 ? int(p % 2) : 0;
        const double *x = &TP.x[p * DIM];
        for (int d = 0; d < DIM; ++d) {
          const double want = (1.0 - pic) * (v_old[p * DIM + d] + dt * lin(C[g], e[g], x, d)) +
                              pic * lin(A[g], b[g], x, d);
          err = std::max(err, std::fabs(TP.v[p * DIM + d] - want));
        }
      }
      // nodal values O(10): interpolation round-off ~ 1e-14
      CHECK_CLOSE(err, 0.0, 1e-12);
    }
  // g2p_kinematics: colour-1 particles follow G1's velocity field
  {
    const std::vector<double> x_old = TP.x;
    std::vector<double> dudx(n * DIM * DIM);
    G2PParams prm;
    prm.dt = dt;
    G2PStats st;
    const double M[1] = {1e6};
    const Grid grid = whole_grid(T0.G);
    g2p_kinematics<Shape>(TP.P, T0.G, &T1.G, grid, prm, M, dudx.data(), st);
    double err_du = 0, err_x = 0;
    for (PetscInt p = 0; p < n; ++p) {
      const int g = int(p % 2);
      for (int d = 0; d < DIM; ++d) {
        const double xn = x_old[p * DIM + d] + dt * lin(A[g], b[g], &x_old[p * DIM], d);
        err_x = std::max(err_x, std::fabs(TP.x[p * DIM + d] - xn));
        for (int c = 0; c < DIM; ++c)
          err_du = std::max(err_du, std::fabs(dudx[p * 4 + d * DIM + c] - A[g][d][c] * dt));
      }
    }
    CHECK_CLOSE(err_du, 0.0, 1e-12);
    CHECK_CLOSE(err_x, 0.0, 1e-12);
    CHECK(st.bad == 0);
  }
}

// ---------------------------------------------------------------------------------------------
// p2g

template <class Shape> void test_p2g_conservation(Lcg &r) {
  TestGrid T(10, 0.3, -0.7, 1.1);
  const PetscInt n = 300;
  TestParticles TP(n);
  // centres anywhere on the grid, including the boundary cells (support reaches the ghosts)
  random_particles(r, T, TP, 0.0, 10.0);
  Load load;
  load.factor = 0.7;
  load.gdir[0] = 0.6;
  load.gdir[1] = -0.8;
  p2g<Shape>(TP.P, load, T.G);
  // sums over nodes
  double m = 0, p[DIM] = {0, 0}, fext[DIM] = {0, 0}, ftot[DIM] = {0, 0}, fint[DIM] = {0, 0};
  double mx[DIM] = {0, 0}, xfint[DIM][DIM] = {{0, 0}, {0, 0}};
  T.for_nodes([&](PetscInt i, PetscInt j, double *node) {
    const double xn[DIM] = {T.xnode(i, 0), T.xnode(j, 1)};
    m += node[GridDof::M];
    for (int d = 0; d < DIM; ++d) {
      p[d] += node[GridDof::P + d];
      fext[d] += node[GridDof::FEXT + d];
      ftot[d] += node[GridDof::F + d];
      const double fi = node[GridDof::F + d] - node[GridDof::FEXT + d];
      fint[d] += fi;
      mx[d] += node[GridDof::M] * xn[d];
      for (int e = 0; e < DIM; ++e) xfint[d][e] += fi * xn[e];
    }
  });
  // the same over particles
  double m_p = 0, p_p[DIM] = {0, 0}, w_p = 0, mx_p[DIM] = {0, 0}, vs_p[DIM][DIM] = {{0, 0}, {0, 0}};
  double fint_scale = 0;
  for (PetscInt q = 0; q < n; ++q) {
    const double *s = &TP.stress[q * NSTRESS];
    const double sig[DIM][DIM] = {{s[0], s[3]}, {s[3], s[1]}};
    m_p += TP.mass[q];
    w_p += TP.weight[q];
    for (int d = 0; d < DIM; ++d) {
      p_p[d] += TP.mass[q] * TP.v[q * DIM + d];
      mx_p[d] += TP.mass[q] * TP.x[q * DIM + d];
      for (int e = 0; e < DIM; ++e) vs_p[d][e] += TP.vol[q] * sig[d][e];
    }
    fint_scale += TP.vol[q] * (std::fabs(s[0]) + std::fabs(s[1]) + std::fabs(s[3])) / T.G.h;
  }
  const double rel = 1e-12;
  CHECK_CLOSE(m, m_p, rel * m_p);
  for (int d = 0; d < DIM; ++d) {
    CHECK_CLOSE(p[d], p_p[d], rel * m_p * 2.0); // |v| <= 2
    const double wd = load.factor * w_p * load.gdir[d];
    CHECK_CLOSE(fext[d], wd, rel * w_p);
    CHECK_CLOSE(ftot[d], wd, rel * (w_p + fint_scale));
    // internal forces are self-equilibrated: sum_k grad S_k = 0
    CHECK_CLOSE(fint[d], 0.0, rel * fint_scale);
    // first moments (linear completeness): sum_k m_k x_k = sum_p m_p x_p and
    // sum_k f_int,k,d x_k,e = -sum_p V_p sigma_p,de (checks the stress components' placement)
    CHECK_CLOSE(mx[d], mx_p[d], rel * m_p * 5.0);
    for (int e = 0; e < DIM; ++e) CHECK_CLOSE(xfint[d][e], -vs_p[d][e], rel * fint_scale * 5.0);
  }
  CHECK(fint_scale > 0 && std::fabs(vs_p[0][1]) > 0); // non-trivial stresses

  // p2g restricted to a list of particles (an interface body): only those are summed
  TestGrid T2(10, 0.3, -0.7, 1.1);
  std::vector<PetscInt> idx;
  for (PetscInt q = 0; q < n; q += 3) idx.push_back(q);
  p2g<Shape>(TP.P, load, T2.G, idx.data(), static_cast<PetscInt>(idx.size()));
  double m2 = 0, p2[DIM] = {0, 0}, m2_p = 0, p2_p[DIM] = {0, 0};
  T2.for_nodes([&](PetscInt, PetscInt, double *node) {
    m2 += node[GridDof::M];
    for (int d = 0; d < DIM; ++d) p2[d] += node[GridDof::P + d];
  });
  for (const PetscInt q : idx) {
    m2_p += TP.mass[q];
    for (int d = 0; d < DIM; ++d) p2_p[d] += TP.mass[q] * TP.v[q * DIM + d];
  }
  CHECK_CLOSE(m2, m2_p, rel * m2_p);
  for (int d = 0; d < DIM; ++d) CHECK_CLOSE(p2[d], p2_p[d], rel * 2.0 * m2_p);
}

// ---------------------------------------------------------------------------------------------
// MUSL

template <class Shape> void test_musl(Lcg &r) {
  TestGrid T(6, 0.4, 0.2, -0.3);
  const PetscInt n = 150;
  TestParticles TP(n);
  random_particles(r, T, TP, 0.0, 6.0); // includes the boundary cells: face nodes get mass
  FaceBC face[2 * DIM] = {FaceBC::Fixed, FaceBC::Free, FaceBC::Roller, FaceBC::Roller};
  p2g_momentum<Shape>(TP.P, T.G);
  const std::vector<double> before = T.data;
  // conservation of mass and momentum
  double m = 0, p[DIM] = {0, 0}, m_p = 0, p_p[DIM] = {0, 0};
  T.for_nodes([&](PetscInt, PetscInt, double *node) {
    m += node[GridDof::M];
    for (int d = 0; d < DIM; ++d) p[d] += node[GridDof::P + d];
  });
  double vmin[DIM] = {1e300, 1e300}, vmax[DIM] = {-1e300, -1e300};
  for (PetscInt q = 0; q < n; ++q) {
    m_p += TP.mass[q];
    for (int d = 0; d < DIM; ++d) {
      p_p[d] += TP.mass[q] * TP.v[q * DIM + d];
      vmin[d] = std::min(vmin[d], TP.v[q * DIM + d]);
      vmax[d] = std::max(vmax[d], TP.v[q * DIM + d]);
    }
  }
  CHECK_CLOSE(m, m_p, 1e-12 * m_p);
  for (int d = 0; d < DIM; ++d) CHECK_CLOSE(p[d], p_p[d], 1e-12 * 2.0 * m_p);
  // p2g_momentum touches only M and P
  bool only_mp = true;
  T.for_nodes([&](PetscInt, PetscInt, double *node) {
    for (int s = GridDof::F; s < GridDof::NDOF; ++s) only_mp = only_mp && node[s] == 0.0;
  });
  CHECK(only_mp);

  grid_velocity(T.G, face);
  double err = 0;
  int n_mass = 0, n_held = 0, n_empty = 0;
  bool held_zero = true, bounded = true, empty_untouched = true;
  T.for_nodes([&](PetscInt i, PetscInt j, double *node) {
    const double *old = &before[node - T.G.data];
    const double mk = old[GridDof::M];
    if (mk <= 0.0) {
      ++n_empty;
      for (int s = 0; s < GridDof::NDOF; ++s)
        empty_untouched = empty_untouched && node[s] == old[s];
      return;
    }
    ++n_mass;
    // held dofs from the geometry: XMIN fixed, YMIN and YMAX rollers (hold y), XMAX free
    const bool hold_x = i == 0, hold_y = i == 0 || j == 0 || j == T.G.ncell[1];
    const bool held[DIM] = {hold_x, hold_y};
    CHECK_CLOSE(node[GridDof::M], mk, 0.0);
    for (int d = 0; d < DIM; ++d) {
      const double v = node[GridDof::P + d];
      if (held[d]) {
        ++n_held;
        held_zero = held_zero && v == 0.0;
      } else {
        err = std::max(err, std::fabs(v - old[GridDof::P + d] / mk));
        // p/m is a convex combination of particle velocities (weights >= 0)
        bounded = bounded && v >= vmin[d] - 1e-12 && v <= vmax[d] + 1e-12;
      }
    }
  });
  CHECK_CLOSE(err, 0.0, 1e-14);
  CHECK(held_zero);
  CHECK(bounded);
  CHECK(empty_untouched);
  CHECK(n_mass > 30 && n_held > 10 && n_empty > 0); // all three kinds of node occur

  // uniform particle velocity u: every free dof with mass gets exactly u
  for (PetscInt q = 0; q < n; ++q) {
    TP.v[q * DIM] = 1.25;
    TP.v[q * DIM + 1] = -0.5;
  }
  std::fill(T.data.begin(), T.data.end(), 0.0);
  p2g_momentum<Shape>(TP.P, T.G);
  grid_velocity(T.G, face);
  double err_u = 0;
  T.for_nodes([&](PetscInt i, PetscInt j, double *node) {
    if (node[GridDof::M] <= 0.0) return;
    if (i != 0) err_u = std::max(err_u, std::fabs(node[GridDof::P] - 1.25));
    if (i != 0 && j != 0 && j != T.G.ncell[1])
      err_u = std::max(err_u, std::fabs(node[GridDof::P + 1] + 0.5));
  });
  CHECK_CLOSE(err_u, 0.0, 1e-14);
}

} // namespace

int main() {
  Lcg r;
  test_damping_law();
  test_faces();
  test_load_stats();
  test_prescribed();
  test_wave_speed();
  test_linear_field<LinearShape>(r);
  test_linear_field<UGIMPShape>(r);
  test_flags();
  test_g2p_velocity_and_interface<LinearShape>(r);
  test_g2p_velocity_and_interface<UGIMPShape>(r);
  test_p2g_conservation<LinearShape>(r);
  test_p2g_conservation<UGIMPShape>(r);
  test_musl<LinearShape>(r);
  test_musl<UGIMPShape>(r);
  return pmpm_test::report("test_kernels");
}
