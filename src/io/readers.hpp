// Private: the individual readers behind read_surface().
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "frictal/io.hpp"

namespace frictal::io_detail {

/// `text` is UTF-8 (already decoded).
bool looks_like_dektak(std::string_view text);
bool looks_like_gwyddion(std::string_view text);
/// Called now and then while a large text is parsed, with how far the parse has gone: the bytes
/// before that pointer are not needed again soon (a mapped file's pages can be given back; the
/// text stays readable). Reading a 10^7-point CSV then holds a fraction of the file at a time.
using ReleaseBehind = std::function<void(const char* upto)>;
Result<SurfaceData> parse_delimited(std::string_view text, const std::string& name, const ReadOptions& options,
                                    const ReleaseBehind* release = nullptr);
Result<SurfaceData> parse_dektak(std::string_view text, const std::string& name, const ReadOptions& options);
Result<SurfaceData> parse_gwyddion(std::string_view text, const std::string& name, const ReadOptions& options);

/// Content-detected native formats (formats.cpp).
bool looks_like_npy(const std::string& bytes);
bool looks_like_gzip(const std::string& bytes);
bool looks_like_sdf_text(std::string_view text);
Result<SurfaceData> read_npy_bytes(std::string_view bytes, const std::string& name, const ReadOptions& options);
Result<std::string> gunzip(const std::string& bytes, const std::string& name, std::uint64_t max_bytes);
Result<SurfaceData> parse_sdf_text(std::string_view text, const std::string& name, const ReadOptions& options);

/// Gwyddion backend (gwyddion.cpp): whether a module recognises the file; read it.
bool gwyddion_detects(const std::string& path, const std::string& module_dir);
Result<SurfaceData> read_gwyddion(const std::string& path, const ReadOptions& options);

/// `bytes` is the whole ZIP archive.
Result<SurfaceData> read_x3p_bytes(const std::string& bytes, const std::string& name, const ReadOptions& options);

}  // namespace frictal::io_detail
