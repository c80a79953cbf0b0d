// What the validator tests share: a valid baseline passes, and each violation alone makes
// Validate() name its field (test/core/validators_test.cpp, test/ros/options_validators_test.cpp).
#ifndef SWARM_TRANSPORT_TEST_VALIDATOR_FIXTURE_H_
#define SWARM_TRANSPORT_TEST_VALIDATOR_FIXTURE_H_

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace swarm_transport {
namespace validator_testing {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// One violation: what it spoils and the field name the error must contain.
template <typename Params>
struct Violation {
  std::string label;
  std::function<void(Params*)> spoil;
  std::string field;
};

// The baseline is valid; each violation alone makes Validate() name its field. A violation that
// does not fail shows that a rule is missing; one whose error names another field shows that
// the rules are checked out of order or the message names the wrong key.
template <typename Params>
void ExpectEachViolationNamed(const Params& baseline,
                              const std::vector<Violation<Params>>& violations) {
  ASSERT_EQ(baseline.Validate(), "") << "the baseline must be valid";
  for (const Violation<Params>& v : violations) {
    Params p = baseline;
    v.spoil(&p);
    const std::string error = p.Validate();
    EXPECT_FALSE(error.empty()) << v.label << " was accepted";
    EXPECT_NE(error.find(v.field), std::string::npos)
        << v.label << ": '" << error << "' does not name " << v.field;
  }
}

// A violation per value in `bad` of the member `m` named `field`.
template <typename Params, typename T>
void Add(std::vector<Violation<Params>>* out, const std::string& field, T Params::*m,
         std::vector<T> bad) {
  for (T value : bad) {
    out->push_back(
        {field + " = " + std::to_string(value), [m, value](Params* p) { p->*m = value; }, field});
  }
}

// The same for a number in a range: values just outside on both sides, NaN, infinity.
template <typename Params>
void AddRange(std::vector<Violation<Params>>* out, const std::string& field, double Params::*m,
              std::vector<double> bad) {
  Add<Params, double>(out, field, m, std::move(bad));
}

}  // namespace validator_testing
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_TEST_VALIDATOR_FIXTURE_H_
