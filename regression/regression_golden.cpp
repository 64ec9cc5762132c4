#include "regression_golden.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"

namespace ashlar::regression {

namespace {

using nlohmann::json;

Value to_value(const json& entry, const std::string& where) {
  if (entry.is_boolean()) return entry.get<bool>();
  if (entry.is_string()) return entry.get<std::string>();
  if (entry.is_number()) {
    const double number = entry.get<double>();
    if (!std::isfinite(number)) throw std::runtime_error(where + ": not a finite double");
    return number;
  }
  if (entry.is_array()) {
    std::vector<double> numbers;
    for (const json& element : entry) {
      if (!element.is_number())
        throw std::runtime_error(where + ": expected a list of numbers, found " + std::string(element.type_name()) +
                                 " in it");
      numbers.push_back(std::get<double>(to_value(element, where)));
    }
    return numbers;
  }
  throw std::runtime_error(where + ": expected a number, boolean, string or list of numbers, found " +
                           std::string(entry.type_name()));
}

GoldenValues to_golden(const json& document) {
  if (!document.is_object())
    throw std::runtime_error(std::string("expected an object keyed by script file, found ") + document.type_name());
  GoldenValues golden;
  for (const auto& [script, checks] : document.items()) {
    if (!checks.is_object())
      throw std::runtime_error(quote(script) + ": expected an object keyed by check name, found " +
                               std::string(checks.type_name()));
    ScriptGolden& values = golden[script];
    for (const auto& [name, entry] : checks.items()) values[name] = to_value(entry, quote(script) + " / " + quote(name));
  }
  return golden;
}

void append_value(std::string& out, const Value& value) {
  if (const auto* number = std::get_if<double>(&value)) {
    out += format_number(*number);
    return;
  }
  const auto* list = std::get_if<std::vector<double>>(&value);
  if (list == nullptr) {  // booleans and strings print as JSON already
    out += format_value(value);
    return;
  }
  if (list->empty()) {
    out += "[]";
    return;
  }
  out += "[\n";
  for (size_t i = 0; i < list->size(); ++i)
    out += "      " + format_number((*list)[i]) + (i + 1 < list->size() ? ",\n" : "\n");
  out += "    ]";
}

}  // namespace

GoldenValues read_golden_file(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return {};
  const std::string text = read_file(path);  // an IoError names the path
  try {
    return to_golden(json::parse(text));
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": malformed golden file: " + e.what());
  }
}

std::string format_golden_file(const GoldenValues& values) {
  std::string out = "{";
  bool first_script = true;
  for (const auto& [script, checks] : values) {
    if (checks.empty()) continue;
    out += first_script ? "\n  " : ",\n  ";
    first_script = false;
    out += quote(script) + ": {";
    bool first_check = true;
    for (const auto& [name, value] : checks) {
      out += first_check ? "\n    " : ",\n    ";
      first_check = false;
      out += quote(name) + ": ";
      append_value(out, value);
    }
    out += "\n  }";
  }
  return out + (first_script ? "}\n" : "\n}\n");
}

}  // namespace ashlar::regression
