#include <catch2/catch.hpp>

#include "io/gnuplot.hpp"

using seismpm::gnuplot_quote;

TEST_CASE("gnuplot_quote doubles quotes and keeps text on one line", "[io][robustness]") {
  CHECK(gnuplot_quote("crest 'A'") == "'crest ''A'''");
  // A line break would end the quoted string's command and run what follows as gnuplot commands.
  const std::string q = gnuplot_quote("x\nsystem 'touch pwned'\r\t");
  CHECK(q.find('\n') == std::string::npos);
  CHECK(q.find('\r') == std::string::npos);
  CHECK(q == "'x system ''touch pwned''  '");
}
