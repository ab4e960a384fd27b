#include "dynslam/graph_io.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <tuple>
#include <unordered_map>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "dynslam/file_io.h"

namespace dynslam {
namespace {

// SPEC §1.2: pose-edge information is stored translation-first in the file; tangent index i
// comes from file index kG2oIndex[i].
constexpr int kG2oIndex[6] = {3, 4, 5, 0, 1, 2};

enum class Tag {
  kVertexPose,
  kVertexPoint,
  kPrior,
  kBetween,
  kPoint,
  kMotion,
  kObjectPoint,
  kObjectMotion,
  kKinematic,
  kLabelCamera,
  kLabelStaticPoint,
  kLabelDynamicPoint,
  kLabelMotion,
  kLabelObjectPose,
  kLabelObjectPoint,
  kLabelFormulation,
  kUnknown,
};

struct TagInfo {
  const char* name;
  Tag tag;
};
constexpr TagInfo kTags[] = {
    {"VERTEX_SE3:QUAT", Tag::kVertexPose},
    {"VERTEX_TRACKXYZ", Tag::kVertexPoint},
    {"EDGE_SE3_PRIOR", Tag::kPrior},
    {"EDGE_SE3:QUAT", Tag::kBetween},
    {"EDGE_SE3_TRACKXYZ", Tag::kPoint},
    {"EDGE_SE3_MOTION", Tag::kMotion},
    {"EDGE_SE3_OBJ_TRACKXYZ", Tag::kObjectPoint},
    {"EDGE_SE3_OBJ_MOTION", Tag::kObjectMotion},
    {"EDGE_SE3_OBJ_KINEMATIC", Tag::kKinematic},
    {"LABEL_CAMERA", Tag::kLabelCamera},
    {"LABEL_STATIC_POINT", Tag::kLabelStaticPoint},
    {"LABEL_DYNAMIC_POINT", Tag::kLabelDynamicPoint},
    {"LABEL_MOTION", Tag::kLabelMotion},
    {"LABEL_OBJECT_POSE", Tag::kLabelObjectPose},
    {"LABEL_OBJECT_POINT", Tag::kLabelObjectPoint},
    {"LABEL_FORMULATION", Tag::kLabelFormulation},
};

Tag LookUp(std::string_view name) {
  for (const TagInfo& info : kTags) {
    if (name == info.name) return info.tag;
  }
  return Tag::kUnknown;
}

const char* kFormulationNames[] = {"frontend", "wc", "oc_a", "oc_b", "oc_c"};

// One line being parsed: its fields after the tag, and errors that name file, line and tag.
class LineParser {
 public:
  // `repaired`: null, or a count of information matrices repaired (ReadOptions).
  LineParser(const std::string& file, int64_t line, std::string_view tag,
             const std::vector<std::string_view>& fields, bool permute_information,
             int64_t* repaired)
      : file_(file), line_(line), tag_(tag), fields_(fields),
        permute_information_(permute_information), repaired_(repaired) {}

  size_t size() const { return fields_.size(); }

  Error Fail(const std::string& message) const {
    return Error{file_, line_, std::string(tag_) + ": " + message};
  }

  Status ExpectCount(std::initializer_list<size_t> allowed, const char* layout) const {
    for (const size_t n : allowed) {
      if (fields_.size() == n) return Status::Ok();
    }
    std::string counts;
    for (const size_t n : allowed) counts += (counts.empty() ? "" : " or ") + std::to_string(n);
    return Fail("has " + std::to_string(fields_.size()) + " fields after the tag, expected " +
                counts + " (" + layout + ")");
  }

