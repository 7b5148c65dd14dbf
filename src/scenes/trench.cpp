// Placeholder: the trench scene is being written.
#include "pmpm/simulation.hpp"
namespace pmpm {
std::unique_ptr<Scene> make_trench_scene() { return nullptr; }
} // namespace pmpm
