// Unit tests of the interface kernels (interface.hpp, transfers.hpp) on plain arrays:
//   p2g_cell_colour + cell_colour_normals: the volume-weighted cell-average colour and the
//     paper's normals from its central differences (flat and 45-degree colour fronts, the
//     interface node rows, zero normal inside uniform colour);
//   interface_update at one node, random states: the paper type keeps one normal velocity, the
//     contact type releases separating bodies; both conserve momentum, and the friction impulse
//     is min(mu N, the impulse that sticks), with N the pressing normal impulse (Coulomb);
//     mu = 0 leaves the tangential velocities alone, a large mu sticks; normal impulses are
//     counted as compression or tension; a body with a tail share takes the common acceleration;
//     a node without a normal or without body 2 is bonded.
#include "check.hpp"
#include "pmpm/contact/interface.hpp"
#include <algorithm>
#include <cmath>
#include <vector>

using namespace pmpm;

namespace {

// Nodes 0 .. n in both directions (no ghosts: the normals take off-grid cells from the nearest).
struct SmallGrid {
  std::vector<double> data;
  GridView G;
  SmallGrid(PetscInt n, double h) {
    G.h = h;
    for (int d = 0; d < DIM; ++d) {
      G.ncell[d] = n;
      G.gs[d] = 0;
      G.gm[d] = n + 1;
    }
    data.assign(static_cast<size_t>(G.gm[0] * G.gm[1] * GridDof::NDOF), 0.0);
    G.data = data.data();
  }
};

// A particle per quarter cell (ppc 2) over an n x n grid, colour 1 where side(x, y) holds.
template <class Side> void colour_normals(PetscInt n, double h, Side side, SmallGrid &out) {
  std::vector<double> x, vol, colour;
  for (PetscInt j = 0; j < 2 * n; ++j)
    for (PetscInt i = 0; i < 2 * n; ++i) {
      const double px = (i + 0.5) * h / 2, py = (j + 0.5) * h / 2;
      x.push_back(px);
      x.push_back(py);
      vol.push_back(h * h / 4);
      colour.push_back(side(px, py) ? 1.0 : 0.0);
    }
  ParticleView P;
  P.n = static_cast<PetscInt>(vol.size());
  P.x = x.data();
  P.vol = vol.data();
  P.colour = colour.data();
  SmallGrid C(n, h);
  p2g_cell_colour(P, C.G);
  cell_colour_normals(C.G, out.G);
}

void test_cell_average() {
  // two particles in one cell: volumes 3 and 1, colours 1 and 0 -> average colour 3/4
  SmallGrid C(4, 0.5);
  double x[4] = {0.6, 0.7, 0.9, 0.8}, vol[2] = {3.0, 1.0}, colour[2] = {1.0, 0.0};
  ParticleView P;
  P.n = 2;
  P.x = x;
  P.vol = vol;
  P.colour = colour;
  p2g_cell_colour(P, C.G);
  const double *c = C.G.node(1, 1); // cell (1, 1) holds both
  CHECK_CLOSE(c[GridDof::FEXT] / c[GridDof::FEXT + 1], 0.75, 1e-15);
  CHECK_CLOSE(c[GridDof::FEXT + 1], 4.0, 1e-15);
  CHECK_CLOSE(C.G.node(0, 0)[GridDof::FEXT + 1], 0.0, 0.0);
}

void test_flat_front() {
  // body 1 below y = 4h: cells 0..3 in y are colour 1, above colour 0
  const PetscInt n = 8;
  const double h = 0.25;
  SmallGrid B(n, h);
  colour_normals(
      n, h, [=](double, double y) { return y < 4 * h; }, B);
  for (PetscInt j = 0; j <= n; ++j)
    for (PetscInt i = 0; i <= n; ++i) { // the grid's edges are no colour edges
      const double *b = B.G.node(i, j);
      // a cell's gradient is 1/(2h) in the two cell rows either side of the front; a node
      // averages four cells: rows j = 3 and 5 see one such row (g h = 1/4), row 4 two (1/2)
      const double want = j == 4 ? 0.5 : (j == 3 || j == 5 ? 0.25 : 0.0);
      CHECK_CLOSE(b[GridDof::FEXT], 0.0, 1e-15);
      CHECK_CLOSE(b[GridDof::FEXT + 1], want, 1e-15);
    }
}

void test_diagonal_front() {
  // body 1 below the staircase x + y < 8h (cells with ci + cj < 8): the colour depends on
  // ci + cj only, so every normal is (1, 1)/sqrt 2; it is defined at the nodes whose cells
  // (i - 2 .. i + 1) see the step, 7 <= i + j <= 10, largest on the front i + j = 8 and 9
  const PetscInt n = 8;
  const double h = 0.25;
  SmallGrid B(n, h);
  colour_normals(
      n, h, [=](double x, double y) { return std::floor(x / h) + std::floor(y / h) < 8; }, B);
  int front = 0;
  for (PetscInt j = 2; j <= n - 2; ++j)
    for (PetscInt i = 2; i <= n - 2; ++i) {
      const double *b = B.G.node(i, j);
      const double gx = b[GridDof::FEXT], gy = b[GridDof::FEXT + 1];
      CHECK_CLOSE(gx, gy, 1e-15);
      const PetscInt s = i + j;
      if (s == 8 || s == 9)
        CHECK_CLOSE(gx, 3 * 0.125, 1e-15); // three of four cells see it
      else if (s == 7 || s == 10)
        CHECK_CLOSE(gx, 0.125, 1e-15);
      else
        CHECK_CLOSE(gx, 0.0, 0.0);
      front += s == 8;
    }
  CHECK(front == 5);
}

// One node state: total field after the grid update (T) and body 1's sums (B).
struct NodeCase {
  double m, m1, vcm[DIM], acm[DIM], p1[DIM], f1[DIM], n[DIM];
};

struct NodeResult {
  double v1[DIM], a1[DIM], v2[DIM], a2[DIM];
  InterfaceStats st;
};

NodeResult run_node(const NodeCase &c, InterfaceType type, double mu, double dt) {
  SmallGrid T(2, 1.0), B(2, 1.0);
  double *t = T.G.node(1, 1), *b = B.G.node(1, 1);
  t[GridDof::M] = c.m;
  b[GridDof::M] = c.m1;
  for (int d = 0; d < DIM; ++d) {
    t[GridDof::P + d] = c.vcm[d];
    t[GridDof::F + d] = c.acm[d];
    b[GridDof::P + d] = c.p1[d];
    b[GridDof::F + d] = c.f1[d];
    b[GridDof::FEXT + d] = c.n[d];
  }
  InterfaceParams prm;
  prm.type = type;
  prm.mu_top = prm.mu_bottom = mu;
  prm.dt = dt;
  NodeResult r;
  interface_update(T.G, B.G, prm, r.st);
  for (int d = 0; d < DIM; ++d) {
    r.v1[d] = b[GridDof::P + d];
    r.a1[d] = b[GridDof::F + d];
    r.v2[d] = t[GridDof::P + d];
    r.a2[d] = t[GridDof::F + d];
  }
  return r;
}

double dot(const double a[DIM], const double b[DIM]) {
  return a[0] * b[0] + a[1] * b[1];
}

void test_node_update(pmpm_test::Lcg &r) {
  const double dt = 1e-3;
  int pressed = 0, pulled = 0, slipped = 0, stuck = 0;
  for (int k = 0; k < 400; ++k) {
    NodeCase c;
    c.m = r.uniform(1.0, 3.0);
    c.m1 = c.m * r.uniform(0.05, 0.95);
    const double m2 = c.m - c.m1, th = r.uniform(0.0, 2 * M_PI);
    c.n[0] = std::cos(th);
    c.n[1] = std::sin(th);
    for (int d = 0; d < DIM; ++d) {
      c.vcm[d] = r.uniform(-1.0, 1.0);
      c.acm[d] = r.uniform(-100.0, 100.0);
      c.p1[d] = c.m1 * r.uniform(-1.0, 1.0);
      c.f1[d] = r.uniform(-1e3, 1e3);
    }
    // body 1 on its own, the trial state the kernel corrects
    double v1old[DIM], v1t[DIM], dv[DIM], v2old[DIM];
    for (int d = 0; d < DIM; ++d) {
      v1old[d] = c.p1[d] / c.m1;
      v1t[d] = v1old[d] + dt * c.f1[d] / c.m1;
      dv[d] = v1t[d] - c.vcm[d];
      v2old[d] = (c.m * (c.vcm[d] - dt * c.acm[d]) - c.m1 * v1old[d]) / m2;
    }
    const double dn = dot(dv, c.n), N = c.m1 * dn; // normal impulse on body 1, > 0 pressing
    const double tv[DIM] = {dv[0] - dn * c.n[0], dv[1] - dn * c.n[1]};
    const double stick = c.m1 * std::hypot(tv[0], tv[1]); // tangential impulse that sticks
    const double mu = r.uniform(0.0, 1.0);
    for (InterfaceType type : {InterfaceType::Paper, InterfaceType::Contact}) {
      const NodeResult o = run_node(c, type, mu, dt);
      double mom = 0, acc = 0;
      for (int d = 0; d < DIM; ++d) {
        mom = std::max(mom, std::fabs(c.m1 * o.v1[d] + m2 * o.v2[d] - c.m * c.vcm[d]));
        acc = std::max(acc, std::fabs(o.a1[d] - (o.v1[d] - v1old[d]) / dt));
        acc = std::max(acc, std::fabs(o.a2[d] - (o.v2[d] - v2old[d]) / dt) * m2 / c.m);
      }
      CHECK_CLOSE(mom, 0.0, 1e-12);
      CHECK_CLOSE(acc * dt, 0.0, 1e-11);
      CHECK_CLOSE(o.st.contact_nodes, 1.0, 0.0);
      if (type == InterfaceType::Contact && dn <= 0.0) { // separating: each body on its own
        for (int d = 0; d < DIM; ++d) CHECK_CLOSE(o.v1[d], v1t[d], 1e-12);
        CHECK_CLOSE(o.st.compression + o.st.tension, 0.0, 0.0);
        continue;
      }
      // one normal velocity; tangential impulse min(mu max(N, 0), stick), opposing the slip
      CHECK_CLOSE(dot(o.v1, c.n), dot(o.v2, c.n), 1e-12);
      CHECK_CLOSE(dot(o.v1, c.n), dot(c.vcm, c.n), 1e-12);
      const double want = std::min(mu * std::max(N, 0.0), stick);
      double jt[DIM]; // tangential impulse on body 1
      for (int d = 0; d < DIM; ++d) jt[d] = c.m1 * (o.v1[d] - v1t[d]) + N * c.n[d];
      CHECK_CLOSE(std::hypot(jt[0], jt[1]), want, 1e-12 * (1 + stick));
      CHECK(dot(jt, tv) <= 1e-12 * (1 + stick));
      CHECK_CLOSE(o.st.compression, std::max(N, 0.0), 1e-12 * std::fabs(N));
      CHECK_CLOSE(o.st.tension, std::max(-N, 0.0), 1e-12 * std::fabs(N));
      (N > 0 ? pressed : pulled) += type == InterfaceType::Paper;
      (want < stick ? slipped : stuck) += 1;
    }
  }
  CHECK(pressed > 50 && pulled > 50 && slipped > 50 && stuck > 50); // every branch was taken
}

void test_limits() {
  NodeCase c = {2.0, 0.5, {0.3, -0.2}, {1.0, 2.0}, {0.5 * 0.9, 0.5 * 0.4}, {-80, -200}, {0, 1}};
  // body 1 alone would move up at 0 against v_cm -0.2: pressed. mu = 0: the tangential (x)
  // velocities stay each body's own; mu = 1e6: both move as one
  for (InterfaceType type : {InterfaceType::Paper, InterfaceType::Contact}) {
    const NodeResult f = run_node(c, type, 0.0, 1e-3);
    CHECK_CLOSE(f.v1[0], 0.9 + 1e-3 * -80 / 0.5, 1e-14);
    const NodeResult s = run_node(c, type, 1e6, 1e-3);
    CHECK_CLOSE(s.v1[0], c.vcm[0], 1e-14);
    CHECK_CLOSE(s.v2[0], c.vcm[0], 1e-14);
  }
  // a tail share (below 1e-3): that body takes the common acceleration, whatever its own force,
  // and with mu = 0 keeps its tangential velocity relative to the other body
  for (int which = 0; which < 2; ++which) {
    NodeCase b = c;
    b.m1 = which == 0 ? 1e-5 * b.m : b.m * (1 - 1e-5);
    for (int d = 0; d < DIM; ++d) b.p1[d] = b.m1 * (d == 0 ? 0.9 : 0.0); // body 1 at (0.9, 0)
    const double m2 = b.m - b.m1;
    const NodeResult o = run_node(b, InterfaceType::Contact, 0.0, 1e-3);
    const double v2old = (b.m * (b.vcm[0] - 1e-3 * b.acm[0]) - b.m1 * 0.9) / m2;
    if (which == 0)
      CHECK_CLOSE(o.v1[0], 0.9 + 1e-3 * b.acm[0], 1e-12);
    else
      CHECK_CLOSE(o.v2[0], v2old + 1e-3 * b.acm[0], 1e-9);
  }
  // no normal, or no body 2: the node keeps the single field
  for (int which = 0; which < 2; ++which) {
    NodeCase b = c;
    if (which == 0)
      b.n[0] = b.n[1] = 0.0;
    else
      b.m1 = b.m;
    const NodeResult o = run_node(b, InterfaceType::Paper, 0.3, 1e-3);
    for (int d = 0; d < DIM; ++d) {
      CHECK_CLOSE(o.v1[d], c.vcm[d], 0.0);
      CHECK_CLOSE(o.a1[d], c.acm[d], 0.0);
    }
    CHECK_CLOSE(o.st.contact_nodes, 0.0, 0.0);
  }
}

} // namespace

int main() {
  pmpm_test::Lcg r(0x5DEECE66Dull);
  test_cell_average();
  test_flat_front();
  test_diagonal_front();
  test_node_update(r);
  test_limits();
  return pmpm_test::report("test_interface");
}
