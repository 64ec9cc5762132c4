// What the cairo drawings (drawing.cpp: elevations and colour legends) need:
// painting into memory and writing the file whole, and placing text. Include
// it only from the .cpp files that draw with cairo, so that cairo's headers
// stay there. Charts are PLplot's (chart.cpp).
#pragma once

#include <cairo.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/image_format.hpp"
#include "io/mesh_io.hpp"

namespace ashlar {

// Paints a white image of width x height (px for PNG, pt for SVG) with
// `paint` and writes it to path atomically. `paint` must not throw.
// Throws IoError naming `what` and the path when cairo fails or the file
// cannot be written.
void render_file(const std::string& path, ImageFormat format, int width, int height,
                 const std::string& what, const std::function<void(cairo_t*)>& paint);

struct CairoDeleter {
  void operator()(cairo_t* cr) const { cairo_destroy(cr); }
};
using CairoContext = std::unique_ptr<cairo_t, CairoDeleter>;

// A context on a 1 x 1 image, for measuring text before drawing anything.
CairoContext measuring_context();

void set_color(cairo_t* cr, const Rgb& color);

// The toy API's sans-serif face (DejaVu Sans on Debian) at `size` px.
void set_font(cairo_t* cr, double size);

// Advance width of text (UTF-8) in the current font, px.
double text_width(cairo_t* cr, const std::string& text);

// Draws text with its anchor at (x, y): align_x 0 puts its left end there,
// 0.5 its middle, 1 its right end; the text's capital height is centred on y.
void show_text(cairo_t* cr, const std::string& text, double x, double y, double align_x);

}  // namespace ashlar
