// The few SQLite calls the study store makes, wrapped so that errors become
// IoError ("study database: ...") and nothing leaks when one is thrown.
// Only the store's .cpp files include this; SQLite's header stays in
// sqlite_statement.cpp.
#pragma once

#include <string>

#include "study/study_value.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace ashlar::study {

// One prepared statement: bind, step, read columns.
class Statement {
public:
  Statement(sqlite3* db, const std::string& sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int index, const Value& value);  // 1-based
  // True while there is a row to read.
  bool step();
  void run();
  // Makes the statement ready to bind and run again.
  void reset();
  // Column `index` (0-based); integers of a column of kind "boolean" come
  // back as booleans.
  Value column(int index, const std::string& kind = "") const;
  std::string text(int index) const;

private:
  [[noreturn]] void fail() const;
  sqlite3* db_;
  sqlite3_stmt* statement_ = nullptr;
};

// Runs SQL without results; throws IoError.
void execute(sqlite3* db, const std::string& sql);

// The changes of the last statement run on `db`.
int changes(sqlite3* db);
std::int64_t last_insert_id(sqlite3* db);

// BEGIN IMMEDIATE ... COMMIT, rolled back when left by an exception. The
// write lock is taken at BEGIN, so what the transaction reads cannot change
// until it commits: decisions made inside hold under races with other
// processes.
class Transaction {
public:
  explicit Transaction(sqlite3* db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

private:
  sqlite3* db_;
  bool committed_ = false;
};

}  // namespace ashlar::study
