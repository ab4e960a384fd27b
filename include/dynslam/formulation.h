// Front-end file → world-centric, object-centric or hybrid graph (SPEC §3; paper Figs. 2 and 3;
// DynoSAM's hybrid, §3.6).
//
// Every formulation built from one front-end file sees identical data: the same cameras,
// measurements, tracklets, object segments and initial values. What is dropped (tracklets of
// length one, segments shorter than min_object_frames, their points, motions and edges) is
// dropped from all formulations and reported. Graph layer: no Ceres.
#ifndef DYNSLAM_FORMULATION_H_
#define DYNSLAM_FORMULATION_H_

#include <optional>
#include <string>
#include <vector>

#include "dynslam/graph.h"
#include "dynslam/ground_truth.h"
#include "dynslam/options.h"
#include "dynslam/status.h"

namespace dynslam {

enum class Formulation {
  kWorldCentric,
  kObjectCentricA,
  kObjectCentricB,
  kObjectCentricC,
  kHybrid,
};

// One row per formulation: everything that tells them apart outside their build step.
struct FormulationInfo {
  Formulation formulation;
  const char* name;     // LABEL_FORMULATION value and CLI name (SPEC §1.4)
  const char* summary;  // for help texts
  bool object_frame_points;  // points fixed in an object frame (else one world point per frame)
  // The formulation-specific edge kinds it emits (§3.2, §3.3, §3.6; the shared prior, odometry
  // and static point edges left out), and those a file must have to be taken for it when it
  // carries no LABEL_FORMULATION.
  std::vector<EdgeKind> emits;
  std::vector<EdgeKind> identified_by;
  bool lm_by_default;  // SolverOptions minimizer `auto`: LM (else dogleg), docs/SOLVER.md
};

inline constexpr Formulation kAllFormulations[] = {
    Formulation::kWorldCentric, Formulation::kObjectCentricA, Formulation::kObjectCentricB,
    Formulation::kObjectCentricC, Formulation::kHybrid};

// The table, in the order of kAllFormulations (SPEC §3, `compare`'s columns).
const std::vector<FormulationInfo>& Formulations();
const FormulationInfo& InfoOf(Formulation formulation);
const char* FormulationName(Formulation formulation);  // "wc", "oc_a", "oc_b", "oc_c", "hy"
bool ParseFormulation(const std::string& text, Formulation* formulation);
// "wc, oc_a, oc_b, oc_c, hy" joined by `separator`.
std::string FormulationNames(const char* separator = ", ");

// The formulation of a graph: its LABEL_FORMULATION, else the row whose `identified_by` kinds
// are all present and whose `emits` cover every formulation-specific kind present. Empty for a
// front end, a static graph or a pose graph; `source` (optional) says "label" or "inferred".
std::optional<Formulation> FormulationOfGraph(const Graph& graph, std::string* source = nullptr);
// FormulationOfGraph's name, or "frontend", "static", "pose_graph", "mixed" for the others.
std::string FormulationLabelOf(const Graph& graph, std::string* source = nullptr);

// Initial object poses after a segment's first frame (SPEC §3.3, §3.5):
// kMotion  L_k = H_k · L_{k−1} with the initial motion: the kinematic edge starts at zero;
// kAlign   rigid alignment of the object-frame points onto the initial world points (the rule the
//          reference scenes' graphs were built with);
// kTruth   every pose from the ground truth where it has the object (a study and test aid);
// kCentroid every pose, the first included, at its points' centroid with identity rotation.
enum class ObjectInit { kMotion, kAlign, kTruth, kCentroid };
inline constexpr ObjectInit kAllObjectInits[] = {ObjectInit::kMotion, ObjectInit::kAlign,
                                                 ObjectInit::kTruth, ObjectInit::kCentroid};
const char* ObjectInitName(ObjectInit rule);  // "motion", "align", "truth", "centroid"
bool ParseObjectInit(const std::string& text, ObjectInit* rule);

enum class MotionInit { kFrontEnd, kIdentity };
const char* MotionInitName(MotionInit init);  // "frontend", "identity"

// SPEC §3.6 `hybrid_smoothing_info`: the information of EDGE_SE3_HY_SMOOTHING.
// kFrontEnd  the front-end smoothing edge's information as written;
// kWorld     that information mapped into the body frame, Ad(L_e)ᵀ · Ω · Ad(L_e), so that the
//            prior is as strong as wc's world-frame smoothing;
// kSigmas    1/σ_r² on ω and 1/σ_t² on ρ (DynoSAM: 0.01 rad, 0.1 m).
enum class HybridSmoothingInfo { kFrontEnd, kWorld, kSigmas };

// SPEC §3.5.
// Every field is an option of BuildOptionTable() below, which says what it does.
struct BuildOptions {
  int min_object_frames = 5;
  ObjectInit object_init = ObjectInit::kMotion;
  MotionInit motion_init = MotionInit::kFrontEnd;
  double kinematic_sigma = 0.01;
  double object_prior_rotation_variance = 0.2;     // rad²
  double object_prior_translation_variance = 0.4;  // m²
  HybridSmoothingInfo hybrid_smoothing_info = HybridSmoothingInfo::kFrontEnd;
  double hybrid_smoothing_sigma_rotation = 0.01;    // rad, with kSigmas
  double hybrid_smoothing_sigma_translation = 0.1;  // m, with kSigmas
  double hybrid_anchor_sigma = 1e-6;
  // SPEC §7 item 5 and SPEC §3.6's DynoSAM items (never defaults; --compat sets them).
  bool dsc_object_centric_noise = false;
  bool dynosam_smoothing = false;
  bool dynosam_embedded_frame = false;
  bool dynosam_points_from_measurements = false;
};

// hybrid_smoothing_info as text: "frontend", "world" or "SIGMA_R,SIGMA_T" (kSigmas).
std::string HybridSmoothingInfoText(const BuildOptions& options);
std::optional<std::string> ParseHybridSmoothingInfo(const std::string& text, BuildOptions* options);

// The option table of BuildOptions (options.h). Groups: "build", "compatibility" (SPEC §7, §3.6).
inline const OptionTable<BuildOptions>& BuildOptionTable() {
  using O = BuildOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t = {
        Integer("min_object_frames", "build", &O::min_object_frames,
                "shortest object segment kept, in frames (SPEC §3.1)", 2, 1000000),
        Choice("object_init", "build", &O::object_init,
               {ObjectInit::kMotion, ObjectInit::kAlign, ObjectInit::kTruth, ObjectInit::kCentroid},
               ObjectInitName,
               "initial object poses after a segment's first (SPEC §3.3): chained from the "
               "initial motions, rigid alignment of the points (the reference graphs' rule), the "
               "ground truth at every frame, or every pose at its points' centroid with identity "
               "rotation"),
        Choice("motion_init", "build", &O::motion_init,
               {MotionInit::kFrontEnd, MotionInit::kIdentity}, MotionInitName,
               "initial motions: the front end's values, or identity"),
        Real("kinematic_sigma", "build", &O::kinematic_sigma,
             "sigma of the object kinematic edge, all six components (oc_b, oc_c)", 1e-9, 1e9),
        Real("object_prior_rotation_variance", "build", &O::object_prior_rotation_variance,
             "variance (rad²) of the prior on each object segment's first pose, rotation",
             1e-18, 1e18),
        Real("object_prior_translation_variance", "build", &O::object_prior_translation_variance,
             "variance (m²) of the prior on each object segment's first pose, translation",
             1e-18, 1e18),
        Real("hybrid_anchor_sigma", "build", &O::hybrid_anchor_sigma,
             "sigma of hy's prior holding each segment's first hybrid motion at identity (SPEC "
             "§3.6)",
             1e-12, 1e12),
        Switch("dsc_object_centric_noise", "compatibility", &O::dsc_object_centric_noise,
               "SPEC §7 item 5: point edges with the first point edge's information, object "
               "motion edges sigma 0.2, a segment's first pose at the true translation with "
               "identity rotation"),
        Switch("dynosam_smoothing", "compatibility", &O::dynosam_smoothing,
               "SPEC §3.6 DynoSAM item 1: hy smoothing sigma 0.01 rad, 0.1 m at every frame"),
        Switch("dynosam_embedded_frame", "compatibility", &O::dynosam_embedded_frame,
               "SPEC §3.6 DynoSAM item 3: the embedded frame at the camera-frame mean of the "
               "measurements, identity rotation"),
        Switch("dynosam_points_from_measurements", "compatibility",
               &O::dynosam_points_from_measurements,
               "SPEC §3.6 DynoSAM item 4: object points from their first measurement"),
    };
    Option<O> smoothing = Declare<O>(
        "hybrid_smoothing_info", "build", OptionType::kText,
        "information of hy's smoothing edges (SPEC §3.6): frontend (the front-end edge's, as "
        "written), world (mapped into the body frame by the embedded frame's adjoint: as strong "
        "as wc's), or SIGMA_R,SIGMA_T in rad and m (DynoSAM: 0.01,0.1)",
        "frontend|world|SR,ST");
    smoothing.get = HybridSmoothingInfoText;
    smoothing.set = ParseHybridSmoothingInfo;
    t.insert(t.begin() + 7, smoothing);
    return t;
  }();
  return table;
}

