// The simple methods beside MPM: mpm.newmark (Newmark's rigid sliding block on a record).
#include <memory>
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "methods/newmark.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

const Key kNewmarkKeys[] = {
    arg::object("acceleration", kHistoryType,
                "the ground acceleration (m/s2, downslope positive), a tabulated history: "
                "mpm.history.at2{ ..., integrate = \"none\" }, mpm.history.table or mpm.history.csv")
        .required(),
    arg::number("ky", "g", "the yield acceleration of the sliding mass").checked_by_kernel(above(0)).required(),
    arg::choice("direction", "normal|inverse", "normal",
                "normal: the record as it is; inverse: the record times -1 (the slope facing the other way)"),
};

// The table behind the acceleration: the method integrates between the record's own samples.
const TableHistory& acceleration_table(const Args& a) {
  const auto& h = object_argument<HistoryObject>(a, "acceleration");
  const auto* table = dynamic_cast<const TableHistory*>(h.history.get());
  if (!table)
    throw Error("key 'acceleration' must be a tabulated history (mpm.history.at2, .table or .csv), not " +
                h.history->describe());
  return *table;
}

// mpm.newmark{ acceleration, ky, direction = "normal" } -> displacement (m), history of it
int newmark(lua_State* L) {
  const Args a(L, 1, kNewmarkKeys);
  const TableHistory& record = acceleration_table(a);
  const double ky = a.number("ky");
  const std::string direction = a.choice("direction");
  const NewmarkResult r = newmark_rigid_block(record.times(), record.values(), ky, parse_polarity(direction));
  std::ostringstream about;
  about << "Newmark rigid-block displacement (m), ky = " << ky << " g, " << direction << ", on " << record.source();
  lua_pushnumber(L, r.displacement);
  push_object(L, HistoryObject{std::make_shared<TableHistory>(r.times, r.history, about.str())});
  return 2;
}

const Function kMethods[] = {
    {"mpm.newmark", &guarded<newmark>, nullptr, kNewmarkKeys,
     "Newmark's rigid sliding block, one-way (downslope) as SLAMMER's rigid-block method: the block slides while "
     "the ground acceleration exceeds ky g and until its relative velocity is back to zero, never upslope; the "
     "relative acceleration a - ky g is integrated with the trapezoidal rule between the record's samples. "
     "Returns the final permanent displacement (m) and its history (m, at the record's times).",
     "local d, dh = mpm.newmark{ acceleration = mpm.history.at2{ file = \"data/TCU068-E.AT2\", integrate = "
     "\"none\" }, ky = 0.1 }"},
};

}  // namespace

std::span<const Function> methods_functions() { return kMethods; }

void open_methods(lua_State* L) { register_functions(L, kMethods); }

}  // namespace seismpm::lua
