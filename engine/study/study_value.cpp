#include "study/study_value.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <type_traits>

#include "core/error.hpp"
#include "core/text.hpp"

namespace ashlar::study {

std::string to_text(const Value& value) {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return "";
        } else if constexpr (std::is_same_v<T, bool>) {
          return v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          return std::to_string(v);
        } else if constexpr (std::is_same_v<T, double>) {
          return shortest_number(v);
        } else {
          return v;
        }
      },
      value);
}

bool value_less(const Value& a, const Value& b) {
  auto numeric = [](const Value& v, double& out) {
    if (const auto* i = std::get_if<std::int64_t>(&v)) return out = static_cast<double>(*i), true;
    if (const auto* d = std::get_if<double>(&v)) return out = *d, true;
    return false;
  };
  double x, y;
  const bool a_numeric = numeric(a, x), b_numeric = numeric(b, y);
  if (a_numeric && b_numeric) return x < y;
  if (a_numeric != b_numeric) return a_numeric;
  return a < b;
}

bool rows_less(const std::vector<Value>& a, const std::vector<Value>& b) {
  return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), value_less);
}

const char* status_name(RunStatus status) {
  return status == RunStatus::ok ? "ok" : "error";
}

namespace {

// Little-endian fixed-width fields: the ranks of one job run on one
// architecture, but a fixed layout keeps the format independent of padding.
class ByteWriter {
public:
  void u8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void i64(std::int64_t v) {
    for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<char>((static_cast<std::uint64_t>(v) >> (8 * i)) & 0xff));
  }
  void f64(double v) {
    std::int64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    i64(bits);
  }
  void text(const std::string& s) {
    i64(static_cast<std::int64_t>(s.size()));
    bytes_ += s;
  }
  void value(const Value& v) {
    u8(static_cast<std::uint8_t>(v.index()));
    if (const auto* b = std::get_if<bool>(&v)) u8(*b ? 1 : 0);
    if (const auto* i = std::get_if<std::int64_t>(&v)) i64(*i);
    if (const auto* d = std::get_if<double>(&v)) f64(*d);
    if (const auto* s = std::get_if<std::string>(&v)) text(*s);
  }
  void task(const Task& t) {
    i64(t.id);
    i64(static_cast<std::int64_t>(t.parameters.size()));
    for (const Value& v : t.parameters) value(v);
  }
  void outcome(const Outcome& o) {
    i64(o.id);
    u8(o.status == RunStatus::ok ? 0 : 1);
    text(o.error);
    i64(static_cast<std::int64_t>(o.fields.size()));
    for (const auto& [name, v] : o.fields) {
      text(name);
      value(v);
    }
    f64(o.seconds);
    i64(o.worker);
  }
  std::string take() { return std::move(bytes_); }

private:
  std::string bytes_;
};

class ByteReader {
public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}

  std::uint8_t u8() {
    need(1);
    return static_cast<std::uint8_t>(bytes_[at_++]);
  }
  std::int64_t i64() {
    need(8);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(static_cast<std::uint8_t>(bytes_[at_ + i])) << (8 * i);
    at_ += 8;
    return static_cast<std::int64_t>(v);
  }
  double f64() {
    const std::int64_t bits = i64();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  std::string text() {
    const std::size_t size = count();
    need(size);
    std::string s = bytes_.substr(at_, size);
    at_ += size;
    return s;
  }
  // A length or count: never more than the bytes left, so a corrupt count
  // cannot make a huge allocation.
  std::size_t count() {
    const std::int64_t n = i64();
    if (n < 0 || static_cast<std::uint64_t>(n) > bytes_.size() - at_)
      throw InvalidArgument("study message: bad length " + std::to_string(n));
    return static_cast<std::size_t>(n);
  }
  Value value() {
    switch (u8()) {
      case 0: return std::monostate{};
      case 1: return u8() != 0;
      case 2: return i64();
      case 3: return f64();
      case 4: return text();
      default: throw InvalidArgument("study message: unknown value type");
    }
  }
  Task task() {
    Task t;
    t.id = i64();
    t.parameters.resize(count());
    for (Value& v : t.parameters) v = value();
    return t;
  }
  Outcome outcome() {
    Outcome o;
    o.id = i64();
    o.status = u8() == 0 ? RunStatus::ok : RunStatus::error;
    o.error = text();
    o.fields.resize(count());
    for (auto& [name, v] : o.fields) {
      name = text();
      v = value();
    }
    o.seconds = f64();
    o.worker = static_cast<int>(i64());
    return o;
  }
  void expect_end() const {
    if (at_ != bytes_.size()) throw InvalidArgument("study message: trailing bytes");
  }

private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) throw InvalidArgument("study message: truncated");
  }
  const std::string& bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::string encode(const Task& task) {
  ByteWriter writer;
  writer.task(task);
  return writer.take();
}

std::string encode(const Outcome& outcome) {
  ByteWriter writer;
  writer.outcome(outcome);
  return writer.take();
}

std::string encode_table(const std::vector<std::string>& parameter_names,
                         const std::vector<std::string>& field_names, const std::vector<Row>& rows) {
  ByteWriter writer;
  for (const auto* names : {&parameter_names, &field_names}) {
    writer.i64(static_cast<std::int64_t>(names->size()));
    for (const std::string& name : *names) writer.text(name);
  }
  writer.i64(static_cast<std::int64_t>(rows.size()));
  for (const Row& row : rows) {
    writer.task(row.task);
    writer.u8(row.finished ? 1 : 0);
    if (row.finished) writer.outcome(row.outcome);
  }
  return writer.take();
}

Task decode_task(const std::string& bytes) {
  ByteReader reader(bytes);
  Task task = reader.task();
  reader.expect_end();
  return task;
}

Outcome decode_outcome(const std::string& bytes) {
  ByteReader reader(bytes);
  Outcome outcome = reader.outcome();
  reader.expect_end();
  return outcome;
}

void decode_table(const std::string& bytes, std::vector<std::string>& parameter_names,
                  std::vector<std::string>& field_names, std::vector<Row>& rows) {
  ByteReader reader(bytes);
  for (auto* names : {&parameter_names, &field_names}) {
    names->resize(reader.count());
    for (std::string& name : *names) name = reader.text();
  }
  rows.resize(reader.count());
  for (Row& row : rows) {
    row.task = reader.task();
    row.finished = reader.u8() != 0;
    if (row.finished) row.outcome = reader.outcome();
  }
  reader.expect_end();
}

}  // namespace ashlar::study
