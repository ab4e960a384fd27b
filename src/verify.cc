#include "dynslam/verify.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "dynslam/graph_io.h"
#include "dynslam/json.h"

namespace dynslam {
namespace {

namespace fs = std::filesystem;

struct RoleDifference {
  int64_t count = 0;
  double max_rotation = 0, sum_sq_rotation = 0;
  double max_translation = 0, sum_sq_translation = 0;
  VertexId worst_rotation_id = -1, worst_translation_id = -1;
};

double Number(const Json& json, std::initializer_list<const char*> path) {
  const Json* node = json.FindPath(path);
  return node != nullptr && node->is_number() ? node->number() : std::nan("");
}

std::string FormatId(VertexId id) { return id < 0 ? "-" : "vertex " + std::to_string(id); }

class Checker {
 public:
  explicit Checker(VerifyReport* report) : report_(report) {}

  // ours ≤ reference · (1 + tolerance) when one_sided; otherwise |ours − reference| relative to
  // |reference| + floor, where the floor keeps rounding noise (a kind's cost of 1e-25 beside a
  // total of 1e6) from being compared relatively (docs/TOLERANCES.md).
  void Relative(const std::string& name, double ours, double reference, double tolerance,
                bool one_sided, bool asserted, double floor = 0) {
    VerifyCheck check{name, ours, reference, 0, tolerance, asserted, true, ""};
    const double scale = std::abs(reference) + floor;
    if (scale == 0) {
      check.difference = std::abs(ours);
    } else {
      check.difference = (one_sided ? ours - reference : std::abs(ours - reference)) / scale;
    }
    check.pass = !std::isnan(ours) && !std::isnan(check.difference) &&
                 check.difference <= tolerance;
    Add(check);
  }

  void Absolute(const std::string& name, double ours, double reference, double tolerance,
                bool asserted, const std::string& note = "") {
    VerifyCheck check{name, ours, reference, std::abs(ours - reference), tolerance, asserted,
                      true, note};
    check.pass = !std::isnan(check.difference) && check.difference <= tolerance;
    Add(check);
  }

  // The difference itself is the value: ours = difference, reference = 0.
  void Bound(const std::string& name, double difference, double tolerance, bool asserted,
             const std::string& note) {
    VerifyCheck check{name, difference, 0, difference, tolerance, asserted,
                      !std::isnan(difference) && difference <= tolerance, note};
    Add(check);
  }

 private:
  void Add(const VerifyCheck& check) {
    if (check.asserted && !check.pass) report_->pass = false;
    report_->checks.push_back(check);
  }

  VerifyReport* report_;
};

void CompareCosts(const Json& ours, const Json& reference, const VerifyTolerances& tol,
                  Checker& checker) {
  const double initial = Number(reference, {"initial_cost"});
  checker.Relative("initial_cost", Number(ours, {"initial_cost"}), initial,
                   tol.initial_cost_relative, false, true);
  checker.Relative("final_cost", Number(ours, {"final_cost"}), Number(reference, {"final_cost"}),
                   tol.final_cost_relative, true, true);
  for (const EdgeKind kind : kAllEdgeKinds) {
    const char* name = EdgeKindName(kind);
    const double ref_initial = Number(reference, {"cost_by_kind", "initial", name});
    if (std::isnan(ref_initial)) continue;
    checker.Relative(std::string("initial_cost.") + name,
                     Number(ours, {"cost_by_kind", "initial", name}), ref_initial,
                     tol.initial_cost_relative, false, true, 1e-6 * std::abs(initial));
  }
  for (const EdgeKind kind : kAllEdgeKinds) {
    const char* name = EdgeKindName(kind);
    const double ref_final = Number(reference, {"cost_by_kind", "final", name});
    if (std::isnan(ref_final) || ref_final == 0) continue;
    checker.Relative(std::string("final_cost.") + name,
                     Number(ours, {"cost_by_kind", "final", name}), ref_final,
                     tol.final_cost_relative, false, false);
  }
  checker.Absolute("iterations", Number(ours, {"iterations"}), Number(reference, {"iterations"}),
                   INFINITY, false);
}

// Rotation angle (rad) and translation distance (m) of every vertex present in both.
Status CompareVariables(const Graph& ours, const Graph& reference, const VerifyTolerances& tol,
                        Checker& checker) {
  std::array<RoleDifference, kAllRoles.size()> by_role{};
  for (const auto& [id, ref] : reference.vertices) {
    const Vertex* mine = ours.Find(id);
    if (mine == nullptr) return Error{"", 0, "our solution has no vertex " + std::to_string(id)};
    if (mine->type != ref.type) {
      return Error{"", 0, "vertex " + std::to_string(id) + " is a pose on one side only"};
    }
    size_t r = 0;
    while (r < kAllRoles.size() && kAllRoles[r] != ref.label.role) ++r;
    if (r == kAllRoles.size()) continue;  // unlabelled reference vertex: no role to report under
    RoleDifference& d = by_role[r];
    ++d.count;
    double translation;
    if (ref.type == VertexType::kPose) {
      const double rotation =
          mine->pose().rotation().normalized().angularDistance(ref.pose().rotation().normalized());
      d.sum_sq_rotation += rotation * rotation;
      if (rotation > d.max_rotation) {
        d.max_rotation = rotation;
        d.worst_rotation_id = id;
      }
      translation = (mine->pose().translation() - ref.pose().translation()).norm();
    } else {
      translation = (mine->point() - ref.point()).norm();
    }
    d.sum_sq_translation += translation * translation;
    if (translation > d.max_translation) {
      d.max_translation = translation;
      d.worst_translation_id = id;
    }
  }
  for (size_t r = 0; r < kAllRoles.size(); ++r) {
    const RoleDifference& d = by_role[r];
    if (d.count == 0) continue;
    const Role role = kAllRoles[r];
    // Object poses and object-frame points are reported only: at frames with few tracked
    // points they are not determined, and equal-cost solutions differ (docs/SPEC_NOTES.md).
    const bool asserted = role == Role::kCamera || role == Role::kStaticPoint ||
                          role == Role::kMotion;
    const std::string name = RoleName(role);
    const std::string count = std::to_string(d.count) + " variables";
    if (role == Role::kCamera || role == Role::kMotion || role == Role::kObjectPose) {
      checker.Bound(name + ".rotation_max_rad", d.max_rotation, tol.rotation_rad, asserted,
                    "worst " + FormatId(d.worst_rotation_id) + ", " + count);
      checker.Bound(name + ".rotation_rms_rad", std::sqrt(d.sum_sq_rotation / d.count),
                    tol.rotation_rad, false, "");
    }
    checker.Bound(name + ".translation_max_m", d.max_translation, tol.translation_m, asserted,
                  "worst " + FormatId(d.worst_translation_id) + ", " + count);
    checker.Bound(name + ".translation_rms_m", std::sqrt(d.sum_sq_translation / d.count),
                  tol.translation_m, false, "");
  }
  return Status::Ok();
}

// Every numeric leaf of the reference metrics: counts must be equal, means within tolerance.
void CompareMetrics(const Json& ours, const Json& reference, const std::string& prefix,
                    const VerifyTolerances& tol, bool asserted, Checker& checker) {
  for (const auto& [key, value] : reference.members()) {
    const std::string name = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object()) {
      const Json* mine = ours.Find(key);
      if (mine != nullptr) {
        CompareMetrics(*mine, value, name, tol, asserted, checker);
      } else {
        checker.Bound("metrics." + name, NAN, 0, asserted, "missing from our metrics");
      }
    } else if (value.is_number()) {
      const Json* mine = ours.Find(key);
      const double our_value = mine != nullptr && mine->is_number() ? mine->number() : NAN;
      const bool is_mean = key.rfind("mean_", 0) == 0;
      checker.Absolute("metrics." + name, our_value, value.number(), is_mean ? tol.metric : 0,
                       asserted);
    }
  }
}

}  // namespace

