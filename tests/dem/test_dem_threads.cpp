// Threads in the spheropolygon engine (dem::set_thread_count, TiltConfig::threads): the thread
// count never changes a result. Independent reference: the same run on one thread (the serial
// passes, unchanged); every compared value must be equal bit for bit (memcmp / EXPECT_EQ on
// doubles, no tolerance). Also the worker team's life cycle (util::Team).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include "frictal/dem.hpp"
#include "frictal/generators.hpp"
#include "frictal/tilt.hpp"
#include "util/team.hpp"

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

frictal::Curve koch(int n, double alpha_deg, double length) {
  frictal::KochParams p;
  p.iterations = n;
  p.alpha = alpha_deg * kDeg;
  p.wavelength = 0.01;
  p.length = length;
  auto c = frictal::koch_curve(p);
  EXPECT_TRUE(c.ok());
  return *c;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every number of a TiltResult that the run computes (not the wall times).
void expect_same_result(const frictal::TiltResult& a, const frictal::TiltResult& b, unsigned threads) {
  SCOPED_TRACE(testing::Message() << threads << " threads");
  EXPECT_EQ(a.slid, b.slid);
  EXPECT_TRUE(same_bits(a.friction_angle, b.friction_angle)) << a.friction_angle << " " << b.friction_angle;
  EXPECT_TRUE(same_bits(a.slide_time, b.slide_time));
  EXPECT_TRUE(same_bits(a.slide_start_displacement, b.slide_start_displacement));
  EXPECT_TRUE(same_bits(a.final_displacement, b.final_displacement));
  EXPECT_TRUE(same_bits(a.predicted_friction_angle, b.predicted_friction_angle));
  EXPECT_TRUE(same_bits(a.predicted_sphero_friction_angle, b.predicted_sphero_friction_angle));
  EXPECT_TRUE(same_bits(a.initial_offset, b.initial_offset));
  EXPECT_TRUE(same_bits(a.rotation_before_slide, b.rotation_before_slide));
  EXPECT_TRUE(same_bits(a.simulated_time, b.simulated_time));
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.steps_beyond_limit, b.steps_beyond_limit);
  EXPECT_TRUE(same_bits(a.min_time_step, b.min_time_step));
  EXPECT_TRUE(same_bits(a.max_time_step, b.max_time_step));
  EXPECT_TRUE(same_bits(a.settled_overlap, b.settled_overlap));
  EXPECT_EQ(a.settled_contacts, b.settled_contacts);
  EXPECT_TRUE(same_bits(a.settled_speed, b.settled_speed));
  EXPECT_EQ(a.timings.list_builds, b.timings.list_builds);
  EXPECT_EQ(a.timings.pairs_evaluated, b.timings.pairs_evaluated);
  EXPECT_EQ(a.timings.hot_refreshes, b.timings.hot_refreshes);
  const frictal::TiltSeries &s = a.series, &t = b.series;
  EXPECT_TRUE(same_bits(s.time, t.time));
  EXPECT_TRUE(same_bits(s.tilt, t.tilt));
  EXPECT_TRUE(same_bits(s.normal_force, t.normal_force));
  EXPECT_TRUE(same_bits(s.tangential_force, t.tangential_force));
  EXPECT_TRUE(same_bits(s.force_angle, t.force_angle));
  EXPECT_TRUE(same_bits(s.displacement, t.displacement));
  EXPECT_TRUE(same_bits(s.velocity, t.velocity));
  EXPECT_TRUE(same_bits(s.contacts, t.contacts));
  ASSERT_EQ(a.warnings.size(), b.warnings.size());
  for (std::size_t i = 0; i < a.warnings.size(); ++i) EXPECT_EQ(a.warnings[i].message, b.warnings[i].message);
}

