#include "dynamics/ground_motion.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <initializer_list>

#include "core/error.hpp"
#include "core/text.hpp"

namespace ashlar {

namespace {

// The file's lines; IoError when it cannot be opened.
std::vector<std::string> file_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("ground_motion: cannot open \"" + path + "\"");
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

[[noreturn]] void malformed(const std::string& path, std::size_t line, const std::string& message) {
  throw InvalidArgument(path + ":" + std::to_string(line + 1) + ": " + message);
}

// The text shown for a token in an error, cut to a readable length.
std::string quoted(const std::string& token) {
  return "\"" + (token.size() > 40 ? token.substr(0, 40) + "..." : token) + "\"";
}

// The line's fields between separators (commas, semicolons, tabs, spaces).
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::string current;
  for (const char c : line) {
    if (c == ',' || c == ';' || c == ' ' || c == '\t') {
      if (!current.empty()) out.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) out.push_back(current);
  return out;
}

// The whole token as a finite number (a leading '+' allowed, as Fortran
// writes them), or false.
bool parse_number(const std::string& token, double& value) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+') ++first;
  const std::from_chars_result result = std::from_chars(first, last, value);
  return result.ec == std::errc() && result.ptr == last && std::isfinite(value);
}

double number_at(const std::string& path, std::size_t line, const std::string& token, const char* what) {
  double value = 0.0;
  if (!parse_number(token, value)) malformed(path, line, std::string("expected ") + what + ", got " + quoted(token));
  return value;
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

// The number after `key` (e.g. "NPTS") and an optional '=' in the line.
bool keyed_number(const std::string& line, const std::string& key, std::string& token) {
  const std::string text = upper(line);
  std::size_t at = text.find(key);
  if (at == std::string::npos) return false;
  at += key.size();
  while (at < line.size() && (line[at] == ' ' || line[at] == '=' || line[at] == '\t')) ++at;
  const std::size_t end = line.find_first_of(" ,\t", at);
  token = line.substr(at, end == std::string::npos ? std::string::npos : end - at);
  return true;
}

}  // namespace

double acceleration_unit_size(AccelerationUnit unit) {
  switch (unit) {
    case AccelerationUnit::g: return kGravity;
    case AccelerationUnit::m_per_s2: return 1.0;
    case AccelerationUnit::cm_per_s2: return 0.01;
  }
  return 1.0;
}

RecordColumns read_at2(const std::string& path) {
  const std::vector<std::string> lines = file_lines(path);
  if (lines.size() < 4) {
    malformed(path, lines.size() == 0 ? 0 : lines.size() - 1,
              "a PEER AT2 file has four header lines (title, event, units, NPTS and DT) before its values; this "
              "file has " + std::to_string(lines.size()) + " lines");
  }
  RecordColumns record;
  // Line 3: "ACCELERATION TIME SERIES IN UNITS OF G" (or of cm/s^2, m/s^2).
  const std::string units = upper(lines[2]);
  const auto names = [&](std::initializer_list<const char*> spellings) {
    return std::any_of(spellings.begin(), spellings.end(),
                       [&](const char* spelling) { return units.find(spelling) != std::string::npos; });
  };
  record.has_unit = true;
  if (names({"CM/S/S", "CM/S^2", "CM/S2", "CM/SEC/SEC", "CM/SEC^2", "CM/SEC2"})) {
    record.unit = AccelerationUnit::cm_per_s2;
  } else if (names({"M/S/S", "M/S^2", "M/S2", "M/SEC/SEC", "M/SEC^2", "M/SEC2"})) {
    record.unit = AccelerationUnit::m_per_s2;
  } else if (names({"UNITS OF G"}) || units.find_first_not_of(" ") == units.find("G ") ||
             (units.size() >= 2 && units.compare(units.size() - 2, 2, " G") == 0)) {
    record.unit = AccelerationUnit::g;
  } else {
    malformed(path, 2, "expected the units of acceleration (\"... UNITS OF G\", or CM/S/S, M/S/S), got " +
                           quoted(lines[2]));
  }
  // Line 4: "NPTS=  3901, DT=   .0100 SEC" (NGA-West2) or "3901  .0100  NPTS, DT" (NGA-West1).
  std::string npts_token, dt_token;
  if (!(keyed_number(lines[3], "NPTS", npts_token) && keyed_number(lines[3], "DT", dt_token)) ||
      upper(lines[3]).find("NPTS") > upper(lines[3]).find_first_of("0123456789")) {
    const std::vector<std::string> words = fields(lines[3]);
    if (words.size() < 2) malformed(path, 3, "expected \"NPTS= n, DT= step\" or \"n step\", got " + quoted(lines[3]));
    npts_token = words[0];
    dt_token = words[1];
  }
  double npts = 0.0;
  if (!parse_number(npts_token, npts) || npts < 2 || npts != std::floor(npts) || npts > 1e9) {
    malformed(path, 3, "expected the number of points NPTS, a whole number >= 2, got " + quoted(npts_token));
  }
  double dt = 0.0;
  if (!parse_number(dt_token, dt) || dt <= 0) malformed(path, 3, "expected the step DT > 0 (s), got " + quoted(dt_token));
  const auto count = static_cast<std::size_t>(npts);
  std::vector<double> values;
  values.reserve(count);
  for (std::size_t line = 4; line < lines.size(); ++line) {
    for (const std::string& token : fields(lines[line])) {
      if (values.size() == count) {
        malformed(path, line, "more values than NPTS = " + std::to_string(count) + ": " + quoted(token));
      }
      values.push_back(number_at(path, line, token, "an acceleration"));
    }
  }
  if (values.size() != count) {
    malformed(path, lines.size() - 1,
              "NPTS = " + std::to_string(count) + " but the file holds " + std::to_string(values.size()) + " values");
  }
  record.times.resize(count);
  for (std::size_t k = 0; k < count; ++k) record.times[k] = static_cast<double>(k) * dt;
  record.columns.push_back(std::move(values));
  return record;
}

RecordColumns read_acceleration_table(const std::string& path) {
  const std::vector<std::string> lines = file_lines(path);
  RecordColumns record;
  std::size_t width = 0;  // fields per data line, from the first
  for (std::size_t line = 0; line < lines.size(); ++line) {
    const std::vector<std::string> words = fields(lines[line]);
    if (words.empty() || words[0][0] == '#') continue;
    double first = 0.0;
    if (width == 0 && !parse_number(words[0], first)) continue;  // a header line
    if (width == 0) {
      if (words.size() < 2 || words.size() > 4) {
        malformed(path, line, "expected a time and 1 to 3 accelerations, got " + std::to_string(words.size()) +
                                  " values: " + quoted(lines[line]));
      }
      width = words.size();
      record.columns.resize(width - 1);
    }
    if (words.size() != width) {
      malformed(path, line, "expected " + std::to_string(width) + " values as on the first data line, got " +
                                std::to_string(words.size()) + ": " + quoted(lines[line]));
    }
    const double t = number_at(path, line, words[0], "a time (s)");
    if (!record.times.empty() && t <= record.times.back()) {
      malformed(path, line, "times must increase: " + shortest_number(t) + " s follows " +
                                shortest_number(record.times.back()) + " s");
    }
    record.times.push_back(t);
    for (std::size_t c = 1; c < width; ++c) record.columns[c - 1].push_back(number_at(path, line, words[c], "an acceleration"));
  }
  if (record.times.size() < 2) {
    malformed(path, lines.empty() ? 0 : lines.size() - 1,
              "expected at least 2 lines of time and acceleration, found " + std::to_string(record.times.size()));
  }
  return record;
}

GroundMotion::Component record_component(const RecordColumns& record, int column, AccelerationUnit unit,
                                         double scale, Baseline baseline, const Vec3& direction) {
  const double size = acceleration_unit_size(record.has_unit ? record.unit : unit) * scale;
  GroundMotion::Component component{record.times, record.columns.at(static_cast<std::size_t>(column)), direction};
  std::vector<double>& a = component.values;
  const std::vector<double>& t = component.times;
  const double n = static_cast<double>(a.size());
  if (baseline != Baseline::none) {
    double mean_t = 0.0, mean_a = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      mean_t += t[k] / n;
      mean_a += a[k] / n;
    }
    double slope = 0.0;
    if (baseline == Baseline::linear) {
      double stt = 0.0, sta = 0.0;
      for (std::size_t k = 0; k < a.size(); ++k) {
        stt += (t[k] - mean_t) * (t[k] - mean_t);
        sta += (t[k] - mean_t) * (a[k] - mean_a);
      }
      slope = sta / stt;
    }
    for (std::size_t k = 0; k < a.size(); ++k) a[k] -= mean_a + slope * (t[k] - mean_t);
  }
  for (double& value : a) value *= size;
  return component;
}

