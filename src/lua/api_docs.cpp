#include "api_docs.hpp"

#include <sstream>

namespace seismpm::lua {

const std::vector<ApiDoc>& api_docs() {
  static const std::vector<ApiDoc> docs = {
      // --- module
      {"mpm.model", "mpm.model{ domain, cell, shape, scheme, gravity, cfl, flip, dt, max_dilation }",
       "Creates a 2D plane-strain model on a background grid. domain = {{x0, y0}, {x1, y1}} (m), required; "
       "cell = cell size (m, > 0), required; shape = \"gimp\" (default) | \"linear\"; scheme = \"musl\" (default) | "
       "\"usl\"; gravity = {gx, gy} (m/s2, default {0, -9.81}); cfl = Courant number in (0, 1] (default 0.4); "
       "flip = FLIP share in [0, 1] (default 1, 0 = PIC); dt = fixed time step (s, default: from cfl); "
       "max_dilation = largest particle volume as a multiple of its initial one (default 2; 0: no limit): where "
       "cohesionless soil breaks up, stress-free particles would otherwise swell without bound and shrink the time "
       "step.",
       "local m = mpm.model{ domain = {{0, 0}, {1, 0.6}}, cell = 0.01, shape = \"gimp\" }"},
      {"mpm.material.linear_elastic", "mpm.material.linear_elastic{ density, young, poisson }",
       "Isotropic linear elasticity (plane strain keeps sigma_zz). density (kg/m3, > 0), young (Pa, > 0), "
       "poisson in [0, 0.5).",
       "local rock = mpm.material.linear_elastic{ density = 2550, young = 5e8, poisson = 0.19 }"},
      {"mpm.material.mohr_coulomb",
       "mpm.material.mohr_coulomb{ density, young, poisson, cohesion, friction, dilation, tension, softening }",
       "Elastic-perfectly plastic Mohr-Coulomb, non-associated. density (kg/m3, > 0), young (Pa, > 0), poisson in "
       "[0, 0.5), cohesion (Pa, >= 0, default 0), friction in [0, 90) degrees, dilation in [0, friction] degrees "
       "(default 0), tension = tensile strength in [0, c cot(phi)] (Pa, default 0: no tension). softening = { cohesion "
       "=, friction =, strain = } softens c and phi linearly to these residual values at that accumulated plastic "
       "shear strain. Particle fields plastic_strain and yield show the state.",
       "local soil = mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, cohesion = 780, "
       "friction = 23, dilation = 0, tension = 0 }"},
      {"mpm.material.drucker_prager",
       "mpm.material.drucker_prager{ density, young, poisson, cohesion, friction, dilation, tension, fit }",
       "Drucker-Prager fitted to Mohr-Coulomb's c, phi, psi: fit = \"plane_strain\" (default: the same plane-strain "
       "limit load as Mohr-Coulomb) | \"outer\" (compression corners) | \"inner\" (extension corners). tension "
       "limits the mean stress (Pa, default 0). Other keys as mohr_coulomb.",
       "local sand = mpm.material.drucker_prager{ density = 2650, young = 8.4e5, poisson = 0.3, friction = 19.8, "
       "fit = \"plane_strain\" }"},
      {"mpm.shape.rectangle", "mpm.shape.rectangle{ x0, y0, x1, y1 }",
       "An axis-aligned rectangle (m), also as { lower = {x0, y0}, upper = {x1, y1} }.",
       "local s = mpm.shape.rectangle{ 0, 0, 0.9, 0.2 }"},
      {"mpm.shape.polygon", "mpm.shape.polygon{ {x, y}, {x, y}, {x, y}, ... }",
       "A simple polygon (m), convex or concave, in either orientation; at least 3 points, edges must not cross.",
       "local s = mpm.shape.polygon{ {0, 0}, {0.9, 0}, {0.9, 0.2}, {0.3, 0.5}, {0, 0.5} }"},
      {"mpm.shape.polyline", "mpm.shape.polyline{ {x, y}, {x, y}, ..., thickness, side }",
       "A band along a polyline: thickness (m, > 0); side = \"both\" (default: thickness/2 each side) | \"left\" | "
       "\"right\" (the full thickness on that side, walking from the first point to the last).",
       "local base = mpm.shape.polyline{ {0, 0.1}, {1, 0.1}, thickness = 0.02, side = \"right\" }"},
      {"mpm.history.table", "mpm.history.table{ {t, v}, {t, v}, ... }",
       "A piecewise-linear history; times (s) must increase; zero before the first and after the last point.",
       "local vx = mpm.history.table{ {0, 0}, {0.1, 2}, {5, 2} }"},
      {"mpm.history.csv", "mpm.history.csv{ file, time = \"t\", value, scale = 1, shift = 0 }",
       "A history from two named columns of a CSV file with a header line; '#' lines are skipped; values are "
       "multiplied by scale and times shifted by shift (s). A relative file not found from the current directory is "
       "looked for next to the script. Errors name the file and line.",
       "local vx = mpm.history.csv{ file = \"data/table_velocity.csv\", time = \"t\", value = \"vx\" }"},
      {"mpm.history.fn", "mpm.history.fn(function(t) return value end)",
       "A history computed by a Lua function of time (s).",
       "local vx = mpm.history.fn(function(t) return 0.1 * math.sin(2 * math.pi * 3 * t) end)"},
      {"mpm.history.at2",
       "mpm.history.at2{ file, integrate = \"velocity\", baseline = \"none\", scale = 1, units = \"g\", format }",
       "A ground-motion record: PEER NGA .AT2 (acceleration in g) or a two-column time, acceleration file (comma or "
       "white space, '#' comments, units = \"g\" | \"m/s2\" | \"gal\"; format = \"at2\" | \"columns\", by "
       "default from the extension). integrate = \"velocity\" (trapezoidal rule) or \"none\" (the acceleration, "
       "m/s2). baseline = \"linear\" removes the drift so velocity and displacement end at zero; \"quadratic\" "
       "first removes a least-squares quadratic trend of the velocity. tostring(h) reports the peak and end values "
       "before and after. Errors name the file and line.",
       "local table = mpm.history.at2{ file = \"data/TCU068-E.AT2\", baseline = \"linear\", scale = 0.5 }"},
      {"history:peak", "h:peak()", "The largest |value| of a tabulated history.", "print(vx:peak())"},
      {"history:duration", "h:duration()", "Time from the first to the last point (s).", "print(vx:duration())"},
      {"history:write_csv", "h:write_csv(file)", "Writes the points as t,value (atomically).",
       "vx:write_csv(\"out/table_velocity.csv\")"},
      {"mpm.plot", "mpm.plot{ file, x, y = {...}, png, title, xlabel, ylabel, color }",
       "A PNG line plot (gnuplot) of columns of a CSV file with a header line ('#' comment lines before it are "
       "skipped): column x against each column in y (names as in the header). With color = a column name: one "
       "point per row at (x, y[1]) coloured by that column, axes to scale (particles over a slope). png defaults "
       "to the CSV's name with .png; returns its path.",
       "mpm.plot{ file = \"out/slide/front.csv\", x = \"time (s)\", y = {\"front x (m)\"}, title = \"Front\" }"},
      {"mpm.param", "mpm.param(name, default)",
       "A scenario parameter: the value given on the command line with --set name=value, converted to the type of "
       "default (number, boolean or string), or default when not given.",
       "local cell = mpm.param(\"cell\", 0.01)"},
      {"mpm.version", "mpm.version()", "The seismpm version as a string.", "print(mpm.version())"},
      {"mpm.out_dir", "mpm.out_dir(default)",
       "The output directory: the one given with --out, or default. --out replaces such defaults only: m:output "
       "writes into the dir it is given, so a script that honours --out passes dir = mpm.out_dir(...).",
       "local dir = mpm.out_dir(\"out/column\")"},
      {"help", "help() | help(object) | help(\"name\")",
       "Lists the API, or shows the documentation and an example of one function or of an object's methods.",
       "help(mpm.model); help(m); help(\"model:run\")"},
      // --- model
      {"model:body", "m:body{ name, material, shape, ppc = 2 }",
       "Fills a shape with particles of a material (ppc per cell per axis, 1..8) and returns the body. The shape must "
       "lie inside the domain; names are unique.",
       "local soil = m:body{ name = \"soil\", material = sand, shape = mpm.shape.rectangle{0, 0, 1, 0.5}, ppc = 2 }"},
      {"model:rigid", "m:rigid{ name, shape, ppc = 2, velocity = {vx, vy}, density = 7850 }",
       "A rigid body of prescribed-velocity particles (a shaking-table box, the surface under a landslide): fills the "
       "shape (rectangle, polygon, or polyline with a thickness; inside the domain) and returns the body. velocity = "
       "{vx, vy}, each a number (m/s) or a history read at the phase time (default {0, 0}). Each step the nodes of "
       "the cells holding its particles take their volume-weighted velocity (the paper's Eq. 9); the soil sees it "
       "through m:contact, or, with no contact declared, moves with it (no slip). density (kg/m3) only gives the "
       "particles a mass to show. Written to rigid_NNNNNN.vtu; b:reaction() gives its force on the soil. For an "
       "inclined sliding surface use a one-sided polyline band (side = \"left\" | \"right\"): its particles carry "
       "the line's normal, so contact follows the true surface rather than the grid's staircase of cells. Make a "
       "rigid body at least one cell thick.",
       "local base = m:rigid{ name = \"base\", shape = mpm.shape.rectangle{-2.5, -0.1, 2.0, 0}, ppc = 1, "
       "velocity = {vx, 0} }"},
      {"model:contact", "m:contact{ body_a, body_b, friction }",
       "Frictional contact between two bodies (Bardenhagen): where they meet they may slide with Coulomb friction "
       "(friction = mu >= 0; 0 smooth, 1 rough) and separate freely; they never interpenetrate. Without m:contact "
       "bodies share one velocity field where they meet (no slip, no separation). One declaration per pair; two "
       "rigid bodies cannot be paired.",
       "m:contact{ block, base, friction = 0.3 }"},
      {"model:set_friction", "m:set_friction{ body_a, body_b, friction }",
       "Changes the Coulomb coefficient of a declared contact pair from the next step on: a peak value for the "
       "gravity phase, a residual one once shaking has broken the interface.",
       "m:set_friction{ rock, bedding, friction = 0.2 }"},
      {"model:fix", "m:fix{ side, dof = \"xy\" }",
       "Holds the grid nodes on one edge: side = \"left\" | \"right\" | \"bottom\" | \"top\"; dof = \"x\" | \"y\" | "
       "\"xy\".",
       "m:fix{ side = \"bottom\", dof = \"xy\" }; m:fix{ side = \"left\", dof = \"x\" }"},
      {"model:probe", "m:probe{ name, body, at = {x, y}, every = 0.01 }",
       "A control point: follows the particle of the body nearest to `at` and records all its fields every `every` "
       "seconds of simulated time (0: every step) and at the end of each run.",
       "local p1 = m:probe{ name = \"crest\", body = soil, at = {0.3, 0.5} }"},
      {"model:output", "m:output{ dir, every = 0.1, fields, grid = false, probe_every, at_run_end = true }",
       "Writes ParaView files into dir (as given; without dir: the --out directory): particles_NNNNNN.vtu now, "
       "every `every` seconds of simulated time and at the end of each run, listed with their times in "
       "particles.pvd (open that one in ParaView); probes.csv with every field of every probe. fields = a list of names (default: all; components "
       "such as ux select their vector); grid = true adds grid_NNNNNN.vtu with nodal mass, velocity and fixities; "
       "probe_every (s) sets every probe's sampling interval. at_run_end = false leaves out the extra file at the "
       "end of each run (a script that runs in short chunks then only writes every `every` seconds).",
       "m:output{ dir = \"out/slope\", every = 0.1, probe_every = 0.01 }"},
      {"model:plot", "m:plot{ quantities = {\"ux\", \"uy\"} }",
       "PNG time histories of the probes in the output directory with gnuplot (probe_<quantity>.png, one curve per "
       "probe, axes with units); returns the file names. From the shell: seismpm plot DIR ux uy.",
       "for _, png in ipairs(m:plot{ quantities = {\"ux\", \"uy\"} }) do print(png) end"},
      {"model:gravity_phase", "m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 10, k0 }",
       "The initial-stress phase: self-weight with rigid bodies at rest and local damping (F_damp = -damping "
       "|F_unbalanced| sign(v) per degree of freedom) until static equilibrium: the out-of-balance force relative to "
       "the external force and the kinetic energy relative to its peak in the phase both below tolerance (shown with "
       "the progress; nodes held by a rigid body or a fixity count as supported). Fails with an error at max_time "
       "(s). At its end displacements and the strain that shear_strain measures are reset to zero; stresses and "
       "plastic state are kept. k0 (in (0, 3]): first set sigma_v = rho g depth (the overburden of the particles "
       "above, per grid column) and sigma_h = k0 sigma_v, then settle. Returns { time, steps, unbalanced, kinetic }.",
       "local eq = m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 5 }; print(eq.time, eq.steps)"},
      {"model:dynamic_phase", "m:dynamic_phase{ duration, damping = 0, every, call }",
       "The shaking phase: inertia on, damping (default 0, in [0, 1)), rigid bodies follow their velocity histories, "
       "read at the phase time, which starts at zero now (so a record starts when the shaking starts). Phases can "
       "follow each other in any number; m:run{ duration } continues the current phase without restarting its "
       "clock. every (s) and call (a function): as for m:run.",
       "m:dynamic_phase{ duration = 14, every = 0.5, call = function(m) print(m:phase_time()) end }"},
      {"model:phase_time", "m:phase_time()", "Time since the current phase started (s); m:time() is the total.",
       "print(m:phase_time(), m:time())"},
      {"model:phase", "m:phase()", "The current phase's name: \"run\" before any phase, \"gravity\" or \"dynamic\".",
       "print(m:phase())"},
      {"model:write", "m:write()",
       "Writes the current state to the output directory now (particles, rigid bodies, probes, reactions), unless "
       "it is on file already; for scripts that run in chunks with at_run_end = false.",
       "m:write()"},
      {"model:step", "m:step(n = 1)", "Takes n explicit steps.", "m:step(10)"},
      {"model:run", "m:run{ duration, damping, every, call }",
       "Runs for duration (s) more, with a progress display; damping = local damping coefficient in [0, 1) for this "
       "and later runs (default: unchanged, 0 at first). call(m) runs every `every` seconds of simulated time (hit "
       "exactly) and at the end of the run, between steps: to sample or print something, or to end the run early by "
       "returning true; it may not step the model itself. Ctrl-C stops at the next step boundary with the model "
       "intact.",
       "m:run{ duration = 60, every = 1, call = function(m) return m:energy().kinetic < 1 end }"},
      {"model:time", "m:time()", "Simulated time (s), total across phases.", "print(m:time())"},
      {"model:steps", "m:steps()", "Number of steps taken.", "print(m:steps())"},
      {"model:dt", "m:dt()", "The last time step (s), or the one the CFL condition allows before the first step.",
       "print(m:dt())"},
      {"model:energy", "m:energy()",
       "Kinetic and elastic strain energy (J per metre out of plane) as a table { kinetic =, strain = }.",
       "local e = m:energy(); print(e.kinetic, e.strain)"},
      {"model:count", "m:count()", "Number of particles in the model.", "print(m:count())"},
      {"model:bodies", "m:bodies()", "The bodies as a table by name.", "for name, b in pairs(m:bodies()) do print(name, b:count()) end"},
      // --- body
      {"body:name", "b:name()", "The body's name.", "print(soil:name())"},
      {"body:count", "b:count()", "Number of particles of the body.", "print(soil:count())"},
      {"body:centroid", "b:centroid()", "Mass centre {x, y} (m).", "local c = soil:centroid(); print(c[1], c[2])"},
      {"body:field", "b:field(name)",
       "A particle field as a Lua array in particle creation order. Fields: id body material mass volume density x y "
       "ux uy vx vy sxx syy szz sxy pressure q shear_strain plastic_strain yield (SI units, stress tension-positive, "
       "pressure compression-positive).",
       "local uy = soil:field(\"uy\"); print(#uy, uy[1])"},
      {"body:set_velocity", "b:set_velocity{vx, vy} | b:set_velocity(function(x, y) return vx, vy end)",
       "Sets the particles' velocity (m/s), uniform or as a function of position. For a rigid body: {vx, vy} with "
       "numbers or histories replaces the velocity it follows from the next step on.",
       "bar:set_velocity(function(x, y) return 0.1 * math.sin(math.pi * x / 50), 0 end)"},
      {"body:reaction", "r:reaction()",
       "For a rigid body: the force {fx, fy} it exerted on the deformable bodies in the last step (N per metre out "
       "of plane; a base carrying soil reads its weight, upward). The output directory's reactions.csv holds its "
       "mean over each output interval.",
       "local f = base:reaction(); print(f[1], f[2])"},
      // --- probe
      {"probe:name", "p:name()", "The probe's name.", "print(p1:name())"},
      {"probe:get", "p:get(field)", "The current value of a field of the probe's particle.", "print(p1:get(\"uy\"))"},
      {"probe:series", "p:series(field)", "The recorded history: two arrays, times (s) and values.",
       "local t, uy = p1:series(\"uy\")"},
      // --- others
      {"history:at", "h:at(t)", "The history's value at time t (s).", "print(vx:at(0.5))"},
      {"shape:contains", "s:contains{x, y}", "Whether the point lies inside the shape.",
       "print(s:contains{0.1, 0.1})"},
      {"material:kind", "mat:kind()", "The constitutive model's name.", "print(rock:kind())"},
      // --- Lua library (lua/seismpm.lua)
      {"mpm.geometry.slope", "mpm.geometry.slope{ left, right, base = 0, crest = {x, y}, toe_level, angle }",
       "The polygon of a slope in a box from x = left to right (m) above `base`: level crest ground at height crest[2] "
       "from `left` to crest[1], a face falling to the right at `angle` degrees (0 < angle < 90) down to toe_level, "
       "then level toe ground to `right`. Returns an mpm.shape.polygon (Lua library, lua/seismpm.lua).",
       "local s = mpm.geometry.slope{ left = 0, right = 0.9, crest = {0.35, 0.53}, toe_level = 0.2, angle = 45 }"},
      {"mpm.geometry.layers", "mpm.geometry.layers{ left, right, base = 0, {top = y, name = ...}, ... }",
       "Horizontal layers from `left` to `right` (m), listed from the bottom up by their top elevation: returns a list "
       "of { name =, shape = rectangle } (Lua library).",
       "for _, l in ipairs(mpm.geometry.layers{ left = 0, right = 10, {top = 2, name = \"clay\"}, {top = 5, name = \"sand\"} }) do print(l.name) end"},
  };
  return docs;
}

const ApiDoc* find_doc(const std::string& name) {
  for (const auto& d : api_docs())
    if (name == d.name) return &d;
  return nullptr;
}

std::string api_markdown() {
  std::ostringstream os;
  os << "# Lua API reference\n\n"
     << "Generated from the same text `help()` shows in the console (`seismpm --api-doc`). Every function takes one\n"
     << "table of named arguments; an unknown key, a missing required key, a wrong type or a value out of range\n"
     << "raises an error naming the key and the allowed range. SI units (m, kg, s, Pa); angles in degrees.\n";
  std::string group;
  for (const auto& d : api_docs()) {
    const std::string name = d.name;
    // Group by module (mpm.shape) or by object (model:, body:).
    const std::string g = name.find(':') != std::string::npos ? name.substr(0, name.find(':'))
                          : name.rfind("mpm.", 0) == 0    ? name.substr(0, name.rfind('.'))
                                                          : "console";
    if (g != group) {
      group = g;
      os << "\n## " << g << "\n";
    }
    os << "\n### `" << d.signature << "`\n\n" << d.summary << "\n\n```lua\n" << d.example << "\n```\n";
  }
  return os.str();
}

}  // namespace seismpm::lua
