#include "output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "atomic_file.hpp"
#include "core/error.hpp"
#include "csv_table.hpp"
#include "paraview_script.hpp"
#include "phases_file.hpp"

namespace seismpm {

namespace {
// Where the last row of `rows` (whole lines) starts.
std::size_t last_row_start(const std::string& rows) {
  if (rows.size() < 2) return 0;
  const auto nl = rows.rfind('\n', rows.size() - 2);
  return nl == std::string::npos ? 0 : nl + 1;
}

std::string numbered(const char* stem, int n) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%06d.vtu", stem, n);
  return buf;
}

// Checks the settings and creates the directory, before the lock is taken in it.
const std::string& checked_directory(const OutputSettings& s) {
  if (!(s.every > 0.0)) throw InputError("output: every must be > 0 (s)");
  if (s.arrays.empty()) throw InputError("output: no fields to write");
  ensure_directory(s.dir);
  return s.dir;
}

// The script's settings from the model: the discs' radius is half the particle spacing (the largest
// of the bodies', so that every body looks filled).
template <int Dim>
ParaViewScriptSettings script_settings(const Model<Dim>& model) {
  ParaViewScriptSettings s{Dim, 0.0, 0.0};
  const auto& P = model.particles();
  const double h = model.settings().cell;
  for (std::size_t p = 0; p < P.size(); ++p) {
    double& r = model.bodies()[P.body[p]].rigid ? s.rigid_radius : s.particle_radius;
    r = std::max(r, P.half_width[p] * h);
  }
  for (double* r : {&s.particle_radius, &s.rigid_radius})
    if (!(*r > 0.0)) *r = 0.25 * h;  // no particle: the spacing of 2 per cell
  return s;
}
}  // namespace

std::string pvd_text(const std::vector<std::pair<double, std::string>>& files) {
  std::ostringstream os;
  os.precision(12);
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
     << "  <Collection>\n";
  for (const auto& [t, file] : files)
    os << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
  os << "  </Collection>\n</VTKFile>\n";
  return os.str();
}

template <int Dim>
std::string probes_csv_header(const std::vector<std::shared_ptr<Probe<Dim>>>& probes) {
  const auto fields = particle_fields(Dim);
  std::string header = "time (s),phase,phase_time (s)";
  for (const auto& p : probes) {
    for (Field f : fields) header += ',' + csv_field(std::string(p->name()) + '.' + std::string(field_name(f)));
    if (p->relative_to().active())
      for (const auto& r : relative_field_names(Dim)) header += ',' + csv_field(std::string(p->name()) + '.' + r);
  }
  return header + '\n';
}

template <int Dim>
std::string probes_csv_rows(const std::vector<std::shared_ptr<Probe<Dim>>>& probes,
                            const std::vector<std::size_t>& first) {
  const auto fields = particle_fields(Dim);
  std::ostringstream os;
  os.precision(10);
  // Rows at every time any probe sampled; a probe without a sample then leaves its cells empty.
  std::map<double, std::vector<std::size_t>> rows;  // time -> sample index per probe (npos: none)
  for (std::size_t k = 0; k < probes.size(); ++k)
    for (std::size_t s = first[k]; s < probes[k]->times().size(); ++s) {
      auto& row = rows[probes[k]->times()[s]];
      row.resize(probes.size(), std::string::npos);
      row[k] = s;
    }
  if (rows.empty()) return {};
  std::vector<std::vector<std::vector<double>>> series(probes.size());  // per probe, its columns
  for (std::size_t k = 0; k < probes.size(); ++k) {
    for (Field f : fields) series[k].push_back(probes[k]->series(f));
    if (probes[k]->relative_to().active())
      for (int d = 0; d < Dim; ++d) series[k].push_back(probes[k]->relative_series(d));
  }
  for (const auto& [t, row] : rows) {
    os << t;
    // The phase and its time from the first probe sampled then (all probes sampled at one time share them).
    std::size_t first_probe = 0;
    while (first_probe < row.size() && row[first_probe] == std::string::npos) ++first_probe;
    const Probe<Dim>& sampled = *probes[first_probe];
    const double phase_time = sampled.phase_time(row[first_probe]);
    os << ',' << csv_field(sampled.phase(row[first_probe])) << ',';
    if (phase_time == phase_time) os << phase_time;  // empty when not known
    for (std::size_t k = 0; k < probes.size(); ++k)
      for (const auto& column : series[k]) {
        os << ',';
        if (k < row.size() && row[k] != std::string::npos) os << column[row[k]];
      }
    os << '\n';
  }
  return os.str();
}

template <int Dim>
std::string probes_csv_text(const std::vector<std::shared_ptr<Probe<Dim>>>& probes) {
  return probes_csv_header(probes) + probes_csv_rows(probes, std::vector<std::size_t>(probes.size(), 0));
}

