// Parametric studies: parameter rows, the SQLite store (resume, no
// duplicates), the runner with worker threads, messages and CSV.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <set>

#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/parallel_loop.hpp"
#include "study/parameter_rows.hpp"
#include "study/study_job.hpp"
#include "study/study_progress.hpp"
#include "study/study_runner.hpp"
#include "study/study_store.hpp"
#include "test_support.hpp"

using namespace ashlar;
using namespace ashlar::study;

namespace {

// Computes t * n for parameter columns (n, t), failing when t > 0.5.
class ProductWorker : public RowWorker {
public:
  Outcome run(const Task& task) override {
    Outcome outcome;
    outcome.id = task.id;
    const double n = static_cast<double>(std::get<std::int64_t>(task.parameters[0]));
    const double t = std::get<double>(task.parameters[1]);
    if (t > 0.5) {
      outcome.status = RunStatus::error;
      outcome.error = "t too large";
      return outcome;
    }
    outcome.fields = {{"product", n * t}, {"big", n * t > 4.0}};
    return outcome;
  }
};

ParameterRows small_grid() {
  std::vector<Value> n = {std::int64_t{4}, std::int64_t{8}};
  std::vector<Value> t;
  for (double v : linear_range(0.1, 0.6, 6)) t.push_back(v);
  return grid({{"t", t}, {"n", n}});
}

double field(const Row& row, const std::string& name) {
  for (const auto& [f, v] : row.outcome.fields)
    if (f == name) return std::get<double>(v);
  return NAN;
}

}  // namespace

TEST(ParameterRows, RangeHasExactEndsAndEvenSteps) {
  const auto values = linear_range(0.08, 0.20, 121);
  ASSERT_EQ(values.size(), 121u);
  EXPECT_EQ(values.front(), 0.08);
  EXPECT_EQ(values.back(), 0.20);
  EXPECT_NEAR(values[60], 0.14, 1e-15);
  EXPECT_NEAR(values[1] - values[0], 0.001, 1e-15);
  EXPECT_THROW(linear_range(0, 1, 1), InvalidArgument);
  EXPECT_THROW(linear_range(0, NAN, 3), InvalidArgument);
  EXPECT_EQ(linear_range(2, 2, 1), std::vector<double>{2});
}

TEST(ParameterRows, RangeGivesTheDecimalsAUserTypes) {
  // 0.08 + 90 * 0.00025 computed in doubles is 0.10250000000000001; a
  // query for 0.1025 must find that row.
  const auto values = linear_range(0.08, 0.20, 481);
  EXPECT_EQ(values[90], 0.1025);
  EXPECT_EQ(values[1], 0.08025);
  EXPECT_EQ(values[480], 0.2);
  EXPECT_EQ(linear_range(0.1, 0.2, 5), (std::vector<double>{0.1, 0.125, 0.15, 0.175, 0.2}));
  EXPECT_EQ(linear_range(-1.5, 1.5, 7), (std::vector<double>{-1.5, -1, -0.5, 0, 0.5, 1, 1.5}));
  // Not decimals (a step of a third): the evenly spaced doubles as before.
  const auto thirds = linear_range(0, 1, 4);
  EXPECT_EQ(thirds[1], 1.0 / 3.0);
  EXPECT_EQ(thirds[2], 2.0 / 3.0);
}

TEST(ParameterRows, GridSortsColumnsAndVariesTheLastFastest) {
  const ParameterRows rows = small_grid();
  ASSERT_EQ(rows.names, (std::vector<std::string>{"n", "t"}));
  ASSERT_EQ(rows.rows.size(), 12u);
  EXPECT_EQ(std::get<std::int64_t>(rows.rows[0][0]), 4);
  EXPECT_EQ(std::get<double>(rows.rows[1][1]), 0.2);
  EXPECT_EQ(std::get<std::int64_t>(rows.rows[6][0]), 8);
  EXPECT_EQ(std::get<double>(rows.rows[6][1]), 0.1);
}

