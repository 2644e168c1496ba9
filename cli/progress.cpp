// The progress bar of long commands (cli/progress.hpp).
#include "progress.hpp"

#include <cstdio>
#include <unistd.h>

namespace nut::cli {

ProgressBar::ProgressBar(bool enabled, std::string command, std::string label)
    : enabled_(enabled), tty_(isatty(fileno(stderr)) != 0), command_(std::move(command)), label_(std::move(label)) {}

void ProgressBar::update(std::string_view phase, double fraction) {
  if (!enabled_) return;
  const int percent = static_cast<int>(100 * fraction);
  if (phase == phase_ && (percent == percent_ || !tty_)) return;
  if (phase != phase_ && !tty_)
    std::fprintf(stderr, "%s: %s: %.*s\n", command_.c_str(), label_.c_str(), static_cast<int>(phase.size()),
                 phase.data());
  phase_ = std::string(phase);
  percent_ = percent;
  draw("");
}

void ProgressBar::updateCount(std::string_view phase, std::size_t done, std::size_t total) {
  if (!enabled_ || total == 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (phase != phase_) {
    phase_ = std::string(phase);
    phaseStart_ = now;
    percent_ = -1;
  }
  const int percent = static_cast<int>(100 * done / total);
  // Off a terminal, a line per tenth: a log shows progress without a line per item.
  if (percent == percent_ || (!tty_ && percent / 10 == percent_ / 10 && percent_ >= 0)) return;
  percent_ = percent;
  const double elapsed = std::chrono::duration<double>(now - phaseStart_).count();
  char suffix[96];
  if (done == 0 || done == total)
    std::snprintf(suffix, sizeof suffix, " %zu/%zu, %.0f s", done, total, elapsed);
  else
    std::snprintf(suffix, sizeof suffix, " %zu/%zu, %.0f s left", done, total,
                  elapsed * static_cast<double>(total - done) / static_cast<double>(done));
  if (!tty_) {
    std::fprintf(stderr, "%s: %s: %s %3d%%%s\n", command_.c_str(), label_.c_str(), phase_.c_str(), percent, suffix);
    return;
  }
  draw(suffix);
}

void ProgressBar::draw(const std::string& suffix) {
  if (!tty_) return;
  constexpr int kWidth = 30;
  const int filled = kWidth * percent_ / 100;
  std::fprintf(stderr, "\r%s %-9s [%s%s] %3d%%%s   ", label_.c_str(), phase_.c_str(),
               std::string(static_cast<std::size_t>(filled), '#').c_str(),
               std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), percent_, suffix.c_str());
  drawn_ = true;
}

void ProgressBar::finish() {
  if (drawn_) std::fputc('\n', stderr);
  drawn_ = false;
}

}  // namespace nut::cli
