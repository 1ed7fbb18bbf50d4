// Inputs of the study harnesses (fuzz/fuzz_study.cpp, fuzz/fuzz_store.cpp) that a reader or parser
// must withstand, kept under tests/data/fuzz-regressions/{study,store}/: each is read through the
// normal API and must give a clean result or a clear error, as in the harness.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "frictal/study.hpp"

using namespace frictal::study;
namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}
std::vector<fs::path> inputs(const std::string& sub) {
  std::vector<fs::path> out;
  const fs::path dir = fs::path(FRICTAL_TEST_DATA) / "fuzz-regressions" / sub;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().extension() != ".md") out.push_back(e.path());
  return out;
}
}  // namespace

TEST(StudyFuzzRegressions, StudyInputsParseOrFailWithAMessage) {
  const TaskRegistry reg = default_registry();
  for (const auto& p : inputs("study")) {
    for (bool quick : {false, true}) {
      auto s = parse_study(slurp(p), p.filename().string(), quick, reg);
      if (!s) {
        EXPECT_FALSE(s.error().message.empty()) << p;
      }
    }
  }
}

TEST(StudyFuzzRegressions, StoreInputsOpenOrFailWithAMessageAndExportStaysInItsDirectory) {
  const TaskRegistry reg = default_registry();
  const fs::path work = fs::path(::testing::TempDir()) / "frictal-store-regressions";
  for (const auto& p : inputs("store")) {
    std::error_code ec;
    fs::remove_all(work, ec);
    fs::create_directories(work / "a" / "b");
    const fs::path store = work / "a" / "b" / "store.sqlite";
    fs::copy_file(p, store);
    auto st = Store::open_existing(store.string());
    if (!st) {
      EXPECT_FALSE(st.error().message.empty()) << p;
      continue;
    }
    auto status = store_status(**st, reg);
    if (status) {
      EXPECT_EQ(status->tasks.total, status->tasks.done + status->tasks.failed + status->tasks.pending) << p;
    } else {
      EXPECT_FALSE(status.error().message.empty()) << p;
    }
    const fs::path out = work / "a" / "b" / "export";
    auto files = export_csv(**st, out.string(), reg);
    if (!files) {
      EXPECT_FALSE(files.error().message.empty()) << p;
    }
    // Nothing written outside the export directory (a part name such as "../../x" in a store
    // that frictal did not write once led out of it).
    for (const auto& e : fs::recursive_directory_iterator(work)) {
      if (!e.is_regular_file()) continue;
      const auto rel = fs::relative(e.path(), work / "a" / "b").string();
      EXPECT_TRUE(rel.rfind("store.sqlite", 0) == 0 || rel.rfind("export", 0) == 0) << p << ": wrote " << e.path();
    }
  }
}

TEST(StudyFuzzRegressions, PartNamesThatCannotNameAFileAreRefused) {
  const TaskRegistry reg = default_registry();
  for (const char* name : {"../x", "a/b", ".hidden", "a b"}) {
    const std::string text = std::string("[study]\nname='t'\nseed=1\n[[part]]\nname='") + name +
                             "'\nkind='divider'\n[part.parameters]\niterations=[1]\n";
    auto s = parse_study(text, "t.toml", false, reg);
    ASSERT_FALSE(s.ok()) << name;
    EXPECT_NE(s.error().message.find("part name"), std::string::npos) << s.error().message;
  }
}

// Found by fuzz_study (a libFuzzer timeout): 2.5 kB of TOML define one part with the axes
// iterations = 1 .. 0x7f5 (2037 values), ion (4), n_max (3) and pair (count 3), a grid of
// 2037 * 4 * 3 * 3 = 73332 tasks, each legitimately built (11 s under ASan). Not a hang: the
// default limit (10^7) lets it through; a caller's lower limit refuses it before any task is built.
TEST(StudyFuzzRegressions, AGridOfTensOfThousandsOfTasksHonoursTheTaskLimit) {
  const TaskRegistry reg = default_registry();
  const std::string text =
      slurp(fs::path(FRICTAL_TEST_DATA) / "fuzz-regressions" / "study" / "grid-of-73332-tasks.toml");
  ASSERT_FALSE(text.empty());
  auto full = parse_study(text, "grid.toml", false, reg);
  ASSERT_TRUE(full.ok()) << full.error().message;
  EXPECT_EQ(full->tasks.size(), 73332u);
  auto limited = parse_study(text, "grid.toml", false, reg, 10000);
  ASSERT_FALSE(limited.ok());
  EXPECT_NE(limited.error().message.find("grid.toml: part '"), std::string::npos) << limited.error().message;
  EXPECT_NE(limited.error().message.find("has more than 10000 tasks"), std::string::npos) << limited.error().message;
}

// Found by fuzz_study (UBSan): a range axis { from = 15, to = 2.1e124, step = 5.0 } has 4e123
// values; converting that count to a 64-bit integer was undefined. Now "too many values".
TEST(StudyFuzzRegressions, ARangeOfMoreValuesThanAnyIntegerIsTooMany) {
  const TaskRegistry reg = default_registry();
  const std::string text =
      slurp(fs::path(FRICTAL_TEST_DATA) / "fuzz-regressions" / "study" / "range-of-4e123-values.toml");
  ASSERT_FALSE(text.empty());
  for (bool quick : {false, true}) {
    auto s = parse_study(text, "range.toml", quick, reg);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("too many values"), std::string::npos) << s.error().message;
  }
}