TEST(ParameterRows, CheckedRejectsDuplicatesNilAndReservedNames) {
  ParameterRows rows{{"t"}, {{0.1}, {0.2}, {0.1}}};
  try {
    checked(rows);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("rows 1 and 3 are the same"), std::string::npos) << e.what();
  }
  // An integer and a number with its value are the same row.
  EXPECT_THROW(checked(ParameterRows{{"n"}, {{std::int64_t{16}}, {16.0}}}), InvalidArgument);
  EXPECT_THROW(checked(ParameterRows{{"run_status"}, {{1.0}}}), InvalidArgument);
  EXPECT_THROW(checked(ParameterRows{{"2x"}, {{1.0}}}), InvalidArgument);
  EXPECT_THROW(checked(ParameterRows{{"t"}, {{Value{}}}}), InvalidArgument);
}

TEST(ParameterRows, LatinHypercubeFillsEveryStratumOnceAndRepeatsWithItsSeed) {
  const int samples = 50;
  std::vector<SampledAxis> axes(2);
  axes[0].name = "t";
  axes[0].min = 0.08;
  axes[0].max = 0.20;
  axes[1].name = "mu";
  axes[1].levels = {0.4, 0.5, 0.6, 0.7, 0.8};
  const ParameterRows rows = latin_hypercube(axes, samples, 42);
  ASSERT_EQ(rows.names, (std::vector<std::string>{"mu", "t"}));
  std::set<int> strata;
  std::map<double, int> level_count;
  for (const auto& row : rows.rows) {
    const double t = std::get<double>(row[1]);
    ASSERT_GE(t, 0.08);
    ASSERT_LT(t, 0.20);
    strata.insert(static_cast<int>((t - 0.08) / 0.12 * samples));
    ++level_count[std::get<double>(row[0])];
  }
  EXPECT_EQ(strata.size(), 50u);  // one sample in each of the 50 strata
  for (const auto& [level, count] : level_count) EXPECT_EQ(count, 10) << level;
  EXPECT_EQ(latin_hypercube(axes, samples, 42).rows, rows.rows);
  EXPECT_NE(latin_hypercube(axes, samples, 43).rows, rows.rows);
}

TEST(StudyValue, MessagesRoundTrip) {
  Task task{7, {std::int64_t{16}, 0.125, true, std::string("a,b"), Value{}}};
  EXPECT_EQ(decode_task(encode(task)).parameters, task.parameters);
  Outcome outcome;
  outcome.id = 9;
  outcome.status = RunStatus::error;
  outcome.error = "boom";
  outcome.fields = {{"x", 1.5}, {"ok", false}};
  outcome.seconds = 0.25;
  outcome.worker = 1002;
  const Outcome back = decode_outcome(encode(outcome));
  EXPECT_EQ(back.id, 9);
  EXPECT_EQ(back.error, "boom");
  EXPECT_EQ(back.fields, outcome.fields);
  EXPECT_EQ(back.worker, 1002);
  std::string truncated = encode(outcome);
  truncated.pop_back();
  EXPECT_THROW(decode_outcome(truncated), InvalidArgument);
  std::vector<std::string> p, f;
  std::vector<Row> rows;
  decode_table(encode_table({"t"}, {"x"}, {Row{task, true, outcome}}), p, f, rows);
  EXPECT_EQ(p, std::vector<std::string>{"t"});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0].finished);
  EXPECT_EQ(rows[0].outcome.error, "boom");
}