struct BuildReport {
  std::vector<std::string> lines;  // "front-end …", "dropped: …", "kept: …", counts
  std::vector<std::string> warnings;
  std::string ToText() const;
};

// `front_end` must have roles assigned (ReadGraph does). `ground_truth` may be null (then the
// first pose of each segment, and hy's embedded frame, is initialised from its points,
// SPEC §3.3). `name` is used in the
// report's first line.
Expected<Graph> BuildFormulation(const Graph& front_end, Formulation formulation,
                                 const BuildOptions& options, const GroundTruth* ground_truth,
                                 BuildReport* report, const std::string& name = "front-end");

// oc_a, oc_b or oc_c.
bool IsObjectCentric(Formulation formulation);

// SPEC §3.5 `start wc`: `built` (oc_a, oc_b or oc_c, built from `front_end` with `options` and
// `ground_truth`) given the initial values the same build gives when the front end's estimates
// are those of `world_centric` (the wc graph of `front_end` with `options`, solved): cameras,
// static points, motions and dynamic points at that solution (whatever `options.motion_init`
// says), object poses and object-frame points by `options.object_init` from them. The edges,
// the object priors included, stay `front_end`'s: the cost function does not change, only
// where its solve starts (docs/CONVERGENCE.md §8). `world_centric` must have exactly the
// vertices and labels of that wc graph; `start_name` (a file name) is what errors blame.
Status StartFromWorldCentric(const Graph& front_end, const Graph& world_centric,
                             const BuildOptions& options, const GroundTruth* ground_truth,
                             Graph* built, const std::string& start_name = "wc solution");

}  // namespace dynslam

#endif  // DYNSLAM_FORMULATION_H_
