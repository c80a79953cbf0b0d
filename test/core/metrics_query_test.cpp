// The text interface of the core's swarm metrics (experiment_batch --metrics): the answers are
// SwarmComponents' and TrimmedMean's, in round-trip precision, and bad requests say why.
#include "swarm_transport/core/metrics_query.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace swarm_transport {
namespace core {
namespace {

TEST(MetricsQueryTest, ComponentsCountAndLabelEachSwarm) {
  // 0.9 apart chain; 1.01 from the nearest is a swarm of its own; exactly the range links.
  EXPECT_EQ(AnswerMetricsQuery("components 1 0 0 0.9 0 1.8 0 2.81 0"), "2 0 0 0 1");
  EXPECT_EQ(AnswerMetricsQuery("components 1.0 0 0 1.0 0"), "1 0 0");
  EXPECT_EQ(AnswerMetricsQuery("components 1.0"), "0");
  EXPECT_EQ(AnswerMetricsQuery("components 1 5 5 0 0 5 5"), "2 0 1 0");
}

TEST(MetricsQueryTest, TrimmedMeanDropsAtEachEndOfTheSortedValues) {
  // Ten values, two dropped at each end: the middle six (thesis 7.2).
  EXPECT_EQ(AnswerMetricsQuery("trimmed_mean 2 10 1 9 2 8 3 7 4 6 5"), "5.5");
  EXPECT_EQ(AnswerMetricsQuery("trimmed_mean 0 3 1 2"), "2");
  // Round trip: the answer parses back to the very double.
  const std::string third = AnswerMetricsQuery("trimmed_mean 0 0.1 0.2");
  EXPECT_EQ(std::strtod(third.c_str(), nullptr), (0.1 + 0.2) / 2.0);
}

TEST(MetricsQueryTest, BadRequestsSayWhy) {
  EXPECT_EQ(AnswerMetricsQuery("median 1 2").rfind("error unknown request 'median'", 0), 0u);
  EXPECT_EQ(AnswerMetricsQuery("components 1 0").rfind("error components", 0), 0u);
  EXPECT_EQ(AnswerMetricsQuery("components 1 0 x").rfind("error components", 0), 0u);
  EXPECT_EQ(AnswerMetricsQuery("trimmed_mean 1 5 6").rfind("error trimmed_mean", 0), 0u);
  EXPECT_EQ(AnswerMetricsQuery("trimmed_mean -1 5").rfind("error trimmed_mean", 0), 0u);
  EXPECT_EQ(AnswerMetricsQuery("trimmed_mean 2").rfind("error trimmed_mean", 0), 0u);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
