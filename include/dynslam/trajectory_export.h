// Trajectories in the formats evo and the KITTI odometry devkit read: TUM
// (`timestamp tx ty tz qx qy qz qw` per line) and KITTI (the 3×4 matrix [R | t], row-major, per
// line, no timestamp). The camera's and each object's estimated trajectory of a solved labelled
// graph — object-centric: its object poses L; world-centric: composed from the motions and a
// ground-truth start as SPEC §5 does — and, with ground truth, the matching true trajectories.
// An estimate and its ground truth hold the same frames (those both have), so that KITTI files,
// which carry no time, pair up line by line. Graph layer: no Ceres.
#ifndef DYNSLAM_TRAJECTORY_EXPORT_H_
#define DYNSLAM_TRAJECTORY_EXPORT_H_

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "dynslam/graph.h"
#include "dynslam/ground_truth.h"
#include "dynslam/options.h"
#include "dynslam/pose.h"
#include "dynslam/status.h"

namespace dynslam {

enum class TrajectoryFormat { kTum, kKitti };
// "tum", "kitti".
const char* TrajectoryFormatName(TrajectoryFormat format);
bool ParseTrajectoryFormat(const std::string& text, TrajectoryFormat* format);

// Which trajectory files a solve writes beside its outputs.
struct ExportOptions {
  std::vector<TrajectoryFormat> formats;  // none: no trajectory files
  double rate_hz = 10;                    // TUM timestamps are frame / rate_hz (KITTI Tracking's)
};

// The export options, `export` and `export_rate` (options.h).
const OptionTable<ExportOptions>& ExportOptionTable();

struct Trajectory {
  std::string name;              // "camera_estimate", "object_7_ground_truth", …
  std::map<int64_t, Pose> poses;  // frame → pose (camera or object to world)
};

// The estimates, then (with `ground_truth`) the true trajectories on the same frames. Without
// ground truth a world-centric graph has no object trajectories (SPEC §5 starts them there).
std::vector<Trajectory> ExportedTrajectories(const Graph& solved, const GroundTruth* ground_truth);

// One line per pose; TUM timestamps are frame / rate_hz seconds (KITTI Tracking: 10 Hz).
std::string FormatTrajectory(const Trajectory& trajectory, TrajectoryFormat format,
                             double rate_hz);

// DIR/<name>.tum.txt or DIR/<name>.kitti.txt for each trajectory, each written whole or not at
// all (file_io.h).
Status WriteTrajectories(const std::string& dir, const std::vector<Trajectory>& trajectories,
                         TrajectoryFormat format, double rate_hz);

}  // namespace dynslam

#endif  // DYNSLAM_TRAJECTORY_EXPORT_H_
