// mpm.model and the model's methods: body, fix, probe, step, run and inspection.
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "binding.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/probe_plot.hpp"
#include "objects.hpp"
#include "core/particle_fields.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

ModelHandle& self(lua_State* L) { return *check_object<ModelObject>(L, 1, kModelType, "self").handle; }

std::string point_text(const Vec<2>& p) {
  std::ostringstream os;
  os << "{" << p[0] << ", " << p[1] << "}";
  return os.str();
}

int model_new(lua_State* L) {
  Args a(L, 1, {"domain", "cell", "shape", "scheme", "gravity", "cfl", "flip", "dt", "max_dilation"});
  ModelSettings<2> s;
  const int domain_type = a.push("domain");
  if (domain_type == LUA_TNIL) throw Error("missing key 'domain' ({{x0, y0}, {x1, y1}} in m)");
  if (domain_type != LUA_TTABLE) throw Error("key 'domain' must be {{x0, y0}, {x1, y1}} (m)");
  if (luaL_len(L, -1) != 2) throw Error("key 'domain' must hold 2 corner points {{x0, y0}, {x1, y1}}");
  lua_rawgeti(L, -1, 1);
  if (lua_istable(L, -1) && luaL_len(L, -1) == 3) throw Error("3D models are not available from Lua yet (domain has 3 coordinates)");
  s.lower = to_point(L, -1, "domain corner 1");
  lua_rawgeti(L, -2, 2);
  s.upper = to_point(L, -1, "domain corner 2");
  lua_pop(L, 3);
  for (int d = 0; d < 2; ++d)
    if (!(s.upper[d] > s.lower[d]))
      throw Error("key 'domain' is empty: the second corner must be above and right of the first, got " +
                  point_text(s.lower) + " to " + point_text(s.upper));
  s.cell = Args::positive("cell", a.number("cell"), "m");
  s.shape = a.choice("shape", {"linear", "gimp"}, "gimp") == "linear" ? ShapeKind::Linear : ShapeKind::Gimp;
  s.scheme = a.choice("scheme", {"musl", "usl"}, "musl") == "usl" ? Scheme::Usl : Scheme::Musl;
  s.gravity = a.has("gravity") ? a.point("gravity") : Vec<2>(0.0, -9.81);
  s.cfl = Args::in_range("cfl", a.number("cfl", 0.4), 1e-6, 1.0, false);
  s.flip = Args::in_range("flip", a.number("flip", 1.0), 0.0, 1.0, false);
  if (auto dt = a.optional_number("dt")) s.fixed_dt = Args::positive("dt", *dt, "s");
  if (auto md = a.optional_number("max_dilation")) {
    if (!(*md == 0.0 || (*md >= 1.0 && std::isfinite(*md))))
      throw Error("key 'max_dilation' must be 0 (no limit) or a finite number >= 1");
    s.max_dilation = *md;
  }
  for (int d = 0; d < 2; ++d)
    if ((s.upper[d] - s.lower[d]) / s.cell < 2.0 - 1e-9)
      throw Error("key 'cell' is too large: the domain must span at least 2 cells along x and y");
  auto handle = std::make_shared<ModelHandle>(s);
  push_object(L, kModelType, ModelObject{handle});
  return 1;
}

int model_tostring(lua_State* L) {
  const auto& m = self(L).model;
  std::ostringstream os;
  os << "model: " << m.grid().domain_cells(0) << " x " << m.grid().domain_cells(1) << " cells of " << m.grid().cell() << " m, "
     << m.bodies().size() << " bodies, " << m.particles().size() << " particles, t = " << m.time() << " s";
  lua_pushstring(L, os.str().c_str());
  return 1;
}

