// The front end's output from a Scene: tracked points, noisy measurements, odometry, motions
// (simulate.h; conventions and choices in docs/SIMULATOR.md).
#include "dynslam/simulate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "dynslam/se3.h"

namespace dynslam {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

// std::mt19937_64 is specified bit for bit by the standard; the distributions are not, so the
// uniform and normal transforms are ours: bytes are the same with every standard library.
class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double Normal() {  // Box–Muller, both values used
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - Uniform();  // (0, 1]
    const double u2 = Uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * kPi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * kPi * u2);
  }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0;
};

Eigen::Matrix3d RotationOf(const Pose& pose) { return pose.rotation().toRotationMatrix(); }

// Ray o + t·d (t > 0) against the box |x_i| ≤ half_i: entry distance and outward face normal.
bool RayBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& half,
            double* t_hit, Eigen::Vector3d* normal) {
  double t_min = -kInf, t_max = kInf;
  int axis = -1;
  double sign = 0;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (std::abs(o[i]) > half[i]) return false;
      continue;
    }
    double t1 = (-half[i] - o[i]) / d[i], t2 = (half[i] - o[i]) / d[i];
    double entry_sign = -1;  // entering through the −half face
    if (t1 > t2) {
      std::swap(t1, t2);
      entry_sign = 1;
    }
    if (t1 > t_min) {
      t_min = t1;
      axis = i;
      sign = entry_sign;
    }
    t_max = std::min(t_max, t2);
  }
  if (axis < 0 || t_min > t_max || t_min <= 0) return false;  // missed, or camera inside
  *t_hit = t_min;
  *normal = Eigen::Vector3d::Zero();
  (*normal)[axis] = sign;
  return true;
}

// One tracked static point.
struct StaticTrack {
  VertexId id;
  Eigen::Vector3d p_w;  // true position
  Eigen::Vector3d n_w;  // outward surface normal (visible from the side it points to)
};

// One tracked point of a moving object: fixed in the object frame; a vertex per frame.
struct DynamicTrack {
  size_t object;        // index into Scene::objects
  Eigen::Vector3d m_o;  // object frame
  Eigen::Vector3d n_o;
  VertexId last_vertex;
  int64_t tracklet;
  size_t length_index;  // into Simulator::dynamic_lengths_
};

class Simulator {
 public:
  Simulator(const Scene& scene, const SimulateOptions& options)
      : scene_(scene),
        options_(options),
        layout_rng_(options.seed),
        noise_rng_(options.seed ^ 0x9E3779B97F4A7C15ull),
        outlier_rng_(options.seed ^ 0xD1B54A32D192ED03ull),
        edge_noise_rng_(options.seed ^ 0x94D049BB133111EBull) {}

  SimulatedScene Run();

 private:
  struct Measurement {
    Eigen::Vector3d z;
    Eigen::Matrix3d information;
  };

  VertexId AddVertex(const Vertex& vertex, const std::array<double, kPoseSize>& truth) {
    const VertexId id = next_id_++;
    out_.graph.vertices.emplace(id, vertex);
    out_.true_values.emplace(id, truth);
    return id;
  }
  static Vertex PointVertex(const Eigen::Vector3d& p, Label label) {
    Vertex v;
    v.type = VertexType::kPoint;
    v.point() = p;
    v.label = label;
    return v;
  }
  static Vertex PoseVertex(const Pose& pose, Label label) {
    Vertex v;
    v.type = VertexType::kPose;
    v.set_pose(pose);
    v.label = label;
    return v;
  }

  bool Visible(const Eigen::Vector3d& p_c, const Eigen::Vector3d& n_c) const;
  Measurement Measure(const Eigen::Vector3d& p_c);
  static Vector6d Draw(Rng& rng, double rotation_sigma, double translation_sigma);
  // options.noise_every_edge: the measurement of a prior, motion or smoothing edge is drawn.
  bool DrawEveryEdge() const { return options_.noise && options_.noise_every_edge; }
  void Smoothing(int64_t k);
  static Matrix6d PoseInformation(double rotation_sigma, double translation_sigma);

