// Valid syntax, bad geometry: front ends that read fine but are degenerate. Each case is the
// synthetic scene (12 frames, seed 1) with one degeneracy put in, built into every formulation
// and solved with the defaults but at most 100 steps. Each formulation must end either solved
// (usable, with a finite cost and finite values) or in an Error that names the edge or vertex;
// never a silent NaN. Each test prints its row of docs/DEGENERATE_GEOMETRY.md (what each
// formulation gave):
//   build/release/tests/degenerate_geometry_test | grep '^|'
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "dynslam/formulation.h"
#include "dynslam/se3.h"
#include "dynslam/simulate.h"
#include "dynslam/solver.h"

namespace dynslam {
namespace {

constexpr int64_t kObject = 1;  // the lead car, seen in every frame of the synthetic scene
constexpr int kMaxSteps = 100;  // enough to show where a solve goes; the defaults allow 500

SimulateOptions Options() {
  SimulateOptions options;
  options.seed = 1;
  options.synthetic_frames = 12;
  return options;
}

SimulatedScene SimulateScene(const Scene& scene) {
  Expected<SimulatedScene> sim = Simulate(scene, Options());
  EXPECT_TRUE(sim.ok()) << sim.error().ToString();
  return sim.ok() ? std::move(sim).value() : SimulatedScene{};
}

SimulatedScene SyntheticScene() { return SimulateScene(MakeSyntheticScene(Options())); }

bool AllFinite(const Graph& graph) {
  for (const auto& [id, vertex] : graph.vertices) {
    for (const double v : vertex.value) {
      if (!std::isfinite(v)) return false;
    }
  }
  return true;
}

// What one formulation gives: "solved (cost A → B, N steps)" or "error: …". Fails the test on a
// usable solve with a non-finite number, a failed solve, or an error that names nothing.
std::string Outcome(const Graph& front_end, Formulation formulation, const GroundTruth& gt) {
  BuildReport build_report;
  Expected<Graph> built = BuildFormulation(front_end, formulation, BuildOptions(), &gt,
                                           &build_report);
  if (!built.ok()) {
    const std::string message = built.error().ToString();
    EXPECT_TRUE(message.find("vertex") != std::string::npos ||
                message.find("edge") != std::string::npos)
        << "a build error that names no vertex or edge: " << message;
    return "build error: " + message;
  }
  SolverOptions options;
  options.max_iterations = kMaxSteps;
  Expected<SolveReport> report = Solve(options, &*built);
  if (!report.ok()) {
    const std::string message = report.error().ToString();
    EXPECT_TRUE(message.find("vertex") != std::string::npos ||
                message.find("edge") != std::string::npos || message.find(':') != std::string::npos)
        << "a solve error that names no vertex or edge: " << message;
    return "error: " + message;
  }
  EXPECT_TRUE(report->usable) << report->termination_detail;
  EXPECT_TRUE(std::isfinite(report->final_cost));
  EXPECT_TRUE(AllFinite(*built)) << "a usable solve holds a non-finite value";
  char text[160];
  std::snprintf(text, sizeof(text), "solved: %.4g → %.4g, %d steps (%s)", report->initial_cost,
                report->final_cost, report->steps, report->termination.c_str());
  const std::string kept = "kept: object " + std::to_string(kObject) + " ";
  const bool object_kept = std::any_of(build_report.lines.begin(), build_report.lines.end(),
                                       [&](const std::string& line) { return line.rfind(kept, 0) == 0; });
  return text + std::string(object_kept ? "" : "; no segment of the object kept");
}

// Every formulation from `front_end`, with the row for docs/DEGENERATE_GEOMETRY.md on stdout.
void SolveEveryFormulation(const std::string& name, const Graph& front_end,
                           const GroundTruth& gt) {
  std::string row = "| " + name + " |";
  for (const Formulation formulation : kAllFormulations) {
    SCOPED_TRACE(FormulationName(formulation));
    row += " " + Outcome(front_end, formulation, gt) + " |";
  }
  std::printf("%s\n", row.c_str());
}

// Puts every dynamic point of kObject at its object-frame coordinates `layout(tracklet)`, exactly
// (values and measurements from the true camera and object poses).
void ReshapeObject(SimulatedScene* sim, const std::function<Eigen::Vector3d(int64_t)>& layout) {
  Graph& graph = sim->graph;
  for (auto& [id, vertex] : graph.vertices) {
    if (vertex.label.role != Role::kDynamicPoint || vertex.label.object != kObject) continue;
    const Pose* object = sim->ground_truth.Object(kObject, vertex.label.frame);
    ASSERT_NE(object, nullptr);
    vertex.point() = Transform(*object, layout(vertex.label.tracklet));
  }
  for (PointEdge& edge : graph.Edges<PointEdge>()) {
    const Vertex& point = *graph.Find(edge.point);
    if (point.label.role != Role::kDynamicPoint || point.label.object != kObject) continue;
    const Pose camera{sim->true_values.at(edge.pose)};
    edge.measurement = Transform(Inverse(camera), point.point());
  }
}

// Sets the measurement of every dynamic point of kObject seen in `frame` to `measurement(z)` and
// the point's value to where that measurement puts it.
void MoveMeasurements(SimulatedScene* sim, int64_t frame,
                      const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& measurement) {
  Graph& graph = sim->graph;
  for (PointEdge& edge : graph.Edges<PointEdge>()) {
    Vertex& point = *graph.Find(edge.point);
    if (point.label.role != Role::kDynamicPoint || point.label.object != kObject ||
        point.label.frame != frame) {
      continue;
    }
    edge.measurement = measurement(edge.measurement);
    point.point() = Transform(Pose{sim->true_values.at(edge.pose)}, edge.measurement);
  }
}

// The control row: the scene as simulated.
TEST(DegenerateGeometry, UndisturbedScene) {
  SimulatedScene sim = SyntheticScene();
  SolveEveryFormulation("none (the scene as simulated)", sim.graph, sim.ground_truth);
}

TEST(DegenerateGeometry, DynamicPointsAtTheCameraCentre) {
  SimulatedScene sim = SyntheticScene();
  MoveMeasurements(&sim, 6, [](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero(); });
  SolveEveryFormulation("an object's points at the camera centre in one frame (z = 0)",
                        sim.graph, sim.ground_truth);
}

TEST(DegenerateGeometry, DynamicPointsBehindTheCamera) {
  SimulatedScene sim = SyntheticScene();
  MoveMeasurements(&sim, 6, [](const Eigen::Vector3d& z) {
    return Eigen::Vector3d(z.x(), z.y(), -z.z());
  });
  SolveEveryFormulation("an object's points behind the camera in one frame (depth negated)",
                        sim.graph, sim.ground_truth);
}

TEST(DegenerateGeometry, ObjectPointsOnOneLine) {
  SimulatedScene sim = SyntheticScene();
  ReshapeObject(&sim, [](int64_t tracklet) {
    return Eigen::Vector3d(0.3 * static_cast<double>(tracklet % 13) - 1.8, 0, 0);
  });
  SolveEveryFormulation("every point of an object on one line (its x axis)", sim.graph,
                        sim.ground_truth);
}

TEST(DegenerateGeometry, CoincidentObjectPoints) {
  SimulatedScene sim = SyntheticScene();
  ReshapeObject(&sim, [](int64_t) { return Eigen::Vector3d(0.5, -0.2, 0.1); });
  SolveEveryFormulation("every point of an object at one place", sim.graph, sim.ground_truth);
}

// The object turns by exactly π about its vertical axis between frames 5 and 6: the SE(3) Log
// of that motion is at the edge of its domain.
TEST(DegenerateGeometry, MotionOfPi) {
  Scene scene = MakeSyntheticScene(Options());
  for (SceneObject& object : scene.objects) {
    if (object.id != kObject) continue;
    Vector6d half_turn = Vector6d::Zero();
    half_turn(1) = M_PI;
    for (auto& [frame, pose] : object.poses) {
      if (frame >= 6) pose = Compose(pose, Exp(half_turn));
    }
  }
  SimulatedScene sim = SimulateScene(scene);
  SolveEveryFormulation("a motion of exactly 180° (the object turns about its vertical axis)",
                        sim.graph, sim.ground_truth);
}

TEST(DegenerateGeometry, ObjectSeenInOneFrameOnly) {
  Scene scene = MakeSyntheticScene(Options());
  for (SceneObject& object : scene.objects) {
    if (object.id == kObject) object.poses.erase(std::next(object.poses.begin()), object.poses.end());
  }
  SimulatedScene sim = SimulateScene(scene);
  SolveEveryFormulation("an object seen in one frame only", sim.graph, sim.ground_truth);
}

void ScaleDynamicPointInformation(double scale) {
  SimulatedScene sim = SyntheticScene();
  for (PointEdge& edge : sim.graph.Edges<PointEdge>()) {
    if (edge.is_dynamic) edge.information *= scale;
  }
  char name[80];
  std::snprintf(name, sizeof(name), "every dynamic point edge's information × %g", scale);
  SolveEveryFormulation(name, sim.graph, sim.ground_truth);
}

TEST(DegenerateGeometry, TinyInformation) { ScaleDynamicPointInformation(1e-12); }
TEST(DegenerateGeometry, HugeInformation) { ScaleDynamicPointInformation(1e12); }

TEST(DegenerateGeometry, CameraPriorFarFromTheOdometry) {
  SimulatedScene sim = SyntheticScene();
  ASSERT_EQ(sim.graph.Edges<PriorEdge>().size(), 1u);
  Pose& prior = sim.graph.Edges<PriorEdge>()[0].measurement;
  prior = Compose(Exp((Vector6d() << 0, 0, 0, 1000, 0, 0).finished()), prior);
  SolveEveryFormulation("the camera prior 1 km from where the odometry starts", sim.graph,
                        sim.ground_truth);
}

}  // namespace
}  // namespace dynslam
