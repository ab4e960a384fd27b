#include "arrays.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>

#include "dynslam/graph_io.h"
#include "errors.h"
#include "src/number_text.h"

namespace dynslam::python {
namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;

// --- the columns of an edge tag, from its struct's Fields (graph_schema.h) ---

// How one field is held: one integer per row (a vertex id, an integer, a flag) or a block of
// doubles per row (a pose [tx ty tz qx qy qz qw], a 3-vector, a 3×3 or 6×6 information).
enum class Shape { kId, kInteger, kFlag, kPose, kVector3, kMatrix3, kMatrix6 };

bool IsInteger(Shape shape) { return shape == Shape::kId || shape == Shape::kInteger || shape == Shape::kFlag; }

// The dimensions of a row after the first: {} for integers, {7}, {3}, {3, 3}, {6, 6}.
std::vector<py::ssize_t> RowDims(Shape shape) {
  switch (shape) {
    case Shape::kPose: return {7};
    case Shape::kVector3: return {3};
    case Shape::kMatrix3: return {3, 3};
    case Shape::kMatrix6: return {6, 6};
    default: return {};
  }
}

struct Column {
  std::string name;
  Shape shape;
  bool optional = false;  // absent means 0 (an optional trailing field)
};

// Lists the columns of an edge struct (g2o's offset parameter id is not one: it is never
// written).
class ColumnLister : public IgnoreFields {
 public:
  std::vector<Column> columns;
  void Vertex(const VertexField& field, VertexId) { columns.push_back({field.name, Shape::kId}); }
  void Integer(const char* name, int64_t) { columns.push_back({name, Shape::kInteger}); }
  void OptionalFlag(const char* name, bool) { columns.push_back({name, Shape::kFlag, true}); }
  void Measurement(const Pose&) { columns.push_back({"measurement", Shape::kPose}); }
  void Measurement(const Eigen::Vector3d&) { columns.push_back({"measurement", Shape::kVector3}); }
  void OptionalMeasurement(const Eigen::Vector3d&) {  // 0 when absent
    columns.push_back({"measurement", Shape::kVector3, true});
  }
  void Information(const Eigen::Matrix3d&) { columns.push_back({"information", Shape::kMatrix3}); }
  void Information(const Matrix6d&) { columns.push_back({"information", Shape::kMatrix6}); }
};

template <typename Edge>
std::vector<Column> ColumnsOf() {
  ColumnLister lister;
  const Edge edge{};
  Edge::Fields(edge, lister);
  return lister.columns;
}

// f(static_cast<Edge*>(nullptr)) for the edge struct whose tag is `tag`; ValueError otherwise.
template <typename F>
void WithEdgeType(const std::string& tag, F&& f) {
  bool found = false;
  std::string tags;
  EdgeTypes::ForEach([&](auto* type) {
    using Edge = std::remove_pointer_t<decltype(type)>;
    tags += (tags.empty() ? "" : ", ") + std::string(Edge::kTag);
    if (tag == Edge::kTag) {
      found = true;
      f(type);
    }
  });
  if (!found) throw py::value_error("unknown edge tag '" + tag + "' (" + tags + ")");
}

// --- graph → arrays ---

// Appends one edge's fields to per-column buffers, numbers in the file's order.
class ColumnAppender : public IgnoreFields {
 public:
  ColumnAppender(std::vector<std::vector<int64_t>>* ints, std::vector<std::vector<double>>* reals)
      : ints_(ints), reals_(reals) {}
  void Vertex(const VertexField&, VertexId id) { (*ints_)[k_++].push_back(id); }
  void Integer(const char*, int64_t value) { (*ints_)[k_++].push_back(value); }
  void OptionalFlag(const char*, bool value) { (*ints_)[k_++].push_back(value ? 1 : 0); }
  void Measurement(const Pose& pose) {
    for (const int i : {4, 5, 6, 0, 1, 2, 3}) (*reals_)[k_].push_back(pose.data[i]);
    ++k_;
  }
  void Measurement(const Eigen::Vector3d& z) { Append(z); }
  void OptionalMeasurement(const Eigen::Vector3d& z) { Append(z); }
  void Information(const Eigen::Matrix3d& m) { Append(m.transpose()); }  // row by row
  void Information(const Matrix6d& tangent) {
    Matrix6d file_order;
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) {
        file_order(r, c) = tangent(kFileIndexOfTangent[r], kFileIndexOfTangent[c]);
      }
    }
    Append(file_order.transpose());
  }

 private:
  template <typename M>
  void Append(const M& column_major) {
    const Eigen::Matrix<double, M::RowsAtCompileTime, M::ColsAtCompileTime> m = column_major;
    (*reals_)[k_].insert((*reals_)[k_].end(), m.data(), m.data() + m.size());
    ++k_;
  }

  std::vector<std::vector<int64_t>>* ints_;
  std::vector<std::vector<double>>* reals_;
  size_t k_ = 0;
};

