// Downstream use of the installed frictal package: the paper's K2 Koch surface (Sec. III) has a
// maximal contact slope of 2 alpha (Fig. 4), so with mu_a = 0.2 Eq. 6 gives phi = 2 alpha +
// atan(0.2). The contact module's FFTW (a dependency the installed package brings along): the
// wavy surface z = D cos(2 pi x / L) in full contact carries the pressure pbar + pi E* D / L at its
// crest (Johnson). Exits 0 only when the installed library says so.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <frictal/contact.hpp>
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
  frictal::Profile wave;
  for (int i = 0; i < 256; ++i) {
    wave.x.push_back(i * 1e-3 / 256);
    wave.z.push_back(1e-6 * std::cos(2 * std::numbers::pi * i / 256.0));
  }
  wave.period = 1e-3;
  frictal::ContactOptions o;
  o.contact_modulus = 1e9;
  const double pstar = std::numbers::pi * 1e9 * 1e-6 / 1e-3;
  auto c = frictal::solve_contact(wave, {frictal::ContactLoadKind::Pressure, 2 * pstar}, o);
  if (!c) {
    std::fprintf(stderr, "solve_contact: %s\n", c.error().message.c_str());
    return 1;
  }
  std::printf("wavy surface in full contact: peak pressure %.6g Pa (expected %.6g)\n", c->max_pressure, 3 * pstar);
  if (std::abs(c->max_pressure / (3 * pstar) - 1) > 1e-6) return 1;
  return std::abs(theta - 2.0 * alpha) < 1e-9 ? 0 : 1;
}
