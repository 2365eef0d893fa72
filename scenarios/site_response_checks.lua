-- The site-response boundaries against closed forms (docs/site-response.md draws these pictures):
--
-- 1. amplification: an elastic layer H = 10 m (rho 2000 kg/m3, Vs 100 m/s) on a compliant base (rock
--    rho 2400 kg/m3, Vs 400 m/s) under a harmonic outcrop velocity, at frequencies from 0.2 to 4 f1
--    (f1 = Vs / 4H = 2.5 Hz): the steady surface amplitude over the outcrop's against
--    1 / sqrt(cos^2 kH + alpha^2 sin^2 kH), alpha = rho Vs / (rho_r Vr) = 0.208.
--    <out>/amplification.csv and .png.
-- 2. free field: a layer 20 m wide on the same base at 0.8 f1, with free-field sides and with rollers
--    (the sides held in x): the surface amplitude across the layer against the 1D value.
--    <out>/free_field.csv and .png.
--
--   seismpm scenarios/site_response_checks.lua [--set cell=0.25] [--set ratios=0.5,1,3] [--set free_field=false]
--                                              [--set check=true]
-- ratios: the frequencies of part 1 as multiples of f1 (default 17 of them from 0.2 to 4); free_field =
-- false skips part 2; duration (s, default 4) is each run's, the last second measured.

local cell = mpm.param("cell", 0.25)
local check = mpm.param("check", false)
local ratios_text = mpm.param("ratios", "0.2,0.5,0.8,0.9,1,1.1,1.3,1.6,2,2.4,2.7,2.85,3,3.15,3.3,3.6,4")
local free_field_part = mpm.param("free_field", true)
local out = mpm.out_dir("out/site_response_checks")
local H, rho, vs, nu = 10, 2000, 100, 0.25
local rock = { density = 2400, vs = 400, vp = 700 }
local alpha = rho * vs / (rock.density * rock.vs)
local f1 = vs / (4 * H)
local amplitude = 0.01 -- m/s, outcrop velocity
local made_out = false

local function closed_form(f, depth)
  local k = 2 * math.pi * f / vs
  return math.cos(k * depth) / math.sqrt(math.cos(k * H) ^ 2 + alpha ^ 2 * math.sin(k * H) ^ 2)
end

-- A layer of the given width on the compliant base, shaken at f; sides "free_field", "rollers" or
-- "column" (held vertically only: a 1D column). Returns the surface displacement amplitudes at xs over
-- the last second of `duration`, as multiples of the outcrop's.
local function shake(width, f, sides, xs, duration)
  local m = mpm.model{ domain = { { 0, 0 }, { width, H } }, cell = cell, shape = "linear", gravity = { 0, 0 } }
  local soil = mpm.material.linear_elastic{ density = rho, young = 2 * rho * vs ^ 2 * (1 + nu), poisson = nu }
  local layer = m:body{ name = "layer", material = soil, shape = mpm.shape.rectangle{ 0, 0, width, H } }
  local w = 2 * math.pi * f
  m:boundary{ side = "bottom", kind = "compliant", frame = "fixed", density = rock.density, vs = rock.vs,
              vp = rock.vp, input = { mpm.history.fn(function(t) return amplitude * math.sin(w * t) end), 0 } }
  for _, side in ipairs({ "left", "right" }) do
    if sides == "free_field" then m:boundary{ side = side, kind = "free_field" }
    elseif sides == "rollers" then m:fix{ side = side, dof = "x" }
    else m:fix{ side = side, dof = "y" } end
  end
  if not made_out then -- the first run makes the output directory (and leaves its first state there)
    m:output{ dir = out, every = 1e6, at_run_end = false }
    made_out = true
  end
  local probes = {}
  for i, x in ipairs(xs) do probes[i] = m:probe{ name = "p" .. i, body = layer, at = { x, H }, every = 0 } end
  m:run{ duration = duration - 1 }
  local lo, hi = {}, {}
  for i = 1, #xs do lo[i], hi[i] = math.huge, -math.huge end
  m:run{ duration = 1, every = 0.002, call = function()
    for i, p in ipairs(probes) do
      local u = p:get("ux")
      lo[i], hi[i] = math.min(lo[i], u), math.max(hi[i], u)
    end
  end }
  local result = {}
  for i = 1, #xs do result[i] = 0.5 * (hi[i] - lo[i]) / (amplitude / w) end
  return result
