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

std::string svg_path(const std::string& png) {
  const std::string ext = ".png";
  if (png.size() > ext.size() && png.compare(png.size() - ext.size(), ext.size(), ext) == 0)
    return png.substr(0, png.size() - ext.size()) + ".svg";
  return png + ".svg";
}

std::string report_style() {
  return "set datafile separator ','\n"
         "set grid\n"
         "set key outside below center horizontal Left reverse spacing 1.2 width 2\n"
         "set autoscale xfix\n"
         "set offsets graph 0, graph 0, graph 0.08, graph 0.08\n";
}

std::string picture_script(const std::string& body, const std::string& png) {
  return "set terminal pngcairo size 960,540 noenhanced font 'sans,11'\n"
         "set output " +
         gnuplot_quote(png + ".tmp") + "\n" + report_style() + body +
         "\n"
         "set terminal svg size 960,540 noenhanced font 'sans,11' background rgb 'white'\n"
         "set output " +
         gnuplot_quote(svg_path(png) + ".tmp") +
         "\n"
         "replot\n"
         "unset output\n";
}

void require_gnuplot() {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw OutputError("cannot plot: gnuplot is not installed (apt-get install gnuplot-nox)");
}

void run_gnuplot(const std::string& body, const std::string& png) {
  require_gnuplot();
  const std::string script_path = png + ".gp", log = png + ".log", svg = svg_path(png);
  write_file_atomically(script_path, picture_script(body, png));
  const int rc = std::system(("gnuplot " + shell_quote(script_path) + " 2>" + shell_quote(log)).c_str());
  std::remove(script_path.c_str());
  if (rc != 0) {
    std::remove((png + ".tmp").c_str());
    std::remove((svg + ".tmp").c_str());
    throw OutputError("gnuplot failed drawing " + png + " (see " + log + ")");
  }
  std::remove(log.c_str());
  commit_file(png + ".tmp", png);
  commit_file(svg + ".tmp", svg);
}

}  // namespace seismpm
