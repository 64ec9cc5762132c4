#include "junit_report.hpp"

#include <cstdio>

namespace ashlar::regression {

namespace {

constexpr const char* kReplacement = "\xEF\xBF\xBD";  // U+FFFD

// The length of the valid UTF-8 sequence of an XML character at text[at],
// or 0 when there is none.
std::size_t xml_character_length(const std::string& text, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[at + k]); };
  const unsigned char first = byte(0);
  if (first < 0x80) return first >= 0x20 || first == '\t' || first == '\n' || first == '\r' ? 1 : 0;
  const std::size_t length = first >= 0xF0 ? 4 : first >= 0xE0 ? 3 : first >= 0xC2 ? 2 : 0;
  if (length == 0 || first > 0xF4 || at + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k)
    if ((byte(k) & 0xC0) != 0x80) return 0;
  // Overlong forms, surrogates, beyond U+10FFFF, and U+FFFE/U+FFFF.
  if (first == 0xE0 && byte(1) < 0xA0) return 0;
  if (first == 0xED && byte(1) >= 0xA0) return 0;
  if (first == 0xF0 && byte(1) < 0x90) return 0;
  if (first == 0xF4 && byte(1) >= 0x90) return 0;
  if (first == 0xEF && byte(1) == 0xBF && (byte(2) == 0xBE || byte(2) == 0xBF)) return 0;
  return length;
}

// Text for an element or (with `attribute`) a double-quoted attribute.
std::string escaped(const std::string& text, bool attribute = false) {
  std::string out;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t length = xml_character_length(text, at);
    if (length == 0) {
      out += kReplacement;
      ++at;
      continue;
    }
    const char c = text[at];
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (attribute && c == '"') out += "&quot;";
    else if (attribute && c == '\n') out += "&#10;";
    else if (attribute && c == '\r') out += "&#13;";
    else if (attribute && c == '\t') out += "&#9;";
    else out.append(text, at, length);
    at += length;
  }
  return out;
}

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", seconds);
  return text;
}

}  // namespace

std::string format_junit(const std::string& suite, const std::vector<JunitCase>& cases) {
  std::size_t failed = 0;
  double seconds = 0.0;
  for (const JunitCase& test : cases) {
    failed += test.failures.empty() ? 0 : 1;
    seconds += test.seconds;
  }
  const std::string counts = "tests=\"" + std::to_string(cases.size()) + "\" failures=\"" + std::to_string(failed) +
                             "\" errors=\"0\" time=\"" + seconds_text(seconds) + "\"";
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += "<testsuites name=\"ashlar test\" " + counts + ">\n";
  xml += "  <testsuite name=\"" + escaped(suite, true) + "\" " + counts + " skipped=\"0\">\n";
  for (const JunitCase& test : cases) {
    xml += "    <testcase classname=\"" + escaped(suite, true) + "\" name=\"" + escaped(test.name, true) +
           "\" time=\"" + seconds_text(test.seconds) + "\">\n";
    if (!test.failures.empty()) {
      std::string lines;
      for (const std::string& line : test.failures) lines += line + "\n";
      xml += "      <failure message=\"" + escaped(test.failures.front(), true) + "\" type=\"" +
             (test.failures.size() == 1 ? "1 failure" : std::to_string(test.failures.size()) + " failures") +
             "\">" + escaped(lines) + "</failure>\n";
    }
    if (!test.output.empty()) xml += "      <system-out>" + escaped(test.output) + "</system-out>\n";
    if (!test.error_output.empty()) xml += "      <system-err>" + escaped(test.error_output) + "</system-err>\n";
    xml += "    </testcase>\n";
  }
  xml += "  </testsuite>\n</testsuites>\n";
  return xml;
}

}  // namespace ashlar::regression
