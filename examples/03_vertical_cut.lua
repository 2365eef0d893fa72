-- Example 3: a vertical cut in cohesive-frictional soil (Mohr-Coulomb, psi = 0).
-- Classical critical height (upper bound): H_c = 3.83 c / gamma tan(45 + phi/2). Cuts of 0.7 H_c and
-- 1.3 H_c settle under gravity with local damping: the first stands, the second collapses.
--   seismpm examples/03_vertical_cut.lua [--set cells=16] [--set duration=3]
local c, phi, rho, g = 10e3, 20, 2000, 9.81                  -- Pa, degrees, kg/m3, m/s2
local cells = mpm.param("cells", 16)                          -- cells over the cut's height
local duration = mpm.param("duration", 3.0)                   -- s
local Hc = 3.83 * c / (rho * g) * math.tan(math.rad(45 + phi / 2))
print(string.format("critical height H_c = %.3f m (c = %g Pa, phi = %g deg, gamma = %g N/m3)", Hc, c, phi, rho * g))

local function cut(ratio)
  local H = ratio * Hc
  local m = mpm.model{ domain = {{0, 0}, {3.5 * H, 1.25 * H}}, cell = H / cells }
  -- H_c assumes the soil takes tension up to the apex of the cone: no cut-off below it.
  local soil = mpm.material.mohr_coulomb{ density = rho, young = 50e6, poisson = 0.3, cohesion = c,
                                          friction = phi, dilation = 0, tension = c / math.tan(math.rad(phi)) }
  local ground = m:body{ name = "soil", material = soil, shape = mpm.shape.rectangle{ 0, 0, 2 * H, H } }
  m:fix{ side = "left", dof = "x" }
  m:fix{ side = "bottom", dof = "xy" }
  local crest = m:probe{ name = "crest", body = ground, at = {2 * H, H} }
  m:run{ duration = duration, damping = 0.7 }
  local u = math.sqrt(crest:get("ux")^2 + crest:get("uy")^2)
  local yielding = 0
  for _, y in ipairs(ground:field("yield")) do yielding = yielding + y end
  print(string.format("  H = %.2f H_c = %.3f m: crest moved %.4f m (%.2f %% of H), %d of %d particles yielding",
                      ratio, H, u, 100 * u / H, yielding, ground:count()))
  return u / H
end

local low, high = cut(0.7), cut(1.3)
assert(low < 0.01, "the 0.7 H_c cut should stand")
assert(high > 0.05, "the 1.3 H_c cut should collapse")
print("the 0.7 H_c cut stands and the 1.3 H_c cut collapses, as the closed form says")
