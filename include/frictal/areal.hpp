// frictal — friction of areal maps: prediction along a sliding direction from the parallel line
// profiles of a map, the polar (anisotropy) table over directions, and the true areal signature
// of two rigid 3D blocks. Angles in radians, lengths in metres. Definitions: docs/analysis.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "frictal/hold.hpp"
#include "frictal/map.hpp"
#include "frictal/outputs.hpp"
#include "frictal/settings.hpp"
#include "frictal/signature.hpp"

namespace frictal {

struct DirectionalOptions {
  /// Distance between parallel lines (0: max(dx, dy), widened so that at most max_lines lines
  /// cover the map) (unit: m).
  double spacing = 0;
  std::size_t max_lines = 128;
  /// Sampling step along each line (0: min(dx, dy)) (unit: m).
  double step = 0;
  /// Shortest line used (unitless); shorter valid runs (map corners, holes) are skipped.
  std::size_t min_points = 32;
  /// Passed to self_signature for every line (its offset range: half of each line).
  SignatureOptions signature = {};
  /// mu_a of Eq. 6 for the prediction (unitless).
  double atomic_friction = 0;
  /// Worker threads over lines (0 = hardware); the result does not depend on it.
  unsigned threads = 1;
};

/// Prediction for sliding along one direction, from all parallel lines: each line is compared
/// with itself turned over (self_signature); results are length-weighted over lines.
struct DirectionalFriction {
  double angle = 0;               ///< sliding direction, from +x towards +y (unit: rad)
  std::size_t lines = 0;          ///< lines used (unitless)
  double total_length = 0;        ///< summed line length (unit: m)
  double theta_forward = 0;       ///< length-weighted mean of theta_max_forward (unit: rad)
  double theta_forward_max = 0;   ///< max over lines (unit: rad)
  double theta_backward = 0;      ///< length-weighted mean of theta_max_backward (unit: rad)
  double theta_backward_max = 0;  ///< (unit: rad)
  double sigma = 0;               ///< length-weighted mean contact-slope std (Eq. 18 sigma) (unit: rad)
  FrictionPrediction prediction;  ///< Eq. 6/18 from theta_forward and sigma
};
Result<DirectionalFriction> friction_along(const Map& m, double angle, const DirectionalOptions& o = {});

/// Polar table: `directions` sliding directions equally spaced over [0, 2 pi).
Result<std::vector<DirectionalFriction>> anisotropy(const Map& m, int directions = 36,
                                                    const DirectionalOptions& o = {});

/// The areal signature of two rigid blocks sliding along direction d = (cos angle, sin angle).
/// The lower block's face is `lower` as measured. By default the upper block is `upper` as
/// measured, turned over onto the lower one about the in-plane axis perpendicular to d (the 3D
/// form of rotate180: the d-component and z change sign), centred on the lower map at s = 0, then
/// moved by s d:
///   h(s) = max over nodes p of `lower` [ f(p) + g(c_g + R (p - s d - c_f)) ],  R v = v - 2 (v.d) d.
/// With turn_over_upper = false, `upper` is the upper face already in place, in the lower map's
/// coordinates (like signature()'s `upper`): h(s) = max_p [ f(p) - g(p - s d) ].
/// g is interpolated bilinearly (NaN-aware; nodes whose image leaves g's grid do not touch), so
/// h is exact on the lower grid. The contact is the maximising node (ties: lowest index); its
/// slope is the lower face's directional slope along d there (Eq. 3), or the mean of both
/// faces' slopes (as the paper's spline method does), by central differences over +-step/2.
enum class ArealContactSlope { Lower, Mean };
struct ArealSignatureOptions {
  double step = 0;              ///< offset step (0: min(dx, dy) of lower) (unit: m)
  double offset_max = 0;        ///< offsets 0, step, ... up to this (0: half the lower map's extent along d) (unit: m)
  bool turn_over_upper = true;  ///< false: `upper` is already in place (see above)
  ArealContactSlope contact_slope = ArealContactSlope::Lower;
  std::size_t block = 16;  ///< block edge for the max bounds (nodes, >= 2)
  bool prune = true;       ///< false: evaluate every node at every offset (the direct method)
  unsigned threads = 1;    ///< worker threads over offsets (0 = hardware); results do not depend on it
};
struct ArealSignature {
  double direction = 0;             ///< the sliding direction d, from +x towards +y (unit: rad)
  std::vector<double> offset;       ///< s (unit: m)
  std::vector<double> lift;         ///< h(s), up to a constant (unit: m)
  std::vector<double> theta;        ///< contact slope at s (unit: rad)
  std::vector<double> contact_x;    ///< contact node of the lower map (unit: m)
  std::vector<double> contact_y;    ///< (unit: m)
  double theta_max_forward = 0;     ///< max theta (unit: rad)
  double theta_max_backward = 0;    ///< max of -theta (unit: rad)
  double theta_max_lift = 0;        ///< max of atan((h(s+step) - h(s)) / step) (unit: rad)
  double contact_slope_mean = 0;    ///< (unit: rad)
  double contact_slope_std = 0;     ///< (unit: rad)
  std::size_t evaluated_nodes = 0;  ///< nodes evaluated exactly, summed over offsets (work measure)
};
Result<ArealSignature> areal_signature(const Map& lower, const Map& upper, double angle,
                                       const ArealSignatureOptions& o = {});

/// What the grid areal signature of two maps takes besides the maps (`frictal areal`, Python
/// areal_signature()): the sliding direction, its options and mu_a of the grid's rigid bound
/// theta_max + atan(mu_a) beside it. Settings table areal_signature_settings().
struct ArealSignatureSettings {
  double direction = 0;        ///< sliding direction d, from +x towards +y (unit: rad)
  double atomic_friction = 0;  ///< mu_a (unitless)
  ArealSignatureOptions options;
};
/// The areal signature's settings table (settings.hpp; src/areal/areal_settings.cpp): direction
/// and in_place (the quantities the prediction shares, shared_field), atomic_friction, step and
/// max_offset (automatic: NaN, the options' 0), contact_slope; defaults are the structs'.
const std::vector<Field>& areal_signature_settings();
/// `base` with the values `si` of areal_signature_settings() applied (SI, checked).
Result<ArealSignatureSettings> make_areal_signature_settings(const ValueSet& si, ArealSignatureSettings base = {});

/// The lift over two dimensions of offset: the upper block moved by s = u d + v e in the plane,
/// d = (cos angle, sin angle) the sliding direction and e = (-sin angle, cos angle) across it,
///   h(u, v) = max over nodes p of `lower` [ f(p) + g(c_g + R (p - s - c_f)) ]
/// with the same faces, turn-over, interpolation and tie rules as areal_signature, which is this
/// lift on the line v = 0 (bit for bit: the same evaluation, the same products u d).
/// Offsets form a grid: u_i = offset_min + i step (i = 0 .. n_along - 1) and v_j = across_min +
/// j across_step with across_min = -m across_step (j = 0 .. 2m: v = 0 is row m).
struct ArealLiftOptions {
  double step = 0;        ///< offset step along d (0: min(dx, dy) of lower) (unit: m)
  double offset_min = 0;  ///< first offset along d (unit: m)
  /// Last offset along d (<= offset_min: offset_min + half the lower map's extent along d) (unit: m).
  double offset_max = 0;
  double across_step = 0;  ///< offset step across d (0: step) (unit: m)
  /// Offsets across d cover [-across_max, across_max] (0: a quarter of the lower map's extent
  /// across d) (unit: m).
  double across_max = 0;
  bool turn_over_upper = true;  ///< false: `upper` is already in place (see areal_signature)
  std::size_t block = 16;       ///< block edge for the max bounds (nodes, >= 2)
  bool prune = true;            ///< false: evaluate every node at every offset (the direct method)
  unsigned threads = 1;         ///< worker threads over offsets (0 = hardware); results do not depend on it
};
struct ArealLift {
  double angle = 0;          ///< sliding direction d (unit: rad)
  std::size_t n_along = 0;   ///< offsets along d (unitless)
  std::size_t n_across = 0;  ///< offsets across d, odd (unitless)
  double along_min = 0;      ///< u_0 (unit: m)
  double step = 0;           ///< u_{i+1} - u_i (unit: m)
  double across_min = 0;     ///< v_0 = -(n_across - 1) / 2 across_step (unit: m)
  double across_step = 0;    ///< v_{j+1} - v_j (unit: m)
  /// h(u_i, v_j) at index j * n_along + i, up to a constant; NaN where the blocks do not touch (unit: m).
  std::vector<double> lift;
  std::vector<std::int64_t> contact;  ///< lower-map node (row-major) of the contact, -1 where none
  std::size_t evaluated_nodes = 0;    ///< nodes evaluated exactly, summed over offsets (work measure)

