--[[ A module's hormone controller in Lua 5.2 (Debian: lua5.2, liblcm-lua, lua-posix), written
from docs/protocol.md ("The module's side") and docs/model.md: the reference for a port to
another language. It joins an arena as module N in lockstep or real time, like ahhs-module.

  lua5.2 module.lua --id N [--arena NAME] [--lcm-url URL] [--hormone-timeout-ms MS] [--seconds S]

The message types are made by `lcm-gen -l` from lcmtypes/ (the build puts them beside a wrapper,
bin/ahhs-example-controller-lua). Lua 5.2 holds 64-bit integers as doubles: episode ids and
ticks are far below 2^53, and the genome hash is echoed rounded to a double, which the launcher
accepts (docs/hardware.md). This controller does not recompute the hash (Lua 5.2 has no 64-bit
integers); the launcher's check of READY catches a module that runs another genome.
Exit status: 0 (stopped by --seconds or a signal), 2 for bad options.
--]]
local here = debug.getinfo(1, 'S').source:match('^@(.*/)') or './'
package.path = here .. '?.lua;' .. package.path
local lcm = require('lcm')
local ahhs = require('ahhs')
local model = require('ahhs_model')
local ptime = require('posix.time')
local psignal = require('posix.signal')

local function usage(msg)
  io.stderr:write('module.lua: ' .. msg .. '\n')
  io.stderr:write('usage: module.lua --id N [--arena NAME] [--lcm-url URL] ' ..
                  '[--hormone-timeout-ms MS] [--seconds S]\n')
  os.exit(2)
end

local opt = {arena = 'AHHS', url = 'udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304',
             hormone_timeout = 0.5, seconds = nil}
do
  local k = 1
  while k <= #arg do
    local name, value = arg[k], arg[k + 1]
    if value == nil then usage(name .. ' needs a value') end
    if name == '--id' then opt.id = tonumber(value)
    elseif name == '--arena' then opt.arena = value
    elseif name == '--lcm-url' then opt.url = value
    elseif name == '--hormone-timeout-ms' then opt.hormone_timeout = (tonumber(value) or -1) / 1000
    elseif name == '--seconds' then opt.seconds = tonumber(value) or -1
    else usage('unknown option ' .. name) end
    k = k + 2
  end
  if not opt.id or opt.id < 0 or opt.id ~= math.floor(opt.id) then usage('--id N is required') end
  if opt.hormone_timeout < 0 then usage('--hormone-timeout-ms needs a number') end
  if opt.seconds and opt.seconds <= 0 then usage('--seconds needs a positive number') end
end

local function now()
  local t = ptime.clock_gettime(ptime.CLOCK_MONOTONIC)
  return t.tv_sec + t.tv_nsec * 1e-9
end
local function utime()
  local t = ptime.clock_gettime(ptime.CLOCK_REALTIME)
  return t.tv_sec * 1000000 + math.floor(t.tv_nsec / 1000)
end

local lc = lcm.lcm.new(opt.url)
local prefix = opt.arena .. '/'
local function module_channel(id, what) return prefix .. 'MODULE' .. id .. '/' .. what end

-- The module's state (docs/protocol.md, "The module's side").
local st = {
  episode = 0, realtime = false,
  controller = nil, hash = 0, state = nil, neighbours = {}, have_topology = false,
  next_tick = 0, sensors = nil, sensors_at = 0,
  packets = {},      -- packets[tick][sender] = amounts, ticks >= next_tick - 1 kept (lockstep)
  hormone_subs = {}, -- by neighbour id
  status = 0, next_heartbeat = 0, announce_ready = false,
  missing = 0, late = 0, dropped = 0, last_error = '',
}

local function publish_status(state)
  st.status = state
  local s = ahhs.module_status_t:new()
  s.utime, s.episode, s.tick, s.module, s.state = utime(), st.episode, st.next_tick - 1, opt.id, state
  s.genome_hash = st.hash
  s.missed_ticks, s.late_messages, s.dropped_messages = st.missing, st.late, st.dropped
  s.message = st.last_error
  lc:publish(module_channel(opt.id, 'STATUS'), s:encode())
  st.next_heartbeat = now() + 1.0
end