  // A finite number.
  bool Number(size_t i, double* value, Error* error) const {
    std::string_view text = fields_[i];
    if (!text.empty() && text[0] == '+') text.remove_prefix(1);
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), *value);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty()) {
      *error = Fail("field " + std::to_string(i + 1) + " '" + std::string(fields_[i]) +
                    "' is not a number");
      return false;
    }
    if (!std::isfinite(*value)) {
      *error = Fail("field " + std::to_string(i + 1) + " '" + std::string(fields_[i]) +
                    "' is not finite");
      return false;
    }
    return true;
  }

  // A non-negative integer below 2^63 (ids, object ids, frames, tracklets).
  bool Integer(size_t i, int64_t* value, const char* what, Error* error) const {
    const std::string_view text = fields_[i];
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), *value);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty() || *value < 0) {
      *error = Fail(std::string(what) + " '" + std::string(text) +
                    "' is not a non-negative integer below 2^63");
      return false;
    }
    return true;
  }

  bool Numbers(size_t first, size_t count, double* out, Error* error) const {
    for (size_t k = 0; k < count; ++k) {
      if (!Number(first + k, &out[k], error)) return false;
    }
    return true;
  }

  // tx ty tz qx qy qz qw → pose block; normalises a quaternion whose norm is off by > 1e-12.
  bool ReadPose(size_t first, Pose* pose, Error* error) const {
    double v[7];
    if (!Numbers(first, 7, v, error)) return false;
    Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    // stableNorm: a component of 1e290 must not overflow the sum of squares to inf, which would
    // normalise the quaternion to zero (found by fuzzing).
    const double norm = q.coeffs().stableNorm();
    if (norm == 0) {
      *error = Fail("the quaternion (fields " + std::to_string(first + 4) + " to " +
                    std::to_string(first + 7) + ") is zero");
      return false;
    }
    if (std::abs(norm - 1.0) > 1e-12) q.coeffs() /= norm;
    *pose = Pose::FromRotationTranslation(q, Eigen::Vector3d(v[0], v[1], v[2]));
    return true;
  }

  // Fails with the reason unless `m` is numerically positive definite.
  template <int N>
  bool IsPositiveDefinite(const Eigen::Matrix<double, N, N>& m, const std::string& where,
                          Error* error) const {
    Eigen::LLT<Eigen::Matrix<double, N, N>> llt(m);
    if (llt.info() != Eigen::Success || !(m.diagonal().array() > 0).all()) {
      *error = Fail(where + " is not symmetric positive definite");
      return false;
    }
    // LLT succeeds on a singular matrix whose last pivot is rounding noise (e.g. the rank-1
    // [1 0.7; 0.7 0.49]: 0.49 rounds above fl(0.7²)); such a matrix is only semi-definite.
    // The eigenvalues tell: λmin ≤ N·ε·λmax is indistinguishable from 0. (The reference pose
    // graphs reach λmin/λmax ≈ 4e-10, far above that.) Diagonal matrices, the common case,
    // need no eigensolver.
    double lambda_min, lambda_max;
    if (m.isDiagonal(0.0)) {
      lambda_min = m.diagonal().minCoeff();
      lambda_max = m.diagonal().maxCoeff();
    } else {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(m, Eigen::EigenvaluesOnly);
      if (eigen.info() != Eigen::Success) {
        *error = Fail(where + ": its eigenvalues could not be computed");
        return false;
      }
      lambda_min = eigen.eigenvalues()(0);
      lambda_max = eigen.eigenvalues()(N - 1);
    }
    if (!(lambda_min > N * std::numeric_limits<double>::epsilon() * lambda_max) ||
        !std::isfinite(lambda_max)) {
      char numbers[96];
      std::snprintf(numbers, sizeof(numbers), " (eigenvalues from %.3g to %.3g)", lambda_min,
                    lambda_max);
      *error = Fail(where + " is numerically singular, not symmetric positive definite" + numbers);
      return false;
    }
    return true;
  }

  // ReadOptions::repair_information: the nearest symmetric matrix (Frobenius norm) whose
  // eigenvalues are at least kRepairFloor × the largest. False when there is nothing to keep
  // (no positive eigenvalue, or a non-finite entry).
  template <int N>
  static bool Repair(Eigen::Matrix<double, N, N>* m) {
    if (!m->allFinite()) return false;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(*m);
    if (eigen.info() != Eigen::Success) return false;
    const double lambda_max = eigen.eigenvalues()(N - 1);
    if (!(lambda_max > 0) || !std::isfinite(lambda_max)) return false;
    const Eigen::Matrix<double, N, 1> clamped =
        eigen.eigenvalues().cwiseMax(kRepairFloor * lambda_max);
    *m = eigen.eigenvectors() * clamped.asDiagonal() * eigen.eigenvectors().transpose();
    *m = (0.5 * (*m + m->transpose())).eval();
    return true;
  }
  static constexpr double kRepairFloor = 1e-9;

  // Upper triangle, row by row, of an N×N symmetric positive definite matrix.
  template <int N>
  bool ReadInformation(size_t first, Eigen::Matrix<double, N, N>* information, Error* error) const {
    Eigen::Matrix<double, N, N> m;
    size_t k = first;
    for (int r = 0; r < N; ++r) {
      for (int c = r; c < N; ++c) {
        if (!Number(k++, &m(r, c), error)) return false;
        m(c, r) = m(r, c);
      }
    }
    const std::string where = "the information matrix (fields " + std::to_string(first + 1) +
                              " to " + std::to_string(k) + ")";
    if (!IsPositiveDefinite(m, where, error)) {
      if (repaired_ == nullptr || !Repair(&m)) return false;
      ++*repaired_;
    }
    *information = m;
    return true;
  }

  bool Read6x6InTangentOrder(size_t first, Matrix6d* information, Error* error) const {
    Matrix6d file_order;
    if (!ReadInformation<6>(first, &file_order, error)) return false;
    if (!permute_information_) {
      *information = file_order;
      return true;
    }
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) (*information)(r, c) = file_order(kG2oIndex[r], kG2oIndex[c]);
    }
    return true;
  }

 private:
  const std::string& file_;
  int64_t line_;
  std::string_view tag_;
  const std::vector<std::string_view>& fields_;
  bool permute_information_;
  int64_t* repaired_;
};

