// Every file under tests/data (measured files and fuzzing regressions) read through every reader,
// forced or detected: each read ends in a consistent result or an error that names the input
// and says something — never a crash, a hang or an inconsistent object. Run under ASan/UBSan by
// `make sanitize`. Crashing inputs found by `make fuzz` go to tests/data/fuzz-regressions/.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "frictal/io.hpp"

namespace {

std::vector<std::filesystem::path> data_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(FRICTAL_TEST_DATA))
    if (e.is_regular_file() && e.path().extension() != ".md") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ReadersOnEveryFile, EveryFormatEitherReadsConsistentlyOrNamesTheInput) {
  const auto files = data_files();
  ASSERT_GE(files.size(), 17u);  // the measured files of tests/data/README.md at least
  int reads = 0, errors = 0;
  for (const auto& path : files) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string bytes = ss.str();
    for (auto f : {frictal::ProfileFormat::Auto, frictal::ProfileFormat::Csv, frictal::ProfileFormat::Dektak,
                   frictal::ProfileFormat::Gwyddion, frictal::ProfileFormat::X3p}) {
      frictal::ReadOptions o;
      o.format = f;
      const std::string name = path.filename().string() + "@" + frictal::format_name(f);
      auto r = frictal::read_surface_bytes(bytes, name, o);
      if (!r) {
        ++errors;
        EXPECT_NE(r.error().message.find(name), std::string::npos)
            << "error does not name the input: " << r.error().message;
        continue;
      }
      ++reads;
      if (r->is_map) {
        EXPECT_EQ(r->map.nx * r->map.ny, r->map.heights.size()) << name;
      } else {
        EXPECT_EQ(r->curve.x.size(), r->curve.z.size()) << name;
        EXPECT_GE(r->curve.x.size(), 1u) << name;
      }
    }
  }
  // Each measured file reads under detection; most forced formats refuse other formats' files.
  EXPECT_GE(reads, static_cast<int>(files.size()) - 2);
  EXPECT_GT(errors, 0);
}

}  // namespace
