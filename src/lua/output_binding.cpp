// A model's files: m:output (ParaView files and probes.csv as a run goes), m:write, m:plot.
#include <algorithm>

#include "api_docs.hpp"
#include "binding.hpp"
#include "core/particle_fields.hpp"
#include "io/atomic_file.hpp"
#include "io/probe_plot.hpp"
#include "objects.hpp"
#include "sandbox.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

const OutputSettings kOutput;  // the writer's defaults

const Key kOutputKeys[] = {
    arg::string("dir", "the directory, used as given").shown("the --out directory (required without --out)"),
    arg::number("every", "s",
                "simulated time between files; one shorter than the time step is refused when a run starts")
        .in(above(0))
        .def(kOutput.every),
    arg::names("fields", "the particle fields written; components such as ux select their vector").shown("all"),
    arg::boolean("grid", kOutput.grid, "also grid_NNNNNN.vtu with nodal mass, velocity and fixities"),
    arg::number("probe_every", "s", "every probe's sampling interval").in(at_least(0)).shown("each probe's own"),
    arg::boolean("at_run_end", true,
                 "a file at the end of each run too (false: a script that runs in short chunks then only writes "
                 "every `every` seconds)"),
    arg::number("checkpoint_every", "s",
                "wall-clock time between checkpoints written during runs to dir/checkpoint.chk (mpm.restart reads "
                "them)")
        .in(above(0))
        .shown("none"),
};
const Key kPlotReferenceKeys[] = {
    arg::string("quantity", "the probe field whose picture gets the curve").required(),
    arg::string("file", "a CSV file with a header line").required(),
    arg::string("x", "its column of times, in the plots' time axis (s since the dynamic phase began, after one)")
        .required(),
    arg::string("y", "its column of values, in the quantity's unit").required(),
    arg::string("title", "the curve's key entry").shown("the y column's name"),
};
const Key kPlotKeys[] = {
    arg::names("quantities",
               "particle fields of the probes (ux_rel, uy_rel of probes with relative_to), one picture each")
        .def_text("ux|uy"),
    arg::table("reference", kPlotReferenceKeys, "a closed form drawn with the probes, dashed and black"),
    arg::choice("x", kProbePlotX, "auto",
                "the time axis: auto (after a dynamic phase the shaking time, earlier phases at negative times "
                "shaded; with a phase kept, its own time), time (the model time), phase_time (the time since the "
                "phase kept began)"),
    arg::choice("phase", kProbePlotPhases, nullptr,
                "keep only the rows of this phase (its last run, if there were several); current: the phase now")
        .with(&Key::mandatory, false)
        .shown("every row; with x = phase_time the current phase"),
};

ModelHandle& handle_of(lua_State* L) { return *self<ModelObject>(L).handle; }

// m:output{ dir, every, fields, grid, probe_every, at_run_end }
int model_output(lua_State* L) {
  ModelHandle& h = handle_of(L);
  refuse_building(L, h, "set the output");
  const Args a(L, 2, kOutputKeys);
  OutputSettings s;
  // A dir given is used as it is; without one, the --out directory (Session::output_dir), if any.
  const Session& command_line = session(L);
  s.dir = a.has("dir") || command_line.out_dir.empty() ? a.string("dir") : command_line.output_dir("");
  refuse_control_characters(s.dir, "key 'dir'");  // m:plot hands it to gnuplot
  check_output_dir(L, s.dir, "key 'dir'");
  s.every = a.number("every");
  s.grid = a.boolean("grid");
  const bool at_run_end = a.boolean("at_run_end");
  if (const auto fields = a.names("fields")) {
    s.arrays.clear();
    for (const auto& name : *fields) {
      const VtuArray array = parse_vtu_array(name);
      if (std::find(s.arrays.begin(), s.arrays.end(), array) == s.arrays.end()) s.arrays.push_back(array);
    }
  }
  if (auto pe = a.optional_number("probe_every")) h.simulation.set_probe_every(*pe);
  h.simulation.set_output(s, at_run_end);  // writes the state as it is now
  allow_writes_under(L, s.dir);            // the script's own files go there too
  if (const auto every = a.optional_number("checkpoint_every"))
    h.simulation.set_periodic_checkpoint(s.dir + "/checkpoint.chk", *every);
  return 0;
}

