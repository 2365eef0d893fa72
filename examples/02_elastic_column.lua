-- Example 2: a laterally confined elastic column settling under its own weight.
-- Local damping brings it to rest; then sigma_v = rho g depth and sigma_h / sigma_v = nu / (1 - nu).
--   seismpm examples/02_elastic_column.lua [--set cells=50]
local H, rho, g, E, nu = 1.0, 2000, 9.81, 1e7, 0.3          -- m, kg/m3, m/s2, Pa, -
local cells = mpm.param("cells", 50)
local h = H / cells

local m = mpm.model{ domain = {{0, 0}, {2 * h, 1.2 * H}}, cell = h, gravity = {0, -g} }
local soil = mpm.material.linear_elastic{ density = rho, young = E, poisson = nu }
local column = m:body{ name = "column", material = soil, shape = mpm.shape.rectangle{ 0, 0, 2 * h, H } }
m:fix{ side = "bottom", dof = "xy" }
m:fix{ side = "left", dof = "x" }
m:fix{ side = "right", dof = "x" }
local mid = m:probe{ name = "mid-depth", body = column, at = {h, H / 2} }

m:run{ duration = 1.0, damping = 0.7 }

-- Compare cell rows (two particles high each) with the closed form, away from the ends.
local y, uy, syy, sxx = column:field("y"), column:field("uy"), column:field("syy"), column:field("sxx")
local rows = {}
for i = 1, #y do
  local y0 = y[i] - uy[i]
  local depth = H - y0
  if depth > 0.1 * H and depth < 0.9 * H then
    local r = math.floor(y0 / h)
    rows[r] = rows[r] or { s = 0, exact = 0, ratio = 0, n = 0 }
    local row = rows[r]
    row.s, row.exact, row.n = row.s + syy[i], row.exact - rho * g * depth, row.n + 1
    row.ratio = math.max(row.ratio, math.abs(sxx[i] / syy[i] - nu / (1 - nu)) / (nu / (1 - nu)))
  end
end
local worst, worst_ratio = 0, 0
local out = mpm.out_dir("out/elastic_column")
m:output{ dir = out }   -- makes the directory, with the settled state for ParaView (particles.pvd)
local csv = assert(io.open(out .. "/vertical_stress.csv", "w"))
csv:write("depth (m),sigma_yy (Pa),exact (Pa)\n")
for r, row in pairs(rows) do
  worst = math.max(worst, math.abs(row.s - row.exact) / math.abs(row.exact))
  worst_ratio = math.max(worst_ratio, row.ratio)
  csv:write(string.format("%.5f,%.6g,%.6g\n", H - (r + 0.5) * h, row.s / row.n, row.exact / row.n))
end
csv:close()
local t, sv = mid:series("syy")
local mid_depth = H - (mid:get("y") - mid:get("uy"))
print(string.format("elastic column, %d particles, %d steps, kinetic energy at the end %.3g J/m",
                    column:count(), m:steps(), m:energy().kinetic))
print(string.format("  cell-average sigma_v vs rho g depth: worst error %.4f %%", 100 * worst))
print(string.format("  sigma_h / sigma_v vs nu / (1 - nu): worst error %.2e", worst_ratio))
print(string.format("  probe at depth %.3f m: sigma_yy = %.1f Pa after %d samples (exact %.1f Pa)",
                    mid_depth, sv[#sv], #t, -rho * g * mid_depth))
assert(worst < 0.01 and worst_ratio < 0.03, "the column is off the geostatic stress")
