#pragma once
// Progress of a long Boolean on stderr, for people watching a terminal:
//
//   ember: solve        [##########..........]  52%   3.1 s
//
// Nothing is drawn before `delay` has passed (short runs stay silent) and
// nothing at all when stderr is not a terminal (logs and pipes stay clean).
// The library reports phases through BooleanOptions::progress; a ticker
// thread redraws the line so the elapsed time moves during a long phase.
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "ember/boolean.hpp"

namespace ember::cli {

class ProgressDisplay {
 public:
  /// A display when `enabled` and stderr is a terminal, else nullptr. The
  /// delay is 2 s; EMBER_PROGRESS_DELAY_MS overrides it (for tests).
  static std::unique_ptr<ProgressDisplay> on_terminal(bool enabled);

  explicit ProgressDisplay(std::chrono::milliseconds delay);
  ~ProgressDisplay();  // stops the ticker and erases the line
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  /// The callback to put into BooleanOptions::progress; valid while *this lives.
  ProgressCallback callback();

 private:
  void update(std::string_view phase, double fraction);
  void draw_locked();  // with mutex_ held
  void tick(std::stop_token stop);

  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  const std::chrono::milliseconds delay_;
  std::mutex mutex_;
  std::condition_variable_any wake_;
  std::string phase_ = "prepare";
  double fraction_ = 0;
  bool drawn_ = false;
  std::jthread ticker_;  // last: started after, and stopped before, the state above
};

}  // namespace ember::cli
