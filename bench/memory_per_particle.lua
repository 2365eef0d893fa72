-- Memory per particle: a Mohr-Coulomb block in a fixed 1 m x 1 m grid (5 mm cells, 2 x 2 particles per
-- cell, uGIMP, contact with a rigid base), run for 50 steps. bench/memory.sh runs it at two heights and
-- divides the difference of the peak resident sets by the difference of the particle counts: the grid
-- and the program are the same in both, so what is left is what one particle costs.
--   seismpm bench/memory_per_particle.lua --set height=0.4
local height = mpm.param("height", 0.4)  -- m of block (at most 0.95)
local m = mpm.model{ domain = {{0, -0.01}, {1, 1}}, cell = 0.005, shape = "gimp" }
local sand = mpm.material.mohr_coulomb{ density = 1800, young = 2e7, poisson = 0.3, cohesion = 1000, friction = 30 }
local block = m:body{ name = "block", material = sand, ppc = 2, shape = mpm.shape.rectangle{ 0.1, 0, 0.9, height } }
local base = m:rigid{ name = "base", ppc = 1, velocity = {0, 0}, shape = mpm.shape.rectangle{ 0, -0.005, 1, 0 } }
m:contact{ block, base, friction = 0.5 }
m:fix{ side = "left", dof = "x" }
m:step(50)
print(string.format("particles %d", m:count()))