Expected<VerifyReport> Verify(const std::string& result_dir, const std::string& reference_dir,
                              const VerifyTolerances& tolerances) {
  const fs::path ours_dir(result_dir), ref_dir(reference_dir);
  Expected<Json> ours = Json::ReadFile((ours_dir / "summary.json").string());
  if (!ours.ok()) return ours.error();
  Expected<Json> reference = Json::ReadFile((ref_dir / "summary.json").string());
  if (!reference.ok()) return reference.error();

  VerifyReport report;
  Checker checker(&report);
  CompareCosts(*ours, *reference, tolerances, checker);

  const fs::path ref_solution = ref_dir / "solution.g2o";
  if (fs::exists(ref_solution)) {
    Expected<Graph> ref_graph = ReadGraph(ref_solution.string());
    if (!ref_graph.ok()) return ref_graph.error();
    Expected<Graph> our_graph = ReadGraph((ours_dir / "solution.g2o").string());
    if (!our_graph.ok()) return our_graph.error();
    if (Status s = CompareVariables(*our_graph, *ref_graph, tolerances, checker);
        !s.ok()) {
      return Error{(ours_dir / "solution.g2o").string(), 0, s.error().message};
    }
  }

  const fs::path ref_metrics = ref_dir / "metrics.json";
  if (fs::exists(ref_metrics)) {
    Expected<Json> metrics = Json::ReadFile(ref_metrics.string());
    if (!metrics.ok()) return metrics.error();
    const Json* our_metrics = ours->Find("metrics");
    const Json empty = Json::Object();
    const Json* object_centric = metrics->Find("object_centric");
    for (const char* family : {"camera", "object_motion", "object_pose"}) {
      const Json* node = metrics->Find(family);
      if (node == nullptr) continue;
      // Object-centric pose metrics follow the object poses, which are reported only (above).
      const bool asserted = std::string(family) != "object_pose" || object_centric == nullptr ||
                            !object_centric->boolean();
      Json reference_family = Json::Object();
      reference_family.Set(family, *node);
      CompareMetrics(our_metrics ? *our_metrics : empty, reference_family, "", tolerances,
                     asserted, checker);
    }
  }
  return report;
}

std::string VerifyReport::ToText() const {
  std::string text;
  char line[512];
  std::snprintf(line, sizeof(line), "%-44s %22s %22s %10s %10s  %s\n", "check", "ours",
                "reference", "difference", "tolerance", "result");
  text += line;
  for (const VerifyCheck& c : checks) {
    const char* result = !c.asserted ? (c.pass ? "(info)" : "(info, over)")
                                     : (c.pass ? "ok" : "FAIL");
    std::snprintf(line, sizeof(line), "%-44s %22.15g %22.15g %10.3g %10.3g  %s%s%s\n",
                  c.name.c_str(), c.ours, c.reference, c.difference, c.tolerance, result,
                  c.note.empty() ? "" : "  ", c.note.c_str());
    text += line;
  }
  text += pass ? "PASS\n" : "FAIL\n";
  return text;
}

}  // namespace dynslam
