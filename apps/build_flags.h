// Builder options shared by `build` and `compare` (SPEC §3.5).
#ifndef DYNSLAM_APPS_BUILD_FLAGS_H_
#define DYNSLAM_APPS_BUILD_FLAGS_H_

#include <optional>
#include <string>
#include <vector>

#include "cli.h"
#include "dynslam/formulation.h"

namespace dynslam::cli {

class BuildFlags {
 public:
  explicit BuildFlags(ArgParser* parser);
  std::optional<std::string> Finish(BuildOptions* options) const;

 private:
  BuildOptions defaults_;
  int64_t min_object_frames_;
  std::string object_init_ = ObjectInitName(BuildOptions{}.object_init);
  std::string motion_init_ = "frontend";
  double kinematic_sigma_;
  std::string hybrid_smoothing_info_ = "frontend";
};

// Every formulation's name, for AddChoice.
std::vector<std::string> FormulationChoices();

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_BUILD_FLAGS_H_
