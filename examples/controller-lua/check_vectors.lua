--[[ Checks ahhs_model.lua against the controller's golden vectors (docs/hardware.md, "Golden
vectors"), offline: every case's genome, the inputs of each tick, and the outputs modules/core
computed, to the last bit.

  lua5.2 check_vectors.lua tools/conformance/data/model-vectors.txt

Prints one line per case and exits 0 when every output matches, 1 at the first that does not.
A port in another language follows the same steps: parse, compile, then per tick receive every
packet, step, and compare hormones, actuators and outflow with ==.
--]]
local dir = arg[0]:match('^(.*)/[^/]*$') or '.'
package.path = dir .. '/?.lua;' .. package.path
local model = require('ahhs_model')

local path = arg[1]
if not path then io.stderr:write('usage: check_vectors.lua FILE\n') os.exit(2) end
local file, err = io.open(path)
if not file then io.stderr:write(err .. '\n') os.exit(2) end

local function words(line)
  local t = {}
  for w in line:gmatch('%S+') do t[#t + 1] = w end
  return t
end

local function numbers(t)
  local v = {}
  for i = 2, #t do v[i - 1] = assert(tonumber(t[i]), 'not a number: ' .. t[i]) end
  return v
end

local function fail(what) print('FAIL: ' .. what) os.exit(1) end

local lines = {}
for line in file:lines() do
  if line ~= '' and line:sub(1, 1) ~= '#' then lines[#lines + 1] = words(line) end
end
file:close()
if lines[1][1] ~= 'ahhs-model-vectors' or lines[1][2] ~= '1' then fail('not a version-1 vectors file') end

local i, cases = 2, 0
while i <= #lines do
  local name = lines[i][2]
  local gl = lines[i + 1]
  local g = {variant = tonumber(gl[2]), num_hormones = tonumber(gl[3]), num_sensors = tonumber(gl[4]),
             num_actuators = tonumber(gl[5]), num_rules = tonumber(gl[6]),
             fields_per_rule = tonumber(gl[7]),
             alpha = numbers(lines[i + 2]), mu = numbers(lines[i + 3]),
             diffusion = numbers(lines[i + 4]), rule_values = numbers(lines[i + 5])}
  g.num_rule_values = #g.rule_values
  local c, why = model.compile(g)
  if not c then fail(name .. ': ' .. why) end
  local s = model.rest(c)
  i = i + 6
  local tick = 0
  while lines[i][1] ~= 'end' do
    local neighbours = tonumber(lines[i][2])
    i = i + 1
    while lines[i][1] == 'received' do model.receive(s, numbers(lines[i])) i = i + 1 end
    local S, sp, ap = {}, {}, {}
    for k = 2, #lines[i] do
      local w = lines[i][k]
      sp[k - 1] = w ~= '-'
      S[k - 1] = w == '-' and 0.0 or tonumber(w)
    end
    for k = 2, #lines[i + 1] do ap[k - 1] = lines[i + 1][k] == '1' end
    model.step(c, s, S, sp, ap, neighbours)
    for k, key in ipairs({'expect_hormones', 'expect_actuators', 'expect_outflow'}) do
      local want = numbers(lines[i + 1 + k])
      local have = ({s.hormones, s.actuators, s.outflow})[k]
      for j = 1, #want do
        if want[j] ~= have[j] then
          fail(string.format('case %s tick %d: %s[%d] is %.17g, ahhs_model.lua gives %.17g',
                             name, tick, key, j - 1, want[j], have[j]))
        end
      end
    end
    i = i + 5
    tick = tick + 1
  end
  print(string.format('%s: %d ticks equal to the bit', name, tick))
  cases = cases + 1
  i = i + 1
end
print(string.format('PASS (%d cases)', cases))
