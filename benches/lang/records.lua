-- Records and arrays of records (the algorithm of records.mod).
local N = tonumber(arg[1]) or 25000

local ps = {}

local function moved(p)
  local q = { x = p.x, y = p.y, vx = p.vx, vy = p.vy, hits = p.hits }
  q.x = q.x + q.vx
  if q.x < 0 or q.x > 1000 then
    q.vx = -q.vx
    q.hits = q.hits + 1
  end
  q.y = q.y + q.vy
  if q.y < 0 or q.y > 1000 then
    q.vy = -q.vy
    q.hits = q.hits + 1
  end
  return q
end

local function busiest()
  local best = 1
  for i = 2, 100 do
    if ps[i].hits > ps[best].hits then
      best = i
    end
  end
  return best
end

local check = 0
local hits = 0
for i = 1, 100 do
  ps[i] = { x = i * 7 % 1000, y = i * 13 % 1000, vx = (i % 7) * 3 - 9, vy = (i % 5) * 4 - 8, hits = 0 }
end
for s = 1, N do
  for i = 1, 100 do
    ps[i] = moved(ps[i])
  end
  if s % 10 == 0 then
    check = (check + busiest() * s) % 1000000
  end
end
for i = 1, 100 do
  hits = hits + ps[i].hits
end
print(string.format("result: %d %d", check, hits))
