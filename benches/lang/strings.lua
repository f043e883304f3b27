-- String building (the algorithm of strings.mod).
local N = tonumber(arg[1]) or 150000

local total = 0
local sevens = 0
for round = 1, N do
  local s = ""
  for i = 1, 10 do
    s = s .. tostring((round * i) % 997) .. ","
  end
  local r = ""
  for k = #s, 1, -1 do
    local c = s:sub(k, k)
    if c == "7" then
      sevens = sevens + 1
    end
    r = r .. c
  end
  local found = string.find(r, "9", 1, true) or (#r + 1)
  total = (total + #r + found) % 1000000
end
print(string.format("result: %d %d", total, sevens))
