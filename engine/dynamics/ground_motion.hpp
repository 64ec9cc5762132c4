// Recorded ground motions (accelerograms) read from files, for
// SimulationOptions::ground_acceleration.
//
// Formats:
// - PEER NGA AT2: four header lines (the third names the units, "UNITS OF
//   G"; the fourth gives the number of points and the step, either
//   "NPTS= 3901, DT= .0100 SEC" or "3901 0.0100 NPTS, DT"), then NPTS
//   accelerations, any number per line; sample k is at time k DT.
// - A table (".csv", ".txt" or any other name): one sample per line, time
//   (s, increasing) then one to three accelerations, separated by commas,
//   semicolons, tabs or spaces; lines starting with '#' and header lines
//   before the first number are skipped. Its units are not in the file:
//   the caller states them.
//
// Between samples the acceleration is linear in time; before the first and
// after the last sample it is zero (the ground is still). Every error names
// the file, the line (1-based) and the text found.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "core/types.hpp"

namespace ashlar {

enum class AccelerationUnit { g, m_per_s2, cm_per_s2 };
inline constexpr EnumNames<AccelerationUnit, 3> kAccelerationUnitNames{{{{AccelerationUnit::g, "g"},
                                                                         {AccelerationUnit::m_per_s2, "m/s2"},
                                                                         {AccelerationUnit::cm_per_s2, "cm/s2"}}}};
// m/s^2 per unit (g is kGravity).
double acceleration_unit_size(AccelerationUnit unit);

// Baseline correction, applied to each component's samples: `mean`
// subtracts their mean, `linear` the least-squares line a + b t through
// them (a constant or drifting offset of the instrument, which would make
// the ground's velocity grow without end).
enum class Baseline { none, mean, linear };
inline constexpr EnumNames<Baseline, 3> kBaselineNames{
    {{{Baseline::none, "none"}, {Baseline::mean, "mean"}, {Baseline::linear, "linear"}}}};

// One file's samples as written: times (s, strictly increasing) and, per
// column, the accelerations in the file's units.
struct RecordColumns {
  std::vector<double> times;
  std::vector<std::vector<double>> columns;  // 1 to 3, each times.size() long
  // The units the file states (AT2); a table states none.
  bool has_unit = false;
  AccelerationUnit unit = AccelerationUnit::g;
};

// Reads a PEER NGA AT2 file. Throws IoError when it cannot be opened, and
// InvalidArgument "<path>:<line>: ..." for a malformed header, units it
// does not name, a value that is not a number, or a count of values other
// than NPTS.
RecordColumns read_at2(const std::string& path);

// Reads a table of time and 1 to 3 accelerations. Throws IoError when it
// cannot be opened, and InvalidArgument "<path>:<line>: ..." for a value
// that is not a finite number, a line whose count of columns differs from
// the first data line's, times that do not increase, or fewer than 2 samples.
RecordColumns read_acceleration_table(const std::string& path);

// A ground acceleration (m/s^2) as the sum of components, each a sampled
// scalar acting along a direction.
class GroundMotion {
public:
  struct Component {
    std::vector<double> times;   // s, strictly increasing, >= 2 of them
    std::vector<double> values;  // m/s^2 at those times
    Vec3 direction;              // unit vector the acceleration acts along
  };

  // Throws InvalidArgument for a component with fewer than 2 samples,
  // times not strictly increasing or not finite, values not finite, or a
  // direction that is not a unit vector.
  explicit GroundMotion(std::vector<Component> components);

  // The acceleration at time t (m/s^2): linear between samples, zero
  // outside each component's samples.
  Vec3 operator()(double t) const;

  const std::vector<Component>& components() const { return components_; }
  double duration() const;     // the last sample's time of any component (s)
  double peak() const;         // the largest |acceleration| over the samples (m/s^2)
  double peak_time() const;    // a time where that peak is reached (s)

private:
  std::vector<Component> components_;
};

// A component from column `column` of a read file: values times the unit's
// size (`unit` when the file states none; a file's own unit otherwise)
// times `scale`, baseline-corrected as asked, along `direction`.
GroundMotion::Component record_component(const RecordColumns& record, int column, AccelerationUnit unit,
                                         double scale, Baseline baseline, const Vec3& direction);

}  // namespace ashlar
