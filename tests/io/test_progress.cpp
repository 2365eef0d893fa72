// The progress line: phase, time against the end, step, dt, speed, ETA; "at most" for runs that may end
// early (a gravity phase stops at equilibrium).
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <thread>

#include "io/progress.hpp"

using seismpm::Progress;

TEST_CASE("the progress line names the phase, the time against the end and the ETA", "[io][progress]") {
  Progress p(stderr, Progress::Mode::Quiet);
  SECTION("a run to a fixed end") {
    p.start("dynamic", 0.0, 14.0, 1000, 0);
    const std::string text = p.line(3.5, 100, 3.1e-5, "");
    CAPTURE(text);
    CHECK(text.rfind("[dynamic] t = 3.5 / 14 s  step 100  dt 3.1e-05 s", 0) == 0);
    CHECK(text.find("ETA ") != std::string::npos);
    CHECK(text.find("at most") == std::string::npos);
  }
  SECTION("a run that may end early says 'at most'") {
    p.start("gravity", 0.0, 5.0, 1000, 0, true);
    const std::string text = p.line(0.04, 600, 6.3e-5, "unbalanced 2.4e-01");
    CAPTURE(text);
    CHECK(text.rfind("[gravity] t = 0.04 / at most 5 s", 0) == 0);
    CHECK(text.find("ETA <= ") != std::string::npos);
    CHECK(text.find("  unbalanced 2.4e-01") != std::string::npos);
  }
}

TEST_CASE("an ETA too large for a clock reads as such, never an overflow", "[io][progress][robustness]") {
  Progress p(stderr, Progress::Mode::Quiet);
  // 1e-300 s of 1 s done after a measurable wall time: the ETA is about 1e300 s, past any integer type.
  p.start("dynamic", 0.0, 1.0, 1000, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  const std::string text = p.line(1e-300, 1, 1e-300, "");
  CAPTURE(text);
  CHECK(text.find("ETA > 1000 h") != std::string::npos);
}

TEST_CASE("the progress line fits the terminal's width", "[io][progress]") {
  const std::string text(120, 'x');
  CHECK(seismpm::fit_width(text, 80).size() == 79);  // a column left for the cursor: no wrap
  CHECK(seismpm::fit_width(text, 0) == text);        // width unknown
  CHECK(seismpm::fit_width("short", 80) == "short");
}
