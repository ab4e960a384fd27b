#include "src/gtsam/problem.h"

#include <algorithm>
#include <cmath>

#include <gtsam/linear/NoiseModel.h>
#include <gtsam/nonlinear/NonlinearEquality.h>
#include <gtsam/slam/BetweenFactor.h>
#include <gtsam/slam/PriorFactor.h>

#include "src/gtsam/factors.h"

namespace dynslam::gtsam_backend {
namespace {

namespace noise = gtsam::noiseModel;

// The rotation as gtsam::readG2o makes it: each quaternion component times 1/‖q‖.
gtsam::Rot3 ToRot3(const Pose& pose) {
  const Eigen::Quaterniond q = pose.rotation();
  const double f = 1.0 / std::sqrt(q.w() * q.w() + q.x() * q.x() + q.y() * q.y() + q.z() * q.z());
  return gtsam::Rot3::Quaternion(f * q.w(), f * q.x(), f * q.y(), f * q.z());
}

class ProblemBuilder {
 public:
  ProblemBuilder(const Graph& graph, const GtsamProfile& profile, const SolverOptions& options)
      : graph_(graph), profile_(profile), options_(options) {}

  Problem Build() {
    AddVariables();
    for (const PriorEdge& e : graph_.Edges<PriorEdge>()) AddPrior(e);
    for (const BetweenEdge& e : graph_.Edges<BetweenEdge>()) AddBetween(e);
    for (const PointEdge& e : graph_.Edges<PointEdge>()) {
      Add(e, new CameraPointFactor(e.pose, e.point, e.measurement, Noise(e, e.information)));
    }
    for (const MotionEdge& e : graph_.Edges<MotionEdge>()) AddMotion(e);
    for (const ObjectPointEdge& e : graph_.Edges<ObjectPointEdge>()) {
      Add(e, new ObjectPointFactor(e.camera, e.object_pose, e.point, e.measurement,
                                   Noise(e, e.information)));
    }
    for (const ObjectMotionEdge& e : graph_.Edges<ObjectMotionEdge>()) {
      Add(e, new ObjectMotionFactor(e.pose_prev, e.pose_curr, e.motion, e.point, e.measurement,
                                    options_.dsc_object_motion_residual, Noise(e, e.information)));
    }
    for (const KinematicEdge& e : graph_.Edges<KinematicEdge>()) {
      Add(e, new KinematicFactor(e.pose_prev, e.pose_curr, e.motion, Noise(e, e.information)));
    }
    for (const HybridPointEdge& e : graph_.Edges<HybridPointEdge>()) {
      Add(e, new HybridPointFactor(e.camera, e.motion, e.point, Constant(e.embedded),
                                   e.measurement, Noise(e, e.information)));
    }
    for (const HybridSmoothingEdge& e : graph_.Edges<HybridSmoothingEdge>()) {
      Add(e, new HybridSmoothingFactor(e.motion_a, e.motion_b, e.motion_c, Constant(e.embedded),
                                       Noise(e, e.information)));
    }
    if (options_.fix_first) HoldFirstPoseConstant();
    return std::move(problem_);
  }

 private:
  void AddVariables() {
    problem_.held_constant = UnusedVertices(graph_);
    for (const auto& [id, vertex] : graph_.vertices) {
      const RoleInfo* role = InfoOf(vertex.label.role);
      if ((role != nullptr && role->constant) ||
          std::binary_search(problem_.held_constant.begin(), problem_.held_constant.end(), id)) {
        continue;
      }
      if (vertex.type == VertexType::kPose) {
        problem_.values.insert(Key(id), ToGtsam(vertex.pose()));
      } else {
        problem_.values.insert(Key(id), gtsam::Point3(vertex.point()));
      }
    }
  }

  static gtsam::Key Key(VertexId id) { return static_cast<gtsam::Key>(id); }

  gtsam::Pose3 Constant(VertexId id) const { return ToGtsam(graph_.Find(id)->pose()); }

  // The file's information as GTSAM's Gaussian model (a diagonal one when it is diagonal, as
  // readG2o does), inside a robust model when SolverOptions::robust names one for the kind.
  template <typename Edge, typename Information>
  gtsam::SharedNoiseModel Noise(const Edge& edge, const Information& information) const {
    return Robust(KindOf(graph_, edge), noise::Gaussian::Information(information));
  }

