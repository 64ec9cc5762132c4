#include "study/study_store.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <map>
#include <set>
#include <thread>

#include <sqlite3.h>

#include "core/error.hpp"
#include "core/text.hpp"
#include "study/sqlite_statement.hpp"

namespace ashlar::study {

namespace {

// A column's kind, kept because SQLite stores booleans as integers.
constexpr const char* kBoolean = "boolean";
constexpr const char* kNumber = "number";
constexpr const char* kText = "text";
constexpr const char* kMixed = "mixed";

const char* kind_of(const Value& value) {
  if (std::holds_alternative<bool>(value)) return kBoolean;
  if (std::holds_alternative<std::string>(value)) return kText;
  if (std::holds_alternative<std::monostate>(value)) return nullptr;
  return kNumber;
}

// The kind of a column that held `kind` and now gets a value of `added`.
std::string merged_kind(const std::string& kind, const char* added) {
  if (added == nullptr || kind == added) return kind;
  return kind.empty() ? added : kMixed;
}

std::string quoted(const std::string& identifier) { return "\"" + identifier + "\""; }

}  // namespace

std::string fields_problem(const Outcome& outcome, const std::vector<std::string>& parameter_names) {
  std::set<std::string> seen;
  for (const auto& field : outcome.fields) {
    const std::string& name = field.first;
    if (std::string problem = column_name_problem(name); !problem.empty()) return problem;
    if (std::find(parameter_names.begin(), parameter_names.end(), name) != parameter_names.end())
      return "'" + name + "' is a parameter";
    if (!seen.insert(name).second) return "'" + name + "' is returned twice";
  }
  return "";
}

std::string study_name_problem(const std::string& name) {
  const bool allowed =
      !name.empty() && name.size() <= 64 &&
      std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; });
  if (!allowed) return "study name '" + name + "' must be 1 to 64 letters, digits, _ or -";
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower.rfind("ashlar_", 0) == 0 || lower.rfind("sqlite_", 0) == 0)
    return "study name '" + name + "' starts with a reserved prefix (ashlar_, sqlite_)";
  return "";
}

struct StudyStore::StudyColumns {
  std::string study;
  std::vector<std::string> parameter_names;
  std::vector<std::string> field_names;
  std::map<std::string, std::string> kind;  // every column's kind
};

StudyStore::StudyStore(const std::string& path, bool read_only) : path_(path) {
  const int flags = read_only ? SQLITE_OPEN_READONLY : (SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  const std::string target = path.empty() ? ":memory:" : path;
  if (sqlite3_open_v2(target.c_str(), &db_, flags | SQLITE_OPEN_NOMUTEX, nullptr) != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw IoError("cannot open study database '" + path + "': " + message);
  }
  sqlite3_busy_timeout(db_, 10000);
  const auto set_up = [&] {
    // WAL with synchronous=NORMAL: a commit survives the process being
    // killed (only a power cut can lose the last ones), and costs no fsync.
    if (!read_only && !path.empty()) execute(db_, "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL");
    if (!read_only)
      execute(db_,
              "CREATE TABLE IF NOT EXISTS ashlar_studies(name TEXT PRIMARY KEY, parameters TEXT NOT NULL,"
              " created TEXT NOT NULL);"
              "CREATE TABLE IF NOT EXISTS ashlar_columns(study TEXT NOT NULL, name TEXT NOT NULL,"
              " role TEXT NOT NULL, kind TEXT NOT NULL, position INTEGER NOT NULL, PRIMARY KEY(study, name));"
              "CREATE TABLE IF NOT EXISTS ashlar_runs(id INTEGER PRIMARY KEY AUTOINCREMENT, study TEXT NOT NULL,"
              " host TEXT NOT NULL, machine TEXT NOT NULL, pid INTEGER NOT NULL, process_started INTEGER NOT NULL,"
              " started TEXT NOT NULL, heartbeat REAL NOT NULL);"
              "CREATE TABLE IF NOT EXISTS ashlar_claims(study TEXT NOT NULL, row INTEGER NOT NULL,"
              " run INTEGER NOT NULL, PRIMARY KEY(study, row));"
              "CREATE INDEX IF NOT EXISTS ashlar_claims_run ON ashlar_claims(run)");
  };
  // Processes opening a new file together: switching it to WAL, or a
  // statement that read the schema and then writes, may find the file
  // locked without SQLite waiting (it would deadlock). Every step is
  // idempotent, so it is tried again, for as long as the busy timeout.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (;;) {
    try {
      set_up();
      break;
    } catch (const IoError& e) {
      const int code = sqlite3_errcode(db_) & 0xff;
      if ((code == SQLITE_BUSY || code == SQLITE_LOCKED) && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        continue;
      }
      sqlite3_close(db_);
      throw IoError("cannot use study database '" + path + "': " + e.what());
    }
  }
}

