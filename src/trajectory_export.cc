#include "dynslam/trajectory_export.h"

#include <filesystem>
#include <sstream>

#include "dynslam/file_io.h"
#include "dynslam/metrics.h"
#include "src/number_text.h"

namespace dynslam {
namespace {

// `estimate` and, with ground truth, the true poses `truth(frame)` on the frames both have.
template <typename TruthAt>
void AddPair(const std::string& name, const std::map<int64_t, Pose>& estimate,
             const GroundTruth* ground_truth, TruthAt truth,
             std::vector<Trajectory>* estimates, std::vector<Trajectory>* truths) {
  Trajectory estimated{name + "_estimate", {}};
  Trajectory true_one{name + "_ground_truth", {}};
  for (const auto& [frame, pose] : estimate) {
    const Pose* true_pose = ground_truth ? truth(frame) : nullptr;
    if (ground_truth && true_pose == nullptr) continue;
    estimated.poses[frame] = pose;
    if (true_pose) true_one.poses[frame] = *true_pose;
  }
  if (estimated.poses.empty()) return;
  estimates->push_back(std::move(estimated));
  if (ground_truth) truths->push_back(std::move(true_one));
}

}  // namespace

const char* TrajectoryFormatName(TrajectoryFormat format) {
  return format == TrajectoryFormat::kTum ? "tum" : "kitti";
}

bool ParseTrajectoryFormat(const std::string& text, TrajectoryFormat* format) {
  for (const TrajectoryFormat f : {TrajectoryFormat::kTum, TrajectoryFormat::kKitti}) {
    if (text == TrajectoryFormatName(f)) {
      *format = f;
      return true;
    }
  }
  return false;
}

const OptionTable<ExportOptions>& ExportOptionTable() {
  static const OptionTable<ExportOptions> table = [] {
    Option<ExportOptions> formats = Declare<ExportOptions>(
        "export", "output", OptionType::kText,
        "also write the camera's and each object's trajectory, estimated and (with --gt) true, "
        "for evo: tum, kitti or tum,kitti (DIR/camera_estimate.tum.txt, "
        "DIR/object_J_ground_truth.kitti.txt, ...)",
        "FORMATS");
    formats.get = [](const ExportOptions& options) {
      std::string text;
      for (const TrajectoryFormat format : options.formats) {
        text += (text.empty() ? "" : ",") + std::string(TrajectoryFormatName(format));
      }
      return text;
    };
    formats.set = [](const std::string& text,
                     ExportOptions* options) -> std::optional<std::string> {
      std::vector<TrajectoryFormat> parsed;
      std::stringstream list(text);
      for (std::string item; std::getline(list, item, ',');) {
        if (!ParseTrajectoryFormat(item, &parsed.emplace_back())) {
          return "unknown format '" + item + "' (tum, kitti)";
        }
      }
      options->formats = std::move(parsed);
      return std::nullopt;
    };
    return OptionTable<ExportOptions>{
        formats, Real<ExportOptions>("export_rate", "output", &ExportOptions::rate_hz,
                                     "frames per second of the TUM timestamps (frame / rate)",
                                     1e-6, 1e9)};
  }();
  return table;
}

std::vector<Trajectory> ExportedTrajectories(const Graph& solved, const GroundTruth* ground_truth) {
  std::vector<Trajectory> estimates, truths;
  std::map<int64_t, Pose> cameras;
  for (const auto& [id, vertex] : solved.vertices) {
    if (vertex.label.role == Role::kCamera) cameras[vertex.label.frame] = vertex.pose();
  }
  AddPair("camera", cameras, ground_truth,
          [&](int64_t frame) { return ground_truth->Camera(frame); }, &estimates, &truths);

  // Without ground truth a world-centric graph composes no object poses (SPEC §5 starts them
  // at the true pose).
  std::map<int64_t, std::map<int64_t, Pose>> objects;  // object → frame → L
  const GroundTruth none;
  for (const auto& [key, pose] :
       EstimatedObjectPoses(solved, ground_truth ? *ground_truth : none)) {
    objects[key.first][key.second] = pose;
  }
  for (const auto& [object, poses] : objects) {
    AddPair("object_" + std::to_string(object), poses, ground_truth,
            [&, object = object](int64_t frame) { return ground_truth->Object(object, frame); },
            &estimates, &truths);
  }
  estimates.insert(estimates.end(), truths.begin(), truths.end());
  return estimates;
}

std::string FormatTrajectory(const Trajectory& trajectory, TrajectoryFormat format,
                             double rate_hz) {
  std::string text;
  for (const auto& [frame, pose] : trajectory.poses) {
    std::string line;
    if (format == TrajectoryFormat::kTum) {
      line = NumberText(static_cast<double>(frame) / rate_hz);
      AppendPoseFields(&line, pose, ' ');
    } else {
      const Eigen::Matrix3d rotation = pose.rotation().toRotationMatrix();
      const Eigen::Vector3d translation = pose.translation();
      for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 4; ++col) {
          if (!line.empty()) line += " ";
          line += NumberText(col < 3 ? rotation(row, col) : translation(row));
        }
      }
    }
    text += line + "\n";
  }
  return text;
}

Status WriteTrajectories(const std::string& dir, const std::vector<Trajectory>& trajectories,
                         TrajectoryFormat format, double rate_hz) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return Error{dir, 0, "cannot create the output directory: " + ec.message()};
  const std::string suffix = std::string(".") + TrajectoryFormatName(format) + ".txt";
  for (const Trajectory& trajectory : trajectories) {
    const std::string path = (std::filesystem::path(dir) / (trajectory.name + suffix)).string();
    if (Status s = WriteFileAtomically(path, FormatTrajectory(trajectory, format, rate_hz));
        !s.ok()) {
      return s;
    }
  }
  return Status::Ok();
}

}  // namespace dynslam
