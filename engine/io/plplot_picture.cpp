// PLplot writes into memory (open_memstream), so that the caller writes the
// file whole or not at all. PLplot calls its exit handler on errors it
// cannot go on from (no memory, a broken driver) and exit()s the process
// when the handler returns: the handler jumps back to draw_on_new_stream
// instead. Between the two there are only PLplot's C frames and the
// painter's, which holds nothing with a destructor. Errors PLplot goes on
// from are written into a buffer (plsError) instead of stderr.
#include "io/plplot_picture.hpp"

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "core/error.hpp"

namespace ashlar {
namespace {

constexpr double kMillimetresPerPoint = 25.4 / 72.0;

std::mutex plplot_mutex;
std::jmp_buf* plplot_exit_jump = nullptr;
char plplot_exit_message[512];

int on_plplot_exit(const char* message) {
  std::snprintf(plplot_exit_message, sizeof plplot_exit_message, "%s", message);
  if (plplot_exit_jump) std::longjmp(*plplot_exit_jump, 1);
  return 1;  // unreachable: PLplot is called only inside draw_on_new_stream
}

const char* device_of(ImageFormat format) {
  switch (format) {
    case ImageFormat::png:
      return "pngcairo";
    case ImageFormat::pdf:
      return "pdfcairo";
    case ImageFormat::svg:
      break;
  }
  return "svg";
}

// Whether PLplot found `device` among its drivers: asked for one it does not
// have, it would ask for another on stdin.
bool has_device(const char* device) {
  const char* menus[128];
  const char* names[128];
  const char** menu_list = menus;
  const char** name_list = names;
  int count = 128;
  plgDevs(&menu_list, &name_list, &count);
  for (int k = 0; k < count; ++k) {
    if (std::strcmp(names[k], device) == 0) return true;
  }
  return false;
}

struct Outcome {
  bool drawn = false;
  std::string error;  // what PLplot said when not drawn
};

// Runs painter on a new PLplot stream with output into `file`, which PLplot
// closes when it ends the stream (or this function, when PLplot never took
// it). Call with plplot_mutex held.
Outcome draw_on_new_stream(const char* device, int width, int height, PlplotPainter painter,
                           void* context, FILE* file) {
  static char abort_message[2048];  // plsError: PLplot writes what failed here
  PLINT abort_code = 0;
  Outcome outcome;
  std::jmp_buf jump;
  volatile int stage = 0;  // 1: the stream exists, 2: ending it after an exit
  plsexit(on_plplot_exit);
  plplot_exit_jump = &jump;
  if (setjmp(jump) == 0) {
    if (!has_device(device)) {
      outcome.error = std::string("its '") + device +
                      "' device is missing (Debian: plplot-driver-cairo, libplplot17)";
      std::fclose(file);
    } else {
      PLINT stream = 0;
      plmkstrm(&stream);
      stage = 1;
      abort_message[0] = '\0';
      plsError(&abort_code, abort_message);
      plsdev(device);
      plsfile(file);
      plspage(0.0, 0.0, width, height, 0, 0);
      plspause(0);
      plscolbg(255, 255, 255);
      plinit();
      pladv(0);
      painter(context);
      plend1();
      outcome.drawn = abort_code == 0;
      if (!outcome.drawn) outcome.error = abort_message;
    }
  } else {
    outcome.error = plplot_exit_message;
    if (stage == 1) {
      stage = 2;
      PLINT level = 0;
      plglevel(&level);
      plend1();
      // Before plinit took it, the file is still ours.
      if (level == 0) std::fclose(file);
    }
  }
  plplot_exit_jump = nullptr;
  return outcome;
}

}  // namespace

std::string plplot_picture(ImageFormat format, int width, int height, PlplotPainter painter,
                           void* context, const std::string& what, const std::string& path) {
  char* buffer = nullptr;
  size_t size = 0;
  Outcome outcome;
  {
    const std::lock_guard<std::mutex> lock(plplot_mutex);
    FILE* file = open_memstream(&buffer, &size);
    if (!file) throw IoError(what + ": cannot draw '" + path + "': out of memory");
    outcome = draw_on_new_stream(device_of(format), width, height, painter, context, file);
  }
  const std::string bytes = buffer ? std::string(buffer, size) : std::string();
  std::free(buffer);
  if (!outcome.drawn) {
    throw IoError(what + ": PLplot could not draw '" + path + "': " + outcome.error);
  }
  return bytes;
}

void plplot_font(double size) {
  plschr(kPlplotCharacterHeight * size * kMillimetresPerPoint, 1.0);
}

std::string plplot_text(const std::string& text) {
  std::string escaped;
  for (const char c : text) escaped += c == '#' ? "##" : std::string(1, c);
  return escaped;
}

void plplot_boolean_label(PLINT, PLFLT value, char* text, PLINT length, PLPointer) {
  const char* label = std::abs(value) < 1e-9 ? "false" : std::abs(value - 1.0) < 1e-9 ? "true" : "";
  std::snprintf(text, static_cast<size_t>(length), "%s", label);
}

void plplot_page_title(const std::string& title, double font_size, double top_offset) {
  if (title.empty()) return;
  plplot_font(font_size);
  plmtex("t", -top_offset / (kPlplotCharacterHeight * font_size), 0.5, 0.5, title.c_str());
}

void plplot_color(PLINT index, const Rgb& color) {
  const auto byte = [](double channel) { return static_cast<PLINT>(std::lround(channel * 255)); };
  plscol0(index, byte(color.r), byte(color.g), byte(color.b));
}

}  // namespace ashlar
