// SPEC §3 builders against the reference set's graphs, built by an independent implementation
// from the same front-end files: same vertex ids with the same labels, the same edges by kind,
// the same initial values and initial cost, and the same builder report (the synthetic scene
// was made to contain SPEC §3.1's edge cases, so its report pins them with exact counts).
#include "dynslam/formulation.h"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>

#include <gtest/gtest.h>

#include "dynslam/graph_io.h"
#include "dynslam/solver.h"
#include "reference_util.h"

namespace dynslam {
namespace {

namespace fs = std::filesystem;

using EdgeSet = std::set<std::vector<VertexId>>;

std::array<EdgeSet, kNumEdgeKinds> EdgesByKind(const Graph& g) {
  std::array<EdgeSet, kNumEdgeKinds> edges;
  auto add = [&](EdgeKind kind, std::vector<VertexId> ids) {
    edges[static_cast<int>(kind)].insert(std::move(ids));
  };
  for (const auto& e : g.priors) add(KindOf(g, e), {e.pose});
  for (const auto& e : g.betweens) add(KindOf(g, e), {e.from, e.to});
  for (const auto& e : g.point_edges) add(KindOf(g, e), {e.pose, e.point});
  for (const auto& e : g.motion_edges) add(EdgeKind::kMotion, {e.prev, e.curr, e.motion, e.camera});
  for (const auto& e : g.object_point_edges) add(EdgeKind::kObjectPoint, {e.camera, e.object_pose, e.point});
  for (const auto& e : g.object_motion_edges) {
    add(EdgeKind::kObjectMotion, {e.pose_prev, e.pose_curr, e.motion, e.point});
  }
  for (const auto& e : g.kinematic_edges) add(EdgeKind::kKinematic, {e.pose_prev, e.pose_curr, e.motion});
  return edges;
}

std::vector<std::string> Lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

struct Case {
  std::string scene;
  Formulation formulation;
};
void PrintTo(const Case& c, std::ostream* out) { *out << c.scene << "/" << FormulationName(c.formulation); }

std::vector<Case> Cases() {
  std::vector<Case> cases;
  for (const char* scene : {"synthetic", "kitti_0003"}) {
    for (const Formulation f : kAllFormulations) {
      if (fs::exists(fs::path(testing::ReferenceDir()) / scene / "graphs" /
                     (std::string(FormulationName(f)) + ".g2o"))) {
        cases.push_back({scene, f});
      }
    }
  }
  return cases;
}

class FormulationReferenceTest : public ::testing::TestWithParam<Case> {};

TEST_P(FormulationReferenceTest, BuildsTheReferenceGraph) {
  const fs::path scene = fs::path(testing::ReferenceDir()) / GetParam().scene;
  const std::string name = FormulationName(GetParam().formulation);
  Expected<Graph> front_end = ReadGraph((scene / "frontend.g2o").string());
  ASSERT_TRUE(front_end.ok()) << front_end.error().ToString();
  Expected<GroundTruth> gt = ReadGroundTruth((scene / "gt.txt").string());
  ASSERT_TRUE(gt.ok()) << gt.error().ToString();
  BuildReport report;
  Expected<Graph> built = BuildFormulation(*front_end, GetParam().formulation, BuildOptions{},
                                           &*gt, &report, "frontend.g2o");
  ASSERT_TRUE(built.ok()) << built.error().ToString();
  Expected<Graph> expected = ReadGraph((scene / "graphs" / (name + ".g2o")).string());
  ASSERT_TRUE(expected.ok()) << expected.error().ToString();

  // Vertices: ids, labels, values.
  ASSERT_EQ(built->vertices.size(), expected->vertices.size());
  double worst = 0;
  for (const auto& [id, want] : expected->vertices) {
    const Vertex* got = built->Find(id);
    ASSERT_NE(got, nullptr) << "vertex " << id;
    ASSERT_EQ(got->label.role, want.label.role) << "vertex " << id;
    EXPECT_EQ(got->label.object, want.label.object) << "vertex " << id;
    EXPECT_EQ(got->label.frame, want.label.frame) << "vertex " << id;
    EXPECT_EQ(got->label.tracklet, want.label.tracklet) << "vertex " << id;
    if (want.type == VertexType::kPose) {
      worst = std::max(worst, got->pose().rotation().angularDistance(want.pose().rotation()));
      worst = std::max(worst, (got->pose().translation() - want.pose().translation()).norm() /
                                  std::max(1.0, want.pose().translation().norm()));
    } else {
      worst = std::max(worst, (got->point() - want.point()).norm() / std::max(1.0, want.point().norm()));
    }
  }
  EXPECT_LT(worst, 1e-9) << "largest initial-value difference";

  // Edges by kind, as tuples of vertex ids.
  const auto got_edges = EdgesByKind(*built), want_edges = EdgesByKind(*expected);
  for (const EdgeKind kind : kAllEdgeKinds) {
    EXPECT_EQ(got_edges[static_cast<int>(kind)], want_edges[static_cast<int>(kind)]) << EdgeKindName(kind);
  }

  // Initial cost, in total and per kind.
  Expected<CostByKind> got_cost = EvaluateCost(*built);
  Expected<CostByKind> want_cost = EvaluateCost(*expected);
  ASSERT_TRUE(got_cost.ok() && want_cost.ok());
  const double total = TotalCost(*want_cost);
  EXPECT_LE(testing::RelativeDifference(TotalCost(*got_cost), total), 1e-9);
  for (int k = 0; k < kNumEdgeKinds; ++k) {
    EXPECT_LE(std::abs((*got_cost)[k] - (*want_cost)[k]), 1e-9 * std::abs((*want_cost)[k]) + 1e-15 * total)
        << EdgeKindName(kAllEdgeKinds[k]);
  }

  // The builder's report, line by line (exact counts of what was kept and dropped).
  EXPECT_EQ(report.lines, Lines((scene / "graphs" / (name + ".build.txt")).string()));
}

INSTANTIATE_TEST_SUITE_P(Reference, FormulationReferenceTest, ::testing::ValuesIn(Cases()),
                         [](const auto& info) {
                           return info.param.scene + "_" + FormulationName(info.param.formulation);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(FormulationReferenceTest);

}  // namespace
}  // namespace dynslam
