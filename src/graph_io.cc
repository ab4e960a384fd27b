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
#include <optional>
#include <tuple>
#include <type_traits>
#include <unordered_map>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "dynslam/file_io.h"
#include "dynslam/formulation.h"
#include "src/number_text.h"
#include "src/text_fields.h"

namespace dynslam {
namespace {

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
  std::string_view field(size_t i) const { return fields_[i]; }

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
    if (!ParseWholeNumber(fields_[i], value)) {
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
      for (int c = 0; c < 6; ++c) {
        (*information)(r, c) = file_order(kFileIndexOfTangent[r], kFileIndexOfTangent[c]);
      }
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

// The field layout of an edge struct (graph_schema.h): required count, optional count, and
// the text that names them in messages ("pose point zx zy zz I(6) [is_dynamic]").
struct EdgeLayout {
  size_t required = 0;
  size_t optional = 0;
  std::string text;

  void Add(size_t n, const std::string& name) {
    required += n;
    text += (text.empty() ? "" : " ") + name;
  }
  void Vertex(const VertexField& field, VertexId) { Add(1, field.name); }
  void Integer(const char* name, int64_t) { Add(1, name); }
  void OptionalOffsetParameter(const char* name, bool) { AddOptional(name); }
  void OptionalFlag(const char* name, bool) { AddOptional(name); }
  void OptionalMeasurement(const Eigen::Vector3d&) { AddOptional("zx zy zz", 3); }
  void Measurement(const Pose&) { Add(7, "tx ty tz qx qy qz qw"); }
  void Measurement(const Eigen::Vector3d&) { Add(3, "zx zy zz"); }
  void Information(const Eigen::Matrix3d&) { Add(6, "I(6)"); }
  void Information(const Matrix6d&) { Add(21, "I(21)"); }

 private:
  void AddOptional(const char* name, size_t n = 1) {
    optional += n;
    text += std::string(text.empty() ? "" : " ") + "[" + name + "]";
  }
};

// Fills an edge from a line's fields, in the order its struct lists them; stops at the first
// error. `with_optional`: the line carries the tag's optional field.
class EdgeFieldParser {
 public:
  EdgeFieldParser(const LineParser& p, bool with_optional) : p_(p), with_optional_(with_optional) {}

  void Vertex(const VertexField&, VertexId& id) {
    Next(1, [&] { return p_.Integer(i_, &id, "vertex id", &error_); });
  }
  void Integer(const char* name, int64_t& value) {
    Next(1, [&] { return p_.Integer(i_, &value, name, &error_); });
  }
  void OptionalOffsetParameter(const char* name, bool& present) {
    present = with_optional_;
    if (!present) return;
    Next(1, [&] {
      int64_t value;
      if (!p_.Integer(i_, &value, name, &error_)) return false;
      if (value == 0) return true;
      error_ = p_.Fail("the offset-parameter id must be 0, not " + std::to_string(value));
      return false;
    });
  }
  void OptionalFlag(const char* name, bool& value) {
    value = false;
    if (!with_optional_) return;
    Next(1, [&] {
      const std::string_view text = p_.field(i_);
      value = text == "1";
      if (text == "0" || text == "1") return true;
      error_ = p_.Fail(std::string(name) + " '" + std::string(text) + "' must be 0 or 1");
      return false;
    });
  }
  void Measurement(Pose& pose) { Next(7, [&] { return p_.ReadPose(i_, &pose, &error_); }); }
  void Measurement(Eigen::Vector3d& z) {
    Next(3, [&] { return p_.Numbers(i_, 3, z.data(), &error_); });
  }
  void OptionalMeasurement(Eigen::Vector3d& z) {
    z.setZero();
    if (with_optional_) Measurement(z);
  }
  void Information(Eigen::Matrix3d& m) {
    Next(6, [&] { return p_.ReadInformation<3>(i_, &m, &error_); });
  }
  void Information(Matrix6d& m) {
    Next(21, [&] { return p_.Read6x6InTangentOrder(i_, &m, &error_); });
  }

  bool ok() const { return ok_; }
  const Error& error() const { return error_; }

 private:
  template <typename Read>
  void Next(size_t width, Read read) {
    if (ok_) ok_ = read();
    i_ += width;
  }

  const LineParser& p_;
  bool with_optional_;
  size_t i_ = 0;
  bool ok_ = true;
  Error error_;
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
      SplitFields(BeforeComment(line), &fields);
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
  Status AddVertex(VertexId id, Vertex vertex, const LineParser& p) {
    auto [it, inserted] = graph_.vertices.emplace(id, vertex);
    if (inserted) return Status::Ok();
    const bool same_type = it->second.type == vertex.type;
    return p.Fail(std::string(same_type ? "duplicate vertex id " : "id ") + std::to_string(id) +
                  (same_type ? "" : " used as two vertex types") + " (first declared on line " +
                  std::to_string(it->second.line) + ")");
  }

  Status ParseLine(int64_t line, std::string_view tag, const std::vector<std::string_view>& f) {
    LineParser p(name_, line, tag, f, !options_.information_in_tangent_order,
                 options_.repair_information ? &repaired_ : nullptr);
    if (tag == "VERTEX_SE3:QUAT") return ParsePoseVertex(p, line);
    if (tag == "VERTEX_TRACKXYZ") return ParsePointVertex(p, line);
    if (tag == "LABEL_FORMULATION") return ParseFormulationLabel(p, line);
    std::optional<Status> edge;
    EdgeTypes::ForEach([&](auto* type) {
      using Edge = std::remove_pointer_t<decltype(type)>;
      if (!edge && tag == Edge::kTag) edge = ParseEdge<Edge>(p, line);
    });
    if (edge) return *edge;
    for (const RoleInfo& role : kRoles) {
      if (tag == role.label_tag) return ParseLabel(role, p, line);
    }
    if (!options_.skip_unknown_tags) {
      return Error{name_, line,
                   "unknown tag '" + std::string(tag) +
                       "' (pass --skip-unknown-tags to skip such lines)"};
    }
    if (report_ != nullptr) ++report_->skipped_tags[std::string(tag)];
    return Status::Ok();
  }

  Status ParsePoseVertex(const LineParser& p, int64_t line) {
    if (Status s = p.ExpectCount({8}, "id tx ty tz qx qy qz qw"); !s.ok()) return s;
    VertexId id;
    Pose pose;
    Error error;
    if (!p.Integer(0, &id, "vertex id", &error) || !p.ReadPose(1, &pose, &error)) return error;
    Vertex vertex;
    vertex.type = VertexType::kPose;
    vertex.value = pose.data;
    vertex.line = line;
    return AddVertex(id, vertex, p);
  }

  Status ParsePointVertex(const LineParser& p, int64_t line) {
    if (Status s = p.ExpectCount({4}, "id x y z"); !s.ok()) return s;
    VertexId id;
    Vertex vertex;
    vertex.type = VertexType::kPoint;
    vertex.value.fill(0);
    vertex.line = line;
    Error error;
    if (!p.Integer(0, &id, "vertex id", &error) || !p.Numbers(1, 3, vertex.value.data(), &error)) {
      return error;
    }
    return AddVertex(id, vertex, p);
  }

  Status ParseFormulationLabel(const LineParser& p, int64_t line) {
    if (Status s = p.ExpectCount({1}, "name"); !s.ok()) return s;
    if (graph_.formulation) {
      return p.Fail("appears twice (first on line " + std::to_string(formulation_line_) + ")");
    }
    const std::string name(p.field(0));
    Formulation formulation;
    if (name != "frontend" && !ParseFormulation(name, &formulation)) {
      return p.Fail("unknown formulation '" + name + "' (frontend, " + FormulationNames() + ")");
    }
    graph_.formulation = name;
    formulation_line_ = line;
    return Status::Ok();
  }

  // Any edge tag of graph_schema.h: the field count, then every field in the struct's order.
  template <typename Edge>
  Status ParseEdge(const LineParser& p, int64_t line) {
    Edge edge;
    EdgeLayout layout;
    Edge::Fields(edge, layout);
    const size_t with_optional = layout.required + layout.optional;
    const Status count = layout.optional == 0
                             ? p.ExpectCount({layout.required}, layout.text.c_str())
                             : p.ExpectCount({layout.required, with_optional}, layout.text.c_str());
    if (!count.ok()) return count;
    EdgeFieldParser parser(p, layout.optional > 0 && p.size() == with_optional);
    Edge::Fields(edge, parser);
    if (!parser.ok()) return parser.error();
    if (const std::string invalid = edge.Invalid(); !invalid.empty()) return p.Fail(invalid);
    edge.line = line;
    graph_.Edges<Edge>().push_back(edge);
    return Status::Ok();
  }

  Status ParseLabel(const RoleInfo& role, const LineParser& p, int64_t line) {
    std::string layout = "id";
    for (int k = 0; k < role.num_fields; ++k) {
      layout += std::string(" ") + LabelFieldName(role.fields[k]);
    }
    if (Status s = p.ExpectCount({1 + static_cast<size_t>(role.num_fields)}, layout.c_str());
        !s.ok()) {
      return s;
    }
    PendingLabel pending{0, Label{role.role}, line, role.label_tag};
    Error error;
    if (!p.Integer(0, &pending.id, "vertex id", &error)) return error;
    for (int k = 0; k < role.num_fields; ++k) {
      const LabelField field = role.fields[k];
      if (!p.Integer(k + 1, &pending.label.at(field), LabelFieldName(field), &error)) return error;
    }
    labels_.push_back(pending);
    return Status::Ok();
  }

  // Every vertex an edge names exists and has the type the edge needs (SPEC §1.6).
  Status ResolveReferences() const {
    Status status;
    graph_.ForEachEdgeVector([&](const auto& edges) {
      for (const auto& e : edges) {
        ForEachVertexField(e, [&](const VertexField& field, VertexId id) {
          if (status.ok()) status = CheckReference(id, field, e.line, e.kTag);
        });
      }
    });
    return status;
  }

  Status CheckReference(VertexId id, const VertexField& field, int64_t line,
                        const char* tag) const {
    const Vertex* vertex = graph_.Find(id);
    if (vertex == nullptr) {
      return Error{name_, line,
                   std::string(tag) + ": field '" + field.name + "' names vertex " +
                       std::to_string(id) + ", which is not declared in the file"};
    }
    if (vertex->type != field.type) {
      return Error{name_, line,
                   std::string(tag) + ": field '" + field.name + "' names vertex " +
                       std::to_string(id) + ", a " +
                       (vertex->type == VertexType::kPose ? "pose" : "point") + " (line " +
                       std::to_string(vertex->line) + "); expected a " +
                       (field.type == VertexType::kPose ? "pose" : "point")};
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
      const bool wants_pose = InfoOf(pending.label.role)->type == VertexType::kPose;
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
    *out_ += ' ';
    AppendNumber(out_, value);
  }
  void PoseFields(const Pose& pose) { AppendPoseFields(out_, pose, ' '); }
  void Upper3(const Eigen::Matrix3d& m) {
    for (int r = 0; r < 3; ++r) {
      for (int c = r; c < 3; ++c) Number(m(r, c));
    }
  }
  // Tangent order back to the file's g2o order (SPEC §1.2).
  void Upper6(const Matrix6d& tangent) {
    int file_to_tangent[6];
    for (int i = 0; i < 6; ++i) file_to_tangent[kFileIndexOfTangent[i]] = i;
    for (int r = 0; r < 6; ++r) {
      for (int c = r; c < 6; ++c) Number(tangent(file_to_tangent[r], file_to_tangent[c]));
    }
  }
  void End() { *out_ += '\n'; }

 private:
  std::string* out_;
};

// Writes one edge's fields in its struct's order (the reader's mirror). g2o's optional offset
// parameter id is not written.
class EdgeFieldWriter : public IgnoreFields {
 public:
  explicit EdgeFieldWriter(Writer& w) : w_(w) {}
  void Vertex(const VertexField&, VertexId id) { w_.Int(id); }
  void Integer(const char*, int64_t value) { w_.Int(value); }
  void OptionalFlag(const char*, bool value) { w_.Int(value ? 1 : 0); }
  void Measurement(const Pose& pose) { w_.PoseFields(pose); }
  void Measurement(const Eigen::Vector3d& z) {
    for (int i = 0; i < 3; ++i) w_.Number(z[i]);
  }
  void OptionalMeasurement(const Eigen::Vector3d& z) {
    if (!z.isZero(0)) Measurement(z);
  }
  void Information(const Eigen::Matrix3d& m) { w_.Upper3(m); }
  void Information(const Matrix6d& m) { w_.Upper6(m); }

 private:
  Writer& w_;
};

// The edges of `kind`, sorted by their parameter vertex ids in field order (SPEC §3.4).
void WriteEdges(const Graph& graph, EdgeKind kind, Writer& w) {
  graph.ForEachEdgeVector([&](const auto& edges) {
    using Edge = typename std::decay_t<decltype(edges)>::value_type;
    std::vector<std::pair<std::vector<VertexId>, const Edge*>> sorted;
    for (const Edge& e : edges) {
      if (KindOf(graph, e) == kind) sorted.emplace_back(VertexIds(e, true), &e);
    }
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    EdgeFieldWriter fields(w);
    for (const auto& [key, e] : sorted) {
      w.Text(Edge::kTag);
      Edge::Fields(*e, fields);
      w.End();
    }
  });
}

void WriteLabel(VertexId id, const Label& label, Writer& w) {
  const RoleInfo* role = InfoOf(label.role);
  if (role == nullptr) return;
  w.Text(role->label_tag);
  w.Int(id);
  for (int k = 0; k < role->num_fields; ++k) w.Int(label.at(role->fields[k]));
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

std::string GraphText(const Graph& graph) { return Serialise(graph); }

void WriteGraph(const Graph& graph, std::ostream& out) { out << Serialise(graph); }

Status WriteGraph(const Graph& graph, const std::string& path) {
  return WriteFileAtomically(path, Serialise(graph));
}

}  // namespace dynslam