struct PendingLabel {
  VertexId id;
  Label label;
  int64_t line;
  const char* tag;
};

class Reader {
 public:
  Reader(const std::string& name, const ReadOptions& options, ReadReport* report)
      : name_(name), options_(options), report_(report) {}

  Expected<Graph> Read(std::istream& in) {
    std::string line;
    std::vector<std::string_view> fields;
    int64_t number = 0;
    while (std::getline(in, line)) {
      ++number;
      Split(line, &fields);
      if (fields.empty()) continue;
      const std::string_view tag = fields.front();
      fields.erase(fields.begin());
      const int64_t repaired_before = repaired_;
      if (Status s = ParseLine(number, tag, fields); !s.ok()) return s.error();
      if (repaired_ != repaired_before && report_ != nullptr) {
        report_->repaired_information_lines.push_back(number);
      }
    }
    if (in.bad()) return Error{name_, number, "reading failed"};
    if (report_ != nullptr) report_->lines = number;
    if (Status s = ResolveReferences(); !s.ok()) return s.error();
    if (Status s = ApplyLabels(); !s.ok()) return s.error();
    if (Status s = AssignRoles(graph_, name_); !s.ok()) return s.error();
    return std::move(graph_);
  }

 private:
  static void Split(const std::string& line, std::vector<std::string_view>* fields) {
    fields->clear();
    std::string_view rest(line);
    if (const size_t hash = rest.find('#'); hash != std::string_view::npos) {
      rest = rest.substr(0, hash);
    }
    size_t i = 0;
    while (i < rest.size()) {
      while (i < rest.size() && (rest[i] == ' ' || rest[i] == '\t' || rest[i] == '\r')) ++i;
      const size_t start = i;
      while (i < rest.size() && rest[i] != ' ' && rest[i] != '\t' && rest[i] != '\r') ++i;
      if (i > start) fields->push_back(rest.substr(start, i - start));
    }
  }

  Status AddVertex(VertexId id, Vertex vertex, const LineParser& p) {
    auto [it, inserted] = graph_.vertices.emplace(id, vertex);
    if (inserted) return Status::Ok();
    const bool same_type = it->second.type == vertex.type;
    return p.Fail(std::string(same_type ? "duplicate vertex id " : "id ") + std::to_string(id) +
                  (same_type ? "" : " used as two vertex types") + " (first declared on line " +
                  std::to_string(it->second.line) + ")");
  }