TEST(StudyStore, ResumesWithoutLosingOrDuplicatingRows) {
  const TempDir folder;
  const std::string db = folder.file("resume.sqlite");
  const ParameterRows rows = small_grid();
  std::vector<Outcome> first_half;
  {
    StudyStore store(db);
    StudyTable table = store.open_study("products", rows);
    EXPECT_EQ(table.finished_count(), 0u);
    ProductWorker worker;
    for (std::size_t r = 0; r < 6; ++r) first_half.push_back(worker.run(table.rows[r].task));
    store.record("products", first_half);
  }  // as if the process died here
  StudyStore store(db);
  StudyTable table = store.open_study("products", rows);
  ASSERT_EQ(table.rows.size(), 12u);
  EXPECT_EQ(table.finished_count(), 6u);
  EXPECT_EQ(table.field_names, (std::vector<std::string>{"product", "big"}));  // in the order first seen
  EXPECT_NEAR(field(table.rows[2], "product"), 4 * 0.3, 1e-15);
  EXPECT_TRUE(std::holds_alternative<bool>(table.rows[2].outcome.fields[1].second));  // booleans come back as booleans
  // Recording a finished row again changes nothing.
  Outcome again = first_half[2];
  again.fields = {{"product", 99.0}};
  store.record("products", {again});
  table = store.open_study("products", rows);
  EXPECT_NEAR(field(table.rows[2], "product"), 1.2, 1e-15);
  EXPECT_EQ(store.read_study("products").rows.size(), 12u);

  // More rows later: the stored ones keep their outcomes, ids stay unique.
  ParameterRows more = rows;
  more.rows.push_back({std::int64_t{16}, 0.1});
  table = store.open_study("products", checked(more));
  ASSERT_EQ(table.rows.size(), 13u);
  EXPECT_EQ(table.finished_count(), 6u);
  std::set<std::int64_t> ids;
  for (const Row& row : table.rows) ids.insert(row.task.id);
  EXPECT_EQ(ids.size(), 13u);

  EXPECT_THROW(store.open_study("products", ParameterRows{{"t"}, {{0.1}}}), InvalidArgument);
  EXPECT_THROW(store.open_study("bad name", rows), InvalidArgument);
  EXPECT_THROW(store.read_study("missing"), InvalidArgument);
}

TEST(StudyStore, RerunErrorsForgetsFailedRuns) {
  StudyStore store("");
  const ParameterRows rows = small_grid();
  StudyTable table = store.open_study("s", rows);
  ProductWorker worker;
  std::vector<Outcome> outcomes;
  for (const Row& row : table.rows) outcomes.push_back(worker.run(row.task));
  store.record("s", outcomes);
  table = store.open_study("s", rows);
  EXPECT_EQ(table.error_count(), 2u);  // t = 0.6 for n = 4 and 8
  table = store.open_study("s", rows, true);
  EXPECT_EQ(table.finished_count(), 10u);
  EXPECT_EQ(table.error_count(), 0u);
}

TEST(StudyRunner, ThreadsRunEveryRowOnceAndRecordErrors) {
  const TempDir folder;
  const std::string db = folder.file("threads.sqlite");
  StudyStore store(db);
  const ParameterRows rows = small_grid();
  const StudyTable table = store.open_study("products", rows);
  StudySettings settings;
  settings.threads = 3;
  settings.progress = false;
  std::atomic<int> started{0};
  const StudyRunInfo info = run_study(store, "products", table, settings, nullptr, [&](int) {
    ++started;
    return std::make_unique<ProductWorker>();
  });
  EXPECT_EQ(started.load(), 3);
  EXPECT_EQ(info.ran, 12u);
  EXPECT_EQ(info.errors, 2u);
  const StudyTable done = store.open_study("products", rows);
  EXPECT_EQ(done.finished_count(), 12u);
  for (const Row& row : done.rows) {
    const double n = static_cast<double>(std::get<std::int64_t>(row.task.parameters[0]));
    const double t = std::get<double>(row.task.parameters[1]);
    if (t > 0.5) {
      EXPECT_EQ(row.outcome.status, RunStatus::error);
      EXPECT_EQ(row.outcome.error, "t too large");
    } else {
      EXPECT_DOUBLE_EQ(field(row, "product"), n * t);
    }
    EXPECT_GE(row.outcome.worker, 1);
    EXPECT_LE(row.outcome.worker, 3);
  }
  // Nothing left: a second run does nothing.
  EXPECT_EQ(run_study(store, "products", done, settings, nullptr, [](int) { return std::make_unique<ProductWorker>(); }).ran, 0u);
}

TEST(StudyRunner, WorkersThatCannotStartAreReported) {
  StudyStore store("");
  const ParameterRows rows = small_grid();
  StudySettings settings;
  settings.threads = 2;
  settings.progress = false;
  const StudyRunInfo info = run_study(store, "half", store.open_study("half", rows), settings, nullptr, [](int number) -> std::unique_ptr<RowWorker> {
    if (number == 2) throw Error("no memory");
    return std::make_unique<ProductWorker>();
  });
  EXPECT_EQ(info.ran, 12u);
  ASSERT_EQ(info.worker_failures.size(), 1u);
  EXPECT_EQ(info.worker_failures[0], "worker 2 could not start: no memory");
  try {
    run_study(store, "none", store.open_study("none", rows), settings, nullptr,
              [](int) -> std::unique_ptr<RowWorker> { throw Error("script error"); });
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no worker left to run the 12 remaining rows"), std::string::npos) << e.what();
  }
}

