// --compat: the released code's choices (SPEC §7), all ("dsc") or by item number ("1,3"), and
// DynoSAM's for the hybrid formulation (SPEC §3.6), all ("dynosam") or some ("dynosam:1,3").
// Each item maps onto a library switch of the reader, the builder or the solver; none is a
// default (docs/COMPAT.md).
#ifndef DYNSLAM_APPS_COMPAT_FLAGS_H_
#define DYNSLAM_APPS_COMPAT_FLAGS_H_

#include <array>
#include <optional>
#include <string>

#include "cli.h"
#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/solver.h"

namespace dynslam::cli {

class CompatFlags {
 public:
  explicit CompatFlags(ArgParser* parser);
  // After parsing: a usage error, or nullopt.
  std::optional<std::string> Finish();

  bool any() const;
  std::string Describe() const;  // "none", or the items on
  void Apply(ReadOptions* options) const;
  void Apply(BuildOptions* options) const;
  // `world_centric`: item 3 (Huber on point edges) applies to world-centric graphs only.
  void Apply(bool world_centric, SolverOptions* options) const;

 private:
  std::string text_ = "none";
  std::array<bool, 9> item_{};     // items 1–8 of SPEC §7
  std::array<bool, 5> dynosam_{};  // items 1–4 of SPEC §3.6 --compat dynosam
};

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_COMPAT_FLAGS_H_
