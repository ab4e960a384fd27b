// --compat (compat.h) on the command line.
#ifndef DYNSLAM_APPS_COMPAT_FLAGS_H_
#define DYNSLAM_APPS_COMPAT_FLAGS_H_

#include <optional>
#include <string>

#include "cli.h"
#include "dynslam/compat.h"

namespace dynslam::cli {

class CompatFlags {
 public:
  explicit CompatFlags(ArgParser* parser);
  // After parsing: a usage error, or nullopt.
  std::optional<std::string> Finish();

  const Compat& value() const { return compat_; }
  bool any() const { return Describe() != "none"; }
  std::string Describe() const { return CompatText(compat_); }
  void Apply(ReadOptions* options) const { ApplyCompat(compat_, options); }
  void Apply(BuildOptions* options) const { ApplyCompat(compat_, options); }
  void Apply(bool world_centric, SolverOptions* options) const {
    ApplyCompat(compat_, world_centric, options);
  }

 private:
  std::string text_ = "none";
  Compat compat_;
};

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_COMPAT_FLAGS_H_
