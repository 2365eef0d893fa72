#include "csv_plot.hpp"

#include <cstdio>
#include <sstream>

#include "atomic_file.hpp"
#include "core/error.hpp"
#include "csv_table.hpp"
#include "gnuplot.hpp"
#include "text_lines.hpp"

namespace seismpm {

CsvHeader::CsvHeader(const std::string& csv) : csv_(csv) {
  if (std::FILE* f = std::fopen(csv.c_str(), "rb"))
    std::fclose(f);
  else
    throw InputError("cannot plot: " + csv + " cannot be opened");
  TextLines in(csv);
  while (in.next(header_) && (header_.empty() || header_[0] == '#')) {
  }  // '#' lines are comments, for gnuplot too
  line_ = in.number();
  try {
    columns_ = split_csv_fields(header_);
  } catch (const InputError& e) {
    throw InputError(in.where() + e.what());
  }
}

std::size_t CsvHeader::column(const std::string& name) const {
  for (std::size_t c = 0; c < columns_.size(); ++c)
    if (columns_[c] == name) return c + 1;  // gnuplot counts from 1
  throw InputError(csv_ + ":" + std::to_string(line_) + ": no column '" + printable(name) +
                   "' (the header is: " + printable(header_, 200) + ")");
}

std::string csv_plot_body(const CsvPlot& p) {
  const CsvHeader header(p.csv);
  auto column = [&](const std::string& name) { return header.column(name); };
  const std::size_t xc = column(p.x);
  if (p.y.empty()) throw InputError("cannot plot: no y columns given");
  const std::string data = gnuplot_quote(p.csv) + " every ::1 using " + std::to_string(xc) + ':';
  std::ostringstream plot;
  if (!p.color.empty()) {
    // A picture of the ground, to scale: a thin equal margin on every side instead of the curves' one.
    plot << "set key off\nset size ratio -1\nset autoscale yfix\nset offsets graph 0.02, graph 0.02, graph 0.02, graph "
            "0.02\nset cblabel "
         << gnuplot_quote(p.color) << "\nset palette rgb 33,13,10\nplot " << data << column(p.y.front()) << ':'
         << column(p.color) << " with points pt 7 ps 0.35 palette notitle";
    for (const auto& r : p.reference)
      plot << ", \\\n     " << data << column(r) << " with lines lw 2 dt 2 lc rgb 'black' notitle";
  } else {
    const bool one_curve = p.y.size() + p.reference.size() == 1;  // its name is on the y axis: no key
    if (one_curve) plot << "set key off\n";
    auto title = [&](const std::string& name) {
      return one_curve ? std::string("notitle") : "title " + gnuplot_quote(name);
    };
    plot << "plot ";
    for (std::size_t k = 0; k < p.y.size(); ++k)
      plot << (k ? ", \\\n     " : "") << data << column(p.y[k]) << " with lines lw 2 " << title(p.y[k]);
    for (const auto& r : p.reference)
      plot << ", \\\n     " << data << column(r) << " with lines lw 2 dt 2 lc rgb 'black' " << title(r);
  }
  std::ostringstream body;
  body << "set title " << gnuplot_quote(p.title) << "\n"
       << "set xlabel " << gnuplot_quote(p.xlabel.empty() ? p.x : p.xlabel) << "\n"
       << "set ylabel " << gnuplot_quote(p.ylabel.empty() ? p.y.front() : p.ylabel) << "\n"
       << (p.log_x ? "set logscale x\n" : "") << plot.str() << "\n";
  return body.str();
}

void plot_csv(const CsvPlot& p) {
  const std::string body = csv_plot_body(p);
  run_gnuplot(body, p.png);
}

}  // namespace seismpm