end

-- 1. Amplification against frequency.
local depth = cell / 4 -- the top particles' depth (2 per cell)
local rows, worst = { "f (Hz),f/f1,seismpm,closed form" }, 0
local ratios = {}
for r in tostring(ratios_text):gmatch("[^,]+") do ratios[#ratios + 1] = assert(tonumber(r), "--set ratios: " .. r) end
for _, ratio in ipairs(ratios) do
  local f = ratio * f1
  local a = shake(2 * cell, f, "column", { cell }, mpm.param("duration", 4))[1]
  local exact = closed_form(f, depth)
  worst = math.max(worst, math.abs(a / exact - 1))
  rows[#rows + 1] = string.format("%.6g,%.6g,%.6g,%.6g", f, ratio, a, exact)
  print(string.format("f = %5.2f Hz (%.1f f1): amplification %.4f, closed form %.4f (%+.2f %%)", f, ratio, a, exact,
                      100 * (a / exact - 1)))
end
local file = out .. "/amplification.csv"
local fh = assert(io.open(file, "w"))
fh:write(table.concat(rows, "\n"), "\n")
fh:close()
mpm.plot{ file = file, x = "f/f1", y = { "seismpm" }, reference = { "closed form" }, xlabel = "f / f1 (f1 = Vs / 4H)",
          ylabel = "surface / outcrop amplitude", title = "Layer on a compliant base (alpha = 0.208)" }
print(string.format("amplification: largest error %.2f %%", 100 * worst))

if not free_field_part then
  if check then
    assert(worst < 0.05, "amplification off the closed form by " .. worst)
    print("check passed")
  end
  return
end

-- 2. Free-field sides against rollers across a wide layer.
local width, f = 20, 0.8 * f1
local xs = {}
for x = cell / 2, width, 1 do xs[#xs + 1] = x end
local exact = closed_form(f, depth)
local free = shake(width, f, "free_field", xs, 4)
local rollers = shake(width, f, "rollers", xs, 4)
rows = { "x (m),free-field sides,rollers,1D column" }
local worst_free, worst_rollers = 0, 0
for i, x in ipairs(xs) do
  rows[#rows + 1] = string.format("%.6g,%.6g,%.6g,%.6g", x, free[i], rollers[i], exact)
  worst_free = math.max(worst_free, math.abs(free[i] / exact - 1))
  worst_rollers = math.max(worst_rollers, math.abs(rollers[i] / exact - 1))
end
file = out .. "/free_field.csv"
fh = assert(io.open(file, "w"))
fh:write(table.concat(rows, "\n"), "\n")
fh:close()
mpm.plot{ file = file, x = "x (m)", y = { "free-field sides", "rollers" }, reference = { "1D column" },
          xlabel = "x across the layer (m)", ylabel = "surface / outcrop amplitude",
          title = "A 20 m wide layer at 0.8 f1: free-field sides and rollers" }
print(string.format("free field: largest departure from the 1D column %.2f %% (rollers: %.1f %%)", 100 * worst_free,
                    100 * worst_rollers))
if check then
  assert(worst < 0.05, "amplification off the closed form by " .. worst)
  assert(worst_free < 0.05, "free-field layer off the 1D column by " .. worst_free)
  assert(worst_rollers > 0.5, "rollers matched the 1D column: the check cannot tell the sides apart")
  print("check passed")
end
