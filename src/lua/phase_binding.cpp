// Calculation phases: m:gravity_phase (initial stresses, damped to equilibrium, or K0), m:dynamic_phase
// (shaking), m:phase_time.
#include "binding.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

ModelHandle& self(lua_State* L) { return *check_object<ModelObject>(L, 1, kModelType, "self").handle; }

// m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 10, k0 } -> { time, steps, unbalanced, kinetic }
int model_gravity_phase(lua_State* L) {
  ModelHandle& h = self(L);
  Args a(L, 2, {"damping", "tolerance", "max_time", "k0"});
  GravityPhaseSettings g;
  g.damping = Args::in_range("damping", a.number("damping", g.damping), 0.0, 1.0, true);
  g.tolerance = Args::in_range("tolerance", a.number("tolerance", g.tolerance), 1e-12, 1.0, true);
  g.max_time = Args::positive("max_time", a.number("max_time", g.max_time), "s");
  if (auto k0 = a.optional_number("k0")) g.k0 = Args::in_range("k0", *k0, 1e-6, 3.0, false);
  if (h.model.particles().size() == 0) throw Error("the model has no particles");
  refuse_inside_a_run(h, "start a phase");
  const GravityPhaseResult r = run_in_session(L, h, [&](Simulation<2>& sim) { return sim.gravity_phase(g); });
  lua_createtable(L, 0, 4);
  lua_pushnumber(L, r.time);
  lua_setfield(L, -2, "time");
  lua_pushinteger(L, r.steps);
  lua_setfield(L, -2, "steps");
  lua_pushnumber(L, r.force_ratio);
  lua_setfield(L, -2, "unbalanced");
  lua_pushnumber(L, r.energy_ratio);
  lua_setfield(L, -2, "kinetic");
  return 1;
}

// m:dynamic_phase{ duration, damping = 0, every, call }
int model_dynamic_phase(lua_State* L) {
  ModelHandle& h = self(L);
  Args a(L, 2, {"duration", "damping", "every", "call"});
  const double duration = Args::positive("duration", a.number("duration"), "s");
  const double damping = Args::in_range("damping", a.number("damping", 0.0), 0.0, 1.0, true);
  if (h.model.particles().size() == 0) throw Error("the model has no particles");
  refuse_inside_a_run(h, "start a phase");
  const PeriodicCall call(a);
  run_in_session(L, h, [&](Simulation<2>& sim) { sim.dynamic_phase(duration, damping, call.run_call(L, h.model)); });
  return 0;
}

int model_phase_time(lua_State* L) {
  lua_pushnumber(L, self(L).model.phase_time());
  return 1;
}

int model_phase(lua_State* L) {
  lua_pushstring(L, self(L).simulation.phase().c_str());
  return 1;
}

}  // namespace

void open_phases(lua_State* L) {
  luaL_getmetatable(L, kModelType);
  lua_getfield(L, -1, "__index");
  set_function<model_gravity_phase>(L, -1, "gravity_phase", "model:gravity_phase");
  set_function<model_dynamic_phase>(L, -1, "dynamic_phase", "model:dynamic_phase");
  set_function<model_phase_time>(L, -1, "phase_time", "model:phase_time");
  set_function<model_phase>(L, -1, "phase", "model:phase");
  lua_pop(L, 2);
}

}  // namespace seismpm::lua
