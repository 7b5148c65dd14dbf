// Output: summary.json, particles.h5 + particles.xmf (ParaView), an optional time series.
// Files are written under temporary names and renamed when complete, so a failed run leaves no
// half-written output.
#pragma once
#include "pmpm/util/json.hpp"
#include "pmpm/model/simulation.hpp"
#include <string>
#include <vector>

namespace pmpm {

PetscErrorCode OutputPrepareDirectory(Simulation &sim);
PetscErrorCode OutputParticles(Simulation &sim, const std::string &h5name);
PetscErrorCode OutputSeriesFrame(Simulation &sim);
PetscErrorCode OutputSeriesFinish(Simulation &sim);
// The time-series frames listed so far for particles_series.xmf (rank 0): a checkpoint carries
// them, so a restarted run's series lists the frames written before the restart too.
std::vector<std::string> &OutputSeriesFrames();
// A new run in the same process (the meshes of -estimate_error): no frames listed yet.
void OutputSeriesReset();
// Writes DIR/summary.json; results is the body of the "results" object ("k": v, ...), design the
// top-level verdict entries (design.hpp: design_json).
PetscErrorCode OutputSummary(Simulation &sim, const std::string &results,
                             const std::string &design);
// Membrane chains: DIR/chain_<name>.csv (profile), DIR/chains.h5 + chains.xmf (polylines).
PetscErrorCode OutputChains(Simulation &sim);
// 3D sheets: DIR/sheet_<name>.csv (points), DIR/sheets.h5 + sheets.xmf (triangulated surfaces).
PetscErrorCode OutputSheets(Simulation &sim);
// The "chains" and "contact" blocks of summary.json (empty without chains).
std::string ChainSummaryJson(const Simulation &sim);
// Rename DIR/name.tmp to DIR/name on rank 0.
PetscErrorCode OutputCommit(Simulation &sim, const std::string &name);

} // namespace pmpm
