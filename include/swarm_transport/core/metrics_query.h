// A line-based text interface to the core's swarm metrics, for the Python tools (issue 10,
// item 5): they ask experiment_batch --metrics instead of re-implementing the core.
#ifndef SWARM_TRANSPORT_CORE_METRICS_QUERY_H_
#define SWARM_TRANSPORT_CORE_METRICS_QUERY_H_

#include <string>

namespace swarm_transport {
namespace core {

// Answers one request line (numbers in any strtod form; answers in round-trip precision):
//   components <local_range_m> <x0> <y0> <x1> <y1> ...
//     -> "<swarm count> <swarm of robot 0> <swarm of robot 1> ..." (SwarmComponents)
//   trimmed_mean <drop_each_end> <v0> <v1> ...
//     -> "<mean of the sorted values without `drop_each_end` at each end>" (TrimmedMean; the
//        values are summed in ascending order, so the answer does not depend on their order)
// Else "error <why>".
std::string AnswerMetricsQuery(const std::string& line);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_METRICS_QUERY_H_
