// The shipped study files (studies/*.toml): they parse at both scales, name known kinds, and
// the runnable quick scales reproduce the paper's findings.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <set>
#include <string>

#include "frictal/study.hpp"

using namespace frictal::study;
namespace fs = std::filesystem;

namespace {
fs::path studies_dir() { return fs::path(__FILE__).parent_path().parent_path().parent_path() / "studies"; }
std::string fresh(const std::string& name) {
  const std::string p = ::testing::TempDir() + "frictal_files_" + name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((p + suffix).c_str());
  return p;
}
}  // namespace

TEST(StudyFiles, EveryPaperFigureHasAStudyThatParsesAtBothScales) {
  const TaskRegistry reg = default_registry();
  const char* names[] = {"fig03-koch-surfaces",   "fig04-koch-signature",  "fig06-koch-friction",
                         "fig07-time-evolution",  "fig08-atomic-friction", "fig09-divider",
                         "fig10-mu-vs-dimension", "fig11-16-wm-profiles",  "fig14-18-wm-statistics"};
  for (const char* n : names) {
    const fs::path p = studies_dir() / (std::string(n) + ".toml");
    for (bool quick : {false, true}) {
      auto s = load_study(p.string(), quick, reg);
      ASSERT_TRUE(s.ok()) << s.error().message;
      EXPECT_EQ(s->name, n);
      EXPECT_FALSE(s->tasks.empty());
    }
    auto full = load_study(p.string(), false, reg), quick = load_study(p.string(), true, reg);
    EXPECT_LE(quick->tasks.size(), full->tasks.size()) << n;
  }
  // The full WM grid is the paper's: 11 D x 11 n_max x 20 pairs.
  auto wm = load_study((studies_dir() / "fig14-18-wm-statistics.toml").string(), false, reg);
  EXPECT_EQ(wm->tasks.size(), 11u * 11u * 20u);
}

TEST(StudyFiles, QuickWmStudyReproducesThePaperFindings) {
  const TaskRegistry reg = default_registry();
  auto s = load_study((studies_dir() / "fig14-18-wm-statistics.toml").string(), true, reg);
  ASSERT_TRUE(s.ok());
  auto st = Store::open(fresh("wm-quick.sqlite"), *s);
  ASSERT_TRUE(st.ok());
  RunOptions o;
  o.threads = 2;
  auto sum = run_threads(*s, **st, reg, o);
  ASSERT_TRUE(sum.ok()) << sum.error().message;
  EXPECT_EQ(sum->failed, 0);
  auto rep = report(**st);
  ASSERT_TRUE(rep.ok()) << rep.error().message;
  // the five slope claims of Figs. 14-18, the narrower contact slopes (Fig. 16) and the rms slope
  // against D (Fig. 12)
  ASSERT_EQ(rep->findings.size(), 7u);
  for (const auto& f : rep->findings) {
    std::string ev;
    for (const auto& e : f.evidence) ev += e + "\n";
    EXPECT_TRUE(f.supported) << f.claim << "\n" << ev;
  }
}

TEST(StudyFiles, QuickTheoryStudiesReproduceThePaperFindings) {
  const TaskRegistry reg = default_registry();
  for (const char* n : {"fig03-koch-surfaces", "fig04-koch-signature", "fig06-koch-friction", "fig08-atomic-friction",
                        "fig11-16-wm-profiles"}) {
    auto s = load_study((studies_dir() / (std::string(n) + ".toml")).string(), true, reg);
    ASSERT_TRUE(s.ok());
    auto st = Store::open(fresh(std::string(n) + ".sqlite"), *s);
    ASSERT_TRUE(st.ok());
    RunOptions o;
    o.threads = 2;
    o.skip_unavailable = true;
    ASSERT_TRUE(run_threads(*s, **st, reg, o).ok());
    auto rep = report(**st);
    ASSERT_TRUE(rep.ok());
    EXPECT_FALSE(rep->findings.empty()) << n;
    std::set<std::string> ids;
    for (const auto& f : rep->findings) {
      ids.insert(f.claim_id);
      EXPECT_TRUE(f.supported) << n << ": " << f.claim << " " << f.evidence.front();
    }
    // The claims of the figures each study is named after.
    if (std::string(n) == "fig03-koch-surfaces") {
      EXPECT_EQ(ids, (std::set<std::string>{"koch-theta-max", "koch-steepest-edge", "koch-length-ratio"}));
    }
    if (std::string(n) == "fig11-16-wm-profiles") {
      EXPECT_EQ(ids, (std::set<std::string>{"wm-contact-below-surface", "wm-contact-narrower",
                                            "wm-phases-keep-rms-slope", "wm-spline-matches-linear"}));
    }
  }
}

TEST(StudyFiles, ArealTiltParsesAtBothScales) {
  // The areal-tilt study: 3 groove angles x 2 diagonals + 2 anisotropies x 4 samples; quick 2 + 2.
  // Parses whether or not this build has MuJoCo (the kind is then declared, not available).
  const TaskRegistry reg = default_registry();
  const std::string p = (studies_dir() / "areal-tilt.toml").string();
  auto full = load_study(p, false, reg), quick = load_study(p, true, reg);
  ASSERT_TRUE(full.ok()) << full.error().message;
  ASSERT_TRUE(quick.ok()) << quick.error().message;
  EXPECT_EQ(full->tasks.size(), 14u);
  EXPECT_EQ(quick->tasks.size(), 4u);
}
