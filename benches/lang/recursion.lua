-- Recursion (the algorithm of recursion.mod): naive Fibonacci and a recursive quicksort.
local N = tonumber(arg[1]) or 240

local data = {}
for i = 1, 2000 do data[i] = 0 end

local function fib(n)
  if n < 2 then return n end
  return fib(n - 1) + fib(n - 2)
end

local function qsort(lo, hi)
  if lo >= hi then return end
  local pivot = data[(lo + hi) // 2]
  local i = lo
  local j = hi
  while i <= j do
    while data[i] < pivot do
      i = i + 1
    end
    while data[j] > pivot do
      j = j - 1
    end
    if i <= j then
      local t = data[i]
      data[i] = data[j]
      data[j] = t
      i = i + 1
      j = j - 1
    end
  end
  qsort(lo, j)
  qsort(i, hi)
end

local f = 0
local seed = 1
local check = 0
for r = 1, N do
  f = f + fib(20 + r % 3)
  for i = 1, 2000 do
    seed = (seed * 251 + 7 + r) % 65521
    data[i] = seed
  end
  qsort(1, 2000)
  for i = 1, 2000, 50 do
    check = (check + data[i] * (i % 7)) % 1000000
  end
end
print(string.format("result: %d %d", f, check))
