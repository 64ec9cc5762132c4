// Several processes on one study database: schema set-up under races,
// claims and their lease, and two runners sharing a study's rows. Two
// StudyStore connections on one file stand for two processes (both alive
// here, so only the heartbeat and the lease decide).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <set>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "core/error.hpp"
#include "study/claimed_rows.hpp"
#include "study/parameter_rows.hpp"
#include "study/process_identity.hpp"
#include "study/study_runner.hpp"
#include "study/study_store.hpp"
#include "test_support.hpp"

using namespace ashlar;
using namespace ashlar::study;

namespace {

ParameterRows numbers(int count) {
  std::vector<Value> i;
  for (int k = 1; k <= count; ++k) i.push_back(std::int64_t{k});
  return grid({{"i", i}});
}

std::vector<std::int64_t> ids_of(const StudyTable& table) {
  std::vector<std::int64_t> ids;
  for (const Row& row : table.rows)
    if (!row.finished) ids.push_back(row.task.id);
  return ids;
}

Outcome squared(const Task& task) {
  Outcome outcome;
  outcome.id = task.id;
  const auto i = std::get<std::int64_t>(task.parameters[0]);
  outcome.fields = {{"square", i * i}};
  return outcome;
}

}  // namespace

TEST(StudyClaims, TwoConnectionsClaimDisjointRowsAndReleaseThem) {
  const TempDir folder;
  const std::string db = folder.file("disjoint.sqlite");
  StudyStore a(db), b(db);
  const StudyTable table = a.open_study("s", numbers(10));
  ASSERT_EQ(b.open_study("s", numbers(10)).rows.size(), 10u);  // the same rows, not added twice
  const std::vector<std::int64_t> ids = ids_of(table);
  const std::int64_t run_a = a.begin_run("s", 60), run_b = b.begin_run("s", 60);
  EXPECT_NE(run_a, run_b);

  const auto first = a.claim("s", run_a, ids, 3, 60);
  EXPECT_EQ(first.claimed, (std::vector<std::int64_t>{ids[0], ids[1], ids[2]}));
  EXPECT_EQ(first.examined, 3u);
  EXPECT_TRUE(first.lease_kept);
  const auto second = b.claim("s", run_b, ids, 3, 60);
  EXPECT_EQ(second.elsewhere, (std::vector<std::int64_t>{ids[0], ids[1], ids[2]}));
  EXPECT_EQ(second.claimed, (std::vector<std::int64_t>{ids[3], ids[4], ids[5]}));
  EXPECT_EQ(second.examined, 6u);

  // A records a row: it is finished for B, and its claim is gone.
  a.record("s", {squared(table.rows[0].task)});
  const auto third = b.claim("s", run_b, {ids[0], ids[1]}, 5, 60);
  EXPECT_EQ(third.finished, (std::vector<std::int64_t>{ids[0]}));
  EXPECT_EQ(third.elsewhere, (std::vector<std::int64_t>{ids[1]}));
  EXPECT_TRUE(third.claimed.empty());

  // A ends: its other claims are free at once.
  a.end_run(run_a);
  const auto fourth = b.claim("s", run_b, ids, 10, 60);
  EXPECT_EQ(fourth.claimed, (std::vector<std::int64_t>{ids[1], ids[2], ids[3], ids[4], ids[5], ids[6], ids[7], ids[8],
                                                        ids[9]}));
  EXPECT_EQ(fourth.finished.size(), 1u);
}

TEST(StudyClaims, AClaimOfARunWhoseHeartbeatIsOlderThanTheLeaseIsTaken) {
  const TempDir folder;
  const std::string db = folder.file("lease.sqlite");
  StudyStore a(db), b(db);
  const std::vector<std::int64_t> ids = ids_of(a.open_study("s", numbers(4)));
  const double lease = 0.3;
  const std::int64_t run_a = a.begin_run("s", lease), run_b = b.begin_run("s", lease);
  ASSERT_EQ(a.claim("s", run_a, ids, 2, lease).claimed.size(), 2u);
  EXPECT_EQ(b.claim("s", run_b, ids, 4, lease).elsewhere.size(), 2u);  // A's heartbeat is fresh
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  // B's heartbeat is as old as A's: B's claim says it lost its lease too,
  // and B takes every row, A's included.
  const auto taken = b.claim("s", run_b, ids, 4, lease);
  EXPECT_FALSE(taken.lease_kept);
  EXPECT_EQ(taken.claimed, ids);
  // A comes back: told it lost the lease, it finds its rows held by B.
  EXPECT_FALSE(a.heartbeat("s", run_a, lease));
  EXPECT_EQ(a.claim("s", run_a, ids, 4, lease).elsewhere, ids);
  EXPECT_TRUE(a.heartbeat("s", run_a, lease));

  // A run forgotten as stale (begin_run of a third connection) registers
  // again on its next heartbeat, under its own id.
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  StudyStore c(db);
  const std::int64_t run_c = c.begin_run("s", lease);
  EXPECT_GT(run_c, run_b);
  EXPECT_EQ(c.claim("s", run_c, ids, 4, lease).claimed, ids);  // B's claims went with B's run
  EXPECT_FALSE(b.heartbeat("s", run_b, lease));
  EXPECT_EQ(b.claim("s", run_b, ids, 4, lease).elsewhere, ids);
}

