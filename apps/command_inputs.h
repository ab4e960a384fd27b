// Inputs that several subcommands read alike (build, compare, solve).
#ifndef DYNSLAM_APPS_COMMAND_INPUTS_H_
#define DYNSLAM_APPS_COMMAND_INPUTS_H_

#include <optional>
#include <string>
#include <vector>

#include "dynslam/covariance.h"
#include "dynslam/ground_truth.h"
#include "dynslam/gtsam_backend.h"
#include "dynslam/solve_output.h"

namespace dynslam::cli {

// Reads the ground-truth file (SPEC §2) at `path` into *gt; leaves *gt empty when `path` is
// empty (no --gt). Returns false after printing the reader's error (file, line, problem) to
// stderr; the caller then exits with kExitBadInput.
bool ReadGroundTruthIfGiven(const std::string& path, std::optional<GroundTruth>* gt);

// --covariance KINDS of solve and compare: *kinds empty when the flag was not `given`. Returns
// false after printing the problem to stderr; the caller then exits with kExitBadInput.
bool CovarianceKindsOfFlag(bool given, const std::string& text, std::vector<CovarianceKind>* kinds);

// --backend NAME of solve and compare (gtsam_backend.h ParseBackend): *gtsam empty for ceres.
// Returns false after printing ParseBackend's problem to stderr; the caller then exits with
// kExitBadInput.
bool BackendOfFlag(const std::string& text, std::optional<GtsamProfile>* gtsam);

// The embedded KITTI Tracking data (oxts/, label_02/, calib/), wherever the command is run from:
// $DYNSLAM_KITTI, else beside the command — the repository's data/kitti_tracking for a command in
// build/<type>/apps/, <prefix>/share/dynslam/kitti_tracking for an installed one, the Python
// package's data/kitti_tracking for the package's bin/dynslam — else data/kitti_tracking of the
// working directory.
std::string EmbeddedKittiDir();

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_COMMAND_INPUTS_H_
