// Writes the seed store of fuzz_store: a tiny study (2 parts, 5 tasks: koch-signature and
// divider, a few milliseconds) run into an SQLite store. Usage: make_store_seed OUT.sqlite
#include <cstdio>
#include <string>

#include "frictal/study.hpp"

int main(int argc, char** argv) {
  using namespace frictal::study;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.sqlite\n", argv[0]);
    return 2;
  }
  const char* text = R"(
[study]
name = "fuzz-seed"
seed = 1
[[part]]
name = "theory"
kind = "koch-signature"
[part.parameters]
iterations = [0, 1, 2]
alpha = 10.0
[[part]]
name = "dimension"
kind = "divider"
[part.parameters]
iterations = [1, 2]
alpha = 20.0
)";
  const TaskRegistry reg = default_registry();
  auto study = parse_study(text, "seed.toml", false, reg);
  if (!study) return std::fprintf(stderr, "%s\n", study.error().message.c_str()), 1;
  for (const char* s : {"", "-wal", "-shm"}) std::remove((std::string(argv[1]) + s).c_str());
  auto store = Store::open(argv[1], *study);
  if (!store) return std::fprintf(stderr, "%s\n", store.error().message.c_str()), 1;
  RunOptions o;
  o.threads = 1;
  auto sum = run_threads(*study, **store, reg, o);
  if (!sum) return std::fprintf(stderr, "%s\n", sum.error().message.c_str()), 1;
  return 0;
}