StudyStore::~StudyStore() { sqlite3_close(db_); }

// Read afresh every time: another process may have added columns since.
StudyStore::StudyColumns StudyStore::columns_of(const std::string& name) {
  const std::string missing = "no study '" + name + "' in '" + path_ + "'";
  Statement bookkeeping(db_, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'ashlar_studies'");
  if (!bookkeeping.step()) throw InvalidArgument(missing);
  Statement study(db_, "SELECT parameters FROM ashlar_studies WHERE name = ?");
  study.bind(1, name);
  if (!study.step()) throw InvalidArgument(missing);
  StudyColumns columns;
  columns.study = name;
  Statement select(db_, "SELECT name, role, kind FROM ashlar_columns WHERE study = ? ORDER BY position");
  select.bind(1, name);
  while (select.step()) {
    const std::string column = select.text(0);
    (select.text(1) == "parameter" ? columns.parameter_names : columns.field_names).push_back(column);
    columns.kind[column] = select.text(2);
  }
  return columns;
}

StudyTable StudyStore::open_study(const std::string& name, const ParameterRows& rows, bool rerun_errors) {
  if (const std::string problem = study_name_problem(name); !problem.empty()) throw InvalidArgument(problem);
  Transaction transaction(db_);
  Statement existing(db_, "SELECT parameters FROM ashlar_studies WHERE name = ?");
  existing.bind(1, name);
  if (existing.step()) {
    const std::string stored = existing.text(0);
    if (stored != join(rows.names, ","))
      throw InvalidArgument("study '" + name + "' in '" + path_ + "' has the parameters (" + stored +
                            "), this one (" + join(rows.names, ",") +
                            "): give the study another name or another db");
  } else {
    std::string create = "CREATE TABLE " + quoted(name) + "(id INTEGER PRIMARY KEY";
    for (const std::string& parameter : rows.names) create += ", " + quoted(parameter);
    create += ", run_status TEXT, run_error TEXT, run_seconds REAL, run_worker INTEGER, run_finished TEXT)";
    execute(db_, create);
    Statement insert(db_, "INSERT INTO ashlar_studies(name, parameters, created) VALUES(?, ?, strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))");
    insert.bind(1, name).bind(2, join(rows.names, ",")).run();
    for (std::size_t c = 0; c < rows.names.size(); ++c) {
      std::string kind;
      for (const auto& row : rows.rows) kind = merged_kind(kind, kind_of(row[c]));
      Statement column(db_, "INSERT INTO ashlar_columns(study, name, role, kind, position) VALUES(?, ?, 'parameter', ?, ?)");
      column.bind(1, name).bind(2, rows.names[c]).bind(3, kind).bind(4, static_cast<std::int64_t>(c)).run();
    }
  }
  StudyColumns columns = columns_of(name);
  if (rerun_errors)
    execute(db_, "UPDATE " + quoted(name) +
                     " SET run_status = NULL, run_error = NULL, run_seconds = NULL, run_worker = NULL,"
                     " run_finished = NULL WHERE run_status = 'error'");

  std::map<std::vector<Value>, std::int64_t, decltype(&rows_less)> stored_ids(&rows_less);
  {
    std::string select = "SELECT id";
    for (const std::string& parameter : rows.names) select += ", " + quoted(parameter);
    Statement stored(db_, select + " FROM " + quoted(name));
    while (stored.step()) {
      std::vector<Value> values;
      for (std::size_t c = 0; c < rows.names.size(); ++c)
        values.push_back(stored.column(static_cast<int>(c) + 1, columns.kind[rows.names[c]]));
      stored_ids.emplace(std::move(values), std::get<std::int64_t>(stored.column(0)));
    }
  }
  std::string insert_sql = "INSERT INTO " + quoted(name) + "(" ;
  std::string placeholders;
  for (std::size_t c = 0; c < rows.names.size(); ++c) {
    insert_sql += (c ? ", " : "") + quoted(rows.names[c]);
    placeholders += c ? ", ?" : "?";
  }
  insert_sql += ") VALUES(" + placeholders + ")";
  std::vector<std::int64_t> ids;
  ids.reserve(rows.rows.size());
  for (const auto& row : rows.rows) {
    if (auto found = stored_ids.find(row); found != stored_ids.end()) {
      ids.push_back(found->second);
      continue;
    }
    Statement insert(db_, insert_sql);
    for (std::size_t c = 0; c < row.size(); ++c) insert.bind(static_cast<int>(c) + 1, row[c]);
    insert.run();
    ids.push_back(last_insert_id(db_));
  }
  transaction.commit();

  StudyTable all = read_rows(name);
  std::map<std::int64_t, std::size_t> position;
  for (std::size_t r = 0; r < all.rows.size(); ++r) position[all.rows[r].task.id] = r;
  StudyTable table;
  table.parameter_names = all.parameter_names;
  table.field_names = all.field_names;
  table.rows.reserve(ids.size());
  for (const std::int64_t id : ids) table.rows.push_back(std::move(all.rows[position.at(id)]));
  return table;
}

StudyTable StudyStore::read_study(const std::string& name) {
  if (const std::string problem = study_name_problem(name); !problem.empty()) throw InvalidArgument(problem);
  return read_rows(name);
}

StudyTable StudyStore::read_rows(const std::string& name) {
  StudyColumns columns = columns_of(name);
  StudyTable table;
  table.parameter_names = columns.parameter_names;
  table.field_names = columns.field_names;
  std::string select = "SELECT id, run_status, run_error, run_seconds, run_worker";
  for (const std::string& parameter : columns.parameter_names) select += ", " + quoted(parameter);
  for (const std::string& field : columns.field_names) select += ", " + quoted(field);
  Statement statement(db_, select + " FROM " + quoted(name) + " ORDER BY id");
  const int first_parameter = 5;
  const int first_field = first_parameter + static_cast<int>(columns.parameter_names.size());
  while (statement.step()) {
    Row row;
    row.task.id = std::get<std::int64_t>(statement.column(0));
    for (std::size_t c = 0; c < columns.parameter_names.size(); ++c)
      row.task.parameters.push_back(statement.column(first_parameter + static_cast<int>(c), columns.kind[columns.parameter_names[c]]));
    const Value status = statement.column(1);
    row.finished = !std::holds_alternative<std::monostate>(status);
    if (row.finished) {
      Outcome& outcome = row.outcome;
      outcome.id = row.task.id;
      outcome.status = to_text(status) == "ok" ? RunStatus::ok : RunStatus::error;
      outcome.error = statement.text(2);
      const Value seconds = statement.column(3);
      outcome.seconds = std::holds_alternative<double>(seconds) ? std::get<double>(seconds) : 0.0;
      const Value worker = statement.column(4);
      outcome.worker = std::holds_alternative<std::int64_t>(worker) ? static_cast<int>(std::get<std::int64_t>(worker)) : 0;
      for (std::size_t f = 0; f < columns.field_names.size(); ++f)
        outcome.fields.emplace_back(columns.field_names[f],
                                    statement.column(first_field + static_cast<int>(f), columns.kind[columns.field_names[f]]));
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

void StudyStore::record(const std::string& name, const std::vector<Outcome>& outcomes) {
  if (outcomes.empty()) return;
  Transaction transaction(db_);
  // Read inside the write transaction: the columns as they are now, with
  // those other processes added, and nobody adds one until this commits.
  StudyColumns columns = columns_of(name);
  Statement release(db_, "DELETE FROM ashlar_claims WHERE study = ? AND row = ?");
  for (const Outcome& outcome : outcomes) {
    if (const std::string problem = fields_problem(outcome, columns.parameter_names); !problem.empty())
      throw InvalidArgument("returned field " + problem);
    std::string update = "UPDATE " + quoted(name) + " SET ";
    for (const auto& [field, value] : outcome.fields) {
      const bool known = columns.kind.count(field) != 0;
      const std::string kind = merged_kind(known ? columns.kind[field] : "", kind_of(value));
      if (!known) {
        execute(db_, "ALTER TABLE " + quoted(name) + " ADD COLUMN " + quoted(field));
        Statement column(db_, "INSERT INTO ashlar_columns(study, name, role, kind, position) VALUES(?, ?, 'field', ?, ?)");
        column.bind(1, name).bind(2, field).bind(3, kind)
            .bind(4, static_cast<std::int64_t>(columns.parameter_names.size() + columns.field_names.size()))
            .run();
        columns.field_names.push_back(field);
      } else if (kind != columns.kind[field]) {
        Statement column(db_, "UPDATE ashlar_columns SET kind = ? WHERE study = ? AND name = ?");
        column.bind(1, kind).bind(2, name).bind(3, field).run();
      }
      columns.kind[field] = kind;
      update += quoted(field) + " = ?, ";
    }
    update += "run_status = ?, run_error = ?, run_seconds = ?, run_worker = ?,"
              " run_finished = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = ? AND run_status IS NULL";
    Statement statement(db_, update);
    int index = 1;
    for (const auto& field : outcome.fields) statement.bind(index++, field.second);
    statement.bind(index, std::string(status_name(outcome.status)));
    statement.bind(index + 1, outcome.error.empty() ? Value{} : Value{outcome.error});
    statement.bind(index + 2, outcome.seconds);
    statement.bind(index + 3, static_cast<std::int64_t>(outcome.worker));
    statement.bind(index + 4, outcome.id);
    statement.run();
    release.reset();
    release.bind(1, name).bind(2, outcome.id).run();
  }
  transaction.commit();
}

}  // namespace ashlar::study
