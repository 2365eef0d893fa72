// Calculation phases: m:gravity_phase (initial stresses, damped to equilibrium, or K0), m:dynamic_phase
// (shaking), m:phase_time.
#include <cstdio>
#include <sstream>

#include "binding.hpp"
#include "core/gravity_phase.hpp"
#include "objects.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

ModelHandle& self(lua_State* L) { return *check_object<ModelObject>(L, 1, kModelType, "self").handle; }

std::string ratios(const EquilibriumMonitor<2>& e) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "unbalanced %.1e, kinetic %.1e of peak (tol %.0e)", e.force_ratio(), e.energy_ratio(),
                e.tolerance());
  return buf;
}

// m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 10, k0 } -> { time, steps, unbalanced, kinetic }
int model_gravity_phase(lua_State* L) {
  ModelHandle& h = self(L);
  Args a(L, 2, {"damping", "tolerance", "max_time", "k0"});
  GravityPhaseSettings g;
  g.damping = Args::in_range("damping", a.number("damping", g.damping), 0.0, 1.0, true);
  g.tolerance = Args::in_range("tolerance", a.number("tolerance", g.tolerance), 1e-12, 1.0, true);
  g.max_time = Args::positive("max_time", a.number("max_time", g.max_time), "s");
  if (auto k0 = a.optional_number("k0")) g.k0 = Args::in_range("k0", *k0, 1e-6, 3.0, false);
  Model<2>& m = h.model;
  if (m.particles().size() == 0) throw Error("the model has no particles");
  refuse_inside_a_run(h, "start a phase");

  h.phase = "gravity";
  m.begin_phase(false);  // rigid bodies at rest
  damping_of(h).set_alpha(g.damping);
  if (g.k0 > 0.0) set_k0_stresses(m, g.k0);
  EquilibriumMonitor<2> equilibrium(g.tolerance);
  m.set_balance_measure(true);
  const double t0 = m.time();
  const long s0 = m.steps();
  bool reached = false;
  try {
    reached = run_for(
        L, h, g.max_time, std::numeric_limits<long>::max(), true,
        [&] {
          equilibrium.update(m);
          return equilibrium.reached();
        },
        [&] { return ratios(equilibrium); });
  } catch (...) {
    m.set_balance_measure(false);
    throw;
  }
  m.set_balance_measure(false);
  if (!reached) {
    std::ostringstream os;
    os << "no static equilibrium within max_time = " << g.max_time << " s: out-of-balance force "
       << equilibrium.force_ratio() << " of the external force, kinetic energy " << equilibrium.energy_ratio()
       << " of its peak (tolerance " << g.tolerance
       << "). Something keeps moving: a slope steeper than its strength allows, a body without support, or too "
          "short a max_time; the outputs show the state at t = "
       << m.time() << " s";
    throw Error(os.str());
  }
  // Displacements and strains start from zero in the next phase; stresses and plastic state are kept.
  m.particles().reset_kinematics();
  if (session(L).progress != Progress::Mode::Quiet) {
    std::fprintf(stderr, "gravity phase: equilibrium after %.4g s (%ld steps): %s\n", m.time() - t0, m.steps() - s0,
                 ratios(equilibrium).c_str());
  }
  lua_createtable(L, 0, 4);
  lua_pushnumber(L, m.time() - t0);
  lua_setfield(L, -2, "time");
  lua_pushinteger(L, m.steps() - s0);
  lua_setfield(L, -2, "steps");
  lua_pushnumber(L, equilibrium.force_ratio());
  lua_setfield(L, -2, "unbalanced");
  lua_pushnumber(L, equilibrium.energy_ratio());
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
  h.phase = "dynamic";
  h.model.begin_phase(true);  // histories start now
  damping_of(h).set_alpha(damping);
  run_for(L, h, duration, std::numeric_limits<long>::max(), true, {}, {}, call);
  return 0;
}

int model_phase_time(lua_State* L) {
  lua_pushnumber(L, self(L).model.phase_time());
  return 1;
}

int model_phase(lua_State* L) {
  lua_pushstring(L, self(L).phase.c_str());
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