  void Camera(int64_t k);
  void StaticPoints(int64_t k);
  void DynamicPoints(int64_t k);
  // Nearest static surface hit along the camera ray d (camera k frame); false when none.
  bool CastStatic(const Eigen::Vector3d& d, double* t, Eigen::Vector3d* normal) const;
  // Nearest hit on a moving object's box at frame k, or +∞.
  double CastMoving(int64_t k, const Eigen::Vector3d& d) const;
  VertexId Motion(size_t object, int64_t k);

  const Scene& scene_;
  const SimulateOptions& options_;
  Rng layout_rng_;   // detections, breaks
  Rng noise_rng_;    // measurement, odometry and motion noise
  Rng outlier_rng_;  // which observations are outliers, and their errors
  Rng edge_noise_rng_;  // prior, motion and smoothing edges (noise_every_edge)
  SimulatedScene out_;
  VertexId next_id_ = 0;
  int64_t next_tracklet_ = 0;

  // Per frame k: the true and initial camera pose, camera vertex.
  Pose X_, X_inv_, X_initial_;
  VertexId camera_id_ = 0;
  std::vector<StaticTrack> static_tracks_;
  std::vector<DynamicTrack> dynamic_tracks_;
  std::vector<int64_t> dynamic_lengths_;  // per dynamic tracklet, its number of points
  std::map<std::pair<size_t, int64_t>, VertexId> motions_;  // (object index, k) → vertex
  std::vector<bool> object_observed_;
};

bool Simulator::Visible(const Eigen::Vector3d& p_c, const Eigen::Vector3d& n_c) const {
  if (!(p_c.z() >= options_.min_depth && p_c.z() <= options_.max_depth)) return false;
  if (n_c.dot(-p_c) <= 0) return false;  // the surface faces away from the camera
  const Eigen::Vector3d uvw = scene_.camera.projection * p_c.homogeneous();
  if (!(uvw.z() > 0)) return false;
  const double u = uvw.x() / uvw.z(), v = uvw.y() / uvw.z();
  return u >= 0 && u < static_cast<double>(options_.image_width) && v >= 0 &&
         v < static_cast<double>(options_.image_height);
}

// Stereo triangulation x = u'·b/d, y = v'·b/d, z = f·b/d (u', v' from the principal point,
// d the disparity): Σ = J·diag(σ_px², σ_px², σ_d²)·Jᵀ + σ_floor²·I with J = ∂(x,y,z)/∂(u',v',d)
// at the true point. The noise is drawn from Σ and the information is Σ⁻¹.
Simulator::Measurement Simulator::Measure(const Eigen::Vector3d& p_c) {
  const double f = scene_.camera.focal(), b = scene_.camera.baseline, z = p_c.z();
  Eigen::Matrix3d J;
  J << z / f, 0, -p_c.x() * z / (f * b),  //
      0, z / f, -p_c.y() * z / (f * b),   //
      0, 0, -z * z / (f * b);
  const Eigen::Vector3d variances(options_.pixel_sigma * options_.pixel_sigma,
                                  options_.pixel_sigma * options_.pixel_sigma,
                                  options_.disparity_sigma * options_.disparity_sigma);
  Eigen::Matrix3d covariance = J * variances.asDiagonal() * J.transpose();
  covariance.diagonal().array() += options_.point_sigma_floor * options_.point_sigma_floor;
  covariance = 0.5 * (covariance + covariance.transpose()).eval();
  Measurement m;
  m.z = p_c;
  if (options_.noise) {
    Eigen::Vector3d n;
    for (int i = 0; i < 3; ++i) n[i] = noise_rng_.Normal();
    m.z += covariance.llt().matrixL() * n;
  }
  if (options_.outlier_fraction > 0 && outlier_rng_.Uniform() < options_.outlier_fraction) {
    Eigen::Vector3d direction;
    do {
      for (int i = 0; i < 3; ++i) direction[i] = outlier_rng_.Normal();
    } while (direction.norm() < 1e-6);
    const double length =
        options_.outlier_min + (options_.outlier_max - options_.outlier_min) * outlier_rng_.Uniform();
    m.z += length * direction.normalized();
    ++out_.statistics.outliers;
  }
  m.information = covariance.inverse();
  m.information = 0.5 * (m.information + m.information.transpose()).eval();
  return m;
}

