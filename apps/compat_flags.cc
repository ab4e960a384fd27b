#include "compat_flags.h"

namespace dynslam::cli {
CompatFlags::CompatFlags(ArgParser* parser) {
  parser->Group("compatibility");
  parser->AddString("compat", &text_,
                    "the released code's choices (SPEC §7): dsc for all, or item numbers such as "
                    "1,3: 1 information unpermuted, 2 motion edge σ=0.1 Huber 1e-6 as m_prev-H⁻¹m_curr, "
                    "3 wc point edges Huber 1e-5, 4 identity initial motions, 5 object-centric "
                    "noise and first poses, 6 object motion residual without -m_L, 7 GTSAM LM "
                    "with the released stopping rule, 8 later object poses at their points' "
                    "centroid; or DynoSAM's for hy (SPEC §3.6): dynosam for all, or dynosam:LIST: "
                    "1 smoothing σ 0.01 rad 0.1 m at every frame, 2 Huber 1e-4 on hybrid point "
                    "edges, 3 embedded frame at the camera-frame mean of the measurements, 4 "
                    "points from their first measurement",
                    "none|dsc|LIST|dynosam[:LIST]");
}

std::optional<std::string> CompatFlags::Finish() {
  std::optional<std::string> problem = ParseCompat(text_, &compat_);
  if (problem) return "--compat: " + *problem;
  return std::nullopt;
}

}  // namespace dynslam::cli
