#include "io/json_document.hpp"

namespace ashlar {
namespace {

std::string scalar_text(const json& value) {
  return value.dump(-1, ' ', false, json::error_handler_t::strict);
}

// "[x, y, z]": arrays of scalars on one line.
std::string inline_array(const json& array) {
  std::string text = "[";
  for (size_t i = 0; i < array.size(); ++i) text += (i > 0 ? ", " : "") + scalar_text(array[i]);
  return text + "]";
}

// Small records of scalars ({"x": .., "y": .., "z": ..}) on one line.
bool is_short_record(const json& value) {
  if (!value.is_object() || value.empty() || value.size() > 4) return false;
  for (const auto& item : value.items()) {
    if (item.value().is_structured()) return false;
  }
  return true;
}

// Objects one key per line but short records of scalars, arrays of scalars
// on one line, arrays of arrays one element per line: a vertex or a face
// reads as one line of the file.
void write_pretty(const json& value, int indent, std::string& out) {
  const std::string pad(static_cast<size_t>(indent) * 2, ' ');
  const std::string inner_pad = pad + "  ";
  if (is_short_record(value)) {
    out += "{";
    bool first = true;
    for (const auto& [key, item] : value.items()) {
      out += (first ? "" : ", ") + json(key).dump() + ": " + scalar_text(item);
      first = false;
    }
    out += "}";
  } else if (value.is_object() && !value.empty()) {
    out += "{\n";
    bool first = true;
    for (const auto& [key, item] : value.items()) {
      if (!first) out += ",\n";
      first = false;
      out += inner_pad + json(key).dump() + ": ";
      write_pretty(item, indent + 1, out);
    }
    out += "\n" + pad + "}";
  } else if (value.is_array() && !value.empty() &&
             (value.front().is_array() || value.front().is_object())) {
    out += "[\n";
    for (size_t i = 0; i < value.size(); ++i) {
      if (i > 0) out += ",\n";
      out += inner_pad;
      if (value[i].is_array()) {
        out += inline_array(value[i]);
      } else {
        write_pretty(value[i], indent + 1, out);
      }
    }
    out += "\n" + pad + "]";
  } else if (value.is_array()) {
    out += inline_array(value);
  } else {
    out += scalar_text(value);
  }
}

}  // namespace

json vec3_to_json(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

bool is_valid_utf8(const json& text) {
  try {
    scalar_text(text);
    return true;
  } catch (const json::type_error&) {
    return false;
  }
}

std::string pretty_json(const json& value) {
  std::string text;
  write_pretty(value, 0, text);
  return text + "\n";
}

std::optional<std::string> quote_non_numbers(const std::string& text) {
  static const std::string kTokens[] = {"-Infinity", "Infinity", "NaN"};
  std::string quoted;
  quoted.reserve(text.size());
  bool in_string = false, changed = false;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (in_string) {
      const size_t length = (c == '\\' && i + 1 < text.size()) ? 2 : 1;
      quoted.append(text, i, length);
      in_string = c != '"';
      i += length;
      continue;
    }
    in_string = c == '"';
    const std::string* token = nullptr;
    for (const std::string& candidate : kTokens) {
      if (text.compare(i, candidate.size(), candidate) == 0) token = &candidate;
      if (token) break;
    }
    if (token) {
      quoted += '"' + *token + '"';
      i += token->size();
      changed = true;
    } else {
      quoted += c;
      ++i;
    }
  }
  if (!changed) return std::nullopt;
  return quoted;
}

}  // namespace ashlar