py::array ToArray(Shape shape, py::ssize_t rows, const std::vector<int64_t>& ints,
                  const std::vector<double>& reals) {
  if (shape == Shape::kFlag) {
    py::array_t<bool> flags(rows);
    for (py::ssize_t i = 0; i < rows; ++i) flags.mutable_at(i) = ints[i] != 0;
    return std::move(flags);
  }
  if (IsInteger(shape)) return py::array_t<int64_t>(rows, ints.data());
  std::vector<py::ssize_t> dims = RowDims(shape);
  dims.insert(dims.begin(), rows);
  return py::array_t<double>(dims, reals.data());
}

template <typename Edge>
py::dict EdgeColumns(const std::vector<Edge>& edges) {
  const std::vector<Column> columns = ColumnsOf<Edge>();
  std::vector<std::vector<int64_t>> ints(columns.size());
  std::vector<std::vector<double>> reals(columns.size());
  for (const Edge& edge : edges) {
    ColumnAppender appender(&ints, &reals);
    Edge::Fields(edge, appender);
  }
  py::dict out;
  for (size_t k = 0; k < columns.size(); ++k) {
    out[columns[k].name.c_str()] =
        ToArray(columns[k].shape, static_cast<py::ssize_t>(edges.size()), ints[k], reals[k]);
  }
  return out;
}

// The vertices `wanted` selects: "id", the label fields `fields` and "value" (n×7 or n×3).
template <typename Wanted>
py::dict VertexColumns(const Graph& graph, VertexType type, const std::vector<LabelField>& fields,
                       Wanted&& wanted) {
  std::vector<int64_t> ids;
  std::vector<std::vector<int64_t>> labels(fields.size());
  std::vector<double> values;
  for (const auto& [id, vertex] : graph.vertices) {
    if (vertex.type != type || !wanted(vertex)) continue;
    ids.push_back(id);
    for (size_t k = 0; k < fields.size(); ++k) labels[k].push_back(vertex.label.at(fields[k]));
    if (type == VertexType::kPose) {
      for (const int i : {4, 5, 6, 0, 1, 2, 3}) values.push_back(vertex.value[i]);
    } else {
      values.insert(values.end(), vertex.value.begin(), vertex.value.begin() + 3);
    }
  }
  const py::ssize_t n = static_cast<py::ssize_t>(ids.size());
  py::dict out;
  out["id"] = py::array_t<int64_t>(n, ids.data());
  for (size_t k = 0; k < fields.size(); ++k) {
    out[LabelFieldName(fields[k])] = py::array_t<int64_t>(n, labels[k].data());
  }
  out["value"] = ToArray(type == VertexType::kPose ? Shape::kPose : Shape::kVector3, n, {}, values);
  return out;
}

// The role named `name` as summary.json names it ("camera", …), or null.
const RoleInfo* RoleNamed(const std::string& name) {
  for (const RoleInfo& info : kRoles) {
    if (name == info.name) return &info;
  }
  return nullptr;
}

// "camera, static_point, …": every role's name, for errors.
std::string RoleNames() {
  std::string names;
  for (const RoleInfo& info : kRoles) names += (names.empty() ? "" : ", ") + std::string(info.name);
  return names;
}

std::vector<LabelField> FieldsOf(const RoleInfo& role) {
  return {role.fields.begin(), role.fields.begin() + role.num_fields};
}

constexpr LabelField kAllLabelFields[] = {LabelField::kObject, LabelField::kFrame,
                                          LabelField::kTracklet, LabelField::kEmbedded};

// --- arrays → graph file text ---

// A graph file being written from tables, with the table row each line came from.
struct RowsText {
  std::string text;
  std::vector<std::string> origin;  // origin[line - 1]: "vertices['camera'] row 3"

  void Line(const std::string& line, const std::string& where) {
    text += line;
    text += '\n';
    origin.push_back(where);
  }
};

std::string Repr(const std::vector<py::ssize_t>& dims) {
  std::string text = "(";
  for (size_t i = 0; i < dims.size(); ++i) {
    text += (i ? ", " : "") + (dims[i] < 0 ? std::string("n") : std::to_string(dims[i]));
  }
  return text + (dims.size() == 1 ? ",)" : ")");
}