  Status ParseLine(int64_t line, std::string_view tag_name, const std::vector<std::string_view>& f) {
    const Tag tag = LookUp(tag_name);
    LineParser p(name_, line, tag_name, f, !options_.information_in_tangent_order,
                 options_.repair_information ? &repaired_ : nullptr);
    Error error;
    switch (tag) {
      case Tag::kUnknown: {
        if (!options_.skip_unknown_tags) {
          return Error{name_, line,
                       "unknown tag '" + std::string(tag_name) +
                           "' (pass --skip-unknown-tags to skip such lines)"};
        }
        if (report_ != nullptr) ++report_->skipped_tags[std::string(tag_name)];
        return Status::Ok();
      }
      case Tag::kVertexPose: {
        if (Status s = p.ExpectCount({8}, "id tx ty tz qx qy qz qw"); !s.ok()) return s;
        VertexId id;
        Pose pose;
        if (!p.Integer(0, &id, "vertex id", &error) || !p.ReadPose(1, &pose, &error)) return error;
        Vertex vertex;
        vertex.type = VertexType::kPose;
        vertex.value = pose.data;
        vertex.line = line;
        return AddVertex(id, vertex, p);
      }
      case Tag::kVertexPoint: {
        if (Status s = p.ExpectCount({4}, "id x y z"); !s.ok()) return s;
        VertexId id;
        Vertex vertex;
        vertex.type = VertexType::kPoint;
        vertex.value.fill(0);
        vertex.line = line;
        if (!p.Integer(0, &id, "vertex id", &error) || !p.Numbers(1, 3, vertex.value.data(), &error)) {
          return error;
        }
        return AddVertex(id, vertex, p);
      }
      case Tag::kPrior: {
        if (Status s = p.ExpectCount({29, 30}, "id [param] tx ty tz qx qy qz qw I(21)"); !s.ok()) {
          return s;
        }
        PriorEdge e;
        e.line = line;
        e.has_parameter_id = f.size() == 30;
        const size_t first = e.has_parameter_id ? 2 : 1;
        if (!p.Integer(0, &e.pose, "vertex id", &error)) return error;
        if (e.has_parameter_id) {
          int64_t parameter;
          if (!p.Integer(1, &parameter, "parameter id", &error)) return error;
          if (parameter != 0) return p.Fail("the offset-parameter id must be 0, not " + std::to_string(parameter));
        }
        if (!p.ReadPose(first, &e.measurement, &error) ||
            !p.Read6x6InTangentOrder(first + 7, &e.information, &error)) {
          return error;
        }
        graph_.priors.push_back(e);
        return Status::Ok();
      }
      case Tag::kBetween: {
        if (Status s = p.ExpectCount({30}, "a b tx ty tz qx qy qz qw I(21)"); !s.ok()) return s;
        BetweenEdge e;
        e.line = line;
        if (!p.Integer(0, &e.from, "vertex id", &error) || !p.Integer(1, &e.to, "vertex id", &error) ||
            !p.ReadPose(2, &e.measurement, &error) ||
            !p.Read6x6InTangentOrder(9, &e.information, &error)) {
          return error;
        }
        graph_.betweens.push_back(e);
        return Status::Ok();
      }
      case Tag::kPoint: {
        if (Status s = p.ExpectCount({11, 12}, "pose point zx zy zz I(6) [is_dynamic]"); !s.ok()) {
          return s;
        }
        PointEdge e;
        e.line = line;
        if (!p.Integer(0, &e.pose, "vertex id", &error) ||
            !p.Integer(1, &e.point, "vertex id", &error) ||
            !p.Numbers(2, 3, e.measurement.data(), &error) ||
            !p.ReadInformation<3>(5, &e.information, &error)) {
          return error;
        }
        if (f.size() == 12) {
          if (f[11] != "0" && f[11] != "1") return p.Fail("is_dynamic '" + std::string(f[11]) + "' must be 0 or 1");
          e.is_dynamic = f[11] == "1";
        }
        graph_.point_edges.push_back(e);
        return Status::Ok();
      }
      case Tag::kMotion: {
        if (Status s = p.ExpectCount({15}, "prev curr motion zx zy zz I(6) object frame camera");
            !s.ok()) {
          return s;
        }
        MotionEdge e;
        e.line = line;
        if (!p.Integer(0, &e.prev, "vertex id", &error) ||
            !p.Integer(1, &e.curr, "vertex id", &error) ||
            !p.Integer(2, &e.motion, "vertex id", &error) ||
            !p.Numbers(3, 3, e.measurement.data(), &error) ||
            !p.ReadInformation<3>(6, &e.information, &error) ||
            !p.Integer(12, &e.object, "object id", &error) ||
            !p.Integer(13, &e.frame, "frame", &error) ||
            !p.Integer(14, &e.camera, "camera id", &error)) {
          return error;
        }
        if (e.frame < 1) return p.Fail("frame must be at least 1 (the current point's frame k)");
        graph_.motion_edges.push_back(e);
        return Status::Ok();
      }
      case Tag::kObjectPoint: {
        if (Status s = p.ExpectCount({12}, "camera objpose point zx zy zz I(6)"); !s.ok()) return s;
        ObjectPointEdge e;
        e.line = line;
        if (!p.Integer(0, &e.camera, "vertex id", &error) ||
            !p.Integer(1, &e.object_pose, "vertex id", &error) ||
            !p.Integer(2, &e.point, "vertex id", &error) ||
            !p.Numbers(3, 3, e.measurement.data(), &error) ||
            !p.ReadInformation<3>(6, &e.information, &error)) {
          return error;
        }
        graph_.object_point_edges.push_back(e);
        return Status::Ok();
      }
      case Tag::kObjectMotion: {
        if (Status s = p.ExpectCount({10}, "pose_prev pose_curr motion point I(6)"); !s.ok()) return s;
        ObjectMotionEdge e;
        e.line = line;
        if (!p.Integer(0, &e.pose_prev, "vertex id", &error) ||
            !p.Integer(1, &e.pose_curr, "vertex id", &error) ||
            !p.Integer(2, &e.motion, "vertex id", &error) ||
            !p.Integer(3, &e.point, "vertex id", &error) ||
            !p.ReadInformation<3>(4, &e.information, &error)) {
          return error;
        }
        graph_.object_motion_edges.push_back(e);
        return Status::Ok();
      }
      case Tag::kKinematic: {
        if (Status s = p.ExpectCount({24}, "pose_prev pose_curr motion I(21)"); !s.ok()) return s;
        KinematicEdge e;
        e.line = line;
        if (!p.Integer(0, &e.pose_prev, "vertex id", &error) ||
            !p.Integer(1, &e.pose_curr, "vertex id", &error) ||
            !p.Integer(2, &e.motion, "vertex id", &error) ||
            !p.Read6x6InTangentOrder(3, &e.information, &error)) {
          return error;
        }
        graph_.kinematic_edges.push_back(e);
        return Status::Ok();
      }
      case Tag::kLabelFormulation: {
        if (Status s = p.ExpectCount({1}, "name"); !s.ok()) return s;
        if (graph_.formulation) {
          return p.Fail("appears twice (first on line " + std::to_string(formulation_line_) + ")");
        }
        const std::string name(f[0]);
        if (std::find(std::begin(kFormulationNames), std::end(kFormulationNames), name) ==
            std::end(kFormulationNames)) {
          return p.Fail("unknown formulation '" + name + "' (frontend, wc, oc_a, oc_b or oc_c)");
        }
        graph_.formulation = name;
        formulation_line_ = line;
        return Status::Ok();
      }
      default:
        return ParseLabel(tag, p, f, line);
    }
  }

