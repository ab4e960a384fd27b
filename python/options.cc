#include "options.h"

#include <functional>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace dynslam::python {
namespace {

template <typename T>
const char* TypeName() {
  if constexpr (std::is_same_v<T, bool>) return "bool";
  if constexpr (std::is_integral_v<T>) return "int";
  return "float";
}

template <typename Options>
using Setters = std::map<std::string, std::function<void(Options*, py::handle)>>;

// A plain field: the Python value cast to the field's type (TypeError when it cannot be).
template <typename Options, typename T>
std::pair<const std::string, std::function<void(Options*, py::handle)>> Plain(
    const char* name, T Options::*member) {
  return {name, [name, member](Options* o, py::handle value) {
            // bool from a bool only: pybind11 would take 0 and 1, and a float from an int.
            const bool wrong_bool = std::is_same_v<T, bool> && !py::isinstance<py::bool_>(value);
            try {
              if (!wrong_bool) {
                o->*member = value.cast<T>();
                return;
              }
            } catch (const py::cast_error&) {
            }
            throw py::type_error(std::string(name) + ": expected " + TypeName<T>() + ", got " +
                                 py::str(py::type::of(value).attr("__name__")).cast<std::string>() +
                                 " " + py::repr(value).cast<std::string>());
          }};
}

template <typename Options>
Options Apply(const Setters<Options>& setters, const py::kwargs& kwargs) {
  Options options;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::cast<std::string>(key);
    auto it = setters.find(name);
    if (it == setters.end()) throw py::type_error("unknown option '" + name + "'");
    it->second(&options, value);
  }
  return options;
}

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
  using O = SimulateOptions;
  static const Setters<O> setters = {
      Plain("first_frame", &O::first_frame),
      Plain("last_frame", &O::last_frame),
      Plain("seed", &O::seed),
      Plain("synthetic_frames", &O::synthetic_frames),
      Plain("noise", &O::noise),
      Plain("pixel_sigma", &O::pixel_sigma),
      Plain("disparity_sigma", &O::disparity_sigma),
      Plain("point_sigma_floor", &O::point_sigma_floor),
      Plain("odometry_rotation_sigma", &O::odometry_rotation_sigma),
      Plain("odometry_translation_sigma", &O::odometry_translation_sigma),
      Plain("motion_init_rotation_sigma", &O::motion_init_rotation_sigma),
      Plain("motion_init_translation_sigma", &O::motion_init_translation_sigma),
      Plain("motion_sigma", &O::motion_sigma),
      Plain("smoothing_rotation_sigma", &O::smoothing_rotation_sigma),
      Plain("smoothing_translation_sigma", &O::smoothing_translation_sigma),
      Plain("outlier_fraction", &O::outlier_fraction),
      Plain("static_points_per_frame", &O::static_points_per_frame),
      Plain("dynamic_points_per_object", &O::dynamic_points_per_object),
  };
  return Apply(setters, kwargs);
}

}  // namespace dynslam::python
