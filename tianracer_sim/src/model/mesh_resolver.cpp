// Mesh URI -> file path: tianracer_assets' resolver (the one shared with tianracer_control),
// its errors reported as the model loader's ModelError.
#include "tianracer_sim/model/robot_model.h"

#include <tianracer_assets/paths.h>

namespace tianracer_sim {

std::string MeshResolver::resolve(const std::string& uri) const {
  tianracer_assets::UriResolver resolver;
  resolver.find_package = find_package;
  resolver.base_dir = base_dir;
  resolver.model_paths = model_paths;
  try {
    return resolver.resolve(uri);
  } catch (const tianracer_assets::ResourceError& e) {
    throw ModelError(e.what());
  }
}

}  // namespace tianracer_sim
