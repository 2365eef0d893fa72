// Where a script may change or step a model (objects.hpp): refused inside a value function (a history
// function, which the kernel evaluates in the middle of a step), and, for what rebuilds the model,
// inside a run.
#include <string>

#include "binding.hpp"
#include "lua_function.hpp"
#include "objects.hpp"

namespace seismpm::lua {

void refuse_inside_a_step(lua_State* L, const char* what) {
  if (inside_a_value_function(L))
    throw Error(std::string("a value function (mpm.history.fn, b:set_velocity(function)) may not ") + what +
                ": it runs while the model is in the middle of a step or an update, and may only compute its value");
}

void refuse_inside_a_run(lua_State* L, const ModelHandle& h, const char* what) {
  refuse_inside_a_step(L, what);
  if (h.simulation.running())
    throw Error(std::string("a run's call may not ") + what +
                " (m:run, m:step or a phase): return true from it to end the run");
}

void refuse_building(lua_State* L, const ModelHandle& h, const char* what) {
  refuse_inside_a_step(L, what);
  if (h.simulation.running())
    throw Error(std::string("a run's call may not ") + what +
                " while the model runs: build the model before the run (the call may sample it, change a "
                "friction or a velocity, or end the run by returning true)");
}

}  // namespace seismpm::lua
