-- The engineer's simple methods beside MPM, on the paper's two slopes (issue 18, item 5): for the
-- shaking-table slope (scenarios/shaking_table.lua) and the Chiu-fen-erh-shan slope
-- (scenarios/chichi_landslide.lua), each run as it is, with its parameters overridden:
--   * limit equilibrium (mpm.lem: Bishop's circle search on the shaking table, Spencer on the bedding
--     plane of the field slope): the static factor of safety (kh = 0) and the yield acceleration ky (g),
--     on the model as built, before any phase;
--   * Newmark's rigid sliding block (mpm.newmark) with that ky on the acceleration of the horizontal
--     base motion the MPM model gets (the table's velocity, the valley floor's record), differentiated
--     between its samples; both slopes descend towards +x, so a base acceleration towards -x drives the
--     mass down-slope: the block is given -dv/dt (the same record reversed beside it, for the polarity);
--   * MPM: the displacement, relative to the moving base, of a probe on the ground surface a quarter of
--     the critical slip surface's span below its upper end (the top of the sliding mass), at the end of
--     shaking. The base's displacement is its velocity history integrated (the table; the bedding, which
--     moves along the dip).
-- One table (printed, and <out>/three_methods.csv) and, per slope, the two displacement histories
-- (<out>/<slope>_displacement.csv and .png). Each MPM run writes into <out>/<slope>/ (its own files);
-- <out> is --out DIR or out/three_methods.
--
-- The field record: the TCU068 EW record (Chi-Chi 1999) where the shared data holds it
-- (../../shared/data/ground_motions/Chi-Chi_1999_TCU068-090.csv from this folder, or --set field_record=
-- FILE), else, as chichi_landslide.lua does without a record, its synthetic near-fault pulse
-- (--set field_record=synthetic asks for that).
--
-- --set reuse=true takes an MPM result this scenario wrote before (<out>/<slope>/three_methods_mpm.csv,
-- same cell size, duration, record and probe) instead of running MPM again: the models are still built, for
-- limit equilibrium and the base motion, but no phase runs.
--
--   seismpm scenarios/three_methods.lua [--set cell=0.0125,10] [--set slopes=shaking_table,chichi_landslide]
--                                       [--set field_record=FILE|synthetic] [--set reuse=true] [--set check=true]

local cells_text = mpm.param("cell", "0.0125,10")   -- m: the shaking table's cell, the field slope's
local slopes_text = mpm.param("slopes", "shaking_table,chichi_landslide")
local reuse = mpm.param("reuse", false)
local check = mpm.param("check", false)             -- assert the numbers (ctest)
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
local out = mpm.out_dir("out/three_methods")
local g = 9.80665

local function exists(file)
  local f = io.open(file)
  if f then f:close() end
  return f ~= nil
end

local field_record = mpm.param("field_record", "")
if field_record == "" then
  local shared = here .. "../../shared/data/ground_motions/Chi-Chi_1999_TCU068-090.csv"
  field_record = exists(shared) and shared or "synthetic"
  if field_record == "synthetic" then
    print("the TCU068 record is not in the shared data: the field slope takes chichi_landslide.lua's synthetic pulse")
  end
end

