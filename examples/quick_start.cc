// README's C++ quick start: every formulation of one front end, solved and scored.
#include <cstdio>

#include "dynslam/compare.h"
#include "dynslam/graph_io.h"

int main(int argc, char** argv) {  // quick_start FRONTEND.g2o GT.txt
  if (argc != 3) return 2;
  dynslam::Expected<dynslam::Graph> front_end = dynslam::ReadGraph(argv[1]);
  dynslam::Expected<dynslam::GroundTruth> gt = dynslam::ReadGroundTruth(argv[2]);
  if (!front_end.ok() || !gt.ok()) return 2;  // .error().ToString(): file:line: problem
  dynslam::CompareOptions options;             // all five formulations, the default solver
  options.solver.threads = 2;
  dynslam::Expected<dynslam::CompareRun> run = CompareFormulations(*front_end, &*gt, options);
  if (!run.ok()) return 1;
  for (const dynslam::CompareRow& row : run->rows) {
    std::printf("%-4s %3d steps, object motion error %.3f deg\n",
                dynslam::FormulationName(row.formulation), row.report.steps,
                row.metrics->object_motion.mean_rot_deg);
  }
}