// The shape under key 'shape', checked to lie in the model's domain.
std::shared_ptr<const Region> shape_argument(Args& a, const ModelHandle& h) {
  lua_State* L = a.state();
  if (a.push("shape") == LUA_TNIL) throw Error("missing key 'shape' (an mpm.shape.rectangle/polygon/polyline)");
  auto region = check_object<ShapeObject>(L, -1, kShapeType, "key 'shape'").region;
  lua_pop(L, 1);
  const auto& g = h.model.grid();
  const double tol = 1e-9 * g.cell();
  const Vec<2> lo = g.domain_lower(), hi = g.domain_upper();
  if ((region->lower().array() < lo.array() - tol).any() || (region->upper().array() > hi.array() + tol).any())
    throw Error("key 'shape': " + region->describe() + " reaches outside the domain " + point_text(lo) + " to " +
                point_text(hi));
  return region;
}

std::string body_name_argument(Args& a, const ModelHandle& h, const char* stem) {
  const std::string name = a.string("name", stem + std::to_string(h.model.bodies().size() + 1));
  for (const auto& b : h.model.bodies())
    if (b.name == name) throw Error("key 'name': a body called '" + name + "' exists already");
  return name;
}

void fill_region(ModelHandle& h, int body, int material, const Region& region, int ppc) {
  const std::size_t added =
      h.model.fill(body, material, region.lower(), region.upper(), [&](const Vec<2>& x) { return region.contains(x); },
                   [&](const Vec<2>& x) { return region.outward_normal(x); });
  if (added == 0)
    throw Error("key 'shape': " + region.describe() + " holds no particle at ppc = " + std::to_string(ppc) +
                " (smaller than a particle spacing of " + std::to_string(h.model.grid().cell() / ppc) + " m?)");
}

int model_body(lua_State* L) {
  auto handle = check_object<ModelObject>(L, 1, kModelType, "self").handle;
  ModelHandle& h = *handle;
  Args a(L, 2, {"name", "material", "shape", "ppc"});
  const std::string name = body_name_argument(a, h, "body");
  a.push("material");
  const auto& mat = check_object<MaterialObject>(L, -1, kMaterialType, "key 'material'");
  lua_pop(L, 1);
  const int ppc = static_cast<int>(Args::in_range("ppc", a.integer("ppc", 2), 1, 8, false));
  const auto region = shape_argument(a, h);
  const int body = h.model.add_body(name, ppc);
  fill_region(h, body, h.material(mat.material), *region, ppc);
  push_object(L, kBodyType, BodyObject{handle, body});
  return 1;
}

}  // namespace

// The velocity of a rigid body at `index`: {vx, vy}, each a number (m/s) or a history.
std::array<std::shared_ptr<const History>, 2> rigid_velocity(lua_State* L, int index, const std::string& what) {
  index = lua_absindex(L, index);
  if (lua_isnil(L, index)) {
    std::array<std::shared_ptr<const History>, 2> rest;
    rest.fill(std::make_shared<ConstantHistory>(0.0));
    return rest;
  }
  if (!lua_istable(L, index) || luaL_len(L, index) != 2)
    throw Error(what + " must be {vx, vy}: two numbers (m/s) or histories, got " + type_name(L, index));
  std::array<std::shared_ptr<const History>, 2> v;
  for (int d = 0; d < 2; ++d) {
    lua_rawgeti(L, index, d + 1);
    v[d] = to_history(L, -1, what + (d ? " vy" : " vx"));
    lua_pop(L, 1);
  }
  return v;
}

