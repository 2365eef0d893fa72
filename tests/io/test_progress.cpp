// The progress line: phase, time against the end, step, dt, speed, ETA; "at most" for runs that may end
// early (a gravity phase stops at equilibrium).
#include <catch2/catch.hpp>

#include <cstdio>

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
