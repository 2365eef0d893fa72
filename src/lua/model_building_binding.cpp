// Building a model: m:body, m:rigid, m:contact, m:set_friction, m:fix, m:boundary, m:probe.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "core/body_overlap.hpp"
#include "core/format.hpp"
#include "input_checks.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

// A body made over another puts twice the mass in their common space: a warning naming both, since a
// rigid body may be laid into soil on purpose.
void warn_overlaps(lua_State* L, ModelHandle& h, int body, std::shared_ptr<const Region> shape) {
  h.body_shapes.resize(h.model.bodies().size());
  h.body_shapes[body] = std::move(shape);
  std::vector<const Region*> shapes;
  for (const auto& s : h.body_shapes) shapes.push_back(s.get());
  const auto& bodies = h.model.bodies();
  for (const auto& o : overlaps_of_body(h.model.particles(), shapes, body)) {
    if (bodies[body].rigid && bodies[o.body].rigid) continue;  // prescribed motion: their masses do not act
    warn(L, "body '" + bodies[body].name + "' overlaps body '" + bodies[o.body].name +
                "': " + std::to_string(o.particles) + " of its particles lie inside the shape of '" +
                bodies[o.body].name + "' (the first at " + point_text(o.first) +
                "), where the two put twice the mass; trim one shape so they only touch");
  }
}

// The kernel's range (Model::new_body refuses the rest).
const Key kPpc = arg::integer("ppc", "particles per cell along each axis").in(closed(1, kMaxParticlesPerCell)).def(2);
const Key kShape = arg::custom("shape", "mpm.shape.*", "", "the region filled, inside the domain").required();

const Key kRegionKeys[] = {
    arg::custom("shape", "mpm.shape.*", "", "where the material applies (it may reach beyond the body)").required(),
    arg::object("material", kMaterialType, "the material of the body's particles inside the shape").required(),
    arg::string("name", "names the region in messages").shown("regionN"),
};
const Key kBodyKeys[] = {
    arg::string("name", "the body's name, unique in the model").shown("bodyN"),
    arg::object("material", kMaterialType, "its material (mpm.material.*); with regions, that of particles in none")
        .shown("required without regions"),
    kShape,
    kPpc,
    arg::custom("regions", "{ {shape =, material =, name =}, ... }", "",
                "materials inside the body: each particle takes the material of the last region whose shape holds "
                "it (mpm.geometry.layers makes a list)"),
};
const Key kRigidKeys[] = {
    arg::string("name", "the body's name, unique in the model").shown("rigidN"),
    kShape,
    kPpc,
    arg::custom("velocity", "{vx, vy}: numbers or histories", "m/s", "the velocity it follows, read at the phase time")
        .shown("{0, 0}"),
    arg::number("density", "kg/m3", "only gives the particles a mass to show").in(above(0)).def(7850),
};
const Key kContactKeys[] = {
    arg::positional("body_a, body_b", "the two bodies (not both rigid)"),
    arg::number("friction", "", "Coulomb coefficient mu: 0 smooth, 1 rough").in(at_least(0)).required(),
};
const Key kFixKeys[] = {
    arg::choice("side", "left|right|bottom|top", nullptr, "the edge of the domain"),
    arg::choice("dof", "x|y|xy", "xy", "the velocity components held"),
};
const Key kBoundaryKeys[] = {
    arg::choice("side", "left|right|bottom|top", nullptr, "the edge of the domain"),
    arg::choice("kind", "absorbing|compliant|free_field", nullptr,
                "absorbing: dashpots rho Vp (normal), rho Vs (along); compliant: the elastic half-space below, "
                "with the outcrop motion coming in; free_field: a side that follows a 1D column of the soil next "
                "to it"),
    arg::custom("input", "{vx, vy}: numbers or histories", "m/s",
                "compliant: the OUTCROP velocity (a record on rock at the surface, twice the incident wave), read "
                "at the phase time")
        .shown("{0, 0}"),
    arg::choice("frame", "outcrop|fixed", "outcrop",
                "compliant with an input: outcrop computes the model relative to the outcrop motion (its "
                "acceleration a body force; ux, vx are relative to it, and a record may carry the ground metres "
                "without leaving the grid), fixed in the grid's frame (absolute motion, for small ones)"),
    arg::number("density", "kg/m3", "of the medium beyond the edge (compliant: required)")
        .in(above(0))
        .shown("the soil next to the edge"),
    arg::number("vs", "m/s", "its shear-wave speed").in(above(0)).shown("the soil next to the edge"),
    arg::number("vp", "m/s", "its p-wave speed (> vs)").in(above(0)).shown("the soil next to the edge"),
};
const Key kProbeKeys[] = {
    arg::string("name", "the probe's name, unique in the model").shown("probeN"),
    arg::object("body", kBodyType, "the body whose particle it follows").required(),
    arg::point("at", "m", "the particle of the body nearest to it is followed (within one cell of the body)")
        .required(),
    arg::number("every", "s",
                "sampling interval of simulated time (0: every step); one shorter than the time step is refused "
                "when a run starts")
        .in(at_least(0))
        .def(0.01),
    arg::custom("relative_to", "a probe or a body", "",
                "also record the displacement relative to it: ux_rel, uy_rel (another probe's particle; a body's "
                "mass-weighted centroid, a rigid body's own displacement; like ux, since the particles were made or "
                "the gravity phase's reset)")
        .shown("none"),
};