namespace {

// m:rigid{ name, shape, ppc, velocity = {vx, vy}, density }
int model_rigid(lua_State* L) {
  auto handle = check_object<ModelObject>(L, 1, kModelType, "self").handle;
  ModelHandle& h = *handle;
  Args a(L, 2, {"name", "shape", "ppc", "velocity", "density"});
  const std::string name = body_name_argument(a, h, "rigid");
  const int ppc = static_cast<int>(Args::in_range("ppc", a.integer("ppc", 2), 1, 8, false));
  const double density = Args::positive("density", a.number("density", 7850.0), "kg/m3");
  a.push("velocity");
  const auto velocity = rigid_velocity(L, -1, "key 'velocity'");
  lua_pop(L, 1);
  const auto region = shape_argument(a, h);
  const int body = h.model.add_rigid_body(name, ppc, density, velocity);
  fill_region(h, body, -1, *region, ppc);
  push_object(L, kBodyType, BodyObject{handle, body});
  return 1;
}

// The two bodies of m:contact{ a, b, ... } and m:set_friction{ a, b, ... }.
std::array<int, 2> body_pair(Args& a, const std::shared_ptr<ModelHandle>& handle, const char* usage) {
  lua_State* L = a.state();
  if (a.length() != 2) throw Error(std::string("name the two bodies: ") + usage);
  std::array<int, 2> body{};
  for (int k = 0; k < 2; ++k) {
    lua_rawgeti(L, a.index(), k + 1);
    const auto& b = check_object<BodyObject>(L, -1, kBodyType, k ? "the second body" : "the first body");
    if (b.handle != handle) throw Error(std::string(k ? "the second" : "the first") + " body belongs to another model");
    body[k] = b.body;
    lua_pop(L, 1);
  }
  return body;
}

// m:contact{ body_a, body_b, friction = mu }
int model_contact(lua_State* L) {
  auto handle = check_object<ModelObject>(L, 1, kModelType, "self").handle;
  Args a(L, 2, {"friction"}, true);
  const auto body = body_pair(a, handle, "m:contact{ body_a, body_b, friction = mu } (bodies in contact)");
  const double mu = Args::at_least("friction", a.number("friction"), 0.0);
  handle->model.add_contact(body[0], body[1], mu);  // names the bodies of a pair declared twice or with itself
  return 0;
}

// m:set_friction{ body_a, body_b, friction = mu }
int model_set_friction(lua_State* L) {
  auto handle = check_object<ModelObject>(L, 1, kModelType, "self").handle;
  Args a(L, 2, {"friction"}, true);
  const auto body = body_pair(a, handle, "m:set_friction{ body_a, body_b, friction = mu }");
  const double mu = Args::at_least("friction", a.number("friction"), 0.0);
  handle->model.set_contact_friction(body[0], body[1], mu);
  return 0;
}

int model_fix(lua_State* L) {
  ModelHandle& h = self(L);
  Args a(L, 2, {"side", "dof"});
  const std::string side = a.choice("side", {"left", "right", "bottom", "top"}, "");
  const std::string dof = a.choice("dof", {"x", "y", "xy"}, "xy");
  h.model.grid().fix(parse_side(side, 2), parse_dof(dof, 2));
  return 0;
}

int model_probe(lua_State* L) {
  auto handle = check_object<ModelObject>(L, 1, kModelType, "self").handle;
  Args a(L, 2, {"name", "body", "at", "every"});
  Simulation<2>& sim = handle->simulation;
  const std::string name = a.string("name", "probe" + std::to_string(sim.probes().size() + 1));
  for (const auto& p : sim.probes())
    if (std::string(p->name()) == name) throw Error("key 'name': a probe called '" + name + "' exists already");
  a.push("body");
  const int body = check_object<BodyObject>(L, -1, kBodyType, "key 'body'").body;
  lua_pop(L, 1);
  const Vec<2> at = a.point("at");
  const double every = Args::at_least("every", a.number("every", 0.01), 0.0, "s");
  // The particle of the body nearest to `at`.
  const auto& p = handle->model.particles();
  double best = INFINITY;
  int id = -1;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body[i] == body && (p.x[i] - at).norm() < best) best = (p.x[i] - at).norm(), id = p.id[i];
  if (id < 0) throw Error("key 'body' has no particles");
  push_object(L, kProbeType, ProbeObject{handle, sim.add_probe(name, id, every)});
  return 1;
}

}  // namespace

PeriodicCall::PeriodicCall(Args& a) {
  const bool has_every = a.has("every"), has_call = a.has("call");
  if (has_every != has_call)
    throw Error(has_every ? "key 'every' needs key 'call' (a function to call every `every` s)"
                          : "key 'call' needs key 'every' (s of simulated time between calls)");
  if (!has_call) return;
  const double interval = Args::positive("every", a.number("every"), "s");
  if (a.push("call") != LUA_TFUNCTION) {
    lua_pop(a.state(), 1);
    throw Error("key 'call' must be a function, function(m) ... end");
  }
  state = a.state();
  every = interval;
  function = luaL_ref(state, LUA_REGISTRYINDEX);
}