// Column `name` of `table` (named `where` in errors) as an array of `shape` with `rows` rows
// (-1: any number). TypeError for a dtype that is not numbers of the kind, ValueError for a
// shape that is not the one wanted.
py::array ColumnArray(const py::dict& table, const std::string& where, const std::string& name,
                      Shape shape, py::ssize_t rows, const std::string& first_column) {
  const std::string at = where + "['" + name + "']";
  const py::array raw = py::module_::import("numpy").attr("asarray")(table[name.c_str()]);
  const char kind = raw.dtype().kind();
  const bool integers = kind == 'i' || kind == 'u' || (shape == Shape::kFlag && kind == 'b');
  if (raw.size() > 0 && !(IsInteger(shape) ? integers : (integers || kind == 'f'))) {
    throw py::type_error(at + ": " + (IsInteger(shape) ? "integers" : "numbers") +
                         " wanted, not " + py::str(raw.dtype()).cast<std::string>());
  }
  std::vector<py::ssize_t> wanted = RowDims(shape);
  wanted.insert(wanted.begin(), rows);
  if (rows >= 0 && (raw.ndim() == 0 || raw.shape(0) != rows)) {
    throw py::value_error(at + ": " + std::to_string(raw.ndim() ? raw.shape(0) : 0) +
                          " rows, '" + first_column + "' has " + std::to_string(rows));
  }
  std::vector<py::ssize_t> dims(raw.shape(), raw.shape() + raw.ndim());
  if (rows < 0 && !dims.empty()) wanted[0] = dims[0];
  if (dims != wanted) throw py::value_error(at + ": shape " + Repr(dims) + ", wanted " + Repr(wanted));
  if (IsInteger(shape)) return IntArray::ensure(raw);
  return DoubleArray::ensure(raw);
}

void CheckColumnNames(const py::dict& table, const std::string& where,
                      const std::vector<std::string>& known) {
  for (const auto& [key, value] : table) {
    const std::string name = py::str(key);
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw py::value_error(where + ": unknown column '" + name + "' (" + list + ")");
    }
  }
}

void Require(const py::dict& table, const std::string& where, const std::string& name) {
  if (!table.contains(name)) throw py::value_error(where + ": no column '" + name + "'");
}

// One row's numbers for a column as ColumnArray gives it (C order, int64 or double): an integer,
// or a pose/vector/matrix's numbers as the file writes them (a matrix's upper triangle, after a
// check that it is symmetric).
void AppendField(const py::array& column, Shape shape, py::ssize_t row, const std::string& at,
                 std::string* line) {
  if (IsInteger(shape)) {
    *line += ' ' + std::to_string(static_cast<const int64_t*>(column.data())[row]);
    return;
  }
  const std::vector<py::ssize_t> dims = RowDims(shape);
  const py::ssize_t width = dims.size() == 1 ? dims[0] : dims[0] * dims[1];
  const double* first = static_cast<const double*>(column.data()) + row * width;
  if (dims.size() == 1) {
    for (py::ssize_t i = 0; i < width; ++i) {
      *line += ' ';
      AppendNumber(line, first[i]);
    }
    return;
  }
  const py::ssize_t n = dims[0];
  double largest = 0;
  for (py::ssize_t i = 0; i < n * n; ++i) largest = std::max(largest, std::abs(first[i]));
  for (py::ssize_t r = 0; r < n; ++r) {
    for (py::ssize_t c = r; c < n; ++c) {
      if (std::abs(first[r * n + c] - first[c * n + r]) > 1e-9 * largest) {
        throw py::value_error(at + " row " + std::to_string(row) + " is not symmetric");
      }
      *line += ' ';
      AppendNumber(line, first[r * n + c]);
    }
  }
}

// What a vertex table's name stands for: a role (labelled vertices) or, for "pose" and "point",
// unlabelled vertices of that type.
struct VertexTable {
  const RoleInfo* role = nullptr;
  VertexType type = VertexType::kPose;
};

VertexTable ParseVertexTable(const std::string& name) {
  if (const RoleInfo* role = RoleNamed(name)) return {role, role->type};
  if (name == "pose") return {nullptr, VertexType::kPose};
  if (name == "point") return {nullptr, VertexType::kPoint};
  throw py::value_error("unknown vertex table '" + name + "' (" + RoleNames() +
                        ", or pose, point for unlabelled vertices)");
}

