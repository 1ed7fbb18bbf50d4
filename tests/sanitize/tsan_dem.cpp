// ThreadSanitizer check of the DEM worker team (`make tsan-dem`, scripts/tsan-dem): two sawtooth blocks
// (5 cm, 401 points, 17 deg flanks) land and slide on a tilting block, stepped on 1 thread and on
// 3 (shares of >= 1 hot pair, so every member works), compared bit for bit at every step. Built
// from the engine sources alone with -fsanitize=thread (not part of the CTest build: TSan cannot
// be mixed with the ASan/UBSan `sanitize` preset). Exit 0 and "ok" when clean.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>
#include "frictal/dem.hpp"
using namespace frictal::dem;
int main() {
  const int n = 400;
  const double L = 0.05, lam = 0.0025, a = 0.3;
  std::vector<double> fx, fz;
  for (int i = 0; i <= n; ++i) {
    double x = L * i / n;
    double ph = std::fmod(x, lam) / lam;
    fx.push_back(x);
    fz.push_back(lam * std::tan(a) * (ph < 0.5 ? ph : 1 - ph));
  }
  double zmax = 0;
  for (double z : fz) zmax = std::max(zmax, z);
  BodyDef lo, up;
  lo.x = fx;
  lo.y = fz;
  lo.x.push_back(L);
  lo.y.push_back(-0.005);
  lo.x.push_back(0);
  lo.y.push_back(-0.005);
  lo.type = BodyType::Kinematic;
  lo.motion.angular_velocity = -0.5;
  lo.motion.start_time = 0.01;
  for (int i = n; i >= 0; --i) {
    up.x.push_back(L - fx[i] + 3e-4);
    up.y.push_back(-fz[i] + 2 * zmax + 1e-4);
  }
  up.x.push_back(up.x.back());
  up.y.push_back(3 * zmax + 0.005);
  up.x.push_back(up.x.front());
  up.y.push_back(3 * zmax + 0.005);
  WorldDef wd;
  wd.adaptive_time_step = true;
  wd.implicit_damping = true;
  wd.time_step = 1e-4;
  auto m = make_model(wd, {lo, up});
  if (!m.ok()) {
    std::printf("model: %s\n", m.error().message.c_str());
    return 1;
  }
  Model model = *m;
  model.motion[0].pivot = model.initial_position[0];
  State s1 = make_state(model), s3 = make_state(model);
  set_thread_count(s3, 3, 1, false);  // every step that can be split is split (no tuner)
  int maxc = 0;
  for (int i = 0; i < 2000; ++i) {
    if (!step(model, s1).ok() || !step(model, s3).ok()) {
      std::printf("step failed\n");
      return 1;
    }
    maxc = std::max(maxc, s1.contact_count);
    if (std::memcmp(s1.position.data(), s3.position.data(), 2 * sizeof(Vec2)) ||
        s1.elastic_energy != s3.elastic_energy) {
      std::printf("differ at %d\n", i);
      return 1;
    }
  }
  std::printf("ok: max contacts %d, split steps %llu\n", maxc, (unsigned long long)s3.timings.split_steps);
  return 0;
}
