#include "study/study_store.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include <sqlite3.h>

#include "core/error.hpp"
#include "core/text.hpp"

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

class Statement {
public:
  Statement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), static_cast<int>(sql.size()), &statement_, nullptr) != SQLITE_OK)
      throw IoError(std::string("study database: ") + sqlite3_errmsg(db) + " in: " + sql);
  }
  ~Statement() { sqlite3_finalize(statement_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int index, const Value& value) {
    int rc = SQLITE_OK;
    if (const auto* b = std::get_if<bool>(&value)) rc = sqlite3_bind_int64(statement_, index, *b ? 1 : 0);
    else if (const auto* i = std::get_if<std::int64_t>(&value)) rc = sqlite3_bind_int64(statement_, index, *i);
    else if (const auto* d = std::get_if<double>(&value)) rc = sqlite3_bind_double(statement_, index, *d);
    else if (const auto* s = std::get_if<std::string>(&value))
      rc = sqlite3_bind_text(statement_, index, s->data(), static_cast<int>(s->size()), SQLITE_TRANSIENT);
    else rc = sqlite3_bind_null(statement_, index);
    if (rc != SQLITE_OK) fail();
    return *this;
  }
  // True while there is a row to read.
  bool step() {
    const int rc = sqlite3_step(statement_);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE) fail();
    return false;
  }
  void run() {
    while (step()) {
    }
  }
  Value column(int index, const std::string& kind = "") const {
    switch (sqlite3_column_type(statement_, index)) {
      case SQLITE_INTEGER: {
        const std::int64_t v = sqlite3_column_int64(statement_, index);
        if (kind == kBoolean) return v != 0;
        return v;
      }
      case SQLITE_FLOAT: return sqlite3_column_double(statement_, index);
      case SQLITE_TEXT:
      case SQLITE_BLOB: {
        const auto* text = static_cast<const char*>(sqlite3_column_blob(statement_, index));
        return std::string(text ? text : "", static_cast<std::size_t>(sqlite3_column_bytes(statement_, index)));
      }
      default: return std::monostate{};
    }
  }
  std::string text(int index) const { return to_text(column(index)); }

private:
  [[noreturn]] void fail() const { throw IoError(std::string("study database: ") + sqlite3_errmsg(db_)); }
  sqlite3* db_;
  sqlite3_stmt* statement_ = nullptr;
};

void execute(sqlite3* db, const std::string& sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string text = message ? message : sqlite3_errmsg(db);
    sqlite3_free(message);
    throw IoError("study database: " + text);
  }
}

// BEGIN IMMEDIATE ... COMMIT, rolled back when left by an exception.
class Transaction {
public:
  explicit Transaction(sqlite3* db) : db_(db) { execute(db_, "BEGIN IMMEDIATE"); }
  ~Transaction() {
    if (!committed_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void commit() {
    execute(db_, "COMMIT");
    committed_ = true;
  }

private:
  sqlite3* db_;
  bool committed_ = false;
};

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
  try {
    // WAL with synchronous=NORMAL: a commit survives the process being
    // killed (only a power cut can lose the last ones), and costs no fsync.
    if (!read_only && !path.empty()) execute(db_, "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL");
    if (!read_only)
      execute(db_,
              "CREATE TABLE IF NOT EXISTS ashlar_studies(name TEXT PRIMARY KEY, parameters TEXT NOT NULL,"
              " created TEXT NOT NULL);"
              "CREATE TABLE IF NOT EXISTS ashlar_columns(study TEXT NOT NULL, name TEXT NOT NULL,"
              " role TEXT NOT NULL, kind TEXT NOT NULL, position INTEGER NOT NULL, PRIMARY KEY(study, name))");
  } catch (const IoError& e) {
    sqlite3_close(db_);
    throw IoError("cannot use study database '" + path + "': " + e.what());
  }
}

StudyStore::~StudyStore() { sqlite3_close(db_); }

StudyStore::StudyColumns& StudyStore::columns_of(const std::string& name) {
  for (auto& columns : columns_)
    if (columns->study == name) return *columns;
  const std::string missing = "no study '" + name + "' in '" + path_ + "'";
  Statement bookkeeping(db_, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'ashlar_studies'");
  if (!bookkeeping.step()) throw InvalidArgument(missing);
  Statement study(db_, "SELECT parameters FROM ashlar_studies WHERE name = ?");
  study.bind(1, name);
  if (!study.step()) throw InvalidArgument(missing);
  auto columns = std::make_unique<StudyColumns>();
  columns->study = name;
  Statement select(db_, "SELECT name, role, kind FROM ashlar_columns WHERE study = ? ORDER BY position");
  select.bind(1, name);
  while (select.step()) {
    const std::string column = select.text(0);
    (select.text(1) == "parameter" ? columns->parameter_names : columns->field_names).push_back(column);
    columns->kind[column] = select.text(2);
  }
  columns_.push_back(std::move(columns));
  return *columns_.back();
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
  StudyColumns& columns = columns_of(name);
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
    ids.push_back(sqlite3_last_insert_rowid(db_));
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
  StudyColumns& columns = columns_of(name);
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
  StudyColumns& columns = columns_of(name);
  Transaction transaction(db_);
  const auto old_fields = columns.field_names;
  const auto old_kinds = columns.kind;
  try {
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
      statement
          .run();
    }
    transaction.commit();
  } catch (...) {
    columns.field_names = old_fields;  // the rollback also took the new columns away
    columns.kind = old_kinds;
    throw;
  }
}

}  // namespace ashlar::study
