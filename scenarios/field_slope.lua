-- A slope in the field on a recorded earthquake (issue 16): two soil layers on a compliant rock base,
-- free-field sides, Rayleigh damping for the soil, a gravity phase to equilibrium, then the Chi-Chi
-- TCU068-090 record, windowed and scaled to a target PGA, as the OUTCROP motion of the rock.
--
--   ground     x = 0 .. 250 m; level crest ground at y = 50 m up to x = 100 m, a 30 degree face down to
--              the toe ground at y = 25 m; the model's base (y = 0) is the top of the rock half-space.
--   layers     stiff clay below y = 30 m (Vs 350 m/s), silty sand above (Vs 200 m/s), both Mohr-Coulomb.
--   rock       rho 2400 kg/m3, Vs 800 m/s, Vp 1500 m/s: the compliant base lets the record in and what
--              the slope sends down out (m:boundary kind = "compliant").
--   sides      free field: each side follows a 1D column of the layering next to it (kind = "free_field").
--   damping    Rayleigh, `damping` (default 3 %) at the left column's fundamental frequency f1 = 1/(4 sum
--              h/Vs) and at 5 f1; the gravity phase uses local damping only to reach equilibrium.
--   cell       2.5 m: 8 cells per shortest wavelength Vs/f_max for f_max = 10 Hz in the sand.
--
-- Probes on the crest, the face, the toe and the left free-field surface record their displacement
-- relative to a probe on the base (the permanent displacement of the slope, without the ground's own
-- motion); probe plots are drawn in shaking time. <out>/summary.csv lists the permanent displacements.
--
--   seismpm scenarios/field_slope.lua [--set pga=0.3] [--set window=10,40] [--set cell=2.5]
--                                     [--set damping=0.03] [--set record=FILE|synthetic] [--set check=true]
--
-- record: the TCU068 record from the shared data (two '#' comment lines, columns time (s), acceleration
-- (g)); without it, or with record=synthetic, a 1.5 Hz tapered sine burst of the same PGA (a message says
-- so). The record is used as an outcrop motion, and it ends with 5 s of the slope coming to rest.

local pga = mpm.param("pga", 0.3)                  -- g, the target peak of the windowed record
local window_text = mpm.param("window", "10,40")    -- s, the part of the record used (its own times)
local cell = mpm.param("cell", 2.5)                 -- m
local ratio = mpm.param("damping", 0.03)            -- Rayleigh damping ratio of both soils
local shape = mpm.param("shape", "linear")
local check = mpm.param("check", false)             -- assert the numbers (ctest)
local every = mpm.param("every", 1.0)               -- s between ParaView files
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
local out = mpm.out_dir("out/field_slope")

local function exists(file)
  local f = io.open(file)
  if f then f:close() end
  return f ~= nil
end

-- Geometry and layering.
local left, right, crest, toe, angle = 0, 250, { 100, 50 }, 25, 30
local layers = {
  { top = 30, name = "stiff_clay", density = 2000, vs = 350, poisson = 0.3, cohesion = 60e3, friction = 30 },
  { top = crest[2], name = "silty_sand", density = 1900, vs = 200, poisson = 0.3, cohesion = 10e3, friction = 32 },
}
local rock = { density = 2400, vs = 800, vp = 1500 }

-- The fundamental frequency of the deeper (left) column, by travel time: f1 = 1 / (4 sum h / Vs).
local travel, bottom = 0, 0
for _, l in ipairs(layers) do
  travel = travel + (l.top - bottom) / l.vs
  bottom = l.top
end
local f1 = 1 / (4 * travel)

local m = mpm.model{ domain = { { left, 0 }, { right, crest[2] + cell } }, cell = cell, shape = shape,
                     gravity = { 0, -9.81 } }
local regions = { left = left, right = right }
for i, l in ipairs(layers) do
  local shear = l.density * l.vs ^ 2
  regions[i] = { top = l.top, name = l.name,
                 material = mpm.material.mohr_coulomb{ density = l.density, young = 2 * shear * (1 + l.poisson),
                                                       poisson = l.poisson, cohesion = l.cohesion,
                                                       friction = l.friction, dilation = 0, tension = 0,
                                                       rayleigh = { ratio = ratio, frequencies = { f1, 5 * f1 } } } }
end
local outline = mpm.geometry.slope{ left = left, right = right, crest = crest, toe_level = toe, angle = angle }
local ground = m:body{ name = "ground", shape = outline, regions = mpm.geometry.layers(regions), ppc = 2 }

-- The record as the outcrop velocity of the rock.
local record = mpm.param("record", "")
if record == "" then
  local shared = here .. "../../shared/data/ground_motions/Chi-Chi_1999_TCU068-090.csv"
  record = exists(shared) and shared or "synthetic"
  if record == "synthetic" then print("the TCU068 record is not in the shared data: a 1.5 Hz sine burst instead") end
end
local t0, t1 = window_text:match("^%s*([%d.]+)%s*,%s*([%d.]+)%s*$")
t0, t1 = tonumber(t0), tonumber(t1)
assert(t0 and t1 and t1 > t0, "--set window must be two times t0,t1 (s) with t1 > t0, got " .. window_text)
local vx, source
if record == "synthetic" then
  -- v(t) = V sin(2 pi f t) under a Tukey taper: its acceleration peaks near 2 pi f V = pga g.
  local f, length = 1.5, math.min(t1 - t0, 8)
  local V = pga * 9.81 / (2 * math.pi * f)
  vx = mpm.history.fn(function(t)
    if t <= 0 or t >= length then return 0 end
    local s = math.min(t, length - t)
    local w = s < 1 and 0.5 * (1 - math.cos(math.pi * s)) or 1
    return V * w * math.sin(2 * math.pi * f * t)
  end)
  source = string.format("synthetic: 1.5 Hz sine burst, %g s, PGA about %g g", length, pga)
