// The C++ objects behind Lua's userdata types, shared by the binding files.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "binding.hpp"
#include "core/history.hpp"
#include "core/local_damping.hpp"
#include "core/material.hpp"
#include "core/model.hpp"
#include "core/probe.hpp"
#include "core/region.hpp"
#include "io/output.hpp"

namespace seismpm::lua {

inline constexpr const char* kModelType = "model";
inline constexpr const char* kBodyType = "body";
inline constexpr const char* kProbeType = "probe";
inline constexpr const char* kMaterialType = "material";
inline constexpr const char* kShapeType = "shape";
inline constexpr const char* kHistoryType = "history";

// A model with what the Lua side adds to it: probes, the materials it knows, the damping fix.
struct ModelHandle {
  explicit ModelHandle(const ModelSettings<2>& s) : model(s) {}
  Model<2> model;
  std::vector<std::shared_ptr<Probe<2>>> probes;
  std::map<const Material*, int> material_index;
  std::shared_ptr<LocalDamping<2>> damping;
  std::unique_ptr<Output<2>> output;
  std::string phase = "run";
  bool write_at_run_end = true;  // m:output{ at_run_end }: the state at the end of every run on file
  bool running = false;          // a run is stepping: its call may not start another

  int material(const std::shared_ptr<const Material>& m) {
    auto it = material_index.find(m.get());
    if (it != material_index.end()) return it->second;
    const int index = model.add_material(m);
    material_index[m.get()] = index;
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
struct MaterialObject {
  std::shared_ptr<const Material> material;
  std::string summary;
};
struct ShapeObject {
  std::shared_ptr<const Region> region;
};
struct HistoryObject {
  std::shared_ptr<const History> history;
};

// Registration of each object's functions and methods into the `mpm` table at `mpm`.
void open_model(lua_State* L, int mpm);
void open_body(lua_State* L);
void open_probe(lua_State* L);
void open_material(lua_State* L, int mpm);
void open_shape(lua_State* L, int mpm);
void open_history(lua_State* L, int mpm);
void open_help(lua_State* L, int mpm);
void open_phases(lua_State* L);
void open_plot(lua_State* L, int mpm);

// A Lua function that a run calls every `every` seconds of simulated time and at its end
// (m:run{ every, call }, m:dynamic_phase{ every, call }); the run stops when it returns true.
struct PeriodicCall {
  PeriodicCall() = default;
  // Reads `every` and `call` (both or neither) from a run's arguments.
  explicit PeriodicCall(Args& a);
  ~PeriodicCall();
  PeriodicCall(const PeriodicCall&) = delete;
  PeriodicCall& operator=(const PeriodicCall&) = delete;
  bool active() const { return every > 0; }

  lua_State* state = nullptr;  // set when a function is held
  double every = 0;
  int function = LUA_NOREF;  // a registry reference to the function
};

// Throws when a run is stepping (its call tried to `what`: "step the model", "start a phase"); a
// phase asks before it changes its state.
void refuse_inside_a_run(const ModelHandle& h, const char* what);

// Steps the model for `duration` s (see model_binding.cpp); true when `done` or the call ended the run.
bool run_for(lua_State* L, ModelHandle& h, double duration, long max_steps, bool final_output,
             const std::function<bool()>& done, const std::function<std::string()>& extra,
             const PeriodicCall& call = {});
// The model's local damping fix (created at alpha 0 on first use).
LocalDamping<2>& damping_of(ModelHandle& h);

// {vx, vy} at `index` (numbers or histories; nil: at rest) as a rigid body's velocity.
std::array<std::shared_ptr<const History>, 2> rigid_velocity(lua_State* L, int index, const std::string& what);

// A number or a history at the top of the stack as a history; `what` names it in messages.
std::shared_ptr<const History> to_history(lua_State* L, int index, const std::string& what);

}  // namespace seismpm::lua
