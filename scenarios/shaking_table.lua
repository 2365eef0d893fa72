-- A 45-degree Masa-soil slope in a steel box on a shaking table: the paper's main case
-- (Bhandari et al. 2016, §3; the test by Hiraoka et al. 2013).
--
-- Geometry (the paper's Fig. 4 prints 0.35, 0.53, 0.2, 0.5, 0.9 m and 45 degrees; this is one
-- consistent reading): a box 0.9 m long and 0.6 m high (0.5 m wide out of plane: plane strain here);
-- the soil's crest is 0.53 m above the box floor and reaches 0.35 m from the left wall, its face falls
-- at 45 degrees to a toe layer 0.2 m thick that runs to the right wall.
-- Soil (the paper's Table 1): density 1680 kg/m3, E = 2570 kPa, nu = 0.33, c = 0.78 kPa, phi = 23 deg,
-- psi = 0, Mohr-Coulomb without tension.
-- The box: prescribed-velocity particles (one cell thick) following the table's velocity history:
-- a rough base (mu = 1) and smooth side walls (mu = 0), as in the paper.
-- Phases: gravity (local damping 0.7, tolerance 0.005), then 14 s of table motion from
-- scenarios/data/table_velocity.csv (a reconstruction: see that file's header).
-- Control points: 1 near the crest (its vertical displacement), 2 on the face (its horizontal one).
-- Outputs under out/shaking_table/: particles.pvd and rigid.pvd for ParaView, probes.csv,
-- reactions.csv (base.fx is the base shear; base.fx + left_wall.fx + right_wall.fx the box's whole
-- horizontal force on the soil), probe_ux.png, probe_uy.png, summary.txt, open_in_paraview.py.
--
--   seismpm scenarios/shaking_table.lua [--set cell=0.0125] [--set duration=14] [--set every=0.25]
--                                       [--set record=FILE.csv] [--set check=true] [--set transfer=apic]

local cell = mpm.param("cell", 0.0125)          -- m: 8,954 soil particles, 2-6 min on 2 cores
local duration = mpm.param("duration", 14.0)    -- s of shaking
local every = mpm.param("every", 0.25)          -- s between ParaView files
local record = mpm.param("record", "data/table_velocity.csv")
local check = mpm.param("check", false)         -- assert the coarse physics (ctest)
local flip = mpm.param("flip", 0.98)            -- FLIP share; the 2 % PIC share damps free-surface noise
local transfer = mpm.param("transfer", "flip")  -- flip | apic (docs/kernel.md: velocity transfer)
local verbose = mpm.param("verbose", false)     -- print the largest particle speed every 0.5 s

local L, Hbox = 0.9, 0.6                        -- box inside (m)
local crest_x, crest_y, toe_y, angle = 0.35, 0.53, 0.2, 45
local rho, g = 1680, 9.81
local c, phi = 780, 23

-- Limit equilibrium (Culmann wedges through the toe of the face, pseudo-static horizontal k g):
-- the slope must stand under gravity and fail under the table's strongest shaking.
local function wedge_safety(k)
  local H = crest_y - toe_y
  local best = math.huge
  for theta = 5, angle - 0.5, 0.25 do
    local th = math.rad(theta)
    if H / math.tan(th) <= crest_x + H then  -- the plane leaves on the crest, not through the wall
      local W = 0.5 * rho * g * H * H * (1 / math.tan(th) - 1 / math.tan(math.rad(angle)))
      local drive = W * (math.sin(th) + k * math.cos(th))
      local resist = c * H / math.sin(th) + W * (math.cos(th) - k * math.sin(th)) * math.tan(math.rad(phi))
      best = math.min(best, resist / drive)
    end
  end
  return best
end
local fs_static = wedge_safety(0)
local lo, hi = 0, 2
for _ = 1, 60 do
  local mid = 0.5 * (lo + hi)
  if wedge_safety(mid) > 1 then lo = mid else hi = mid end
end
local k_critical = lo

local table_vx = mpm.history.csv{ file = record, time = "t", value = "vx" }
local peak_a, peak_v = 0, table_vx:peak()
for t = 0, table_vx:duration() - 0.001, 0.001 do
  peak_a = math.max(peak_a, math.abs(table_vx:at(t + 0.001) - table_vx:at(t)) / 0.001)
end
print(string.format("limit equilibrium: factor of safety %.2f under gravity; critical acceleration %.2f g", fs_static,
                    k_critical))
print(string.format("table motion: peak velocity %.3f m/s, peak acceleration %.2f g over %.1f s", peak_v, peak_a / g,
                    table_vx:duration()))
assert(fs_static > 1, "the slope must stand under gravity alone")
if peak_a / g <= k_critical then
  print("warning: the table motion stays below the critical acceleration: expect little movement")
end

-- The model: the box walls one cell thick, the domain two cells beyond them.
local t = cell
local m = mpm.model{ domain = {{-2 * t, -2 * t}, {L + 2 * t, Hbox + 2 * t}}, cell = cell, gravity = {0, -g},
                     shape = "gimp", flip = flip, transfer = transfer }
local masa = mpm.material.mohr_coulomb{ density = rho, young = 2.57e6, poisson = 0.33, cohesion = c,
                                        friction = phi, dilation = 0, tension = 0 }
local soil = m:body{ name = "soil", material = masa, ppc = 2,
                     shape = mpm.geometry.slope{ left = 0, right = L, base = 0, crest = {crest_x, crest_y},
                                                 toe_level = toe_y, angle = angle } }
local velocity = {table_vx, 0}
local base = m:rigid{ name = "base", ppc = 1, velocity = velocity, shape = mpm.shape.rectangle{ -t, -t, L + t, 0 } }
local left = m:rigid{ name = "left_wall", ppc = 1, velocity = velocity, shape = mpm.shape.rectangle{ -t, 0, 0, Hbox } }
local right = m:rigid{ name = "right_wall", ppc = 1, velocity = velocity, shape = mpm.shape.rectangle{ L, 0, L + t, Hbox } }
m:contact{ soil, base, friction = 1.0 }
m:contact{ soil, left, friction = 0.0 }
m:contact{ soil, right, friction = 0.0 }

local face_mid = {crest_x + 0.5 * (crest_y - toe_y), 0.5 * (crest_y + toe_y)}
local p1 = m:probe{ name = "point1", body = soil, at = {crest_x - 0.02, crest_y}, every = 0.02 }
local p2 = m:probe{ name = "point2", body = soil, at = face_mid, every = 0.02 }
print(string.format("soil: %d particles, cell %.4g m; box: %d prescribed-velocity particles",
                    soil:count(), cell, base:count() + left:count() + right:count()))

local dir = mpm.out_dir("out/shaking_table")
m:output{ dir = dir, every = every }
local clock = os.clock()
local wall0 = os.time()

local eq = m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 5 }
local function largest_speed()
  local vx, vy = soil:field("vx"), soil:field("vy")
  local s = 0
  for i = 1, #vx do s = math.max(s, math.sqrt(vx[i] ^ 2 + vy[i] ^ 2)) end
  return s
end
local fastest = 0
-- The table motion; every 0.5 s of it, between steps, the largest particle speed is sampled.
m:dynamic_phase{ duration = duration, every = 0.5, call = function()
  local v = largest_speed()
  fastest = math.max(fastest, v)
  if verbose then print(string.format("t = %5.2f s: largest particle speed %.3f m/s", m:phase_time(), v)) end
end }

local ux, uy = soil:field("ux"), soil:field("uy")
local u_max = 0
for i = 1, #ux do u_max = math.max(u_max, math.sqrt(ux[i] ^ 2 + uy[i] ^ 2)) end
local yielding = 0
for _, y in ipairs(soil:field("yield")) do yielding = yielding + y end
local wall = os.time() - wall0
local lines = {
  string.format("soil particles: %d, cell: %g m", soil:count(), cell),
  string.format("gravity phase: equilibrium after %.3f s (%d steps)", eq.time, eq.steps),
  string.format("maximum total displacement at %.1f s of shaking: %.4f m (paper: about 0.21 m)", duration, u_max),
  string.format("point 1 (crest) uy = %.4f m, point 2 (face) ux = %.4f m", p1:get("uy"), p2:get("ux")),
  string.format("particles yielding at the end: %d; largest particle speed (every 0.5 s): %.3f m/s", yielding,
                fastest),
  string.format("wall time: %d s (%.0f s CPU), %d steps", wall, os.clock() - clock, m:steps()),
}
local f = assert(io.open(dir .. "/summary.txt", "w"))
for _, line in ipairs(lines) do
  print(line)
  f:write(line, "\n")
end
f:close()
for _, png in ipairs(m:plot{ quantities = {"ux", "uy"} }) do print("plot: " .. png) end
-- The failure mechanism: every particle at its final place, coloured by its total displacement.
do
  local xs, ys = soil:field("x"), soil:field("y")
  local rows = { "x (m),y (m),total displacement (m)" }
  for i = 1, #xs do rows[#rows + 1] = string.format("%.5f,%.5f,%.5f", xs[i], ys[i], math.sqrt(ux[i] ^ 2 + uy[i] ^ 2)) end
  local out = assert(io.open(dir .. "/final_displacement.csv", "w"))
  out:write(table.concat(rows, "\n"), "\n")
  out:close()
  print("plot: " .. mpm.plot{ file = dir .. "/final_displacement.csv", x = "x (m)", y = {"y (m)"},
                              color = "total displacement (m)", ylabel = "y (m)",
                              title = string.format("Total displacement after %g s of shaking", duration) })
end
table_vx:write_csv(dir .. "/table_velocity.csv")
print("plot: " .. mpm.plot{ file = dir .. "/table_velocity.csv", x = "t", y = {"value"},
                            title = "Horizontal velocity of the shaking table (input motion)",
                            xlabel = "time since the dynamic phase began (s)", ylabel = "table velocity vx (m/s)" })

if check then
  assert(p1:get("uy") < -0.002, "the crest should settle")
  assert(p2:get("ux") > 0.002, "the face should move down-slope (+x)")
  assert(u_max < 0.5, "displacements should stay bounded by the box")
  print("check passed")
end
