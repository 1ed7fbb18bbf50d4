// frictal stats FILE — statistics of a profile or an areal map (any readable format).
#include "frictal/stats.hpp"
#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/scan_stats.hpp"
#include "frictal/signature.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string file;
  bool json = false;
  std::string detrend;  ///< --detrend (empty: form_to_remove's default)
  std::string psd_out, acf_out, spline_out;
  int spline_samples = 20;
  int bins = 0;
  std::string tip_radius;
  InputOptions input;
  ConditioningOptions cond;
};

void write_columns(const std::string& path, const char* header, const std::vector<double>& a,
                   const std::vector<double>& b) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw UsageError(fmt::format("{}: cannot open for writing", path));
  std::string buf = std::string(header) + "\n";
  for (std::size_t k = 0; k < a.size(); ++k) buf += fmt::format("{:.17g},{:.17g}\n", a[k], b[k]);
  const bool ok = std::fwrite(buf.data(), 1, buf.size(), f) == buf.size();
  if (std::fclose(f) != 0 || !ok) throw UsageError(fmt::format("{}: write failed", path));
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("file", a->file, "Profile or map file (any readable format; see 'frictal formats')")->required();
  app.add_flag("--json", a->json, "Print one JSON object");
  add_detrend_option(app, a->detrend);
  add_conditioning_options(app, a->cond);
  app.add_option("--psd", a->psd_out, "Write the power spectrum (q_rad_per_m,C_m3) of the profile to this CSV");
  app.add_option("--acf", a->acf_out, "Write the autocorrelation (lag_m,acf) of the profile to this CSV");
  app.add_option("--spline", a->spline_out,
                 "Write the natural cubic spline through the profile's points (x_m,z_m,slope_deg), the curve whose "
                 "slopes `signature --slopes spline` takes (paper Fig. 13), to this CSV");
  app.add_option("--spline-samples", a->spline_samples,
                 "Samples of --spline per interval between two points (1..10000)");
  app.add_option("--histograms", a->bins, "Add height and slope distributions with this many bins to --json");
  app.add_option(
      "--tip-radius", a->tip_radius,
      "Tip radius for the short reliability cutoff, a length such as 20nm (no unit: metres); see docs/analysis.md");
  add_input_options(app, a->input);
  return [a]() {
    require(a->bins >= 0 && a->bins <= 100000, "--histograms must be in 0..100000");
    const double tip = a->tip_radius.empty() ? 0.0 : parse_length_option(a->tip_radius, "--tip-radius");
    const Conditioning cond = conditioning(a->cond, form_to_remove(a->detrend, false));
    const SurfaceData data = load_surface(a->file, a->input);
    // The reader's warnings (printed as it read) and the plausibility of what was read (warnings.hpp).
    std::vector<Warning> warnings;
    for (const auto& w : data.warnings) add_warning(warnings, w);
    auto report_warnings = [&] {
      for (const Warning& w : warnings)
        if (w.code != "reader") print_warnings({w});
    };
    // What the JSON says beside the statistics: the file, how it was read and conditioned.
    auto record = [&](const ConditioningRecord& r) {
      RunRecord in;
      in.file = a->file;
      in.format = format_name(data.format);
      in.kind = data.is_map ? "map" : "profile";
      in.conditioning = r.text();
      in.warnings = warnings;
      return in;
    };
    StatsExtras extras;
    extras.is_map = data.is_map;
    extras.tip_radius = tip;
    if (data.is_map) {
      require(a->spline_out.empty(), "--spline: profiles only (this file is a map)");
      const ConditionedMap cm = unwrap(condition(data.map, cond, a->file));
      const Map& m = cm.map;
      for (Warning& w : check_map(m, a->file, {}, rms_height_as_read(data.map.heights)))
        add_warning(warnings, std::move(w));
      const MapStats s = map_stats(m);
      const MapScanStats sc = map_scan_stats(m);
      const double cutoff = tip > 0 ? unwrap(short_reliability_cutoff(m, tip)) : 0.0;
      extras.short_reliability_cutoff = cutoff;  // NaN (unreliable at every scale) prints as null
      if (a->json) {
        nlohmann::json j;
        put_columns(j, map_stats_columns(), s);
        put_columns(j, map_grid_columns(), m);
        put_columns(j, map_scan_stats_columns(), sc);
        put_columns(j, stats_extras_columns(), extras);
        put_columns(j, run_record_columns(), record(cm.record));
        report_warnings();
        print_json(j);
      } else {
        fmt::print(
            "{}: {} x {} map ({} valid of {} points), {:.6g} x {:.6g} m\n"
            "  Sq {:.6g} m  Sa {:.6g} m  Sz {:.6g} m  Ssk {:.4g}  Sku {:.4g}\n  Sdq {:.6g}  max slope {:.4f} deg\n",
            a->file, m.nx, m.ny, s.valid, s.points, s.width, s.height, s.Sq, s.Sa, s.Sz, s.Ssk, s.Sku, s.Sdq,
            to_deg(s.max_slope));
        fmt::print(
            "  physical size (n dx) {:.6g} x {:.6g} m, bandwidth {:.6g} .. {:.6g} m\n"
            "  along x: Rq {:.6g} m  Rdq {:.6g}   along y: Rq {:.6g} m  Rdq {:.6g}   rms gradient (fd) {:.6g}\n",
            sc.physical_size_x, sc.physical_size_y, sc.bandwidth_short, sc.bandwidth_long, sc.Rq_x, sc.Rdq_x, sc.Rq_y,
            sc.Rdq_y, sc.rms_gradient_fd);
        if (tip > 0) fmt::print("  short reliability cutoff for a {:.6g} m tip: {:.6g} m\n", tip, cutoff);
        fmt::print("  conditioning: {}\n", cm.record.text());
        report_warnings();
      }
      return 0;
    }
    const Profile read = surface_profile(data, a->file);
    Conditioning own = cond;  // a file that carries its period: the default form is the mean
    if (a->detrend.empty() && read.period) own.form = default_form(true);
    const ConditionedProfile cp = unwrap(condition(read, own, a->file));
    const Profile& p = cp.profile;
    for (Warning& w : check_profile(p, a->file, {}, rms_height_as_read(read.z))) add_warning(warnings, std::move(w));
    const ProfileStats s = profile_stats(p);
    const ProfileScanStats sc = profile_scan_stats(p);
    const double cutoff = tip > 0 ? unwrap(short_reliability_cutoff(p, tip)) : 0.0;
    extras.short_reliability_cutoff = cutoff;
    if (!a->psd_out.empty()) {
      const Spectrum sp = unwrap(power_spectrum(p));
      write_columns(a->psd_out, "q_rad_per_m,C_m3", sp.q, sp.psd);
    }
    if (!a->spline_out.empty()) {
      const SplineSamples sp = unwrap(sample_spline(p, a->spline_samples));
      std::FILE* f = std::fopen(a->spline_out.c_str(), "wb");
      if (!f) throw UsageError(fmt::format("{}: cannot open for writing", a->spline_out));
      std::string buf = "x_m,z_m,slope_deg\n";
      for (std::size_t k = 0; k < sp.x.size(); ++k)
        buf += fmt::format("{:.17g},{:.17g},{:.17g}\n", sp.x[k], sp.z[k], units::to_deg(std::atan(sp.slope[k])));
      const bool ok = std::fwrite(buf.data(), 1, buf.size(), f) == buf.size();
      if (std::fclose(f) != 0 || !ok) throw UsageError(fmt::format("{}: write failed", a->spline_out));
    }
    if (!a->acf_out.empty()) {
      const Autocorrelation ac = unwrap(autocorrelation(p));
      write_columns(a->acf_out, "lag_m,acf", ac.lag, ac.acf);
      extras.correlation_length = ac.correlation_length;
    }
    if (a->json) {
      if (a->bins > 0) {
        extras.height_distribution = height_distribution(p, a->bins);
        extras.slope_distribution = slope_distribution(p, a->bins);
      }
      nlohmann::json j;
      put_columns(j, profile_stats_columns(), s);
      put_columns(j, profile_scan_stats_columns(), sc);
      put_columns(j, stats_extras_columns(), extras);
      put_columns(j, run_record_columns(), record(cp.record));
      report_warnings();
      print_json(j);
    } else {
      fmt::print(
          "{}: {} points over {:.6g} m\n  rms height {:.6g} m (about the mean {:.6g} m)\n  rms slope {:.6g}\n"
          "  max slope {:.4f} deg\n",
          a->file, s.points, s.length, s.rms_height, s.mean_height, s.rms_slope, to_deg(s.max_slope));
      fmt::print("  physical length (n dx) {:.6g} m, bandwidth {:.6g} .. {:.6g} m\n", sc.physical_length,
                 sc.bandwidth_short, sc.bandwidth_long);
      if (tip > 0) fmt::print("  short reliability cutoff for a {:.6g} m tip: {:.6g} m\n", tip, cutoff);
      fmt::print("  conditioning: {}\n", cp.record.text());
      report_warnings();
    }
    return 0;
  };
}

FRICTAL_COMMAND({"stats", "Statistics of a profile or map: rms height, rms slope, max slope (Sq, Sdq, ... for maps)",
                 setup, 30});

}  // namespace
}  // namespace frictal::cli