TEST(StudyClaims, AFieldColumnAnotherConnectionAddedIsNotAddedTwice) {
  const TempDir folder;
  const std::string db = folder.file("columns.sqlite");
  StudyStore a(db), b(db);
  const StudyTable table = a.open_study("s", numbers(3));
  b.open_study("s", numbers(3));  // B has read the columns: none yet
  a.record("s", {squared(table.rows[0].task)});
  // Before: "study database: duplicate column name: square".
  EXPECT_NO_THROW(b.record("s", {squared(table.rows[1].task)}));
  Outcome other = squared(table.rows[2].task);
  other.fields.emplace_back("flag", true);
  EXPECT_NO_THROW(b.record("s", {other}));
  const StudyTable read = a.read_study("s");  // A sees B's column too
  EXPECT_EQ(read.field_names, (std::vector<std::string>{"square", "flag"}));
  EXPECT_EQ(read.finished_count(), 3u);
  EXPECT_TRUE(std::get<bool>(read.rows[2].outcome.fields[1].second));
}

TEST(StudyClaims, OpeningANewStudyFromManyConnectionsAtOnceMakesOneTable) {
  const TempDir folder;
  const std::string db = folder.file("open.sqlite");
  std::vector<std::thread> threads;
  std::atomic<int> failures{0};
  for (int t = 0; t < 6; ++t)
    threads.emplace_back([&] {
      try {
        StudyStore store(db);
        if (store.open_study("s", numbers(50)).rows.size() != 50u) ++failures;
      } catch (const std::exception& e) {
        ADD_FAILURE() << e.what();
        ++failures;
      }
    });
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(failures.load(), 0);
  StudyStore store(db);
  EXPECT_EQ(store.read_study("s").rows.size(), 50u);
}

namespace {

// Squares slowly, counting each row's runs (shared by every runner).
class SlowWorker : public RowWorker {
public:
  explicit SlowWorker(std::vector<std::atomic<int>>& runs) : runs_(runs) {}
  Outcome run(const Task& task) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
    ++runs_[static_cast<std::size_t>(task.id)];
    return squared(task);
  }

private:
  std::vector<std::atomic<int>>& runs_;
};

}  // namespace

TEST(StudyClaims, TwoRunnersOnOneDatabaseRunEveryRowOnce) {
  const TempDir folder;
  const std::string db = folder.file("runners.sqlite");
  const int count = 200;
  std::vector<std::atomic<int>> runs(count + 1);
  StudyRunInfo infos[2];
  std::size_t unfinished[2] = {0, 0};  // at each runner's start: the other may have recorded rows by then
  std::vector<std::thread> coordinators;
  for (int c = 0; c < 2; ++c)
    coordinators.emplace_back([&, c] {
      StudyStore store(db);
      const StudyTable table = store.open_study("s", numbers(count));
      unfinished[c] = table.rows.size() - table.finished_count();
      StudySettings settings;
      settings.threads = c == 0 ? 2 : 0;  // one with worker threads, one on its calling thread
      settings.progress = false;
      SlowWorker calling(runs);
      infos[c] = run_study(store, "s", table, settings, &calling,
                           [&](int) { return std::make_unique<SlowWorker>(runs); });
    });
  for (auto& thread : coordinators) thread.join();
  for (int id = 1; id <= count; ++id) EXPECT_EQ(runs[static_cast<std::size_t>(id)].load(), 1) << "row " << id;
  // How the rows split depends on when each runner got going (under the
  // sanitizers one may start after the other is done): not asserted.
  EXPECT_EQ(infos[0].ran + infos[1].ran, static_cast<std::size_t>(count));
  EXPECT_EQ(infos[0].ran + infos[0].elsewhere, unfinished[0]);  // each waited for the other's rows
  EXPECT_EQ(infos[1].ran + infos[1].elsewhere, unfinished[1]);
  StudyStore store(db);
  EXPECT_EQ(store.read_study("s").finished_count(), static_cast<std::size_t>(count));
}