Vector6d Simulator::Draw(Rng& rng, double rotation_sigma, double translation_sigma) {
  Vector6d xi;
  for (int i = 0; i < 6; ++i) xi[i] = rng.Normal() * (i < 3 ? rotation_sigma : translation_sigma);
  return xi;
}

Matrix6d Simulator::PoseInformation(double rotation_sigma, double translation_sigma) {
  Vector6d d;
  d << Eigen::Vector3d::Constant(1.0 / (rotation_sigma * rotation_sigma)),
      Eigen::Vector3d::Constant(1.0 / (translation_sigma * translation_sigma));
  return d.asDiagonal();  // tangent order [ω; ρ]
}

// Odometry Z = X_{k−1}⁻¹·X_k·Exp(ξ), ξ ~ N(0, Σ): at the truth the residual
// Log(Z⁻¹·X_{k−1}⁻¹·X_k) = −ξ, whose covariance is Σ = information⁻¹. Initial poses chain Z
// from the prior's Z (the true first pose unless noise_every_edge draws it the same way).
void Simulator::Camera(int64_t k) {
  X_ = scene_.cameras[k];
  X_inv_ = Inverse(X_);
  Label label;
  label.role = Role::kCamera;
  label.frame = k;
  if (k == 0) {
    X_initial_ = X_;
    if (DrawEveryEdge()) {
      const double sigma = options_.prior_sigma;
      X_initial_ = Compose(X_, Exp(Draw(edge_noise_rng_, sigma, sigma)));
    }
    camera_id_ = AddVertex(PoseVertex(X_initial_, label), X_.data);
    PriorEdge prior;
    prior.pose = camera_id_;
    prior.measurement = X_initial_;
    prior.information = PoseInformation(options_.prior_sigma, options_.prior_sigma);
    out_.graph.Edges<PriorEdge>().push_back(prior);
    return;
  }
  Pose Z = Compose(Inverse(scene_.cameras[k - 1]), X_);
  if (options_.noise) {
    Z = Compose(Z, Exp(Draw(noise_rng_, options_.odometry_rotation_sigma,
                            options_.odometry_translation_sigma)));
  }
  X_initial_ = Compose(X_initial_, Z);
  const VertexId previous = camera_id_;
  camera_id_ = AddVertex(PoseVertex(X_initial_, label), X_.data);
  BetweenEdge odometry;
  odometry.from = previous;
  odometry.to = camera_id_;
  odometry.measurement = Z;
  odometry.information =
      PoseInformation(options_.odometry_rotation_sigma, options_.odometry_translation_sigma);
  out_.graph.Edges<BetweenEdge>().push_back(odometry);
  ++out_.statistics.odometry_edges;
  out_.statistics.camera_path_length +=
      (scene_.cameras[k].translation() - scene_.cameras[k - 1].translation()).norm();
}

bool Simulator::CastStatic(const Eigen::Vector3d& d, double* t, Eigen::Vector3d* normal) const {
  *t = kInf;
  const double h = options_.camera_height;
  if (d.y() > 1e-9) {  // the ground plane y = h (camera y points down)
    *t = h / d.y();
    *normal = Eigen::Vector3d(0, -1, 0);
  }
  for (const double side : {-1.0, 1.0}) {  // façades x = ±facade_distance, up to facade_height
    if (side * d.x() <= 1e-9) continue;
    const double s = options_.facade_distance / (side * d.x());
    const double y = s * d.y();
    if (s < *t && y <= h && y >= h - options_.facade_height) {
      *t = s;
      *normal = Eigen::Vector3d(-side, 0, 0);
    }
  }
  for (const SceneObject& object : scene_.objects) {  // parked objects
    if (object.moving) continue;
    const Pose T_oc = Compose(Inverse(object.parked_pose), X_);
    if (T_oc.translation().norm() > options_.max_depth + object.size.norm()) continue;
    const Eigen::Matrix3d R_oc = RotationOf(T_oc);
    double s;
    Eigen::Vector3d n_o;
    if (RayBox(T_oc.translation(), R_oc * d, object.size / 2, &s, &n_o) && s < *t) {
      *t = s;
      *normal = R_oc.transpose() * n_o;
    }
  }
  return std::isfinite(*t);
}

