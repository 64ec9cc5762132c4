// A colour with its opacity, shared by the exports, drawings and charts.
#pragma once

namespace ashlar {

struct Rgb {
  double r = 0.8, g = 0.8, b = 0.8;  // each in [0, 1]
  double a = 1.0;                    // opacity in [0, 1]: 1 opaque
};

}  // namespace ashlar
