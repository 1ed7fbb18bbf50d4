// Task kinds, the store and the thread runner.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "frictal/study.hpp"

using namespace frictal::study;

namespace {
std::string tmp(const std::string& name) {
  const std::string p = ::testing::TempDir() + "frictal_study_" + name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((p + suffix).c_str());
  return p;
}
// The default kinds plus a declared-but-unavailable one, as a kind whose engine is not built.
const TaskRegistry& reg() {
  static const TaskRegistry r = [] {
    TaskRegistry t = default_registry();
    t.add_unavailable("future-engine", "test placeholder");
    return t;
  }();
  return r;
}
Study parse(const std::string& text, bool quick = false) {
  auto s = parse_study(text, "test.toml", quick, reg());
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
  return *s;
}
/// Every stored column that does not depend on the run (no timings, worker or attempts).
std::string dump(Store& s) {
  auto r = s.content();
  EXPECT_TRUE(r.ok());
  return r.ok() ? *r : std::string{};
}
/// Runs a task kind of the default registry.
frictal::Result<TaskOutput> run_kind(const std::string& name, const Params& p, std::uint64_t seed) {
  return default_registry().find(name)->run(p, seed);
}
const char* kWmSmall = R"(
[study]
name = "wm-small"
seed = 3
[[part]]
name = "wm"
kind = "wm-pair-statistics"
[part.parameters]
dimension = [1.3, 1.7]
n_max = [3, 6]
pair = { count = 3 }
)";
}  // namespace

TEST(StudyKinds, KochSignatureMaximaAreOneOneTwoThreeAlpha) {
  // Paper Sec. III / Fig. 4: theta_max = 1, 1, 2, 3 alpha for K0..K3 (alpha = 5 deg).
  const double expect[] = {1, 1, 2, 3};
  for (int n = 0; n <= 3; ++n) {
    Params p{{"iterations", std::int64_t{n}}, {"alpha", 5.0}, {"length", 0.01}};
    auto r = run_kind("koch-signature", p, 0);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_NEAR(r->scalars.at("theta_max_over_alpha"), expect[n], 1e-9) << "K" << n;
    // The steepest edge of K_n is (n+1) alpha (Sec. III).
    EXPECT_NEAR(r->scalars.at("surface_slope_max_over_alpha"), n + 1, 1e-9);
    EXPECT_EQ(r->arrays.at("signature_offset_over_wavelength").size(),
              r->arrays.at("signature_theta_over_alpha").size());
  }
}

TEST(StudyKinds, KochDimensionEq13) {
  // alpha = 60 deg: 6 cos(alpha) = 3, so Eq. 13 reads 4 (1/3)^D = 1: the classic Koch curve,
  // D = ln 4 / ln 3. alpha -> 0: the flat line, D = 1.
  Params p{{"iterations", std::int64_t{0}}, {"alpha", 60.0}, {"length", 0.01}};
  auto r = run_kind("koch-signature", p, 0);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->scalars.at("dimension_eq13"), std::log(4.0) / std::log(3.0), 1e-12);
  p["alpha"] = 1e-3;
  EXPECT_NEAR(run_kind("koch-signature", p, 0)->scalars.at("dimension_eq13"), 1.0, 1e-6);
  // Friction (Eq. 6): phi = atan(mu_a) + theta_max; K1 at 20 deg with mu_a = 1: 45 + 20 deg.
  Params q{{"iterations", std::int64_t{1}}, {"alpha", 20.0}, {"length", 0.01}, {"atomic_friction", 1.0}};
  EXPECT_NEAR(run_kind("koch-signature", q, 0)->scalars.at("friction_angle_deg"), 65.0, 1e-9);
}

TEST(StudyKinds, WmPairIsDeterministicAndContactBelowSurface) {
  Params p{{"dimension", 1.6}, {"n_max", std::int64_t{5}}, {"pair", std::int64_t{0}}};
  auto a = run_kind("wm-pair-statistics", p, 11), b = run_kind("wm-pair-statistics", p, 11),
       c = run_kind("wm-pair-statistics", p, 12);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  // Bit for bit, NaN (an output the part did not ask for) included.
  ASSERT_EQ(a->scalars.size(), b->scalars.size());
  for (const auto& [key, v] : a->scalars) {
    const double w = b->scalars.at(key);
    EXPECT_TRUE(v == w || (std::isnan(v) && std::isnan(w))) << key << ": " << v << " vs " << w;
  }
  EXPECT_EQ(a->arrays, b->arrays);
  EXPECT_NE(a->scalars.at("contact_slope_max_deg"), c->scalars.at("contact_slope_max_deg"));
  EXPECT_LE(a->scalars.at("contact_slope_max_deg"), a->scalars.at("surface_slope_max_deg"));
  EXPECT_GT(a->scalars.at("contact_slope_std_deg"), 0);
  // dx = L_s / 10 with L_s = L / gamma^5 over L_b = 20 L: 200 gamma^5 intervals.
  EXPECT_NEAR(a->scalars.at("points"), std::floor(200 * std::pow(1.5, 5)) + 1, 1.0);
  // PDFs integrate to one.
  const auto& e = a->arrays.at("contact_slope_pdf_edges_deg");
  const auto& d = a->arrays.at("contact_slope_pdf_density_per_deg");
  double sum = 0;
  for (std::size_t i = 0; i < d.size(); ++i) sum += d[i] * (e[i + 1] - e[i]);
  EXPECT_NEAR(sum, 1.0, 1e-9);
  Params bad = p;
  bad["slopes"] = std::string("cubic");
  auto r = run_kind("wm-pair-statistics", bad, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("slopes"), std::string::npos);
}