// A label field the role does not have is accepted when every row holds -1 (as vertices()
// gives it), so that vertices(role) can be passed back.
void CheckAbsentLabel(const py::dict& table, const std::string& where, const RoleInfo* role,
                      LabelField field, py::ssize_t rows) {
  const std::string name = LabelFieldName(field);
  if (!table.contains(name)) return;
  const py::array column = ColumnArray(table, where, name, Shape::kInteger, rows, "id");
  for (py::ssize_t i = 0; i < rows; ++i) {
    if (static_cast<const int64_t*>(column.data())[i] != -1) {
      throw py::value_error(where + "['" + name + "']: a" +
                            (role ? std::string(" ") + role->name : std::string("n unlabelled vertex")) +
                            " has no " + name + " label");
    }
  }
}

void WriteVertexTable(const std::string& name, const py::dict& table, RowsText* out) {
  const VertexTable kind = ParseVertexTable(name);
  const std::string where = "vertices['" + name + "']";
  const std::vector<LabelField> fields = kind.role ? FieldsOf(*kind.role) : std::vector<LabelField>{};
  std::vector<std::string> known = {"id", "value"};
  for (const LabelField field : kAllLabelFields) known.push_back(LabelFieldName(field));
  CheckColumnNames(table, where, known);
  Require(table, where, "id");
  Require(table, where, "value");
  for (const LabelField field : fields) Require(table, where, LabelFieldName(field));
  const py::array ids = ColumnArray(table, where, "id", Shape::kId, -1, "id");
  const py::ssize_t rows = ids.ndim() ? ids.shape(0) : 0;
  const Shape value_shape = kind.type == VertexType::kPose ? Shape::kPose : Shape::kVector3;
  const py::array values = ColumnArray(table, where, "value", value_shape, rows, "id");
  std::vector<py::array> labels;
  for (const LabelField field : fields) {
    labels.push_back(ColumnArray(table, where, LabelFieldName(field), Shape::kInteger, rows, "id"));
  }
  for (const LabelField field : kAllLabelFields) {
    if (std::find(fields.begin(), fields.end(), field) == fields.end()) {
      CheckAbsentLabel(table, where, kind.role, field, rows);
    }
  }
  const char* tag = kind.type == VertexType::kPose ? "VERTEX_SE3:QUAT" : "VERTEX_TRACKXYZ";
  for (py::ssize_t i = 0; i < rows; ++i) {
    const std::string row = where + " row " + std::to_string(i);
    std::string line = tag;
    AppendField(ids, Shape::kId, i, where, &line);
    AppendField(values, value_shape, i, where, &line);
    out->Line(line, row);
    if (kind.role == nullptr) continue;
    std::string label = kind.role->label_tag;
    AppendField(ids, Shape::kId, i, where, &label);
    for (const py::array& column : labels) AppendField(column, Shape::kInteger, i, where, &label);
    out->Line(label, row);
  }
}

template <typename Edge>
void WriteEdgeTable(const py::dict& table, RowsText* out) {
  const std::string where = std::string("edges['") + Edge::kTag + "']";
  const std::vector<Column> columns = ColumnsOf<Edge>();
  std::vector<std::string> known;
  for (const Column& column : columns) known.push_back(column.name);
  CheckColumnNames(table, where, known);
  std::vector<py::array> arrays;
  py::ssize_t rows = -1;
  for (const Column& column : columns) {
    if (column.optional && !table.contains(column.name)) break;  // optional fields come last
    Require(table, where, column.name);
    arrays.push_back(ColumnArray(table, where, column.name, column.shape, rows, columns[0].name));
    if (rows < 0) rows = arrays.back().ndim() ? arrays.back().shape(0) : 0;
  }
  for (py::ssize_t i = 0; i < rows; ++i) {
    std::string line = Edge::kTag;
    for (size_t k = 0; k < arrays.size(); ++k) {
      AppendField(arrays[k], columns[k].shape, i, where + "['" + columns[k].name + "']", &line);
    }
    out->Line(line, where + " row " + std::to_string(i));
  }
}

}  // namespace

py::dict Vertices(const Graph& graph, const std::string& role_name) {
  const RoleInfo* role = RoleNamed(role_name);
  if (role == nullptr) {
    throw py::value_error("unknown role '" + role_name + "' (" + RoleNames() + ")");
  }
  return VertexColumns(graph, role->type, {std::begin(kAllLabelFields), std::end(kAllLabelFields)},
                       [&](const Vertex& v) { return v.label.role == role->role; });
}

