// libFuzzer harness for the study TOML parser: the bytes of one study file, parsed with the
// default registry at both scales (first byte's low bit picks), and a parsed study's grid used
// the way a run uses it (definition hash, task keys and seeds). Built by `make fuzz`.
#include <cstddef>
#include <cstdint>
#include <string>

#include "frictal/study.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const frictal::study::TaskRegistry registry = frictal::study::default_registry();
  const std::string text(reinterpret_cast<const char*>(data), size);
  const bool quick = size > 0 && (data[0] & 1);
  // At most 10^4 tasks: a few bytes can define a grid of millions of tasks, each legitimately
  // built (the limit, 10^7 by default, is what stops a larger one); building 10^5 of them took
  // 11 s under ASan (a libFuzzer timeout, not a hang). The limit's own paths are still fuzzed.
  auto s = frictal::study::parse_study(text, "fuzz.toml", quick, registry, 10000);
  if (!s) {
    if (s.error().message.empty()) __builtin_trap();  // every error must say something
    return 0;
  }
  // A parsed study is consistent: ids in order, kinds known, keys unique per part grid.
  std::int64_t id = 0;
  for (const auto& t : s->tasks) {
    if (t.id != id++) __builtin_trap();
    if (registry.version(t.kind) == 0) __builtin_trap();
    if (t.key.empty()) __builtin_trap();
  }
  if (s->hash != frictal::study::digest(s->definition)) __builtin_trap();
  return 0;
}