double Simulator::CastMoving(int64_t k, const Eigen::Vector3d& d) const {
  double best = kInf;
  for (const SceneObject& object : scene_.objects) {
    if (!object.moving) continue;
    const auto it = object.poses.find(k);
    if (it == object.poses.end()) continue;
    const Pose T_oc = Compose(Inverse(it->second), X_);
    const Eigen::Matrix3d R_oc = RotationOf(T_oc);
    double s;
    Eigen::Vector3d n_o;
    if (RayBox(T_oc.translation(), R_oc * d, object.size / 2, &s, &n_o)) best = std::min(best, s);
  }
  return best;
}

void Simulator::StaticPoints(int64_t k) {
  const Eigen::Matrix3d R_cw = RotationOf(X_inv_);
  int64_t observations = 0;
  auto observe = [&](VertexId id, const Measurement& m) {
    PointEdge edge;
    edge.pose = camera_id_;
    edge.point = id;
    edge.measurement = m.z;
    edge.information = m.information;
    edge.is_dynamic = false;
    out_.graph.Edges<PointEdge>().push_back(edge);
    ++observations;
  };
  std::vector<StaticTrack> kept;
  for (const StaticTrack& track : static_tracks_) {
    const Eigen::Vector3d p_c = Transform(X_inv_, track.p_w);
    if (!Visible(p_c, R_cw * track.n_w)) continue;
    if (layout_rng_.Uniform() < options_.static_break_probability) {
      ++out_.statistics.static_breaks;
      continue;
    }
    observe(track.id, Measure(p_c));
    kept.push_back(track);
  }
  // New detections: random pixels, cast into the scenery; a ray that first meets a moving object
  // or nothing in range is not a static detection.
  const CameraModel& camera = scene_.camera;
  const double f = camera.focal(), cx = camera.projection(0, 2), cy = camera.projection(1, 2);
  const int64_t target = options_.static_points_per_frame;
  for (int64_t attempt = 0; static_cast<int64_t>(kept.size()) < target && attempt < 20 * target;
       ++attempt) {
    const double u = layout_rng_.Uniform() * static_cast<double>(options_.image_width);
    const double v = layout_rng_.Uniform() * static_cast<double>(options_.image_height);
    const Eigen::Vector3d d((u - cx) / f, (v - cy) / f, 1.0);
    double t;
    Eigen::Vector3d n_c;
    if (!CastStatic(d, &t, &n_c)) continue;
    const Eigen::Vector3d p_c = t * d;
    if (!Visible(p_c, n_c) || CastMoving(k, d) < t) continue;
    const Measurement m = Measure(p_c);
    Label label;
    label.role = Role::kStaticPoint;
    label.tracklet = next_tracklet_++;
    StaticTrack track;
    track.p_w = Transform(X_, p_c);
    track.n_w = RotationOf(X_) * n_c;
    Vertex truth = PointVertex(track.p_w, label);
    track.id = AddVertex(PointVertex(Transform(X_initial_, m.z), label), truth.value);
    observe(track.id, m);
    kept.push_back(track);
    ++out_.statistics.static_points;
  }
  static_tracks_ = std::move(kept);
  out_.statistics.static_observations += observations;
  if (k == 0 || observations < out_.statistics.static_obs_per_frame_min) {
    out_.statistics.static_obs_per_frame_min = observations;
  }
  out_.statistics.static_obs_per_frame_max =
      std::max(out_.statistics.static_obs_per_frame_max, observations);
}

