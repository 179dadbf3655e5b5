#include "cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace ember::cli {

std::unique_ptr<ProgressDisplay> ProgressDisplay::on_terminal(bool enabled) {
  if (!enabled || !::isatty(STDERR_FILENO)) return nullptr;
  std::chrono::milliseconds delay{2000};
  if (const char* env = std::getenv("EMBER_PROGRESS_DELAY_MS"); env && *env)
    delay = std::chrono::milliseconds(std::max(0L, std::strtol(env, nullptr, 10)));
  return std::make_unique<ProgressDisplay>(delay);
}

ProgressDisplay::ProgressDisplay(std::chrono::milliseconds delay)
    : delay_(delay), ticker_([this](std::stop_token stop) { tick(stop); }) {}

ProgressDisplay::~ProgressDisplay() {
  ticker_.request_stop();
  ticker_.join();
  if (drawn_) {
    std::fputs("\r\033[K", stderr);  // erase the bar so later messages start on a clean line
    std::fflush(stderr);
  }
}

ProgressCallback ProgressDisplay::callback() {
  return [this](std::string_view phase, double fraction) { update(phase, fraction); };
}

void ProgressDisplay::update(std::string_view phase, double fraction) {
  // The library calls from one thread, but the ticker draws too: lock.
  const std::lock_guard lock(mutex_);
  phase_.assign(phase);
  fraction_ = std::clamp(fraction, 0.0, 1.0);
  if (std::chrono::steady_clock::now() - start_ >= delay_) draw_locked();
}

void ProgressDisplay::draw_locked() {
  constexpr int kWidth = 20;
  const int filled = static_cast<int>(fraction_ * kWidth + 0.5);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(kWidth - filled), '.');
  std::fprintf(stderr, "\r\033[Kember: %-12s [%s] %3d%% %6.1f s", phase_.c_str(), bar.c_str(),
               static_cast<int>(fraction_ * 100 + 0.5), seconds);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressDisplay::tick(std::stop_token stop) {
  // Nobody notifies wake_: the waits end by timeout or by the stop request.
  std::unique_lock lock(mutex_);
  wake_.wait_until(lock, stop, start_ + delay_, [] { return false; });
  while (!stop.stop_requested()) {
    draw_locked();
    wake_.wait_for(lock, stop, std::chrono::milliseconds(250), [] { return false; });
  }
}

}  // namespace ember::cli