  double along(std::size_t i) const { return along_min + double(i) * step; }           ///< u_i (unit: m)
  double across(std::size_t j) const { return across_min + double(j) * across_step; }  ///< v_j (unit: m)
  /// The offset of node k = j * n_along + i in the lower map's frame, u d + v e (unit: m).
  std::array<double, 2> offset_xy(std::size_t k) const;
};
/// Errors: maps that are not valid or smaller than 2 x 2, a direction that is not finite, steps
/// or ranges that are negative or not finite, more than 5e7 offsets, and blocks that never touch
/// over the offsets (maps that do not overlap along d).
Result<ArealLift> areal_lift(const Map& lower, const Map& upper, double angle, const ArealLiftOptions& o = {});

/// What the polar table over directions takes besides the map (`frictal anisotropy`, Python
/// anisotropy()): how many directions, and per direction either the map's line profiles
/// (DirectionalOptions: lines, atomic_friction) or the grid areal signature (areal, contact_slope).
/// Settings table anisotropy_settings().
struct AnisotropySettings {
  int directions = 36;  ///< sliding directions over [0, 2 pi), equally spaced (unitless)
  bool areal = false;   ///< the grid areal signature of the map against itself, not its line profiles
  ArealContactSlope contact_slope = ArealContactSlope::Lower;  ///< with areal
  DirectionalOptions lines;                                    ///< max_lines, atomic_friction (line profiles)
};
/// The polar table's settings table (settings.hpp; src/areal/areal_settings.cpp): directions,
/// lines (DirectionalOptions::max_lines), atomic_friction (shared_field; the bound of both
/// methods), areal, contact_slope (areal_signature_settings()' field).
const std::vector<Field>& anisotropy_settings();
/// `base` with the values `si` of anisotropy_settings() applied (SI, checked).
Result<AnisotropySettings> make_anisotropy_settings(const ValueSet& si, AnisotropySettings base = {});

/// One sliding direction of the polar table (frictal anisotropy): the rigid bound of the
/// signature, and with the hold model (frictal predict --direction) the hold angle over drops.
struct AnisotropyRow {
  double direction = 0;                                  ///< from +x towards +y (unit: rad)
  std::optional<std::size_t> lines;                      ///< map lines theta_max is over (line profiles only)
  double theta_forward = 0;                              ///< theta_max along the direction (unit: rad)
  double theta_backward = 0;                             ///< theta_max against it (unit: rad)
  double sigma = 0;                                      ///< sigma of Eq. 18 (unit: rad)
  double upper_bound_friction_angle = 0;                 ///< theta_max + theta_a, or the hold model's bound (unit: rad)
  double upper_bound_friction_coefficient = 0;           ///< tan of it (unitless)
  std::optional<double> signature_bound_friction_angle;  ///< hold model: the signature's bound beside it (unit: rad)
  double eq18_low_friction_coefficient = 0;              ///< tan of Eq. 18's low end (unitless)
  std::optional<double> hold_runaway_distance;           ///< hold model: run-away distance d (unit: m)
  std::optional<HoldStatistics> hold_angle;              ///< hold model: over drops, the block free (unit: rad)
  std::optional<HoldStatistics> hold_angle_locked;       ///< the block locked to the direction; quantiles (unit: rad)
};
/// The polar table over directions: frictal anisotropy --json, Python anisotropy().
struct AnisotropyTable {
  std::optional<std::string> hold_model;  ///< the hold angles' model (frictal predict's)
  std::optional<double> hold_drops;       ///< drops per direction (unitless count)
  double atomic_friction = 0;             ///< mu_a (unitless)
  std::vector<AnisotropyRow> directions;
};
/// Their output tables (frictal/outputs.hpp; src/areal/areal_columns.cpp).
const Columns<AnisotropyRow>& anisotropy_row_columns();
/// The areal signature's output table "areal": the keys of `frictal areal --json` (with the grid's
/// rigid bound, areal_bound_columns) and of Python's areal_signature() dict (SI).
const Columns<ArealSignature>& areal_signature_columns();
/// The grid's rigid bound of `frictal areal --json`: the columns of friction_columns() it prints.
const Columns<FrictionPrediction>& areal_bound_columns();
const Columns<AnisotropyTable>& anisotropy_columns();

}  // namespace frictal
