// Scenes for the simulator: true camera and object trajectories from KITTI Tracking ground truth
// or from a small hand-made layout (simulate.h; conventions in docs/SIMULATOR.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Geometry>

#include "dynslam/se3.h"
#include "dynslam/simulate.h"

namespace dynslam {
namespace {

constexpr double kPi = 3.14159265358979323846;

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Extent (largest distance between two centres) and the largest speed over windows of at least
// `window` frames (the whole track when it is shorter), from frame-sorted centres.
void MotionEvidence(const std::vector<std::pair<int64_t, Eigen::Vector3d>>& centres,
                    int64_t window, double* extent, double* max_speed) {
  *extent = 0;
  *max_speed = 0;
  const size_t n = centres.size();
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = a + 1; b < n; ++b) {
      *extent = std::max(*extent, (centres[a].second - centres[b].second).norm());
    }
  }
  if (n < 2) return;
  const int64_t span = centres.back().first - centres.front().first;
  const int64_t w = std::min(window, span);
  for (size_t a = 0, b = 0; a < n; ++a) {
    while (b < n && centres[b].first - centres[a].first < w) ++b;
    if (b == n) break;
    const double dt = static_cast<double>(centres[b].first - centres[a].first) / kKittiFrameRate;
    *max_speed = std::max(*max_speed, (centres[b].second - centres[a].second).norm() / dt);
  }
}

std::string FrameMapping(const std::string& what, int64_t first, int64_t last) {
  return what + ", frames " + std::to_string(first) + ":" + std::to_string(last) +
         " (frame k here is " + (what.rfind("KITTI", 0) == 0 ? "KITTI" : "source") +
         " frame k+" + std::to_string(first) + ")";
}

void AddObjectLists(Scene* scene) {
  std::string moving = "moving objects:", parked = "parked objects (static points):";
  for (const SceneObject& object : scene->objects) {
    if (object.moving) {
      moving += " " + std::to_string(object.id) + "(" + object.type + ")";
    } else {
      parked += " " + std::to_string(object.id);
    }
  }
  scene->header.push_back(moving);
  scene->header.push_back(parked);
}

// Camera model of the synthetic scene: KITTI 0003's P2 and colour stereo baseline.
CameraModel KittiLikeCamera() {
  CameraModel camera;
  camera.projection << 721.5377, 0, 609.5593, 44.85728,  //
      0, 721.5377, 172.854, 0.2163791,                   //
      0, 0, 1, 0.002745884;
  camera.baseline = 0.5327;
  return camera;
}

// A pose with heading θ in the camera-0 ground plane (camera y down: θ turns z towards x) whose
// local x axis points along the heading when `along_x`, else its local z axis does (cameras).
Pose HeadingPose(double theta, const Eigen::Vector3d& t, bool along_x) {
  Eigen::Quaterniond q(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()));
  if (along_x) q = q * Eigen::Quaterniond(Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitY()));
  return Pose::FromRotationTranslation(q.normalized(), t);
}

}  // namespace

Expected<Scene> MakeKittiScene(const KittiSequence& sequence, const SimulateOptions& options) {
  const int64_t n = static_cast<int64_t>(sequence.oxts.size());
  const int64_t first = options.first_frame;
  const int64_t last = options.last_frame < 0 ? n : options.last_frame;
  if (first < 0 || last > n || last - first < 2) {
    return Error{"", 0, "frames " + std::to_string(first) + ":" + std::to_string(last) +
                            " are not a range of at least 2 of the sequence's " +
                            std::to_string(n) + " frames"};
  }
  Scene scene;
  scene.first_source_frame = first;
  scene.cameras = CameraPoses(sequence, first, last);
  scene.camera.projection = sequence.calib.P[2];
  const double f = sequence.calib.P[2](0, 0);
  scene.camera.baseline = (sequence.calib.P[2](0, 3) - sequence.calib.P[3](0, 3)) / f;
  if (!(scene.camera.baseline > 0.1 && scene.camera.baseline < 2.0)) {
    scene.camera.baseline = -sequence.calib.P[1](0, 3) / sequence.calib.P[1](0, 0);
  }
  if (!(scene.camera.baseline > 0.1 && scene.camera.baseline < 2.0)) {
    return Error{"", 0, "calib: no plausible stereo baseline from P2/P3 or P0/P1"};
  }
  scene.header.push_back(
      FrameMapping("KITTI Tracking training sequence " + sequence.name, first, last));

  // Labels of the chosen types in the range, by track id.
  std::map<int64_t, std::vector<const LabelRecord*>> tracks;
  for (const LabelRecord& label : sequence.labels) {
    if (label.track_id < 0 || label.frame < first || label.frame >= last) continue;
    if (std::find(options.object_types.begin(), options.object_types.end(), label.type) ==
        options.object_types.end()) {
      continue;
    }
    tracks[label.track_id].push_back(&label);
  }
  for (auto& [id, labels] : tracks) {
    std::stable_sort(labels.begin(), labels.end(),
                     [](const LabelRecord* a, const LabelRecord* b) { return a->frame < b->frame; });
    SceneObject object;
    object.id = id;
    object.type = labels.front()->type;
    std::vector<double> l, h, w;
    std::vector<std::pair<int64_t, Eigen::Vector3d>> centres;
    for (size_t i = 0; i < labels.size(); ++i) {
      const LabelRecord& label = *labels[i];
      if (i > 0 && labels[i - 1]->frame == label.frame) {
        return Error{"label_02/" + sequence.name + ".txt", label.line,
                     "object " + std::to_string(id) + " is labelled twice in frame " +
                         std::to_string(label.frame)};
      }
      const int64_t k = label.frame - first;
      const Pose L = Compose(scene.cameras[k], ObjectInCamera(label));
      object.poses[k] = L;
      centres.emplace_back(k, L.translation());
      l.push_back(label.length);
      h.push_back(label.height);
      w.push_back(label.width);
    }
    object.size = Eigen::Vector3d(Median(l), Median(h), Median(w));
    MotionEvidence(centres, options.speed_window_frames, &object.extent, &object.max_speed);
    object.moving =
        object.extent >= options.moving_min_extent && object.max_speed >= options.moving_min_speed;
    if (!object.moving) {
      // One pose for the whole range: the mean centre and the rotation of the middle label.
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const auto& c : centres) mean += c.second;
      mean /= static_cast<double>(centres.size());
      object.parked_pose = object.poses[centres[centres.size() / 2].first];
      object.parked_pose.translation() = mean;
    }
    scene.objects.push_back(std::move(object));
  }
  AddObjectLists(&scene);
  return scene;
}