// Two blocks with K2 faces (alpha = 25 deg, 5 cm long) as in the tilt test, the upper one (the
// face turned over, shifted by 1.3 mm) dropped from 0.1 mm above the lower one's highest point,
// the lower one tilting fast (0.5 rad/s): contacts come, go and slide.
frictal::dem::Model k2_blocks() {
  const frictal::Curve c = koch(2, 25, 0.05);
  double zmin = 1e9, zmax = -1e9;
  for (double z : c.z) zmin = std::min(zmin, z), zmax = std::max(zmax, z);
  frictal::dem::BodyDef lower, upper;
  lower.x = c.x;
  lower.y = c.z;
  lower.x.push_back(c.x.back());
  lower.y.push_back(zmin - 0.005);
  lower.x.push_back(c.x.front());
  lower.y.push_back(zmin - 0.005);
  lower.type = frictal::dem::BodyType::Kinematic;
  lower.motion.angular_velocity = -0.5;
  lower.motion.start_time = 0.01;
  // Upper: the same face turned over (x -> L - x, z -> -z), left to right, its lowest point
  // 0.1 mm above the lower face's highest.
  const double length = c.x.back();
  for (std::size_t i = c.x.size(); i-- > 0;) {
    upper.x.push_back(length - c.x[i] + 1.3e-3);
    upper.y.push_back(-c.z[i] + 2 * zmax + 1e-4);
  }
  double top = -1e9;
  for (double y : upper.y) top = std::max(top, y);
  upper.x.push_back(upper.x.back());
  upper.y.push_back(top + 0.005);
  upper.x.push_back(upper.x.front());
  upper.y.push_back(top + 0.005);
  frictal::dem::WorldDef wd;
  wd.adaptive_time_step = true;
  wd.implicit_damping = true;
  wd.time_step = 1e-4;
  auto m = frictal::dem::make_model(wd, {lower, upper});
  EXPECT_TRUE(m.ok()) << (m.ok() ? "" : m.error().message);
  frictal::dem::Model model = std::move(*m);
  model.motion[0].pivot = model.initial_position[0];
  return model;
}

}  // namespace

