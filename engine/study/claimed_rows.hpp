// A study's coordinator's share of the rows when other processes may run
// the same study on the same database: the rows it still has to see, taken
// a few at a time by claims in the store (StudyStore::claim), the run's
// heartbeat, and the rows other processes hold.
//
// Rows held by another live run are put aside and looked at again only
// when nothing else is left, at most every `retry` seconds: this process
// then waits for them to be recorded (or for their run to go stale, and
// takes them). So every process ends with every row of its table finished.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "study/study_store.hpp"

namespace ashlar::study {

struct ClaimTimes {
  double lease = 60.0;     // a run whose heartbeat is older than this (s) has lost its claims
  double heartbeat = 5.0;  // seconds between heartbeats
  double retry = 0.5;      // seconds between looks at rows other runs hold
  double batch = 0.2;      // seconds of work per worker claimed at a time (at most 256 rows, at least 1)
};

class ClaimedRows {
public:
  // Registers a run of study `name` in `store` for these unfinished rows.
  ClaimedRows(StudyStore& store, std::string name, std::vector<Task> unfinished, ClaimTimes times);
  // Releases the claims (end_run); an error doing so is ignored: the claims
  // then lapse with the lease.
  ~ClaimedRows();
  ClaimedRows(const ClaimedRows&) = delete;
  ClaimedRows& operator=(const ClaimedRows&) = delete;

  // Claims up to `count` rows and returns them. Empty when none is free now.
  std::vector<Task> take(std::size_t count);
  // Refreshes the heartbeat when it is due. False when the run lost its
  // lease since the last call: rows taken and not started must be given
  // back (their claims may have gone to another process).
  bool beat();
  // Rows taken and not started, to be claimed again (first).
  void give_back(std::vector<Task> tasks);

  // Every row was taken by this run or found finished.
  bool done() const { return candidates_.empty() && elsewhere_.empty(); }
  // Rows other processes finished, seen so far.
  std::size_t finished_elsewhere() const { return finished_elsewhere_; }
  // Rows other live runs held when last looked at.
  std::size_t held_elsewhere() const { return elsewhere_.size(); }
  // Seconds to wait before rows held elsewhere are looked at again.
  double retry_in() const;

  std::int64_t run() const { return run_; }
  const ClaimTimes& times() const { return times_; }
  // Releases the claims now.
  void end();

private:
  StudyStore& store_;
  std::string name_;
  ClaimTimes times_;
  std::int64_t run_ = 0;
  bool ended_ = false;
  bool lease_lost_ = false;
  std::deque<Task> candidates_;  // not looked at yet, or given back
  std::deque<Task> elsewhere_;   // held by other runs when last looked at
  std::size_t finished_elsewhere_ = 0;
  double last_beat_ = 0.0;
  double next_retry_ = 0.0;
};

// Refreshes a run's heartbeat from a thread of its own (with its own
// connection to the database) while the calling thread is busy running a
// row: a timed wait between beats, no work otherwise. Nothing happens for
// an in-memory store, which no other process can see.
class HeartbeatThread {
public:
  HeartbeatThread(const std::string& db, const std::string& name, std::int64_t run, ClaimTimes times);
  ~HeartbeatThread();
  HeartbeatThread(const HeartbeatThread&) = delete;
  HeartbeatThread& operator=(const HeartbeatThread&) = delete;

private:
  std::mutex mutex_;
  std::condition_variable stop_changed_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace ashlar::study