// The shape under key 'shape', checked to lie in the model's domain.
std::shared_ptr<const Region> shape_argument(const Args& a, const ModelHandle& h) {
  auto region = object_argument<ShapeObject>(a, "shape").region;
  const auto& g = h.model.grid();
  const double tol = 1e-9 * g.cell();
  const Vec<2> lo = g.domain_lower(), hi = g.domain_upper();
  if ((region->lower().array() < lo.array() - tol).any() || (region->upper().array() > hi.array() + tol).any())
    throw Error("key 'shape': " + region->describe() + " reaches outside the domain " + point_text(lo) + " to " +
                point_text(hi));
  return region;
}

std::string body_name_argument(const Args& a, const ModelHandle& h, const char* stem) {
  const std::string name = a.string("name", stem + std::to_string(h.model.bodies().size() + 1));
  for (const auto& b : h.model.bodies())
    if (b.name == name) throw Error("key 'name': a body called '" + name + "' exists already");
  return name;
}

using MaterialAt = std::function<int(const Vec<2>&)>;

void fill_region(ModelHandle& h, int body, const MaterialAt& material_at, const Region& region, int ppc) {
  const std::size_t added = h.model.fill(
      body, material_at, region.lower(), region.upper(), [&](const Vec<2>& x) { return region.contains(x); },
      [&](const Vec<2>& x) { return region.outward_normal(x); });
  if (added == 0)
    throw Error("key 'shape': " + region.describe() + " holds no particle at ppc = " + std::to_string(ppc) +
                " (smaller than a particle spacing of " + std::to_string(h.model.grid().cell() / ppc) + " m?)");
}

struct MaterialRegion {
  std::string name;
  std::shared_ptr<const Region> shape;
  int material;
  std::size_t particles = 0;  // of the body that took its material
};

// The list under key 'regions' (none when absent), each entry checked against kRegionKeys.
std::vector<MaterialRegion> regions_argument(const Args& a, ModelHandle& h) {
  std::vector<MaterialRegion> regions;
  if (!a.has("regions")) return regions;
  lua_State* L = a.state();
  a.push("regions");
  const int list = lua_gettop(L);
  const lua_Integer n = lua_istable(L, list) ? static_cast<lua_Integer>(lua_rawlen(L, list)) : 0;
  if (n == 0)
    throw Error("key 'regions' must be a list { {shape =, material =}, ... } of at least one region, got " +
                type_name(L, list));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, list, i);
    const std::string where = "regions[" + std::to_string(i) + "]";
    const Args r(L, -1, kRegionKeys, where.c_str());
    const std::string name = r.string("name", "region" + std::to_string(i));
    regions.push_back({name, object_argument<ShapeObject>(r, "shape").region,
                       h.material(object_argument<MaterialObject>(r, "material"))});
    lua_pop(L, 1);
  }
  lua_pop(L, 1);  // the argument table keeps the list alive
  return regions;
}

