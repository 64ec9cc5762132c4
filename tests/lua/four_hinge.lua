-- An independent reference for the load factor of an arch without sliding:
-- the kinematic (upper-bound) theorem over every four-hinge mechanism.
-- Voussoirs 1..n run from the left support (block n + 1) to the right one
-- (n + 2); joint j lies between voussoirs j and j + 1 (joint 0 on the left
-- support, n on the right). A mechanism puts hinges at four joints
-- j1 < j2 < j3 < j4, each at one end of its joint: voussoirs j1+1..j2 turn
-- about hinge 1, j3+1..j4 about hinge 4, and the middle about the
-- intersection of the lines through hinges 1, 2 and 3, 4. It is admissible
-- when every hinge opens its joint at the other end. Virtual work of the
-- weights and of the lateral load lambda * weight along +x gives lambda; the
-- smallest over admissible mechanisms in which the lateral load does
-- positive work is the collapse factor. Planar (x-z), rotations about +y.
local M = {}

-- Velocity (x, z) at p of a body turning at omega about c.
local function velocity(omega, c, p)
  return omega * (p[2] - c[2]), -omega * (p[1] - c[1])
end

local function intersection(p1, p2, p3, p4)
  local d1x, d1z = p2[1] - p1[1], p2[2] - p1[2]
  local d2x, d2z = p4[1] - p3[1], p4[2] - p3[2]
  local det = d1x * d2z - d1z * d2x
  if math.abs(det) < 1e-14 * (d1x * d1x + d1z * d1z + d2x * d2x + d2z * d2z) then return nil end
  local t = ((p3[1] - p1[1]) * d2z - (p3[2] - p1[2]) * d2x) / det
  return { p1[1] + t * d1x, p1[2] + t * d1z }
end

-- The joints' two ends (x, z) and unit normals from voussoir j to j + 1.
local function joints(s, n)
  local found = {}
  for _, f in ipairs(s:interfaces()) do
    -- a < b; the left support's joint is 0 and its normal points into the
    -- support, against the voussoir order.
    local j = f.b == n + 1 and 0 or f.b == n + 2 and n or f.a
    local sign = f.b == n + 1 and -1 or 1
    -- Ends: the vertices farthest apart in the x-z plane.
    local best, ends = -1, nil
    for _, p in ipairs(f.vertices) do
      for _, q in ipairs(f.vertices) do
        local d = (p[1] - q[1]) ^ 2 + (p[3] - q[3]) ^ 2
        if d > best then best, ends = d, { { p[1], p[3] }, { q[1], q[3] } } end
      end
    end
    found[j] = { ends = ends, normal = { sign * f.normal[1], sign * f.normal[3] } }
  end
  return found
end

-- The collapse factor and its hinges { joint, end } (end 1 or 2 of the joint).
function M.collapse_factor(s, n)
  local joint = joints(s, n)
  for j = 0, n do assert(joint[j], "four_hinge: joint " .. j .. " not found") end
  -- Prefix sums of W, W x, W z over voussoirs 1..k.
  local S0, Sx, Sz = { [0] = 0 }, { [0] = 0 }, { [0] = 0 }
  for k = 1, n do
    local b = s:block(k)
    local w, c = b:mass() * 9.81, b:centroid()
    S0[k], Sx[k], Sz[k] = S0[k - 1] + w, Sx[k - 1] + w * c[1], Sz[k - 1] + w * c[3]
  end
  -- Work of voussoirs first+1..last turning at omega about c: dead, live.
  local function work(first, last, omega, c)
    local w0, wx, wz = S0[last] - S0[first], Sx[last] - Sx[first], Sz[last] - Sz[first]
    return omega * (wx - c[1] * w0), omega * (wz - c[2] * w0)
  end
  -- Whether the relative rotation turn (next minus previous) about hinge
  -- end e of joint j opens the joint's other end.
  local function opens(j, e, turn)
    local h, p = joint[j].ends[e], joint[j].ends[3 - e]
    local vx, vz = velocity(turn, h, p)
    return vx * joint[j].normal[1] + vz * joint[j].normal[2] >= 0
  end
  local best, hinges = math.huge, nil
  for j1 = 0, n - 3 do
    for j2 = j1 + 1, n - 2 do
      for j3 = j2 + 1, n - 1 do
        for j4 = j3 + 1, n do
          for e1 = 1, 2 do
            local h1 = joint[j1].ends[e1]
            for e2 = 1, 2 do
              local h2 = joint[j2].ends[e2]
              for e3 = 1, 2 do
                local h3 = joint[j3].ends[e3]
                for e4 = 1, 2 do
                  local h4 = joint[j4].ends[e4]
                  local c = intersection(h1, h2, h3, h4)
                  if c then
                    local d12 = { h2[1] - h1[1], h2[2] - h1[2] }
                    local alpha = ((h2[1] - c[1]) * d12[1] + (h2[2] - c[2]) * d12[2]) / (d12[1] ^ 2 + d12[2] ^ 2)
                    local d34 = { h3[1] - h4[1], h3[2] - h4[2] }
                    local beta = ((h3[1] - c[1]) * d34[1] + (h3[2] - c[2]) * d34[2]) / (d34[1] ^ 2 + d34[2] ^ 2)
                    if alpha ~= 0 then
                      local w1 = 1
                      local w2 = w1 / alpha
                      local w3 = w2 * beta
                      local dead1, live1 = work(j1, j2, w1, h1)
                      local dead2, live2 = work(j2, j3, w2, c)
                      local dead3, live3 = work(j3, j4, w3, h4)
                      local dead, live = dead1 + dead2 + dead3, live1 + live2 + live3
                      local sign = live > 0 and 1 or -1
                      if live ~= 0 and opens(j1, e1, sign * w1) and opens(j2, e2, sign * (w2 - w1))
                          and opens(j3, e3, sign * (w3 - w2)) and opens(j4, e4, -sign * w3) then
                        local lambda = -dead / live
                        if lambda < best then
                          best = lambda
                          hinges = { { j1, e1 }, { j2, e2 }, { j3, e3 }, { j4, e4 } }
                        end
                      end
                    end
                  end
                end
              end
            end
          end
        end
      end
    end
  end
  return best, hinges
end

return M
