// m:strength_reduction: the factor of safety by strength reduction in MPM (src/run/strength_reduction.hpp).
#include <cmath>

#include "api_docs.hpp"
#include "args.hpp"
#include "binding.hpp"
#include "io/atomic_file.hpp"
#include "objects.hpp"
#include "run/strength_reduction.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

const StrengthReductionSettings kDefaults;  // the run layer's

const Key kStrengthReductionKeys[] = {
    arg::custom("srf", "{lo, hi}", "",
                "bracket of the strength reduction factor: the slope must hold at lo, fail at hi")
        .shown("{1, 3}"),
    arg::number("tolerance", "", "the bisection ends when the bracket is no wider (on the SRF)")
        .in(open_closed(0, 1))
        .def(kDefaults.tolerance),
    arg::number("damping", "", "local damping coefficient alpha of every trial")
        .in(closed_open(0, 1))
        .def(kDefaults.damping),
    arg::number("equilibrium", "", "tolerance of both equilibrium ratios (as m:gravity_phase's tolerance)")
        .in(closed_open(1e-12, 1))
        .def(kDefaults.equilibrium),
    arg::number("max_time", "s", "simulated time a trial may take to reach equilibrium; later it fails")
        .in(above(0))
        .def(kDefaults.max_time),
    arg::number("max_displacement", "m", "a trial in which a deformable particle moves farther fails (a slide)")
        .in(above(0))
        .shown("a tenth of the deformable bodies' height"),
    arg::boolean("write", false,
                 "write the end of the failing trial at the smallest SRF (the mechanism: displacement field) as "
                 "strength_reduction_mechanism.vtu into the output directory (m:output's, else --out)"),
};

void read_bracket(lua_State* L, const Args& a, StrengthReductionSettings& s) {
  if (!a.has("srf")) return;
  a.push("srf");
  if (!lua_istable(L, -1) || lua_rawlen(L, -1) != 2) throw Error("key 'srf' must be {lo, hi}, two numbers");
  lua_rawgeti(L, -1, 1);
  lua_rawgeti(L, -2, 2);
  if (!lua_isnumber(L, -2) || !lua_isnumber(L, -1)) throw Error("key 'srf' must be {lo, hi}, two numbers");
  s.srf_low = lua_tonumber(L, -2);
  s.srf_high = lua_tonumber(L, -1);
  lua_pop(L, 3);
  if (!(s.srf_low > 0 && std::isfinite(s.srf_low) && s.srf_high > s.srf_low && std::isfinite(s.srf_high)))
    throw Error("key 'srf' must be {lo, hi} with 0 < lo < hi");
}

// The directory the mechanism goes into: the model's output directory, else the --out one.
std::string output_directory(lua_State* L, const ModelHandle& h) {
  if (const auto* output = h.simulation.output()) return output->settings().dir;
  const std::string dir = session(L).output_dir("");
  if (dir.empty()) throw Error("key 'write': no output directory: call m:output{ dir = ... } first, or run with --out");
  ensure_directory(dir);
  return dir;
}

void set_number(lua_State* L, const char* key, double value) {
  lua_pushnumber(L, value);
  lua_setfield(L, -2, key);
}

void push_trial(lua_State* L, const StrengthReductionTrial& t) {
  lua_createtable(L, 0, 10);
  set_number(L, "srf", t.srf);
  lua_pushboolean(L, t.holds);
  lua_setfield(L, -2, "converged");
  lua_pushstring(L, to_string(t.end));
  lua_setfield(L, -2, "ended");
  set_number(L, "displacement", t.displacement);
  set_number(L, "kinetic_energy", t.kinetic_energy);
  set_number(L, "time", t.time);
  lua_pushinteger(L, t.steps);
  lua_setfield(L, -2, "steps");
  set_number(L, "unbalanced", t.force_ratio);
  set_number(L, "kinetic", t.energy_ratio);
  if (!t.error.empty()) {
    lua_pushstring(L, t.error.c_str());
    lua_setfield(L, -2, "error");
  }
}

