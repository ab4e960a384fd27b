// --export and --export-rate, shared by `solve` and `compare`: trajectories for evo
// (dynslam/trajectory_export.h) beside a solve's outputs.
#ifndef DYNSLAM_APPS_EXPORT_FLAGS_H_
#define DYNSLAM_APPS_EXPORT_FLAGS_H_

#include <optional>
#include <string>
#include <vector>

#include "cli.h"
#include "dynslam/solve_output.h"
#include "dynslam/trajectory_export.h"

namespace dynslam::cli {

class ExportFlags {
 public:
  explicit ExportFlags(ArgParser* parser);
  // After a successful Parse: a usage error message, or nullopt.
  std::optional<std::string> Finish();
  // The formats and rate into `outputs` (WriteSolveOutputs writes the files).
  void Apply(SolveOutputs* outputs) const;

 private:
  std::string formats_text_;
  double rate_hz_ = 10;  // KITTI Tracking's frame rate
  std::vector<TrajectoryFormat> formats_;
};

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_EXPORT_FLAGS_H_