PeriodicCall::~PeriodicCall() {
  if (state) luaL_unref(state, LUA_REGISTRYINDEX, function);
}

namespace {

// Calls the run's function with the model (stack index 1); true when it asks the run to stop.
bool invoke(lua_State* L, int function, double t) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, function);
  lua_pushvalue(L, 1);
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "error";
    lua_pop(L, 1);
    std::ostringstream os;
    os << "the run's call failed at t = " << t << " s: " << msg;
    throw Error(os.str());
  }
  const bool stop = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return stop;
}

}  // namespace

RunCall PeriodicCall::run_call(lua_State* L, const Model<2>& model) const {
  if (every <= 0) return {};
  return {every, [L, f = function, &model] { return invoke(L, f, model.time()); }};
}

void refuse_inside_a_run(const ModelHandle& h, const char* what) {
  if (h.simulation.running())
    throw Error(std::string("a run's call may not ") + what +
                " (m:run, m:step or a phase): return true from it to end the run");
}

void prepare_run(lua_State* L, ModelHandle& h) {
  Session& s = session(L);
  s.interrupted = false;
  h.simulation.set_progress(s.progress);
  h.simulation.set_interrupt(&s.interrupted);
}

namespace {

int model_step(lua_State* L) {
  ModelHandle& h = self(L);
  lua_Integer n = 1;
  if (!lua_isnoneornil(L, 2)) {
    if (!lua_isinteger(L, 2) || lua_tointeger(L, 2) < 1) throw Error("the number of steps must be a whole number >= 1");
    n = lua_tointeger(L, 2);
  }
  refuse_inside_a_run(h, "step the model");
  run_in_session(L, h, [&](Simulation<2>& sim) { sim.step(n); });
  return 0;
}

int model_run(lua_State* L) {
  ModelHandle& h = self(L);
  Args a(L, 2, {"duration", "damping", "every", "call"});
  const double duration = Args::positive("duration", a.number("duration"), "s");
  const PeriodicCall call(a);  // read first: a bad call leaves the damping as it was
  refuse_inside_a_run(h, "step the model");
  const auto damping = a.optional_number("damping");
  if (damping) h.simulation.set_damping(Args::in_range("damping", *damping, 0.0, 1.0, true));
  run_in_session(L, h, [&](Simulation<2>& sim) { sim.run(duration, call.run_call(L, h.model)); });
  return 0;
}

// m:output{ dir, every, fields, grid, probe_every }
int model_output(lua_State* L) {
  ModelHandle& h = self(L);
  Args a(L, 2, {"dir", "every", "fields", "grid", "probe_every", "at_run_end"});
  OutputSettings s;
  // A dir given is used as it is; without one, the --out directory (Session::output_dir), if any.
  const Session& command_line = session(L);
  s.dir = a.has("dir") || command_line.out_dir.empty() ? a.string("dir") : command_line.output_dir("");
  s.every = Args::positive("every", a.number("every", 0.1), "s");
  s.grid = a.boolean("grid", false);
  const bool at_run_end = a.boolean("at_run_end", true);
  if (const auto fields = a.names("fields")) {
    s.arrays.clear();
    for (const auto& name : *fields) {
      const VtuArray array = parse_vtu_array(name);
      if (std::find(s.arrays.begin(), s.arrays.end(), array) == s.arrays.end()) s.arrays.push_back(array);
    }
  }
  if (auto pe = a.optional_number("probe_every")) {
    Args::at_least("probe_every", *pe, 0.0, "s");
    h.simulation.set_probe_every(*pe);
  }
  h.simulation.set_output(s, at_run_end);  // writes the state as it is now
  return 0;
}

// m:write(): the current state on file now (when it is not already).
int model_write(lua_State* L) {
  ModelHandle& h = self(L);
  if (!h.simulation.output()) throw Error("no output directory yet: call m:output{ dir = ... } first");
  h.simulation.write();
  return 0;
}

// m:plot{ quantities = {"ux", "uy"} } -> list of PNG files
int model_plot(lua_State* L) {
  ModelHandle& h = self(L);
  std::vector<std::string> quantities = {"ux", "uy"};
  if (!lua_isnoneornil(L, 2)) {
    Args a(L, 2, {"quantities"});
    if (auto names = a.names("quantities")) quantities = std::move(*names);
  }
  for (const auto& q : quantities)
    if (!parse_field(q, 2)) throw Error("key 'quantities': '" + q + "' is not a field name (" + field_names(2) + ")");
  const Output<2>* output = h.simulation.output();
  if (!output) throw Error("no output directory yet: call m:output{ dir = ... } first");
  if (h.simulation.probes().empty()) throw Error("the model has no probes to plot (m:probe{ ... })");
  write_file_atomically(output->settings().dir + "/probes.csv", probes_csv_text(h.simulation.probes()));
  const auto files = plot_probes(output->settings().dir, quantities);
  lua_createtable(L, static_cast<int>(files.size()), 0);
  for (std::size_t i = 0; i < files.size(); ++i) {
    lua_pushstring(L, files[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

int model_time(lua_State* L) {
  lua_pushnumber(L, self(L).model.time());
  return 1;
}

int model_steps(lua_State* L) {
  lua_pushinteger(L, self(L).model.steps());
  return 1;
}

int model_dt(lua_State* L) {
  const auto& m = self(L).model;
  // Before the first step: the step the CFL condition would take now.
  lua_pushnumber(L, m.steps() > 0 ? m.dt() : (m.particles().size() ? m.stable_time_step() : 0.0));
  return 1;
}

int model_energy(lua_State* L) {
  const auto& m = self(L).model;
  lua_createtable(L, 0, 2);
  lua_pushnumber(L, m.kinetic_energy());
  lua_setfield(L, -2, "kinetic");
  lua_pushnumber(L, m.strain_energy());
  lua_setfield(L, -2, "strain");
  return 1;
}

int model_count(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(self(L).model.particles().size()));
  return 1;
}

int model_bodies(lua_State* L) {
  auto handle = check_object<ModelObject>(L, 1, kModelType, "self").handle;
  lua_newtable(L);
  for (std::size_t b = 0; b < handle->model.bodies().size(); ++b) {
    push_object(L, kBodyType, BodyObject{handle, static_cast<int>(b)});
    lua_setfield(L, -2, handle->model.bodies()[b].name.c_str());
  }
  return 1;
}

}  // namespace

void open_model(lua_State* L, int mpm) {
  new_type<ModelObject, model_tostring>(L, kModelType);
  set_function<model_body>(L, -1, "body", "model:body");
  set_function<model_rigid>(L, -1, "rigid", "model:rigid");
  set_function<model_contact>(L, -1, "contact", "model:contact");
  set_function<model_set_friction>(L, -1, "set_friction", "model:set_friction");
  set_function<model_fix>(L, -1, "fix", "model:fix");
  set_function<model_probe>(L, -1, "probe", "model:probe");
  set_function<model_step>(L, -1, "step", "model:step");
  set_function<model_run>(L, -1, "run", "model:run");
  set_function<model_output>(L, -1, "output", "model:output");
  set_function<model_plot>(L, -1, "plot", "model:plot");
  set_function<model_write>(L, -1, "write", "model:write");
  set_function<model_time>(L, -1, "time", "model:time");
  set_function<model_steps>(L, -1, "steps", "model:steps");
  set_function<model_dt>(L, -1, "dt", "model:dt");
  set_function<model_energy>(L, -1, "energy", "model:energy");
  set_function<model_count>(L, -1, "count", "model:count");
  set_function<model_bodies>(L, -1, "bodies", "model:bodies");
  lua_pop(L, 1);
  set_function<model_new>(L, mpm, "model", "mpm.model");
}

}  // namespace seismpm::lua
