#include "dynslam/verify.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "dynslam/graph_io.h"
#include "src/json_io.h"

namespace dynslam {
namespace {

namespace fs = std::filesystem;

struct RoleDifference {
  int64_t count = 0;
  double max_rotation = 0, sum_sq_rotation = 0;
  double max_translation = 0, sum_sq_translation = 0;
  VertexId worst_rotation_id = -1, worst_translation_id = -1;
};

// A JSON file whose top level is an object (summary.json, metrics.json).
Expected<JsonValue> ReadJsonObject(const std::string& path) {
  Expected<JsonValue> json = ReadJsonFile(path);
  if (json.ok() && !json->is_object()) return Error{path, 1, "expected a JSON object"};
  return json;
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

void CompareCosts(const JsonValue& ours, const JsonValue& reference, const VerifyTolerances& tol,
                  Checker& checker) {
  const double initial = NumberAt(reference, {"initial_cost"});
  checker.Relative("initial_cost", NumberAt(ours, {"initial_cost"}), initial,
                   tol.initial_cost_relative, false, true);
  checker.Relative("final_cost", NumberAt(ours, {"final_cost"}), NumberAt(reference, {"final_cost"}),
                   tol.final_cost_relative, true, true);
  for (const EdgeKind kind : kAllEdgeKinds) {
    const char* name = EdgeKindName(kind);
    const double ref_initial = NumberAt(reference, {"cost_by_kind", "initial", name});
    if (std::isnan(ref_initial)) continue;
    checker.Relative(std::string("initial_cost.") + name,
                     NumberAt(ours, {"cost_by_kind", "initial", name}), ref_initial,
                     tol.initial_cost_relative, false, true, 1e-6 * std::abs(initial));
  }
  for (const EdgeKind kind : kAllEdgeKinds) {
    const char* name = EdgeKindName(kind);
    const double ref_final = NumberAt(reference, {"cost_by_kind", "final", name});
    if (std::isnan(ref_final) || ref_final == 0) continue;
    checker.Relative(std::string("final_cost.") + name,
                     NumberAt(ours, {"cost_by_kind", "final", name}), ref_final,
                     tol.final_cost_relative, false, false);
  }
  checker.Absolute("iterations", NumberAt(ours, {"iterations"}), NumberAt(reference, {"iterations"}),
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
    const bool asserted = tol.assert_variables && (role == Role::kCamera ||
                                                   role == Role::kStaticPoint ||
                                                   role == Role::kMotion);
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
void CompareMetrics(const JsonValue& ours, const JsonValue& reference, const std::string& prefix,
                    const VerifyTolerances& tol, bool asserted, Checker& checker) {
  for (const auto& [key, value] : reference.items()) {
    const std::string name = prefix.empty() ? key : prefix + "." + key;
    const auto mine = ours.is_object() ? ours.find(key) : ours.end();
    if (value.is_object()) {
      // One object's means follow that object's variables: asserted with them.
      const bool leaf_asserted = asserted && (key != "per_object" || tol.assert_variables);
      if (mine != ours.end()) {
        CompareMetrics(*mine, value, name, tol, leaf_asserted, checker);
      } else {
        checker.Bound("metrics." + name, NAN, 0, asserted, "missing from our metrics");
      }
    } else if (value.is_number()) {
      const double our_value =
          mine != ours.end() && mine->is_number() ? mine->get<double>() : NAN;
      const bool is_mean = key.rfind("mean_", 0) == 0;
      checker.Absolute("metrics." + name, our_value, value.get<double>(),
                       is_mean ? tol.metric : 0, asserted);
    }
  }
}

}  // namespace

Expected<VerifyReport> Verify(const std::string& result_dir, const std::string& reference_dir,
                              const VerifyTolerances& tolerances) {
  const fs::path ours_dir(result_dir), ref_dir(reference_dir);
  Expected<JsonValue> ours = ReadJsonObject((ours_dir / "summary.json").string());
  if (!ours.ok()) return ours.error();
  Expected<JsonValue> reference = ReadJsonObject((ref_dir / "summary.json").string());
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
    Expected<JsonValue> metrics = ReadJsonObject(ref_metrics.string());
    if (!metrics.ok()) return metrics.error();
    const auto our_metrics = ours->find("metrics");
    const auto object_centric_entry = metrics->find("object_centric");
    const bool object_centric = object_centric_entry != metrics->end() &&
                                *object_centric_entry == true;
    for (const char* family : {"camera", "object_motion", "object_pose"}) {
      if (!metrics->contains(family)) continue;
      // Object-centric pose metrics follow the object poses, which are reported only (above).
      const bool asserted = std::string(family) != "object_pose" || !object_centric;
      CompareMetrics(our_metrics != ours->end() ? *our_metrics : JsonValue::object(),
                     JsonValue{{family, (*metrics)[family]}}, "", tolerances, asserted, checker);
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