template <int Dim>
VtuMeta particle_meta(const Model<Dim>& model, const std::string& phase) {
  VtuMeta meta{model.time(), phase, {}, {}, model.phase_time()};
  for (int m = 0; m < model.material_count(); ++m) meta.material_names.push_back(model.material_name(m));
  for (const Body& b : model.bodies()) meta.body_names.push_back(b.name);
  return meta;
}

template <int Dim>
Output<Dim>::Output(OutputSettings settings) : settings_(std::move(settings)), lock_(checked_directory(settings_)) {}

template <int Dim>
void Output<Dim>::write(const Model<Dim>& model, const std::vector<std::shared_ptr<Probe<Dim>>>& probes,
                        const std::string& phase) {
  const double t = model.time();
  const int n = static_cast<int>(files_.size());
  const auto& P = model.particles();
  const auto& bodies = model.bodies();
  const VtuMeta meta = particle_meta(model, phase);
  note_phase(phase, t - model.phase_time());
  auto rigid = [&](std::size_t p) { return bodies[P.body[p]].rigid; };
  const std::string name = numbered("particles", n);
  write_particles_vtu(settings_.dir + "/" + name, P, settings_.arrays, meta, [&](std::size_t p) { return !rigid(p); });
  files_.emplace_back(t, name);
  write_file_atomically(settings_.dir + "/particles.pvd", pvd_text(files_));
  if (n == 0)  // the script that opens the run: it finds rigid.pvd and grid.pvd when it runs
    write_file_atomically(settings_.dir + "/" + kParaViewScript, paraview_script_text(script_settings(model)));
  if (std::any_of(bodies.begin(), bodies.end(), [](const Body& b) { return b.rigid; })) {
    const std::string rigid_name = numbered("rigid", n);
    write_particles_vtu(settings_.dir + "/" + rigid_name, P, settings_.arrays, meta, rigid);
    rigid_files_.emplace_back(t, rigid_name);
    write_file_atomically(settings_.dir + "/rigid.pvd", pvd_text(rigid_files_));
    write_reactions(model, phase);
  }
  if (settings_.grid) {
    const std::string grid_name = numbered("grid", n);
    write_grid_vtu(settings_.dir + "/" + grid_name, model.grid(), model.mass_threshold(),
                   VtuMeta{t, phase, {}, {}, model.phase_time()});
    grid_files_.emplace_back(t, grid_name);
    write_file_atomically(settings_.dir + "/grid.pvd", pvd_text(grid_files_));
  }
  if (!probes.empty()) write_probes(probes);
}

template <int Dim>
void Output<Dim>::note_phase(const std::string& phase, double start) {
  if (phase == phase_on_file_ && same_start(start, phase_start_on_file_)) return;
  record_phase(settings_.dir, phase, start);
  phase_on_file_ = phase;
  phase_start_on_file_ = start;
}

template <int Dim>
void Output<Dim>::write_probes(const std::vector<std::shared_ptr<Probe<Dim>>>& probes) {
  if (probes.empty()) return;
  if (probe_samples_written_.size() != probes.size() || probes_csv_header(probes) != probes_header_)
    return write_probes_whole(probes);  // the first write, or probes added since: other columns
  std::vector<std::size_t> first = probe_samples_written_;
  double earliest = std::numeric_limits<double>::infinity(), latest = earliest;
  for (std::size_t k = 0; k < probes.size(); ++k)
    if (first[k] < probes[k]->samples()) {
      earliest = std::min(earliest, probes[k]->times()[first[k]]);
      latest = std::isinf(latest) ? probes[k]->times().back() : std::max(latest, probes[k]->times().back());
    }
  if (std::isinf(earliest)) return;                                         // nothing new
  if (earliest < probes_last_row_time_) return write_probes_whole(probes);  // not in time order: rewrite
  std::uint64_t offset = probes_bytes_;
  if (earliest == probes_last_row_time_) {
    // A probe sampled at the last row's time after it was written (at a run's end): that row again.
    offset = probes_last_row_;
    for (std::size_t k = 0; k < probes.size(); ++k)
      if (first[k] > 0 && probes[k]->times()[first[k] - 1] == probes_last_row_time_) --first[k];
  }
  const std::string rows = probes_csv_rows(probes, first);
  if (!replace_file_tail(settings_.dir + "/probes.csv", probes_bytes_, offset, rows))
    return write_probes_whole(probes);  // the file was changed or removed meanwhile
  probes_last_row_ = offset + last_row_start(rows);
  probes_bytes_ = offset + rows.size();
  probes_last_row_time_ = std::max(latest, probes_last_row_time_);
  for (std::size_t k = 0; k < probes.size(); ++k) probe_samples_written_[k] = probes[k]->samples();
}

