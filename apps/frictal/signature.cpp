// frictal signature LOWER [UPPER] | signature <generator> [options] — the signature function and
// the friction prediction, of two measured surfaces or of a generated surface with itself.
#include <algorithm>
#include <array>
#include <chrono>
#include <fstream>
#include <future>
#include <iterator>
#include <thread>

#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/hold.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"
#include "frictal/tilt.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

// The hold analysis as JSON keys: its output tables (frictal/hold.hpp), in interface units.
void add_hold_json(nlohmann::json& j, const HoldAnalysis& h) {
  put_columns(j, hold_columns(), h);
  if (h.has_start) put_columns(j, hold_start_columns(), h);
}

void print_hold_text(std::FILE* text, const HoldAnalysis& h, const FrictionPrediction& eq18) {
  const HoldDistribution& f = h.distribution.forward;
  const HoldDistribution& b = h.distribution.backward;
  fmt::print(text,
             "hold angle (what a tilt test reads; run-away d = {:.6g} m, drops over [{:.6g}, {:.6g}] m, {} basins):\n",
             h.runaway_distance, f.drop_min, f.drop_max, f.basins.rest.size());
  auto line = [text](const char* what, const HoldStatistics& s) {
    fmt::print(
        text, "  {} mean {:.4f} deg, std {:.4f} deg, 5/50/95 % {:.4f} / {:.4f} / {:.4f} deg, range [{:.4f}, {:.4f}]\n",
        what, to_deg(s.mean), to_deg(s.std), to_deg(s.q05), to_deg(s.q50), to_deg(s.q95), to_deg(s.min), to_deg(s.max));
  };
  line("forward  quasi-static", f.hold);
  line("forward  inertial    ", f.inertial);
  line("backward quasi-static", b.hold);
  line("backward inertial    ", b.inertial);
  fmt::print(text,
             "  Eq. 18 range [theta_max - sigma, theta_max] + theta_a = [{:.4f}, {:.4f}] deg; drops' 5-95 % [{:.4f}, "
             "{:.4f}] deg\n",
             to_deg(eq18.friction_angle_low), to_deg(eq18.friction_angle), to_deg(f.hold.q05), to_deg(f.hold.q95));
  if (h.has_start) {
    for (const auto& [name, a] : {std::pair{"forward ", h.start.forward}, std::pair{"backward", h.start.backward}})
      fmt::print(text,
                 "  {} from the start: rests at {:.6g} m, held up to {:.4f} deg by the stop at {:.6g} m (after {} "
                 "short slips{}); inertial bound {:.4f} deg\n",
                 name, a.rest_offset, to_deg(a.hold_angle), a.hold_offset, a.slips,
                 a.ran_off_end ? ", then off the end of the lift" : "", to_deg(a.inertial_hold_angle));
  }
}

struct Args {
  std::string lower, upper, out, contacts_out, pdf_out;
  double mu_a = 0;
  double period = 0;
  unsigned threads = 0;
  bool json = false;
  double start_offset = std::numeric_limits<double>::quiet_NaN();
  bool no_hold = false;
  std::string detrend;  ///< --detrend (empty: form_to_remove's default)
  GeneratorOptions gen;
  InputOptions input;        ///< --format, --unit, --spacing, ... of LOWER and UPPER
  ConditioningOptions cond;  ///< --crop, --remove-spikes, --spike-threshold (before --detrend)
  FieldWords period_words;   ///< --period and --runaway-distance, the quantities shared with the tilt test
  FieldWords words;          ///< the signature's settings (signature_settings()) as typed
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
  // --slopes, --offsets, --keep-grid, --exact, --offset-range, --bins, --spheroradius: the
  // signature's settings table; --offset-range takes its two lengths as two words (MIN MAX).
  add_field_options(app, signature_settings(), a->words, {"offset_range"});
  {
    const Field& f = *find_field(signature_settings(), "offset_range");
    app.add_option_function<std::vector<std::string>>(
           cli_option_name(f),
           [a](const std::vector<std::string>& w) {
             a->words.words.insert_or_assign("offset_range", w.at(0) + " " + w.at(1));
           },
           field_help(f))
        ->expected(2)
        ->type_name("LENGTH");
  }
  add_detrend_option(app, a->detrend);
  add_conditioning_options(app, a->cond);
  // --period and --runaway-distance (the hold angle's run-away): the quantities shared with the tilt
  // test and the prediction (shared_field), one description everywhere.
  std::vector<std::string> skip = all_but(tilt_settings(), "period");
  skip.erase(std::remove(skip.begin(), skip.end(), "runaway_distance"), skip.end());
  add_field_options(app, tilt_settings(), a->period_words, skip);
  app.add_option("--threads", a->threads, "Worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  app.add_option("--start-offset", a->start_offset,
                 "Hold angle of a block put down at this offset (m, inside the offset range): where it rests, the "
                 "tilt that holds it (quasi-static) and its inertial bound; without it, the distribution over drops");
  app.add_flag("--no-hold", a->no_hold,
               "Skip the hold-angle analysis (which reads the signature's lift, and for a non-periodic pair "
               "the lift a run-away distance or two beyond the offset range)");

