// dynslam simulate --kitti DIR --seq NNNN [--frames A:B] [--seed N] [options] --out PREFIX
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>

#include "arg_parser.h"
#include "command_inputs.h"
#include "commands.h"
#include "dynslam/file_io.h"
#include "dynslam/graph_io.h"
#include "dynslam/ground_truth.h"
#include "dynslam/kitti.h"
#include "dynslam/simulate.h"

namespace dynslam::cli {
namespace {

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
  std::string kitti_dir = EmbeddedKittiDir(), sequence, out_prefix;
  std::string density = "default";
  ArgParser parser(
      "dynslam simulate --seq NNNN [--frames A:B] [--seed N] [options] --out PREFIX\n"
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
  TableFlags<SimulateOptions> simulate_flags(&parser, SimulateOptionTable());
  parser.Group("density and visibility");
  parser.AddChoice("density", &density, {"default", "paper"},
                   "paper: as many tracked points as the paper's front end, per sequence, so that "
                   "whole sequences build to its Table I variable counts (docs/SIMULATOR.md); "
                   "sets --static-points and --dynamic-points");
  parser.Group("output");
  parser.AddString("out", &out_prefix, "writes PREFIX.g2o and PREFIX.gt.txt (required)",
                   "PREFIX");
  bool check_options = false;
  parser.AddFlag("check-options", &check_options,
                 "check the other options and exit (0, or 2 naming the problem) without reading "
                 "data or writing anything (what a sweep does before it starts)");
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;
  auto usage_error = [](const std::string& message) { return ErrorExit(message, kExitBadInput); };
  SimulateOptions o;
  if (ReportedProblem(simulate_flags.Finish(&o))) return kExitBadInput;
  if (check_options) {
    const Status status = CheckSimulateOptions(o);
    return status.ok() ? kExitOk : usage_error(status.error().message);
  }
  if (out_prefix.empty()) return usage_error("--out PREFIX is required");
  if (!o.synthetic && sequence.empty()) return usage_error("--seq NNNN is required (or --synthetic)");
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
    return ErrorExit(status.error(), kExitFailed);
  }
  if (Status status = WriteGroundTruth(simulated->ground_truth, gt_path,
                                       "ground truth written by dynslam simulate\n" + header);
      !status.ok()) {
    return ErrorExit(status.error(), kExitFailed);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("scene: %s\n%s", title.c_str(), FormatStatistics(simulated->statistics).c_str());
  std::printf("written: %s %s (%.2f s)\n", graph_path.c_str(), gt_path.c_str(), seconds);
  return kExitOk;
}

}  // namespace dynslam::cli
