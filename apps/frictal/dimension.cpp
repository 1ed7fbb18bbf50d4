// frictal dimension FILE | dimension <generator> — fractal dimension of a measured or generated
// profile (divider, box counting or PSD slope), or of the Koch construction (koch --method eq13,
// Eq. 13).
#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/fractal.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string file;
  std::string method = "divider";
  double scale_min = 0, scale_max = 0;
  int scales = 0;  // 0: 16 rulers, 12 boxes, 10 PSD bins per decade
  bool json = false;
  std::string detrend;  ///< --detrend (empty: form_to_remove's default)
  InputOptions input;
  ConditioningOptions cond;
  GeneratorOptions gen;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("file", a->file, "Profile file (any readable format); - reads standard input");
  add_generator_subcommands(app, a->gen, true, " (measured on the generated surface; koch: the full curve)");
  app.add_option("--method", a->method,
                 "divider (ruler), box (box counting), psd (spectrum slope), or eq13 (koch only: Eq. 13 from alpha)");
  app.add_option("--min", a->scale_min, "Smallest ruler/box (m) or wavelength (m) of the fit (default: automatic)");
  app.add_option("--max", a->scale_max, "Largest ruler/box (m) or wavelength (m) of the fit (default: automatic)");
  app.add_option("--scales", a->scales, "Number of rulers (default 16) or boxes (12), or PSD bins per decade (10)");
  add_detrend_option(app, a->detrend);
  add_conditioning_options(app, a->cond);
  app.add_flag("--json", a->json, "Print one JSON object");
  add_input_options(app, a->input);
  return [a]() {
    const std::optional<SurfaceSpec> spec = a->gen.spec();
    if (a->method == "eq13") {
      require(spec && spec->generator == "koch",
              "--method eq13: the Koch dimension of Eq. 13 needs the koch generator");
      const KochParams kp = unwrap(koch_params(*spec));
      const double D = unwrap(koch_dimension(kp.alpha));
      if (a->json) {
        print_json(object_of(koch_dimension_columns(), KochDimension{kp.alpha, D}));
      } else {
        fmt::print("Koch dimension for alpha = {} deg (Eq. 13): D = {:.12f}\n", to_deg(kp.alpha), D);
      }
      return 0;
    }
    if (spec) {
      require(a->file.empty(), fmt::format("dimension {}: a generated surface takes no FILE", spec->generator));
      a->file = spec->generator;
    } else if (a->file.empty()) {
      throw UsageError("dimension: give a FILE, or a generator (koch, wm, sawtooth, sine, self-affine, fourier)");
    }
    require(a->scale_min >= 0 && a->scale_max >= 0, "--min and --max must be positive lengths in metres");
    const Detrend d = form_to_remove(a->detrend, spec.has_value());
    const Conditioning cond = conditioning(a->cond, d);
    ConditioningRecord record;
    record.form = d;
    auto conditioned = [&](const Profile& p) {
      ConditionedProfile c = unwrap(condition(p, cond, a->file));
      record = c.record;
      return std::move(c.profile);
    };
    SurfaceData s;
    if (spec)
      s.curve = unwrap(generate_curve(*spec));
    else
      s = load_surface(a->file, a->input);
    if (s.is_map)
      throw UsageError(
          fmt::format("{}: an areal map; the dimension needs a line profile (extract one first)", a->file));
    FractalFit f;
    if (a->method == "divider" || a->method == "box") {
      Curve c = s.curve;
      // A curve that folds over (Koch) is measured as it is when no conditioning is asked for (the
      // default form included: the record then says none).
      const bool asked = !a->detrend.empty() || cond.crop || cond.remove_spikes;
      if (d.kind != DetrendKind::None || cond.crop || cond.remove_spikes) {
        auto p = as_profile(c, a->file);
        if (p.ok() || asked)
          c = as_curve(conditioned(unwrap(std::move(p))));
        else
          record.form = Detrend{DetrendKind::None, 0};
      }
      if (a->method == "divider")
        f = unwrap(divider_dimension(c, {a->scale_min, a->scale_max, a->scales ? a->scales : 16}));
      else
        f = unwrap(box_dimension(c, {a->scale_min, a->scale_max, a->scales ? a->scales : 12}));
    } else if (a->method == "psd") {
      Profile p = conditioned(spec ? unwrap(generate_profile(*spec)) : surface_profile(s, a->file));
      PsdFitOptions o;
      // Wavelength bounds -> wavenumber bounds.
      if (a->scale_max > 0) o.q_min = 2 * std::numbers::pi / a->scale_max;
      if (a->scale_min > 0) o.q_max = 2 * std::numbers::pi / a->scale_min;
      o.bins_per_decade = a->scales > 0 ? a->scales : 10;
      f = unwrap(psd_dimension(p, o));
    } else {
      throw UsageError(fmt::format("--method '{}' not understood (expected divider, box, psd or eq13)", a->method));
    }
    std::vector<Warning> warnings;
    for (const auto& w : s.warnings) add_warning(warnings, w);
    for (Warning& w : check_dimension_fit(f.dimension, f.r_squared, a->method)) add_warning(warnings, std::move(w));
    if (a->json) {
      RunRecord in;
      in.file = a->file;
      in.method = a->method;
      in.conditioning = record.text();
      in.warnings = warnings;
      nlohmann::json j = object_of(fractal_fit_columns(), f);
      put_columns(j, run_record_columns(), in);
      print_json(j);
    } else {
      fmt::print("{}: D = {:.4f} ({} method, r^2 = {:.4f}, fit over {:.4g} .. {:.4g} m)\n", a->file, f.dimension,
                 a->method, f.r_squared, f.scale_min, f.scale_max);
      fmt::print("  conditioning: {}\n", record.text());
      for (const Warning& w : warnings)
        if (w.code != "reader") print_warnings({w});
    }
    return 0;
  };
}

FRICTAL_COMMAND({"dimension", "Fractal dimension of a profile (divider, box, psd) or of a Koch curve (Eq. 13)", setup,
                 50});

}  // namespace
}  // namespace frictal::cli