TEST(StudyRunner, BrokenFieldsBecomeErrorRows) {
  Outcome outcome;
  outcome.fields = {{"t", 1.0}};
  EXPECT_EQ(checked_outcome(outcome, {"t"}).error, "returned field 't' is a parameter");
  outcome.fields = {{"run_status", 1.0}};
  EXPECT_EQ(checked_outcome(outcome, {"t"}).status, RunStatus::error);
  outcome.fields = {{"bad name", 1.0}};
  EXPECT_EQ(checked_outcome(outcome, {"t"}).status, RunStatus::error);
  outcome.fields = {{"x", 1.0}};
  EXPECT_EQ(checked_outcome(outcome, {"t"}).status, RunStatus::ok);
}

// The worker threads a study asks for: one worker means the calling
// thread; never more threads than rows; 0 is every core only when threads
// can be made.
TEST(StudyJob, ThreadsFollowWorkersAndRowsLeft) {
  const int cores = worker_count(0, 1 << 20);
  EXPECT_EQ(study_threads(1, true, 12), 0);
  EXPECT_EQ(study_threads(3, true, 12), 3);
  EXPECT_EQ(study_threads(3, true, 2), 2);
  EXPECT_EQ(study_threads(3, true, 1), 0);
  EXPECT_EQ(study_threads(3, true, 0), 0);
  EXPECT_EQ(study_threads(0, false, 12), 0);
  EXPECT_EQ(study_threads(0, true, 12), std::min(cores, 12) > 1 ? std::min(cores, 12) : 0);
}

namespace {

// A counting worker for the calling thread, so a test sees which path ran.
class CountingWorker : public ProductWorker {
public:
  Outcome run(const Task& task) override {
    ++runs;
    return ProductWorker::run(task);
  }
  int runs = 0;
};

}  // namespace

TEST(StudyJob, OneWorkerRunsOnTheCallingThreadAndResumesFromTheStore) {
  StudyJob job;
  job.name = "single";
  const TempDir folder;
  job.db = folder.file("single.sqlite");
  job.rows = small_grid();
  job.workers = 1;
  job.progress = false;
  CountingWorker local;
  const StudyResult first = run_study_job(job, local, [](int) -> std::unique_ptr<RowWorker> {
    throw Error("no thread should start");
  });
  EXPECT_EQ(local.runs, 12);
  EXPECT_EQ(first.info.ran, 12u);
  EXPECT_EQ(first.info.errors, 2u);
  EXPECT_EQ(first.info.workers, 1);
  ASSERT_EQ(first.table.rows.size(), 12u);
  EXPECT_EQ(first.table.finished_count(), 12u);
  for (const Row& row : first.table.rows) EXPECT_EQ(row.outcome.worker, 1);
  // n = 8, t = 0.3 (grid order: the last axis, t, varies fastest).
  EXPECT_DOUBLE_EQ(field(first.table.rows[8], "product"), 8 * 0.3);

  // Everything is stored: running the job again runs nothing, and with
  // rerun_errors only the two rows that ended in error.
  EXPECT_EQ(run_study_job(job, local, {}).info.ran, 0u);
  job.rerun_errors = true;
  const StudyResult again = run_study_job(job, local, {});
  EXPECT_EQ(again.info.ran, 2u);
  EXPECT_EQ(local.runs, 14);
  EXPECT_EQ(again.table.error_count(), 2u);
}

