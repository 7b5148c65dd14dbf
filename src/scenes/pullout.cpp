// Placeholder: the pullout scene is being written.
#include "pmpm/simulation.hpp"
namespace pmpm {
std::unique_ptr<Scene> make_pullout_scene() { return nullptr; }
} // namespace pmpm
