// JSON documents with nlohmann_json, shared by the structure format
// (structure_json.cpp) and COMPAS assembly files (compas_assembly.cpp):
// pretty printing that keeps a vertex or a face on one line, and strict
// reading that names the entry at fault.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "core/error.hpp"
#include "core/types.hpp"

namespace ashlar {

// ordered_json keeps fields in the order written, so files read top-down.
using json = nlohmann::ordered_json;

json vec3_to_json(const Vec3& v);
// Whether a JSON string holds valid UTF-8 (nlohmann's strict dump refuses
// anything else).
bool is_valid_utf8(const json& text);
// Objects one key per line but records of up to 4 scalars (one line),
// arrays of scalars on one line, arrays of arrays one element per line;
// ends with a newline.
std::string pretty_json(const json& value);

// Reads a document, throwing IoError "<source>: <where>: <problem>".
class JsonReader {
public:
  explicit JsonReader(std::string source_name) : source_(std::move(source_name)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    throw IoError(source_ + ": " + (where.empty() ? "" : where + ": ") + problem);
  }

  const json& member(const json& object, const char* key, const std::string& where) const {
    const auto found = object.find(key);
    if (found == object.end()) fail(where, std::string("missing field '") + key + "'");
    return *found;
  }

  void expect_object(const json& value, const std::string& where) const {
    if (!value.is_object()) fail(where, "expected an object, got " + describe(value));
  }

  void expect_array(const json& value, const std::string& where) const {
    if (!value.is_array()) fail(where, "expected an array, got " + describe(value));
  }

  void reject_unknown_keys(const json& object, const std::set<std::string>& allowed,
                           const std::string& where) const {
    for (const auto& item : object.items()) {
      if (allowed.count(item.key()) == 0) {
        std::string names;
        for (const auto& name : allowed) names += (names.empty() ? "" : ", ") + name;
        fail(where, "unknown field '" + item.key() + "' (allowed: " + names + ")");
      }
    }
  }

  // Numbers are finite here: the parser rejects NaN, Infinity and overflow.
  double number(const json& value, const std::string& where) const {
    if (!value.is_number()) fail(where, "expected a finite number, got " + describe(value));
    return value.get<double>();
  }

  Vec3 vec3(const json& value, const std::string& where) const {
    if (!value.is_array() || value.size() != 3 || !value[0].is_number() ||
        !value[1].is_number() || !value[2].is_number()) {
      fail(where, "expected 3 finite numbers, got " + describe(value));
    }
    return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
  }

  // A 0-based index below `count`; `what` names what it indexes.
  int index(const json& value, size_t count, const std::string& what,
            const std::string& where) const {
    if (!value.is_number_integer()) {
      fail(where, "expected an integer index, got " + describe(value));
    }
    const bool negative = !value.is_number_unsigned() && value.get<std::int64_t>() < 0;
    if (negative || value.get<std::uint64_t>() >= count) {
      fail(where, "index " + value.dump() + " is out of range (" + std::to_string(count) + " " +
                      what + ", 0-based)");
    }
    return static_cast<int>(value.get<std::uint64_t>());
  }

  const std::string& source() const { return source_; }

private:
  static std::string describe(const json& value) {
    std::string text = value.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return std::string(value.type_name()) + " " + text;
  }

  std::string source_;
};

// JSON has no NaN or Infinity, but some writers (Python's json module)
// emit them bare. The text with them quoted, or nothing when it has none.
std::optional<std::string> quote_non_numbers(const std::string& text);

// Parses `text` and returns read(document). Syntax errors and numbers beyond
// the double range throw IoError through `reader`; a bare NaN or Infinity is
// reported by `read` at the entry that holds it (a number was expected
// there), should it refuse it; else the syntax error stands.
template <class Read>
auto read_json_document(const std::string& text, const JsonReader& reader, Read&& read) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {
    // Drop nlohmann's "[json.exception.parse_error.101] " prefix.
    std::string message = e.what();
    if (const auto end = message.find("] "); end != std::string::npos) message = message.substr(end + 2);
    if (const std::optional<std::string> quoted = quote_non_numbers(text)) {
      const json tolerant = json::parse(*quoted, nullptr, false);
      if (!tolerant.is_discarded()) read(tolerant);
    }
    reader.fail("", "not valid JSON: " + message);
  }
  return read(root);
}

}  // namespace ashlar