// The material of a particle at x: the last region holding it, else the body's own (-1: none, an error).
MaterialAt material_chooser(std::vector<MaterialRegion>& regions, int fallback, const std::string& body) {
  return [&regions, fallback, body](const Vec<2>& x) {
    for (auto r = regions.rbegin(); r != regions.rend(); ++r)
      if (r->shape->contains(x)) return ++r->particles, r->material;
    if (fallback < 0)
      throw Error("body '" + body + "': the particle at " + point_text(x) +
                  " lies in none of its regions, and the body has no material of its own (key 'material')");
    return fallback;
  };
}

// Before the body exists: every particle has a material, and every region gives its material to some.
void check_regions(const ModelHandle& h, std::vector<MaterialRegion>& regions, const MaterialAt& material_at,
                   const Region& shape, int ppc, const std::string& body) {
  if (regions.empty()) return;
  for (const Vec<2>& x :
       h.model.fill_points(ppc, shape.lower(), shape.upper(), [&](const Vec<2>& x) { return shape.contains(x); }))
    material_at(x);
  for (auto& r : regions) {
    if (r.particles == 0)
      throw Error("body '" + body + "': region '" + r.name + "' (" + r.shape->describe() +
                  ") gives none of its particles its material: outside the body, thinner than the particle "
                  "spacing, or covered by later regions?");
    r.particles = 0;
  }
}

int model_body(lua_State* L) {
  const auto handle = self<ModelObject>(L).handle;
  ModelHandle& h = *handle;
  refuse_building(L, h, "add a body");
  const Args a(L, 2, kBodyKeys);
  const std::string name = body_name_argument(a, h, "body");
  if (!a.has("material") && !a.has("regions"))
    throw Error("key 'material' must be a material, got nil (or give regions = { ... })");
  const int material = a.has("material") ? h.material(object_argument<MaterialObject>(a, "material")) : -1;
  auto regions = regions_argument(a, h);
  const int ppc = a.integer("ppc");
  const auto region = shape_argument(a, h);
  const MaterialAt material_at = material_chooser(regions, material, name);
  check_regions(h, regions, material_at, *region, ppc, name);
  const int body = h.model.add_body(name, ppc);
  fill_region(h, body, material_at, *region, ppc);
  warn_overlaps(L, h, body, region);
  push_object(L, BodyObject{handle, body});
  return 1;
}

// m:rigid{ name, shape, ppc, velocity = {vx, vy}, density }
int model_rigid(lua_State* L) {
  const auto handle = self<ModelObject>(L).handle;
  ModelHandle& h = *handle;
  refuse_building(L, h, "add a rigid body");
  const Args a(L, 2, kRigidKeys);
  const std::string name = body_name_argument(a, h, "rigid");
  const int ppc = a.integer("ppc");
  const double density = a.number("density");
  a.push("velocity");
  const auto velocity = rigid_velocity(L, -1, "key 'velocity'");
  lua_pop(L, 1);
  const auto region = shape_argument(a, h);
  const int body = h.model.add_rigid_body(name, ppc, density, velocity);
  fill_region(
      h, body, [](const Vec<2>&) { return -1; }, *region, ppc);  // a rigid body has its own
  warn_overlaps(L, h, body, region);
  push_object(L, BodyObject{handle, body});
  return 1;
}

// The two bodies of m:contact{ a, b, ... } and m:set_friction{ a, b, ... }.
std::array<int, 2> body_pair(const Args& a, const std::shared_ptr<ModelHandle>& handle, const char* usage) {
  lua_State* L = a.state();
  if (a.length() != 2) throw Error(std::string("name the two bodies: ") + usage);
  std::array<int, 2> body{};
  for (int k = 0; k < 2; ++k) {
    lua_rawgeti(L, a.index(), k + 1);
    const auto& b = check_object<BodyObject>(L, -1, k ? "the second body" : "the first body");
    if (b.handle != handle) throw Error(std::string(k ? "the second" : "the first") + " body belongs to another model");
    body[k] = b.body;
    lua_pop(L, 1);
  }
  return body;
}