// H^W_{k−1,k} = L_k·L_{k−1}⁻¹ (true); initial H_true·Exp(ξ). One vertex per (object, k), made
// when the first motion edge needs it.
VertexId Simulator::Motion(size_t object_index, int64_t k) {
  const auto key = std::make_pair(object_index, k);
  if (const auto it = motions_.find(key); it != motions_.end()) return it->second;
  const SceneObject& object = scene_.objects[object_index];
  const Pose H = Compose(object.poses.at(k), Inverse(object.poses.at(k - 1)));
  Pose initial = H;
  if (options_.noise) {
    initial = Compose(H, Exp(Draw(noise_rng_, options_.motion_init_rotation_sigma,
                                  options_.motion_init_translation_sigma)));
  }
  Label label;
  label.role = Role::kMotion;
  label.object = object.id;
  label.frame = k;
  const VertexId id = AddVertex(PoseVertex(initial, label), H.data);
  motions_.emplace(key, id);
  ++out_.statistics.motions;
  return id;
}

void Simulator::DynamicPoints(int64_t k) {
  std::vector<DynamicTrack> kept;
  const Eigen::Matrix3d motion_information =
      Eigen::Matrix3d::Identity() / (options_.motion_sigma * options_.motion_sigma);
  auto add_point = [&](size_t object_index, const DynamicTrack& track, const Pose& L) {
    const Eigen::Vector3d p_c = Transform(X_inv_, Transform(L, track.m_o));
    const Measurement m = Measure(p_c);
    Label label;
    label.role = Role::kDynamicPoint;
    label.object = scene_.objects[object_index].id;
    label.frame = k;
    label.tracklet = track.tracklet;
    Vertex truth = PointVertex(Transform(L, track.m_o), label);
    const VertexId id = AddVertex(PointVertex(Transform(X_initial_, m.z), label), truth.value);
    PointEdge edge;
    edge.pose = camera_id_;
    edge.point = id;
    edge.measurement = m.z;
    edge.information = m.information;
    edge.is_dynamic = true;
    out_.graph.Edges<PointEdge>().push_back(edge);
    ++out_.statistics.dynamic_observations;
    object_observed_[object_index] = true;
    return id;
  };
  // Continued tracks: the object must be labelled at k (tracks end when it is not).
  for (DynamicTrack& track : dynamic_tracks_) {
    const SceneObject& object = scene_.objects[track.object];
    const auto it = object.poses.find(k);
    if (it == object.poses.end()) continue;
    const Pose T_co = Compose(X_inv_, it->second);
    if (!Visible(Transform(T_co, track.m_o), RotationOf(T_co) * track.n_o)) continue;
    if (layout_rng_.Uniform() < options_.dynamic_break_probability) {
      ++out_.statistics.dynamic_breaks;
      continue;
    }
    const VertexId id = add_point(track.object, track, it->second);
    MotionEdge edge;
    edge.prev = track.last_vertex;
    edge.curr = id;
    edge.motion = Motion(track.object, k);
    edge.information = motion_information;
    if (DrawEveryEdge()) {
      for (int i = 0; i < 3; ++i) {
        edge.measurement[i] = edge_noise_rng_.Normal() * options_.motion_sigma;
      }
    }
    edge.object = object.id;
    edge.frame = k;
    edge.camera = camera_id_;
    out_.graph.Edges<MotionEdge>().push_back(edge);
    track.last_vertex = id;
    ++dynamic_lengths_[track.length_index];
    kept.push_back(track);
  }
  // New detections per visible moving object, up to the target: random pixels inside the
  // projection of its box, cast onto the box (in the object frame).
  const CameraModel& camera = scene_.camera;
  const double f = camera.focal(), cx = camera.projection(0, 2), cy = camera.projection(1, 2);
  const double width = static_cast<double>(options_.image_width);
  const double height = static_cast<double>(options_.image_height);
  const int64_t target = options_.dynamic_points_per_object;
  for (size_t index = 0; index < scene_.objects.size(); ++index) {
    const SceneObject& object = scene_.objects[index];
    if (!object.moving) continue;
    const auto it = object.poses.find(k);
    if (it == object.poses.end()) continue;
    const Pose T_co = Compose(X_inv_, it->second);
    const Pose T_oc = Inverse(T_co);
    if (T_co.translation().z() < -object.size.norm() ||
        T_co.translation().norm() > options_.max_depth + object.size.norm()) {
      continue;
    }
    // Pixel bounds of the box's projection (the whole image when a corner is behind the camera).
    double u0 = 0, u1 = width, v0 = 0, v1 = height;
    bool in_front = true;
    Eigen::Vector2d lo(kInf, kInf), hi(-kInf, -kInf);
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d c_o((corner & 1 ? 0.5 : -0.5) * object.size.x(),
                                (corner & 2 ? 0.5 : -0.5) * object.size.y(),
                                (corner & 4 ? 0.5 : -0.5) * object.size.z());
      const Eigen::Vector3d c = Transform(T_co, c_o);
      if (c.z() < 0.1) {
        in_front = false;
        break;
      }
      const Eigen::Vector2d uv(f * c.x() / c.z() + cx, f * c.y() / c.z() + cy);
      lo = lo.cwiseMin(uv);
      hi = hi.cwiseMax(uv);
    }
    if (in_front) {
      u0 = std::max(0.0, lo.x());
      u1 = std::min(width, hi.x());
      v0 = std::max(0.0, lo.y());
      v1 = std::min(height, hi.y());
      if (u1 <= u0 || v1 <= v0) continue;
    }
    int64_t active = 0;
    for (const DynamicTrack& track : kept) active += track.object == index ? 1 : 0;
    const Eigen::Matrix3d R_oc = RotationOf(T_oc);
    for (int64_t attempt = 0; active < target && attempt < 10 * target; ++attempt) {
      const double u = u0 + (u1 - u0) * layout_rng_.Uniform();
      const double v = v0 + (v1 - v0) * layout_rng_.Uniform();
      const Eigen::Vector3d d((u - cx) / f, (v - cy) / f, 1.0);
      double t;
      Eigen::Vector3d n_o;
      if (!RayBox(T_oc.translation(), R_oc * d, object.size / 2, &t, &n_o)) continue;
      const Eigen::Vector3d m_o = T_oc.translation() + t * (R_oc * d);
      if (!Visible(Transform(T_co, m_o), RotationOf(T_co) * n_o)) continue;
      DynamicTrack track;
      track.object = index;
      track.m_o = m_o;
      track.n_o = n_o;
      track.tracklet = next_tracklet_++;
      track.length_index = dynamic_lengths_.size();
      dynamic_lengths_.push_back(1);
      track.last_vertex = add_point(index, track, it->second);
      kept.push_back(track);
      ++active;
    }
  }
  dynamic_tracks_ = std::move(kept);
}