// Engine level: every step of a K2 pair landing and sliding, split over 2, 3 and 4 threads with
// shares of at least 1, 8 and 64 hot pairs (1: the smallest shares, every member busy), equals
// the serial step bit for bit: poses, velocities, forces, torques, energy, contacts, springs.
TEST(DemThreads, EveryStepEqualsTheSerialStep) {
  const frictal::dem::Model m = k2_blocks();
  frictal::dem::State serial = frictal::dem::make_state(m);
  struct Run {
    unsigned threads, min_pairs;
    bool tune;
    frictal::dem::State st;
  };
  std::vector<Run> runs;
  for (unsigned t : {2u, 3u, 4u})
    for (unsigned min_pairs : {1u, 8u, 64u}) {
      runs.push_back({t, min_pairs, false, frictal::dem::make_state(m)});
      frictal::dem::set_thread_count(runs.back().st, t, min_pairs, false);
      EXPECT_EQ(frictal::dem::thread_count(runs.back().st), t);
    }
  // With the tuner (serial and split steps alternate as timed; every choice gives the same step).
  runs.push_back({2, 1, true, frictal::dem::make_state(m)});
  frictal::dem::set_thread_count(runs.back().st, 2, 1, true);
  int max_contacts = 0;
  for (int i = 0; i < 3000; ++i) {
    ASSERT_TRUE(frictal::dem::step(m, serial).ok()) << i;
    max_contacts = std::max(max_contacts, serial.contact_count);
    for (Run& r : runs) {
      SCOPED_TRACE(testing::Message() << r.threads << " threads, >= " << r.min_pairs << " pairs, tune " << r.tune
                                      << ", step " << i);
      ASSERT_TRUE(frictal::dem::step(m, r.st).ok());
      ASSERT_TRUE(same_bits(r.st.time, serial.time));
      ASSERT_TRUE(same_bits(r.st.time_step, serial.time_step));
      ASSERT_EQ(r.st.contact_count, serial.contact_count);
      ASSERT_TRUE(same_bits(r.st.elastic_energy, serial.elastic_energy));
      ASSERT_TRUE(same_bits(r.st.max_overlap, serial.max_overlap));
      ASSERT_EQ(std::memcmp(r.st.position.data(), serial.position.data(), 2 * sizeof(frictal::dem::Vec2)), 0);
      ASSERT_EQ(std::memcmp(r.st.velocity.data(), serial.velocity.data(), 2 * sizeof(frictal::dem::Vec2)), 0);
      ASSERT_EQ(std::memcmp(r.st.force.data(), serial.force.data(), 2 * sizeof(frictal::dem::Vec2)), 0);
      ASSERT_TRUE(same_bits(r.st.angle, serial.angle));
      ASSERT_TRUE(same_bits(r.st.angular_velocity, serial.angular_velocity));
      ASSERT_TRUE(same_bits(r.st.torque, serial.torque));
      ASSERT_TRUE(same_bits(r.st.step_limit, serial.step_limit));
      ASSERT_EQ(r.st.pairs.size(), serial.pairs.size());
      for (std::size_t k = 0; k < serial.pairs.size(); ++k) {
        ASSERT_TRUE(same_bits(r.st.pairs[k].elongation, serial.pairs[k].elongation));
        ASSERT_TRUE(same_bits(r.st.pairs[k].overlap, serial.pairs[k].overlap));
      }
    }
  }
  // The run exercised what it should: the blocks touched with many contacts, and the steps were
  // split (all but the full passes with shares of >= 1 pair; never with shares of >= 64 here).
  EXPECT_GT(max_contacts, 20);
  EXPECT_EQ(serial.timings.split_steps, 0u);
  for (const Run& r : runs) {
    SCOPED_TRACE(testing::Message() << r.threads << " threads, >= " << r.min_pairs << " pairs");
    if (r.tune) {
      EXPECT_GT(r.st.timings.split_steps, 0u);  // the tuner tried split steps
      continue;
    }
    if (r.min_pairs == 1) {
      EXPECT_GT(r.st.timings.split_steps, 2000u);
    } else if (r.min_pairs == 8) {
      EXPECT_GT(r.st.timings.split_steps, 1000u);
    } else {
      EXPECT_EQ(r.st.timings.split_steps, 0u);
    }
  }
  // A copy continues bitwise like the original (without the original's team).
  frictal::dem::State copy = runs.front().st;
  EXPECT_EQ(frictal::dem::thread_count(copy), runs.front().threads);
  for (int i = 0; i < 200; ++i) {
    ASSERT_TRUE(frictal::dem::step(m, copy).ok());
    ASSERT_TRUE(frictal::dem::step(m, serial).ok());
  }
  EXPECT_EQ(std::memcmp(copy.position.data(), serial.position.data(), 2 * sizeof(frictal::dem::Vec2)), 0);
  EXPECT_TRUE(same_bits(copy.elastic_energy, serial.elastic_energy));
}

// The tilt test on K3 (alpha = 20 deg; ~250 hot pairs, split over up to 3 threads by the default
// share of 64) up to 3 degrees of tilt, with the set-up's two predictions (side by side from 2
// threads on): the same TiltResult, series included, for 1, 2, 3 and 4 threads.
TEST(DemThreads, K3TiltIsTheSameForOneToFourThreads) {
  const frictal::Curve c = koch(3, 20, 0.2);
  frictal::TiltConfig cfg = frictal::tilt_config_for_surface(0.01, 0.01);
  cfg.max_tilt = 3 * kDeg;
  auto one = frictal::run_tilt(c, c, cfg);
  ASSERT_TRUE(one.ok()) << one.error().message;
  EXPECT_GT(one->timings.pairs_evaluated, 128u * one->steps);  // enough hot pairs to split
  EXPECT_EQ(one->timings.split_steps, 0u);
  EXPECT_GT(one->series.time.size(), 300u);
  for (int threads : {2, 3, 4}) {
    frictal::TiltConfig ct = cfg;
    ct.threads = threads;
    auto r = frictal::run_tilt(c, c, ct);
    ASSERT_TRUE(r.ok()) << r.error().message;
    expect_same_result(*one, *r, static_cast<unsigned>(threads));
    // Split in the tuner's trial windows at least, in all if it pays.
    EXPECT_GT(r->timings.split_steps, 0u);
  }
}

