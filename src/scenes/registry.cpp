// The scene table: one line per scene (name, factory, one-line description). -scene's help, the
// error for an unknown scene, -help's scene list and docs/options.md all come from it.
#include "pmpm/model/simulation.hpp"

namespace pmpm {

std::unique_ptr<Scene> make_bar_scene();
std::unique_ptr<Scene> make_column_scene();
std::unique_ptr<Scene> make_landfill_scene();
std::unique_ptr<Scene> make_incline_scene();
std::unique_ptr<Scene> make_layers_scene();
std::unique_ptr<Scene> make_block_scene();
std::unique_ptr<Scene> make_catenary_scene();
std::unique_ptr<Scene> make_pullout_scene();
std::unique_ptr<Scene> make_trench_scene();
std::unique_ptr<Scene> make_cover_scene();
std::unique_ptr<Scene> make_footing_scene();
std::unique_ptr<Scene> make_trapdoor_scene();
std::unique_ptr<Scene> make_cylinder_scene();
std::unique_ptr<Scene> make_sheet_scene();

const std::vector<SceneEntry> &Scenes() {
  static const std::vector<SceneEntry> scenes = {
      {"bar", make_bar_scene, "elastic bar under end traction, or vibrating (method.md 2.1, 2.4)"},
      {"column", make_column_scene,
       "column under self-weight, small or large strain (method.md 2.2)"},
      {"landfill", make_landfill_scene,
       "the seed paper's landfill cover, its Section 4 (method.md 1.1-1.4)"},
      {"incline", make_incline_scene,
       "block on an incline: the frictional interface (method.md 2.5)"},
      {"layers", make_layers_scene, "two bonded elastic layers under self-weight"},
      {"block", make_block_scene, "free block in rigid motion: migration between ranks"},
      {"catenary", make_catenary_scene,
       "one membrane chain sagging under its weight (method.md 6.1)"},
      {"pullout", make_pullout_scene,
       "pull-out of a sheet anchored between two blocks (method.md 6.2)"},
      {"trench", make_trench_scene,
       "geomembrane over an open trench, Giroud's regime (method.md 6.2-6.5)"},
      {"cover", make_cover_scene,
       "landfill cover at field scale, described in an options file (method.md 7, cover.md)"},
      {"footing", make_footing_scene,
       "strip or circular footing: bearing capacity in pressure stages (method.md 2.6)"},
      {"trapdoor", make_trapdoor_scene,
       "active trapdoor in cohesionless soil (method.md 6.4, trapdoor.md)"},
      {"cylinder", make_cylinder_scene,
       "thick-walled cylinder under pressure, axisymmetric (Lame; method.md 9)"},
      {"sheet", make_sheet_scene,
       "3D: a circular membrane clamped at its rim under its weight (method.md 10)"},
  };
  return scenes;
}

std::string SceneList() {
  std::string s;
  for (const SceneEntry &e : Scenes()) s += (s.empty() ? "" : ", ") + std::string(e.name);
  return s;
}

std::string ExtrudingScenes() {
  std::string s;
  for (const SceneEntry &e : Scenes())
    if (e.make()->extrudes()) s += (s.empty() ? "" : ", ") + std::string(e.name);
  return s;
}

std::unique_ptr<Scene> make_scene(const std::string &name) {
  for (const SceneEntry &e : Scenes())
    if (name == e.name) return e.make();
  return nullptr;
}

} // namespace pmpm