// Smoothing Z = I between consecutive motions of one object: at the truth its residual is the
// true change of motion, not noise (the paper's constant-motion assumption). noise_every_edge:
// Z = H_{k−1}⁻¹·H_k·Exp(ξ) instead, a measurement of the true change.
void Simulator::Smoothing(int64_t k) {
  for (size_t index = 0; index < scene_.objects.size() && k >= 2; ++index) {
    const auto a = motions_.find({index, k - 1}), b = motions_.find({index, k});
    if (a == motions_.end() || b == motions_.end()) continue;
    BetweenEdge smoothing;
    smoothing.from = a->second;
    smoothing.to = b->second;
    if (DrawEveryEdge()) {
      Pose H_a, H_b;
      H_a.data = out_.true_values.at(a->second);
      H_b.data = out_.true_values.at(b->second);
      smoothing.measurement =
          Compose(Compose(Inverse(H_a), H_b),
                  Exp(Draw(edge_noise_rng_, options_.smoothing_rotation_sigma,
                           options_.smoothing_translation_sigma)));
    }
    smoothing.information = PoseInformation(options_.smoothing_rotation_sigma,
                                            options_.smoothing_translation_sigma);
    out_.graph.Edges<BetweenEdge>().push_back(smoothing);
    ++out_.statistics.smoothing_edges;
  }
}

