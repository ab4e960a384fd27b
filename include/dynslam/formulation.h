// Front-end file → world-centric or object-centric graph (SPEC §3; paper Figs. 2 and 3).
//
// Every formulation built from one front-end file sees identical data: the same cameras,
// measurements, tracklets, object segments and initial values. What is dropped (tracklets of
// length one, segments shorter than min_object_frames, their points, motions and edges) is
// dropped from all formulations and reported. Graph layer: no Ceres.
#ifndef DYNSLAM_FORMULATION_H_
#define DYNSLAM_FORMULATION_H_

#include <string>
#include <vector>

#include "dynslam/graph.h"
#include "dynslam/ground_truth.h"
#include "dynslam/status.h"

namespace dynslam {

enum class Formulation { kWorldCentric, kObjectCentricA, kObjectCentricB, kObjectCentricC };
inline constexpr Formulation kAllFormulations[] = {
    Formulation::kWorldCentric, Formulation::kObjectCentricA, Formulation::kObjectCentricB,
    Formulation::kObjectCentricC};

const char* FormulationName(Formulation formulation);  // "wc", "oc_a", "oc_b", "oc_c"
bool ParseFormulation(const std::string& text, Formulation* formulation);

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

// SPEC §3.5.
struct BuildOptions {
  int min_object_frames = 5;
  ObjectInit object_init = ObjectInit::kMotion;
  MotionInit motion_init = MotionInit::kFrontEnd;
  double kinematic_sigma = 0.01;  // information 1/σ² on all six components
  // Prior on the first pose of each segment, as variances (information = 1 / variance).
  double object_prior_rotation_variance = 0.2;     // rad²
  double object_prior_translation_variance = 0.4;  // m²
  // SPEC §7 item 5 (the released code's object-centric noise, never a default): point edges
  // take the information of the first point edge of their kind, object motion edges isotropic
  // σ = 0.2, and a segment's first pose the ground-truth translation with identity rotation.
  // (Item 4, identity motions, is motion_init = kIdentity.)
  bool dsc_object_centric_noise = false;
};

struct BuildReport {
  std::vector<std::string> lines;  // "front-end …", "dropped: …", "kept: …", counts
  std::vector<std::string> warnings;
  std::string ToText() const;
};

// `front_end` must have roles assigned (ReadGraph does). `ground_truth` may be null (then the
// first pose of each segment is initialised from its points, SPEC §3.3). `name` is used in the
// report's first line.
Expected<Graph> BuildFormulation(const Graph& front_end, Formulation formulation,
                                 const BuildOptions& options, const GroundTruth* ground_truth,
                                 BuildReport* report, const std::string& name = "front-end");

}  // namespace dynslam

#endif  // DYNSLAM_FORMULATION_H_
