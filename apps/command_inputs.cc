#include "command_inputs.h"

#include "dynslam/consistency.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <utility>

namespace dynslam::cli {

bool ReadGroundTruthIfGiven(const std::string& path, std::optional<GroundTruth>* gt) {
  gt->reset();
  if (path.empty()) return true;
  Expected<GroundTruth> read = ReadGroundTruth(path);
  if (!read.ok()) {
    std::cerr << "error: " << read.error().ToString() << "\n";
    return false;
  }
  *gt = std::move(read).value();
  return true;
}

bool CovarianceKindsOfFlag(bool given, const std::string& text, std::vector<CovarianceKind>* kinds) {
  kinds->clear();
  if (!given) return true;
  if (std::optional<std::string> problem = ParseCovarianceKinds(text, kinds)) {
    std::cerr << "error: --covariance: " << *problem << "\n";
    return false;
  }
  return true;
}

bool BackendOfFlag(const std::string& text, std::optional<GtsamProfile>* gtsam) {
  Expected<std::optional<GtsamProfile>> parsed = ParseBackend(text);
  if (!parsed.ok()) {
    std::cerr << "error: --backend " << text << ": " << parsed.error().message << "\n";
    return false;
  }
  *gtsam = std::move(parsed).value();
  return true;
}

std::string EmbeddedKittiDir() {
  namespace fs = std::filesystem;
  auto has_data = [](const fs::path& dir) {
    std::error_code ec;
    return fs::is_directory(dir / "label_02", ec);
  };
  if (const char* given = std::getenv("DYNSLAM_KITTI"); given != nullptr && *given != '\0') {
    return given;
  }
  std::error_code ec;
  const fs::path command = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path dir = command.parent_path();
    // The build tree, an installed tree, the Python package (scripts/install_python_module).
    for (const fs::path& candidate : {dir / "../../../data/kitti_tracking",
                                      dir / "../share/dynslam/kitti_tracking",
                                      dir / "../data/kitti_tracking"}) {
      if (has_data(candidate)) return candidate.lexically_normal().string();
    }
  }
  return "data/kitti_tracking";
}

}  // namespace dynslam::cli
