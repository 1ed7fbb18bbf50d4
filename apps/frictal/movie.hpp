// frictal CLI — `tilt --movie FILE.mp4|FILE.gif`: renders the frames of a tilt run (both blocks,
// contact points and forces, time, tilt angle and atan(F_t/F_n)), each frame drawn with cairo,
// and pipes raw RGB frames to Debian's ffmpeg.
// The CLI owns this (the library never spawns processes).
#pragma once

#include <string>

#include "frictal/tilt.hpp"

namespace frictal::cli {

/// Writes the movie of `r` (which needs frames) to `path` (.mp4 or .gif) at `fps` frames per
/// second. `radius`: the spheroradius drawn as the blocks' rims (m). Throws CliError on failure.
/// The full path of `program` on PATH, or "" when it is not there.
std::string find_on_path(const std::string& program);

/// Checks `--movie PATH` before a run: a .mp4 or .gif name and ffmpeg on PATH (throws UsageError).
void check_movie_tool(const std::string& path);

void write_tilt_movie(const std::string& path, const TiltResult& r, double radius, int fps = 25);

}  // namespace frictal::cli
