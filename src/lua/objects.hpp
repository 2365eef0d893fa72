// The C++ objects behind Lua's userdata types, shared by the binding files.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "binding.hpp"
#include "core/history.hpp"
#include "core/material.hpp"
#include "core/region.hpp"
#include "run/simulation.hpp"

namespace seismpm::lua {

inline constexpr const char* kModelType = "model";
inline constexpr const char* kBodyType = "body";
inline constexpr const char* kProbeType = "probe";
inline constexpr const char* kMaterialType = "material";
inline constexpr const char* kShapeType = "shape";
inline constexpr const char* kHistoryType = "history";

struct MaterialObject {
  std::shared_ptr<const Material> material;
  std::string summary;
  std::string name;  // "" when none was given
};

// A simulation (the model, its probes, output, damping and runs) with what the Lua side adds to it:
// the materials it knows by their Lua objects.
struct ModelHandle {
  explicit ModelHandle(const ModelSettings<2>& s) : simulation(s) {}
  ModelHandle(const ModelHandle&) = delete;
  ModelHandle& operator=(const ModelHandle&) = delete;
  Simulation<2> simulation;
  Model<2>& model = simulation.model();  // what most bindings build and inspect
  std::map<const Material*, int> material_index;
  // The shape each body was filled from, by body (null where not known), to tell overlapping bodies.
  std::vector<std::shared_ptr<const Region>> body_shapes;

  int material(const MaterialObject& m) {
    auto it = material_index.find(m.material.get());
    if (it != material_index.end()) return it->second;
    const int index = model.add_material(m.material, m.name);
    material_index[m.material.get()] = index;
    return index;
  }
};

struct ModelObject {
  std::shared_ptr<ModelHandle> handle;
};
struct BodyObject {
  std::shared_ptr<ModelHandle> handle;
  int body;
};
struct ProbeObject {
  std::shared_ptr<ModelHandle> handle;
  std::shared_ptr<Probe<2>> probe;
};
struct ShapeObject {
  std::shared_ptr<const Region> region;
};
struct HistoryObject {
  std::shared_ptr<const History> history;
};

// Lua's type name of each object (self<T>, push_object<T>, check_object<T>).
template <>
struct LuaType<ModelObject> {
  static constexpr const char* name = kModelType;
};
template <>
struct LuaType<BodyObject> {
  static constexpr const char* name = kBodyType;
};
template <>
struct LuaType<ProbeObject> {
  static constexpr const char* name = kProbeType;
};
template <>
struct LuaType<MaterialObject> {
  static constexpr const char* name = kMaterialType;
};
template <>
struct LuaType<ShapeObject> {
  static constexpr const char* name = kShapeType;
};
template <>
struct LuaType<HistoryObject> {
  static constexpr const char* name = kHistoryType;
};

// Registration of each binding file's table of functions (open_model first: it makes the model type).
void open_model(lua_State* L);
void open_model_building(lua_State* L);
void open_phases(lua_State* L);
void open_output(lua_State* L);
void open_body(lua_State* L);
void open_probe(lua_State* L);
void open_material(lua_State* L);
void open_shape(lua_State* L);
void open_history(lua_State* L);
void open_methods(lua_State* L);
void open_help(lua_State* L);
void open_plot(lua_State* L);
void open_library_support(lua_State* L);
void open_lem(lua_State* L);
void open_strength_reduction(lua_State* L);
void open_checkpoint(lua_State* L);

// A Lua function that a run calls every `every` seconds of simulated time and at its end
// (m:run{ every, call }, m:dynamic_phase{ every, call }); the run stops when it returns true. Holds a
// registry reference to the function while it lives.
struct PeriodicCall {
  // Reads `every` and `call` (both or neither) from a run's arguments.
  explicit PeriodicCall(const Args& a);
  ~PeriodicCall();
  PeriodicCall(const PeriodicCall&) = delete;
  PeriodicCall& operator=(const PeriodicCall&) = delete;
  // The call as the simulation makes it: the function with the model at stack index 1, through
  // lua_pcall; a Lua error becomes a C++ exception once the Lua stack is clean again.
  RunCall run_call(lua_State* L, const Model<2>& model) const;

  lua_State* state = nullptr;  // set when a function is held
  double every = 0;
  int function = LUA_NOREF;  // a registry reference to the function
};

// What a script may do to a model depends on where it runs (model_guard.cpp). A value function
// (lua_function.hpp: a history function runs inside a step, the kernel halfway through it) may read,
// never change or step a model. A run's
// call runs between steps: it may change what a step reads afresh (friction, velocities) and write
// files, but not rebuild the model (bodies, contacts, fixities, probes, output) nor step it.
//
// Throws when `what` ("step the model", "start a phase") would step the model: inside a value
// function or a run (a phase asks before it changes its state).
void refuse_inside_a_run(lua_State* L, const ModelHandle& h, const char* what);
// Throws when `what` ("add a body") would rebuild the model: inside a value function or a run.
void refuse_building(lua_State* L, const ModelHandle& h, const char* what);
// Throws when `what` ("change a friction") would change a model a step is using: inside a value function.
void refuse_inside_a_step(lua_State* L, const char* what);

// The simulation, ready for a run from this session: its progress display and Ctrl-C flag (cleared
// now). run_in_session(L, h, run) calls run(h.simulation) so; an interrupted run leaves the Lua hook
// cleared too, so that its message survives.
void prepare_run(lua_State* L, ModelHandle& h);
template <class Run>
decltype(auto) run_in_session(lua_State* L, ModelHandle& h, Run&& run) {
  prepare_run(L, h);
  try {
    return run(h.simulation);
  } catch (const RunInterrupted&) {
    lua_sethook(L, nullptr, 0, 0);  // the Ctrl-C hook would replace the message in the error handler
    throw;
  }
}

// {vx, vy} at `index` (numbers or histories; nil: at rest) as a rigid body's velocity.
std::array<std::shared_ptr<const History>, 2> rigid_velocity(lua_State* L, int index, const std::string& what);

// A number or a history at the top of the stack as a history; `what` names it in messages.
std::shared_ptr<const History> to_history(lua_State* L, int index, const std::string& what);

}  // namespace seismpm::lua
