#include "options.h"

#include <functional>
#include <map>
#include <string>
#include <type_traits>

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

// An enum field spelled as on the command line.
template <typename Options, typename E>
std::pair<const std::string, std::function<void(Options*, py::handle)>> Named(
    const char* name, E Options::*member, bool (*parse)(const std::string&, E*)) {
  return {name, [name, member, parse](Options* o, py::handle value) {
            if (!py::isinstance<py::str>(value)) {
              throw py::type_error(std::string(name) + ": expected str, got " +
                                   py::repr(value).cast<std::string>());
            }
            const std::string text = value.cast<std::string>();
            if (!parse(text, &(o->*member))) {
              throw py::value_error(std::string(name) + ": unknown value '" + text + "'");
            }
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

bool ParseMotionInit(const std::string& text, MotionInit* init) {
  if (text != "frontend" && text != "identity") return false;
  *init = text == "frontend" ? MotionInit::kFrontEnd : MotionInit::kIdentity;
  return true;
}

bool ParseHybridSmoothingInfo(const std::string& text, HybridSmoothingInfo* info) {
  if (text != "frontend" && text != "world" && text != "sigmas") return false;
  *info = text == "frontend" ? HybridSmoothingInfo::kFrontEnd
          : text == "world"  ? HybridSmoothingInfo::kWorld
                             : HybridSmoothingInfo::kSigmas;
  return true;
}

// robust_kernels={"point": ("huber", 1.345), ...}: kinds by their SPEC §1.5 names.
void SetKernels(SolverOptions* options, py::handle value) {
  for (const auto& [key, spec] : value.cast<py::dict>()) {
    const std::string kind = key.cast<std::string>();
    const auto [type, threshold] = spec.cast<std::pair<std::string, double>>();
    int index = -1;
    for (const EdgeKind k : kAllEdgeKinds) {
      if (kind == EdgeKindName(k)) index = static_cast<int>(k);
    }
    if (index < 0) throw py::value_error("robust_kernels: unknown edge kind '" + kind + "'");
    RobustKernel& kernel = options->kernels[index];
    if (type == "huber") {
      kernel.type = RobustKernel::Type::kHuber;
    } else if (type == "cauchy") {
      kernel.type = RobustKernel::Type::kCauchy;
    } else {
      throw py::value_error("robust_kernels: unknown kernel '" + type + "' (huber, cauchy)");
    }
    kernel.threshold = threshold;
  }
}

}  // namespace

SolverOptions ToSolverOptions(const py::kwargs& kwargs) {
  using O = SolverOptions;
  static const Setters<O> setters = {
      Named<O, MinimizerType>("minimizer", &O::minimizer, Parse),
      Named<O, LinearSolverType>("linear_solver", &O::linear_solver, Parse),
      Named<O, SparseBackend>("sparse_backend", &O::sparse_backend, Parse),
      Plain("threads", &O::threads),
      Plain("max_iterations", &O::max_iterations),
      Plain("max_time_s", &O::max_time_s),
      Plain("function_tolerance", &O::function_tolerance),
      Plain("gradient_tolerance", &O::gradient_tolerance),
      Plain("parameter_tolerance", &O::parameter_tolerance),
      Plain("remaining_chi2", &O::remaining_chi2),
      Plain("extrapolate", &O::extrapolate),
      Plain("snap_segment_gauges", &O::snap_segment_gauges),
      Plain("initial_lambda", &O::initial_lambda),
      Plain("nonmonotonic_steps", &O::nonmonotonic_steps),
      Plain("eliminate_object_points", &O::eliminate_object_points),
      Plain("world_anchored_object_points", &O::world_anchored_object_points),
      Plain("world_frame_kinematic_residual", &O::world_frame_kinematic_residual),
      Plain("fix_first", &O::fix_first),
      Plain("dsc_motion_residual", &O::dsc_motion_residual),
      Plain("dsc_motion_sigma", &O::dsc_motion_sigma),
      Plain("dsc_object_motion_residual", &O::dsc_object_motion_residual),
      {"robust_kernels", SetKernels},
  };
  return Apply(setters, kwargs);
}

BuildOptions ToBuildOptions(const py::kwargs& kwargs) {
  using O = BuildOptions;
  static const Setters<O> setters = {
      Plain("min_object_frames", &O::min_object_frames),
      Named<O, ObjectInit>("object_init", &O::object_init, ParseObjectInit),
      Named<O, MotionInit>("motion_init", &O::motion_init, ParseMotionInit),
      Plain("kinematic_sigma", &O::kinematic_sigma),
      Plain("object_prior_rotation_variance", &O::object_prior_rotation_variance),
      Plain("object_prior_translation_variance", &O::object_prior_translation_variance),
      Plain("dsc_object_centric_noise", &O::dsc_object_centric_noise),
      Named<O, HybridSmoothingInfo>("hybrid_smoothing_info", &O::hybrid_smoothing_info,
                                    ParseHybridSmoothingInfo),
      Plain("hybrid_smoothing_sigma_rotation", &O::hybrid_smoothing_sigma_rotation),
      Plain("hybrid_smoothing_sigma_translation", &O::hybrid_smoothing_sigma_translation),
      Plain("hybrid_anchor_sigma", &O::hybrid_anchor_sigma),
      Plain("dynosam_smoothing", &O::dynosam_smoothing),
      Plain("dynosam_embedded_frame", &O::dynosam_embedded_frame),
      Plain("dynosam_points_from_measurements", &O::dynosam_points_from_measurements),
  };
  return Apply(setters, kwargs);
}

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
