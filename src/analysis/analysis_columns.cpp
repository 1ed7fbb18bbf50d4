// The output tables of a map's statistics and of the scan quantities of profiles and maps
// (frictal/outputs.hpp): the keys of `frictal stats --json` and of Python's map_stats() and
// profile_stats() dicts.
#include <vector>

#include "frictal/analysis.hpp"
#include "frictal/conditioning.hpp"
#include "frictal/fractal.hpp"
#include "frictal/scan_stats.hpp"

namespace frictal {

const Columns<MapStats>& map_stats_columns() {
  using T = MapStats;
  static const Columns<T> cols = {
      column<T>("points", "count", "nodes of the grid, nx ny", [](const T& s) { return double(s.points); }),
      column<T>("valid_points", "count", "nodes with a measured height", [](const T& s) { return double(s.valid); }),
      column<T>(
          "length_m", "m", "extent along x, (nx - 1) dx (as for profiles)", [](const T& s) { return s.width; }, "-"),
      column<T>(
          "size_x_m", "m", "extent along x, (nx - 1) dx", [](const T& s) { return s.width; }, "-"),
      column<T>(
          "size_y_m", "m", "extent along y, (ny - 1) dy", [](const T& s) { return s.height; }, "-"),
      column<T>("mean_height_m", "m", "mean height", [](const T& s) { return s.mean; }),
      column<T>("Sa_m", "m", "arithmetic mean height about the mean (ISO 25178-2)", [](const T& s) { return s.Sa; }),
      column<T>("Sq_m", "m", "rms height about the mean", [](const T& s) { return s.Sq; }),
      column<T>(
          "rms_height_m", "m", "rms height (Sq; as for profiles)", [](const T& s) { return s.Sq; }, "-"),
      column<T>("Sp_m", "m", "highest peak above the mean", [](const T& s) { return s.Sp; }),
      column<T>("Sv_m", "m", "deepest valley below the mean", [](const T& s) { return s.Sv; }),
      column<T>("Sz_m", "m", "Sp + Sv", [](const T& s) { return s.Sz; }),
      column<T>("Ssk", "1", "skewness", [](const T& s) { return s.Ssk; }),
      column<T>("Sku", "1", "kurtosis", [](const T& s) { return s.Sku; }),
      column<T>("Sdq", "1", "rms gradient", [](const T& s) { return s.Sdq; }),
      column<T>(
          "rms_slope", "1", "rms gradient (Sdq; the profiles' rms slope)", [](const T& s) { return s.Sdq; }, "-"),
      column<T>("max_slope_deg", "deg", "steepest gradient angle", [](const T& s) { return s.max_slope; }),
  };
  return cols;
}

const Columns<Map>& map_grid_columns() {
  using T = Map;
  static const Columns<T> cols = {
      column<T>("nx", "count", "nodes along x", [](const T& m) { return double(m.nx); }),
      column<T>("ny", "count", "nodes along y", [](const T& m) { return double(m.ny); }),
      column<T>("dx_m", "m", "node spacing along x", [](const T& m) { return m.dx; }),
      column<T>("dy_m", "m", "node spacing along y", [](const T& m) { return m.dy; }),
  };
  return cols;
}

const Columns<Map>& map_data_columns() {
  using T = Map;
  static const Columns<T> cols = {
      with_shape(column<T>(
                     "", "m", "heights, rows along y (ny x nx)", [](const T& m) { return m.heights; }, "heights"),
                 [](const T& m) {
                   return std::vector<std::size_t>{m.ny, m.nx};
                 }),
      column<T>(
          "", "m", "node spacing along x", [](const T& m) { return m.dx; }, "dx"),
      column<T>(
          "", "m", "node spacing along y", [](const T& m) { return m.dy; }, "dy"),
      column<T>(
          "", "m", "x of the first node", [](const T& m) { return m.x0; }, "x0"),
      column<T>(
          "", "m", "y of the first node", [](const T& m) { return m.y0; }, "y0"),
  };
  return cols;
}

const Columns<Autocorrelation>& autocorrelation_columns() {
  using T = Autocorrelation;
  static const Columns<T> cols = {
      column<T>(
          "", "m", "lags", [](const T& a) { return a.lag; }, "lag"),
      column<T>(
          "", "1", "normalised autocorrelation at each lag", [](const T& a) { return a.acf; }, "acf"),
      column<T>(
          "", "m", "where it falls to 1/e (0: never)", [](const T& a) { return a.correlation_length; },
          "correlation_length"),
  };
  return cols;
}

const Columns<ConditioningRecord>& conditioning_record_columns() {
  using T = ConditioningRecord;
  auto cropped = [](Column<T> c) { return only_if(std::move(c), [](const T& r) { return r.cropped; }); };
  static const Columns<T> cols = {
      column<T>(
          "", "text", "the steps as frictal prints them", [](const T& r) { return r.text(); }, "text"),
      column<T>(
          "", "flag", "a window was cut", [](const T& r) { return r.cropped; }, "cropped"),
      cropped(fixed_length(column<T>(
          "", "m", "the window (x0, x1[, y0, y1])",
          [](const T& r) {
            const CropWindow& w = r.window;
            return w.has_y ? std::vector<double>{w.x_min, w.x_max, w.y_min, w.y_max}
                           : std::vector<double>{w.x_min, w.x_max};
          },
          "window"))),
      cropped(fixed_length(column<T>(
          "", "count", "points before the crop (nx, ny; profiles: ny = 1)",
          [](const T& r) {
            return std::vector<double>{double(r.nx_before), double(r.ny_before)};
          },
          "points_before"))),
      cropped(fixed_length(column<T>(
          "", "count", "points after it (nx, ny)",
          [](const T& r) {
            return std::vector<double>{double(r.nx_after), double(r.ny_after)};
          },
          "points_after"))),
      column<T>(
          "", "flag", "spikes were looked for", [](const T& r) { return r.spikes_checked; }, "spikes_checked"),
      column<T>(
          "", "1", "k: spikes are more than k rms heights from the neighbours' median",
          [](const T& r) { return r.spike_threshold; }, "spike_threshold"),
      column<T>(
          "", "count", "points replaced (profiles) or masked (maps)",
          [](const T& r) { return double(r.spikes_removed); }, "spikes_removed"),
      column<T>(
          "", "count", "profiles: spikes at the ends, dropped", [](const T& r) { return double(r.spikes_dropped); },
          "spikes_dropped"),
      column<T>(
          "", "count", "passes of the spike filter", [](const T& r) { return double(r.spike_passes); }, "spike_passes"),
      column<T>(
          "", "text", "the form removed: none, mean, line, plane, poly:N",
          [](const T& r) { return detrend_name(r.form, r.is_map); }, "form"),
  };
  return cols;
}

const Columns<MapScanStats>& map_scan_stats_columns() {
  using T = MapScanStats;
  static const Columns<T> cols = {
      column<T>("physical_size_x_m", "m", "nx dx (the pixel convention)", [](const T& s) { return s.physical_size_x; }),
      column<T>("physical_size_y_m", "m", "ny dy", [](const T& s) { return s.physical_size_y; }),
      column<T>(
          "physical_length_m", "m", "nx dx (as for profiles)", [](const T& s) { return s.physical_size_x; }, "-"),
      column<T>(
          "bandwidth_short_m", "m", "shortest scale the scan resolves: (dx + dy) / 2",
          [](const T& s) { return s.bandwidth_short; }, "-"),
      column<T>(
          "bandwidth_long_m", "m", "longest scale: (nx dx + ny dy) / 2", [](const T& s) { return s.bandwidth_long; },
          "-"),
      column<T>(
          "", "m", "(shortest, longest) scale the scan resolves",
          [](const T& s) {
            return std::vector<double>{s.bandwidth_short, s.bandwidth_long};
          },
          "bandwidth"),
      column<T>(
          "nyquist_wavelength_m", "m", "2 max(dx, dy): the shortest wavelength both axes resolve",
          [](const T& s) { return s.nyquist_wavelength; }, "-"),
      column<T>("Rq_x_m", "m", "rms height of the rows (x), each about its own mean",
                [](const T& s) { return s.Rq_x; }),
      column<T>("Rdq_x", "1", "rms slope of the rows (x)", [](const T& s) { return s.Rdq_x; }),
      column<T>("Rq_y_m", "m", "rms height of the columns (y)", [](const T& s) { return s.Rq_y; }),
      column<T>("Rdq_y", "1", "rms slope of the columns (y)", [](const T& s) { return s.Rdq_y; }),
      column<T>("rms_gradient_fd", "1", "rms gradient from forward differences at common nodes",
                [](const T& s) { return s.rms_gradient_fd; }),
  };
  return cols;
}

const Columns<ProfileScanStats>& profile_scan_stats_columns() {
  using T = ProfileScanStats;
  static const Columns<T> cols = {
      column<T>("physical_length_m", "m", "n dx with dx = length / (n - 1)",
                [](const T& s) { return s.physical_length; }),
      column<T>("sampling_interval_m", "m", "mean spacing (x_max - x_min) / (n - 1)",
                [](const T& s) { return s.sampling_interval; }),
      column<T>(
          "bandwidth_short_m", "m", "shortest scale the scan resolves: the sampling interval",
          [](const T& s) { return s.bandwidth_short; }, "-"),
      column<T>(
          "bandwidth_long_m", "m", "longest scale: the physical length", [](const T& s) { return s.bandwidth_long; },
          "-"),
      column<T>(
          "", "m", "(shortest, longest) scale the scan resolves",
          [](const T& s) {
            return std::vector<double>{s.bandwidth_short, s.bandwidth_long};
          },
          "bandwidth"),
      column<T>("nyquist_wavelength_m", "m", "2 x the sampling interval",
                [](const T& s) { return s.nyquist_wavelength; }),
  };
  return cols;
}

const Columns<FractalFit>& fractal_fit_columns() {
  using T = FractalFit;
  static const Columns<T> cols = {
      column<T>("dimension", "1", "the fractal dimension D", [](const T& f) { return f.dimension; }),
      column<T>("slope", "1", "fitted log-log slope", [](const T& f) { return f.slope; }),
      column<T>("r_squared", "1", "coefficient of determination of the fit", [](const T& f) { return f.r_squared; }),
      column<T>("fit_range_m", "m", "[smallest, largest] scale in the fit",
                [](const T& f) {
                  return std::vector<double>{f.scale_min, f.scale_max};
                }),
      column<T>("scales_m", "m", "every scale used: ruler, box or wavelength", [](const T& f) { return f.scales; }),
      column<T>("values", "1", "L(eps) (m), N(eps) (unitless) or binned C(q) (m^3), by method",
                [](const T& f) { return f.values; }),
  };
  return cols;
}

const Columns<KochDimension>& koch_dimension_columns() {
  using T = KochDimension;
  static const Columns<T> cols = {
      column<T>(
          "alpha_deg", "deg", "the Koch angle alpha", [](const T& k) { return k.alpha; }, "-"),
      column<T>(
          "method", "text", "the method the numbers come from", [](const T&) { return std::string("eq13"); }, "-"),
      column<T>(
          "dimension", "1", "the fractal dimension D", [](const T& k) { return k.dimension; }, "-"),
      column<T>(
          "equation", "text", "the equation solved (Eq. 13)",
          [](const T&) { return std::string("2 (1/3)^D + 2 (1/(6 cos alpha))^D = 1"); }, "-"),
  };
  return cols;
}

const Columns<StatsExtras>& stats_extras_columns() {
  using T = StatsExtras;
  auto tip = [](const T& e) { return e.tip_radius > 0; };
  auto cutoff = [](const T& e) { return e.short_reliability_cutoff; };
  static const Columns<T> cols = {
      only_if(column<T>(
                  "tip_radius_m", "m", "the stylus tip radius given (--tip-radius)",
                  [](const T& e) { return e.tip_radius; }, "-"),
              tip),
      only_if(column<T>("short_reliability_cutoff_m", "m",
                        "shortest scale the tip resolves (null, Python NaN: unreliable at every scale)", cutoff),
              tip),
      only_if(column<T>(
                  "correlation_length_m", "m", "where the autocorrelation falls to 1/e",
                  [](const T& e) { return *e.correlation_length; }, "-"),
              [](const T& e) { return e.correlation_length.has_value(); }),
      object_column<T>(
          "height_distribution", "histogram", "density of the heights (edges in m, density per m)", histogram_columns(),
          [](const T& e) { return e.height_distribution; }, "-"),
      object_column<T>("slope_distribution_rad", "histogram",
                       "density of the slope angles (edges in rad, density per rad)", histogram_columns(),
                       [](const T& e) { return e.slope_distribution; }),
  };
  return cols;
}

}  // namespace frictal
