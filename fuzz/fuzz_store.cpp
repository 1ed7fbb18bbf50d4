// libFuzzer harness for the study store reader: the bytes of one file written to a temporary
// file, opened as a store (Store::open_existing), then what `frictal study status` and
// `frictal study export` do with it (status, report, CSV export into a temporary directory).
// Built by `make fuzz`.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "frictal/study.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  static const frictal::study::TaskRegistry registry = frictal::study::default_registry();
  // On a RAM file system when there is one (an SQLite file per execution).
  static const fs::path dir = (fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path()) /
                              ("frictal-fuzz-store-" + std::to_string(::getpid()));
  static const std::string path = (dir / "store.sqlite").string();
  static const std::string out = (dir / "export").string();
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir, ec);
  {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  {
    auto st = frictal::study::Store::open_existing(path);
    if (!st) {
      if (st.error().message.empty()) __builtin_trap();
    } else {
      auto& store = **st;
      auto status = frictal::study::store_status(store, registry);
      if (status && status->tasks.total != status->tasks.done + status->tasks.failed + status->tasks.pending)
        __builtin_trap();
      (void)store.tasks();
      (void)store.content();
      auto files = frictal::study::export_csv(store, out, registry);
      if (files) {
        // Nothing is written outside the export directory.
        for (const auto& name : *files)
          if (!fs::exists(fs::path(out) / name) || fs::path(name).has_parent_path()) __builtin_trap();
      } else if (files.error().message.empty()) {
        __builtin_trap();
      }
    }
  }
  fs::remove_all(dir, ec);
  return 0;
}
