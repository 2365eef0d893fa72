-- Example 1: the vibrating elastic bar (Sulsky, Chen & Schreyer 1994), first axial mode.
-- A bar fixed at x = 0 and free at x = L starts with v(x) = v0 sin(pi x / 2L). The closed form:
-- the centre of mass moves with v_cm(t) = (2/pi) v0 cos(omega t), omega = (pi / 2L) sqrt(E / rho),
-- period T = 4 L / sqrt(E / rho). Plane strain with nu = 0 makes the 2D model a 1D bar.
-- E and rho are the benchmark's own (dimensionless) values: seismpm warns that they are no soil's.
--   seismpm examples/01_vibrating_bar.lua [--set cells=25]
local L, E, rho, v0 = 25.0, 100.0, 1.0, 0.1                -- m, Pa, kg/m3, m/s
local cells = mpm.param("cells", 25)                          -- cells along the bar
local h = L / cells

local m = mpm.model{ domain = {{0, 0}, {L + 4 * h, 2 * h}}, cell = h, gravity = {0, 0}, cfl = 0.1 }
local steel = mpm.material.linear_elastic{ density = rho, young = E, poisson = 0 }
local bar = m:body{ name = "bar", material = steel, ppc = 2, shape = mpm.shape.rectangle{ 0, 0, L, h } }
m:fix{ side = "left", dof = "x" }
bar:set_velocity(function(x, y) return v0 * math.sin(math.pi * x / (2 * L)), 0 end)

local tip = m:probe{ name = "free_end", body = bar, at = {L, h / 2}, every = 0.05 }
local c = math.sqrt(E / rho)
local period, amplitude = 4 * L / c, 2 / math.pi * v0

-- Centre-of-mass velocity from the particle fields.
local mass = bar:field("mass")
local function v_cm()
  local vx, s, mt = bar:field("vx"), 0, 0
  for i = 1, #vx do s, mt = s + mass[i] * vx[i], mt + mass[i] end
  return s / mt
end

local out = mpm.out_dir("out/vibrating_bar")
m:output{ dir = out, every = 0.5 }                           -- ParaView: open out/vibrating_bar/particles.pvd
local csv = assert(io.open(out .. "/centre_of_mass_velocity.csv", "w"))
csv:write("time (s),v_cm (m/s),v_cm exact (m/s)\n")

local t_prev, v_prev, crossings, peak = 0, v_cm(), {}, 0
while m:time() < 2 * period do
  m:step()
  local t, v = m:time(), v_cm()
  csv:write(string.format("%.6g,%.8g,%.8g\n", t, v, amplitude * math.cos(math.pi / (2 * L) * c * t)))
  if (v_prev > 0) ~= (v > 0) then crossings[#crossings + 1] = t_prev + (t - t_prev) * v_prev / (v_prev - v) end
  peak = math.max(peak, math.abs(v))
  t_prev, v_prev = t, v
end
csv:close()

local measured = crossings[3] - crossings[1]
local period_error = math.abs(measured - period) / period
local amplitude_error = math.abs(peak - amplitude) / amplitude
print(string.format("vibrating bar, %d cells, %d particles, %d steps", cells, bar:count(), m:steps()))
print(string.format("  period    %.5f s (exact %.5f s): error %.3f %%", measured, period, 100 * period_error))
print(string.format("  amplitude %.6f m/s (exact %.6f m/s): error %.3f %%", peak, amplitude, 100 * amplitude_error))
print("  history written to " .. out .. "/centre_of_mass_velocity.csv")
for _, png in ipairs(m:plot{ quantities = {"ux", "vx"} }) do print("  plot " .. png) end
print("  plot " .. mpm.plot{ file = out .. "/centre_of_mass_velocity.csv", x = "time (s)", y = {"v_cm (m/s)"},
                             reference = {"v_cm exact (m/s)"}, title = "Velocity of the bar's centre of mass",
                             ylabel = "centre-of-mass velocity (m/s)" })
print("  ParaView: " .. out .. "/particles.pvd")
assert(period_error < 0.02 and amplitude_error < 0.02, "the bar is off its closed form by more than 2 %")
