-- TEST/CASE dispatch (the algorithm of testcase.mod): a stack machine and a word classifier.
local N = tonumber(arg[1]) or 750

local code = { 2, 2, 2, 1, 2, 1, 6, 4, 1, 10007, 7, 3, 2, 2, 1, 1, 1, 5, 9, 3, 1, 8, 1, 0 }
local stack = {}
for i = 1, 16 do stack[i] = 0 end
local reg = { 0, 0, 0, 0 }
local VOCAB = { "red", "one", "square", "blue", "three", "tree", "green", "circle", "two", "sky" }

local function run(n)
  local pc = 1
  local sp = 0
  local going = true
  reg[1] = n
  reg[2] = 0
  while going do
    local op = code[pc]
    pc = pc + 1
    if op == 1 then
      sp = sp + 1
      stack[sp] = code[pc]
      pc = pc + 1
    elseif op == 2 then
      sp = sp + 1
      stack[sp] = reg[code[pc]]
      pc = pc + 1
    elseif op == 3 then
      reg[code[pc]] = stack[sp]
      sp = sp - 1
      pc = pc + 1
    elseif op == 4 then
      stack[sp - 1] = stack[sp - 1] + stack[sp]
      sp = sp - 1
    elseif op == 5 then
      stack[sp - 1] = stack[sp - 1] - stack[sp]
      sp = sp - 1
    elseif op == 6 then
      stack[sp - 1] = stack[sp - 1] * stack[sp]
      sp = sp - 1
    elseif op == 7 then
      stack[sp - 1] = stack[sp - 1] % stack[sp]
      sp = sp - 1
    elseif op == 8 then
      if stack[sp] ~= 0 then
        pc = code[pc]
      else
        pc = pc + 1
      end
      sp = sp - 1
    elseif op == 9 then
      sp = sp + 1
      stack[sp] = stack[sp - 1]
    else
      going = false
    end
  end
  return reg[2]
end

local function classify(w)
  if w == "red" or w == "green" or w == "blue" then
    return 1
  elseif w == "circle" or w == "square" then
    return 2
  elseif w == "one" or w == "two" or w == "three" then
    return 3
  else
    return 0
  end
end

local check = 0
local words = 0
for k = 1, N do
  check = (check + run(1000 + k % 7)) % 1000000
end
for k = 1, 500 * N do
  words = words + classify(VOCAB[k % 10 + 1]) * (k % 3)
end
print(string.format("result: %d %d", check, words))
