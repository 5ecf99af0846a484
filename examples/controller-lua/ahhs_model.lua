--[[ The hormone system of one compartment (docs/model.md), in plain Lua 5.2: AHHS1 and AHHS2.
Pure: no LCM, no clock. Every value is a Lua number (an IEEE double), and every sum is taken in
the order of modules/core/hormone_system.cc, so a module running this gives the same actuator
values and outflows as ahhs-module to the bit.

  local model = require('ahhs_model')
  local controller, err = model.compile(genome)   -- genome: a decoded ahhs.genome_t
  local state = model.rest(controller)
  model.receive(state, amounts)                   -- each neighbour's packet, increasing sender id
  model.step(controller, state, sensors, sensor_present, actuator_present, num_neighbours)
  -- state.actuators[a], state.outflow[h] (1-based)
--]]
local M = {}

M.PORTS = 4                -- docking ports of a module: the diffusion denominator P
M.THRESHOLD_TIE = 1e-12    -- AHHS1: values this close to tau count as equal to it
M.AHHS1, M.AHHS2 = 1, 2    -- genome_t.variant
local FIELDS = {[1] = 7, [2] = 13}

local floor, min = math.floor, math.min

-- A floating index x in [0, n) -> 0-based items floor(x), (floor(x) + 1) mod n and weights.
local function split_index(x, n)
  local k = min(floor(x), n - 1)
  local f = x - k
  return k, (k + 1) % n, 1.0 - f, f
end

local function finite(x) return x == x and x ~= math.huge and x ~= -math.huge end

-- Checks sizes and ranges; returns the compiled controller, or nil and the reason.
function M.compile(g)
  local per = FIELDS[g.variant]
  if not per then return nil, 'unknown variant' end
  if g.fields_per_rule ~= per or g.num_rule_values ~= g.num_rules * per then
    return nil, 'rule array has the wrong size'
  end
  local nh, ns, na = g.num_hormones, g.num_sensors, g.num_actuators
  if nh < 1 or ns < 1 or na < 1 then return nil, 'a genome needs hormones, sensors, actuators' end
  local c = {variant = g.variant, nh = nh, ns = ns, na = na, alpha = {}, mu = {}, dpp = {}, rules = {}}
  for h = 1, nh do
    local a, m, d = g.alpha[h], g.mu[h], g.diffusion[h]
    if not (a >= 0 and a <= 0.1 and m >= 0 and m <= 1 and d >= 0 and d <= 1) then
      return nil, 'hormone ' .. (h - 1) .. ': alpha, mu or diffusion out of range'
    end
    c.alpha[h], c.mu[h], c.dpp[h] = a, m, d / M.PORTS
  end
  for r = 0, g.num_rules - 1 do
    local v = {}
    for k = 1, per do
      v[k] = g.rule_values[r * per + k]
      if not finite(v[k]) then return nil, 'rule ' .. r .. ': a value that is not finite' end
    end
    local rule
    if g.variant == M.AHHS2 then
      if not (v[7] >= 0.01 and v[10] >= 0 and v[10] < ns and v[11] >= 0 and v[11] < nh and
              v[12] >= 0 and v[12] < nh and v[13] >= 0 and v[13] < na) then
        return nil, 'rule ' .. r .. ': eta or an index out of range'
      end
      rule = {w_sensor = v[2], w_linear = v[3], w_nonlinear = v[4], w_actuator = v[5],
              zeta = v[6], inv_eta = 1.0 / v[7], kappa = v[8], lambda = v[9],
              sensor = floor(v[10]), input = floor(v[11])}
      rule.out0, rule.out1, rule.out_w0, rule.out_w1 = split_index(v[12], nh)
      rule.act0, rule.act1, rule.act_w0, rule.act_w1 = split_index(v[13], na)
    else
      local kind, input, output, dir = v[1], v[2], v[3], v[5]
      local inputs = kind == 1 and ns or nh
      local outputs = kind == 3 and na or nh
      if not (kind >= 0 and kind <= 3 and floor(kind) == kind and (dir == 0 or dir == 1) and
              floor(input) == input and input >= 0 and input < inputs and
              floor(output) == output and output >= 0 and output < outputs) then
        return nil, 'rule ' .. r .. ': type, direction or an index out of range'
      end
      rule = {kind = kind, input = input, output = output, tau = v[4], above = dir == 1,
              lambda = v[6], kappa = v[7]}
    end
    c.rules[r + 1] = rule
  end
  return c
end

