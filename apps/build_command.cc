// dynslam build FRONTEND.g2o --formulation F --out FILE [--gt GT] [--start WC_SOLUTION.g2o] [options]
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "arg_parser.h"
#include "command_inputs.h"
#include "commands.h"
#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/ground_truth.h"
#include "solver_flags.h"

namespace dynslam::cli {

int RunBuild(int argc, char** argv) {
  std::string front_end_path, out_path, gt_path, formulation_name = "wc";
  ArgParser parser("dynslam build FRONTEND.g2o --formulation F --out FILE [--gt GT] [options]",
                   "Builds one formulation (SPEC §3) from a front-end file and writes it as a graph\n"
                   "file (SPEC §3.4 order, full labels) that `dynslam solve` or any other solver reads.\n"
                   "Prints what was kept and dropped.");
  parser.AddExample("dynslam build scene.g2o --formulation oc_b --gt scene.gt.txt --out oc_b.g2o");
  parser.AddExample("dynslam build scene.g2o --formulation hy --hybrid-smoothing-info world --out hy.g2o");
  parser.Group("input and output");
  parser.AddPositional("FRONTEND.g2o", &front_end_path, "front-end graph file (SPEC §1.2, labels optional)");
  parser.AddChoice("formulation", &formulation_name, FormulationChoices(),
                   "world-centric, object-centric variant (paper Figs. 2 and 3) or hybrid "
                   "(DynoSAM, SPEC §3.6)");
  parser.AddString("out", &out_path, "graph file to write (required)", "FILE");
  parser.AddString("gt", &gt_path,
                   "ground truth (SPEC §2): initialises the first object pose (hy: the embedded "
                   "frame) of each segment",
                   "GT");
  std::string start_path;
  parser.AddString("start", &start_path,
                   "oc_a, oc_b, oc_c: take the initial values from this solved wc graph of the same "
                   "front end (`dynslam solve`'s solution.g2o), the edges from the front end "
                   "(SPEC §3.5 start wc)",
                   "WC_SOLUTION.g2o");
  BuildFlags build_flags(&parser, BuildOptionTable());
  CompatFlags compat_flags(&parser, CompatOptionTable());
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;
  Compat compat;
  if (ReportedProblem(compat_flags.Finish(&compat))) return kExitBadInput;
  if (out_path.empty()) return ErrorExit("--out FILE is required", kExitBadInput);
  BuildOptions options;
  if (ReportedProblem(build_flags.Finish(&options))) return kExitBadInput;
  ApplyCompat(compat, &options);
  Formulation formulation;
  ParseFormulation(formulation_name, &formulation);
  if (!start_path.empty() && !IsObjectCentric(formulation)) {
    return ErrorExit("--start applies to oc_a, oc_b and oc_c, not " + formulation_name, kExitBadInput);
  }

  ReadOptions read_options;
  ApplyCompat(compat, &read_options);
  Expected<Graph> front_end = ReadGraph(front_end_path, read_options);
  if (!front_end.ok()) return ErrorExit(front_end.error(), kExitBadInput);
  std::optional<GroundTruth> gt;
  if (!ReadGroundTruthIfGiven(gt_path, &gt)) return kExitBadInput;
  BuildReport report;
  Expected<Graph> built = BuildFormulation(*front_end, formulation, options, gt ? &*gt : nullptr,
                                           &report, std::filesystem::path(front_end_path).filename().string());
  if (!built.ok()) return ErrorExit(built.error(), kExitBadInput);
  if (!start_path.empty()) {
    Expected<Graph> world_centric = ReadGraph(start_path, read_options);
    if (!world_centric.ok()) return ErrorExit(world_centric.error(), kExitBadInput);
    Status started = StartFromWorldCentric(*front_end, *world_centric, options,
                                           gt ? &*gt : nullptr, &*built, start_path);
    if (!started.ok()) return ErrorExit("--start: " + started.error().ToString(), kExitBadInput);
    report.lines.push_back("initial values from " + start_path + " (--start, SPEC §3.5)");
  }
  if (Status status = WriteGraph(*built, out_path); !status.ok()) {
    return ErrorExit(status.error(), kExitFailed);
  }
  std::fputs(report.ToText().c_str(), stdout);
  std::printf("written: %s\n", out_path.c_str());
  return kExitOk;
}

}  // namespace dynslam::cli
