#include "study/sqlite_statement.hpp"

#include <sqlite3.h>

#include "core/error.hpp"

namespace ashlar::study {

Statement::Statement(sqlite3* db, const std::string& sql) : db_(db) {
  if (sqlite3_prepare_v2(db, sql.c_str(), static_cast<int>(sql.size()), &statement_, nullptr) != SQLITE_OK)
    throw IoError(std::string("study database: ") + sqlite3_errmsg(db) + " in: " + sql);
}

Statement::~Statement() { sqlite3_finalize(statement_); }

Statement& Statement::bind(int index, const Value& value) {
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

bool Statement::step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  if (rc != SQLITE_DONE) fail();
  return false;
}

void Statement::run() {
  while (step()) {
  }
}

void Statement::reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

Value Statement::column(int index, const std::string& kind) const {
  switch (sqlite3_column_type(statement_, index)) {
    case SQLITE_INTEGER: {
      const std::int64_t v = sqlite3_column_int64(statement_, index);
      if (kind == "boolean") return v != 0;
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

std::string Statement::text(int index) const { return to_text(column(index)); }

void Statement::fail() const { throw IoError(std::string("study database: ") + sqlite3_errmsg(db_)); }

void execute(sqlite3* db, const std::string& sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string text = message ? message : sqlite3_errmsg(db);
    sqlite3_free(message);
    throw IoError("study database: " + text);
  }
}

int changes(sqlite3* db) { return sqlite3_changes(db); }

std::int64_t last_insert_id(sqlite3* db) { return sqlite3_last_insert_rowid(db); }

Transaction::Transaction(sqlite3* db) : db_(db) { execute(db_, "BEGIN IMMEDIATE"); }

Transaction::~Transaction() {
  if (!committed_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
}

void Transaction::commit() {
  execute(db_, "COMMIT");
  committed_ = true;
}

}  // namespace ashlar::study