local function ready() return st.controller ~= nil and st.have_topology end

local function new_episode(episode)
  st.episode, st.controller, st.state, st.have_topology = episode, nil, nil, false
  st.neighbours, st.next_tick, st.sensors, st.packets = {}, 0, nil, {}
end

local function decode(type, data)
  local ok, m = pcall(type.decode, data)
  if ok then return m end
  st.dropped = st.dropped + 1
  return nil
end

local function on_hormone(n, data)
  local m = decode(ahhs.hormone_packet_t, data)
  if not m then return end
  local to_me = false
  for _, id in ipairs(m.to_modules) do to_me = to_me or id == opt.id end
  if not to_me then return end
  if m.from_module ~= n or m.episode ~= st.episode or not ready() or
     m.num_hormones ~= st.controller.nh then
    st.dropped = st.dropped + 1
    return
  end
  for _, a in ipairs(m.amounts) do
    if not (a >= 0 and a <= 1) then st.dropped = st.dropped + 1; return end
  end
  if m.tick < st.next_tick - 1 and not st.realtime then st.late = st.late + 1; return end
  st.packets[m.tick] = st.packets[m.tick] or {}
  st.packets[m.tick][n] = m.amounts
end

-- Listen to exactly the docked neighbours' HORMONE channels (done outside any handler).
local function sync_hormone_subscriptions()
  local wanted = {}
  for _, n in ipairs(st.neighbours) do wanted[n] = true end
  for n, sub in pairs(st.hormone_subs) do
    if not wanted[n] then lc:unsubscribe(sub); st.hormone_subs[n] = nil end
  end
  for _, n in ipairs(st.neighbours) do
    if not st.hormone_subs[n] then
      st.hormone_subs[n] = lc:subscribe(module_channel(n, 'HORMONE'),
                                        function(_, data) on_hormone(n, data) end)
    end
  end
end

lc:subscribe(prefix .. 'GENOME', function(_, data)
  local m = decode(ahhs.genome_t, data)
  if not m then return end
  if m.episode ~= st.episode then
    new_episode(m.episode)
  elseif st.controller then -- a repeat: never rebuild (it would wipe the hormones)
    if m.genome_hash ~= st.hash then
      st.dropped, st.last_error = st.dropped + 1, 'a second, different genome for this episode was ignored'
    elseif ready() and st.next_tick == 0 then
      st.announce_ready = true
    end
    return
  end
  local c, err = model.compile(m)
  if not c then
    st.dropped, st.last_error = st.dropped + 1, 'genome refused: ' .. err
    publish_status(ahhs.module_status_t.ERROR)
    return
  end
  st.controller, st.hash, st.state = c, m.genome_hash, model.rest(c)
  if ready() then st.announce_ready = true end
end)

