// Error and Result: context added to an error keeps its code, and no code in
// src/ or apps/ rebuilds an error from another's message with a fixed code.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "frictal/result.hpp"

using frictal::Error;
using frictal::ErrorCode;

TEST(Result, WithPrefixKeepsTheCode) {
  for (ErrorCode c :
       {ErrorCode::InvalidInput, ErrorCode::Io, ErrorCode::Unstable, ErrorCode::NotAvailable, ErrorCode::Internal}) {
    const Error e = frictal::with_prefix("lower surface: ", frictal::make_error("disk gone", c));
    EXPECT_EQ(e.code, c);
    EXPECT_EQ(e.message, "lower surface: disk gone");
  }
}

// `make_error("context: " + r.error().message)` drops r's code (it becomes InvalidInput): such
// rewraps are written with_prefix("context: ", r.error()) (or pass the code on explicitly).
TEST(Result, NoRewrapResetsTheCode) {
  const std::filesystem::path root = std::filesystem::path(FRICTAL_TEST_DATA).parent_path().parent_path();
  // make_error( or UsageError( whose first argument concatenates another error's message.
  const std::regex rewrap(
      R"((make_error|UsageError)\(\s*[^;,()]*(\([^()]*\))?[^;,()]*\+\s*\w+(\.error\(\)|)\.message\s*\))");
  std::vector<std::string> found;
  std::size_t files = 0;
  for (const char* dir : {"src", "apps"})
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root / dir)) {
      const auto ext = entry.path().extension();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp")) continue;
      ++files;
      std::ifstream in(entry.path());
      std::stringstream ss;
      ss << in.rdbuf();
      const std::string text = ss.str();
      for (auto it = std::sregex_iterator(text.begin(), text.end(), rewrap); it != std::sregex_iterator(); ++it)
        found.push_back(entry.path().lexically_relative(root).string() + ": " + it->str());
    }
  EXPECT_GT(files, 50u) << "source tree not found under " << root;
  for (const auto& f : found) ADD_FAILURE() << "error rebuilt with a fixed code (use with_prefix): " << f;
  // The pattern itself finds the form it is meant to find.
  EXPECT_TRUE(std::regex_search(std::string(R"(return make_error("hold angle: " + hold.error().message);)"), rewrap));
  EXPECT_TRUE(
      std::regex_search(std::string(R"(return make_error(std::string(what) + ": " + e.error().message);)"), rewrap));
  EXPECT_TRUE(
      std::regex_search(std::string(R"(throw UsageError("--start-offset: " + node.error().message);)"), rewrap));
  EXPECT_FALSE(
      std::regex_search(std::string(R"(throw UsageError("x: " + s.error().message, s.error().code);)"), rewrap));
}
