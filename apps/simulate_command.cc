// dynslam simulate --kitti DIR --seq NNNN [--frames A:B] [--seed N] [options] --out PREFIX
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>

#include "cli.h"
#include "command_inputs.h"
#include "commands.h"
#include "dynslam/file_io.h"
#include "dynslam/graph_io.h"
#include "dynslam/ground_truth.h"
#include "dynslam/kitti.h"
#include "dynslam/simulate.h"

namespace dynslam::cli {
namespace {

// "A:B", "A:" or ":B" → [first, last); last −1 means the end.
bool ParseFrames(const std::string& text, int64_t* first, int64_t* last) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos) return false;
  auto number = [](const std::string& s, int64_t* value) {
    if (s.empty() || s.size() > 12 || s.find_first_not_of("0123456789") != std::string::npos) {
      return false;
    }
    *value = std::stoll(s);
    return true;
  };
  const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
  *first = 0;
  *last = -1;
  if (!a.empty() && !number(a, first)) return false;
  if (!b.empty() && !number(b, last)) return false;
  return *last < 0 || *last > *first;
}

std::vector<std::string> SplitComma(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

// The command line without --out and --kitti (paths would make the files depend on where they
// were written).
std::string ArgumentsLine(int argc, char** argv) {
  std::string line;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" || arg == "--kitti") {
      ++i;
      continue;
    }
    if (arg.rfind("--out=", 0) == 0 || arg.rfind("--kitti=", 0) == 0) continue;
    line += (line.empty() ? "" : " ") + arg;
  }
  return line;
}

}  // namespace

