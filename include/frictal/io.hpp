// frictal — reading and writing surfaces. Readers never trust the file: every problem is an
// Error naming the file, the line (or archive member) and what was expected. Sizes are checked
// against limits before anything is allocated. Formats and quirks: docs/io.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "frictal/geometry.hpp"
#include "frictal/map.hpp"
#include "frictal/outputs.hpp"
#include "frictal/result.hpp"

namespace frictal {

enum class ProfileFormat {
  Auto,         ///< detect from content
  Csv,          ///< delimited text: CSV/TSV/whitespace, optional header and unit line
  Dektak,       ///< Bruker Dektak CSV export (metadata block, "Scan Data" section)
  Gwyddion,     ///< Gwyddion "export as text" matrix (# Width/Height/Value units header) or plain matrix
  X3p,          ///< ISO 25178-71 X3P (ZIP with main.xml), profiles (PRF) and areal maps (SUR)
  Matrix,       ///< text matrix of heights, with or without a small "w= h=" / "x-pixels =" header
  Xyz,          ///< text x, y, z point list lying on a regular grid
  Sdf,          ///< ISO 25178-71 SDF / BCR surface data file, ASCII (aISO-1.0, aBCR-1.0)
  Npy,          ///< NumPy .npy array (1-D: profile at ReadOptions::spacing, 2-D: map)
  GwyddionLib,  ///< any file a Gwyddion file module loads, through Gwyddion's libraries
};

/// Name of a format ("auto", "csv", "dektak", "gwyddion", "x3p", "matrix", "xyz", "sdf", "npy",
/// "gwyddion-lib").
const char* format_name(ProfileFormat f);
/// Parses a format name (case-insensitive); error naming the accepted names.
Result<ProfileFormat> parse_format(const std::string& name);

struct ReadOptions {
  ProfileFormat format = ProfileFormat::Auto;
  /// Unit assumed for text columns that carry no unit ("m", "mm", "um", "nm"; empty = metres).
  std::string default_unit;
  /// The unit of the file's numbers, overriding whatever the file says (a header, a column name,
  /// a format's metadata; "m", "mm", "um", "nm", "pm", "angstrom"; empty = the file's own):
  /// x_unit for the lateral lengths (x, y, their spacing and origin), z_unit for the heights. The
  /// values read are rescaled from the unit the reader applied (SurfaceData::x_unit_scale,
  /// z_unit_scale; metres for formats that store SI values) and a warning says so when that
  /// changes them (docs/io.md, "Units").
  std::string x_unit, z_unit;
  /// Columns (0-based) used for x and z in delimited text; -1 = automatic (an index column
  /// 0, 1, 2, ... before two more columns is skipped).
  int x_column = -1;
  int z_column = -1;
  /// Sampling interval for data that carry none: a single column of heights, a 1-D .npy, a
  /// matrix without sizes (unit: m; 0 = none: a single column is then an error).
  double spacing = 0;
  /// Channel of a multi-channel file (Gwyddion-backed formats): its 0-based index or its name;
  /// empty = the first channel with heights in metres.
  std::string channel;
  /// Directory of Gwyddion's file modules (holds file/*.so); empty = the directory found when
  /// frictal was built (see `gwyddion_available`).
  std::string gwyddion_module_dir;
  /// Largest input accepted: file size, and the uncompressed size of an X3P member (unit: bytes).
  std::uint64_t max_bytes = std::uint64_t(1) << 30;
  /// Largest number of points of a map or profile (unitless).
  std::uint64_t max_points = std::uint64_t(1) << 27;
};

/// One data channel of a file: an image (map) or a graph curve (profile).
struct ChannelInfo {
  std::string name;               ///< title in the file ("Height", "Z", ...), or the format's name
  bool is_map = true;             ///< image channel (true) or graph curve (false)
  std::size_t nx = 0, ny = 0;     ///< points (ny = 1 for curves)
  double size_x = 0, size_y = 0;  ///< physical size nx dx, ny dy in the file's lateral unit
  std::string xy_unit, z_unit;    ///< units as the file gives them ("m", "V", "deg", ...)
  bool readable = true;           ///< units are lengths, or an image has none (read in ReadOptions::default_unit)
};

/// Everything a surface file gave: a line profile or an areal map, plus warnings (e.g. an X3P
/// checksum mismatch, a count line that does not match) that did not stop the reading, each with
/// the code the reader gives it ("reader", warnings.hpp).
struct SurfaceData {
  bool is_map = false;                         ///< true: `map` holds the data; false: `curve` does
  Curve curve;                                 ///< line profile in metres (x may decrease only in curve formats)
  Map map;                                     ///< areal map in metres
  ProfileFormat format = ProfileFormat::Auto;  ///< the format actually read
  std::vector<Warning> warnings;
  /// Which reader read it: "native" or "gwyddion:<module>" (e.g. "gwyddion:surffile"), with
  /// " (gzip)" when the file was gzip-compressed.
  std::string reader;
  /// Every channel the file holds (one for the native formats); `channel` is the one read.
  std::vector<ChannelInfo> channels;
  std::size_t channel = 0;
  /// Metres per unit of the file's lateral numbers and of its heights as read: the unit the reader
  /// applied (the file's, ReadOptions::default_unit's, or an override's; 1 for formats that store
  /// SI values; x_unit_scale 0 where the file holds no lateral numbers and the spacing was given,
  /// in metres: then ReadOptions::x_unit changes nothing) (unit: m per file unit).
  double x_unit_scale = 1, z_unit_scale = 1;
};

/// A readable format, for `frictal formats`.
struct FormatInfo {
  std::string name;         ///< "csv", "x3p", ... or the Gwyddion module name ("surffile")
  std::string description;  ///< what it is, with the usual extensions
  std::string reader;       ///< "native" or "gwyddion"
  bool can_write = false;   ///< frictal can write it (native) / Gwyddion's module saves it
};
/// The native formats, then (when available) every format a Gwyddion file module loads.
std::vector<FormatInfo> readable_formats(const std::string& gwyddion_module_dir = "");
/// The formats Gwyddion's file modules load (empty when the backend is not available).
std::vector<FormatInfo> gwyddion_formats(const std::string& gwyddion_module_dir = "");
/// Whether the Gwyddion backend can be used: its libraries load (at run time) and
/// `module_dir` (empty = the directory found at build time) holds file modules. `why` gets the
/// reason and the packages to install when not. The first call initialises Gwyddion for the
/// whole process (type system and file modules; never GTK).
bool gwyddion_available(const std::string& module_dir = "", std::string* why = nullptr);
/// Writes a map through Gwyddion's file modules, the format from the extension: .gwy, .gsf,
/// .sdf (text), .sur, .asc (SPIP), .ibw, .nrrd, .tom (WSxM), .afm (Assing), .spm (ISO 28600)
/// -- the ones tested. Invalid points go to a mask (kept by .gwy only).
Status write_gwyddion(const std::string& path, const Map& m, const std::string& module_dir = "");

/// Checks, without opening it, that `path` names a regular file (symbolic links followed), so
/// that nothing blocks on a FIFO with no writer. Otherwise an error that says what the path is:
/// "PATH: is a directory, expected EXPECTED", likewise a FIFO (named pipe), a character device
/// (/dev/null), a block device or a socket; "PATH: cannot open: no such file, expected EXPECTED"
/// (ErrorCode::Io) when nothing is there. `expected` names what the caller reads, e.g. "a surface file". Every
/// reader of an input file (read_surface, the study file, an existing study store) checks this.
Status check_input_file(const std::string& path, const std::string& expected);

/// Reads any supported file (format from content unless options.format says otherwise). Files
/// no native reader recognises go to the Gwyddion backend when it is available.
Result<SurfaceData> read_surface(const std::string& path, const ReadOptions& options = {});
/// Same, from bytes already in memory; `name` is used in messages.
Result<SurfaceData> read_surface_bytes(const std::string& bytes, const std::string& name,
                                       const ReadOptions& options = {});

/// Reads a line profile as a Curve in metres (x may be non-monotonic only for curve formats).
Result<Curve> read_curve(const std::string& path, const ReadOptions& options = {});
/// Reads a line profile and checks that it is single-valued (x non-decreasing).
Result<Profile> read_profile(const std::string& path, const ReadOptions& options = {});
/// Reads an areal map (X3P SUR, Gwyddion text); a line-profile file is an error.
Result<Map> read_map(const std::string& path, const ReadOptions& options = {});
/// Parses delimited text already in memory; `name` is used in messages.
Result<Curve> parse_curve_text(const std::string& text, const std::string& name);

/// Decodes text bytes to UTF-8: UTF-8 (with or without BOM), UTF-16 LE/BE (BOM, or detected
/// from NUL bytes), otherwise Latin-1. Never fails; invalid UTF-8 is read as Latin-1.
std::string decode_text(const std::string& bytes);

/// Writes "x_m,z_m" CSV with full double precision (17 significant digits).
Status write_profile_csv(const std::string& path, const Curve& c);
Status write_profile_csv(const std::string& path, const Profile& p);
/// Writes a map as text: "# Width: W m", "# Height: H m", "# Value units: m" then ny rows of
/// nx values ("NaN" for invalid points); read back by the Gwyddion reader.
Status write_map_text(const std::string& path, const Map& m);

/// X3P data types: signed int16, signed int32, float32, float64 (ISO 25178-71 I, L, F, D).
enum class X3pDataType { I, L, F, D };

struct X3pWriteOptions {
  X3pDataType type = X3pDataType::D;
  /// Binary bindata/data.bin (true) or an XML <DataList> (false).
  bool binary = true;
  /// z = offset + increment * raw for the integer types (unit: m). increment <= 0 chooses
  /// the finest increment that fits the data's range in the type.
  double z_increment = 0;
  double z_offset = 0;
  /// Record2 Date and CalibrationDate (ISO 8601); empty = the current UTC time. Set it for
  /// byte-identical output.
  std::string date;
  std::string creator = "frictal";             ///< Record2 Creator
  std::string comment = "written by frictal";  ///< Record2 Comment
};

/// Writes an areal map as X3P (FeatureType SUR). Invalid points: NaN for F/D data plus a
/// valid-point mask (bindata/valid.bin) when any point is invalid; the mask alone for I/L.
Status write_x3p(const std::string& path, const Map& m, const X3pWriteOptions& options = {});
/// Writes a uniformly spaced profile as X3P (FeatureType PRF, SizeY = 1). Error if x is not
/// uniform (every x within 1% of the spacing of x0 + k dx; written as x0 + k dx).
Status write_x3p(const std::string& path, const Profile& p, const X3pWriteOptions& options = {});

/// A readable format's output columns (table "format") and the list of them with the Gwyddion
/// backend's state (table "formats"): `frictal formats --json` (src/io/io_columns.cpp).
struct FormatList {
  std::vector<FormatInfo> formats;
  bool gwyddion = false;         ///< the Gwyddion backend is available
  std::string gwyddion_missing;  ///< why not (when it is not)
};
const Columns<FormatInfo>& format_info_columns();
const Columns<FormatList>& format_list_columns();

/// What a surface file holds as output columns (frictal/outputs.hpp; src/io/io_columns.cpp):
/// `frictal info --json` (with the map's grid) and Python read_surface's dict (SI).
const Columns<SurfaceData>& surface_data_columns();
/// One channel of a file (table "info_channel"), in the file's own units.
const Columns<ChannelInfo>& channel_info_columns();

}  // namespace frictal
