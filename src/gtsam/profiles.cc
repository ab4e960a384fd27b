// GTSAM profiles (SPEC §6 and docs/GTSAM_BACKEND.md); compiled with or without GTSAM.
#include <optional>
#include <string>
#include <vector>

#include "dynslam/gtsam_backend.h"

namespace dynslam {
namespace {

GtsamProfile Tight(GtsamProfile profile) {
  profile.relative_error_tol = 1e-12;
  profile.absolute_error_tol = 0;
  profile.max_iterations = 500;
  profile.lambda_upper_bound = 1e10;
  return profile;
}

std::vector<GtsamProfile> Profiles() {
  const GtsamProfile released{"released"};  // SPEC §6: the released code's LM settings
  GtsamProfile tight = Tight(released);
  tight.name = "tight";
  GtsamProfile tight_exact = tight;
  tight_exact.name = "tight_exact";
  tight_exact.exact_pose_jacobians = true;
  GtsamProfile dogleg = released;  // GTSAM's DoglegParams with the released stopping rule
  dogleg.name = "dogleg";
  dogleg.algorithm = GtsamProfile::Algorithm::kDogleg;
  GtsamProfile gauss_newton = released;
  gauss_newton.name = "gn";
  gauss_newton.algorithm = GtsamProfile::Algorithm::kGaussNewton;
  return {released, tight, tight_exact, dogleg, gauss_newton};
}

}  // namespace

std::vector<std::string> GtsamProfileNames() {
  std::vector<std::string> names;
  for (const GtsamProfile& profile : Profiles()) names.push_back(profile.name);
  return names;
}

Expected<GtsamProfile> GtsamProfileNamed(const std::string& name) {
  std::string known;
  for (const GtsamProfile& profile : Profiles()) {
    if (profile.name == name || (name.empty() && profile.name == "released")) return profile;
    known += (known.empty() ? "" : ", ") + profile.name;
  }
  return Error{"", 0, "unknown GTSAM profile '" + name + "' (known: " + known + ")"};
}

Expected<std::optional<GtsamProfile>> ParseBackend(const std::string& text) {
  if (text == "ceres") return std::optional<GtsamProfile>();
  if (text == "gtsam" || text.rfind("gtsam:", 0) == 0) {
    Expected<GtsamProfile> profile = GtsamProfileNamed(text == "gtsam" ? "" : text.substr(6));
    if (!profile.ok()) return profile.error();
    if (!GtsamBackendBuilt()) return Error{"", 0, GtsamBackendMissingMessage()};
    return std::optional<GtsamProfile>(std::move(profile).value());
  }
  std::string profiles;
  for (const std::string& name : GtsamProfileNames()) profiles += ", gtsam:" + name;
  return Error{"", 0, "unknown backend '" + text + "' (known: ceres, gtsam" + profiles + ")"};
}

std::string GtsamBackendMissingMessage() {
  return "this dynslam was built without the GTSAM backend: build GTSAM 4.2 with "
         "scripts/build_gtsam SOURCE PREFIX, which then builds dynslam against it "
         "(docs/GTSAM_BACKEND.md)";
}

}  // namespace dynslam