// m:contact{ body_a, body_b, friction = mu }
int model_contact(lua_State* L) {
  const auto handle = self<ModelObject>(L).handle;
  refuse_building(L, *handle, "declare a contact");
  const Args a(L, 2, kContactKeys);
  const auto body = body_pair(a, handle, "m:contact{ body_a, body_b, friction = mu } (bodies in contact)");
  handle->model.add_contact(body[0], body[1],
                            a.number("friction"));  // names the bodies of a pair declared twice or with itself
  return 0;
}

// m:set_friction{ body_a, body_b, friction = mu }
int model_set_friction(lua_State* L) {
  const auto handle = self<ModelObject>(L).handle;
  refuse_inside_a_step(L, "change a friction");
  const Args a(L, 2, kContactKeys);
  const auto body = body_pair(a, handle, "m:set_friction{ body_a, body_b, friction = mu }");
  handle->model.set_contact_friction(body[0], body[1], a.number("friction"));
  return 0;
}

int model_fix(lua_State* L) {
  ModelHandle& h = *self<ModelObject>(L).handle;
  refuse_building(L, h, "fix an edge");
  const Args a(L, 2, kFixKeys);
  const Side side = parse_side(a.choice("side"), 2);
  for (const auto& b : h.simulation.boundaries())
    if (b->settings().side == side)
      throw Error("key 'side': the " + a.choice("side") + " edge is a boundary (m:boundary, kind " +
                  std::string(boundary_kind_name(b->settings().kind)) + "); an edge is either fixed or a boundary");
  h.model.grid().fix(side, parse_dof(a.choice("dof"), 2));
  return 0;
}

// m:boundary{ side, kind, input = {vx, vy}, density, vs, vp }
int model_boundary(lua_State* L) {
  ModelHandle& h = *self<ModelObject>(L).handle;
  refuse_building(L, h, "add a boundary");
  const Args a(L, 2, kBoundaryKeys);
  BoundarySettings<2> s;
  s.side = parse_side(a.choice("side"), 2);
  s.kind = parse_boundary_kind(a.choice("kind"));
  const int given = a.has("density") + a.has("vs") + a.has("vp");
  const std::string missing = a.has("density") ? (a.has("vs") ? "vp" : "vs") : "density";
  if (s.kind == BoundaryKind::Compliant && given < 3)
    throw Error("key '" + missing + "': a compliant edge needs the half-space below it: density, vs and vp");
  if (given > 0 && given < 3)
    throw Error("key '" + missing + "': give density, vs and vp together, or none (the soil next to the edge)");
  s.density = a.number("density", 0.0);
  s.vs = a.number("vs", 0.0);
  s.vp = a.number("vp", 0.0);
  if (given == 3 && !(s.vp > s.vs)) throw Error("key 'vp': it must exceed vs");
  s.moving_frame = a.choice("frame") == "outcrop";
  if (a.has("frame") && s.kind != BoundaryKind::Compliant)
    throw Error("key 'frame': only a compliant edge moves the frame (kind = \"compliant\")");
  if (a.has("input")) {
    if (s.kind != BoundaryKind::Compliant)
      throw Error("key 'input': only a compliant edge takes an input motion (kind = \"compliant\")");
    a.push("input");
    s.input = rigid_velocity(L, -1, "key 'input'");
    lua_pop(L, 1);
  }
  h.simulation.add_boundary(s);
  return 0;
}

