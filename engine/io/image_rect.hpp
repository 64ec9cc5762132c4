// A rectangle of an image, shared by the drawings and the charts.
#pragma once

namespace ashlar {

// A rectangle of an image (px, pt for vector formats), y down.
struct ImageRect {
  double left = 0.0, top = 0.0, width = 0.0, height = 0.0;

  double right() const { return left + width; }
  double bottom() const { return top + height; }
};

}  // namespace ashlar
