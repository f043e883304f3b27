-- Late binding (the algorithm of latebind.mod): functions called by a name built at run time.
local N = tonumber(arg[1]) or 1000000
local NAMES = { "op_1", "op_2", "op_3", "op_4" }
acc = 0

function op_1(x)
  acc = (acc + x + 1) % 99991
end

function op_2(x)
  acc = (acc + 2 * x + 3) % 99991
end

function op_3(x)
  acc = (acc * 3 + x + 5) % 99991
end

function op_4(x)
  acc = (acc + x * x + 7) % 99991
end

for i = 1, N do
  _G["op_" .. tostring(i % 4 + 1)](i % 100)
end
local check = acc
for i = 1, N do
  _G[NAMES[(i * 3) % 4 + 1]](i % 50)
end
print(string.format("result: %d %d", check, acc))