void push_result(lua_State* L, const StrengthReductionResult& r) {
  lua_createtable(L, 0, 7);
  set_number(L, "fos", r.fos);
  set_number(L, "holds", r.holds);
  set_number(L, "fails", r.fails);
  set_number(L, "max_displacement", r.max_displacement);
  lua_pushstring(L, strength_reduction_criterion().c_str());
  lua_setfield(L, -2, "criterion");
  lua_createtable(L, static_cast<int>(r.trials.size()), 0);
  for (std::size_t i = 0; i < r.trials.size(); ++i) {
    push_trial(L, r.trials[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "trials");
  if (!r.mechanism_file.empty()) {
    lua_pushstring(L, r.mechanism_file.c_str());
    lua_setfield(L, -2, "file");
  }
}

// m:strength_reduction{ srf = {1, 3}, tolerance = 0.01, damping = 0.7, equilibrium = 1e-3, max_time = 10,
//                       max_displacement, write = false } -> { fos, holds, fails, max_displacement, criterion,
//                       trials = {...}, file }
int model_strength_reduction(lua_State* L) {
  const auto held = self<ModelObject>(L).handle;  // held by the call: see phase_binding.cpp
  ModelHandle& h = *held;
  const Args a(L, 2, kStrengthReductionKeys);
  StrengthReductionSettings s;
  read_bracket(L, a, s);
  s.tolerance = a.number("tolerance");
  s.damping = a.number("damping");
  s.equilibrium = a.number("equilibrium");
  s.max_time = a.number("max_time");
  if (const auto limit = a.optional_number("max_displacement")) s.max_displacement = *limit;
  if (a.boolean("write")) s.mechanism_file = output_directory(L, h) + "/strength_reduction_mechanism.vtu";
  refuse_inside_a_run(L, h, "run a strength reduction");
  Session& session_now = session(L);
  s.progress = session_now.progress;
  s.interrupt = &session_now.interrupted;
  // run_in_session clears the Ctrl-C flag and, when interrupted, the Lua hook.
  const auto r = run_in_session(L, h, [&](Simulation<2>& sim) {
    // The trials are static: edge boundaries hold as in a gravity phase, and let go again after.
    struct Held {
      Simulation<2>& sim;
      explicit Held(Simulation<2>& s) : sim(s) { sim.hold_boundaries(true); }
      ~Held() { sim.hold_boundaries(false); }
    } edges_held(sim);
    return strength_reduction(sim.model(), s);
  });
  push_result(L, r);
  return 1;
}

const Function kStrengthReduction[] = {
    {"model:strength_reduction", &guarded<model_strength_reduction>, nullptr, kStrengthReductionKeys,
     "The factor of safety by strength reduction: damped gravity phases (rigid bodies at rest) on copies of the "
     "model, which stays as it is, each with every Mohr-Coulomb and Drucker-Prager material's c / SRF, tan(phi) / "
     "SRF and tension / SRF (dilation kept, at most the reduced friction angle). The first trial, at srf lo, "
     "starts from the model's state and gives the initial stresses; the others start from its equilibrium. A trial "
     "holds when it reaches static equilibrium (both ratios below `equilibrium`) within max_time with no "
     "deformable particle moving farther than max_displacement; otherwise it fails (the slope keeps moving or "
     "slides). Bisection between lo (must hold) and hi (must fail) until the bracket is no wider than tolerance. "
     "Returns { fos, holds, fails, max_displacement, criterion, trials = { {srf, converged, ended, displacement, "
     "kinetic_energy, time, steps, unbalanced, kinetic}, ... }, file }. See docs/methods.md.",
     "local r = m:strength_reduction{ srf = {1, 2}, tolerance = 0.01, write = true }  print(r.fos, #r.trials)"},
};

}  // namespace

std::span<const Function> strength_reduction_functions() { return kStrengthReduction; }

void open_strength_reduction(lua_State* L) { register_functions(L, kStrengthReduction); }

}  // namespace seismpm::lua
