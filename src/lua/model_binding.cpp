// mpm.model and the model's inspection methods (time, steps, dt, energy, count, bodies). The model's
// other methods: model_building_binding.cpp (bodies, contact, fixities, probes), phase_binding.cpp
// (runs and phases), output_binding.cpp (files and plots).
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

const ModelSettings<2> kKernel;  // the kernel's defaults

const Key kModelKeys[] = {
    arg::custom("domain", "{{x0, y0}, {x1, y1}}", "m", "the lower-left and upper-right corners").required(),
    arg::number("cell", "m",
                "cell size; the grid rounds the domain up to whole cells, at least 2 along x and y (the kernel's rule)")
        .in(above(0))
        .required(),
    arg::choice("shape", "linear|gimp", "gimp", "shape functions: GIMP (generalised interpolation) or linear"),
    arg::choice("scheme", "musl|usl", "musl", "stresses updated after the velocity re-map (MUSL) or before it (USL)"),
    arg::point("gravity", "m/s2", "gravity").def_point(0, -9.81),
    arg::number("cfl", "", "Courant number: the time step is cfl times the cell over the fastest wave")
        .in(open_closed(0, 1))
        .def(kKernel.cfl),
    arg::choice("transfer", "flip|apic", "flip",
                "particle velocity update: FLIP (blended with PIC by flip) or APIC (the grid velocity and its "
                "gradient around the particle: no FLIP noise, no PIC damping of rotation and shear)"),
    arg::number("flip", "", "FLIP share of the particle velocity update (0: PIC)").in(closed(0, 1)).def(kKernel.flip),
    arg::number("dt", "s", "a fixed time step").in(above(0)).shown("from cfl"),
    arg::number("max_dilation", "",
                "largest particle volume as a multiple of its initial one (0: no limit): where cohesionless soil "
                "breaks up, stress-free particles would otherwise swell without bound and shrink the time step")
        .in(zero_or_at_least(1))
        .def(kKernel.max_dilation),
    arg::boolean("cell_volumetric_strain", kKernel.cell_volumetric_strain,
                 "average the volumetric strain increment over each cell (B-bar style, against volumetric locking)"),
    arg::boolean("crack_closure", kKernel.crack_closure,
                 "a tensionless particle looser than its initial density closes that opening first when compressed, "
                 "without raising its mean stress; with `cell_volumetric_strain`, the opening is its cell's (the "
                 "particles' volumes in the cell against their stress-free volumes)"),
    arg::boolean("check_memory", kKernel.check_memory,
                 "refuse a grid or a body whose arrays need more memory than the machine has available now (the "
                 "error gives both figures); false builds it anyway"),
};

// The domain {{x0, y0}, {x1, y1}} of mpm.model's arguments, read raw.
void read_domain(const Args& a, ModelSettings<2>& s) {
  lua_State* L = a.state();
  a.push("domain");
  const int domain = lua_gettop(L);  // left on the stack: it goes when the function returns
  if (!lua_istable(L, domain))
    throw Error("key 'domain' must be {{x0, y0}, {x1, y1}} (m), got " + type_name(L, domain));
  if (lua_rawlen(L, domain) != 2) throw Error("key 'domain' must hold 2 corner points {{x0, y0}, {x1, y1}}");
  lua_rawgeti(L, domain, 1);
  if (lua_istable(L, -1) && lua_rawlen(L, -1) == 3)
    throw Error("3D models are not available from Lua yet (domain has 3 coordinates)");
  s.lower = to_point(L, -1, "domain corner 1");
  lua_rawgeti(L, domain, 2);
  s.upper = to_point(L, -1, "domain corner 2");
  lua_settop(L, domain - 1);
  for (int d = 0; d < 2; ++d)
    if (!(s.upper[d] > s.lower[d]))
      throw Error("key 'domain' is empty: the second corner must be above and right of the first, got " +
                  point_text(s.lower) + " to " + point_text(s.upper));
}

// mpm.model{ domain, cell, ... }. The kernel (Grid, Model) checks that the domain spans 2 cells.
int model_new(lua_State* L) {
  const Args a(L, 1, kModelKeys);
  ModelSettings<2> s;
  read_domain(a, s);
  s.cell = a.number("cell");
  s.shape = a.choice("shape") == "linear" ? ShapeKind::Linear : ShapeKind::Gimp;
  s.scheme = a.choice("scheme") == "usl" ? Scheme::Usl : Scheme::Musl;
  s.gravity = a.point("gravity");
  s.cfl = a.number("cfl");
  s.transfer = a.choice("transfer") == "apic" ? Transfer::Apic : Transfer::Flip;
  s.flip = a.number("flip");
  if (auto dt = a.optional_number("dt")) s.fixed_dt = *dt;
  s.max_dilation = a.number("max_dilation");
  s.cell_volumetric_strain = a.boolean("cell_volumetric_strain");
  s.crack_closure = a.boolean("crack_closure");
  s.check_memory = a.boolean("check_memory");
  auto handle = std::make_shared<ModelHandle>(s);
  push_object(L, ModelObject{std::move(handle)});
  return 1;
}