// The reference under key 'relative_to' (none when absent): a probe or a body of the same model.
ProbeRelativeTo relative_to(const Args& a, const std::shared_ptr<ModelHandle>& handle) {
  ProbeRelativeTo r;
  if (!a.has("relative_to")) return r;
  lua_State* L = a.state();
  a.push("relative_to");
  const ProbeObject* probe = nullptr;
  const BodyObject* body = nullptr;
  try {
    probe = test_object<ProbeObject>(L, -1);
    body = probe ? nullptr : test_object<BodyObject>(L, -1);
  } catch (const Error& e) {  // an object whose __gc ran
    throw Error(std::string("key 'relative_to': ") + e.what());
  }
  if (!probe && !body) {
    const std::string type = type_name(L, -1);
    lua_pop(L, 1);
    throw Error("key 'relative_to' must be a probe or a body, got " + type);
  }
  lua_pop(L, 1);  // the argument table keeps the userdata alive
  if ((probe ? probe->handle : body->handle) != handle) throw Error("key 'relative_to' belongs to another model");
  if (probe) {
    r.kind = ProbeRelativeTo::Kind::Particle;
    r.index = probe->probe->particle_id();
    r.what = "probe '" + std::string(probe->probe->name()) + "'";
  } else {
    r.kind = ProbeRelativeTo::Kind::Body;
    r.index = body->body;
    r.what = "body '" + handle->model.bodies()[body->body].name + "'";
    const auto& P = handle->model.particles();
    if (std::find(P.body.begin(), P.body.end(), body->body) == P.body.end())
      throw Error("key 'relative_to': body '" + handle->model.bodies()[body->body].name + "' has no particles");
  }
  return r;
}

int model_probe(lua_State* L) {
  const auto handle = self<ModelObject>(L).handle;
  refuse_building(L, *handle, "add a probe");
  const Args a(L, 2, kProbeKeys);
  Simulation<2>& sim = handle->simulation;
  const std::string name = a.string("name", "probe" + std::to_string(sim.probes().size() + 1));
  for (const auto& p : sim.probes())
    if (std::string(p->name()) == name) throw Error("key 'name': a probe called '" + name + "' exists already");
  const auto& of = object_argument<BodyObject>(a, "body");
  if (of.handle != handle) throw Error("key 'body' belongs to another model");
  const int body = of.body;
  const Vec<2> at = a.point("at");
  // The particle of the body nearest to `at`.
  const auto& p = handle->model.particles();
  double best = INFINITY;
  std::size_t nearest = p.size();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body[i] == body && (p.x[i] - at).norm() < best) best = (p.x[i] - at).norm(), nearest = i;
  if (nearest == p.size()) throw Error("key 'body' has no particles");
  // A point outside the body would silently follow whatever particle is nearest, however far.
  const double cell = handle->model.grid().cell();
  if (best > cell)
    throw Error("key 'at': " + point_text(at) + " is " + format_number(best, 4) +
                " m from the nearest particle of body '" + handle->model.bodies()[body].name + "', at " +
                point_text(p.x[nearest]) + "; a probe must lie within one cell (" + format_number(cell, 4) +
                " m) of its body");
  push_object(L, ProbeObject{handle, sim.add_probe(name, p.id[nearest], a.number("every"), relative_to(a, handle))});
  return 1;
}

