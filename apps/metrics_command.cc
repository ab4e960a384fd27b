// dynslam metrics SOLVED.g2o GT [--out FILE]   (SPEC §5)
#include <cstdio>
#include <iostream>

#include "arg_parser.h"
#include "commands.h"
#include "dynslam/file_io.h"
#include "dynslam/graph_io.h"
#include "dynslam/ground_truth.h"
#include "dynslam/metrics.h"
#include "src/json_io.h"

namespace dynslam::cli {

int RunMetrics(int argc, char** argv) {
  std::string solved_path, gt_path, out_path;
  ArgParser parser("dynslam metrics SOLVED.g2o GT [--out FILE]",
                   "Scores a solved, labelled graph file (e.g. solution.g2o of any solver) against\n"
                   "ground truth: camera relative pose error, object motion and object pose errors\n"
                   "with their counts (SPEC §5; paper Tables I-III). Prints JSON in the shape of\n"
                   "summary.json's `metrics`.");
  parser.AddExample("dynslam metrics result/solution.g2o scene.gt.txt");
  parser.AddExample("dynslam metrics result/solution.g2o scene.gt.txt --out metrics.json");
  parser.AddPositional("SOLVED.g2o", &solved_path, "labelled graph file at its solution");
  parser.AddPositional("GT", &gt_path, "ground-truth file (SPEC §2)");
  parser.AddString("out", &out_path, "also write the JSON to this file", "FILE");
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;

  Expected<Graph> solved = ReadGraph(solved_path);
  if (!solved.ok()) return ErrorExit(solved.error(), kExitBadInput);
  if (!solved->labelled) {
    return ErrorExit(solved_path + ": the file has no labels; metrics need the frame and object of "
                     "every variable",
                     kExitBadInput);
  }
  Expected<GroundTruth> gt = ReadGroundTruth(gt_path);
  if (!gt.ok()) return ErrorExit(gt.error(), kExitBadInput);
  // The shape of the reference metrics.json: the metrics and what they were computed from,
  // keys in alphabetical order.
  const JsonValue metrics = MetricsToJson(ComputeMetrics(*solved, *gt));
  JsonValue document = {{"camera", metrics.at("camera")}};
  if (solved->formulation) document["formulation"] = *solved->formulation;
  document["ground_truth"] = gt_path;
  document["object_centric"] = metrics.at("object_centric");
  document["object_motion"] = metrics.at("object_motion");
  document["object_pose"] = metrics.at("object_pose");
  document["solution"] = solved_path;
  const std::string json = DumpJson(document) + "\n";
  std::fputs(json.c_str(), stdout);
  if (!out_path.empty()) {
    if (Status status = WriteFileAtomically(out_path, json); !status.ok()) {
      return ErrorExit(status.error(), kExitFailed);
    }
  }
  return kExitOk;
}

}  // namespace dynslam::cli
