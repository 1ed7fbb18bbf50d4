// Inputs that are no regular file: /dev/null, a directory, a FIFO (named pipe). Every reader of
// an input file -- surfaces (read_surface, read_profile, read_map), the study file, an existing
// study store -- says what the path is and what was expected, and never blocks on a FIFO that
// has no writer (the path is checked with stat before anything opens it).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <string>

#include <gtest/gtest.h>

#include "frictal/io.hpp"
#include "frictal/study.hpp"

using namespace frictal;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

/// A FIFO in the test's temporary folder, removed at the end.
struct Fifo {
  std::string path;
  explicit Fifo(const std::string& name) : path(::testing::TempDir() + "frictal_" + name) {
    ::unlink(path.c_str());
    if (::mkfifo(path.c_str(), 0600) != 0) path.clear();
  }
  ~Fifo() {
    if (!path.empty()) ::unlink(path.c_str());
  }
};

/// Runs `read` with a watchdog: if it has not returned after 20 s it is blocked on the FIFO;
/// opening the FIFO's write end and closing it again gives the blocked reader an end of file,
/// so that the test fails instead of hanging.
template <class F>
auto without_hanging(const std::string& fifo, F read) {
  auto fut = std::async(std::launch::async, read);
  if (fut.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
    ADD_FAILURE() << fifo << ": the reader blocked on a FIFO with no writer";
    const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  }
  return fut.get();
}

}  // namespace

TEST(InputKinds, DevNullIsNamedAsACharacterDevice) {
  for (auto f : {ProfileFormat::Auto, ProfileFormat::Csv, ProfileFormat::X3p}) {
    ReadOptions o;
    o.format = f;
    auto r = read_surface("/dev/null", o);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().message,
              "/dev/null: is a character device (/dev/null, which holds no data), expected a "
              "surface file");
  }
  auto p = read_profile("/dev/null");
  ASSERT_FALSE(p);
  EXPECT_TRUE(contains(p.error().message, "is a character device")) << p.error().message;
  auto st = check_input_file("/dev/zero", "a surface file");
  ASSERT_FALSE(st);
  EXPECT_EQ(st.error().message, "/dev/zero: is a character device, expected a surface file");
}

TEST(InputKinds, ADirectoryIsNamedAsADirectory) {
  const std::string dir = ::testing::TempDir() + "frictal_input_dir";
  fs::create_directories(dir);
  auto r = read_surface(dir);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, dir + ": is a directory, expected a surface file");
  auto m = read_map(dir);
  ASSERT_FALSE(m);
  EXPECT_TRUE(contains(m.error().message, "is a directory")) << m.error().message;
  // The Gwyddion backend (which reads files itself) is given the same check first.
  ReadOptions o;
  o.format = ProfileFormat::GwyddionLib;
  auto g = read_surface(dir, o);
  ASSERT_FALSE(g);
  EXPECT_EQ(g.error().message, dir + ": is a directory, expected a surface file");
  fs::remove_all(dir);
}

TEST(InputKinds, AFifoWithNoWriterIsNamedAndNeverBlocks) {
  Fifo fifo("input_fifo");
  ASSERT_FALSE(fifo.path.empty()) << "mkfifo failed";
  for (auto f : {ProfileFormat::Auto, ProfileFormat::Dektak, ProfileFormat::GwyddionLib}) {
    ReadOptions o;
    o.format = f;
    auto r = without_hanging(fifo.path, [&] { return read_surface(fifo.path, o); });
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().message, fifo.path + ": is a FIFO (named pipe), expected a surface file");
  }
}

TEST(InputKinds, AMissingFileSaysSo) {
  auto r = read_surface("/nonexistent/frictal-input.csv");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::Io);
  EXPECT_EQ(r.error().message, "/nonexistent/frictal-input.csv: cannot open: no such file, expected a surface file");
}

TEST(InputKinds, StudyFileAndStoreSayWhatThePathIs) {
  const study::TaskRegistry reg = study::default_registry();
  const std::string dir = ::testing::TempDir() + "frictal_input_dir2";
  fs::create_directories(dir);
  Fifo fifo("study_fifo");
  ASSERT_FALSE(fifo.path.empty());
  auto s = study::load_study(dir, false, reg);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().message, dir + ": is a directory, expected a study file (TOML)");
  s = without_hanging(fifo.path, [&] { return study::load_study(fifo.path, false, reg); });
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().message, fifo.path + ": is a FIFO (named pipe), expected a study file (TOML)");
  s = study::load_study("/dev/null", false, reg);
  ASSERT_FALSE(s);
  EXPECT_TRUE(contains(s.error().message, "/dev/null: is a character device")) << s.error().message;

  for (const std::string& p : {dir, fifo.path, std::string("/dev/null")}) {
    auto e = without_hanging(fifo.path, [&] { return study::Store::open_existing(p); });
    ASSERT_FALSE(e) << p;
    EXPECT_TRUE(contains(e.error().message, p + ": is a")) << e.error().message;
    EXPECT_TRUE(contains(e.error().message, "expected a study store (SQLite file)")) << e.error().message;
  }
  auto fe = study::Store::open_existing(fifo.path);
  ASSERT_FALSE(fe);
  EXPECT_EQ(fe.error().message, fifo.path + ": is a FIFO (named pipe), expected a study store (SQLite file)");
  auto missing = study::Store::open_existing(dir + "/none.sqlite");
  ASSERT_FALSE(missing);
  EXPECT_TRUE(contains(missing.error().message, "no such store file")) << missing.error().message;
  // A store opened for a run (created when missing) is checked the same way when the path exists.
  auto st = study::parse_study(
      "[study]\nname='a'\nseed=1\n[[part]]\nname='sim'\nkind='tilt'\n[part.parameters]\nalpha_deg=[5.0]\n", "t.toml",
      false, reg);
  ASSERT_TRUE(st.ok()) << st.error().message;
  for (const std::string& p : {dir, fifo.path, std::string("/dev/null")}) {
    auto o = without_hanging(fifo.path, [&] { return study::Store::open(p, *st); });
    ASSERT_FALSE(o) << p;
    EXPECT_TRUE(contains(o.error().message, p + ": is a")) << o.error().message;
  }
  auto fresh = study::Store::open(dir + "/new.sqlite", *st);  // a missing store is created
  EXPECT_TRUE(fresh.ok()) << fresh.error().message;
  fs::remove_all(dir);
}
