// frictal signature LOWER [UPPER] | signature <generator> [options] — the signature function and
// the friction prediction, of two measured surfaces or of a generated surface with itself.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <future>
#include <iterator>
#include <thread>

#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"
#include "frictal/tilt.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string lower, upper, out, contacts_out, pdf_out;
  double mu_a = 0;
  std::string slopes = "exact";
  std::size_t offsets = 0;
  std::vector<double> range;
  double period = 0;
  unsigned threads = 0;
  int bins = 90;
  double spheroradius = 0;
  bool json = false;
  bool exact = false;
  std::string detrend = "none";
  GeneratorOptions gen;
  InputOptions input;       ///< --format, --unit, --spacing, ... of LOWER and UPPER
  FieldWords period_words;  ///< --period, the tilt table's field
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("lower", a->lower, "Lower surface file (as measured: material below); - reads standard input");
  app.add_option("upper", a->upper,
                 "Upper surface file, as measured (material below); it is rotated by 180 degrees to face LOWER. "
                 "Default: LOWER itself");
  add_generator_subcommands(app, a->gen, true, " (its self-signature: the surface against itself turned over)");
  add_input_options(app, a->input);
  add_atomic_friction_option(app, a->mu_a);
  app.add_option("--slopes", a->slopes, "exact: polyline contact rules; spline: cubic-spline slopes averaged")
      ->check(CLI::IsMember({"exact", "spline"}))
      ->capture_default_str();
  app.add_option("--offsets", a->offsets,
                 "0: every event offset (exact; if there are too many, offsets sampled at the finer point spacing); "
                 "N: N equally spaced offsets")
      ->capture_default_str();
  app.add_option("--detrend", a->detrend,
                 "Remove none, mean, line or poly:N from each measured surface first (form and tilt of the scan)")
      ->capture_default_str();
  app.add_flag("--exact", a->exact, "Refuse to sample offsets when the exact signature has too many events");
  app.add_option("--offset-range", a->range, "MIN MAX offsets (m); default one period or half the block")->expected(2);
  // --period and --spheroradius (the spheroradius: the signature of the DEM's rounded blocks, one core
  // against the other dilated by a disk of radius 2r), the tilt table's fields.
  std::vector<std::string> skip = all_but(tilt_settings(), "period");
  skip.erase(std::remove(skip.begin(), skip.end(), "spheroradius"), skip.end());
  add_field_options(app, tilt_settings(), a->period_words, skip);
  app.add_option("--threads", a->threads, "Worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  app.add_option("--bins", a->bins, "Bins of the contact-slope PDF")->capture_default_str();

  app.add_option("-o,--output", a->out, "Write the signature function as CSV (- for standard output)");
  app.add_option("--contacts", a->contacts_out,
                 "Write every contact (offset, x, z, slope, type) as CSV (- for standard output)");
  app.add_option("--pdf", a->pdf_out, "Write the contact-slope PDF as CSV (- for standard output)");
  app.add_flag("--json", a->json, "Print one JSON object with the results");
  return [a]() {
    require(std::isfinite(a->mu_a) && a->mu_a >= 0,
            fmt::format("--atomic-friction: expected a number >= 0, got {}", a->mu_a));
    const Detrend dt = unwrap(parse_detrend(a->detrend));
    const int to_stdout = (a->out == "-") + (a->contacts_out == "-") + (a->pdf_out == "-") + (a->json ? 1 : 0);
    require(to_stdout <= 1, "only one of -o -, --contacts -, --pdf - and --json can write to standard output");
    const std::optional<SurfaceSpec> spec = a->gen.spec();
    if (spec) {
      require(
          a->lower.empty() && a->upper.empty(),
          fmt::format("signature {}: a generated surface is signed against itself; give no files", spec->generator));
      a->lower = spec->generator;
    } else if (a->lower.empty()) {
      throw UsageError(
          "signature: give LOWER [UPPER] files, or a generator (koch, wm, sawtooth, sine, self-affine, fourier)");
    }
    const ReadOptions ro = read_options(a->input);
    // Two files are read at the same time when more than one thread is allowed (parsing a text
    // profile is CPU-bound: ~1 s per 10^7 points); the profiles are the same either way.
    std::future<Profile> upper_read;
    if (!a->upper.empty() && a->threads != 1 && a->upper != "-" && a->lower != "-")
      upper_read =
          std::async(std::launch::async, [&a, &ro, &dt]() { return unwrap(detrend(load_profile(a->upper, ro), dt)); });
    Profile lower = unwrap(detrend(spec ? unwrap(generate_profile(*spec)) : load_profile(a->lower, ro), dt));
    Profile upper_measured = a->upper.empty()     ? lower
                             : upper_read.valid() ? upper_read.get()
                                                  : unwrap(detrend(load_profile(a->upper, ro), dt));
    const ValueSet pv = si_values(tilt_settings(), a->period_words);
    if (pv.count("period")) a->period = as_real(pv.at("period"));
    if (pv.count("spheroradius")) a->spheroradius = as_real(pv.at("spheroradius"));
    if (a->period != 0) {
      require(a->period > 0 && std::isfinite(a->period),
              fmt::format("--period: expected a positive length in m, got {}", a->period));
      lower.period = a->period;
      upper_measured.period = a->period;
      unwrap(validate(lower, a->lower));
      unwrap(validate(upper_measured, a->upper.empty() ? a->lower : a->upper));
    }
    SignatureOptions o;
    o.slopes = (a->slopes == "spline") ? SlopeMethod::Spline : SlopeMethod::Exact;
    o.offsets = a->offsets;
    o.require_exact = a->exact;
    o.threads = a->threads;
    o.bins = a->bins;
    require(a->spheroradius == 0 || a->slopes == "exact",
            "--spheroradius: the rounded faces have their own exact slopes; use --slopes exact");
    o.spheroradius = a->spheroradius;
    o.keep_contacts = !a->contacts_out.empty();
    if (!a->range.empty()) {
      require(a->range[1] > a->range[0], "--offset-range: expected MIN < MAX (m)");
      o.offset_min = a->range[0];
      o.offset_max = a->range[1];
    }
    // The profiles are handed over to the evaluator (no copies: 160 MB each at 10^7 points);
    // what the summary needs of them is taken first.
    const double smax = std::max(profile_stats(lower).max_slope, profile_stats(upper_measured).max_slope);
    Profile upper = rotate180(upper_measured);
    upper_measured = Profile{};
    const auto t0 = std::chrono::steady_clock::now();
    SignatureResult r = unwrap(signature(std::move(lower), std::move(upper), o));
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (a->offsets == 0 && !r.exact)
      fmt::print(stderr,
                 "frictal: note: the two point grids do not align and the exact signature would need more "
                 "event offsets than the limit; sampled {} offsets at the finer point spacing instead, each "
                 "evaluated exactly (--exact refuses instead)\n",
                 r.offset.size());
    FrictionPrediction fwd = unwrap(predict_friction(a->mu_a, r.theta_max_forward, r.contact_slope_std));
    FrictionPrediction bwd = unwrap(predict_friction(a->mu_a, r.theta_max_backward, r.contact_slope_std));

    if (!a->out.empty())
      write_text_rows(a->out, "offset_m,lift_m,theta_deg,theta_min_deg,theta_left_deg,theta_right_deg\n",
                      r.offset.size(), [&r](std::string& s, std::size_t i) {
                        fmt::format_to(std::back_inserter(s), "{:.17g},{:.17g},{:.12g},{:.12g},{:.12g},{:.12g}\n",
                                       r.offset[i], r.lift[i], to_deg(r.theta[i]), to_deg(r.theta_min[i]),
                                       to_deg(r.theta_left[i]), to_deg(r.theta_right[i]));
                      });
    if (!a->contacts_out.empty())
      write_text_rows(
          a->contacts_out, "offset_m,x_m,z_m,slope_deg,type\n", r.offset.size(),
          [&r](std::string& s, std::size_t i) {
            for (auto k = r.contact_begin[i]; k < r.contact_begin[i + 1]; ++k) {
              const Contact& c = r.contacts[k];
              fmt::format_to(std::back_inserter(s), "{:.17g},{:.17g},{:.17g},{:.12g},{}\n", r.offset[i], c.x, c.z,
                             to_deg(c.slope), contact_type_name(c.type));
            }
          },
          "--contacts");
    if (!a->pdf_out.empty()) {
      std::string s = "slope_lo_deg,slope_hi_deg,density_per_deg\n";
      const auto& h = r.contact_slope_pdf;
      for (std::size_t i = 0; i < h.density.size(); ++i)
        s += fmt::format("{:.12g},{:.12g},{:.12g}\n", to_deg(h.edges[i]), to_deg(h.edges[i + 1]), h.density[i] * kDeg);
      write_text_output(a->pdf_out, s, "--pdf");
    }
    if (a->json) {
      nlohmann::json j;
      j["lower"] = a->lower;
      j["upper"] = a->upper.empty() ? a->lower : a->upper;
      j["slopes"] = a->slopes;
      j["spheroradius_m"] = r.spheroradius;
      j["exact"] = r.exact;
      j["offsets"] = r.offset.size();
      j["offset_range_m"] = {r.offset.front(), r.offset.back()};
      j["theta_max_forward_deg"] = to_deg(r.theta_max_forward);
      j["theta_max_backward_deg"] = to_deg(r.theta_max_backward);
      j["offset_at_forward_m"] = r.offset_at_forward;
      j["offset_at_backward_m"] = r.offset_at_backward;
      j["contact_slope_mean_deg"] = to_deg(r.contact_slope_mean);
      j["contact_slope_std_deg"] = to_deg(r.contact_slope_std);
      j["surface_slope_max_deg"] = to_deg(smax);
      j["atomic_friction"] = a->mu_a;
      j["atomic_friction_angle_deg"] = to_deg(fwd.atomic_angle);
      j["friction_angle_deg"] = to_deg(fwd.friction_angle);
      j["friction_coefficient"] = fwd.friction_coefficient;
      j["friction_angle_low_deg"] = to_deg(fwd.friction_angle_low);
      j["friction_coefficient_low"] = fwd.friction_coefficient_low;
      j["friction_angle_backward_deg"] = to_deg(bwd.friction_angle);
      j["friction_coefficient_backward"] = bwd.friction_coefficient;
      j["wall_time_s"] = wall;
      print_json(j);
    } else {
      // With a CSV on standard output, the summary goes to standard error.
      std::FILE* text = to_stdout ? stderr : stdout;
      fmt::print(text, "signature: {} offsets ({}) from {:.6g} to {:.6g} m in {:.3f} s\n", r.offset.size(),
                 r.exact ? "every event, exact" : "sampled", r.offset.front(), r.offset.back(), wall);
      if (r.spheroradius > 0)
        fmt::print(text, "  spheropolygons: spheroradius r = {:.6g} m (one core against the other dilated by 2r)\n",
                   r.spheroradius);
      fmt::print(text, "  theta_max forward  (+x) {:10.4f} deg at offset {:.6g} m\n", to_deg(r.theta_max_forward),
                 r.offset_at_forward);
      fmt::print(text, "  theta_max backward (-x) {:10.4f} deg at offset {:.6g} m\n", to_deg(r.theta_max_backward),
                 r.offset_at_backward);
      fmt::print(text, "  contact slope mean {:.4f} deg, std (sigma) {:.4f} deg; max surface slope {:.4f} deg\n",
                 to_deg(r.contact_slope_mean), to_deg(r.contact_slope_std), to_deg(smax));
      fmt::print(text,
                 "friction (mu_a = {}): phi = {:.4f} deg, mu = {:.6g}; Eq. 18 range phi in [{:.4f}, {:.4f}] deg; "
                 "backward phi = {:.4f} deg\n",
                 a->mu_a, to_deg(fwd.friction_angle), fwd.friction_coefficient, to_deg(fwd.friction_angle_low),
                 to_deg(fwd.friction_angle), to_deg(bwd.friction_angle));
    }
    return 0;
  };
}

FRICTAL_COMMAND({"signature", "Signature function theta(x_ofs) of two surfaces and the friction prediction", setup,
                 20});

}  // namespace
}  // namespace frictal::cli