const Function kBuilding[] = {
    {"model:body", &guarded<model_body>, nullptr, kBodyKeys,
     "Fills a shape with particles of a material and returns the body. With regions, one body holds several "
     "materials (layered ground without interfaces): each particle takes the material of the last region whose "
     "shape contains it, else the body's material; the particle field material and the .vtu files' "
     "material_names show which.",
     "local soil = m:body{ name = \"soil\", material = sand, shape = mpm.shape.rectangle{0, 0, 1, 0.5}, ppc = 2, "
     "regions = { { shape = mpm.shape.rectangle{0, 0, 1, 0.2}, material = clay } } }"},
    {"model:rigid", &guarded<model_rigid>, nullptr, kRigidKeys,
     "A rigid body of prescribed-velocity particles (a shaking-table box, the surface under a landslide): fills the "
     "shape (rectangle, polygon, or polyline with a thickness) and returns the body. Each step the nodes of the "
     "cells holding its particles take their volume-weighted velocity (the paper's Eq. 9); the soil sees it through "
     "m:contact, or, with no contact declared, moves with it (no slip). Written to rigid_NNNNNN.vtu; b:reaction() "
     "gives its force on the soil. For an inclined sliding surface use a one-sided polyline band (side = \"left\" | "
     "\"right\"): its particles carry the line's normal, so contact follows the true surface rather than the grid's "
     "staircase of cells. Make a rigid body at least one cell thick.",
     "local base = m:rigid{ name = \"base\", shape = mpm.shape.rectangle{-2.5, -0.1, 2.0, 0}, ppc = 1, "
     "velocity = {vx, 0} }"},
    {"model:contact", &guarded<model_contact>, nullptr, kContactKeys,
     "Frictional contact between two bodies (Bardenhagen): where they meet they may slide with Coulomb friction and "
     "separate freely; they never interpenetrate. Without m:contact bodies share one velocity field where they meet "
     "(no slip, no separation). One declaration per pair.",
     "m:contact{ block, base, friction = 0.3 }"},
    {"model:set_friction", &guarded<model_set_friction>, nullptr, kContactKeys,
     "Changes the Coulomb coefficient of a declared contact pair from the next step on: a peak value for the "
     "gravity phase, a residual one once shaking has broken the interface.",
     "m:set_friction{ rock, bedding, friction = 0.2 }"},
    {"model:fix", &guarded<model_fix>, nullptr, kFixKeys, "Holds the grid nodes on one edge of the domain.",
     "m:fix{ side = \"bottom\", dof = \"xy\" }; m:fix{ side = \"left\", dof = \"x\" }"},
    {"model:boundary", &guarded<model_boundary>, nullptr, kBoundaryKeys,
     "Makes a grid edge stand for the ground beyond the model. absorbing: viscous (Lysmer-Kuhlemeyer) dashpots, "
     "rho Vp normal and rho Vs along the edge, from the soil next to it unless density, vs, vp are given: waves "
     "leave. compliant: the base on an elastic half-space (density, vs, vp required) with the OUTCROP velocity "
     "`input` coming in: the traction rho_r Vs_r (vx_in - v) along and rho_r Vp_r (vy_in - v) normal, so the "
     "incident wave enters and the reflected one leaves. free_field (left, right): the side follows a 1D elastic "
     "column of the soil next to it (its layering, on the base's boundary), with dashpots for what the slope "
     "radiates. While a gravity phase runs the edge holds like m:fix (the base in x and y, a side in its normal); "
     "the force it carried stays as a constant force afterwards, so the ground neither sinks nor jumps when "
     "shaking starts. Acts in every dynamic phase and in m:run. An edge is either fixed or a boundary.",
     "m:boundary{ side = \"bottom\", kind = \"compliant\", input = { vx, 0 }, density = 2400, vs = 800, vp = 1390 }; "
     "m:boundary{ side = \"left\", kind = \"free_field\" }"},
    {"model:probe", &guarded<model_probe>, nullptr, kProbeKeys,
     "A control point: follows a particle of the body and records all its fields every `every` seconds of "
     "simulated time and at the end of each run, with the phase and the time since it began (probes.csv: time (s), "
     "phase, phase_time (s), then NAME.FIELD). With relative_to (another probe, or a body), it also records its "
     "displacement less the reference's: NAME.ux_rel, NAME.uy_rel, p:get(\"ux_rel\"), p:series(\"ux_rel\") (the "
     "permanent displacement of a crest relative to the slope's base).",
     "local base = m:probe{ name = \"toe\", body = soil, at = {0.1, 0.0} }; "
     "local p1 = m:probe{ name = \"crest\", body = soil, at = {0.3, 0.5}, relative_to = base }"},
};

}  // namespace

// The velocity of a rigid body at `index`: {vx, vy}, each a number (m/s) or a history (read raw).
std::array<std::shared_ptr<const History>, 2> rigid_velocity(lua_State* L, int index, const std::string& what) {
  index = lua_absindex(L, index);
  std::array<std::shared_ptr<const History>, 2> v;
  if (lua_isnil(L, index)) {
    v.fill(std::make_shared<ConstantHistory>(0.0));
    return v;
  }
  if (!lua_istable(L, index) || lua_rawlen(L, index) != 2)
    throw Error(what + " must be {vx, vy}: two numbers (m/s) or histories, got " + type_name(L, index));
  for (int d = 0; d < 2; ++d) {
    lua_rawgeti(L, index, d + 1);
    v[d] = to_history(L, -1, what + (d ? " vy" : " vx"));
    lua_pop(L, 1);
  }
  return v;
}

std::span<const Function> model_building_functions() { return kBuilding; }

void open_model_building(lua_State* L) { register_functions(L, kBuilding); }

}  // namespace seismpm::lua
