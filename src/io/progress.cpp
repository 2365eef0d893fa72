#include "progress.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>

namespace seismpm {

namespace {

std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  // An ETA from a first step that hardly moved the clock can be astronomical: no conversion of it to an
  // integer may overflow, and past 1000 hours the figure says nothing more anyway.
  if (seconds >= 1000.0 * 3600.0) return "> 1000 h";
  const long s = std::lround(seconds);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

// The width of the terminal `out` writes to, 0 when it cannot be told.
int terminal_width(std::FILE* out) {
  winsize size{};
  if (ioctl(fileno(out), TIOCGWINSZ, &size) != 0) return 0;
  return size.ws_col;
}

}  // namespace

std::string fit_width(const std::string& text, int width) {
  // A line wider than the terminal wraps, and "\r" then rewrites only its last row: the rows above stay
  // on the screen, one more at every update. One column is kept free for the cursor.
  if (width <= 1 || static_cast<int>(text.size()) < width) return text;
  return text.substr(0, static_cast<std::size_t>(width - 1));
}

Progress::Mode Progress::detect(std::FILE* out, bool quiet) {
  if (quiet) return Mode::Quiet;
  return isatty(fileno(out)) ? Mode::Terminal : Mode::Log;
}

void Progress::start(const std::string& label, double t_start, double t_end, std::size_t particles, long step,
                     bool open_end) {
  label_ = label;
  t_start_ = t_start;
  t_end_ = t_end;
  open_end_ = open_end;
  particles_ = particles;
  step_start_ = step;
  wall_start_ = last_print_ = std::chrono::steady_clock::now();
  printed_ = false;
}

std::string Progress::line(double t, long step, double dt, const std::string& extra) const {
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
  const double rate = wall > 0 ? particles_ * static_cast<double>(step - step_start_) / wall : 0.0;
  const double done = t_end_ > t_start_ ? (t - t_start_) / (t_end_ - t_start_) : 1.0;
  const double eta = done > 0 ? wall * (1.0 - done) / done : NAN;
  char buf[256];
  std::snprintf(buf, sizeof buf, "[%s] t = %.4g %s %.4g s  step %ld  dt %.3g s  %.3gM p-steps/s  ETA %s%s%s%s",
                label_.c_str(), t, open_end_ ? "/ at most" : "/", t_end_, step, dt, rate / 1e6, open_end_ ? "<= " : "",
                clock_text(eta).c_str(), extra.empty() ? "" : "  ", extra.c_str());
  return buf;
}

void Progress::update(double t, long step, double dt, const std::string& extra) {
  if (mode_ == Mode::Quiet) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_print_).count();
  if (since < (mode_ == Mode::Terminal ? 0.2 : 5.0)) return;
  last_print_ = now;
  if (mode_ == Mode::Terminal)
    std::fprintf(out_, "\r\033[K%s", fit_width(line(t, step, dt, extra), terminal_width(out_)).c_str());
  else
    std::fprintf(out_, "%s\n", line(t, step, dt, extra).c_str());
  std::fflush(out_);
  printed_ = true;
}

void Progress::finish(double t, long step, const std::string& how) {
  if (mode_ == Mode::Quiet) return;
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
  const double rate = wall > 0 ? particles_ * static_cast<double>(step - step_start_) / wall : 0.0;
  if (mode_ == Mode::Terminal && printed_) std::fprintf(out_, "\r\033[K");
  // Short runs from the console stay silent; anything that took a while says how it ended.
  if (printed_ || wall > 1.0 || how != "done")
    std::fprintf(out_, "[%s] %s at t = %.6g s, step %ld, %.1f s wall, %.3gM particle-steps/s\n", label_.c_str(),
                 how.c_str(), t, step, wall, rate / 1e6);
  std::fflush(out_);
}

}  // namespace seismpm