SimulatedScene Simulator::Run() {
  const int64_t frames = static_cast<int64_t>(scene_.cameras.size());
  object_observed_.assign(scene_.objects.size(), false);
  out_.graph.formulation = "frontend";
  out_.graph.labelled = true;
  for (int64_t k = 0; k < frames; ++k) {
    Camera(k);
    StaticPoints(k);
    DynamicPoints(k);
    Smoothing(k);
  }
  // Ground truth: every camera; moving objects at every labelled frame of the range.
  for (int64_t k = 0; k < frames; ++k) out_.ground_truth.cameras[k] = scene_.cameras[k];
  SimulateStatistics& s = out_.statistics;
  for (size_t index = 0; index < scene_.objects.size(); ++index) {
    const SceneObject& object = scene_.objects[index];
    if (!object.moving) {
      ++s.parked_objects;
      continue;
    }
    ++s.moving_objects;
    s.moving_objects_observed += object_observed_[index] ? 1 : 0;
    for (const auto& [k, L] : object.poses) out_.ground_truth.objects[{object.id, k}] = L;
  }
  s.frames = frames;
  s.dynamic_tracklets = static_cast<int64_t>(dynamic_lengths_.size());
  for (const int64_t length : dynamic_lengths_) s.dynamic_tracklets_of_length_one += length == 1;
  s.motion_edges = static_cast<int64_t>(out_.graph.Edges<MotionEdge>().size());
  s.vertices = static_cast<int64_t>(out_.graph.vertices.size());
  s.edges = static_cast<int64_t>(out_.graph.NumEdges());
  out_.header = scene_.header;
  return std::move(out_);
}

Status CheckOptions(const Scene& scene, const SimulateOptions& o) {
  auto bad = [](const std::string& message) { return Status(Error{"", 0, message}); };
  const auto positive = [](double x) { return std::isfinite(x) && x > 0; };
  if (scene.cameras.size() < 2) return bad("a scene needs at least 2 frames");
  if (Status status = CheckSimulateOptions(o); !status.ok()) return status;
  if (!positive(scene.camera.focal()) || !positive(scene.camera.baseline)) {
    return bad("the camera needs a positive focal length and baseline");
  }
  return Status::Ok();
}

}  // namespace

Status CheckSimulateOptions(const SimulateOptions& o) {
  auto bad = [](const std::string& message) { return Status(Error{"", 0, message}); };
  const auto positive = [](double x) { return std::isfinite(x) && x > 0; };
  if (!positive(o.pixel_sigma) || !positive(o.disparity_sigma) ||
      !(std::isfinite(o.point_sigma_floor) && o.point_sigma_floor >= 0)) {
    return bad("pixel and disparity sigmas must be positive, the point sigma floor non-negative");
  }
  if (!positive(o.odometry_rotation_sigma) || !positive(o.odometry_translation_sigma) ||
      !positive(o.motion_init_rotation_sigma) || !positive(o.motion_init_translation_sigma) ||
      !positive(o.prior_sigma) || !positive(o.motion_sigma) ||
      !positive(o.smoothing_rotation_sigma) || !positive(o.smoothing_translation_sigma)) {
    return bad("every sigma must be positive (use noise = false for exact measurements)");
  }
  if (!(o.outlier_fraction >= 0 && o.outlier_fraction <= 1) || !(o.outlier_min >= 0) ||
      !(o.outlier_max >= o.outlier_min) || !std::isfinite(o.outlier_max)) {
    return bad("outlier fraction must be in [0, 1] and 0 <= outlier_min <= outlier_max");
  }
  if (!(o.static_break_probability >= 0 && o.static_break_probability <= 1) ||
      !(o.dynamic_break_probability >= 0 && o.dynamic_break_probability <= 1)) {
    return bad("break probabilities must be in [0, 1]");
  }
  if (!(o.min_depth > 0 && o.max_depth > o.min_depth && std::isfinite(o.max_depth))) {
    return bad("depth range must satisfy 0 < min_depth < max_depth");
  }
  if (o.image_width <= 0 || o.image_height <= 0 || o.static_points_per_frame < 0 ||
      o.dynamic_points_per_object < 0) {
    return bad("image size must be positive and point targets non-negative");
  }
  if (!positive(o.camera_height) || !positive(o.facade_distance) || !positive(o.facade_height)) {
    return bad("camera height, facade distance and facade height must be positive");
  }
  return Status::Ok();
}