lc:subscribe(prefix .. 'TOPOLOGY', function(_, data)
  local m = decode(ahhs.topology_t, data)
  if not m then return end
  if m.episode ~= st.episode then new_episode(m.episode) end
  local set = {}
  for k = 1, m.num_links do
    if m.module_a[k] == opt.id then set[m.module_b[k]] = true end
    if m.module_b[k] == opt.id then set[m.module_a[k]] = true end
  end
  st.neighbours = {}
  for n in pairs(set) do st.neighbours[#st.neighbours + 1] = n end
  table.sort(st.neighbours)
  while #st.neighbours > model.PORTS do table.remove(st.neighbours) end
  st.have_topology = true
  if ready() and st.next_tick == 0 then st.announce_ready = true end
end)

lc:subscribe(module_channel(opt.id, 'SENSORS'), function(_, data)
  local m = decode(ahhs.module_sensors_t, data)
  if not m then return end
  local c = st.controller
  if m.episode ~= st.episode or m.module ~= opt.id or not ready() or
     m.num_sensors ~= c.ns or m.num_actuators ~= c.na then
    st.dropped = st.dropped + 1
    return
  end
  for j = 1, m.num_sensors do
    local v = m.values[j]
    if m.present[j] and not (v >= 0 and v <= 1) then st.dropped = st.dropped + 1; return end
  end
  if m.tick < st.next_tick then st.late = st.late + 1; return end
  if m.tick > st.next_tick then -- the sim went on without us: jump to its tick
    st.late = st.late + (m.tick - st.next_tick)
    st.next_tick = m.tick
  end
  st.sensors, st.sensors_at = m, now()
end)

lc:subscribe(prefix .. 'SIM/CLOCK', function(_, data)
  local m = decode(ahhs.sim_clock_t, data)
  if m and m.episode == st.episode then
    st.realtime = m.clock_mode == ahhs.sim_clock_t.MODE_REALTIME
  end
end)

-- Packets in increasing (tick, sender) order, ticks below `below`; removes them.
local function take_packets_before(below)
  local ticks = {}
  for t in pairs(st.packets) do if t < below then ticks[#ticks + 1] = t end end
  table.sort(ticks)
  local out = {}
  for _, t in ipairs(ticks) do
    local senders = {}
    for n in pairs(st.packets[t]) do senders[#senders + 1] = n end
    table.sort(senders)
    for _, n in ipairs(senders) do out[#out + 1] = st.packets[t][n] end
    st.packets[t] = nil
  end
  return out
end

local function try_step()
  local m = st.sensors
  if not ready() or not m or m.tick ~= st.next_tick then return false end
  local t = st.next_tick
  local got = st.packets[t - 1] or {}
  local all_in = true
  if t > 0 then for _, n in ipairs(st.neighbours) do all_in = all_in and got[n] ~= nil end end
  if not st.realtime and not all_in
      and (opt.hormone_timeout == 0 or now() < st.sensors_at + opt.hormone_timeout) then
    return false
  end
  -- 1. Received hormone, increasing sender id (real time: every packet not yet added).
  local c, s = st.controller, st.state
  if st.realtime then
    for _, amounts in ipairs(take_packets_before(t)) do model.receive(s, amounts) end
  elseif t > 0 then
    for _, n in ipairs(st.neighbours) do
      if got[n] then model.receive(s, got[n]) else st.missing = st.missing + 1 end
    end
  end
  -- 2-6. Step on this tick's sensors, then HORMONE(t) and HINGE(t).
  model.step(c, s, m.values, m.present, m.actuator_present, #st.neighbours)
  local stamp = utime()
  if #st.neighbours > 0 then
    local p = ahhs.hormone_packet_t:new()
    p.utime, p.episode, p.tick, p.from_module = stamp, st.episode, t, opt.id
    p.num_receivers, p.to_modules = #st.neighbours, st.neighbours
    p.num_hormones, p.amounts = c.nh, s.outflow
    lc:publish(module_channel(opt.id, 'HORMONE'), p:encode())
  end
  local h = ahhs.hinge_command_t:new()
  h.utime, h.episode, h.tick, h.module = stamp, st.episode, t, opt.id
  h.num_actuators, h.values, h.present = c.na, s.actuators, m.actuator_present
  h.target_angle = math.pi / 2 * s.actuators[1]
  lc:publish(module_channel(opt.id, 'HINGE'), h:encode())
  st.next_tick = t + 1
  if not st.realtime then -- keep tick t onwards
    for tick in pairs(st.packets) do if tick < t then st.packets[tick] = nil end end
  end
  if st.status ~= ahhs.module_status_t.RUNNING then publish_status(ahhs.module_status_t.RUNNING) end
  return true
end

local running = true
psignal.signal(psignal.SIGINT, function() running = false end)
psignal.signal(psignal.SIGTERM, function() running = false end)
local stop_at = opt.seconds and now() + opt.seconds
publish_status(ahhs.module_status_t.IDLE)
while running and not (stop_at and now() >= stop_at) do
  -- Wait at most until the hormone timeout of a tick whose sensors are in.
  local wait = 0.1
  if st.sensors and st.sensors.tick == st.next_tick and opt.hormone_timeout > 0 then
    wait = math.max(0, math.min(wait, st.sensors_at + opt.hormone_timeout - now()))
  end
  pcall(lc.handle_timeout, lc, math.floor(wait * 1000)) -- a signal interrupts the wait
  sync_hormone_subscriptions()
  if st.announce_ready then
    st.announce_ready = false
    if ready() then publish_status(ahhs.module_status_t.READY) end
  end
  while try_step() do end
  if now() >= st.next_heartbeat then publish_status(st.status) end
end
