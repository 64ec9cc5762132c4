// A study's results as a table: parameter columns, returned-field columns
// and the rows in parameter order. What the store gives back and what CSV
// export, charts and the Lua bindings read.
#pragma once

#include <string>
#include <vector>

#include "study/study_value.hpp"

namespace ashlar::study {

struct StudyTable {
  std::vector<std::string> parameter_names;
  std::vector<std::string> field_names;  // returned fields, in the order first seen
  std::vector<Row> rows;                 // finished rows have every field, nil where absent

  std::size_t finished_count() const;
  std::size_t error_count() const;
};

// CSV (RFC 4180): a header of parameter names, field names and run_status,
// run_error, run_seconds, run_worker; one line per row; numbers with 17
// significant digits, booleans true/false, nil and unfinished runs empty.
std::string csv_text(const StudyTable& table);

}  // namespace ashlar::study
