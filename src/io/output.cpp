#include "output.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "atomic_file.hpp"
#include "core/error.hpp"

namespace seismpm {

namespace {
std::string numbered(const char* stem, int n) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%06d.vtu", stem, n);
  return buf;
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
std::string probes_csv_text(const std::vector<std::shared_ptr<Probe<Dim>>>& probes) {
  const auto fields = particle_fields(Dim);
  std::ostringstream os;
  os.precision(10);
  os << "time (s)";
  for (const auto& p : probes)
    for (Field f : fields) os << ',' << p->name() << '.' << field_name(f);
  os << '\n';
  // Rows at every time any probe sampled; a probe without a sample then leaves its cells empty.
  std::map<double, std::vector<std::size_t>> rows;  // time -> sample index per probe (npos: none)
  for (std::size_t k = 0; k < probes.size(); ++k)
    for (std::size_t s = 0; s < probes[k]->times().size(); ++s) {
      auto& row = rows[probes[k]->times()[s]];
      row.resize(probes.size(), std::string::npos);
      row[k] = s;
    }
  std::vector<std::vector<double>> series;  // probe-major, field-minor
  for (const auto& p : probes)
    for (Field f : fields) series.push_back(p->series(f));
  for (const auto& [t, row] : rows) {
    os << t;
    for (std::size_t k = 0; k < probes.size(); ++k)
      for (std::size_t f = 0; f < fields.size(); ++f) {
        os << ',';
        if (k < row.size() && row[k] != std::string::npos) os << series[k * fields.size() + f][row[k]];
      }
    os << '\n';
  }
  return os.str();
}

template <int Dim>
VtuMeta particle_meta(const Model<Dim>& model, const std::string& phase) {
  VtuMeta meta{model.time(), phase, {}, {}, model.phase_time()};
  for (int m = 0; m < model.material_count(); ++m) meta.material_names.push_back(model.material_name(m));
  for (const Body& b : model.bodies()) meta.body_names.push_back(b.name);
  return meta;
}

template <int Dim>
Output<Dim>::Output(OutputSettings settings) : settings_(std::move(settings)) {
  if (!(settings_.every > 0.0)) throw InputError("output: every must be > 0 (s)");
  if (settings_.arrays.empty()) throw InputError("output: no fields to write");
  ensure_directory(settings_.dir);
}

template <int Dim>
void Output<Dim>::write(const Model<Dim>& model, const std::vector<std::shared_ptr<Probe<Dim>>>& probes,
                        const std::string& phase) {
  const double t = model.time();
  const int n = static_cast<int>(files_.size());
  const auto& P = model.particles();
  const auto& bodies = model.bodies();
  const VtuMeta meta = particle_meta(model, phase);
  auto rigid = [&](std::size_t p) { return bodies[P.body[p]].rigid; };
  const std::string name = numbered("particles", n);
  write_particles_vtu(settings_.dir + "/" + name, P, settings_.arrays, meta, [&](std::size_t p) { return !rigid(p); });
  files_.emplace_back(t, name);
  write_file_atomically(settings_.dir + "/particles.pvd", pvd_text(files_));
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
  if (!probes.empty()) write_file_atomically(settings_.dir + "/probes.csv", probes_csv_text(probes));
}

template <int Dim>
void Output<Dim>::write_reactions(const Model<Dim>& model, const std::string& phase) {
  static const char* axis[] = {"x", "y", "z"};
  const auto& bodies = model.bodies();
  const double t = model.time();
  std::ostringstream os;
  os.precision(10);
  if (reactions_.empty()) {
    os << "time (s),phase";
    for (const auto& b : bodies)
      if (b.rigid)
        for (int d = 0; d < Dim; ++d) os << ',' << b.name << ".f" << axis[d] << " (N" << (Dim == 2 ? "/m" : "") << ")";
    os << '\n';
    last_impulse_.assign(bodies.size(), Vec<Dim>::Zero());
  }
  last_impulse_.resize(bodies.size(), Vec<Dim>::Zero());
  os << t << ',' << phase;
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
  reactions_ += os.str();
  last_time_ = t;
  write_file_atomically(settings_.dir + "/reactions.csv", reactions_);
}

template std::string probes_csv_text<2>(const std::vector<std::shared_ptr<Probe<2>>>&);
template std::string probes_csv_text<3>(const std::vector<std::shared_ptr<Probe<3>>>&);
template VtuMeta particle_meta<2>(const Model<2>&, const std::string&);
template VtuMeta particle_meta<3>(const Model<3>&, const std::string&);
template class Output<2>;
template class Output<3>;

}  // namespace seismpm