bool UsePaperDensity(const std::string& sequence, SimulateOptions* options) {
  // sequence → {static points per frame, dynamic points per object}: one least-squares step
  // from three whole-sequence runs (seed 1) at (150, 20), (450, 20) and (150, 100), then checked
  // (docs/SIMULATOR.md has the command and the counts).
  static const std::map<std::string, std::pair<int64_t, int64_t>> kDensity = {
      {"0000", {796, 440}}, {"0001", {534, 289}}, {"0002", {513, 53}},
      {"0003", {429, 376}}, {"0004", {376, 95}},  {"0005", {334, 140}},
      {"0006", {583, 162}}, {"0018", {507, 241}}, {"0020", {435, 149}},
  };
  const auto it = kDensity.find(sequence);
  if (it == kDensity.end()) return false;
  options->static_points_per_frame = it->second.first;
  options->dynamic_points_per_object = it->second.second;
  return true;
}

Expected<SimulatedScene> Simulate(const Scene& scene, const SimulateOptions& options) {
  if (Status status = CheckOptions(scene, options); !status.ok()) return status.error();
  SimulatedScene simulated = Simulator(scene, options).Run();
  // The labels and edges must agree (SPEC §1.4) — an internal invariant, checked like input.
  if (Status status = AssignRoles(simulated.graph, "simulated scene"); !status.ok()) {
    return status.error();
  }
  return simulated;
}

std::string FormatStatistics(const SimulateStatistics& s) {
  std::string text;
  char buffer[128];
  auto line = [&](const char* name, const std::string& value) {
    std::snprintf(buffer, sizeof(buffer), "  %-32s %s\n", name, value.c_str());
    text += buffer;
  };
  auto integer = [&](const char* name, int64_t value) { line(name, std::to_string(value)); };
  char number[64];
  integer("frames", s.frames);
  std::snprintf(number, sizeof(number), "%.1f", s.camera_path_length);
  line("camera_path_length_m", number);
  integer("static_points", s.static_points);
  integer("static_observations", s.static_observations);
  std::snprintf(number, sizeof(number), "mean %.1f min %lld max %lld",
                s.frames > 0 ? static_cast<double>(s.static_observations) / s.frames : 0.0,
                static_cast<long long>(s.static_obs_per_frame_min),
                static_cast<long long>(s.static_obs_per_frame_max));
  line("static_obs_per_frame", number);
  integer("parked_objects", s.parked_objects);
  integer("moving_objects", s.moving_objects);
  integer("moving_objects_observed", s.moving_objects_observed);
  integer("dynamic_observations", s.dynamic_observations);
  integer("dynamic_tracklets", s.dynamic_tracklets);
  integer("dynamic_tracklets_of_length_one", s.dynamic_tracklets_of_length_one);
  integer("motions", s.motions);
  integer("motion_edges", s.motion_edges);
  integer("smoothing_edges", s.smoothing_edges);
  integer("odometry_edges", s.odometry_edges);
  integer("static_breaks", s.static_breaks);
  integer("dynamic_breaks", s.dynamic_breaks);
  integer("outliers", s.outliers);
  integer("vertices", s.vertices);
  integer("edges", s.edges);
  return text;
}

}  // namespace dynslam
