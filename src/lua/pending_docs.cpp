// The model's and the phases' functions as help() and docs/lua-api.md show them, until
// model_binding.cpp and phase_binding.cpp hold their own key tables (after the run layer moves out).
#include "api_docs.hpp"

namespace seismpm::lua {

namespace {
const Function kModel[] = {
      {"mpm.model", nullptr, "mpm.model{ domain, cell, shape, scheme, gravity, cfl, flip, dt, max_dilation }", {},
       "Creates a 2D plane-strain model on a background grid. domain = {{x0, y0}, {x1, y1}} (m), required; "
       "cell = cell size (m, > 0), required; shape = \"gimp\" (default) | \"linear\"; scheme = \"musl\" (default) | "
       "\"usl\"; gravity = {gx, gy} (m/s2, default {0, -9.81}); cfl = Courant number in (0, 1] (default 0.4); "
       "flip = FLIP share in [0, 1] (default 1, 0 = PIC); dt = fixed time step (s, default: from cfl); "
       "max_dilation = largest particle volume as a multiple of its initial one (default 2; 0: no limit): where "
       "cohesionless soil breaks up, stress-free particles would otherwise swell without bound and shrink the time "
       "step.",
       "local m = mpm.model{ domain = {{0, 0}, {1, 0.6}}, cell = 0.01, shape = \"gimp\" }"},
      {"model:body", nullptr, "m:body{ name, material, shape, ppc = 2 }", {},
       "Fills a shape with particles of a material (ppc per cell per axis, 1..8) and returns the body. The shape must "
       "lie inside the domain; names are unique.",
       "local soil = m:body{ name = \"soil\", material = sand, shape = mpm.shape.rectangle{0, 0, 1, 0.5}, ppc = 2 }"},
      {"model:rigid", nullptr, "m:rigid{ name, shape, ppc = 2, velocity = {vx, vy}, density = 7850 }", {},
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
      {"model:contact", nullptr, "m:contact{ body_a, body_b, friction }", {},
       "Frictional contact between two bodies (Bardenhagen): where they meet they may slide with Coulomb friction "
       "(friction = mu >= 0; 0 smooth, 1 rough) and separate freely; they never interpenetrate. Without m:contact "
       "bodies share one velocity field where they meet (no slip, no separation). One declaration per pair; two "
       "rigid bodies cannot be paired.",
       "m:contact{ block, base, friction = 0.3 }"},
      {"model:set_friction", nullptr, "m:set_friction{ body_a, body_b, friction }", {},
       "Changes the Coulomb coefficient of a declared contact pair from the next step on: a peak value for the "
       "gravity phase, a residual one once shaking has broken the interface.",
       "m:set_friction{ rock, bedding, friction = 0.2 }"},
      {"model:fix", nullptr, "m:fix{ side, dof = \"xy\" }", {},
       "Holds the grid nodes on one edge: side = \"left\" | \"right\" | \"bottom\" | \"top\"; dof = \"x\" | \"y\" | "
       "\"xy\".",
       "m:fix{ side = \"bottom\", dof = \"xy\" }; m:fix{ side = \"left\", dof = \"x\" }"},
      {"model:probe", nullptr, "m:probe{ name, body, at = {x, y}, every = 0.01 }", {},
       "A control point: follows the particle of the body nearest to `at` and records all its fields every `every` "
       "seconds of simulated time (0: every step) and at the end of each run.",
       "local p1 = m:probe{ name = \"crest\", body = soil, at = {0.3, 0.5} }"},
      {"model:output", nullptr, "m:output{ dir, every = 0.1, fields, grid = false, probe_every, at_run_end = true }", {},
       "Writes ParaView files into dir (as given; without dir: the --out directory): particles_NNNNNN.vtu now, "
       "every `every` seconds of simulated time and at the end of each run, listed with their times in "
       "particles.pvd (open that one in ParaView); probes.csv with every field of every probe. fields = a list of names (default: all; components "
       "such as ux select their vector); grid = true adds grid_NNNNNN.vtu with nodal mass, velocity and fixities; "
       "probe_every (s) sets every probe's sampling interval. at_run_end = false leaves out the extra file at the "
       "end of each run (a script that runs in short chunks then only writes every `every` seconds).",
       "m:output{ dir = \"out/slope\", every = 0.1, probe_every = 0.01 }"},
      {"model:plot", nullptr, "m:plot{ quantities = {\"ux\", \"uy\"} }", {},
       "PNG time histories of the probes in the output directory with gnuplot (probe_<quantity>.png, one curve per "
       "probe, axes with units); returns the file names. From the shell: seismpm plot DIR ux uy.",
       "for _, png in ipairs(m:plot{ quantities = {\"ux\", \"uy\"} }) do print(png) end"},
      {"model:write", nullptr, "m:write()", {},
       "Writes the current state to the output directory now (particles, rigid bodies, probes, reactions), unless "
       "it is on file already; for scripts that run in chunks with at_run_end = false.",
       "m:write()"},
      {"model:step", nullptr, "m:step(n = 1)", {}, "Takes n explicit steps.", "m:step(10)"},
      {"model:run", nullptr, "m:run{ duration, damping, every, call }", {},
       "Runs for duration (s) more, with a progress display; damping = local damping coefficient in [0, 1) for this "
       "and later runs (default: unchanged, 0 at first). call(m) runs every `every` seconds of simulated time (hit "
       "exactly) and at the end of the run, between steps: to sample or print something, or to end the run early by "
       "returning true; it may not step the model itself. Ctrl-C stops at the next step boundary with the model "
       "intact.",
       "m:run{ duration = 60, every = 1, call = function(m) return m:energy().kinetic < 1 end }"},
      {"model:time", nullptr, "m:time()", {}, "Simulated time (s), total across phases.", "print(m:time())"},
      {"model:steps", nullptr, "m:steps()", {}, "Number of steps taken.", "print(m:steps())"},
      {"model:dt", nullptr, "m:dt()", {}, "The last time step (s), or the one the CFL condition allows before the first step.",
       "print(m:dt())"},
      {"model:energy", nullptr, "m:energy()", {},
       "Kinetic and elastic strain energy (J per metre out of plane) as a table { kinetic =, strain = }.",
       "local e = m:energy(); print(e.kinetic, e.strain)"},
      {"model:count", nullptr, "m:count()", {}, "Number of particles in the model.", "print(m:count())"},
      {"model:bodies", nullptr, "m:bodies()", {}, "The bodies as a table by name.", "for name, b in pairs(m:bodies()) do print(name, b:count()) end"},
};
const Function kPhases[] = {
      {"model:gravity_phase", nullptr, "m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 10, k0 }", {},
       "The initial-stress phase: self-weight with rigid bodies at rest and local damping (F_damp = -damping "
       "|F_unbalanced| sign(v) per degree of freedom) until static equilibrium: the out-of-balance force relative to "
       "the external force and the kinetic energy relative to its peak in the phase both below tolerance (shown with "
       "the progress; nodes held by a rigid body or a fixity count as supported). Fails with an error at max_time "
       "(s). At its end displacements and the strain that shear_strain measures are reset to zero; stresses and "
       "plastic state are kept. k0 (in (0, 3]): first set sigma_v = rho g depth (the overburden of the particles "
       "above, per grid column) and sigma_h = k0 sigma_v, then settle. Returns { time, steps, unbalanced, kinetic }.",
       "local eq = m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 5 }; print(eq.time, eq.steps)"},
      {"model:dynamic_phase", nullptr, "m:dynamic_phase{ duration, damping = 0, every, call }", {},
       "The shaking phase: inertia on, damping (default 0, in [0, 1)), rigid bodies follow their velocity histories, "
       "read at the phase time, which starts at zero now (so a record starts when the shaking starts). Phases can "
       "follow each other in any number; m:run{ duration } continues the current phase without restarting its "
       "clock. every (s) and call (a function): as for m:run.",
       "m:dynamic_phase{ duration = 14, every = 0.5, call = function(m) print(m:phase_time()) end }"},
      {"model:phase_time", nullptr, "m:phase_time()", {}, "Time since the current phase started (s); m:time() is the total.",
       "print(m:phase_time(), m:time())"},
      {"model:phase", nullptr, "m:phase()", {}, "The current phase's name: \"run\" before any phase, \"gravity\" or \"dynamic\".",
       "print(m:phase())"},
};
}  // namespace

std::span<const Function> model_functions() { return kModel; }
std::span<const Function> phase_functions() { return kPhases; }

}  // namespace seismpm::lua
