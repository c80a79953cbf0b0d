#include "swarm_transport/core/metrics_query.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/metrics.h"

namespace swarm_transport {
namespace core {
namespace {

// Every remaining word of `in` as a double; false at the first word that is not one.
bool ReadNumbers(std::istringstream* in, std::vector<double>* out) {
  std::string word;
  while (*in >> word) {
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0') return false;
    out->push_back(v);
  }
  return true;
}

std::string RoundTrip(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", v);
  return buffer;
}

std::string Components(std::istringstream* in) {
  std::vector<double> numbers;
  if (!ReadNumbers(in, &numbers) || numbers.empty() || numbers.size() % 2 != 1) {
    return "error components: a local range and x y pairs expected";
  }
  std::vector<Vec2> positions;
  for (std::size_t i = 1; i + 1 < numbers.size(); i += 2) {
    positions.push_back({numbers[i], numbers[i + 1]});
  }
  const SwarmComponents swarms(positions, numbers[0]);
  std::string answer = std::to_string(swarms.SwarmCount());
  for (std::size_t label : swarms.labels()) answer += " " + std::to_string(label);
  return answer;
}

std::string Trimmed(std::istringstream* in) {
  std::vector<double> numbers;
  if (!ReadNumbers(in, &numbers) || numbers.size() < 2 || !(numbers[0] >= 0.0) ||
      numbers[0] != std::floor(numbers[0])) {
    return "error trimmed_mean: a count to drop at each end and at least one value expected";
  }
  const std::size_t drop = static_cast<std::size_t>(numbers[0]);
  std::vector<double> values(numbers.begin() + 1, numbers.end());
  if (2 * drop >= values.size()) return "error trimmed_mean: drops every value";
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() - 2 * drop;
  return RoundTrip(TrimmedMean(std::move(values), middle));
}

}  // namespace

std::string AnswerMetricsQuery(const std::string& line) {
  std::istringstream in(line);
  std::string verb;
  in >> verb;
  if (verb == "components") return Components(&in);
  if (verb == "trimmed_mean") return Trimmed(&in);
  return "error unknown request '" + verb + "' (components, trimmed_mean)";
}

}  // namespace core
}  // namespace swarm_transport
