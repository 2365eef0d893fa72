// Runs and calculation phases: m:step, m:run, m:gravity_phase (initial stresses, damped to equilibrium,
// or K0), m:dynamic_phase (shaking), m:phase_time, m:phase. The stepping itself is the run layer's
// (src/run/simulation.hpp); this file reads the arguments and makes the run's Lua call.
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "objects.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

const GravityPhaseSettings kGravity;  // the run layer's defaults

const Key kEvery = arg::number("every", "s", "interval of simulated time between calls (with call)").in(above(0));
const Key kCall = arg::function("call", "function(m) ... end, called every `every` s and at the end (with every)");
const Key kRunKeys[] = {
    arg::number("duration", "s", "simulated time to run")
        .in(above(0))
        .shown("required, except after mpm.restart to finish the interrupted run"),
    arg::number("damping", "", "local damping coefficient for this and later runs")
        .in(closed_open(0, 1))
        .shown("unchanged (0 at first)"),
    kEvery,
    kCall,
};
const Key kDynamicKeys[] = {
    arg::number("duration", "s", "length of the phase").in(above(0)).required(),
    arg::number("damping", "", "local damping coefficient").in(closed_open(0, 1)).def(0),
    kEvery,
    kCall,
};
const Key kGravityKeys[] = {
    arg::number("damping", "", "local damping coefficient alpha").in(closed_open(0, 1)).def(kGravity.damping),
    arg::number("tolerance", "", "of both equilibrium ratios").in(closed_open(1e-12, 1)).def(kGravity.tolerance),
    arg::number("max_time", "s", "simulated time before the phase fails with an error")
        .in(above(0))
        .def(kGravity.max_time),
    arg::number("k0", "",
                "first set sigma_v = rho g depth and sigma_h = k0 sigma_v, then settle (none: settle from "
                "the current stresses)")
        .in(open_closed(0, 3))
        .shown("none"),
};

ModelHandle& handle_of(lua_State* L) { return *self<ModelObject>(L).handle; }

// The model a run steps, held by the run itself: Lua code that it calls (a history function, the
// run's call) may destroy the userdata by hand (its __gc) while the run goes on.
std::shared_ptr<ModelHandle> held_handle(lua_State* L) { return self<ModelObject>(L).handle; }

// Calls the run's function with the model (stack index 1); true when it asks the run to stop.
bool invoke(lua_State* L, int function, double t) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, function);
  lua_pushvalue(L, 1);
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
    std::string msg = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "(an error object that is not a string)";
    lua_pop(L, 1);
    std::ostringstream os;
    os << "the run's call failed at t = " << t << " s: " << msg;
    throw Error(os.str());
  }
  const bool stop = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return stop;
}

int model_step(lua_State* L) {
  const auto held = held_handle(L);
  ModelHandle& h = *held;
  lua_Integer n = 1;
  if (!lua_isnoneornil(L, 2)) {
    if (!lua_isinteger(L, 2) || lua_tointeger(L, 2) < 1) throw Error("the number of steps must be a whole number >= 1");
    n = lua_tointeger(L, 2);
  }
  refuse_inside_a_run(L, h, "step the model");
  run_in_session(L, h, [&](Simulation<2>& sim) { sim.step(n); });
  return 0;
}

void push_result(lua_State* L, const GravityPhaseResult& r) {
  lua_createtable(L, 0, 4);
  lua_pushnumber(L, r.time);
  lua_setfield(L, -2, "time");
  lua_pushinteger(L, r.steps);
  lua_setfield(L, -2, "steps");
  lua_pushnumber(L, r.force_ratio);
  lua_setfield(L, -2, "unbalanced");
  lua_pushnumber(L, r.energy_ratio);
  lua_setfield(L, -2, "kinetic");
}

// m:run{} after mpm.restart: the interrupted run, finished; a gravity phase returns its result.
int finish_interrupted_run(lua_State* L, ModelHandle& h, const Args& a, const PeriodicCall& call) {
  if (!h.simulation.has_interrupted_run())
    throw Error(
        "key 'duration' must be a number, got nil (only a model restored from a checkpoint written during "
        "a run, by mpm.restart, finishes that run with m:run{})");
  if (a.has("damping")) throw Error("key 'damping': the interrupted run goes on with its own damping");
  const double every = h.simulation.interrupted_call_every();
  if (every > 0.0 && call.every <= 0.0)
    throw Error("the interrupted run called a function every " + number_text(every) +
                " s, which a checkpoint cannot hold: give it again, m:run{ every = " + number_text(every) +
                ", call = f }");
  const ResumedRun r = run_in_session(L, h, [&](Simulation<2>& sim) { return sim.resume(call.run_call(L, h.model)); });
  if (!r.gravity) return 0;
  push_result(L, *r.gravity);
  return 1;
}

int model_run(lua_State* L) {
  const auto held = held_handle(L);
  ModelHandle& h = *held;
  const Args a(L, 2, kRunKeys);
  const PeriodicCall call(a);  // read first: a bad call leaves the damping as it was
  refuse_inside_a_run(L, h, "step the model");
  if (!a.has("duration")) return finish_interrupted_run(L, h, a, call);
  const double duration = a.number("duration");
  if (const auto damping = a.optional_number("damping")) h.simulation.set_damping(*damping);
  run_in_session(L, h, [&](Simulation<2>& sim) { sim.run(duration, call.run_call(L, h.model)); });
  return 0;
}