  gtsam::SharedNoiseModel Robust(EdgeKind kind, const gtsam::SharedNoiseModel& gaussian) const {
    const RobustKernel& kernel = options_.robust[static_cast<int>(kind)];
    switch (kernel.type) {
      case RobustKernel::Type::kHuber:
        return noise::Robust::Create(noise::mEstimator::Huber::Create(kernel.threshold), gaussian);
      case RobustKernel::Type::kCauchy:
        return noise::Robust::Create(noise::mEstimator::Cauchy::Create(kernel.threshold), gaussian);
      case RobustKernel::Type::kNone: break;
    }
    return gaussian;
  }

  template <typename Edge>
  void Add(const Edge& edge, gtsam::NonlinearFactor* factor) {
    problem_.factors.push_back(gtsam::NonlinearFactor::shared_ptr(factor));
    problem_.kinds.push_back(KindOf(graph_, edge));
  }

  void AddPrior(const PriorEdge& e) {
    const gtsam::Pose3 Z = ToGtsam(e.measurement);
    const gtsam::SharedNoiseModel model = Noise(e, e.information);
    if (profile_.exact_pose_jacobians) {
      Add(e, new ExactPriorFactor(e.pose, Z, model));
    } else {
      Add(e, new gtsam::PriorFactor<gtsam::Pose3>(e.pose, Z, model));
    }
  }

  void AddBetween(const BetweenEdge& e) {
    const gtsam::Pose3 Z = ToGtsam(e.measurement);
    const gtsam::SharedNoiseModel model = Noise(e, e.information);
    if (profile_.exact_pose_jacobians) {
      Add(e, new ExactBetweenFactor(e.from, e.to, Z, model));
    } else {
      Add(e, new gtsam::BetweenFactor<gtsam::Pose3>(e.from, e.to, Z, model));
    }
  }

  // SPEC §7 item 2: the released code's residual with isotropic σ instead of the file's
  // information.
  void AddMotion(const MotionEdge& e) {
    const bool released = options_.dsc_motion_residual;
    const gtsam::SharedNoiseModel model =
        released ? Robust(EdgeKind::kMotion, noise::Isotropic::Sigma(3, options_.dsc_motion_sigma))
                 : Noise(e, e.information);
    Add(e, new PointMotionFactor(e.prev, e.curr, e.motion, e.measurement, released, model));
  }

  // SPEC §1.7 --fix-first: the smallest-id pose that is a variable, held by a hard constraint.
  void HoldFirstPoseConstant() {
    for (const auto& [id, vertex] : graph_.vertices) {
      if (vertex.type != VertexType::kPose || !problem_.values.exists(Key(id))) continue;
      problem_.factors.push_back(boost::make_shared<gtsam::NonlinearEquality<gtsam::Pose3>>(
          Key(id), problem_.values.at<gtsam::Pose3>(Key(id))));
      problem_.held_constant.push_back(id);
      return;
    }
  }

  const Graph& graph_;
  const GtsamProfile& profile_;
  const SolverOptions& options_;
  Problem problem_;
};

}  // namespace

gtsam::Pose3 ToGtsam(const Pose& pose) {
  return gtsam::Pose3(ToRot3(pose), gtsam::Point3(pose.translation()));
}

Pose FromGtsam(const gtsam::Pose3& pose) {
  return Pose::FromRotationTranslation(pose.rotation().toQuaternion(), pose.translation());
}

Expected<Problem> BuildProblem(const Graph& graph, const GtsamProfile& profile,
                               const SolverOptions& options) {
  if (graph.NumEdges() == 0) {
    return Error{"", 0, "the graph has no edges: there is nothing to solve"};
  }
  if (graph.Edges<PriorEdge>().empty() && !options.fix_first) {
    return Error{"", 0,
                 "the graph has no EDGE_SE3_PRIOR, so it is determined only up to a rigid motion "
                 "(SPEC §1.7); add a prior or pass --fix-first"};
  }
  return ProblemBuilder(graph, profile, options).Build();
}

CostByKind CostsByKind(const Problem& problem, const gtsam::Values& values) {
  CostByKind costs{};
  for (size_t i = 0; i < problem.kinds.size(); ++i) {
    costs[static_cast<int>(problem.kinds[i])] += problem.factors[i]->error(values);
  }
  return costs;
}

void WriteBack(const gtsam::Values& values, Graph* graph) {
  for (auto& [id, vertex] : graph->vertices) {
    const gtsam::Key key = static_cast<gtsam::Key>(id);
    if (!values.exists(key)) continue;
    if (vertex.type == VertexType::kPose) {
      vertex.set_pose(FromGtsam(values.at<gtsam::Pose3>(key)));
    } else {
      vertex.point() = values.at<gtsam::Point3>(key);
    }
  }
}

}  // namespace dynslam::gtsam_backend
