// The scene table: one line per scene.
#include "pmpm/simulation.hpp"

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

std::unique_ptr<Scene> make_scene(const std::string &name) {
  if (name == "bar") return make_bar_scene();
  if (name == "column") return make_column_scene();
  if (name == "landfill") return make_landfill_scene();
  if (name == "incline") return make_incline_scene();
  if (name == "layers") return make_layers_scene();
  if (name == "block") return make_block_scene();
  if (name == "catenary") return make_catenary_scene();
  if (name == "pullout") return make_pullout_scene();
  if (name == "trench") return make_trench_scene();
  if (name == "cover") return make_cover_scene();
  if (name == "footing") return make_footing_scene();
  if (name == "trapdoor") return make_trapdoor_scene();
  return nullptr;
}

} // namespace pmpm
