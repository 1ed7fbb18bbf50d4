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
    if (e.is_regular_file() && e.path().extension() != ".md" && e.path().parent_path().filename() != "LICENSES")
      files.push_back(e.path());  // LICENSES/: the licence notices of the files, not inputs
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
                   frictal::ProfileFormat::Gwyddion, frictal::ProfileFormat::X3p, frictal::ProfileFormat::Sdf,
                   frictal::ProfileFormat::Npy}) {
      frictal::ReadOptions o;
      o.format = f;
      if (f == frictal::ProfileFormat::Npy) o.spacing = 1e-6;  // as in fuzz/fuzz_reader.cpp
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

std::string slurp(const std::string& name) {
  std::ifstream in(std::filesystem::path(FRICTAL_TEST_DATA) / "fuzz-regressions" / name, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Found by fuzz_read_npy: a dtype whose item size has ten digits ("f4294967296, ...") does not fit
// the int that parses it (UBSan: signed integer overflow).
TEST(FuzzRegressions, NpyDtypeWithAHugeItemSizeIsUnsupported) {
  const std::string bytes = slurp("npy-dtype-size-overflow.npy");
  ASSERT_FALSE(bytes.empty());
  for (auto f : {frictal::ProfileFormat::Auto, frictal::ProfileFormat::Npy}) {
    frictal::ReadOptions o;
    o.format = f;
    auto r = frictal::read_surface_bytes(bytes, "big-dtype.npy", o);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("big-dtype.npy: .npy dtype"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("is not supported"), std::string::npos) << r.error().message;
  }
}

// Found by fuzz_read_sdf: NumPoints = 1e308 is a whole number, but converting it to a 64-bit
// integer was undefined (UBSan: outside the range of long long). A count must be below 2^62.
TEST(FuzzRegressions, SdfCountBeyondAnyIntegerIsAnError) {
  const std::string bytes = slurp("sdf-numpoints-1e308.sdf");
  ASSERT_FALSE(bytes.empty());
  frictal::ReadOptions o;
  o.format = frictal::ProfileFormat::Sdf;
  auto r = frictal::read_surface_bytes(bytes, "huge.sdf", o);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("numpoints = '1e308' is not a positive integer"), std::string::npos)
      << r.error().message;
  auto ok = frictal::read_surface_bytes(
      "aBCR-1.0\nNumPoints = 2\nNumProfiles = 1\nXscale = 1\nYscale = 1\nZscale = 1\n*\n1 2\n", "small.sdf", o);
  EXPECT_TRUE(ok.ok()) << ok.error().message;
}

}  // namespace
