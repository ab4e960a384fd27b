// The released code's choices (SPEC §7), all ("dsc") or by item number ("1,3"), and DynoSAM's
// for the hybrid formulation (SPEC §3.6), all ("dynosam") or some ("dynosam:1,3"). Each item
// sets options of the reader, the builder or the solver; none is a default (docs/COMPAT.md).
#ifndef DYNSLAM_COMPAT_H_
#define DYNSLAM_COMPAT_H_

#include <array>
#include <optional>
#include <string>

#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/options.h"
#include "dynslam/solver_options.h"

namespace dynslam {

struct Compat {
  std::array<bool, 9> dsc{};      // items 1–8 of SPEC §7 (index 0 unused)
  std::array<bool, 5> dynosam{};  // items 1–4 of SPEC §3.6 (index 0 unused)
};

// "none", "dsc", "1,3", "dynosam", "dynosam:2,4" → *compat; otherwise what is wrong.
std::optional<std::string> ParseCompat(const std::string& text, Compat* compat);
// "none", or the items on ("1,3 dynosam:2").
std::string CompatText(const Compat& compat);

// One option, `compat`, whose text is ParseCompat's (options.h).
const OptionTable<Compat>& CompatOptionTable();

// Each item given switches its options on; the others are left as they are, so an item's option
// given by itself (`--dsc-released-lm on`) holds under `--compat none`.
void ApplyCompat(const Compat& compat, ReadOptions* options);
void ApplyCompat(const Compat& compat, BuildOptions* options);
// `world_centric`: item 3 (Huber on point edges) applies to world-centric graphs only.
void ApplyCompat(const Compat& compat, bool world_centric, SolverOptions* options);

}  // namespace dynslam

#endif  // DYNSLAM_COMPAT_H_
