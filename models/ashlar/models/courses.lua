-- Forces of a models.dome structure course by course, for any analysis
-- whose interfaces carry a, b and normal_force (ashlar.analyze's result,
-- ashlar.fea's result): the thesis's figure 15 compares them.
local courses = {}

-- For each course (1 = bottom): the mean normal force of its hoop joints
-- (between two blocks of the course) over the mean normal force of the bed
-- joints under its blocks. Blocks are matched to courses by their names
-- ("course c block m"); the keystone and supports belong to none.
function courses.hoop_ratios(s, interfaces)
  local course = {}
  for i = 1, #s do course[i] = tonumber(s:name(i):match("^course (%d+) ")) end
  local hoop, hoops, bed, beds = {}, {}, {}, {}
  for _, f in ipairs(interfaces) do
    local ca, cb = course[f.a], course[f.b]
    if ca and ca == cb then
      hoop[ca], hoops[ca] = (hoop[ca] or 0) + f.normal_force, (hoops[ca] or 0) + 1
    elseif ca or cb then
      local upper = s:block(f.a):centroid()[3] > s:block(f.b):centroid()[3] and f.a or f.b
      local c = course[upper]
      if c then bed[c], beds[c] = (bed[c] or 0) + f.normal_force, (beds[c] or 0) + 1 end
    end
  end
  local ratios = {}
  for c = 1, #hoop do ratios[c] = (hoop[c] / hoops[c]) / (bed[c] / beds[c]) end
  return ratios
end

return courses
