-- Mesh sensitivity of the shaking-table slope (the paper's Table A.1: about 25k, 48k and 100k
-- particles): runs scenarios/shaking_table.lua at three cell sizes and prints, for each, the particle
-- count, cell size, wall time, the maximum total displacement at the end of shaking and the two
-- control points, then the spread. The cell sizes divide the 0.9 m box into 120, 168 and 240 cells,
-- so the walls lie on grid lines (2 x 2 particles per cell: 24,820, 48,816 and 99,672 particles).
-- The fine runs are long on 2 cores (measured: 0.75 cm 12-35 min, 0.536 cm 91 min, 0.375 cm 1.9 hours,
-- depending on the machine; docs/validation.md has the study's results): pick fewer with
-- --set cells=0.0075,0.0055 or shorten them with --set duration=4. Each run writes into
-- <out>/cell_<size>/, and the table goes to <out>/mesh_sensitivity.csv, where <out> is --out DIR or
-- out/mesh_sensitivity.
--
-- --set reuse=true takes the summary of a run already made at the same duration (an interrupted study
-- goes on where it stopped; runs made by hand with shaking_table.lua --out <out>/cell_<size> count too).
--
--   seismpm scenarios/mesh_sensitivity.lua [--set cells=0.0075,0.00535714,0.00375] [--set duration=14]
--                                          [--set reuse=true]

local cells_text = mpm.param("cells", string.format("%.8g,%.8g,%.8g", 0.9 / 120, 0.9 / 168, 0.9 / 240))  -- m
local duration = mpm.param("duration", 14.0)
local check = mpm.param("check", false)   -- assert the runs are consistent (ctest)
local reuse = mpm.param("reuse", false)   -- take a finished run's summary.txt instead of running it again
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
local base_out = mpm.out_dir("out/mesh_sensitivity")

local cells = {}
for c in tostring(cells_text):gmatch("[^,]+") do cells[#cells + 1] = tonumber(c) end
assert(#cells > 0, "--set cells must be a comma-separated list of cell sizes (m)")

local function read_summary(cell)
  local f = io.open(string.format("%s/cell_%g/summary.txt", base_out, cell))
  if not f then return nil end
  local text = f:read("a")
  f:close()
  local shaken = tonumber(text:match("maximum total displacement at ([%d%.]+) s of shaking"))
  if not shaken or math.abs(shaken - duration) > 0.05 then return nil end  -- another duration: run again
  return {
    cell = cell,
    particles = tonumber(text:match("soil particles: (%d+)")),
    u_max = tonumber(text:match("maximum total displacement at [%d%.]+ s of shaking: ([%d%.]+) m")),
    crest_uy = tonumber(text:match("point 1 %(crest%) uy = ([-%d%.]+) m")),
    face_ux = tonumber(text:match("point 2 %(face%) ux = ([-%d%.]+) m")),
    wall = tonumber(text:match("wall time: (%d+) s")),
  }
end

-- Each run is the scenario itself, with its parameters overridden.
local function run(cell)
  if reuse then
    local done = read_summary(cell)
    if done then
      print(string.format("cell %g m: reusing %s/cell_%g/summary.txt", cell, base_out, cell))
      return done
    end
  end
  local saved = mpm.param
  local overrides = { cell = cell, duration = duration, every = duration, verbose = false, check = false }
  mpm.param = function(name, default)
    if overrides[name] ~= nil then return overrides[name] end
    return saved(name, default)
  end
  -- The scenario writes into mpm.out_dir(its default): here, this run's folder.
  local saved_out = mpm.out_dir
  mpm.out_dir = function() return string.format("%s/cell_%g", base_out, cell) end
  local start = os.time()
  local ok, err = pcall(dofile, here .. "shaking_table.lua")
  mpm.param, mpm.out_dir = saved, saved_out
  if not ok then error(err, 0) end
  -- The scenario's summary has what we need.
  local r = assert(read_summary(cell), "the run wrote no summary.txt")
  r.wall = os.time() - start
  return r
end

local results = {}
for _, c in ipairs(cells) do results[#results + 1] = run(c) end

local lines = { "cell (m),particles,wall time (s),maximum total displacement (m),point 1 uy (m),point 2 ux (m)" }
print(string.format("\n%10s %10s %10s %12s %12s %12s", "cell (m)", "particles", "wall (s)", "u_max (m)",
                    "point1 uy", "point2 ux"))
for _, r in ipairs(results) do
  print(string.format("%10.5f %10d %10d %12.4f %12.4f %12.4f", r.cell, r.particles, r.wall, r.u_max, r.crest_uy,
                      r.face_ux))
  lines[#lines + 1] = string.format("%.8g,%d,%d,%.5f,%.5f,%.5f", r.cell, r.particles, r.wall, r.u_max, r.crest_uy,
                                    r.face_ux)
end
-- The spread of each measure: half the range about the mean, in per cent (the paper's +-7 %).
local function spread(key)
  local lo, hi, sum = math.huge, -math.huge, 0
  for _, r in ipairs(results) do lo, hi, sum = math.min(lo, r[key]), math.max(hi, r[key]), sum + r[key] end
  local mean = sum / #results
  return lo, hi, mean, 50 * (hi - lo) / math.abs(mean)
end
for _, q in ipairs{ {"u_max", "maximum total displacement"}, {"crest_uy", "point 1 (crest) uy"},
                    {"face_ux", "point 2 (face) ux"} } do
  local lo, hi, mean, pct = spread(q[1])
  print(string.format("spread of the %s: %.4f .. %.4f m, +-%.1f %% about the mean %.4f m%s", q[2], lo, hi, pct,
                      mean, q[1] == "u_max" and " (paper: about +-7 %)" or ""))
end
local f = assert(io.open(base_out .. "/mesh_sensitivity.csv", "w"))
f:write(table.concat(lines, "\n"), "\n")
f:close()

if check then
  for k = 2, #results do
    assert(results[k].particles > results[k - 1].particles, "finer cells must give more particles")
  end
  for _, r in ipairs(results) do assert(r.u_max == r.u_max and r.u_max >= 0, "displacement not finite") end
  print("check passed")
end
