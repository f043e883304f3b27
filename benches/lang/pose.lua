-- Pose math (the algorithm of pose.mod): quaternions and vectors as tables.
local N = tonumber(arg[1]) or 200000

local function qmul(a, b)
  return { a[1] * b[1] - a[2] * b[2] - a[3] * b[3] - a[4] * b[4],
           a[1] * b[2] + a[2] * b[1] + a[3] * b[4] - a[4] * b[3],
           a[1] * b[3] - a[2] * b[4] + a[3] * b[1] + a[4] * b[2],
           a[1] * b[4] + a[2] * b[3] - a[3] * b[2] + a[4] * b[1] }
end

local function cross(a, b)
  return { a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1] }
end

local function rotate(q, v)
  local u = { q[2], q[3], q[4] }
  local t = cross(u, v)
  t = { 2 * t[1], 2 * t[2], 2 * t[3] }
  local c = cross(u, t)
  return { v[1] + q[1] * t[1] + c[1], v[2] + q[1] * t[2] + c[2], v[3] + q[1] * t[3] + c[3] }
end

local function compose(a, b)
  local p = rotate(a.rot, b.trans)
  return { trans = { a.trans[1] + p[1], a.trans[2] + p[2], a.trans[3] + p[3] }, rot = qmul(a.rot, b.rot) }
end

local function about_z(deg)
  local h = math.rad(deg / 2)
  return { math.cos(h), 0, 0, math.sin(h) }
end

local check = 0
for i = 1, N do
  local a = { trans = { i % 100, 0, 50 }, rot = about_z(i % 360) }
  local b = { trans = { 10, 20, 30 }, rot = about_z((i * 7) % 360) }
  local c = compose(a, b)
  local v = rotate(c.rot, { 100, 0, 0 })
  check = (check + math.floor((v[1] + c.trans[1] + 1000) / 10)) % 100000
end
print(string.format("result: %d", check))
