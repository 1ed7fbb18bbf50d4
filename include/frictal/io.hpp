// frictal — reading and writing surfaces. Readers never trust the file: every problem is an
// Error naming the file, the line (or archive member) and what was expected.
#pragma once

#include <string>

#include "frictal/geometry.hpp"

namespace frictal {

enum class ProfileFormat {
  Auto,  ///< detect from content
  Csv,   ///< delimited text: CSV/TSV/whitespace, optional header and unit line
};

struct ReadOptions {
  ProfileFormat format = ProfileFormat::Auto;
};

/// Reads a line profile as a Curve in metres (x may be non-monotonic only for curve formats).
Result<Curve> read_curve(const std::string& path, const ReadOptions& options = {});
/// Reads a line profile and checks that it is single-valued (x non-decreasing).
Result<Profile> read_profile(const std::string& path, const ReadOptions& options = {});
/// Parses delimited text already in memory; `name` is used in messages.
Result<Curve> parse_curve_text(const std::string& text, const std::string& name);

/// Writes "x_m,z_m" CSV with full double precision (17 significant digits).
Status write_profile_csv(const std::string& path, const Curve& c);
Status write_profile_csv(const std::string& path, const Profile& p);

}  // namespace frictal
