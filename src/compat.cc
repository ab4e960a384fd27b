#include "dynslam/compat.h"

#include <sstream>

namespace dynslam {
namespace {

void Huber(SolverOptions* options, EdgeKind kind, double threshold) {
  options->robust[static_cast<int>(kind)] = {RobustKernel::Type::kHuber, threshold};
}

// "1,3" → items[1] = items[3] = true; an error unless every entry is a digit from 1 to size − 1.
template <size_t N>
std::optional<std::string> ParseItems(const std::string& text, std::array<bool, N>* items,
                                      const std::string& what) {
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) {
    if (item.size() != 1 || item[0] < '1' || static_cast<size_t>(item[0] - '0') >= N) {
      return "'" + item + "' is not " + what;
    }
    (*items)[item[0] - '0'] = true;
  }
  return std::nullopt;
}

template <size_t N>
std::string Items(const std::array<bool, N>& items, const std::string& first_prefix) {
  std::string text;
  for (size_t i = 1; i < N; ++i) {
    if (items[i]) text += (text.empty() ? first_prefix : ",") + std::to_string(i);
  }
  return text;
}

}  // namespace

std::optional<std::string> ParseCompat(const std::string& text, Compat* compat) {
  Compat parsed;
  std::optional<std::string> problem;
  if (text == "dsc") {
    parsed.dsc.fill(true);
  } else if (text == "dynosam") {
    parsed.dynosam.fill(true);
  } else if (text.rfind("dynosam:", 0) == 0) {
    problem = ParseItems(text.substr(8), &parsed.dynosam, "a DynoSAM item number 1 to 4");
  } else if (text != "none") {
    problem = ParseItems(text, &parsed.dsc, "dsc, dynosam, none or an item number 1 to 8");
  }
  if (!problem) *compat = parsed;
  return problem;
}

const OptionTable<Compat>& CompatOptionTable() {
  static const OptionTable<Compat> table = [] {
    Option<Compat> compat = Declare<Compat>(
        "compat", "compatibility", OptionType::kText,
        "the released code's choices (SPEC §7): dsc for all, or item numbers such as 1,3: 1 "
        "information unpermuted, 2 motion edge σ=0.1 Huber 1e-6 as m_prev-H⁻¹m_curr, 3 wc point "
        "edges Huber 1e-5, 4 identity initial motions, 5 object-centric noise and first poses, 6 "
        "object motion residual without -m_L, 7 GTSAM LM with the released stopping rule, 8 later "
        "object poses at their points' centroid; or DynoSAM's for hy (SPEC §3.6): dynosam for "
        "all, or dynosam:LIST: 1 smoothing σ 0.01 rad 0.1 m at every frame, 2 Huber 1e-4 on "
        "hybrid point edges, 3 embedded frame at the camera-frame mean of the measurements, 4 "
        "points from their first measurement",
        "none|dsc|LIST|dynosam[:LIST]");
    compat.get = CompatText;
    compat.set = ParseCompat;
    return OptionTable<Compat>{compat};
  }();
  return table;
}

std::string CompatText(const Compat& compat) {
  std::string text = Items(compat.dsc, "");
  const std::string dynosam = Items(compat.dynosam, "dynosam:");
  if (!dynosam.empty()) text += (text.empty() ? "" : " ") + dynosam;
  return text.empty() ? "none" : text;
}

void ApplyCompat(const Compat& compat, ReadOptions* options) {
  if (compat.dsc[1]) options->information_in_tangent_order = true;
}

void ApplyCompat(const Compat& compat, BuildOptions* options) {
  if (compat.dsc[4]) options->motion_init = MotionInit::kIdentity;
  if (compat.dsc[5]) options->dsc_object_centric_noise = true;
  if (compat.dsc[8]) options->object_init = ObjectInit::kCentroid;
  if (compat.dynosam[1]) options->dynosam_smoothing = true;
  if (compat.dynosam[3]) options->dynosam_embedded_frame = true;
  if (compat.dynosam[4]) options->dynosam_points_from_measurements = true;
}

void ApplyCompat(const Compat& compat, bool world_centric, SolverOptions* options) {
  if (compat.dsc[2]) {
    options->dsc_motion_residual = true;
    Huber(options, EdgeKind::kMotion, 1e-6);
  }
  if (compat.dsc[3] && world_centric) {
    Huber(options, EdgeKind::kPoint, 1e-5);
    Huber(options, EdgeKind::kDynamicPoint, 1e-5);
  }
  if (compat.dsc[5]) Huber(options, EdgeKind::kObjectMotion, 1e-3);
  if (compat.dsc[6]) options->dsc_object_motion_residual = true;
  if (compat.dsc[7]) options->dsc_released_lm = true;
  if (compat.dynosam[2]) Huber(options, EdgeKind::kHybridPoint, 1e-4);
}

}  // namespace dynslam