template <int Dim>
void Output<Dim>::write_probes_whole(const std::vector<std::shared_ptr<Probe<Dim>>>& probes) {
  const std::string header = probes_csv_header(probes);
  const std::string rows = probes_csv_rows(probes, std::vector<std::size_t>(probes.size(), 0));
  write_file_atomically(settings_.dir + "/probes.csv", header + rows);
  probes_header_ = header;
  probes_bytes_ = header.size() + rows.size();
  probes_last_row_ = header.size() + last_row_start(rows);
  probes_last_row_time_ = std::numeric_limits<double>::quiet_NaN();
  probe_samples_written_.clear();
  for (const auto& p : probes) {
    probe_samples_written_.push_back(p->samples());
    if (p->samples() > 0 && !(p->times().back() <= probes_last_row_time_)) probes_last_row_time_ = p->times().back();
  }
}

template <int Dim>
void Output<Dim>::rewrite_tables(const std::vector<std::shared_ptr<Probe<Dim>>>& probes) {
  if (!probes.empty()) write_probes_whole(probes);
  const std::string reactions = settings_.dir + "/reactions.csv";
  if (!reactions_.empty())
    write_file_atomically(reactions, reactions_);
  else
    std::remove(reactions.c_str());  // no row before the checkpoint
}

template <int Dim>
void Output<Dim>::write_reactions(const Model<Dim>& model, const std::string& phase) {
  static const char* axis[] = {"x", "y", "z"};
  const auto& bodies = model.bodies();
  const double t = model.time();
  std::ostringstream os;
  os.precision(10);
  std::string header = "time (s),phase";
  std::size_t rigid = 0;
  for (const auto& b : bodies)
    if (b.rigid) {
      ++rigid;
      for (int d = 0; d < Dim; ++d)
        header += ',' + csv_field(b.name + ".f" + axis[d] + " (N" + (Dim == 2 ? "/m" : "") + ")");
    }
  header += '\n';
  bool whole = reactions_.empty();
  if (whole) {
    os << header;
    last_impulse_.assign(bodies.size(), Vec<Dim>::Zero());
  } else if (const std::size_t on_file =
                 (split_csv_fields(reactions_.substr(0, reactions_.find('\n'))).size() - 2) / Dim;
             rigid > on_file) {
    // A rigid body added since the header was written (m:rigid between runs) comes after the others
    // (bodies keep their order): the header gains its columns and the rows before get empty cells
    // there, so that every row keeps the header's columns. The file is then written whole once.
    const std::string empty_cells((rigid - on_file) * Dim, ',');
    std::string widened = header;
    for (std::size_t at = reactions_.find('\n') + 1; at < reactions_.size();) {
      const std::size_t end = reactions_.find('\n', at);
      widened += reactions_.substr(at, end - at) + empty_cells + '\n';
      at = end + 1;
    }
    reactions_ = std::move(widened);
    whole = true;
  }
  last_impulse_.resize(bodies.size(), Vec<Dim>::Zero());
  os << t << ',' << csv_field(phase);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!bodies[b].rigid) continue;
    const auto& motion = model.rigid_motion(static_cast<int>(b));
    // The mean over the interval since the last row; the last step's force when no time has passed.
    const bool interval = files_.size() > 1 && t > last_time_;
    const Vec<Dim> f = interval ? Vec<Dim>((motion.impulse - last_impulse_[b]) / (t - last_time_)) : motion.force;
    for (int d = 0; d < Dim; ++d) os << ',' << f[d];
    last_impulse_[b] = motion.impulse;
  }
  os << '\n';
  const std::string text = os.str();
  const std::string path = settings_.dir + "/reactions.csv";
  // The first row comes with the header, written whole; the next ones are appended, one write each.
  // Appending needs the file as this run left it: after a widened header, or when it was changed or
  // removed meanwhile, the file is written whole.
  const std::uint64_t on_disk = whole ? 0 : reactions_.size();
  if (whole || !replace_file_tail(path, on_disk, on_disk, text)) write_file_atomically(path, reactions_ + text);
  reactions_ += text;
  last_time_ = t;
}

template std::string probes_csv_header<2>(const std::vector<std::shared_ptr<Probe<2>>>&);
template std::string probes_csv_header<3>(const std::vector<std::shared_ptr<Probe<3>>>&);
template std::string probes_csv_rows<2>(const std::vector<std::shared_ptr<Probe<2>>>&, const std::vector<std::size_t>&);
template std::string probes_csv_rows<3>(const std::vector<std::shared_ptr<Probe<3>>>&, const std::vector<std::size_t>&);
template std::string probes_csv_text<2>(const std::vector<std::shared_ptr<Probe<2>>>&);
template std::string probes_csv_text<3>(const std::vector<std::shared_ptr<Probe<3>>>&);
template VtuMeta particle_meta<2>(const Model<2>&, const std::string&);
template VtuMeta particle_meta<3>(const Model<3>&, const std::string&);
template class Output<2>;
template class Output<3>;

}  // namespace seismpm