  Status ParseLabel(Tag tag, const LineParser& p, const std::vector<std::string_view>& f,
                    int64_t line) {
    PendingLabel pending{0, Label{}, line, ""};
    Error error;
    // Field names after the id, per label tag (SPEC §1.4).
    struct Layout {
      Tag tag;
      Role role;
      const char* name;
      std::vector<const char*> fields;
    };
    static const Layout kLayouts[] = {
        {Tag::kLabelCamera, Role::kCamera, "LABEL_CAMERA", {"frame"}},
        {Tag::kLabelStaticPoint, Role::kStaticPoint, "LABEL_STATIC_POINT", {"tracklet"}},
        {Tag::kLabelDynamicPoint, Role::kDynamicPoint, "LABEL_DYNAMIC_POINT", {"object", "frame", "tracklet"}},
        {Tag::kLabelMotion, Role::kMotion, "LABEL_MOTION", {"object", "frame"}},
        {Tag::kLabelObjectPose, Role::kObjectPose, "LABEL_OBJECT_POSE", {"object", "frame"}},
        {Tag::kLabelObjectPoint, Role::kObjectPoint, "LABEL_OBJECT_POINT", {"object", "tracklet"}},
    };
    const Layout* layout = nullptr;
    for (const Layout& l : kLayouts) {
      if (l.tag == tag) layout = &l;
    }
    if (layout == nullptr) return p.Fail("internal: no label layout");
    std::string layout_text = "id";
    for (const char* field : layout->fields) layout_text += std::string(" ") + field;
    if (Status s = p.ExpectCount({1 + layout->fields.size()}, layout_text.c_str()); !s.ok()) return s;
    if (!p.Integer(0, &pending.id, "vertex id", &error)) return error;
    pending.label.role = layout->role;
    pending.tag = layout->name;
    for (size_t k = 0; k < layout->fields.size(); ++k) {
      int64_t value;
      if (!p.Integer(k + 1, &value, layout->fields[k], &error)) return error;
      const std::string_view field = layout->fields[k];
      if (field == "object") pending.label.object = value;
      if (field == "frame") pending.label.frame = value;
      if (field == "tracklet") pending.label.tracklet = value;
    }
    (void)f;
    labels_.push_back(pending);
    return Status::Ok();
  }

