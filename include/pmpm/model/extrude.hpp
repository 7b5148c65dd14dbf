// -dim 3 -depth D: a 2D scene extruded along z over a depth D, run on a 3D grid (the first
// three-dimensional runs, and the strongest check of the 3D engine: with rollers on the two z
// faces the extruded body is in plane strain, so it must give the 2D answer to round-off).
//
// The scene sets up its plane as in 2D (box, faces, materials) and generates its plane's
// particles; each becomes ppc particles per z cell over the depth (half-size h / (2 ppc) along
// z, volume times the z spacing, id = 2D id x (z cells x ppc) + z index: rank-independent). The
// 3D grid has the plane's cells and depth / h cells along z, the z faces -bc_zmin and -bc_zmax
// (rollers by default), and its partition is PETSc's or -da_processors_x/y/z, with -balance setup
// moving the x and y cuts to the plane's particle counts (BalanceSetupExtruded). Each rank
// generates the whole plane (no grid: the plane's particles are O(N^(2/3)) of the run's N) and
// keeps the particles of its 3D cells, so nothing is redistributed.
//
// A scene's membrane chains extrude as strips of 3D sheet (sheet.hpp) across the whole depth,
// each a body of its own between the continuum below and above it (sheet_contact.hpp), its
// faces, pins, law and end force the chain's: points at the chain's spacing along its line and a
// cell apart across, from z = 0 to z = depth (the edge rows held in z where the z faces are
// rollers), the end force spread over the last column by the points' widths; the plane's
// particles take their bodies from the chains' lines before the extrusion (AssignBodies). A
// level chain is a rectangle (sheet_rectangle), a sloped or bent one its line swept along z
// (sheet_strip); the chain's x must increase along it. The scene's results read the sheet under
// -dim 3 (the pull-out and the cover do).
//
// What the 3D step does not run yet is refused before the run, by name (ExtrusionCheck): the
// step's hooks that act inside the step's phases (the colour interface, an imposed
// eigenstrain; cpGIMP's support check runs after the step and reads the dimension), -solver
// newton, -geometry axisymmetric, supports inside the box, -balance run, and scenes whose
// results read the plane only
// (Scene::extrudes). Face tractions extrude: the plane's load table (per unit depth) becomes
// sim.model.loads3, each entry times the particles' z spacing, shared by a particle's z copies.
#pragma once
#include "pmpm/model/prerun.hpp"

namespace pmpm {

// After the scene's setup and every option (-dim 2: only that -depth is not given).
PetscErrorCode ExtrusionCheck(Simulation &sim);

// -dim 3: the 3D grid (sim.grid3, its memory checked first), the swarm on it and this rank's
// extruded particles, indexed. In place of the 2D grid and particles (simulation.cpp).
PetscErrorCode ExtrudedGridAndParticles(Simulation &sim, const MemoryCheck &mem);

// sim.model.loads3 from sim.model.loads (per unit depth): each entry for a particle of z spacing
// h / ppc. At setup, and after a restart read the table.
PetscErrorCode ExtrudeLoads(Simulation &sim);

} // namespace pmpm