TEST(StudyStore, OneAndTwoThreadsGiveIdenticalStores) {
  Study s = parse(kWmSmall);
  std::string dumps[2];
  for (unsigned t = 1; t <= 2; ++t) {
    const std::string path = tmp("threads" + std::to_string(t) + ".sqlite");
    auto st = Store::open(path, s);
    ASSERT_TRUE(st.ok()) << st.error().message;
    RunOptions o;
    o.threads = t;
    auto sum = run_threads(s, **st, reg(), o);
    ASSERT_TRUE(sum.ok()) << sum.error().message;
    EXPECT_EQ(sum->ran, 12);
    EXPECT_EQ(sum->failed, 0);
    dumps[t - 1] = dump(**st);
  }
  EXPECT_EQ(dumps[0], dumps[1]);
  EXPECT_NE(dumps[0].find("contact_slope_max_deg"), std::string::npos);
}

TEST(StudyStore, ResumesRefusesOtherStudiesAndKeepsDoneTasks) {
  Study s = parse(kWmSmall);
  const std::string path = tmp("resume.sqlite");
  std::atomic<bool> stop{false};
  {
    auto st = Store::open(path, s);
    ASSERT_TRUE(st.ok());
    RunOptions o;
    o.threads = 1;
    o.stop = &stop;
    int seen = 0;
    o.progress = [&](const Progress& p) {
      if (p.this_run > 0 && ++seen == 4) stop = true;  // interrupt after 4 tasks
    };
    auto sum = run_threads(s, **st, reg(), o);
    ASSERT_TRUE(sum.ok());
    EXPECT_TRUE(sum->interrupted);
    EXPECT_GE(sum->ran, 4);
    EXPECT_LT(sum->ran, 12);
    auto c = (*st)->counts();
    EXPECT_EQ(c->done, sum->ran);
  }
  {
    auto st = Store::open(path, s);
    ASSERT_TRUE(st.ok());
    auto before = (*st)->counts()->done;
    RunOptions o;
    o.threads = 2;
    auto sum = run_threads(s, **st, reg(), o);
    ASSERT_TRUE(sum.ok());
    EXPECT_EQ(sum->ran, 12 - before);  // done tasks are skipped
    EXPECT_EQ((*st)->counts()->done, 12);
    auto again = run_threads(s, **st, reg(), o);
    EXPECT_EQ(again->ran, 0);
  }
  Study quick = parse(std::string(kWmSmall) + "[part.quick]\npair = { count = 1 }\n", true);
  auto refused = Store::open(path, quick);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("another study definition"), std::string::npos);
  EXPECT_NE(refused.error().message.find("wm-small"), std::string::npos);
  auto existing = Store::open_existing(tmp("missing.sqlite"));
  EXPECT_FALSE(existing.ok());
}

TEST(StudyStore, UnavailableKindIsReportedOrSkipped) {
  Study s = parse(R"(
[study]
name = "mixed"
seed = 1
[[part]]
name = "theory"
kind = "koch-signature"
[part.parameters]
iterations = [0, 1]
alpha = 10.0
length = 0.01
[[part]]
name = "simulation"
kind = "future-engine"
[part.parameters]
iterations = [0, 1]
alpha = 10.0
)");
  const std::string path = tmp("mixed.sqlite");
  auto st = Store::open(path, s);
  ASSERT_TRUE(st.ok());
  RunOptions o;
  auto r = run_threads(s, **st, reg(), o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("task kind 'future-engine' is not available in this build"), std::string::npos);
  o.skip_unavailable = true;
  r = run_threads(s, **st, reg(), o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->ran, 2);
  EXPECT_EQ(r->skipped_unavailable, 2);
  EXPECT_EQ((*st)->counts()->pending, 2);
  // A later build that has the engine resumes the same store and runs only those tasks.
  TaskRegistry more = default_registry();
  more.add({"future-engine", "stand-in", 1, [](const Params&, std::uint64_t) -> frictal::Result<TaskOutput> {
              TaskOutput t;
              t.scalars["phi_deg"] = 1;
              return t;
            }});
  Study s2 = *parse_study(R"(
[study]
name = "mixed"
seed = 1
[[part]]
name = "theory"
kind = "koch-signature"
[part.parameters]
iterations = [0, 1]
alpha = 10.0
length = 0.01
[[part]]
name = "simulation"
kind = "future-engine"
[part.parameters]
iterations = [0, 1]
alpha = 10.0
)",
                          "t", false, more);
  // The placeholder declared version 1, as the engine will: same definition, same store.
  EXPECT_EQ(s2.hash, s.hash);
  auto reopened = Store::open(path, s2);
  ASSERT_TRUE(reopened.ok());
  o.skip_unavailable = false;
  r = run_threads(s2, **reopened, more, o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->ran, 2);
  EXPECT_EQ((*reopened)->counts()->done, 4);
}