  app.add_option("-o,--output", a->out, "Write the signature function as CSV (- for standard output)");
  app.add_option("--contacts", a->contacts_out,
                 "Write every contact (offset, x, z, slope, type) as CSV (- for standard output)");
  app.add_option("--pdf", a->pdf_out, "Write the contact-slope PDF as CSV (- for standard output)");
  app.add_flag("--json", a->json, "Print one JSON object with the results");
  return [a]() {
    require(std::isfinite(a->mu_a) && a->mu_a >= 0,
            fmt::format("--atomic-friction: expected a number >= 0, got {}", a->mu_a));
    const std::optional<SurfaceSpec> spec = a->gen.spec();
    const ValueSet pv = si_values(tilt_settings(), a->period_words);
    if (pv.count("period")) a->period = as_real(pv.at("period"));
    const ValueSet sv = si_values(signature_settings(), a->words);
    require(!sv.count("spheroradius") || as_real(sv.at("spheroradius")) == 0 || !sv.count("slopes") ||
                std::get<std::string>(sv.at("slopes")) == "exact",
            "--spheroradius: the rounded faces have their own exact slopes; use --slopes exact");
    SignatureOptions o = unwrap(make_signature_options(sv));
    const Conditioning cond = conditioning(a->cond, form_to_remove(a->detrend, spec.has_value(), a->period > 0));
    const int to_stdout = (a->out == "-") + (a->contacts_out == "-") + (a->pdf_out == "-") + (a->json ? 1 : 0);
    require(to_stdout <= 1, "only one of -o -, --contacts -, --pdf - and --json can write to standard output");
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
    // Warnings as results: the readers' (printed as they read) and the plausibility checks of each
    // profile as it enters the signature (warnings.hpp).
    std::vector<Warning> warnings;
    // Each side's warnings apart (the two files may be read at the same time), then lower's
    // before upper's: the same order on every run.
    std::array<std::vector<Warning>, 2> side_warnings;
    auto load = [&](const std::string& path, int side) {
      SurfaceData sd = unwrap(read_surface(input_path(path), ro));
      for (Warning& w : sd.warnings) add_warning(side_warnings[side], {std::move(w.code), stdin_name(w.message)});
      return surface_profile(std::move(sd), path);
    };
    // Each profile conditioned (crop, spikes, form: conditioning.hpp), its record kept.
    std::vector<ConditioningRecord> records(a->upper.empty() ? 1 : 2);
    // Each side's steepest edge (the summary's surface_slope_max_deg), taken while the side is
    // read: the two sides at the same time, not one after the other once both are in.
    std::array<double, 2> side_max_slope{0, 0};
    auto conditioned = [&](Profile p, const std::string& name, int side) {
      Conditioning own = cond;  // a file's own period (as --period) makes the default the mean
      if (a->detrend.empty() && !spec && p.period) own.form = default_form(true);
      ConditionedProfile c = unwrap(condition(std::move(p), own, name));
      records[std::size_t(side)] = c.record;
      for (Warning& x : check_profile(c.profile, name)) add_warning(side_warnings[side], std::move(x));
      side_max_slope[std::size_t(side)] = max_slope_angle(c.profile);
      return std::move(c.profile);
    };
    // Two files are read at the same time when more than one thread is allowed (parsing a text
    // profile is CPU-bound: ~1 s per 10^7 points); the profiles are the same either way.
    std::future<Profile> upper_read;
    if (!a->upper.empty() && a->threads != 1 && a->upper != "-" && a->lower != "-")
      upper_read = std::async(std::launch::async,
                              [&a, &conditioned, &load]() { return conditioned(load(a->upper, 1), a->upper, 1); });
    Profile lower = conditioned(spec ? unwrap(generate_profile(*spec)) : load(a->lower, 0), a->lower, 0);
    Profile upper_measured = a->upper.empty()     ? lower
                             : upper_read.valid() ? upper_read.get()
                                                  : conditioned(load(a->upper, 1), a->upper, 1);
    for (auto& side : side_warnings)
      for (Warning& w : side) add_warning(warnings, std::move(w));
    if (!a->upper.empty()) {  // two scans of one pair: of similar size (as predict and tilt check)
      auto length = [](const Profile& p) { return p.x.back() - p.x.front(); };
      auto spacing = [&](const Profile& p) { return length(p) / double(p.x.size() - 1); };
      for (Warning& w : check_pair_scales(length(lower), spacing(lower), length(upper_measured),
                                          spacing(upper_measured), a->lower, a->upper))
        add_warning(warnings, std::move(w));
    }
    const double runaway = pv.count("runaway_distance") ? as_real(pv.at("runaway_distance")) : 0.0;
    require(!a->no_hold || (std::isnan(a->start_offset) && runaway == 0),
            "--no-hold: --start-offset and --runaway-distance ask for the hold analysis");
    require(!std::isinf(a->start_offset),
            fmt::format("--start-offset: expected a finite offset in m, got {}", a->start_offset));
    if (a->period != 0) {
      require(a->period > 0 && std::isfinite(a->period),
              fmt::format("--period: expected a positive length in m, got {}", a->period));
      lower.period = a->period;
      upper_measured.period = a->period;
      unwrap(validate(lower, a->lower));
      unwrap(validate(upper_measured, a->upper.empty() ? a->lower : a->upper));
    }
    o.threads = a->threads;
    o.keep_contacts = !a->contacts_out.empty();
    // The profiles are handed over to the evaluator (no copies: 160 MB each at 10^7 points);
    // what the summary needs of them is taken first.
    const double smax = std::max(side_max_slope[0], a->upper.empty() ? side_max_slope[0] : side_max_slope[1]);
    Profile upper = rotate180(std::move(upper_measured));  // in place
    // The hold angle (what a tilt test reads), from the same lift in one pass.
    std::optional<HoldAnalysis> hold;
    double hold_wall = 0;
    const auto t0 = std::chrono::steady_clock::now();
    SignatureResult r;
    if (!a->no_hold) {
      HoldOptions ho;
      ho.runaway_distance = runaway;
      ho.atomic_friction = a->mu_a;
      ho.keep_curve = !a->out.empty();  // the lift's basins are written with --out only
      // The profiles handed over.
      SignatureWithHold both = unwrap(signature_with_hold(std::move(lower), std::move(upper), o, ho, a->start_offset));
      r = std::move(both.signature);
      hold = std::move(both.hold);
    } else {
      r = unwrap(signature(std::move(lower), std::move(upper), o));
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (hold) hold_wall = wall;
    if (r.grid_replaced)
      fmt::print(stderr,
                 "frictal: note: --offsets {}: the two point grids align, and the exact signature's {} event offsets "
                 "cost less than {} offsets off the grid; computed every event instead (exact)\n",
                 o.offsets, r.offset.size(), o.offsets);
    if (o.offsets == 0 && !r.exact)
      fmt::print(stderr,
                 "frictal: note: the two point grids do not align and the exact signature would need more "
                 "event offsets than the limit; sampled {} offsets at the finer point spacing instead, each "
                 "evaluated exactly (--exact refuses instead)\n",
                 r.offset.size());
    FrictionPrediction fwd = unwrap(predict_friction(a->mu_a, r.theta_max_forward, r.contact_slope_std));
    FrictionPrediction bwd = unwrap(predict_friction(a->mu_a, r.theta_max_backward, r.contact_slope_std));
    for (Warning& w : check_signature_bounds(fwd, bwd)) add_warning(warnings, std::move(w));

    if (!a->out.empty()) {
      // The basin each offset drains into at zero tilt (numbered along the hold analysis' lift).
      const std::vector<std::int32_t> basin = hold ? basin_index(hold->curve, r.offset) : std::vector<std::int32_t>{};
      write_text_rows(a->out,
                      std::string("offset_m,lift_m,theta_deg,theta_min_deg,theta_left_deg,theta_right_deg") +
                          (hold ? ",basin\n" : "\n"),
                      r.offset.size(), [&r, &basin](std::string& s, std::size_t i) {
                        fmt::format_to(std::back_inserter(s), "{:.17g},{:.17g},{:.12g},{:.12g},{:.12g},{:.12g}",
                                       r.offset[i], r.lift[i], to_deg(r.theta[i]), to_deg(r.theta_min[i]),
                                       to_deg(r.theta_left[i]), to_deg(r.theta_right[i]));
                        if (basin.empty())
                          s += '\n';
                        else
                          fmt::format_to(std::back_inserter(s), ",{}\n", basin[i]);
                      });
    }
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
      RunRecord run;
      run.lower = a->lower;
      run.upper = a->upper.empty() ? a->lower : a->upper;
      run.slopes = o.slopes == SlopeMethod::Spline ? "spline" : "exact";
      run.surface_slope_max = smax;
      run.conditioning = conditioning_text(records);
      run.warnings = warnings;
      run.wall_time = wall;
      run.hold_wall_time = hold_wall;  // the one pass: signature and hold analysis together
      nlohmann::json j = object_of(signature_columns(), r);
      put_columns(j, friction_columns(), fwd);
      put_columns(j, friction_backward_columns(), bwd);
      if (hold) add_hold_json(j, *hold);
      put_columns(j, run_record_columns(), run);
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
      fmt::print(text, "  conditioning: {}\n", conditioning_text(records));
      fmt::print(text,
                 "rigid upper bound (mu_a = {}): theta_max + theta_a = {:.4f} deg, mu <= {:.6g}; Eq. 18 range [{:.4f}, "
                 "{:.4f}] deg; backward {:.4f} deg (what a tilt test reads: frictal predict)\n",
                 a->mu_a, to_deg(fwd.friction_angle), fwd.friction_coefficient, to_deg(fwd.friction_angle_low),
                 to_deg(fwd.friction_angle), to_deg(bwd.friction_angle));
      if (hold) print_hold_text(text, *hold, fwd);
      print_warnings(warnings);
    }
    return 0;
  };
}

FRICTAL_COMMAND({"signature", "Signature function theta(x_ofs) of two surfaces and the friction prediction", setup,
                 20});

}  // namespace
}  // namespace frictal::cli
