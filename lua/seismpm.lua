-- seismpm's Lua-side library: geometry builders and console conveniences, loaded at start.
-- Everything here is plain Lua on top of the `mpm` module.

local geometry = {}

-- Checks a call's table of named arguments against the function's key table in the bindings
-- (src/lua/library_binding.cpp) as every binding does (unknown, missing, wrong type, out of range) and
-- returns the named values with their defaults.
local check_args = mpm._check_args

-- A slope in a box: level crest ground from `left` to crest.x at height crest.y, a face falling to
-- the right at `angle` degrees down to `toe_level`, level toe ground to `right`; all above `base`.
function geometry.slope(t)
  local f = "mpm.geometry.slope"
  local a = check_args(f, t)
  local left, right, base, toe, angle = a.left, a.right, a.base, a.toe_level, a.angle
  local cx, cy = a.crest[1], a.crest[2]
  if not (right > left) then error(f .. ": key 'right' must exceed 'left'", 2) end
  if not (toe > base and cy > toe) then
    error(f .. ": need base < toe_level < crest height, got " .. base .. ", " .. toe .. ", " .. cy, 2)
  end
  local toe_x = cx + (cy - toe) / math.tan(math.rad(angle))
  if not (cx > left and toe_x < right) then
    error(string.format("%s: the face runs from x = %g to %g, outside left = %g .. right = %g", f, cx, toe_x, left, right), 2)
  end
  return mpm.shape.polygon{ {left, base}, {right, base}, {right, toe}, {toe_x, toe}, {cx, cy}, {left, cy} }
end

-- Horizontal layers listed from the bottom up, each by its top elevation or its thickness: a list of
-- { name, shape = rectangle, material } that m:body takes as its regions (one body, no interfaces).
local layer_keys = { top = true, thickness = true, name = true, material = true }

function geometry.layers(t)
  local f = "mpm.geometry.layers"
  local a = check_args(f, t)
  local left, right, bottom = a.left, a.right, a.base
  if not (right > left) then error(f .. ": key 'right' must exceed 'left'", 2) end
  if #t == 0 then error(f .. ": give at least one layer {top = y, name = ..., material = ...}", 2) end
  local out = {}
  for i, layer in ipairs(t) do
    if type(layer) ~= "table" then error(f .. ": layer " .. i .. " must be a table {top = y (m), ...}", 2) end
    for k in pairs(layer) do
      if not layer_keys[k] then
        error(f .. ": layer " .. i .. ": unknown key '" .. tostring(k) .. "' (allowed: top thickness name material)", 2)
      end
    end
    local top = layer.top
    if layer.thickness ~= nil then
      if top ~= nil then error(f .. ": layer " .. i .. ": give top or thickness, not both", 2) end
      if type(layer.thickness) ~= "number" or not (layer.thickness > 0) then
        error(f .. ": layer " .. i .. ": thickness must be a number > 0 (m)", 2)
      end
      top = bottom + layer.thickness
    end
    if type(top) ~= "number" then error(f .. ": layer " .. i .. " must be {top = y (m) or thickness = t (m), ...}", 2) end
    if not (top > bottom) then
      error(f .. ": layer " .. i .. " top " .. top .. " must be above " .. bottom, 2)
    end
    if layer.name ~= nil and type(layer.name) ~= "string" then
      error(f .. ": layer " .. i .. ": name must be a string", 2)
    end
    out[i] = { name = layer.name or ("layer" .. i), shape = mpm.shape.rectangle{ left, bottom, right, top },
               material = layer.material }
    bottom = top
  end
  return out
end

mpm.geometry = geometry

-- Console support ------------------------------------------------------------------------------

-- A short printable form of a value: tables show their first entries.
function mpm._show(v, depth)
  depth = depth or 0
  if type(v) == "string" then return string.format("%q", v) end
  if type(v) ~= "table" or depth > 1 then return tostring(v) end
  local parts, n = {}, 0
  for i, x in ipairs(v) do
    n = n + 1
    if n > 10 then parts[#parts + 1] = "... (" .. #v .. " entries)"; break end
    parts[#parts + 1] = mpm._show(x, depth + 1)
  end
  for k, x in pairs(v) do
    if type(k) ~= "number" or k > #v or k < 1 then
      n = n + 1
      if n > 20 then parts[#parts + 1] = "..."; break end
      parts[#parts + 1] = tostring(k) .. " = " .. mpm._show(x, depth + 1)
    end
  end
  return "{" .. table.concat(parts, ", ") .. "}"
end

-- Completion candidates for the text before the cursor: globals, table fields (a.b.c) and
-- methods of objects (m:).
function mpm._complete(text)
  local prefix, sep, partial = text:match("^(.-)([%.:])([%w_]*)$")
  local names, base = {}, _G
  if prefix then
    local value = _G
    for part in prefix:gmatch("[^%.]+") do
      if type(value) ~= "table" then value = nil; break end
      value = value[part]
    end
    if sep == ":" then
      local mt = getmetatable(value)
      base = mt and type(mt.__index) == "table" and mt.__index or nil
    else
      base = type(value) == "table" and value or nil
    end
  else
    partial, prefix, sep = text, "", ""
  end
  if base == nil then return names end
  for k in pairs(base) do
    if type(k) == "string" and k:sub(1, #partial) == partial and k:sub(1, 1) ~= "_" then
      names[#names + 1] = prefix .. sep .. k
    end
  end
  table.sort(names)
  return names
end

return mpm