TEST(StudyReport, VariantsAreAnalysedSeparately) {
  // Pairs are pooled over `pair` only; another axis (slopes) makes separate variants.
  Study s = parse(R"(
[study]
name = "variants"
seed = 5
[[part]]
name = "wm"
kind = "wm-pair-statistics"
seed_from = ["pair"]
[part.parameters]
dimension = [1.3, 1.7]
n_max = [2, 4, 6]
pair = { count = 1 }
slopes = ["exact", "spline"]
)");
  auto st = Store::open(tmp("variants.sqlite"), s);
  ASSERT_TRUE(st.ok());
  RunOptions o;
  o.threads = 2;
  ASSERT_TRUE(run_threads(s, **st, reg(), o).ok());
  auto rep = report(**st);
  ASSERT_TRUE(rep.ok());
  int exact = 0, spline = 0;
  for (const auto& f : rep->findings) {
    exact += f.claim.find("Part 'wm [slopes=exact]'") != std::string::npos;
    spline += f.claim.find("Part 'wm [slopes=spline]'") != std::string::npos;
  }
  // Seven claims per variant: contact below surface, slopes grow with D, with n_max, the contact
  // slope's limit, the slopes' spread grows with D, contact narrower than surface, rougher with D.
  EXPECT_EQ(exact, 7);
  EXPECT_EQ(spline, 7);
}

TEST(StudyReport, PooledPdfsRebinOntoCommonEdges) {
  // Two replicates with all their mass in [0, 1] and in [2, 3]: the common range is [0, 3] with
  // two bins of 1.5, so each bin holds half the pooled mass: density 0.5 / 1.5 = 1/3.
  TaskRegistry r = default_registry();
  r.add({"fake-pdf", "test", 1, [](const Params& p, std::uint64_t) -> frictal::Result<TaskOutput> {
           TaskOutput t;
           const bool first = std::get<std::int64_t>(p.at("pair")) == 0;
           t.arrays["x_pdf_edges_deg"] = first ? std::vector<double>{0, 1, 2} : std::vector<double>{1, 2, 3};
           t.arrays["x_pdf_density_per_deg"] = first ? std::vector<double>{1, 0} : std::vector<double>{0, 1};
           return t;
         }});
  auto s = parse_study(
      "[study]\nname='p'\nseed=1\n[[part]]\nname='f'\nkind='fake-pdf'\n[part.parameters]\n"
      "pair={count=2}\nD=[1.5]\n",
      "t", false, r);
  ASSERT_TRUE(s.ok());
  auto st = Store::open(tmp("pooled.sqlite"), *s);
  ASSERT_TRUE(st.ok());
  RunOptions o;
  ASSERT_TRUE(run_threads(*s, **st, r, o).ok());
  auto pooled = pooled_pdfs(**st, "f");
  ASSERT_TRUE(pooled.ok());
  ASSERT_EQ(pooled->size(), 1u);
  const PooledPdf& pp = pooled->front();
  EXPECT_EQ(pp.name, "x_pdf");
  EXPECT_EQ(pp.members, 2);
  EXPECT_EQ(canonical(pp.params), R"({"D":1.5})");
  ASSERT_EQ(pp.edges.size(), 3u);
  EXPECT_DOUBLE_EQ(pp.edges[1], 1.5);
  EXPECT_NEAR(pp.density[0], 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(pp.density[1], 1.0 / 3.0, 1e-15);
}

TEST(StudyStore, SerializeRoundTrip) {
  TaskRecord r;
  r.id = 42;
  r.status = TaskStatus::Done;
  r.wall_s = 0.25;
  r.worker = "rank 3";
  r.output.scalars["a"] = 1.0 / 3.0;
  r.output.scalars["nan"] = std::nan("");
  r.output.arrays["v"] = {1, -2.5, 1e-300};
  auto b = deserialize(serialize(r));
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(b->id, 42);
  EXPECT_EQ(b->worker, "rank 3");
  EXPECT_EQ(b->output.scalars.at("a"), 1.0 / 3.0);
  EXPECT_TRUE(std::isnan(b->output.scalars.at("nan")));
  EXPECT_EQ(b->output.arrays.at("v"), r.output.arrays.at("v"));
  std::string cut = serialize(r);
  cut.pop_back();
  EXPECT_FALSE(deserialize(cut).ok());
}