-- A compartment at rest. Arrays are 1-based: hormones[h + 1] is hormone h.
function M.rest(c)
  local s = {hormones = {}, delta = {}, outflow = {}, actuators = {}}
  for h = 1, c.nh do s.hormones[h], s.delta[h], s.outflow[h] = 0.0, 0.0, 0.0 end
  for a = 1, c.na do s.actuators[a] = 0.0 end
  return s
end

-- Step 1: one received packet's amounts (nh values, 1-based).
function M.receive(s, amounts)
  local H = s.hormones
  for h = 1, #H do H[h] = H[h] + amounts[h] end
end

local function tent(x, zeta, inv_eta)
  local d = x - zeta
  if d < 0 then d = -d end
  local t = 1.0 - d * inv_eta
  if t > 0.0 then return t end
  return 0.0
end

local function threshold(x, tau, above)
  if above then return x > tau + M.THRESHOLD_TIE end
  return x < tau - M.THRESHOLD_TIE
end

local function step_ahhs2(c, s, S, sp, ap)
  local H, dH, A = s.hormones, s.delta, s.actuators
  for _, r in ipairs(c.rules) do
    local v_out = 0.0
    if r.w_sensor > 0 and sp[r.sensor + 1] then
      local xs = S[r.sensor + 1]
      local ts = tent(xs, r.zeta, r.inv_eta)
      if ts > 0 then v_out = r.w_sensor * ts * (r.lambda * xs + r.kappa) end
    end
    local o0, o1 = r.out0 + 1, r.out1 + 1
    local x = H[r.input + 1]
    local t = tent(x, r.zeta, r.inv_eta)
    if t > 0 then
      local dose = r.lambda * x + r.kappa
      if r.w_linear > 0 then v_out = v_out + r.w_linear * t * dose end
      if r.w_nonlinear > 0 then -- dx/dt = x*y: each target item uses its own concentration
        local wt = r.w_nonlinear * t
        dH[o0] = dH[o0] + r.out_w0 * (v_out + wt * (r.lambda * x * H[o0] + r.kappa))
        dH[o1] = dH[o1] + r.out_w1 * (v_out + wt * (r.lambda * x * H[o1] + r.kappa))
        v_out = 0.0
      end
      if r.w_actuator > 0 then
        local v = r.w_actuator * t * dose
        local a0, a1 = r.act0 + 1, r.act1 + 1
        if ap[a0] then A[a0] = A[a0] + r.act_w0 * v end
        if ap[a1] then A[a1] = A[a1] + r.act_w1 * v end
      end
    end
    if v_out ~= 0.0 then
      dH[o0] = dH[o0] + r.out_w0 * v_out
      dH[o1] = dH[o1] + r.out_w1 * v_out
    end
  end
end

local function step_ahhs1(c, s, S, sp, ap)
  local H, dH, A = s.hormones, s.delta, s.actuators
  for _, r in ipairs(c.rules) do
    local i, o = r.input + 1, r.output + 1
    if r.kind == 1 then -- sensor rule
      if sp[i] and threshold(S[i], r.tau, r.above) then
        dH[o] = dH[o] + (r.lambda * S[i] + r.kappa)
      end
    elseif r.kind == 2 then -- hormone rule
      if threshold(H[i], r.tau, r.above) then dH[o] = dH[o] + (r.lambda * H[i] + r.kappa) end
    elseif r.kind == 3 then -- actuator rule
      if ap[o] and threshold(H[i], r.tau, r.above) then
        A[o] = A[o] + (r.lambda * H[i] + r.kappa)
      end
    end
  end
end

-- Steps 2-6 of a tick: rules on start-of-tick values, production, decay, clamp, diffusion
-- (s.outflow is what each docked neighbour gets; it has left s.hormones), actuators clamped.
-- S, sp, ap: sensor values, sensor and actuator ownership (1-based, booleans).
function M.step(c, s, S, sp, ap, num_neighbours)
  local H, dH, A, q = s.hormones, s.delta, s.actuators, s.outflow
  for h = 1, c.nh do dH[h] = 0.0 end
  for a = 1, c.na do A[a] = 0.0 end
  if c.variant == M.AHHS2 then step_ahhs2(c, s, S, sp, ap) else step_ahhs1(c, s, S, sp, ap) end
  for h = 1, c.nh do
    local v = H[h] + c.alpha[h] - c.mu[h] * H[h] + dH[h]
    local clamped = v < 0.0 and 0.0 or (v > 1.0 and 1.0 or v)
    q[h] = c.dpp[h] * clamped
    if num_neighbours > 0 then H[h] = clamped - num_neighbours * q[h] else H[h] = clamped end
  end
  for a = 1, c.na do A[a] = A[a] < -1.0 and -1.0 or (A[a] > 1.0 and 1.0 or A[a]) end
end

return M
