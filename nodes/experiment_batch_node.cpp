// Experiment runs in this process, one after the other, without a ROS master (issue 10, item 9):
//   experiment_batch --base-config config/swarm.yaml < job_paths
// reads one job.json path per line from stdin, runs it (swarm_transport::RunBatchJob: the
// run's files and result.json go where the job says) and answers one line per job on stdout,
// "ok <path>" or "error <path>: <why>", so that scripts/experiment can hand it the next job.
//   experiment_batch --metrics
// answers the core's swarm metrics one line per request line instead (core/metrics_query.h), for
// the Python tools (src/swarm_transport/core_metrics.py).
#include <iostream>
#include <string>

#include "swarm_transport/core/metrics_query.h"
#include "swarm_transport/ros/common/crash_trace.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/engine/batch_run.h"

int main(int argc, char** argv) {
  swarm_transport::InstallCrashTrace("experiment_batch");
  std::string base_path;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--base-config" && i + 1 < argc) {
      base_path = argv[++i];
    } else if (arg == "--metrics" && argc == 2) {
      std::string line;
      while (std::getline(std::cin, line)) {
        std::cout << swarm_transport::core::AnswerMetricsQuery(line) << std::endl;
      }
      return 0;
    } else {
      std::cerr << "usage: experiment_batch --base-config SWARM_YAML < job.json paths\n"
                   "       experiment_batch --metrics < requests\n";
      return 2;
    }
  }
  if (base_path.empty()) {
    std::cerr << "experiment_batch: --base-config is required (config/swarm.yaml)\n";
    return 2;
  }
  XmlRpc::XmlRpcValue base;
  std::string error;
  if (!swarm_transport::XmlRpcFromYamlFile(base_path, &base, &error)) {
    std::cerr << "experiment_batch: " << error << "\n";
    return 2;
  }
  std::string path;
  while (std::getline(std::cin, path)) {
    if (path.empty()) continue;
    swarm_transport::BatchJob job;
    error.clear();
    if (!swarm_transport::ReadBatchJob(path, &job, &error) ||
        !swarm_transport::RunBatchJob(job, base, &error)) {
      std::cout << "error " << path << ": " << error << std::endl;
      continue;
    }
    std::cout << "ok " << path << std::endl;
  }
  return 0;
}
