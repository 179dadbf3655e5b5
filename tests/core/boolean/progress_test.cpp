// BooleanOptions::progress: phases in order, fractions non-decreasing, ending
// at "done" = 1, on the calling thread only.
#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

#include "ember/boolean.hpp"
#include "ember/error.hpp"
#include "ember/shapes.hpp"

namespace ember {
namespace {

struct Call {
  std::string phase;
  double fraction;
  std::thread::id thread;
};

std::vector<Call> record(const BooleanOptions& base) {
  std::vector<Call> calls;
  BooleanOptions options = base;
  options.progress = [&](std::string_view phase, double fraction) {
    calls.push_back({std::string(phase), fraction, std::this_thread::get_id()});
  };
  boolean({shapes::torus(1.0, 0.35, 48, 24), shapes::uv_sphere({0.9, 0, 0.2}, 0.6, 32, 16)}, Operation::Union, options);
  return calls;
}

TEST(Progress, PhasesInOrderOnTheCallingThread) {
  for (const bool detect : {true, false}) {
    BooleanOptions options;
    options.detect_solid = detect;
    const std::vector<Call> calls = record(options);
    ASSERT_GE(calls.size(), 4u);
    EXPECT_EQ(calls.front().phase, "prepare");
    EXPECT_EQ(calls.front().fraction, 0.0);
    EXPECT_EQ(calls.back().phase, "done");
    EXPECT_EQ(calls.back().fraction, 1.0);
    std::vector<std::string> phases;
    for (std::size_t i = 0; i < calls.size(); ++i) {
      EXPECT_EQ(calls[i].thread, std::this_thread::get_id());
      if (i) {
        EXPECT_GE(calls[i].fraction, calls[i - 1].fraction);
      }
      if (phases.empty() || phases.back() != calls[i].phase) phases.push_back(calls[i].phase);
    }
    const std::vector<std::string> expected =
        detect ? std::vector<std::string>{"prepare", "solid check", "solve", "export", "done"}
               : std::vector<std::string>{"prepare", "solve", "export", "done"};
    EXPECT_EQ(phases, expected);
  }
}

TEST(Progress, AnExceptionFromTheCallbackPropagates) {
  BooleanOptions options;
  options.progress = [](std::string_view phase, double) {
    if (phase == "solve") throw Error("cancelled by the caller");
  };
  EXPECT_THROW(boolean({shapes::torus(1.0, 0.35, 24, 12), shapes::uv_sphere({0.9, 0, 0.2}, 0.6, 16, 8)},
                       Operation::Union, options),
               Error);
}

}  // namespace
}  // namespace ember