local cells = {}
for c in tostring(cells_text):gmatch("[^,]+") do cells[#cells + 1] = tonumber(c) end
assert(#cells == 2 and cells[1] and cells[2], "--set cell must be two cell sizes (m): the shaking table's, the field slope's")

-- Each slope: its scenario, the parameters it is run with, its base bodies (by name), its method.
local slopes = {
  shaking_table = {
    title = "shaking table (45 deg Masa-soil slope)", script = "shaking_table.lua",
    params = { cell = cells[1], duration = 14, every = 14, record = "data/table_velocity.csv", verbose = false },
    base = "base", driver = "base", probe_every = 0.02,
    method = "bishop", lem = function(m) return { model = m } end,
  },
  chichi_landslide = {
    title = "Chiu-fen-erh-shan (22 deg dip slope)", script = "chichi_landslide.lua",
    params = { cell = cells[2], duration = 120, every = 120,
               record = field_record == "synthetic" and "" or field_record },
    base = "bedding", driver = "valley_floor", probe_every = 0.5,
    -- The slide is on the bedding, not on a circle: Spencer's method on the bedding plane (22 degrees,
    -- reaching the valley floor at x = 1400 m, as chichi_landslide.lua builds it), then along the floor
    -- under the toe, and up out of the ground beyond it. The surface carries the rock's c and phi.
    method = "spencer",
    lem = function(m)
      local t = math.tan(math.rad(22))
      return { model = m, method = "spencer", surface = { {-50, 1450 * t}, {1400, 0}, {1650, 0}, {1750, 100} } }
    end,
  },
}
local order = {}
for key in tostring(slopes_text):gmatch("[^,]+") do
  assert(slopes[key], "--set slopes: unknown slope '" .. key .. "' (shaking_table, chichi_landslide)")
  order[#order + 1] = key
end

-- A value of a rigid body's velocity component: a number or a history, at phase time t.
local function component(v, t)
  if type(v) == "number" then return v end
  return v:at(t)
end

-- The base's displacement (x, y) since the start of shaking at the times asked (increasing): its
-- velocity integrated with the trapezoidal rule every millisecond.
local function base_displacement(velocity, times)
  local dt, t, ux, uy = 0.001, 0, 0, 0
  local vx, vy = component(velocity[1], 0), component(velocity[2], 0)
  local out = {}
  for k, tk in ipairs(times) do
    while t + dt <= tk do
      local wx, wy = component(velocity[1], t + dt), component(velocity[2], t + dt)
      ux, uy = ux + 0.5 * dt * (vx + wx), uy + 0.5 * dt * (vy + wy)
      vx, vy, t = wx, wy, t + dt
    end
    local h = tk - t  -- the last part step, to the sample
    local wx, wy = component(velocity[1], tk), component(velocity[2], tk)
    out[k] = { ux + 0.5 * h * (vx + wx), uy + 0.5 * h * (vy + wy) }
  end
  return out
end

-- The acceleration that drives the mass down-slope (+x): -dvx/dt of the base's horizontal velocity,
-- between samples 5 ms apart (the records' own spacing), at the samples' midpoints; and its peak (g).
local function driving_acceleration(vx, duration)
  local dt, points, peak = 0.005, {}, 0
  local n = math.floor(math.min(duration, vx:duration()) / dt + 1e-9)
  for k = 0, n - 1 do
    local a = -(vx:at((k + 1) * dt) - vx:at(k * dt)) / dt
    points[#points + 1] = { (k + 0.5) * dt, a }
    peak = math.max(peak, math.abs(a))
  end
  return mpm.history.table(points), peak / g, (n - 0.5) * dt, points
end

-- The probe's place: on the ground surface, a quarter of the slip surface's span below its upper end.
local function probe_point(soil, surface, cell)
  local a, b = surface[1], surface[#surface]
  if a[2] < b[2] then a, b = b, a end
  local x = a[1] + 0.25 * (b[1] - a[1])
  local xs, ys = soil:field("x"), soil:field("y")
  local top = -math.huge
  for i = 1, #xs do
    if math.abs(xs[i] - x) < cell then top = math.max(top, ys[i]) end
  end
  return { x, top }
end

-- An earlier MPM result of this scenario for the same run, or nil.
local function mpm_signature(s)
  return string.format("# cell=%.8g duration=%.8g record=%s probe=%.6g,%.6g", s.params.cell, s.params.duration,
                       s.params.record, s.probe_at[1], s.probe_at[2])
end
local function read_mpm(s)
  local f = io.open(s.dir .. "/three_methods_mpm.csv")
  if not f then return nil end
  local first = f:read("l")
  if first ~= mpm_signature(s) then
    f:close()
    return nil
  end
  f:read("l")  -- the header
  local r = { times = {}, d = {} }
  for line in f:lines() do
    local t, d = line:match("^([^,]+),([^,]+)$")
    r.times[#r.times + 1], r.d[#r.d + 1] = tonumber(t), tonumber(d)
  end
  f:close()
  if #r.d == 0 then return nil end
  return r
end
local function write_mpm(s, r)
  local lines = { mpm_signature(s), "time (s),displacement relative to the base (m)" }
  for k = 1, #r.times do lines[#lines + 1] = string.format("%.5f,%.6g", r.times[k], r.d[k]) end
  local f = assert(io.open(s.dir .. "/three_methods_mpm.csv", "w"))
  f:write(table.concat(lines, "\n"), "\n")
  f:close()
end

-- The scenario with its parameters overridden, into s.dir; its model seen through a proxy that notes
-- its soil body and rigid bodies' velocities, and before the gravity phase runs limit equilibrium and
-- places the probe (or, with reuse and an MPM result of the same run on file, stops the scenario there).
local function run_scenario(s)
  local seen = { rigid = {} }
  local stop = {}
  local saved_model, saved_param, saved_out = mpm.model, mpm.param, mpm.out_dir
  mpm.param = function(name, default)
    if s.params[name] ~= nil then return s.params[name] end
    return saved_param(name, default)
  end
  mpm.out_dir = function() return s.dir end
  mpm.model = function(args)
    local m = saved_model(args)
    local wrapped = {
      body = function(_, a)
        local b = m:body(a)
        seen.soil = seen.soil or b
        return b
      end,
      rigid = function(_, a)
        seen.rigid[a.name] = a.velocity
        return m:rigid(a)
      end,
      gravity_phase = function(_, a)
        local clock = os.clock()
        seen.lem = mpm.lem(s.lem(m))
        seen.lem_time = os.clock() - clock
        s.probe_at = probe_point(seen.soil, seen.lem.surface, s.params.cell)
        seen.probe = m:probe{ name = "three_methods_top", body = seen.soil, every = s.probe_every, at = s.probe_at }
        seen.reused = reuse and read_mpm(s) or nil
        if seen.reused then error(stop, 0) end
        local r = m:gravity_phase(a)
        seen.t0 = m:time()
        return r
      end,
    }
    return setmetatable({}, { __index = function(_, k)
      if wrapped[k] then return wrapped[k] end
      local v = m[k]
      if type(v) == "function" then return function(_, ...) return v(m, ...) end end
      return v
    end })
  end
  local start = os.time()
  local ok, err = pcall(dofile, here .. s.script)
  mpm.model, mpm.param, mpm.out_dir = saved_model, saved_param, saved_out
  if not ok and err ~= stop then error(err, 0) end
  assert(seen.lem, s.script .. " ran no gravity phase: nothing to compare")
  seen.wall = os.time() - start
  return seen
end

-- The MPM result: the probe's displacement relative to the base, at its samples from the start of shaking.
local function mpm_result(s, seen)
  local t, ux = seen.probe:series("ux")
  local _, uy = seen.probe:series("uy")
  local r = { times = {}, d = {} }
  local first
  for k = 1, #t do
    if t[k] >= seen.t0 - 1e-9 then
      first = first or k
      r.times[#r.times + 1] = math.max(t[k] - seen.t0, 0)
    end
  end
  local base = base_displacement(seen.rigid[s.base], r.times)
  for k = 1, #r.times do
    local i = first + k - 1
    r.d[k] = math.sqrt((ux[i] - base[k][1]) ^ 2 + (uy[i] - base[k][2]) ^ 2)
  end
  return r
end

local function run_slope(s)
  local seen = run_scenario(s)
  local lem, reused = seen.lem, seen.reused
  print(string.format("%s: static FoS %.4f, ky %.4f g (limit equilibrium %.1f s); MPM probe at (%.4g, %.4g) m",
                      s.key, lem.fos, lem.ky, seen.lem_time, s.probe_at[1], s.probe_at[2]))
  assert(lem.ky > 0, s.key .. ": the slope fails statically (ky = 0): Newmark's method does not apply")
  local mpm_run = reused or mpm_result(s, seen)
  if reused then
    print(string.format("%s: reusing %s/three_methods_mpm.csv", s.key, s.dir))
  else
    write_mpm(s, mpm_run)
  end
  local a, pba, t_end, points = driving_acceleration(seen.rigid[s.driver][1], s.params.duration)
  local d, history = mpm.newmark{ acceleration = a, ky = lem.ky }
  local d_reversed = mpm.newmark{ acceleration = a, ky = lem.ky, direction = "inverse" }
  local lines = { "time (s),Newmark sliding block (m),MPM top of the sliding mass relative to the base (m)" }
  for k, t in ipairs(mpm_run.times) do
    local nm = t >= t_end and d or history:at(t)
    lines[#lines + 1] = string.format("%.5f,%.6g,%.6g", t, nm, mpm_run.d[k])
  end
  local file = out .. "/" .. s.key .. "_displacement.csv"
  local f = assert(io.open(file, "w"))
  f:write(table.concat(lines, "\n"), "\n")
  f:close()
  local png = mpm.plot{ file = file, x = "time (s)",
                        y = { "Newmark sliding block (m)", "MPM top of the sliding mass relative to the base (m)" },
                        title = string.format("%s: FoS %.2f, ky %.3f g; Newmark %.3g m, MPM %.3g m", s.title,
                                              lem.fos, lem.ky, d, mpm_run.d[#mpm_run.d]),
                        xlabel = "time since the dynamic phase began (s)", ylabel = "permanent displacement (m)" }
  return { key = s.key, title = s.title, cell = s.params.cell, fos = lem.fos, ky = lem.ky, pba = pba, newmark = d,
           newmark_reversed = d_reversed, mpm = mpm_run.d[#mpm_run.d], wall = not reused and seen.wall or nil,
           png = png, method = s.method, acceleration = points }
end

local rows = {}
for _, key in ipairs(order) do
  local s = slopes[key]
  s.key, s.check = key, false
  s.params.check = false
  s.dir = out .. "/" .. key
  rows[#rows + 1] = run_slope(s)
end

-- The table.
local header = { "slope", "cell (m)", "LEM method", "static FoS (LEM kh = 0)", "ky (g)", "peak base acceleration (g)",
                 "Newmark displacement along the slip surface (m)", "Newmark with the record reversed (m)",
                 "MPM displacement of the sliding mass's top relative to the base (m)", "MPM / Newmark",
                 "MPM run (s)" }
local csv = { table.concat(header, ",") }
print(string.format("\n%-40s %8s %8s %8s %9s %12s %12s %12s %8s", "slope", "cell (m)", "FoS", "ky (g)", "PBA (g)",
                    "Newmark (m)", "reversed (m)", "MPM (m)", "MPM/NM"))
for _, r in ipairs(rows) do
  print(string.format("%-40s %8.4g %8.3f %8.4f %9.3f %12.4g %12.4g %12.4g %8.3g", r.title, r.cell, r.fos, r.ky, r.pba,
                      r.newmark, r.newmark_reversed, r.mpm, r.mpm / r.newmark))
  csv[#csv + 1] = string.format("%s,%.6g,%s,%.5f,%.5f,%.5f,%.6g,%.6g,%.6g,%.6g,%s", r.key, r.cell, r.method, r.fos,
                                r.ky, r.pba,
                                r.newmark, r.newmark_reversed, r.mpm, r.mpm / r.newmark,
                                r.wall and tostring(r.wall) or "reused")
end
for _, r in ipairs(rows) do
  print(string.format("%s: FoS by %s", r.key, r.method == "spencer" and "Spencer's method on the bedding" or
                      "Bishop's method, the least over the circles searched"))
end
print("Newmark: rigid block with that ky, along the slip surface; MPM: |u(probe) - u(base)| at the end of shaking")
local f = assert(io.open(out .. "/three_methods.csv", "w"))
f:write(table.concat(csv, "\n"), "\n")
f:close()
print("table: " .. out .. "/three_methods.csv")
for _, r in ipairs(rows) do print("plot: " .. r.png) end

-- What the check asserts of each slope (ctest).
local s_check = {
  -- Bishop's least FoS of the paper's geometry (the exact polygon, not the particles), searched over
  -- toe and deeper circles with 400 slices by an independent program: 1.654 (centre 0.673, 0.670,
  -- r 0.470). The particle model's surface is a staircase of half-cells: 2 %.
  -- The rigid block and the MPM slope: the soil column under the crest (0.53 m, Vs = sqrt(G / rho) =
  -- 24 m/s) has its first shear-beam frequency Vs / (4 H) = 11 Hz, above the table's 6 Hz, so the mass
  -- amplifies the base motion (at most 1 / cos(pi f / (2 f1)) = 1.5 at the crest) and never de-amplifies
  -- it: MPM's mass slides at least as far as the block on the base motion, and at most as far as a block
  -- on the crest's amplified motion.
  shaking_table = function(r)
    assert(math.abs(r.fos / 1.654 - 1) < 0.02, string.format("shaking table: FoS %.4f, not 1.654 +- 2 %%", r.fos))
    assert(r.ky < r.pba, "shaking table: the table must shake past ky, or nothing slides")
    local vs = math.sqrt(2.57e6 / (2 * (1 + 0.33)) / 1680)
    local amplification = 1 / math.cos(math.pi * 6 / (2 * vs / (4 * 0.53)))
    local scaled = {}
    for k, p in ipairs(r.acceleration) do scaled[k] = { p[1], amplification * p[2] } end
    local upper = mpm.newmark{ acceleration = mpm.history.table(scaled), ky = r.ky }
    print(string.format("shaking table: Newmark %.4f m <= MPM %.4f m <= Newmark on the motion x %.2f: %.4f m",
                        r.newmark, r.mpm, amplification, upper))
    assert(r.mpm >= r.newmark and r.mpm <= upper, "shaking table: MPM outside the rigid blocks' bracket")
  end,
  -- Spencer on the bedding against the infinite slope of the pile's thickness (60 m normal to the bedding,
  -- Tv = 64.7 m vertically; rock 2550 kg/m3, c = 20 kPa, phi = 24): F = c / (gamma Tv cos^2 b tan b) +
  -- tan phi / tan b = 1.138. The real pile's toe rests on the level valley floor and buttresses it, so
  -- F lies above that; the toe holds 6 % of the mass, and the band stated for its effect is +15 %.
  -- The bedding loses its strength with the strong motion (friction 0.445 -> 0.2 < tan 22 deg = 0.40:
  -- a static FoS of 0.50), so the MPM mass runs out until the valley floor stops it (hundreds of
  -- metres; about 1 km published), while the block with the peak strength's ky stops after each pulse
  -- (metres): at least ten times the block's displacement.
  chichi_landslide = function(r)
    local b, gamma, tv = math.rad(22), 2550 * 9.81, 60 / math.cos(math.rad(22))
    local infinite = 20e3 / (gamma * tv * math.cos(b) ^ 2 * math.tan(b)) + math.tan(math.rad(24)) / math.tan(b)
    print(string.format("field slope: Spencer on the bedding %.4f, infinite slope %.4f", r.fos, infinite))
    assert(r.fos > infinite and r.fos < 1.15 * infinite, "field slope: FoS outside the infinite slope's band")
    assert(r.ky > 0 and r.ky < r.pba, "field slope: the record must shake past ky")
    assert(r.mpm > 10 * r.newmark, "field slope: the run-out must exceed the rigid block's displacement tenfold")
  end,
}

if check then
  for _, r in ipairs(rows) do
    assert(r.newmark > 0 and r.newmark < math.huge, r.key .. ": the Newmark displacement must be positive and finite")
    assert(r.mpm == r.mpm and r.mpm < math.huge, r.key .. ": the MPM displacement must be finite")
    s_check[r.key](r)
  end
  print("check passed")
end