// m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 10, k0 } -> { time, steps, unbalanced, kinetic }
int model_gravity_phase(lua_State* L) {
  const auto held = held_handle(L);
  ModelHandle& h = *held;
  const Args a(L, 2, kGravityKeys);
  GravityPhaseSettings g;
  g.damping = a.number("damping");
  g.tolerance = a.number("tolerance");
  g.max_time = a.number("max_time");
  if (auto k0 = a.optional_number("k0")) g.k0 = *k0;
  if (h.model.particles().size() == 0) throw Error("the model has no particles");
  refuse_inside_a_run(L, h, "start a phase");
  const GravityPhaseResult r = run_in_session(L, h, [&](Simulation<2>& sim) { return sim.gravity_phase(g); });
  push_result(L, r);
  return 1;
}

// m:dynamic_phase{ duration, damping = 0, every, call }
int model_dynamic_phase(lua_State* L) {
  const auto held = held_handle(L);
  ModelHandle& h = *held;
  const Args a(L, 2, kDynamicKeys);
  const double duration = a.number("duration"), damping = a.number("damping");
  if (h.model.particles().size() == 0) throw Error("the model has no particles");
  refuse_inside_a_run(L, h, "start a phase");
  const PeriodicCall call(a);
  run_in_session(L, h, [&](Simulation<2>& sim) { sim.dynamic_phase(duration, damping, call.run_call(L, h.model)); });
  return 0;
}

int model_phase_time(lua_State* L) {
  lua_pushnumber(L, handle_of(L).model.phase_time());
  return 1;
}

int model_phase(lua_State* L) {
  lua_pushstring(L, handle_of(L).simulation.phase().c_str());
  return 1;
}

const Function kPhases[] = {
    {"model:step", &guarded<model_step>, "m:step(n = 1)", {}, "Takes n explicit steps.", "m:step(10)"},
    {"model:run", &guarded<model_run>, nullptr, kRunKeys,
     "Runs for duration (s) more in the current phase, with a progress display. call(m) runs every `every` seconds "
     "of simulated time (hit exactly) and at the end of the run, between steps: to sample or print something, or to "
     "end the run early by returning true, or to change a friction (m:set_friction) or a velocity "
     "(b:set_velocity); it may not step the model itself, nor add bodies, contacts, fixities, probes or an "
     "output. Ctrl-C stops at the next step boundary with the model intact. After mpm.restart from a checkpoint "
     "written during a run, m:run{} (no duration) finishes that run as it would have gone on: a dynamic phase or "
     "run to its end, a gravity phase to equilibrium with the reset at its end (it then returns the phase's result "
     "table); give every and call again when the run had them. A run or phase started instead drops it.",
     "m:run{ duration = 60, every = 1, call = function(m) return m:energy().kinetic < 1 end }"},
    {"model:gravity_phase", &guarded<model_gravity_phase>, nullptr, kGravityKeys,
     "The initial-stress phase: self-weight with rigid bodies at rest and local damping (F_damp = -damping "
     "|F_unbalanced| sign(v) per degree of freedom) until static equilibrium: the out-of-balance force relative to "
     "the external force and the kinetic energy relative to its peak in the phase both below tolerance (shown with "
     "the progress; nodes held by a rigid body or a fixity count as supported). Fails with an error at max_time. "
     "At its end displacements and the strain that shear_strain measures are reset to zero; stresses and plastic "
     "state are kept. k0: the overburden of the particles above, per grid column. Returns { time, steps, "
     "unbalanced, kinetic }.",
     "local eq = m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 5 }; print(eq.time, eq.steps)"},
    {"model:dynamic_phase", &guarded<model_dynamic_phase>, nullptr, kDynamicKeys,
     "The shaking phase: inertia on, rigid bodies follow their velocity histories, read at the phase time, which "
     "starts at zero now (so a record starts when the shaking starts). Phases can follow each other in any number; "
     "m:run{ duration } continues the current phase without restarting its clock. every and call: as for m:run.",
     "m:dynamic_phase{ duration = 14, every = 0.5, call = function(m) print(m:phase_time()) end }"},
    {"model:phase_time",
     &guarded<model_phase_time>,
     "m:phase_time()",
     {},
     "Time since the current phase started (s); m:time() is the total.",
     "print(m:phase_time(), m:time())"},
    {"model:phase",
     &guarded<model_phase>,
     "m:phase()",
     {},
     "The current phase's name: \"run\" before any phase, \"gravity\" or \"dynamic\".",
     "print(m:phase())"},
};

}  // namespace

PeriodicCall::PeriodicCall(const Args& a) {
  const bool has_every = a.has("every"), has_call = a.has("call");
  if (has_every != has_call)
    throw Error(has_every ? "key 'every' needs key 'call' (a function to call every `every` s)"
                          : "key 'call' needs key 'every' (s of simulated time between calls)");
  if (!has_call) return;
  const double interval = a.number("every");
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

RunCall PeriodicCall::run_call(lua_State* L, const Model<2>& model) const {
  if (every <= 0) return {};
  return {every, [L, f = function, &model] { return invoke(L, f, model.time()); }};
}

void prepare_run(lua_State* L, ModelHandle& h) {
  Session& s = session(L);
  s.interrupted = false;
  h.simulation.set_progress(s.progress);
  h.simulation.set_interrupt(&s.interrupted);
}

std::span<const Function> phase_functions() { return kPhases; }

void open_phases(lua_State* L) { register_functions(L, kPhases); }

}  // namespace seismpm::lua