  // Every vertex an edge names exists and has the type the edge needs (SPEC §1.6).
  Status ResolveReferences() const {
    auto check = [&](VertexId id, VertexType type, int64_t line, const char* tag,
                     const char* field) -> Status {
      const Vertex* vertex = graph_.Find(id);
      if (vertex == nullptr) {
        return Error{name_, line,
                     std::string(tag) + ": field '" + field + "' names vertex " +
                         std::to_string(id) + ", which is not declared in the file"};
      }
      if (vertex->type != type) {
        return Error{name_, line,
                     std::string(tag) + ": field '" + field + "' names vertex " +
                         std::to_string(id) + ", a " +
                         (vertex->type == VertexType::kPose ? "pose" : "point") +
                         " (line " + std::to_string(vertex->line) + "); expected a " +
                         (type == VertexType::kPose ? "pose" : "point")};
      }
      return Status::Ok();
    };
    const VertexType P = VertexType::kPose, M = VertexType::kPoint;
    for (const auto& e : graph_.priors) {
      if (Status s = check(e.pose, P, e.line, "EDGE_SE3_PRIOR", "id"); !s.ok()) return s;
    }
    for (const auto& e : graph_.betweens) {
      for (const auto& [id, field] : {std::pair{e.from, "a"}, std::pair{e.to, "b"}}) {
        if (Status s = check(id, P, e.line, "EDGE_SE3:QUAT", field); !s.ok()) return s;
      }
    }
    for (const auto& e : graph_.point_edges) {
      if (Status s = check(e.pose, P, e.line, "EDGE_SE3_TRACKXYZ", "pose"); !s.ok()) return s;
      if (Status s = check(e.point, M, e.line, "EDGE_SE3_TRACKXYZ", "point"); !s.ok()) return s;
    }
    for (const auto& e : graph_.motion_edges) {
      const char* tag = "EDGE_SE3_MOTION";
      for (const auto& [id, type, field] :
           {std::tuple{e.prev, M, "prev"}, std::tuple{e.curr, M, "curr"},
            std::tuple{e.motion, P, "motion"}, std::tuple{e.camera, P, "camera"}}) {
        if (Status s = check(id, type, e.line, tag, field); !s.ok()) return s;
      }
    }
    for (const auto& e : graph_.object_point_edges) {
      const char* tag = "EDGE_SE3_OBJ_TRACKXYZ";
      for (const auto& [id, type, field] :
           {std::tuple{e.camera, P, "camera"}, std::tuple{e.object_pose, P, "objpose"},
            std::tuple{e.point, M, "point"}}) {
        if (Status s = check(id, type, e.line, tag, field); !s.ok()) return s;
      }
    }
    for (const auto& e : graph_.object_motion_edges) {
      const char* tag = "EDGE_SE3_OBJ_MOTION";
      for (const auto& [id, type, field] :
           {std::tuple{e.pose_prev, P, "pose_prev"}, std::tuple{e.pose_curr, P, "pose_curr"},
            std::tuple{e.motion, P, "motion"}, std::tuple{e.point, M, "point"}}) {
        if (Status s = check(id, type, e.line, tag, field); !s.ok()) return s;
      }
    }
    for (const auto& e : graph_.kinematic_edges) {
      const char* tag = "EDGE_SE3_OBJ_KINEMATIC";
      for (const auto& [id, field] : {std::pair{e.pose_prev, "pose_prev"},
                                      std::pair{e.pose_curr, "pose_curr"}, std::pair{e.motion, "motion"}}) {
        if (Status s = check(id, P, e.line, tag, field); !s.ok()) return s;
      }
    }
    return Status::Ok();
  }

  // A file is fully labelled or carries no labels (SPEC §1.4).
  Status ApplyLabels() {
    if (labels_.empty()) return Status::Ok();
    graph_.labelled = true;
    std::unordered_map<VertexId, int64_t> labelled_on;
    for (const PendingLabel& pending : labels_) {
      Vertex* vertex = graph_.Find(pending.id);
      if (vertex == nullptr) {
        return Error{name_, pending.line,
                     std::string(pending.tag) + " names vertex " + std::to_string(pending.id) +
                         ", which is not declared in the file"};
      }
      const bool wants_pose = pending.label.role == Role::kCamera ||
                              pending.label.role == Role::kMotion ||
                              pending.label.role == Role::kObjectPose;
      if (wants_pose != (vertex->type == VertexType::kPose)) {
        return Error{name_, pending.line,
                     std::string(pending.tag) + " names vertex " + std::to_string(pending.id) +
                         ", a " + (vertex->type == VertexType::kPose ? "pose" : "point") +
                         "; this label is for a " + (wants_pose ? "pose" : "point")};
      }
      if (auto [it, inserted] = labelled_on.emplace(pending.id, pending.line); !inserted) {
        return Error{name_, pending.line,
                     "vertex " + std::to_string(pending.id) + " has a second label (the first on line " +
                         std::to_string(it->second) + ")"};
      }
      vertex->label = pending.label;
    }
    for (const auto& [id, vertex] : graph_.vertices) {
      if (vertex.label.role == Role::kUnknown) {
        return Error{name_, vertex.line,
                     "vertex " + std::to_string(id) +
                         " has no label, but the file labels others: a file is fully labelled or "
                         "carries no labels (SPEC §1.4)"};
      }
    }
    return Status::Ok();
  }