Scene MakeSyntheticScene(const SimulateOptions& options) {
  const int64_t frames = options.last_frame > options.first_frame
                             ? options.last_frame - options.first_frame
                             : std::max<int64_t>(options.synthetic_frames, 2);
  Scene scene;
  scene.camera = KittiLikeCamera();
  scene.header.push_back("synthetic scene, " + std::to_string(frames) + " frames");
  const double dt = 1.0 / kKittiFrameRate;
  // The road: an arc of curvature κ through the first camera, heading θ = κ·s at arc length s.
  const double kappa = 0.0025;  // 1/m: a 400 m radius, gently right
  const auto road = [&](double s, double lateral, double y, bool reverse) {
    const double theta = kappa * s;
    const Eigen::Vector3d centre((1 - std::cos(theta)) / kappa, y, std::sin(theta) / kappa);
    const Eigen::Vector3d right(std::cos(theta), 0, -std::sin(theta));
    return HeadingPose(reverse ? theta + kPi : theta, centre + lateral * right, true);
  };
  const double camera_speed = 8.0;  // m/s
  for (int64_t k = 0; k < frames; ++k) {
    const double s = camera_speed * dt * static_cast<double>(k);
    const double theta = kappa * s;
    scene.cameras.push_back(HeadingPose(
        theta, Eigen::Vector3d((1 - std::cos(theta)) / kappa, 0, std::sin(theta) / kappa), false));
  }
  scene.cameras.front() = Pose::Identity();
  const Eigen::Vector3d car(3.9, 1.5, 1.6);  // l, h, w
  const double y = options.camera_height - car.y() / 2;  // centre height, camera y down
  auto add = [&](int64_t id, const std::string& description, bool moving, auto pose_at) {
    SceneObject object;
    object.id = id;
    object.type = "Car";
    object.size = car;
    object.moving = moving;
    for (int64_t k = 0; k < frames; ++k) object.poses[k] = pose_at(dt * static_cast<double>(k));
    object.parked_pose = object.poses[0];
    scene.objects.push_back(std::move(object));
    scene.header.push_back("object " + std::to_string(id) + ": " + description);
  };
  add(1, "lead car, same lane, 12 m ahead at 9 m/s", true,
      [&](double t) { return road(12.0 + 9.0 * t, 0.0, y, false); });
  add(2, "oncoming car in the left lane at 8 m/s (leaves view)", true,
      [&](double t) { return road(40.0 - 8.0 * t, -3.5, y, true); });
  add(3, "car turning across from the right at 5 m/s, 0.3 rad/s", true, [&](double t) {
    const double v = 5.0, w = 0.3, theta0 = -kPi / 2, theta = theta0 + w * t;
    const Eigen::Vector3d p(12.0 - v / w * (std::cos(theta) - std::cos(theta0)), y,
                            30.0 + v / w * (std::sin(theta) - std::sin(theta0)));
    return HeadingPose(theta, p, true);
  });
  add(4, "parked car on the right", false, [&](double) { return road(20.0, 3.5, y, false); });
  for (SceneObject& object : scene.objects) {
    std::vector<std::pair<int64_t, Eigen::Vector3d>> centres;
    for (const auto& [k, L] : object.poses) centres.emplace_back(k, L.translation());
    MotionEvidence(centres, options.speed_window_frames, &object.extent, &object.max_speed);
  }
  AddObjectLists(&scene);
  return scene;
}

}  // namespace dynslam