// m:write(): the current state on file now (when it is not already).
int model_write(lua_State* L) {
  ModelHandle& h = handle_of(L);
  refuse_inside_a_step(L, "write the model's files");
  if (!h.simulation.output()) throw Error("no output directory yet: call m:output{ dir = ... } first");
  h.simulation.write();
  return 0;
}

// m:plot{ quantities = {"ux", "uy"} } -> list of PNG files
int model_plot(lua_State* L) {
  ModelHandle& h = handle_of(L);
  refuse_inside_a_step(L, "plot the probes");
  if (lua_isnoneornil(L, 2)) {  // m:plot(): every default
    lua_settop(L, 1);
    lua_newtable(L);
  }
  const Args a(L, 2, kPlotKeys);
  const auto quantities = *a.names("quantities");
  for (const auto& q : quantities)
    if (!parse_field(q, 2) && !parse_relative_field(q, 2))
      throw Error("key 'quantities': '" + q + "' is not a field name (" + field_names(2) + ", ux_rel, uy_rel)");
  ProbePlotOptions options;
  options.x = a.choice("x");
  if (a.has("phase")) options.phase = a.choice("phase");
  std::vector<ProbeReference> references;
  if (a.has("reference")) {
    const Args r = a.table("reference");
    ProbeReference ref{r.string("quantity"), r.string("file"), r.string("x"), r.string("y"), r.string("title", "")};
    for (const std::string* text : {&ref.quantity, &ref.csv, &ref.x, &ref.y, &ref.title})
      refuse_control_characters(*text, "key 'reference'");
    if (std::find(quantities.begin(), quantities.end(), ref.quantity) == quantities.end())
      throw Error("key 'reference': quantity '" + ref.quantity + "' is not among the quantities plotted");
    check_readable(L, ref.csv, "key 'reference'");
    references.push_back(ref);
  }
  const Output<2>* output = h.simulation.output();
  if (!output) throw Error("no output directory yet: call m:output{ dir = ... } first");
  if (h.simulation.probes().empty()) throw Error("the model has no probes to plot (m:probe{ ... })");
  h.simulation.write_probes();
  const auto files = plot_probes(output->settings().dir, quantities, references, options);
  lua_createtable(L, static_cast<int>(files.size()), 0);
  for (std::size_t i = 0; i < files.size(); ++i) {
    lua_pushstring(L, files[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

const Function kOutputFunctions[] = {
    {"model:output", &guarded<model_output>, nullptr, kOutputKeys,
     "Writes ParaView files into dir: particles_NNNNNN.vtu now, every `every` seconds of simulated time and at the "
     "end of each run, listed with their times in particles.pvd (open that one in ParaView, or run "
     "open_in_paraview.py: "
     "paraview --script=DIR/open_in_paraview.py); probes.csv with every field of every probe. With checkpoint_every, a "
     "checkpoint dir/checkpoint.chk during runs whenever that many "
     "seconds of wall time have passed (the previous one stays valid until the new one replaces it).",
     "m:output{ dir = \"out/slope\", every = 0.1, probe_every = 0.01 }"},
    {"model:write",
     &guarded<model_write>,
     "m:write()",
     {},
     "Writes the current state to the output directory now (particles, rigid bodies, probes, reactions), unless "
     "it is on file already; for scripts that run in chunks with at_run_end = false.",
     "m:write()"},
    {"model:plot", &guarded<model_plot>, nullptr, kPlotKeys,
     "Time histories of the probes in the output directory with gnuplot, as PNG and SVG (probe_<quantity>.png and "
     ".svg, one curve per probe, axes with units, the key outside the curves); returns the PNG file names. After a "
     "dynamic phase the time axis is the time since it began (the shaking time), with the phases before it shaded at "
     "negative "
     "times (phases.csv); otherwise the model time. phase keeps one phase's rows (phase = \"dynamic\", or "
     "\"current\"), x = \"phase_time\" puts them on that phase's own clock, x = \"time\" on the model time. From the "
     "shell: seismpm plot DIR ux uy --phase dynamic --x phase_time.",
     "m:plot{ quantities = {\"ux\"}, reference = { quantity = \"ux\", file = dir .. \"/motion.csv\", x = \"t (s)\", "
     "y = \"closed form (m)\" } }; m:plot{ quantities = {\"ux_rel\"}, phase = \"dynamic\", x = \"phase_time\" }"},
};

}  // namespace

std::span<const Function> output_functions() { return kOutputFunctions; }

void open_output(lua_State* L) { register_functions(L, kOutputFunctions); }

}  // namespace seismpm::lua
