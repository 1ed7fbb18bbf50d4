// Downstream use of the installed frictal package: the paper's K2 Koch surface (Sec. III) has a
// maximal contact slope of 2 alpha (Fig. 4), so with mu_a = 0.2 Eq. 6 gives phi = 2 alpha +
// atan(0.2). Exits 0 only when the installed library says so.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <frictal/generators.hpp>
#include <frictal/signature.hpp>
#include <frictal/version.hpp>

int main() {
  const double alpha = 20.0 * std::numbers::pi / 180.0;
  frictal::KochParams p;
  p.iterations = 2;
  p.alpha = alpha;
  auto k2 = frictal::koch_profile(p);
  if (!k2) {
    std::fprintf(stderr, "koch_profile: %s\n", k2.error().message.c_str());
    return 1;
  }
  auto sig = frictal::self_signature(*k2);
  if (!sig) {
    std::fprintf(stderr, "self_signature: %s\n", sig.error().message.c_str());
    return 1;
  }
  const double theta = sig->theta_max_forward;
  const double phi = theta + std::atan(0.2);
  std::printf("%s: K2 alpha 20 deg: theta_max %.9f deg (expected 40), phi %.6f deg\n", frictal::version_line().c_str(),
              theta * 180.0 / std::numbers::pi, phi * 180.0 / std::numbers::pi);
  return std::abs(theta - 2.0 * alpha) < 1e-9 ? 0 : 1;
}