else
  vx = mpm.history.csv{ file = record, time = 1, value = 2, kind = "acceleration", units = "g",
                        window = { t0, t1 }, taper = 1, pga = pga, baseline = "linear" }
  source = string.format("%s, window %g-%g s, taper 1 s, PGA %g g, linear baseline", record, t0, t1, pga)
end
local duration = (record == "synthetic" and math.min(t1 - t0, 8) or (t1 - t0)) + 5

m:boundary{ side = "bottom", kind = "compliant", input = { vx, 0 }, density = rock.density, vs = rock.vs,
            vp = rock.vp }
m:boundary{ side = "left", kind = "free_field" }
m:boundary{ side = "right", kind = "free_field" }

local base = m:probe{ name = "base", body = ground, at = { 125, 0 } }
local face_x = crest[1] + 0.5 * (crest[2] - toe) / math.tan(math.rad(angle))
local probes = {
  crest = m:probe{ name = "crest", body = ground, at = { crest[1] - cell, crest[2] }, relative_to = base },
  face = m:probe{ name = "face", body = ground, at = { face_x, 0.5 * (crest[2] + toe) }, relative_to = base },
  toe = m:probe{ name = "toe", body = ground, at = { crest[1] + (crest[2] - toe) / math.tan(math.rad(angle)) + 2 * cell,
                                                    toe }, relative_to = base },
  free_field = m:probe{ name = "free_field", body = ground, at = { left + cell, crest[2] }, relative_to = base },
}
m:output{ dir = out, every = every, probe_every = 0.02 }

print(string.format("field slope: %d particles, cell %g m, f1 = %.3g Hz, Rayleigh %g %% at %.3g and %.3g Hz",
                    ground:count(), cell, f1, 100 * ratio, f1, 5 * f1))
print("input (outcrop velocity): " .. source)
local eq = m:gravity_phase{ tolerance = 0.001, max_time = 20 }
local base_syy = base:get("syy")
m:dynamic_phase{ duration = duration }
m:plot{ quantities = { "ux_rel", "uy_rel", "vx" }, phase = "dynamic" }

-- The permanent displacements (relative to the base probe) at the end, and their peaks.
local rows = { "probe,ux_rel (m),uy_rel (m),peak |ux_rel| (m),x (m),y (m)" }
local summary = {}
for _, name in ipairs({ "crest", "face", "toe", "free_field" }) do
  local p = probes[name]
  local _, ux = p:series("ux_rel")
  local peak = 0
  for _, v in ipairs(ux) do peak = math.max(peak, math.abs(v)) end
  summary[name] = { ux = p:get("ux_rel"), uy = p:get("uy_rel"), peak = peak }
  rows[#rows + 1] = string.format("%s,%.6g,%.6g,%.6g,%.6g,%.6g", name, p:get("ux_rel"), p:get("uy_rel"), peak,
                                  p:get("x"), p:get("y"))
end
local f = assert(io.open(out .. "/summary.csv", "w"))
f:write(table.concat(rows, "\n"), "\n")
f:close()
print(string.format("gravity phase: %.3g s, %d steps; base sigma_yy %.4g kPa", eq.time, eq.steps, base_syy / 1e3))
print(string.format("end of shaking (%g s): the base moved ux %.4g m, uy %.4g m relative to the outcrop motion", duration, base:get("ux"),
                    base:get("uy")))
for _, name in ipairs({ "crest", "face", "toe", "free_field" }) do
  local s = summary[name]
  print(string.format("  %-10s permanent ux %8.4f m, uy %8.4f m (relative to the base; peak |ux| %.4f m)", name, s.ux,
                      s.uy, s.peak))
end

if check then
  -- The weight on the base: sigma_yy there carries the overburden of the face above it (within the
  -- arching of a 2.5-5 m cell: 10 %).
  local expected = 0
  local y_surface = crest[2] - (base:get("x") - crest[1]) * math.tan(math.rad(angle))
  bottom = 0
  for _, l in ipairs(layers) do
    local top = math.min(l.top, y_surface)
    if top > bottom then expected = expected + l.density * 9.81 * (top - bottom) end
    bottom = math.max(bottom, l.top)
  end
  local ratio_syy = -base_syy / expected
  assert(math.abs(ratio_syy - 1) < 0.1, string.format("base sigma_yy %.4g kPa, overburden %.4g kPa", -base_syy / 1e3,
                                                      expected / 1e3))
  -- No drift of the ground on its dashpots: the outcrop displacement ends at zero (baseline corrected),
  -- so must the base's, within a few cm.
  assert(math.abs(base:get("ux")) < 0.05 and math.abs(base:get("uy")) < 0.05,
         string.format("the base drifted: ux %.4g m, uy %.4g m", base:get("ux"), base:get("uy")))
  -- The slope moves down and out (+x, down); the level ground far behind it hardly moves.
  assert(summary.crest.ux > 0 and summary.crest.uy < 0,
         string.format("the crest moved %.4g, %.4g m: not down the slope", summary.crest.ux, summary.crest.uy))
  assert(summary.crest.ux < 2, "the crest moved over 2 m")
  assert(math.abs(summary.free_field.ux) < 0.5 * summary.crest.ux + 0.01,
         string.format("the free-field surface kept %.4g m against the crest's %.4g m", summary.free_field.ux,
                       summary.crest.ux))
  print("check passed")
end
