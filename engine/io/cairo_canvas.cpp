// Rendering into memory (the SVG surface writes to a stream, the
// image surface is encoded as PNG into a string), so that the file is
// written whole by write_file_atomically or not at all.
#include "io/cairo_canvas.hpp"

#include <cairo-svg.h>

#include <new>

#include "core/error.hpp"
#include "core/atomic_file.hpp"

namespace ashlar {
namespace {

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  // No exception may unwind through cairo's C frames.
  try {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  } catch (const std::bad_alloc&) {
    return CAIRO_STATUS_NO_MEMORY;
  }
  return CAIRO_STATUS_SUCCESS;
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* surface) const { cairo_surface_destroy(surface); }
};

// Drawings are SVG or PNG (drawing_format).
cairo_surface_t* create_surface(ImageFormat format, int width, int height, std::string& bytes) {
  if (format == ImageFormat::svg) {
    return cairo_svg_surface_create_for_stream(append_to_string, &bytes, width, height);
  }
  return cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
}

}  // namespace

void render_file(const std::string& path, ImageFormat format, int width, int height,
                 const std::string& what, const std::function<void(cairo_t*)>& paint) {
  std::string bytes;
  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
      create_surface(format, width, height, bytes));
  cairo_status_t status = cairo_surface_status(surface.get());
  if (status == CAIRO_STATUS_SUCCESS) {
    CairoContext cr(cairo_create(surface.get()));
    cairo_set_source_rgb(cr.get(), 1.0, 1.0, 1.0);
    cairo_paint(cr.get());
    paint(cr.get());
    status = cairo_status(cr.get());
  }
  if (status == CAIRO_STATUS_SUCCESS && format == ImageFormat::png) {
    status = cairo_surface_write_to_png_stream(surface.get(), append_to_string, &bytes);
  }
  // Finishing a vector surface writes its last part into `bytes`.
  cairo_surface_finish(surface.get());
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface.get());
  if (status != CAIRO_STATUS_SUCCESS) {
    throw IoError(what + ": cannot draw '" + path + "': " + cairo_status_to_string(status));
  }
  write_file_atomically(path, bytes);
}

CairoContext measuring_context() {
  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1));
  // The context keeps its own reference to the surface.
  return CairoContext(cairo_create(surface.get()));
}

void set_color(cairo_t* cr, const Rgb& color) {
  cairo_set_source_rgba(cr, color.r, color.g, color.b, color.a);
}

void set_font(cairo_t* cr, double size) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double text_width(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  return extents.x_advance;
}

void show_text(cairo_t* cr, const std::string& text, double x, double y, double align_x) {
  cairo_text_extents_t capital;
  cairo_text_extents(cr, "H", &capital);
  cairo_move_to(cr, x - align_x * text_width(cr, text), y - capital.y_bearing / 2);
  cairo_show_text(cr, text.c_str());
}

}  // namespace ashlar
