// Checkpoints and restarts: m:checkpoint{ file } and mpm.restart{ file, histories }. What a checkpoint
// holds is the run layer's (src/run/checkpoint.hpp); the periodic one is m:output{ checkpoint_every }.
#include "api_docs.hpp"
#include "binding.hpp"
#include "objects.hpp"
#include "run/checkpoint.hpp"
#include "sandbox.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

const Key kCheckpointKeys[] = {
    arg::string("file", "the checkpoint file, written whole or not at all").required(),
};
const Key kRestartKeys[] = {
    arg::string("file",
                "the checkpoint file; a relative one not found from the current directory is looked for next to "
                "the script")
        .required(),
    arg::custom("histories", "{ [\"<rigid body>.vx\"] = h, ... }", "",
                "histories to use instead of the saved ones, by key \"<body>.vx\" / \"<body>.vy\": required for "
                "those made by Lua functions (mpm.history.fn), which a checkpoint cannot hold"),
};

// m:checkpoint{ file }
int model_checkpoint(lua_State* L) {
  ModelHandle& h = *self<ModelObject>(L).handle;
  const Args a(L, 2, kCheckpointKeys);
  const std::string file = a.string("file");
  if (file.empty()) throw Error("key 'file' is empty");
  // A run's call is in the middle of a run, which a restart could not take up where the call left it.
  refuse_inside_a_run(L, h, "write a checkpoint (m:output{ checkpoint_every } writes them during runs)");
  check_writable(L, file, "key 'file'");
  write_checkpoint(h.simulation, file);
  return 0;
}

// The table under key 'histories' as supplied histories (numbers or mpm.history.* by string keys).
SuppliedHistories histories_argument(const Args& a) {
  SuppliedHistories out;
  if (!a.has("histories")) return out;
  lua_State* L = a.state();
  a.push("histories");
  const int table = lua_gettop(L);
  if (!lua_istable(L, table))
    throw Error("key 'histories' must be a table { [\"<body>.vx\"] = h, ... }, got " + type_name(L, table));
  lua_pushnil(L);
  while (lua_next(L, table) != 0) {
    if (lua_type(L, -2) != LUA_TSTRING)
      throw Error("key 'histories': its keys are strings \"<rigid body>.vx\" or \"<rigid body>.vy\", got " +
                  type_name(L, -2));
    const std::string key = lua_tostring(L, -2);
    out[key] = to_history(L, -1, "histories[\"" + key + "\"]");
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return out;
}

// mpm.restart{ file, histories } -> the model
int restart(lua_State* L) {
  const Args a(L, 1, kRestartKeys);
  const std::string file = data_path(L, a.string("file"));
  check_readable(L, file, "key 'file'");
  const SuppliedHistories histories = histories_argument(a);
  const CheckpointReader checkpoint(file);
  // The restore creates, locks and rewrites files in the checkpoint's output directory: a checkpoint
  // is data, and under --sandbox the directory it names must be one the run may write to.
  if (const auto dir = checkpoint_output_dir(checkpoint)) check_output_dir(L, *dir, "checkpoint's output");
  auto handle = std::make_shared<ModelHandle>(checkpoint_settings<2>(checkpoint));
  restore_checkpoint(checkpoint, handle->simulation, histories);
  if (const Output<2>* output = handle->simulation.output()) allow_writes_under(L, output->settings().dir);
  push_object(L, ModelObject{std::move(handle)});
  return 1;
}

const Function kCheckpoint[] = {
    {"model:checkpoint", &guarded<model_checkpoint>, nullptr, kCheckpointKeys,
     "Writes the model's whole state to a checkpoint file (docs/checkpoint.md): particles with every field, "
     "materials with their plastic state, bodies, rigid bodies with their velocity histories, contacts, fixities, "
     "probes with their samples, the output directory with the files written so far and the next output time, "
     "the phase with its clock and damping. Written atomically (a temporary file, flushed, then renamed), so a "
     "previous checkpoint stays valid until the new one replaces it. Not from inside a run's call: "
     "m:output{ checkpoint_every } writes checkpoints during runs.",
     "m:checkpoint{ file = \"out/after_gravity.chk\" }"},
    {"mpm.restart", &guarded<restart>, nullptr, kRestartKeys,
     "The model as a checkpoint saved it (its bodies through m:bodies(); its output directory as it was at the "
     "checkpoint: files listed later are dropped from the .pvd lists and probes.csv). m:run{ duration } continues "
     "the current phase; a checkpoint written during a run (checkpoint_every) restores that run unfinished, and "
     "m:run{} without duration finishes it exactly as the uninterrupted run would have (a gravity phase to "
     "equilibrium, with its reset; a run with a call needs the call again). Histories made by Lua functions must "
     "be given again under histories.",
     "local m = mpm.restart{ file = \"out/slope/checkpoint.chk\", histories = { [\"base.vx\"] = vx } }; m:run{}"},
};

}  // namespace

std::span<const Function> checkpoint_functions() { return kCheckpoint; }

void open_checkpoint(lua_State* L) { register_functions(L, kCheckpoint); }

}  // namespace seismpm::lua
