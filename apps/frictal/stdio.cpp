// frictal CLI — "-" as a file name: standard input for inputs, standard output for -o (common.hpp).
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "common.hpp"

namespace frictal::cli {
namespace {

/// A temporary file removed at exit.
struct TempFile {
  std::string path;
  TempFile() {
    const char* dir = std::getenv("TMPDIR");
    std::string tmpl = std::string(dir && *dir ? dir : "/tmp") + "/frictal-XXXXXX";
    const int fd = ::mkstemp(tmpl.data());
    if (fd < 0) throw UsageError("cannot create a temporary file for '-' (set TMPDIR to a writable folder)");
    ::close(fd);
    path = tmpl;
  }
  ~TempFile() { std::remove(path.c_str()); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
};

TempFile*& stdin_copy() {
  static TempFile* t = nullptr;
  return t;
}

}  // namespace

std::string input_path(const std::string& path) {
  if (path != "-") return path;
  if (!stdin_copy()) {
    static TempFile file;  // removed at exit
    std::ofstream out(file.path, std::ios::binary);
    out << std::cin.rdbuf();
    if (!out) throw UsageError("-: cannot copy standard input to a temporary file");
    stdin_copy() = &file;
  }
  return stdin_copy()->path;
}

std::string stdin_name(std::string message) {
  if (!stdin_copy()) return message;
  const std::string& p = stdin_copy()->path;
  for (std::size_t at = message.find(p); at != std::string::npos; at = message.find(p, at + 1))
    message.replace(at, p.size(), "-");
  return message;
}

void write_output(const std::string& path, const std::function<Status(const std::string&)>& write,
                  const std::string& option) {
  if (path != "-") {
    if (Status s = write(path); !s) throw UsageError(option + ": " + s.error().message, s.error().code);
    return;
  }
  TempFile file;
  if (Status s = write(file.path); !s) throw UsageError(option + " -: " + s.error().message, s.error().code);
  std::ifstream in(file.path, std::ios::binary);
  std::fflush(stdout);
  std::cout << in.rdbuf();
  std::cout.flush();
  if (!std::cout) throw UsageError(option + " -: cannot write to standard output");
}

void write_text_output(const std::string& path, const std::string& text, const std::string& option) {
  if (path == "-") {
    std::fflush(stdout);
    std::cout << text;
    std::cout.flush();
    if (!std::cout) throw UsageError(option + " -: cannot write to standard output");
    return;
  }
  std::ofstream f(path, std::ios::binary);
  if (!f) throw UsageError(fmt::format("{} {}: cannot open for writing", option, path));
  f << text;
  if (!f) throw UsageError(fmt::format("{} {}: write failed", option, path));
}

void write_text_rows(const std::string& path, const std::string& header, std::size_t rows,
                     const std::function<void(std::string& out, std::size_t i)>& row, const std::string& option) {
  const bool to_stdout = path == "-";
  std::ofstream f;
  if (!to_stdout) {
    f.open(path, std::ios::binary);
    if (!f) throw UsageError(fmt::format("{} {}: cannot open for writing", option, path));
  } else {
    std::fflush(stdout);
  }
  std::ostream& out = to_stdout ? std::cout : static_cast<std::ostream&>(f);
  std::string buf = header;
  constexpr std::size_t kPiece = std::size_t{1} << 20;
  buf.reserve(kPiece + 4096);
  auto flush = [&]() {
    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    buf.clear();
    if (!out)
      throw UsageError(to_stdout ? option + " -: cannot write to standard output"
                                 : fmt::format("{} {}: write failed", option, path));
  };
  for (std::size_t i = 0; i < rows; ++i) {
    row(buf, i);
    if (buf.size() >= kPiece) flush();
  }
  flush();
  out.flush();
  if (!out)
    throw UsageError(to_stdout ? option + " -: cannot write to standard output"
                               : fmt::format("{} {}: write failed", option, path));
}

}  // namespace frictal::cli