// A whole tilt to the run-away on the kind of random pair (WM, D = 1.5, rms 1e-5 m; ~1900
// hot pairs) and the thread budget of a study (TiltConfig::thread_budget, changing every call):
// the same friction angle, steps and series, bit for bit.
TEST(DemThreads, WmTiltToTheRunawayIsTheSameWithABudget) {
  frictal::WmParams w;
  w.dimension = 1.5;
  w.n_max = 6;
  w.longest_wavelength = 0.01;
  w.length = 0.1;
  w.rms_height = 1e-5;
  w.seed = 1;
  auto lower = frictal::wm_profile(w);
  w.seed = 2;
  auto upper = frictal::wm_profile(w);
  ASSERT_TRUE(lower.ok() && upper.ok());
  const frictal::Curve lc = frictal::as_curve(*lower), uc = frictal::as_curve(*upper);
  frictal::TiltConfig cfg = frictal::tilt_config_for_surface(0, 0.01);
  cfg.radius = 2e-5;
  cfg.runaway_distance = 0.002;
  auto one = frictal::run_tilt(lc, uc, cfg);
  ASSERT_TRUE(one.ok()) << one.error().message;
  ASSERT_TRUE(one->slid);
  frictal::TiltConfig two = cfg;
  two.threads = 2;
  auto r2 = frictal::run_tilt(lc, uc, two);
  ASSERT_TRUE(r2.ok()) << r2.error().message;
  expect_same_result(*one, *r2, 2);
  EXPECT_GT(r2->timings.split_steps, 0u);
  frictal::TiltConfig budget = cfg;
  unsigned calls = 0;
  budget.thread_budget = [&calls](unsigned) { return 1 + (calls++ % 3); };  // 1, 2, 3, 1, ...
  auto rb = frictal::run_tilt(lc, uc, budget);
  ASSERT_TRUE(rb.ok()) << rb.error().message;
  EXPECT_GT(calls, 2u);
  expect_same_result(*one, *rb, 0);
  EXPECT_GT(rb->timings.split_steps, 0u);
}

// The team starts and stops cleanly, many times over: short runs (each state starts a team and
// joins it), and util::Team on its own (sections of every size, workers asleep or spinning when
// it is destroyed).
TEST(DemThreads, TeamsStartAndStopCleanly) {
  const frictal::dem::Model m = k2_blocks();
  frictal::dem::State base = frictal::dem::make_state(m);
  ASSERT_TRUE(frictal::dem::advance(m, base, 400).ok());  // in contact
  for (int i = 0; i < 100; ++i) {
    frictal::dem::State st = base;
    frictal::dem::set_thread_count(st, 2 + static_cast<unsigned>(i % 3), 1, false);
    ASSERT_TRUE(frictal::dem::advance(m, st, 5).ok());
    if (i % 10 == 0) frictal::dem::set_thread_count(st, 1);  // drops the team
  }
  for (unsigned members = 1; members <= 4; ++members) {
    for (int rep = 0; rep < 20; ++rep) {
      frictal::util::Team team(members);
      EXPECT_EQ(team.members(), members);
      std::vector<std::atomic<int>> hits(members);
      struct Ctx {
        std::vector<std::atomic<int>>* hits;
      } ctx{&hits};
      for (int s = 0; s < 50; ++s) {
        const unsigned n = 1 + static_cast<unsigned>(s) % members;
        team.run(
            n, [](void* c, unsigned j) { (*static_cast<Ctx*>(c)->hits)[j].fetch_add(1); }, &ctx);
      }
      int total = 0;
      for (auto& h : hits) total += h.load();
      int expected = 0;
      for (int s = 0; s < 50; ++s) expected += 1 + s % static_cast<int>(members);
      EXPECT_EQ(total, expected);
      if (rep % 2) std::this_thread::sleep_for(std::chrono::microseconds(200));  // workers asleep
    }
  }
}
