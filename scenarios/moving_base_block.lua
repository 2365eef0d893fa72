-- A block on a suddenly moving base: the paper's check of prescribed-velocity particles with
-- frictional contact (Bhandari et al. 2016, §2.4.2).
--
-- A 1 m x 1 m elastic block of unit weight 10 kN/m3 rests on a layer of 45 prescribed-velocity
-- particles (one row, 0.1 m apart). A gravity phase brings it to rest (local damping 0.7, tolerance
-- 0.005); then, in the dynamic phase, the base suddenly moves at 2 m/s to the right. Three variants:
--   --set contact=none    no contact declared: block and base share one velocity field where they
--                         meet, so the block is carried along (glued);
--   --set contact=rough   Coulomb friction mu (--set friction=0.3): the glue breaks, the block slides,
--                         accelerating at mu g until it has the base's speed (at t* = v / (mu g)), then
--                         rides along; its centroid moves 0.5 mu g t^2 up to t*;
--   --set contact=smooth  mu = 0: the base slides away under the block, which stays where it is.
-- Outputs (out/moving_base_block_<contact>/): particles.pvd and rigid.pvd for ParaView, probes.csv,
-- reactions.csv (the base's force on the block), block_motion.csv, closed_form.csv, and probe_ux and
-- probe_vx (.png and .svg): the block's centre against the closed form, in the time since the base started.
--
--   seismpm scenarios/moving_base_block.lua --set contact=rough [--set friction=0.3] [--set cell=0.1]

local contact = mpm.param("contact", "rough")   -- none | rough | smooth
local friction = mpm.param("friction", 0.3)     -- Coulomb mu of the rough variant
local cell = mpm.param("cell", 0.1)             -- m; the base layer is one particle per cell
local speed = mpm.param("speed", 2.0)           -- m/s, the base's sudden velocity
local duration = mpm.param("duration", 1.0)     -- s of base motion
local check = mpm.param("check", false)         -- assert the closed-form answers (ctest)
if contact ~= "none" and contact ~= "rough" and contact ~= "smooth" then
  error("--set contact must be none, rough or smooth, got '" .. tostring(contact) .. "'", 0)
end
if contact == "smooth" then friction = 0 end
local g = 9.81

if not (duration > 0) then error("--set duration must be positive, got " .. duration, 0) end
-- The base reaches 0.5 m plus its travel (at least 2 m) behind the block and 1 m ahead of it, so the
-- block keeps its support whatever the variant, and the grid holds the base wherever it goes.
local reach = math.max(2.0, math.abs(speed) * duration)
local base_lo, base_hi = -0.5 - reach, 2.0
local lo, hi = base_lo - 0.2, base_hi + 0.3 + reach
if speed < 0 then base_lo, base_hi, lo, hi = -1.0, 1.5 + reach, -1.0 - 0.3 - reach, 1.5 + reach + 0.2 end
local m = mpm.model{ domain = {{lo, -0.3}, {hi, 1.3}}, cell = cell, gravity = {0, -g} }
local elastic = mpm.material.linear_elastic{ density = 10e3 / g, young = 10e6, poisson = 0.3 }
local block = m:body{ name = "block", material = elastic, shape = mpm.shape.rectangle{ 0, 0, 1, 1 }, ppc = 2 }
-- The base follows `speed` in the dynamic phase; the gravity phase holds every rigid body at rest.
local base = m:rigid{ name = "base", shape = mpm.shape.rectangle{ base_lo, -cell, base_hi, 0 }, ppc = 1,
                      velocity = {speed, 0} }
if contact ~= "none" then m:contact{ block, base, friction = friction } end
print(string.format("block: %d particles; base: %d prescribed-velocity particles; contact: %s%s",
                    block:count(), base:count(), contact,
                    contact == "none" and "" or string.format(" (mu = %g)", friction)))

local centre = m:probe{ name = "block_centre", body = block, at = {0.5, 0.5}, every = 0.01 }
local dir = mpm.out_dir("out/moving_base_block_" .. contact)
m:output{ dir = dir, every = 0.05 }

-- 1. Rest under gravity, base held still, damped to equilibrium; displacements reset at the end.
local eq = m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 2 }
local f = base:reaction()
print(string.format("at rest after %.3f s: the base carries %.0f N/m (the block's weight is %.0f N/m)",
                    eq.time, f[2], 10e3 * 1 * 1))

-- 2. The dynamic phase: the base moves at `speed` from its first step.
local x0 = block:centroid()[1]
local function exact(t)  -- centroid displacement with Coulomb friction
  if contact == "none" then return speed * t end
  if friction == 0 then return 0 end
  local a = friction * g
  local ts = speed / a
  if t <= ts then return 0.5 * a * t * t end
  return 0.5 * a * ts * ts + speed * (t - ts)
end
local function exact_velocity(t)  -- its velocity
  if contact == "none" then return speed end
  return math.min(friction * g * t, speed)
end

local rows = { "time since the base started (s),block centroid ux (m),closed form (m)" }
print("   t (s)   block ux (m)   closed form (m)")
local worst = 0
-- The base moves; every 0.1 s the block's centroid is compared with the closed form.
m:dynamic_phase{ duration = duration, every = 0.1, call = function()
  local t = m:phase_time()
  local u = block:centroid()[1] - x0
  local e = exact(t)
  print(string.format("%8.3f %14.5f %17.5f", t, u, e))
  rows[#rows + 1] = string.format("%.6g,%.8g,%.8g", t, u, e)
  if e > 0 then worst = math.max(worst, math.abs(u - e) / e) end
end }
local file = assert(io.open(dir .. "/block_motion.csv", "w"))
file:write(table.concat(rows, "\n"), "\n")
file:close()
-- The closed form every 0.01 s, drawn with the block's centre in probe_ux and probe_vx.
local closed = { "time since the base started (s),centroid ux (m),centroid vx (m/s)" }
for k = 0, math.floor(duration / 0.01 + 0.5) do
  local t = k * 0.01
  closed[#closed + 1] = string.format("%.4f,%.8g,%.8g", t, exact(t), exact_velocity(t))
end
file = assert(io.open(dir .. "/closed_form.csv", "w"))
file:write(table.concat(closed, "\n"), "\n")
file:close()
local title = contact == "none" and "closed form: carried along" or
              string.format("closed form: Coulomb friction, mu = %g", friction)
for _, q in ipairs({ {"ux", "centroid ux (m)"}, {"vx", "centroid vx (m/s)"} }) do
  for _, png in ipairs(m:plot{ quantities = {q[1]}, reference = { quantity = q[1], file = dir .. "/closed_form.csv",
                                                                   x = "time since the base started (s)", y = q[2],
                                                                   title = title } }) do
    print("plot: " .. png)
  end
end

local u_end = block:centroid()[1] - x0
if contact == "smooth" then
  print(string.format("smooth: the block moved %.2e m while the base moved %.2f m", u_end, speed * duration))
else
  print(string.format("largest relative error of the centroid displacement: %.2f %%", 100 * worst))
end

if check then
  if contact == "smooth" then
    assert(math.abs(u_end) < 1e-3, "a smooth base must leave the block behind")
  elseif contact == "rough" then
    assert(worst < 0.03, "the block should follow 0.5 mu g t^2 within 3 %")
  else
    assert(math.abs(u_end - speed * duration) < 0.05 * speed * duration, "the glued block should ride along")
  end
  print("check passed")
end
