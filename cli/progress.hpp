// cli/progress.hpp — the progress bar long commands draw on stderr: redrawn in place on a terminal,
// a line per phase (and per tenth of counted work, with the time left) otherwise.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>

namespace nut::cli {

class ProgressBar {
 public:
  // `command` and `label` start every line: "convert: street: ...".
  ProgressBar(bool enabled, std::string command, std::string label);
  ~ProgressBar() { finish(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // A phase of unknown length, `fraction` of it done.
  void update(std::string_view phase, double fraction);
  // `done` of `total` items of a phase, with the time left estimated from the rate so far.
  void updateCount(std::string_view phase, std::size_t done, std::size_t total);
  // Ends the line the bar was drawn on.
  void finish();

 private:
  void draw(const std::string& suffix);

  bool enabled_, tty_;
  std::string command_, label_, phase_;
  int percent_ = -1;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point phaseStart_;
};

}  // namespace nut::cli