  const std::string& name_;
  const ReadOptions& options_;
  ReadReport* report_;
  int64_t repaired_ = 0;  // information matrices repaired (ReadOptions::repair_information)
  Graph graph_;
  std::vector<PendingLabel> labels_;
  int64_t formulation_line_ = 0;
};

// --- writing ---

class Writer {
 public:
  explicit Writer(std::string* out) : out_(out) {}

  void Text(const char* text) { *out_ += text; }
  void Int(int64_t value) {
    *out_ += ' ';
    *out_ += std::to_string(value);
  }
  void Number(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), " %.17g", value);
    *out_ += buffer;
  }
  void PoseFields(const Pose& pose) {
    for (const int i : {4, 5, 6, 0, 1, 2, 3}) Number(pose.data[i]);
  }
  void Upper3(const Eigen::Matrix3d& m) {
    for (int r = 0; r < 3; ++r) {
      for (int c = r; c < 3; ++c) Number(m(r, c));
    }
  }
  // Tangent order back to the file's g2o order (SPEC §1.2).
  void Upper6(const Matrix6d& tangent) {
    int file_to_tangent[6];
    for (int i = 0; i < 6; ++i) file_to_tangent[kG2oIndex[i]] = i;
    for (int r = 0; r < 6; ++r) {
      for (int c = r; c < 6; ++c) Number(tangent(file_to_tangent[r], file_to_tangent[c]));
    }
  }
  void End() { *out_ += '\n'; }

 private:
  std::string* out_;
};

template <typename Edge, typename Key>
std::vector<const Edge*> SortedOfKind(const Graph& graph, const std::vector<Edge>& edges,
                                      EdgeKind kind, Key key) {
  std::vector<const Edge*> sorted;
  for (const Edge& e : edges) {
    if (KindOf(graph, e) == kind) sorted.push_back(&e);
  }
  std::stable_sort(sorted.begin(), sorted.end(),
                   [&](const Edge* a, const Edge* b) { return key(*a) < key(*b); });
  return sorted;
}

void WriteEdges(const Graph& graph, EdgeKind kind, Writer& w) {
  switch (kind) {
    case EdgeKind::kPrior:
    case EdgeKind::kObjectPrior:
      for (const PriorEdge* e :
           SortedOfKind(graph, graph.priors, kind, [](const PriorEdge& e) { return e.pose; })) {
        w.Text("EDGE_SE3_PRIOR");
        w.Int(e->pose);
        w.PoseFields(e->measurement);
        w.Upper6(e->information);
        w.End();
      }
      return;
    case EdgeKind::kOdometry:
    case EdgeKind::kSmoothing:
      for (const BetweenEdge* e : SortedOfKind(graph, graph.betweens, kind, [](const BetweenEdge& e) {
             return std::pair{e.from, e.to};
           })) {
        w.Text("EDGE_SE3:QUAT");
        w.Int(e->from);
        w.Int(e->to);
        w.PoseFields(e->measurement);
        w.Upper6(e->information);
        w.End();
      }
      return;
    case EdgeKind::kPoint:
    case EdgeKind::kDynamicPoint:
      for (const PointEdge* e : SortedOfKind(graph, graph.point_edges, kind, [](const PointEdge& e) {
             return std::pair{e.pose, e.point};
           })) {
        w.Text("EDGE_SE3_TRACKXYZ");
        w.Int(e->pose);
        w.Int(e->point);
        for (int i = 0; i < 3; ++i) w.Number(e->measurement[i]);
        w.Upper3(e->information);
        w.Int(e->is_dynamic ? 1 : 0);
        w.End();
      }
      return;
    case EdgeKind::kMotion:
      for (const MotionEdge* e : SortedOfKind(graph, graph.motion_edges, kind, [](const MotionEdge& e) {
             return std::tuple{e.prev, e.curr, e.motion};
           })) {
        w.Text("EDGE_SE3_MOTION");
        w.Int(e->prev);
        w.Int(e->curr);
        w.Int(e->motion);
        for (int i = 0; i < 3; ++i) w.Number(e->measurement[i]);
        w.Upper3(e->information);
        w.Int(e->object);
        w.Int(e->frame);
        w.Int(e->camera);
        w.End();
      }
      return;
    case EdgeKind::kObjectPoint:
      for (const ObjectPointEdge* e :
           SortedOfKind(graph, graph.object_point_edges, kind, [](const ObjectPointEdge& e) {
             return std::tuple{e.camera, e.object_pose, e.point};
           })) {
        w.Text("EDGE_SE3_OBJ_TRACKXYZ");
        w.Int(e->camera);
        w.Int(e->object_pose);
        w.Int(e->point);
        for (int i = 0; i < 3; ++i) w.Number(e->measurement[i]);
        w.Upper3(e->information);
        w.End();
      }
      return;
    case EdgeKind::kObjectMotion:
      for (const ObjectMotionEdge* e :
           SortedOfKind(graph, graph.object_motion_edges, kind, [](const ObjectMotionEdge& e) {
             return std::tuple{e.pose_prev, e.pose_curr, e.motion, e.point};
           })) {
        w.Text("EDGE_SE3_OBJ_MOTION");
        w.Int(e->pose_prev);
        w.Int(e->pose_curr);
        w.Int(e->motion);
        w.Int(e->point);
        w.Upper3(e->information);
        w.End();
      }
      return;
    case EdgeKind::kKinematic:
      for (const KinematicEdge* e :
           SortedOfKind(graph, graph.kinematic_edges, kind, [](const KinematicEdge& e) {
             return std::tuple{e.pose_prev, e.pose_curr, e.motion};
           })) {
        w.Text("EDGE_SE3_OBJ_KINEMATIC");
        w.Int(e->pose_prev);
        w.Int(e->pose_curr);
        w.Int(e->motion);
        w.Upper6(e->information);
        w.End();
      }
      return;
  }
}