int RunSimulate(int argc, char** argv) {
  SimulateOptions o;
  std::string kitti_dir = EmbeddedKittiDir(), sequence, frames, out_prefix;
  std::string object_types = "Car,Van,Truck,Tram,Cyclist,Misc";
  std::string density = "default";
  int64_t seed = 0;
  bool no_noise = false;
  ArgParser parser(
      "dynslam simulate --kitti DIR --seq NNNN [--frames A:B] [--seed N] [options] --out PREFIX\n"
      "       dynslam simulate --synthetic [--frames 0:N] [--seed N] [options] --out PREFIX",
      "Simulates a visual front end on real KITTI Tracking motion (oxts, label_02, calib) or on a\n"
      "small synthetic scene, and writes PREFIX.g2o (a front-end file: SPEC §1.2 edges and §1.4\n"
      "labels) and PREFIX.gt.txt (SPEC §2). Deterministic for a seed. See docs/SIMULATOR.md.");
  parser.AddExample("dynslam simulate --seq 0003 --seed 1 --out scene");
  parser.AddExample("dynslam simulate --seq 0020 --density paper --frames 0:100 --out big");
  parser.Group("scene");
  parser.AddString("kitti", &kitti_dir,
                   "KITTI tracking folder (oxts/, label_02/, calib/); default: the embedded data "
                   "(the repository's data/kitti_tracking, found from where the command is, or "
                   "$DYNSLAM_KITTI)",
                   "DIR");
  parser.AddString("seq", &sequence, "sequence number, e.g. 0003 (required unless --synthetic)",
                   "NNNN");
  parser.AddString("frames", &frames, "frame range A:B, B exclusive; A: and :B allowed; all frames when absent", "A:B");
  parser.AddInt("seed", &seed, "random seed", 0, INT64_MAX);
  parser.AddFlag("synthetic", &o.synthetic, "a tiny hand-made scene, no KITTI data");
  parser.AddInt("synthetic-frames", &o.synthetic_frames, "frames of the synthetic scene", 2,
                100000);
  parser.Group("noise");
  parser.AddFlag("no-noise", &no_noise,
                 "exact measurements and initial values (informations unchanged)");
  parser.AddDouble("pixel-sigma", &o.pixel_sigma, "image noise, px", 1e-9, 1e6);
  parser.AddDouble("disparity-sigma", &o.disparity_sigma, "disparity noise, px", 1e-9, 1e6);
  parser.AddDouble("point-sigma-floor", &o.point_sigma_floor,
                   "m, added in quadrature to each axis of a point's noise", 0, 1e6);
  parser.AddDouble("odometry-rotation-sigma", &o.odometry_rotation_sigma, "rad per frame", 1e-12,
                   10);
  parser.AddDouble("odometry-translation-sigma", &o.odometry_translation_sigma, "m per frame",
                   1e-12, 1e6);
  parser.AddDouble("motion-init-rotation-sigma", &o.motion_init_rotation_sigma,
                   "rad, noise of initial motions", 1e-12, 10);
  parser.AddDouble("motion-init-translation-sigma", &o.motion_init_translation_sigma,
                   "m, noise of initial motions", 1e-12, 1e6);
  parser.AddDouble("motion-sigma", &o.motion_sigma, "m, ternary motion edge (isotropic)", 1e-12,
                   1e6);
  parser.AddDouble("smoothing-rotation-sigma", &o.smoothing_rotation_sigma, "rad, smoothing edge",
                   1e-12, 10);
  parser.AddDouble("smoothing-translation-sigma", &o.smoothing_translation_sigma,
                   "m, smoothing edge", 1e-12, 1e6);
  parser.AddDouble("prior-sigma", &o.prior_sigma, "rad and m, prior on the first camera", 1e-12,
                   1e6);
  parser.AddDouble("outlier-fraction", &o.outlier_fraction,
                   "fraction of point observations with a gross error", 0, 1);
  parser.AddDouble("outlier-min", &o.outlier_min, "m, smallest gross error", 0, 1e6);
  parser.AddDouble("outlier-max", &o.outlier_max, "m, largest gross error", 0, 1e6);
  parser.Group("density and visibility");
  parser.AddChoice("density", &density, {"default", "paper"},
                   "paper: as many tracked points as the paper's front end, per sequence, so that "
                   "whole sequences build to its Table I variable counts (docs/SIMULATOR.md); "
                   "sets --static-points and --dynamic-points");
  parser.AddInt("static-points", &o.static_points_per_frame,
                "tracked static points kept per frame", 0, 1000000);
  parser.AddInt("dynamic-points", &o.dynamic_points_per_object,
                "tracked points kept per visible moving object", 0, 1000000);
  parser.AddDouble("static-break", &o.static_break_probability,
                   "probability per frame that a static track ends", 0, 1);
  parser.AddDouble("dynamic-break", &o.dynamic_break_probability,
                   "probability per frame that a dynamic track ends", 0, 1);
  parser.AddDouble("min-depth", &o.min_depth, "m, nearest visible depth", 1e-3, 1e6);
  parser.AddDouble("max-depth", &o.max_depth, "m, farthest visible depth", 1e-3, 1e6);
  parser.AddDouble("moving-min-extent", &o.moving_min_extent,
                   "m, an object is moving when its centre spans at least this ...", 0, 1e6);
  parser.AddDouble("moving-min-speed", &o.moving_min_speed,
                   "m/s, ... and reaches this speed over 1 s somewhere", 0, 1e6);
  parser.AddString("object-types", &object_types, "label types simulated as rigid objects",
                   "LIST");
  parser.Group("output");
  parser.AddString("out", &out_prefix, "writes PREFIX.g2o and PREFIX.gt.txt (required)",
                   "PREFIX");
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;
  auto usage_error = [](const std::string& message) {
    std::cerr << "error: " << message << "\n";
    return kExitBadInput;
  };
  if (out_prefix.empty()) return usage_error("--out PREFIX is required");
  if (!o.synthetic && sequence.empty()) return usage_error("--seq NNNN is required (or --synthetic)");
  if (!frames.empty() && !ParseFrames(frames, &o.first_frame, &o.last_frame)) {
    return usage_error("--frames '" + frames + "' is not A:B with A < B");
  }
  if (!sequence.empty() && sequence.find_first_not_of("0123456789") == std::string::npos &&
      sequence.size() < 4) {
    sequence = std::string(4 - sequence.size(), '0') + sequence;  // 3 → 0003
  }
  if (density == "paper") {
    if (o.synthetic || !UsePaperDensity(sequence, &o)) {
      return usage_error("--density paper: only for the paper's sequences 0000-0006, 0018, 0020");
    }
    if (parser.Given("static-points") || parser.Given("dynamic-points")) {
      return usage_error("--density paper sets --static-points and --dynamic-points: give one");
    }
  }
  o.seed = static_cast<uint64_t>(seed);
  o.noise = !no_noise;
  o.object_types = SplitComma(object_types);

  const auto start = std::chrono::steady_clock::now();
  Scene scene;
  std::string title;
  if (o.synthetic) {
    scene = MakeSyntheticScene(o);
    title = "synthetic";
  } else {
    Expected<KittiSequence> read = ReadKittiSequence(kitti_dir, sequence);
    if (!read.ok()) return usage_error(read.error().ToString());
    Expected<Scene> made = MakeKittiScene(*read, o);
    if (!made.ok()) return usage_error(made.error().ToString());
    scene = std::move(made).value();
    title = "kitti " + sequence + " frames " + std::to_string(scene.first_source_frame) + ":" +
            std::to_string(scene.first_source_frame +
                           static_cast<int64_t>(scene.cameras.size()));
  }
  Expected<SimulatedScene> simulated = Simulate(scene, o);
  if (!simulated.ok()) return usage_error(simulated.error().ToString());

  std::string header = "arguments: " + ArgumentsLine(argc, argv) + "\n";
  for (const std::string& line : simulated->header) header += line + "\n";
  const std::string graph_path = out_prefix + ".g2o", gt_path = out_prefix + ".gt.txt";
  std::ostringstream graph_text;
  graph_text << "# front-end graph written by dynslam simulate\n";
  std::istringstream lines(header);
  for (std::string line; std::getline(lines, line);) graph_text << "# " << line << "\n";
  WriteGraph(simulated->graph, graph_text);
  if (Status status = WriteFileAtomically(graph_path, graph_text.str()); !status.ok()) {
    std::cerr << "error: " << status.error().ToString() << "\n";
    return kExitFailed;
  }
  if (Status status = WriteGroundTruth(simulated->ground_truth, gt_path,
                                       "ground truth written by dynslam simulate\n" + header);
      !status.ok()) {
    std::cerr << "error: " << status.error().ToString() << "\n";
    return kExitFailed;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("scene: %s\n%s", title.c_str(), FormatStatistics(simulated->statistics).c_str());
  std::printf("written: %s %s (%.2f s)\n", graph_path.c_str(), gt_path.c_str(), seconds);
  return kExitOk;
}

}  // namespace dynslam::cli