const Model<2>& model_of(lua_State* L) { return self<ModelObject>(L).handle->model; }

int model_tostring(lua_State* L) {
  const auto& m = model_of(L);
  std::ostringstream os;
  os << "model: " << m.grid().domain_cells(0) << " x " << m.grid().domain_cells(1) << " cells of " << m.grid().cell()
     << " m, " << m.bodies().size() << " bodies, " << m.particles().size() << " particles, t = " << m.time() << " s";
  lua_pushstring(L, os.str().c_str());
  return 1;
}

int model_time(lua_State* L) {
  lua_pushnumber(L, model_of(L).time());
  return 1;
}

int model_steps(lua_State* L) {
  lua_pushinteger(L, model_of(L).steps());
  return 1;
}

int model_dt(lua_State* L) {
  const auto& m = model_of(L);
  // Before the first step: the step the CFL condition would take now.
  lua_pushnumber(L, m.steps() > 0 ? m.dt() : (m.particles().size() ? m.stable_time_step() : 0.0));
  return 1;
}

int model_energy(lua_State* L) {
  const auto& m = model_of(L);
  lua_createtable(L, 0, 2);
  lua_pushnumber(L, m.kinetic_energy());
  lua_setfield(L, -2, "kinetic");
  lua_pushnumber(L, m.strain_energy());
  lua_setfield(L, -2, "strain");
  return 1;
}

int model_count(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(model_of(L).particles().size()));
  return 1;
}

int model_bodies(lua_State* L) {
  const auto& handle = self<ModelObject>(L).handle;
  lua_newtable(L);
  for (std::size_t b = 0; b < handle->model.bodies().size(); ++b) {
    push_object(L, BodyObject{handle, static_cast<int>(b)});
    lua_setfield(L, -2, handle->model.bodies()[b].name.c_str());
  }
  return 1;
}

// The names of the material indices, as a list: entry k + 1 names index k.
int model_materials(lua_State* L) {
  const auto& m = model_of(L);
  lua_createtable(L, m.material_count(), 0);
  for (int k = 0; k < m.material_count(); ++k) {
    lua_pushstring(L, m.material_name(k).c_str());
    lua_rawseti(L, -2, k + 1);
  }
  return 1;
}

const Function kModel[] = {
    {"mpm.model", &guarded<model_new>, nullptr, kModelKeys, "Creates a 2D plane-strain model on a background grid.",
     "local m = mpm.model{ domain = {{0, 0}, {1, 0.6}}, cell = 0.01, shape = \"gimp\" }"},
    {"model:time", &guarded<model_time>, "m:time()", {}, "Simulated time (s), total across phases.", "print(m:time())"},
    {"model:steps", &guarded<model_steps>, "m:steps()", {}, "Number of steps taken.", "print(m:steps())"},
    {"model:dt",
     &guarded<model_dt>,
     "m:dt()",
     {},
     "The last time step (s), or the one the CFL condition allows before the first step.",
     "print(m:dt())"},
    {"model:energy",
     &guarded<model_energy>,
     "m:energy()",
     {},
     "Kinetic and elastic strain energy (J per metre out of plane) as a table { kinetic =, strain = }.",
     "local e = m:energy(); print(e.kinetic, e.strain)"},
    {"model:count", &guarded<model_count>, "m:count()", {}, "Number of particles in the model.", "print(m:count())"},
    {"model:bodies",
     &guarded<model_bodies>,
     "m:bodies()",
     {},
     "The bodies as a table by name.",
     "for name, b in pairs(m:bodies()) do print(name, b:count()) end"},
    {"model:materials",
     &guarded<model_materials>,
     "m:materials()",
     {},
     "The materials' names (key name of mpm.material.*, else the kind; a rigid body's stand-in is \"rigid "
     "<body>\") as a list in index order: entry k + 1 names the material index k that the particle field "
     "material holds (the .vtu files carry the same list as material_names).",
     "for k, name in ipairs(m:materials()) do print(k - 1, name) end"},
};

}  // namespace

std::span<const Function> model_functions() { return kModel; }

void open_model(lua_State* L) { open_type<ModelObject, model_tostring>(L, kModel); }

}  // namespace seismpm::lua
