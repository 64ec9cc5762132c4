// StudyStore's claims: which process computes which row, so that several
// processes on one database share a study's rows and none computes a row
// another one holds. See study_store.hpp for the tables and the rule.
#include <chrono>
#include <map>

#include "study/process_identity.hpp"
#include "study/sqlite_statement.hpp"
#include "study/study_store.hpp"

namespace ashlar::study {

namespace {

// Heartbeats are wall-clock seconds (Unix time), so that every process
// (and the sqlite3 shell: unixepoch()) reads them alike.
double now_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

std::string quoted(const std::string& identifier) { return "\"" + identifier + "\""; }

// Runs to forget: those whose heartbeat is older than the lease or whose
// process has ended. Their claims are free either way; forgetting them
// keeps ashlar_runs to the runs that may still be going.
void forget_stale_runs(sqlite3* db, double lease, std::int64_t keep) {
  std::vector<std::int64_t> stale;
  {
    Statement runs(db, "SELECT id, heartbeat, host, machine, pid, process_started FROM ashlar_runs WHERE id != ?");
    runs.bind(1, keep);
    const double now = now_seconds();
    while (runs.step()) {
      const Value heartbeat = runs.column(1);
      ProcessIdentity process{runs.text(2), runs.text(3), std::get<std::int64_t>(runs.column(4)),
                              std::get<std::int64_t>(runs.column(5))};
      const double beat = std::holds_alternative<double>(heartbeat) ? std::get<double>(heartbeat) : 0.0;
      if (beat < now - lease || has_ended(process)) stale.push_back(std::get<std::int64_t>(runs.column(0)));
    }
  }
  Statement claims(db, "DELETE FROM ashlar_claims WHERE run = ?");
  Statement run(db, "DELETE FROM ashlar_runs WHERE id = ?");
  for (const std::int64_t id : stale) {
    claims.reset();
    claims.bind(1, id).run();
    run.reset();
    run.bind(1, id).run();
  }
}

void insert_run(sqlite3* db, const std::string& name, std::int64_t id) {
  const ProcessIdentity& self = this_process();
  Statement insert(db,
                   "INSERT INTO ashlar_runs(id, study, host, machine, pid, process_started, started, heartbeat)"
                   " VALUES(?, ?, ?, ?, ?, ?, strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), ?)");
  insert.bind(1, id == 0 ? Value{} : Value{id}).bind(2, name).bind(3, self.host).bind(4, self.machine);
  insert.bind(5, self.pid).bind(6, self.started).bind(7, now_seconds()).run();
}

// Refreshes the heartbeat of `run` (inside a transaction); false when the
// run had lost its lease.
bool refresh_run(sqlite3* db, const std::string& name, std::int64_t run, double lease) {
  const double now = now_seconds();
  bool kept = false, registered = false;
  {
    Statement select(db, "SELECT heartbeat FROM ashlar_runs WHERE id = ?");
    select.bind(1, run);
    if (select.step()) {
      registered = true;
      const Value beat = select.column(0);
      kept = std::holds_alternative<double>(beat) && std::get<double>(beat) >= now - lease;
    }
  }
  if (registered) {
    Statement update(db, "UPDATE ashlar_runs SET heartbeat = ? WHERE id = ?");
    update.bind(1, now).bind(2, run).run();
  } else {
    // Forgotten as stale by another process: back under the same id
    // (AUTOINCREMENT never hands it to another run); its claims are gone.
    insert_run(db, name, run);
  }
  return kept;
}

}  // namespace

std::int64_t StudyStore::begin_run(const std::string& name, double lease) {
  Transaction transaction(db_);
  forget_stale_runs(db_, lease, 0);
  insert_run(db_, name, 0);
  const std::int64_t run = last_insert_id(db_);
  transaction.commit();
  return run;
}

bool StudyStore::heartbeat(const std::string& name, std::int64_t run, double lease) {
  Transaction transaction(db_);
  const bool kept = refresh_run(db_, name, run, lease);
  transaction.commit();
  return kept;
}

StudyStore::ClaimResult StudyStore::claim(const std::string& name, std::int64_t run,
                                          const std::vector<std::int64_t>& candidates, std::size_t count,
                                          double lease) {
  ClaimResult result;
  Transaction transaction(db_);
  result.lease_kept = refresh_run(db_, name, run, lease);
  const double now = now_seconds();
  Statement row(db_, "SELECT s.run_status IS NOT NULL, c.run, r.heartbeat, r.host, r.machine, r.pid,"
                     " r.process_started FROM " + quoted(name) +
                     " s LEFT JOIN ashlar_claims c ON c.study = ? AND c.row = s.id"
                     " LEFT JOIN ashlar_runs r ON r.id = c.run WHERE s.id = ?");
  Statement take(db_, "INSERT OR REPLACE INTO ashlar_claims(study, row, run) VALUES(?, ?, ?)");
  std::map<std::int64_t, bool> live;  // by run: does its claim hold?
  for (const std::int64_t id : candidates) {
    if (result.claimed.size() >= count) break;
    ++result.examined;
    row.reset();
    row.bind(1, name).bind(2, id);
    if (!row.step()) {  // not in the table (cannot happen through open_study): nothing to run
      result.finished.push_back(id);
      continue;
    }
    if (std::get<std::int64_t>(row.column(0)) != 0) {
      result.finished.push_back(id);
      continue;
    }
    const Value holder = row.column(1);
    bool held = false;
    if (const auto* other = std::get_if<std::int64_t>(&holder); other && *other != run) {
      auto known = live.find(*other);
      if (known == live.end()) {
        const Value beat = row.column(2);
        bool alive = std::holds_alternative<double>(beat) && std::get<double>(beat) >= now - lease;
        if (alive) {
          const ProcessIdentity process{row.text(3), row.text(4), std::get<std::int64_t>(row.column(5)),
                                        std::get<std::int64_t>(row.column(6))};
          alive = !has_ended(process);
        }
        known = live.emplace(*other, alive).first;
      }
      held = known->second;
    }
    if (held) {
      result.elsewhere.push_back(id);
      continue;
    }
    take.reset();
    take.bind(1, name).bind(2, id).bind(3, run).run();
    result.claimed.push_back(id);
  }
  transaction.commit();
  return result;
}

void StudyStore::end_run(std::int64_t run) {
  Transaction transaction(db_);
  Statement claims(db_, "DELETE FROM ashlar_claims WHERE run = ?");
  claims.bind(1, run).run();
  Statement remove(db_, "DELETE FROM ashlar_runs WHERE id = ?");
  remove.bind(1, run).run();
  transaction.commit();
}

}  // namespace ashlar::study
