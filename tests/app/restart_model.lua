-- A slope of Mohr-Coulomb soil on a shaken rigid base with frictional contact, two probes and a fixity,
-- run whole (mode=full) or finished from DIR/checkpoint.chk (mode=restart). restart_after_kill_test.sh
-- kills a full run after its first periodic checkpoint and checks that the restart ends with the same files.
local dir = mpm.param("dir", "out/restart_model")
local mode = mpm.param("mode", "full")
local checkpoint_every = mpm.param("checkpoint_every", 0)
local shaking = mpm.param("shaking", 0.6)
local vx = mpm.history.table{ {0, 0}, {0.1, 0.1}, {0.3, -0.1}, {0.5, 0.1}, {0.6, 0} }

if mode == "full" then
  local m = mpm.model{ domain = {{-0.2, -0.1}, {1.5, 0.6}}, cell = 0.025 }
  local soil = mpm.material.mohr_coulomb{ density = 1700, young = 5e6, poisson = 0.3, cohesion = 5000, friction = 30,
                                          dilation = 0, tension = 0 }
  local slope = m:body{ name = "soil", material = soil, ppc = 2,
                        shape = mpm.shape.polygon{ {0, 0}, {1, 0}, {1, 0.2}, {0.6, 0.2}, {0.3, 0.45}, {0, 0.45} } }
  local base = m:rigid{ name = "base", shape = mpm.shape.rectangle{ -0.15, -0.05, 1.15, 0 }, ppc = 2,
                        velocity = { vx, 0 } }
  m:contact{ slope, base, friction = 0.6 }
  m:fix{ side = "top", dof = "y" }
  m:probe{ name = "crest", body = slope, at = { 0.3, 0.45 }, every = 0.01 }
  m:probe{ name = "toe", body = slope, at = { 0.6, 0.2 }, every = 0.005 }
  m:output{ dir = dir, every = 0.05, checkpoint_every = checkpoint_every > 0 and checkpoint_every or nil }
  m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 3 }
  m:dynamic_phase{ duration = shaking }
else
  local m = mpm.restart{ file = dir .. "/checkpoint.chk" }
  local phase = m:phase()
  m:run{}  -- the interrupted phase, to its end
  if phase == "gravity" then m:dynamic_phase{ duration = shaking } end
end
