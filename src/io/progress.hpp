// Progress of a long run: on a terminal one line rewritten in place (phase, t / t_end, step, dt,
// particle-steps per second, ETA) clipped to the terminal's width; otherwise a plain log line every few seconds; or
// nothing.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace seismpm {

// `text` cut to fit a terminal `width` columns wide (the progress line holds only ASCII); as it is when
// the width is unknown (0).
std::string fit_width(const std::string& text, int width);

class Progress {
 public:
  enum class Mode { Terminal, Log, Quiet };

  // Terminal when `out` is a terminal, Log otherwise; Quiet when asked.
  static Mode detect(std::FILE* out, bool quiet);

  Progress(std::FILE* out, Mode mode) : out_(out), mode_(mode) {}
  // open_end: the run may end before t_end (a gravity phase ends at equilibrium): the line says
  // "at most" for the end time and the ETA.
  void start(const std::string& label, double t_start, double t_end, std::size_t particles, long step,
             bool open_end = false);
  void update(double t, long step, double dt, const std::string& extra = "");
  void finish(double t, long step, const std::string& how);

  // The text of the progress line at time t.
  std::string line(double t, long step, double dt, const std::string& extra) const;

 private:
  std::FILE* out_;
  Mode mode_;
  std::string label_;
  double t_start_ = 0, t_end_ = 0;
  bool open_end_ = false;
  std::size_t particles_ = 0;
  long step_start_ = 0;
  std::chrono::steady_clock::time_point wall_start_, last_print_;
  bool printed_ = false;
};

}  // namespace seismpm
