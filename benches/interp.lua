-- The interpreter benchmark in Lua 5.4: the same algorithm as benches/interp.mod.
-- Usage: lua5.4 interp.lua ITERATIONS -> prints "acc: <value>".
local n = tonumber(arg[1]) or 10000000

local function f(x)
  return x * 2 + 1
end

local data = {}
for i = 1, 100 do data[i] = 0 end
local acc = 0
for i = 1, n do
  local k = i % 100 + 1
  data[k] = (data[k] + f(k)) % 1000
  acc = (acc + data[k]) % 65536
end
print(string.format("acc: %d", acc))
