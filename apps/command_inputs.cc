#include "command_inputs.h"

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

}  // namespace dynslam::cli
