// A graph as NumPy arrays and back (the Python module's Graph.vertices, edges, arrays,
// with_values and from_arrays). Columns are named by graph_schema.h's tables, so a new edge tag
// or label field is here without a change to this file. Numbers are in the file's order
// (SPEC §1.2): poses [tx ty tz qx qy qz qw], 6×6 information translation first.
#ifndef DYNSLAM_PYTHON_ARRAYS_H_
#define DYNSLAM_PYTHON_ARRAYS_H_

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "dynslam/graph.h"

namespace dynslam::python {

namespace py = pybind11;

// The vertices of one role (`role_name` as summary.json names it): id, object, frame, tracklet,
// embedded (int64, -1 where the role has no such field) and value (n×7 poses or n×3 points).
py::dict Vertices(const Graph& graph, const std::string& role_name);

// The edges of one tag (`EDGE_SE3:QUAT`, …): one array per field of the tag, named as
// graph_schema.h names it, in the graph's order. ValueError for an unknown tag.
py::dict Edges(const Graph& graph, const std::string& tag);

// {"vertices": {table: columns}, "edges": {tag: columns}, "formulation": str | None}: the whole
// graph, such that FromArrays(**it) writes the same file. A labelled graph's vertex tables are
// its roles (only the label fields each role has); an unlabelled graph's are "pose" and "point".
py::dict Arrays(const Graph& graph);

// The inverse of Arrays(). The graph is read as a file holding these rows would be, with every
// check of SPEC §1.6; an error names the table and row (`edges['EDGE_SE3:QUAT'] row 3: …`).
Graph FromArrays(const py::dict& vertices, const py::dict& edges, const py::object& formulation);

// A copy of `graph` with the values of the vertices `ids` replaced by the rows of `values`
// (n×7 poses, quaternions normalised, or n×3 points): the inverse of Vertices()'s values.
Graph WithValues(const Graph& graph,
                 const py::array_t<int64_t, py::array::c_style | py::array::forcecast>& ids,
                 const py::array_t<double, py::array::c_style | py::array::forcecast>& values);

}  // namespace dynslam::python

#endif  // DYNSLAM_PYTHON_ARRAYS_H_