void WriteLabel(VertexId id, const Label& label, Writer& w) {
  switch (label.role) {
    case Role::kUnknown: return;
    case Role::kCamera: w.Text("LABEL_CAMERA"); w.Int(id); w.Int(label.frame); break;
    case Role::kStaticPoint: w.Text("LABEL_STATIC_POINT"); w.Int(id); w.Int(label.tracklet); break;
    case Role::kDynamicPoint:
      w.Text("LABEL_DYNAMIC_POINT");
      w.Int(id);
      w.Int(label.object);
      w.Int(label.frame);
      w.Int(label.tracklet);
      break;
    case Role::kMotion: w.Text("LABEL_MOTION"); w.Int(id); w.Int(label.object); w.Int(label.frame); break;
    case Role::kObjectPose:
      w.Text("LABEL_OBJECT_POSE");
      w.Int(id);
      w.Int(label.object);
      w.Int(label.frame);
      break;
    case Role::kObjectPoint:
      w.Text("LABEL_OBJECT_POINT");
      w.Int(id);
      w.Int(label.object);
      w.Int(label.tracklet);
      break;
  }
  w.End();
}

std::string Serialise(const Graph& graph) {
  std::string out;
  out.reserve(64 * (graph.vertices.size() + graph.NumEdges()) + 1024);
  Writer w(&out);
  if (graph.formulation) {
    w.Text("LABEL_FORMULATION ");
    w.Text(graph.formulation->c_str());
    w.End();
  }
  for (const auto& [id, vertex] : graph.vertices) {
    if (vertex.type == VertexType::kPose) {
      w.Text("VERTEX_SE3:QUAT");
      w.Int(id);
      w.PoseFields(vertex.pose());
    } else {
      w.Text("VERTEX_TRACKXYZ");
      w.Int(id);
      for (int i = 0; i < 3; ++i) w.Number(vertex.value[i]);
    }
    w.End();
  }
  for (const EdgeKind kind : kAllEdgeKinds) WriteEdges(graph, kind, w);
  if (graph.labelled) {
    for (const auto& [id, vertex] : graph.vertices) WriteLabel(id, vertex.label, w);
  }
  return out;
}

}  // namespace

Expected<Graph> ReadGraph(std::istream& in, const std::string& name, const ReadOptions& options,
                          ReadReport* report) {
  return Reader(name, options, report).Read(in);
}

Expected<Graph> ReadGraph(const std::string& path, const ReadOptions& options, ReadReport* report) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Error{path, 0, "is a directory, not a graph file"};
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, 0, std::string("cannot open the file: ") + std::strerror(errno)};
  return ReadGraph(in, path, options, report);
}

void WriteGraph(const Graph& graph, std::ostream& out) { out << Serialise(graph); }

Status WriteGraph(const Graph& graph, const std::string& path) {
  return WriteFileAtomically(path, Serialise(graph));
}

}  // namespace dynslam
