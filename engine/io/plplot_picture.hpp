// Pictures drawn with PLplot (charts, colour legends). PLplot keeps global
// state (the current stream, its error handlers, the LC_NUMERIC switches
// around each driver call), so every picture is drawn on a stream of its
// own under one mutex. Include it only from the .cpp files that draw with
// PLplot, so that its headers stay there.
#pragma once

#include <plplot.h>

#include <string>

#include "io/color.hpp"
#include "io/image_format.hpp"

namespace ashlar {

// The PLplot calls of one picture, between plinit (and pladv) and plend1,
// which plplot_picture makes; `context` is the caller's. It must hold
// nothing with a destructor while it calls PLplot: PLplot's exit handler
// jumps out of it.
using PlplotPainter = void (*)(void* context);

// Draws a width x height picture (px for PNG, pt for SVG and PDF) on a
// white page with `painter` and returns the file's bytes. Devices: the cairo
// drivers for PNG and PDF (pango text, antialiased), PLplot's own svg driver
// for SVG, which writes text as <text> elements (cairo's SVG surface writes
// every glyph as a path). Throws IoError "<what>: PLplot could not draw
// '<path>': ..." when PLplot fails or lacks the device.
std::string plplot_picture(ImageFormat format, int width, int height, PlplotPainter painter,
                           void* context, const std::string& what, const std::string& path);

// Sets the character height for text of `size` px (pt): the cairo and svg
// drivers take the page at 72 dpi and write text at 4/3 of PLplot's
// character height (pango's 96 dpi, the svg driver's ratio 1.34).
void plplot_font(double size);

// PLplot's character height over the drivers' font size: plmtex and the
// like measure distances in character heights.
constexpr double kPlplotCharacterHeight = 0.75;

// Text as PLplot reads it: '#' starts its escape sequences (#u:
// superscript, ...), so a '#' of the text is doubled.
std::string plplot_text(const std::string& text);

// A PLplot label function (plslabelfunc) for axes of booleans: "false" at
// 0, "true" at 1, nothing elsewhere. plbox and plcolorbar call it for the
// axes whose options have 'o'.
void plplot_boolean_label(PLINT axis, PLFLT value, char* text, PLINT length, PLPointer data);

// A chart's title, centred at the top of the page: its baseline
// top_offset px below the page's top edge, in a font of font_size px, in
// the current colour. Nothing for an empty title. The viewport and window
// must span the page (plvpor and plwind over [0, 1]).
void plplot_page_title(const std::string& title, double font_size, double top_offset);

// Sets entry `index` of colour map 0 (opacity ignored).
void plplot_color(PLINT index, const Rgb& color);

}  // namespace ashlar
