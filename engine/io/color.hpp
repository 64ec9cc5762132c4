// A colour, shared by the exports, drawings and charts.
#pragma once

namespace ashlar {

struct Rgb {
  double r = 0.8, g = 0.8, b = 0.8;  // each in [0, 1]
};

}  // namespace ashlar