TEST(StudyClaims, ClaimedRowsWaitForRowsHeldElsewhereAndTakeThemWhenStale) {
  const TempDir folder;
  const std::string db = folder.file("wait.sqlite");
  StudyStore a(db), b(db);
  const StudyTable table = a.open_study("s", numbers(3));
  ClaimTimes times;
  times.lease = 0.3;
  times.retry = 0.05;
  const std::int64_t run_a = a.begin_run("s", times.lease);
  ASSERT_EQ(a.claim("s", run_a, ids_of(table), 1, times.lease).claimed.size(), 1u);  // then A goes silent
  std::vector<Task> tasks;
  for (const Row& row : table.rows) tasks.push_back(row.task);
  ClaimedRows rows(b, "s", tasks, times);
  EXPECT_EQ(rows.take(5).size(), 2u);
  EXPECT_EQ(rows.held_elsewhere(), 1u);
  EXPECT_FALSE(rows.done());
  EXPECT_TRUE(rows.take(5).empty());  // not looked at again before retry
  const auto start = std::chrono::steady_clock::now();
  std::vector<Task> late;
  while (late.empty() && std::chrono::steady_clock::now() - start < std::chrono::seconds(5)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    late = rows.take(5);
  }
  ASSERT_EQ(late.size(), 1u);
  EXPECT_EQ(late[0].id, table.rows[0].task.id);
  EXPECT_GE(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.2);
  EXPECT_TRUE(rows.done());
}

// A run silent for longer than the lease (a process stopped, a laptop
// asleep) is told so by its next beat, and claims its unstarted rows again:
// those another run took meanwhile it leaves to that run.
TEST(StudyClaims, ARunThatLostItsLeaseClaimsItsUnstartedRowsAgain) {
  const TempDir folder;
  const std::string db = folder.file("lost.sqlite");
  StudyStore a(db), b(db);
  const StudyTable table = a.open_study("s", numbers(4));
  std::vector<Task> tasks;
  for (const Row& row : table.rows) tasks.push_back(row.task);
  ClaimTimes times;
  times.lease = 0.2;
  times.heartbeat = 0.05;
  ClaimedRows rows(a, "s", tasks, times);
  std::vector<Task> held = rows.take(4);
  ASSERT_EQ(held.size(), 4u);
  EXPECT_TRUE(rows.done());
  EXPECT_TRUE(rows.beat());
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const std::int64_t run_b = b.begin_run("s", times.lease);  // forgets A's run: stale
  ASSERT_EQ(b.claim("s", run_b, {tasks[0].id}, 1, times.lease).claimed.size(), 1u);
  EXPECT_FALSE(rows.beat());
  rows.give_back(std::move(held));
  EXPECT_FALSE(rows.done());
  const std::vector<Task> again = rows.take(4);
  ASSERT_EQ(again.size(), 3u);
  EXPECT_EQ(again[0].id, tasks[1].id);
  EXPECT_EQ(rows.held_elsewhere(), 1u);
  EXPECT_TRUE(rows.beat());
}

namespace {

class SleepingWorker : public RowWorker {
public:
  Outcome run(const Task& task) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    ++runs;
    return squared(task);
  }
  std::atomic<int> runs{0};
};

}  // namespace

// A row longer than the lease, run on the calling thread: the heartbeat
// thread keeps the claim.
TEST(StudyClaims, ARowLongerThanTheLeaseKeepsItsClaim) {
  const TempDir folder;
  const std::string db = folder.file("long.sqlite");
  StudyStore a(db), b(db);
  const StudyTable table = a.open_study("s", numbers(2));
  StudySettings settings;
  settings.threads = 0;
  settings.progress = false;
  settings.claims.lease = 0.3;
  settings.claims.heartbeat = 0.05;
  SleepingWorker worker;
  StudyRunInfo info;
  std::thread runner([&] { info = run_study(a, "s", table, settings, &worker, {}); });
  std::this_thread::sleep_for(std::chrono::milliseconds(400));  // the first row runs, claimed 0.4 s ago
  const std::int64_t run_b = b.begin_run("s", settings.claims.lease);
  const auto result = b.claim("s", run_b, {table.rows[0].task.id}, 1, settings.claims.lease);
  b.end_run(run_b);
  runner.join();
  EXPECT_EQ(result.elsewhere, (std::vector<std::int64_t>{table.rows[0].task.id}));
  EXPECT_TRUE(result.claimed.empty());
  EXPECT_EQ(worker.runs.load(), 2);
  EXPECT_EQ(info.ran, 2u);
}

TEST(ProcessIdentity, AProcessThatEndedIsKnownToHaveEnded) {
  const ProcessIdentity& self = this_process();
  EXPECT_FALSE(has_ended(self));
  const pid_t child = fork();
  if (child == 0) _exit(0);
  ASSERT_GT(child, 0);
  int status = 0;
  waitpid(child, &status, 0);
  ProcessIdentity gone = self;
  gone.pid = child;
  EXPECT_TRUE(has_ended(gone));
  ProcessIdentity reused = self;  // this pid, but started at another time: another process
  reused.started = self.started + 1;
  if (self.started != 0) {
    EXPECT_TRUE(has_ended(reused));
  }
  ProcessIdentity elsewhere = gone;  // another machine: cannot be told
  elsewhere.host += "-other";
  EXPECT_FALSE(has_ended(elsewhere));
}