GroundMotion::GroundMotion(std::vector<Component> components) : components_(std::move(components)) {
  if (components_.empty()) throw InvalidArgument("ground_motion: no component");
  for (const Component& c : components_) {
    if (c.times.size() < 2 || c.times.size() != c.values.size()) {
      throw InvalidArgument("ground_motion: a component needs at least 2 samples, as many times as values");
    }
    for (std::size_t k = 0; k < c.times.size(); ++k) {
      if (!std::isfinite(c.times[k]) || !std::isfinite(c.values[k]) || (k > 0 && c.times[k] <= c.times[k - 1])) {
        throw InvalidArgument("ground_motion: sample " + std::to_string(k + 1) +
                              " has a time that is not finite or does not increase, or a value that is not finite");
      }
    }
    if (!c.direction.allFinite() || std::abs(c.direction.norm() - 1.0) > 1e-12) {
      throw InvalidArgument("ground_motion: a component's direction must be a unit vector");
    }
  }
}

Vec3 GroundMotion::operator()(double t) const {
  Vec3 a = Vec3::Zero();
  for (const Component& c : components_) {
    if (!(t >= c.times.front() && t <= c.times.back())) continue;
    // The first sample later than t (or the last), and the one before it.
    const auto after = std::upper_bound(c.times.begin(), c.times.end() - 1, t);
    const std::size_t k = static_cast<std::size_t>(after - c.times.begin());
    const double t0 = c.times[k - 1], t1 = c.times[k];
    const double w = (t - t0) / (t1 - t0);
    a += ((1.0 - w) * c.values[k - 1] + w * c.values[k]) * c.direction;
  }
  return a;
}

double GroundMotion::duration() const {
  double end = 0.0;
  for (const Component& c : components_) end = std::max(end, c.times.back());
  return end;
}

double GroundMotion::peak() const { return (*this)(peak_time()).norm(); }

double GroundMotion::peak_time() const {
  double best = -1.0, when = 0.0;
  for (const Component& c : components_) {
    for (const double t : c.times) {
      const double size = (*this)(t).norm();
      if (size > best) {
        best = size;
        when = t;
      }
    }
  }
  return when;
}

}  // namespace ashlar
