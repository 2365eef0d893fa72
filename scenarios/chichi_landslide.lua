-- The Chiu-fen-erh-shan landslide, triggered by the 1999 Chi-Chi earthquake (Bhandari et al. 2016, §4).
--
-- What is published (the paper's Fig. 11 and the literature it cites): a dip slope of about 22 degrees
-- along bedding; a sliding pile about 60 m thick and 1.5 km long; 42-50 million m3; run-out about 1 km;
-- the deposit up to 110 m thick. The profile below is a reconstruction from those facts, not a survey:
--   * the bedding plane (the sliding surface) dips at 22 degrees and reaches the valley floor (y = 0) at
--     x = 1400 m; the valley floor is level to x = 3200 m;
--   * the pile is 60 m thick normal to the bedding, thinning to nothing over its upper 150 m (the head);
--     its surface keeps the 22-degree slope down onto the valley floor, where its toe rests (a steeper
--     toe face would not stand: a 45-degree face in this rock is critical at about 31 m): about 1.5 km
--     along the dip, 89,000 m2 in section, i.e. 45 million m3 for a slide 500 m wide;
--   * rock mass (the paper): 2550 kg/m3, E = 500 MPa, nu = 0.19, c = 20 kPa, phi = 24 deg (Mohr-Coulomb);
--   * the sliding surface and the valley floor are prescribed-velocity particles (two cells thick):
--     the bedding moves with the record's horizontal velocity projected on the slope, the floor with
--     the horizontal velocity itself;
--   * contact between the pile and both surfaces: the peak friction tan(24 deg) = 0.445 holds the pile
--     in the gravity phase (factor of safety 0.445 / tan 22 = 1.10); once the strong motion arrives
--     (the record's peak velocity) the bedding has lost its strength: the friction drops to a residual
--     value (--set residual=0.2, an assumption: the literature puts the bedding's residual friction
--     angle near 10-15 degrees).
-- The record: by default a synthetic near-fault velocity pulse (Mavroeidis & Papageorgiou 2003 form)
--   v(t) = A/2 (1 + cos(2 pi (t - t0) / (gamma Tp))) cos(2 pi (t - t0) / Tp),  |t - t0| <= gamma Tp / 2,
-- with A = 1.8 m/s (the raw peak velocity of the TCU068 EW record), Tp = 12 s (TCU068's pulse period in
-- Baker 2007), gamma = 2, t0 = 15 s. --set record=FILE takes a user's record instead: a PEER .AT2 or a
-- two-column time, acceleration file in g (e.g. ../shared/data/ground_motions/Chi-Chi_1999_TCU068-090.csv),
-- integrated to velocity with a linear baseline correction.
-- Outputs (out/chichi_landslide/): particles.pvd, rigid.pvd, front.csv + front.png (the front's
-- position against time), deposit.csv + deposit.png (surface before and after), record.csv, summary.txt.
--
--   seismpm scenarios/chichi_landslide.lua [--set cell=5] [--set duration=120] [--set residual=0.2]
--                                          [--set record=FILE] [--set check=true]

local cell = mpm.param("cell", 5.0)             -- m
local duration = mpm.param("duration", 120.0)   -- s of dynamic phase
local residual = mpm.param("residual", 0.2)     -- bedding friction once the strong motion has arrived
local record = mpm.param("record", "")          -- "" = the synthetic pulse
local check = mpm.param("check", false)         -- assert the coarse physics (ctest)
local soften = mpm.param("soften", 0.0)         -- > 0: rock cohesion lost at this plastic shear strain

local dip = math.rad(22)
local x_toe, x_end = 1400, 3200                 -- m: where the bedding meets the valley floor; its end
local T = 60                                    -- m, pile thickness normal to the bedding
local Tv = T / math.cos(dip)                    -- ... measured vertically
local function bedding_y(x) return (x_toe - x) * math.tan(dip) end

-- The record: horizontal ground velocity (m/s) against time (s).
local vh, source
if record == "" then
  local A, Tp, gamma, t0 = 1.8, 12.0, 2.0, 15.0
  local points = {}
  for k = 0, 4000 do
    local t = k * 0.01
    local v = 0
    if math.abs(t - t0) <= gamma * Tp / 2 then
      v = A / 2 * (1 + math.cos(2 * math.pi * (t - t0) / (gamma * Tp))) * math.cos(2 * math.pi * (t - t0) / Tp)
    end
    points[#points + 1] = {t, v}
  end
  vh = mpm.history.table(points)
  source = string.format("synthetic near-fault pulse: A = %g m/s, Tp = %g s, gamma = %g, t0 = %g s", A, Tp, gamma, t0)
else
  vh = mpm.history.at2{ file = record, integrate = "velocity", baseline = "linear", units = "g" }
  source = record .. " (acceleration in g, integrated, linear baseline)"
end
-- The time of the peak velocity: the strong motion's arrival, when the bedding weakens.
local t_peak, v_peak = 0, 0
for t = 0, vh:duration(), 0.01 do
  if math.abs(vh:at(t)) > v_peak then t_peak, v_peak = t, math.abs(vh:at(t)) end
end
print(string.format("record: %s; peak velocity %.2f m/s at %.2f s", source, v_peak, t_peak))

local h = cell
local m = mpm.model{ domain = {{-200, -4 * h}, {3400, 700}}, cell = h, gravity = {0, -9.81}, flip = 0.98 }
local rock = mpm.material.mohr_coulomb{ density = 2550, young = 500e6, poisson = 0.19, cohesion = 20e3,
                                        friction = 24, dilation = 0, tension = 0,
                                        softening = soften > 0 and { cohesion = 0, friction = 24, strain = soften } or nil }
local pile_shape = mpm.shape.polygon{ {0, bedding_y(0)}, {x_toe, 0}, {x_toe + Tv / math.tan(dip), 0},
                                      {150, bedding_y(150) + Tv} }
local pile = m:body{ name = "rock", material = rock, shape = pile_shape, ppc = 2 }
local c, s = math.cos(dip), math.sin(dip)
-- (v . d) d with d = (cos, -sin), tabulated once at 0.005 s (no Lua call in the time loop).
local along_points, down_points = {}, {}
for k = 0, math.ceil(vh:duration() / 0.005) do
  local t = k * 0.005
  along_points[#along_points + 1] = {t, vh:at(t) * c * c}
  down_points[#down_points + 1] = {t, -vh:at(t) * c * s}
end
local along, down = mpm.history.table(along_points), mpm.history.table(down_points)
local bedding = m:rigid{ name = "bedding", ppc = 1, velocity = {along, down},
                         shape = mpm.shape.polyline{ {-100, bedding_y(-100)}, {x_toe, 0}, thickness = 2 * h, side = "right" } }
local floor = m:rigid{ name = "valley_floor", ppc = 1, velocity = {vh, 0},
                       shape = mpm.shape.polyline{ {x_toe, 0}, {x_end, 0}, thickness = 2 * h, side = "right" } }
local peak = math.tan(math.rad(24))
m:contact{ pile, bedding, friction = peak }
m:contact{ pile, floor, friction = peak }
local area = pile:count() * (h / 2) ^ 2
print(string.format("rock: %d particles (%.0f m2 in section: %.1f million m3 for a slide 500 m wide), cell %g m",
                    pile:count(), area, area * 500 / 1e6, h))

local dir = mpm.out_dir("out/chichi_landslide")
m:output{ dir = dir, every = mpm.param("every", 5.0) }
if record == "" then vh:write_csv(dir .. "/record.csv") end

-- Surface profile: the highest rock particle in each cell column.
local function surface()
  local xs, ys = pile:field("x"), pile:field("y")
  local top = {}
  for i = 1, #xs do
    local k = math.floor(xs[i] / h)
    if not top[k] or ys[i] > top[k] then top[k] = ys[i] end
  end
  return top
end
local function front()
  local xs = pile:field("x")
  local f = -math.huge
  for i = 1, #xs do f = math.max(f, xs[i]) end
  return f
end

local wall0 = os.time()
local eq = m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 30 }
local before = surface()
local front0 = front()

-- Dynamic phase: peak friction until the strong motion arrives, then residual.
local rows = { "time (s),front x (m),front travel (m)" }
local function sample()
  local f = front()
  rows[#rows + 1] = string.format("%.3f,%.3f,%.3f", m:phase_time(), f, f - front0)
  return f
end
sample()
local weakened = false
local last = front0
local speed = 0
-- Every second of the phase, between steps: sample the front, and weaken the bedding once the
-- strong motion has arrived.
m:dynamic_phase{ duration = duration, every = 1.0, call = function()
  local f = sample()
  speed = f - last  -- m/s: samples 1 s apart
  last = f
  if not weakened and m:phase_time() >= t_peak - 1e-9 then
    m:set_friction{ pile, bedding, friction = residual }
    m:set_friction{ pile, floor, friction = residual }
    weakened = true
    print(string.format("t = %.1f s: the bedding weakens, friction %.3f -> %.3f", m:phase_time(), peak, residual))
  end
end }

local file = assert(io.open(dir .. "/front.csv", "w"))
file:write(table.concat(rows, "\n"), "\n")
file:close()

local after = surface()
local prof = { "x (m),surface before (m),surface after (m),deposit thickness above the ground (m)" }
local max_deposit = 0
for k = math.floor(-100 / h), math.floor(x_end / h) do
  local x = (k + 0.5) * h
  local ground = x < x_toe and bedding_y(x) or 0
  local b, a = before[k], after[k]
  if b or a then
    local thick = a and (a - ground) or 0
    if x >= x_toe then max_deposit = math.max(max_deposit, thick) end
    prof[#prof + 1] = string.format("%.2f,%s,%s,%.3f", x, b and string.format("%.3f", b) or "", a and string.format("%.3f", a) or "", thick)
  end
end
file = assert(io.open(dir .. "/deposit.csv", "w"))
file:write(table.concat(prof, "\n"), "\n")
file:close()

local travel = front() - front0
local lines = {
  string.format("rock particles: %d, cell: %g m", pile:count(), h),
  string.format("record: %s", source),
  string.format("gravity phase: equilibrium after %.2f s (%d steps)", eq.time, eq.steps),
  string.format("front travel at %.0f s: %.0f m (published run-out: about 1 km)", duration, travel),
  string.format("front speed over the last second: %.2f m/s", speed),
  string.format("deposit on the valley floor: up to %.0f m thick (published: up to 110 m)", max_deposit),
  string.format("wall time: %d s, %d steps", os.time() - wall0, m:steps()),
}
file = assert(io.open(dir .. "/summary.txt", "w"))
for _, line in ipairs(lines) do
  print(line)
  file:write(line, "\n")
end
file:close()
print("plot: " .. mpm.plot{ file = dir .. "/front.csv", x = "time (s)", y = {"front travel (m)"},
                            title = "Chiu-fen-erh-shan: travel of the landslide front", xlabel = "time since the dynamic phase began (s)",
                            ylabel = "front travel (m)" })
print("plot: " .. mpm.plot{ file = dir .. "/deposit.csv", x = "x (m)", y = {"surface before (m)", "surface after (m)"},
                            title = "Chiu-fen-erh-shan: surface before and after", ylabel = "elevation (m)" })

if check then
  assert(travel > 200, "the front should travel")
  assert(math.abs(speed) < 1.0, "the front should come to rest")
  print("check passed")
end
