#include "study/study_table.hpp"

#include <algorithm>

namespace ashlar::study {

std::size_t StudyTable::finished_count() const {
  return static_cast<std::size_t>(std::count_if(rows.begin(), rows.end(), [](const Row& r) { return r.finished; }));
}

std::size_t StudyTable::error_count() const {
  return static_cast<std::size_t>(std::count_if(rows.begin(), rows.end(), [](const Row& r) {
    return r.finished && r.outcome.status == RunStatus::error;
  }));
}

namespace {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

const Value* field_value(const Outcome& outcome, const std::string& name) {
  for (const auto& [field, value] : outcome.fields)
    if (field == name) return &value;
  return nullptr;
}

}  // namespace

std::string csv_text(const StudyTable& table) {
  std::string csv;
  auto add_line = [&csv](const std::vector<std::string>& cells) {
    for (std::size_t i = 0; i < cells.size(); ++i) csv += (i ? "," : "") + csv_field(cells[i]);
    csv += "\r\n";
  };
  std::vector<std::string> header = table.parameter_names;
  header.insert(header.end(), table.field_names.begin(), table.field_names.end());
  for (const char* run_column : {"run_status", "run_error", "run_seconds", "run_worker"}) header.push_back(run_column);
  add_line(header);
  for (const Row& row : table.rows) {
    std::vector<std::string> cells;
    for (const Value& value : row.task.parameters) cells.push_back(to_text(value));
    for (const std::string& name : table.field_names) {
      const Value* value = row.finished ? field_value(row.outcome, name) : nullptr;
      cells.push_back(value ? to_text(*value) : "");
    }
    if (row.finished) {
      cells.push_back(status_name(row.outcome.status));
      cells.push_back(row.outcome.error);
      cells.push_back(to_text(row.outcome.seconds));
      cells.push_back(std::to_string(row.outcome.worker));
    } else {
      cells.insert(cells.end(), 4, "");
    }
    add_line(cells);
  }
  return csv;
}

}  // namespace ashlar::study
