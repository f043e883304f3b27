-- WHILE loops (the algorithm of loops.mod): Collatz chain lengths and Euclid's gcd.
local N = tonumber(arg[1]) or 48

local function collatz(n)
  local steps = 0
  local x = n
  while x ~= 1 do
    if x % 2 == 0 then
      x = x // 2
    else
      x = 3 * x + 1
    end
    steps = steps + 1
  end
  return steps
end

local function gcd(a, b)
  local x = a
  local y = b
  while y ~= 0 do
    local t = x % y
    x = y
    y = t
  end
  return x
end

local total = 0
local g = 0
local round = 1
while round <= N do
  local k = 1
  while k <= 3000 do
    total = (total + collatz(k)) % 1000000
    k = k + 1
  end
  local i = 1
  while i <= 150 do
    local j = 1
    while j <= 150 do
      g = (g + gcd(i * 7 + round, j * 3)) % 1000000
      j = j + 1
    end
    i = i + 1
  end
  round = round + 1
end
print(string.format("result: %d %d", total, g))
