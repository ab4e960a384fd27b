// dynslam metrics SOLVED.g2o GT [--out FILE]   (SPEC §5)
#include <cstdio>
#include <iostream>

#include "cli.h"
#include "commands.h"
#include "dynslam/file_io.h"
#include "dynslam/graph_io.h"
#include "dynslam/ground_truth.h"
#include "dynslam/metrics.h"

namespace dynslam::cli {

int RunMetrics(int argc, char** argv) {
  std::string solved_path, gt_path, out_path;
  ArgParser parser("dynslam metrics SOLVED.g2o GT [--out FILE]",
                   "Scores a solved, labelled graph file (e.g. solution.g2o of any solver) against\n"
                   "ground truth: camera relative pose error, object motion and object pose errors\n"
                   "with their counts (SPEC §5; paper Tables I-III). Prints JSON in the shape of\n"
                   "summary.json's `metrics`.");
  parser.AddPositional("SOLVED.g2o", &solved_path, "labelled graph file at its solution");
  parser.AddPositional("GT", &gt_path, "ground-truth file (SPEC §2)");
  parser.AddString("out", &out_path, "also write the JSON to this file", "FILE");
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;

  Expected<Graph> solved = ReadGraph(solved_path);
  if (!solved.ok()) {
    std::cerr << "error: " << solved.error().ToString() << "\n";
    return kExitBadInput;
  }
  if (!solved->labelled) {
    std::cerr << "error: " << solved_path
              << ": the file has no labels; metrics need the frame and object of every variable\n";
    return kExitBadInput;
  }
  Expected<GroundTruth> gt = ReadGroundTruth(gt_path);
  if (!gt.ok()) {
    std::cerr << "error: " << gt.error().ToString() << "\n";
    return kExitBadInput;
  }
  // The shape of the reference metrics.json: the metrics and what they were computed from,
  // keys in alphabetical order.
  const Json metrics = MetricsJson(ComputeMetrics(*solved, *gt));
  Json document = Json::Object();
  document.Set("camera", *metrics.Find("camera"));
  if (solved->formulation) document.Set("formulation", *solved->formulation);
  document.Set("ground_truth", gt_path)
      .Set("object_centric", *metrics.Find("object_centric"))
      .Set("object_motion", *metrics.Find("object_motion"))
      .Set("object_pose", *metrics.Find("object_pose"))
      .Set("solution", solved_path);
  const std::string json = document.Dump() + "\n";
  std::fputs(json.c_str(), stdout);
  if (!out_path.empty()) {
    if (Status status = WriteFileAtomically(out_path, json); !status.ok()) {
      std::cerr << "error: " << status.error().ToString() << "\n";
      return kExitFailed;
    }
  }
  return kExitOk;
}

}  // namespace dynslam::cli
