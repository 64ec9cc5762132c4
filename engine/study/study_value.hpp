// The values a parametric study passes around: parameter values going into a
// run and the fields coming out, plus the record of one run. Shared by the
// parameter generators, the SQLite store, the local runner and the MPI
// transport (which sends them as bytes).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace ashlar::study {

// nil, boolean, integer, number or string: what a run may take and return.
using Value = std::variant<std::monostate, bool, std::int64_t, double, std::string>;

// Readable form for messages and CSV: numbers with 17 significant digits
// (round-trip exact), booleans as true/false, nil as the empty string.
std::string to_text(const Value& value);

// Strict weak order in which an integer and a number with its value are
// equal (16 and 16.0: rows match this way when a study resumes): numbers by
// value, then the other kinds.
bool value_less(const Value& a, const Value& b);
// The same order over rows, value by value.
bool rows_less(const std::vector<Value>& a, const std::vector<Value>& b);

// One row to run: its id in the study's table and its parameter values, in
// the order of the study's parameter names.
struct Task {
  std::int64_t id = 0;
  std::vector<Value> parameters;
};

enum class RunStatus { ok, error };
const char* status_name(RunStatus status);  // "ok", "error"

// What one run gave back.
struct Outcome {
  std::int64_t id = 0;
  RunStatus status = RunStatus::ok;
  std::string error;  // the error message when status is error
  std::vector<std::pair<std::string, Value>> fields;  // returned fields, by name
  double seconds = 0.0;  // wall time of the run
  int worker = 0;        // 1-based worker number; under MPI, rank * 1000 + thread
};

// A row of a study's results: its parameters and, once run, its outcome.
struct Row {
  Task task;
  bool finished = false;
  Outcome outcome;  // meaningful when finished
};

// Bytes for messages between processes, and back. decode_* throw
// InvalidArgument on truncated or malformed input.
std::string encode(const Task& task);
std::string encode(const Outcome& outcome);
std::string encode_table(const std::vector<std::string>& parameter_names,
                         const std::vector<std::string>& field_names, const std::vector<Row>& rows);
Task decode_task(const std::string& bytes);
Outcome decode_outcome(const std::string& bytes);
void decode_table(const std::string& bytes, std::vector<std::string>& parameter_names,
                  std::vector<std::string>& field_names, std::vector<Row>& rows);

}  // namespace ashlar::study
