// Every tick is an integer n times 10^e, and its label is written from those
// integers, so that labels never show round-off ("0.30000000000000004") and
// values equal the decimal numbers they stand for.
#include "io/axis_ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.hpp"

namespace ashlar {
namespace {

// Ticks within this fraction of a step (linear) or of their value (log)
// outside the range still count: the range's ends are often ticks
// themselves, up to round-off.
constexpr double kEdgeTolerance = 1e-9;
// Plain numbers for ticks in [kPlainFrom, kPlainTo); powers of ten outside.
constexpr double kPlainFrom = 1e-4;
constexpr double kPlainTo = 1e6;
const char* const kMinus = "\u2212";

// A tick: n × 10^e.
struct Decimal {
  long long n;
  int e;

  double value() const {
    // Dividing by an exact power of ten rounds correctly: 8 / 100 == 0.08.
    const double power = std::pow(10.0, std::abs(e));
    return e >= 0 ? static_cast<double>(n) * power : static_cast<double>(n) / power;
  }
};

// n × 10^e written out with max(0, -e) decimals: "0.08", "120", "−1.5".
std::string plain_label(const Decimal& tick) {
  std::string digits = std::to_string(std::llabs(tick.n));
  if (tick.e >= 0) {
    if (tick.n != 0) digits += std::string(tick.e, '0');
  } else {
    const size_t decimals = -tick.e;
    if (digits.size() <= decimals) digits.insert(0, decimals + 1 - digits.size(), '0');
    digits.insert(digits.size() - decimals, ".");
  }
  return (tick.n < 0 ? kMinus : "") + digits;
}

// A log axis tick n × 10^e (n = 1, 2 or 5) as "10⁻⁶" or "2×10⁻⁵".
std::string power_label(const Decimal& tick) {
  const std::string power = power_of_ten_text(tick.e);
  return tick.n == 1 ? power : std::to_string(tick.n) + "\u00d7" + power;
}

// Log axis ticks labelled on their own: plain numbers while every one lies
// in [1e-4, 1e6), powers of ten otherwise.
AxisTicks log_ticks_of(const std::vector<Decimal>& decimals) {
  AxisTicks ticks;
  const bool plain = std::all_of(decimals.begin(), decimals.end(), [](const Decimal& tick) {
    return tick.value() >= kPlainFrom && tick.value() < kPlainTo;
  });
  for (const Decimal& tick : decimals) {
    ticks.values.push_back(tick.value());
    ticks.labels.push_back(plain ? plain_label(tick) : power_label(tick));
  }
  return ticks;
}

void check_count(int max_count, const char* what) {
  if (max_count < 2) {
    throw InvalidArgument(std::string(what) + ": need room for at least 2 ticks, got " +
                          std::to_string(max_count));
  }
}

// Smallest and largest integers k with lo <= 10^k <= hi (to the tolerance).
std::pair<int, int> decades_inside(double lo, double hi) {
  return {static_cast<int>(std::ceil(std::log10(lo) - kEdgeTolerance)),
          static_cast<int>(std::floor(std::log10(hi) + kEdgeTolerance))};
}

// Powers of ten from 10^first to 10^last whose exponents are multiples of
// the smallest step of 1, 2 or 5 times a power of ten that keeps at most
// max_count of them.
std::vector<Decimal> thinned_decades(int first, int last, int max_count) {
  for (long long scale = 1;; scale *= 10) {
    for (const long long mantissa : {1, 2, 5}) {
      const long long step = mantissa * scale;
      // Multiples of step in [first, last], rounding towards the inside.
      const long long from = first >= 0 ? (first + step - 1) / step : -((-first) / step);
      const long long to = last >= 0 ? last / step : -((-last + step - 1) / step);
      if (to - from + 1 > max_count) continue;
      std::vector<Decimal> decades;
      for (long long k = from; k <= to; ++k) decades.push_back({1, static_cast<int>(k * step)});
      return decades;
    }
  }
}

}  // namespace

int linear_label_power(double lo, double hi) {
  const double largest = std::max(std::abs(lo), std::abs(hi));
  if (largest >= kPlainTo || (largest > 0.0 && largest < kPlainFrom)) {
    return static_cast<int>(std::floor(std::log10(largest)));
  }
  return 0;
}

AxisTicks linear_ticks(double lo, double hi, int max_count) {
  check_count(max_count, "linear ticks");
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
    std::ostringstream message;
    message << "linear ticks: need a finite range with lo < hi, got [" << lo << ", " << hi << "]";
    throw InvalidArgument(message.str());
  }
  // A step a hundredth of the range gives more than max_count ticks; grow it.
  int exponent = static_cast<int>(std::floor(std::log10((hi - lo) / max_count))) - 1;
  for (;; ++exponent) {
    for (const long long mantissa : {1, 2, 5}) {
      const double step = Decimal{mantissa, exponent}.value();
      const double first = std::ceil(lo / step - kEdgeTolerance);
      const double last = std::floor(hi / step + kEdgeTolerance);
      if (last - first + 1 > max_count) continue;
      AxisTicks ticks;
      ticks.power = linear_label_power(lo, hi);
      for (double k = first; k <= last; ++k) {
        const long long n = static_cast<long long>(k) * mantissa;
        ticks.values.push_back(Decimal{n, exponent}.value());
        // n × 10^exponent / 10^power, exactly.
        ticks.labels.push_back(plain_label({n, exponent - ticks.power}));
      }
      return ticks;
    }
  }
}

