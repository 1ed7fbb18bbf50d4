// libFuzzer harness for frictal's readers: the bytes of one file, read as FRICTAL_FUZZ_FORMAT
// (auto = detection by content, as a user's file is read), then the result is used the way the
// CLI uses it (validation, profile statistics, envelopes), so that a reader that returns nonsense
// which later code trips over is found too. Built by `make fuzz` (clang, ASan + UBSan).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "frictal/geometry.hpp"
#include "frictal/io.hpp"
#include "frictal/map.hpp"
#include "frictal/stats.hpp"

#ifndef FRICTAL_FUZZ_FORMAT
#define FRICTAL_FUZZ_FORMAT Auto
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  frictal::ReadOptions o;
  o.format = frictal::ProfileFormat::FRICTAL_FUZZ_FORMAT;
  // Limits a user would set for a 2 GB machine; within them nothing may crash or leak.
  o.max_bytes = std::uint64_t(1) << 24;
  o.max_points = std::uint64_t(1) << 20;
  // A 1-D .npy array carries no spacing; without one it is an error and its profile is never
  // used. Other formats keep spacing 0, so that a single column stays an error there.
  if (o.format == frictal::ProfileFormat::Npy) o.spacing = 1e-6;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  auto r = frictal::read_surface_bytes(bytes, "fuzz-input", o);
  if (!r) {
    if (r.error().message.empty()) __builtin_trap();  // every error must say something
    return 0;
  }
  if (r->is_map) {
    const frictal::Map& m = r->map;
    if (m.nx * m.ny != m.heights.size()) __builtin_trap();  // a reader must return a consistent map
    (void)frictal::validate(m, "fuzz-map");
    if (m.nx > 1 && m.ny > 1) (void)frictal::interpolate(m, m.x0 + 0.5 * m.dx, m.y0 + 0.5 * m.dy);
  } else {
    const frictal::Curve& c = r->curve;
    if (c.x.size() != c.z.size()) __builtin_trap();
    if (frictal::validate(c, "fuzz-curve").ok() && c.size() >= 2 && c.size() < 20000) {
      auto env = frictal::upper_envelope(c);
      if (env) (void)frictal::profile_stats(*env);
    }
  }
  return 0;
}
