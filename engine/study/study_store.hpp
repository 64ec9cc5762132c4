// Where a study's runs are kept: a SQLite database with one table per study
// (a column per parameter and per returned field, plus id, run_status,
// run_error, run_seconds, run_worker, run_finished) and two bookkeeping
// tables, ashlar_studies and ashlar_columns, that remember each study's
// parameters and which columns hold booleans.
//
// Every change is one transaction in WAL mode, so a process killed at any
// instant (kill -9 included) leaves every recorded run and no partial one;
// a finished row is recorded once: recording skips rows already finished.
//
// Several processes may use one database at once. Every decision about the
// schema (a study's table, a new field column) is taken inside the write
// transaction that acts on it, from what the database holds then, never
// from what this connection saw earlier. Rows are shared out by claims
// (study_store_claims.cpp): two more tables, ashlar_runs (one row per
// process running a study: host, pid, started, heartbeat) and ashlar_claims
// (study, row, run), say which process is computing which row. A claim
// counts while its run's heartbeat is younger than the lease; a claim of a
// run whose heartbeat is older, or whose process is known to have ended,
// is free to take.
#pragma once

#include <cstdint>

#include <string>
#include <vector>

#include "study/parameter_rows.hpp"
#include "study/study_table.hpp"

struct sqlite3;

namespace ashlar::study {

class StudyStore {
public:
  // Opens (creating if missing) the database at `path`; an empty path is a
  // private in-memory database. read_only opens an existing file without
  // creating or changing anything. Throws IoError naming the path.
  explicit StudyStore(const std::string& path, bool read_only = false);
  ~StudyStore();
  StudyStore(const StudyStore&) = delete;
  StudyStore& operator=(const StudyStore&) = delete;

  // Opens study `name` ([A-Za-z0-9_-], at most 64 characters) for the given
  // rows: creates its table when new, adds the rows it does not hold yet
  // (rows match by parameter values) and returns the table of these rows, in
  // their order, with what earlier runs recorded. rerun_errors forgets the
  // outcome of rows that ended in error so they run again. Throws
  // InvalidArgument when the stored study has other parameter names.
  StudyTable open_study(const std::string& name, const ParameterRows& rows, bool rerun_errors = false);

  // Every row of a study as stored (for reading results without running).
  // Throws InvalidArgument when there is no such study.
  StudyTable read_study(const std::string& name);

  // Records finished runs of study `name` in one transaction: returned
  // fields not seen before become columns. Rows already finished are left
  // as they are; the claims of the recorded rows are released. Throws
  // InvalidArgument for fields that fields_problem rejects.
  void record(const std::string& name, const std::vector<Outcome>& outcomes);

  // Claims (study_store_claims.cpp). `lease` is in seconds.

  // Registers this process as a run of study `name` and returns the run's
  // id. Forgets runs whose lease ran out or whose process has ended, with
  // their claims.
  std::int64_t begin_run(const std::string& name, double lease);
  // Refreshes the run's heartbeat. False when the run had lost its lease
  // (its last heartbeat older than `lease`, or forgotten as stale by another
  // process): its claims may have been taken, so rows it holds but has not
  // started must be claimed again. The run is registered again either way.
  bool heartbeat(const std::string& name, std::int64_t run, double lease);
  // Claims for `run`, in one transaction, up to `count` of the rows
  // `candidates` (ids, looked at in order) that are unfinished and not
  // claimed by another live run; refreshes the run's heartbeat as
  // heartbeat() does.
  struct ClaimResult {
    bool lease_kept = true;               // as heartbeat() returns
    std::vector<std::int64_t> claimed;    // now the run's
    std::vector<std::int64_t> finished;   // recorded already
    std::vector<std::int64_t> elsewhere;  // claimed by other live runs
    std::size_t examined = 0;             // candidates looked at: the first ones
  };
  ClaimResult claim(const std::string& name, std::int64_t run, const std::vector<std::int64_t>& candidates,
                    std::size_t count, double lease);
  // Releases every claim of `run` and removes it.
  void end_run(std::int64_t run);

  const std::string& path() const { return path_; }

private:
  struct StudyColumns;
  StudyColumns columns_of(const std::string& name);
  StudyTable read_rows(const std::string& name);

  std::string path_;
  sqlite3* db_ = nullptr;
};

// Empty when the outcome's fields may be columns of a study with these
// parameters (column_name_problem, not a parameter's name, each name once),
// otherwise what is wrong, starting with the field's quoted name.
std::string fields_problem(const Outcome& outcome, const std::vector<std::string>& parameter_names);

// Empty when `name` may name a study, otherwise why not.
std::string study_name_problem(const std::string& name);

}  // namespace ashlar::study