TEST(StudyJob, SeveralWorkersRunOnThreadsOfTheirOwn) {
  StudyJob job;
  job.name = "threads";
  job.rows = small_grid();
  job.workers = 3;
  job.progress = false;
  CountingWorker local;
  std::atomic<int> started{0};
  const StudyResult result = run_study_job(job, local, [&](int) {
    ++started;
    return std::make_unique<ProductWorker>();
  });
  EXPECT_EQ(local.runs, 0);
  EXPECT_EQ(started.load(), 3);
  EXPECT_EQ(result.info.ran, 12u);
  EXPECT_EQ(result.table.finished_count(), 12u);
  EXPECT_EQ(result.table.error_count(), 2u);
  std::set<int> workers;
  for (const Row& row : result.table.rows) workers.insert(row.outcome.worker);
  EXPECT_TRUE(*workers.begin() >= 1 && *workers.rbegin() <= 3);
  EXPECT_DOUBLE_EQ(field(result.table.rows[1], "product"), 4 * 0.2);

  // Without a way to make worker threads, more than one worker is refused.
  EXPECT_THROW(run_study_job(job, local, {}), InvalidArgument);
}

namespace {

// Stops the study (as Ctrl-C does) after `stop_after` rows.
class InterruptingWorker : public ProductWorker {
public:
  explicit InterruptingWorker(int stop_after) : stop_after_(stop_after) {}
  Outcome run(const Task& task) override {
    if (++runs_ == stop_after_) interrupt_requested() = true;
    return ProductWorker::run(task);
  }

private:
  int stop_after_;
  int runs_ = 0;
};

}  // namespace

TEST(StudyJob, AnInterruptedStudyKeepsItsFinishedRows) {
  StudyJob job;
  job.name = "stopped";
  const TempDir folder;
  job.db = folder.file("stopped.sqlite");
  job.rows = small_grid();
  job.workers = 1;
  job.progress = false;
  InterruptingWorker local(5);
  try {
    run_study_job(job, local, {});
    FAIL() << "an interrupted study throws";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "interrupted! study 'stopped' keeps its 5 finished rows of 12; run the script again to go on");
  }
  interrupt_requested() = false;
  CountingWorker rest;
  EXPECT_EQ(run_study_job(job, rest, {}).table.finished_count(), 12u);
  EXPECT_EQ(rest.runs, 7);
}

TEST(StudyTable, CsvQuotesAndLeavesPendingRowsEmpty) {
  StudyTable table;
  table.parameter_names = {"t"};
  table.field_names = {"note"};
  Row done{{1, {0.5}}, true, {}};
  done.outcome.fields = {{"note", std::string("a \"b\", c")}};
  done.outcome.seconds = 0.5;
  done.outcome.worker = 2;
  table.rows = {done, Row{{2, {0.25}}, false, {}}};
  EXPECT_EQ(csv_text(table),
            "t,note,run_status,run_error,run_seconds,run_worker\r\n"
            "0.5,\"a \"\"b\"\", c\",ok,,0.5,2\r\n"
            "0.25,,,,,\r\n");
}

TEST(StudyProgress, AnUnknownTotalShowsTheCountTheRateAndTheTime) {
  // A solver's iterations (load_factor): no bar, percentage or ETA.
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  StudyProgress line("1010 blocks", StudyProgress::kUnknownTotal, true, out, 10.0, "load_factor", "iteration");
  line.update(27577, 0);
  line.finish(41049, 0, "optimal");
  std::rewind(out);
  std::string text;
  for (int c; (c = std::fgetc(out)) != EOF;) text += static_cast<char>(c);
  std::fclose(out);
  EXPECT_EQ(text.rfind("load_factor 1010 blocks: 27577 iterations  ", 0), 0u) << text;
  EXPECT_NE(text.find("iterations/s  0 s\n"), std::string::npos) << text;
  EXPECT_NE(text.find("load_factor 1010 blocks: 41049 iterations in 0 s"), std::string::npos) << text;
  EXPECT_EQ(text.find("ETA"), std::string::npos) << text;
  EXPECT_EQ(text.find('%'), std::string::npos) << text;
}

TEST(StudyProgress, ClockText) {
  EXPECT_EQ(StudyProgress::clock_text(7.2), "7 s");
  EXPECT_EQ(StudyProgress::clock_text(245), "4:05");
  EXPECT_EQ(StudyProgress::clock_text(3723), "1:02:03");
  EXPECT_EQ(StudyProgress::clock_text(NAN), "?");
}
