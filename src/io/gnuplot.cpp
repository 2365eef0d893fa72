#include "gnuplot.hpp"

#include <cstdio>
#include <cstdlib>

#include "atomic_file.hpp"
#include "core/error.hpp"

namespace seismpm {

namespace {
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
}  // namespace

std::string gnuplot_quote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    if (c == '\'')
      out += "''";
    else
      out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? ' ' : c;
  }
  return out + "'";
}

void require_gnuplot() {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw OutputError("cannot plot: gnuplot is not installed (apt-get install gnuplot-nox)");
}

void run_gnuplot(const std::string& script, const std::string& png) {
  require_gnuplot();
  const std::string script_path = png + ".gp", log = png + ".log";
  write_file_atomically(script_path, script);
  const int rc = std::system(("gnuplot " + shell_quote(script_path) + " 2>" + shell_quote(log)).c_str());
  std::remove(script_path.c_str());
  if (rc != 0) throw OutputError("gnuplot failed drawing " + png + " (see " + log + ")");
  std::remove(log.c_str());
  commit_file(png + ".tmp", png);
}

}  // namespace seismpm