AxisTicks log_ticks(double lo, double hi, int max_count) {
  check_count(max_count, "log ticks");
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo > 0.0) || !(lo < hi)) {
    std::ostringstream message;
    message << "log ticks: need a finite range with 0 < lo < hi, got [" << lo << ", " << hi << "]";
    throw InvalidArgument(message.str());
  }
  // Not a structured binding: the lambda below captures these, which C++17
  // (and clang before 16) does not allow for bindings.
  const std::pair<int, int> decades_range = decades_inside(lo, hi);
  const int first = decades_range.first;
  const int last = decades_range.second;
  const int decade_count = last - first + 1;
  const auto with_minor_ticks = [&](AxisTicks ticks) {
    for (int k = first - 1; k <= last; ++k) {
      for (long long m = 2; m <= 9; ++m) {
        const double value = Decimal{m, k}.value();
        if (value >= lo && value <= hi) ticks.minor.push_back(value);
      }
    }
    return ticks;
  };
  if (decade_count >= 3) {
    const std::vector<Decimal> decades = thinned_decades(first, last, max_count);
    const bool every_decade = static_cast<int>(decades.size()) == decade_count;
    return every_decade ? with_minor_ticks(log_ticks_of(decades)) : log_ticks_of(decades);
  }
  std::vector<Decimal> one_two_five;
  for (int k = first - 1; k <= last; ++k) {
    for (const long long m : {1, 2, 5}) {
      const double value = Decimal{m, k}.value();
      if (value >= lo * (1 - kEdgeTolerance) && value <= hi * (1 + kEdgeTolerance)) {
        one_two_five.push_back({m, k});
      }
    }
  }
  const int count = static_cast<int>(one_two_five.size());
  if (count >= 2 && count <= max_count) return log_ticks_of(one_two_five);
  if (decade_count == 2) return with_minor_ticks(log_ticks_of({{1, first}, {1, last}}));
  return linear_ticks(lo, hi, max_count);
}

std::string power_of_ten_text(int exponent) {
  static const char* const kDigits[] = {"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                                        "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::string text = exponent < 0 ? "10\u207b" : "10";
  for (const char digit : std::to_string(std::abs(exponent))) text += kDigits[digit - '0'];
  return text;
}

}  // namespace ashlar