py::dict Edges(const Graph& graph, const std::string& tag) {
  py::dict out;
  WithEdgeType(tag, [&](auto* type) {
    using Edge = std::remove_pointer_t<decltype(type)>;
    out = EdgeColumns(graph.Edges<Edge>());
  });
  return out;
}

py::dict Arrays(const Graph& graph) {
  py::dict vertices;
  if (graph.labelled) {
    for (const RoleInfo& info : kRoles) {
      py::dict table = VertexColumns(graph, info.type, FieldsOf(info),
                                     [&](const Vertex& v) { return v.label.role == info.role; });
      if (py::len(table["id"]) > 0) vertices[info.name] = table;
    }
  } else {
    for (const auto& [name, type] : {std::pair{"pose", VertexType::kPose},
                                     std::pair{"point", VertexType::kPoint}}) {
      py::dict table = VertexColumns(graph, type, {}, [](const Vertex&) { return true; });
      if (py::len(table["id"]) > 0) vertices[name] = table;
    }
  }
  py::dict edges;
  EdgeTypes::ForEach([&](auto* type) {
    using Edge = std::remove_pointer_t<decltype(type)>;
    if (!graph.Edges<Edge>().empty()) edges[Edge::kTag] = EdgeColumns(graph.Edges<Edge>());
  });
  py::dict out;
  out["vertices"] = vertices;
  out["edges"] = edges;
  out["formulation"] = graph.formulation ? py::object(py::str(*graph.formulation)) : py::none();
  return out;
}

Graph FromArrays(const py::dict& vertices, const py::dict& edges, const py::object& formulation) {
  RowsText text;
  if (!formulation.is_none()) {
    text.Line("LABEL_FORMULATION " + formulation.cast<std::string>(), "formulation");
  }
  for (const auto& [name, table] : vertices) {
    WriteVertexTable(py::str(name), table.cast<py::dict>(), &text);
  }
  for (const auto& [tag, table] : edges) {
    WithEdgeType(py::str(tag), [&](auto* type) {
      WriteEdgeTable<std::remove_pointer_t<decltype(type)>>(table.cast<py::dict>(), &text);
    });
  }
  std::istringstream in(text.text);
  Expected<Graph> graph = ReadGraph(in, "<arrays>");
  if (graph.ok()) return std::move(graph).value();
  Error error = graph.error();
  if (error.line >= 1 && error.line <= static_cast<int64_t>(text.origin.size())) {
    error.message = text.origin[error.line - 1] + ": " + error.message;
    error.file.clear();
    error.line = 0;
  }
  throw ErrorException{error};
}

Graph WithValues(const Graph& graph, const IntArray& ids, const DoubleArray& values) {
  if (ids.ndim() != 1 || values.ndim() != 2 || values.shape(0) != ids.shape(0) ||
      (values.shape(1) != 7 && values.shape(1) != 3)) {
    throw py::value_error("values: one row per id, 7 columns (poses) or 3 (points)");
  }
  const bool poses = values.shape(1) == 7;
  Graph out = graph;
  for (py::ssize_t i = 0; i < ids.shape(0); ++i) {
    auto it = out.vertices.find(ids.at(i));
    if (it == out.vertices.end()) {
      throw py::value_error("id " + std::to_string(ids.at(i)) + " is not a vertex of the graph");
    }
    if ((it->second.type == VertexType::kPose) != poses) {
      throw py::value_error("vertex " + std::to_string(ids.at(i)) + " is a " +
                            (poses ? "point: give 3 columns" : "pose: give 7 columns"));
    }
    const double* row = values.data(i, 0);
    for (py::ssize_t k = 0; k < values.shape(1); ++k) {
      if (!std::isfinite(row[k])) {
        throw py::value_error("vertex " + std::to_string(ids.at(i)) + ": a value is not finite");
      }
    }
    if (!poses) {
      it->second.point() = Eigen::Vector3d(row[0], row[1], row[2]);
      continue;
    }
    const Eigen::Quaterniond q(row[6], row[3], row[4], row[5]);  // w, x, y, z
    if (!(q.norm() > 1e-12)) {
      throw py::value_error("vertex " + std::to_string(ids.at(i)) + ": a zero quaternion");
    }
    const bool unit = std::abs(q.norm() - 1) < 1e-15;  // as vertices() gave it: exactly
    it->second.set_pose(Pose::FromRotationTranslation(unit ? q : q.normalized(),
                                                      Eigen::Vector3d(row[0], row[1], row[2])));
  }
  return out;
}

}  // namespace dynslam::python
