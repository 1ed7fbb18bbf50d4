// Idle cores of a study run lent to its tasks (borrow_idle_threads): how many a task gets, and
// that the tilt kinds take no thread count as a parameter (it is not in the content address).
#include <gtest/gtest.h>

#include <cstdio>

#include "frictal/study.hpp"

using namespace frictal::study;

namespace {
std::string tmp(const std::string& name) {
  const std::string p = ::testing::TempDir() + "frictal_study_idle_" + name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((p + suffix).c_str());
  return p;
}
}  // namespace

// Outside a run nothing is lent. A run with 3 threads and one task starts one compute thread
// (util::thread_count caps the threads at the tasks): the two cores without a compute thread are
// lent to that task, and no more however many it asks for.
TEST(StudyIdleCores, ALoneTaskBorrowsTheCoresWithoutComputeThreads) {
  EXPECT_EQ(borrow_idle_threads(4), 0u);
  return_idle_threads(0);
  TaskRegistry r = default_registry();
  r.add({"borrow", "test", 1, [](const Params&, std::uint64_t) -> frictal::Result<TaskOutput> {
           TaskOutput t;
           const unsigned got = borrow_idle_threads(8);
           t.scalars["borrowed"] = got;
           t.scalars["again"] = borrow_idle_threads(8);  // none left
           return_idle_threads(got);
           t.scalars["after_return"] = borrow_idle_threads(1);  // given back: lendable again
           return_idle_threads(static_cast<unsigned>(t.scalars["after_return"]));
           return t;
         }});
  auto s = parse_study("[study]\nname='b'\nseed=1\n[[part]]\nname='one'\nkind='borrow'\n[part.parameters]\nx=[1]\n",
                       "t", false, r);
  ASSERT_TRUE(s.ok()) << s.error().message;
  auto st = Store::open(tmp("one.sqlite"), *s);
  ASSERT_TRUE(st.ok());
  RunOptions o;
  o.threads = 3;
  ASSERT_TRUE(run_threads(*s, **st, r, o).ok());
  auto rows = (*st)->rows("one");
  ASSERT_TRUE(rows.ok()) << rows.error().message;
  ASSERT_EQ(rows->size(), 1u);
  const TaskOutput& out = rows->front().output;
  EXPECT_EQ(out.scalars.at("borrowed"), 2);
  EXPECT_EQ(out.scalars.at("again"), 0);
  EXPECT_EQ(out.scalars.at("after_return"), 1);
}

TEST(StudyIdleCores, TiltKindsTakeNoThreadsParameter) {
  for (const char* kind : {"tilt", "wm-tilt"}) {
    auto res = default_registry().find(kind)->run({{"threads", std::int64_t{2}}}, 1);
    ASSERT_FALSE(res.ok()) << kind;
    EXPECT_NE(res.error().message.find("parameter 'threads'"), std::string::npos) << res.error().message;
  }
}

// Several studies in one run lend their idle cores too: 4 threads for 2 tasks (one per study)
// start 2 compute threads, so the task that borrows gets at least the 2 cores without a compute
// thread (and at most one more: the other study's thread once its quick task is done).
TEST(StudyIdleCores, SeveralStudiesInOneRunLendTheirIdleCores) {
  TaskRegistry r = default_registry();
  r.add({"borrow", "test", 1, [](const Params&, std::uint64_t) -> frictal::Result<TaskOutput> {
           TaskOutput t;
           const unsigned got = borrow_idle_threads(8);
           t.scalars["borrowed"] = got;
           return_idle_threads(got);
           return t;
         }});
  r.add({"quick", "test", 1, [](const Params&, std::uint64_t) -> frictal::Result<TaskOutput> {
           TaskOutput t;
           t.scalars["x"] = 1;
           return t;
         }});
  auto a = parse_study("[study]\nname='a'\nseed=1\n[[part]]\nname='one'\nkind='borrow'\n[part.parameters]\nx=[1]\n",
                       "a", false, r);
  auto b = parse_study("[study]\nname='b'\nseed=1\n[[part]]\nname='one'\nkind='quick'\n[part.parameters]\nx=[2]\n", "b",
                       false, r);
  ASSERT_TRUE(a.ok() && b.ok());
  auto sa = Store::open(tmp("multi-a.sqlite"), *a);
  auto sb = Store::open(tmp("multi-b.sqlite"), *b);
  ASSERT_TRUE(sa.ok() && sb.ok());
  RunOptions o;
  o.threads = 4;
  auto res = run_threads(std::vector<StudyRun>{{&*a, sa->get(), "", nullptr}, {&*b, sb->get(), "", nullptr}}, r, o);
  ASSERT_TRUE(res.ok()) << res.error().message;
  auto rows = (*sa)->rows("one");
  ASSERT_TRUE(rows.ok()) << rows.error().message;
  ASSERT_EQ(rows->size(), 1u);
  const double got = rows->front().output.scalars.at("borrowed");
  EXPECT_GE(got, 2);
  EXPECT_LE(got, 3);
}
