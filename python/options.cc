#include "options.h"

#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace dynslam::python {
namespace {

// numpy.bool_, or an empty handle without NumPy; kept for the life of the process (released, so
// that nothing is destroyed after the interpreter).
py::handle NumpyBool() {
  static const py::handle type = []() -> py::handle {
    try {
      return py::object(py::module_::import("numpy").attr("bool_")).release();
    } catch (const py::error_already_set&) {
      return py::handle();
    }
  }();
  return type;
}

// A keyword argument's value as the option's text: TypeError when its Python type does not fit.
template <typename Options>
std::string TextOf(const Option<Options>& option, py::handle value) {
  // NumPy scalars too: an integer is anything with __index__ (np.int64), a float anything with
  // __float__ (np.float32); a bool is neither.
  const bool is_bool = py::isinstance<py::bool_>(value) ||
                       (NumpyBool() && py::isinstance(value, NumpyBool()));
  const bool is_int = !is_bool && PyIndex_Check(value.ptr());
  const bool is_float = !is_bool && !py::isinstance<py::str>(value) &&
                        (is_int || PyFloat_Check(value.ptr()) || py::hasattr(value, "__float__"));
  const char* expected = nullptr;
  switch (option.type) {
    case OptionType::kSwitch:
      if (is_bool) return PyObject_IsTrue(value.ptr()) == 1 ? "on" : "off";
      expected = "bool";
      break;
    case OptionType::kInteger:
      if (is_int) return py::str(py::int_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
      expected = "int";
      break;
    case OptionType::kReal:
      if (is_float) return RealText(py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>());
      expected = "float";
      break;
    case OptionType::kChoice:
    case OptionType::kText:
    case OptionType::kPreset:
      if (py::isinstance<py::str>(value)) return value.cast<std::string>();
      expected = "str";
      break;
  }
  throw py::type_error(option.name + ": expected " + expected + ", got " +
                       py::str(py::type::of(value).attr("__name__")).cast<std::string>() + " " +
                       py::repr(value).cast<std::string>());
}

template <typename Options>
Options FromTable(const OptionTable<Options>& table, const py::kwargs& kwargs) {
  std::vector<std::pair<std::string, std::string>> given;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::cast<std::string>(key);
    const Option<Options>* option = FindOption(table, name);
    if (option == nullptr || name.find('-') != std::string::npos) {
      throw py::type_error("unknown option '" + name + "'");
    }
    given.emplace_back(name, TextOf(*option, value));
  }
  Options options;
  if (std::optional<std::string> problem =
          ApplyOptions(table, given, [](const std::string& name) { return name; }, &options)) {
    throw py::value_error(*problem);
  }
  return options;
}

const char* PythonType(OptionType type) {
  switch (type) {
    case OptionType::kSwitch: return "bool";
    case OptionType::kInteger: return "int";
    case OptionType::kReal: return "float";
    default: return "str";
  }
}

template <typename Options>
std::string TableDoc(const OptionTable<Options>& table) {
  const Options defaults;
  std::string doc;
  for (const Option<Options>& option : table) {
    std::string value = option.get(defaults);
    if (option.type == OptionType::kSwitch) value = value == "on" ? "True" : "False";
    if (option.type == OptionType::kChoice || option.type == OptionType::kText ||
        option.type == OptionType::kPreset) {
      value = "'" + value + "'";
    }
    doc += "    " + option.name + " (" + PythonType(option.type) + ", default " + value;
    if (!option.values.empty() && option.type != OptionType::kSwitch) {
      doc += "; one of " + option.metavar;
    }
    doc += "): " + option.help + "\n";
  }
  return doc;
}

}  // namespace

SolverOptions ToSolverOptions(const py::kwargs& kwargs) {
  return FromTable(SolverOptionTable(), kwargs);
}

BuildOptions ToBuildOptions(const py::kwargs& kwargs) {
  return FromTable(BuildOptionTable(), kwargs);
}

std::string SolverOptionsDoc() { return TableDoc(SolverOptionTable()); }
std::string BuildOptionsDoc() { return TableDoc(BuildOptionTable()); }

SimulateOptions ToSimulateOptions(const py::kwargs& kwargs) {
  return FromTable(SimulateOptionTable(), kwargs);
}

std::string SimulateOptionsDoc() { return TableDoc(SimulateOptionTable()); }

}  // namespace dynslam::python
