// frictal contact LOWER [UPPER] — elastic normal contact of rough surfaces (frictal/contact.hpp):
// LOWER alone is an elastic body pressed against a rigid flat; LOWER and UPPER are two elastic
// bodies (the same material unless --upper-modulus/--upper-poisson say otherwise) whose composite
// topography is pressed against a rigid flat. One load, or a list of loads (a load curve).
#include <cmath>
#include <cstdlib>

#include "common.hpp"
#include "frictal/conditioning.hpp"
#include "frictal/contact.hpp"
#include "map_hold.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string lower, upper, detrend;
  std::vector<std::string> loads;
  std::string modulus, poisson, upper_modulus, upper_poisson, hardness;
  bool periodic = false, json = false, no_stiffness = false;
  FieldWords predict_words;  ///< --in-place (the prediction's table: one help text)
  double tolerance = ContactOptions{}.tolerance;
  unsigned threads = 1;
  InputOptions input;
  ConditioningOptions cond;
};

/// --load's words: a force (N, mN, kN), a force per unit length (N/m, for profiles) or a nominal
/// pressure (Pa, kPa, MPa, GPa); comma-separated lists allowed.
std::vector<ContactLoad> parse_loads(const std::vector<std::string>& words, bool is_map) {
  std::vector<ContactLoad> loads;
  for (const std::string& item : list_items(words)) {
    const char* s = item.c_str();
    char* end = nullptr;
    const double v = std::strtod(s, &end);
    std::string unit(end);
    while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
    if (end == s || !std::isfinite(v) || unit.empty())
      throw UsageError(fmt::format(
          "--load '{}': expected a number with its unit: a force ({}) or a nominal pressure (Pa, kPa, MPa, GPa)", item,
          is_map ? "N, mN, kN" : "per unit length for a profile: N/m"));
    ContactLoad l;
    l.value = v;
    bool known = false;
    for (const auto& [name, factor] : kPressureUnits)
      if (!name.empty() && unit == name) l.kind = ContactLoadKind::Pressure, l.value = v * factor, known = true;
    const std::vector<std::pair<std::string, double>> forces = {{"N", 1}, {"mN", 1e-3}, {"kN", 1e3}};
    for (const auto& [name, factor] : forces) {
      if (unit == name) {
        if (!is_map)
          throw UsageError(
              fmt::format("--load '{}': a profile is in plane strain and takes a force per unit length "
                          "of its depth (e.g. {}/m) or a nominal pressure (Pa)",
                          item, item));
        l.kind = ContactLoadKind::Force, l.value = v * factor, known = true;
      }
      if (unit == name + "/m") {
        if (is_map)
          throw UsageError(fmt::format("--load '{}': a map takes a total force (N) or a nominal pressure (Pa)", item));
        l.kind = ContactLoadKind::Force, l.value = v * factor, known = true;
      }
    }
    if (!known)
      throw UsageError(fmt::format("--load '{}': unit '{}' not understood (expected {}, or Pa, kPa, MPa, GPa)", item,
                                   unit, is_map ? "N, mN, kN" : "N/m, mN/m, kN/m"));
    if (!(l.value > 0)) throw UsageError(fmt::format("--load '{}': expected a load > 0", item));
    loads.push_back(l);
  }
  if (loads.empty()) throw UsageError("--load: give at least one load (e.g. 2N, 1e7Pa)");
  return loads;
}

struct Surface {
  bool is_map = false;
  Map map;
  Profile profile;
  std::string record;
};

Surface read(const std::string& path, const Args& a, const Conditioning& c, std::vector<Warning>& warnings) {
  SurfaceData s = load_surface(path, a.input);
  for (const auto& w : s.warnings) add_warning(warnings, w);
  Surface out;
  out.is_map = s.is_map;
  if (s.is_map) {
    const double read_rms = rms_height_as_read(s.map.heights);
    ConditionedMap m = unwrap(condition(s.map, c, path));
    for (Warning& w : check_map(m.map, path, {}, read_rms)) add_warning(warnings, std::move(w));
    out.map = std::move(m.map);
    out.record = m.record.text();
  } else {
    Profile read = surface_profile(std::move(s), path);
    const double read_rms = rms_height_as_read(read.z);
    ConditionedProfile p = unwrap(condition(std::move(read), c, path));
    for (Warning& w : check_profile(p.profile, path, {}, read_rms)) add_warning(warnings, std::move(w));
    std::vector<Warning> resampled;
    out.profile = unwrap(equally_spaced(p.profile, path, resampled));
    for (Warning& w : resampled) add_warning(warnings, std::move(w));
    out.record = p.record.text();
  }
  return out;
}

std::string si_text(double v, const char* unit) {
  return std::isfinite(v) ? fmt::format("{:.5g} {}", v, unit) : std::string(std::isinf(v) ? "inf" : "n/a");
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("lower", a->lower,
                 "Lower surface: a line profile or an areal map (any readable format); alone, it is pressed against a "
                 "rigid flat")
      ->required();
  app.add_option("upper", a->upper,
                 "Upper surface, as measured (turned over onto LOWER): the two bodies' composite topography is pressed "
                 "against a rigid flat (the same grid as LOWER)");
  app.add_option("--load", a->loads,
                 "Load(s) with their unit: a force (maps: N, mN, kN; profiles, per unit depth: N/m) or a nominal "
                 "pressure (Pa, kPa, MPa, GPa); several (or a comma-separated list) give a load curve")
      ->required();
  app.add_option("--modulus", a->modulus,
                 "Young's modulus E of LOWER (and of UPPER unless --upper-modulus): Pa, MPa, GPa")
      ->required();
  app.add_option("--poisson", a->poisson,
                 "Poisson's ratio nu of LOWER (and of UPPER unless --upper-poisson), in (-1, 0.5]")
      ->required();
  app.add_option("--upper-modulus", a->upper_modulus,
                 "Young's modulus of UPPER (default: --modulus); 'rigid' for a rigid UPPER");
  app.add_option("--upper-poisson", a->upper_poisson, "Poisson's ratio of UPPER (default: --poisson)");
  app.add_option("--hardness", a->hardness,
                 "Hardness H: the pressure is capped at H (perfect plasticity), Pa, MPa, GPa (default: elastic)");
  app.add_flag("--periodic", a->periodic,
               "The surface repeats with its length (a generated periodic surface); default: not periodic (padded)");
  add_predict_options(app, a->predict_words, {"in_place"});
  add_detrend_option(app, a->detrend);
  add_conditioning_options(app, a->cond);
  app.add_option("--tolerance", a->tolerance,
                 "Convergence: gap residual over the rms height of the composite topography")
      ->capture_default_str();
  app.add_flag("--no-stiffness", a->no_stiffness, "Skip the contact stiffness (one linear solve less per load)");
  app.add_option("--threads", a->threads, "FFT threads (0 = all cores)")->capture_default_str();
  add_input_options(app, a->input);
  app.add_flag("--json", a->json,
               "Print one JSON object (the keys of `frictal columns`, table contact; several loads: a list under "
               "'curve')");
  return [a]() {
    const double E = parse_quantity(a->modulus, "--modulus", kPressureUnits, "a modulus such as 2e11, 200GPa");
    const double nu = parse_quantity(a->poisson, "--poisson", {{"", 1}}, "a number in (-1, 0.5]");
    ContactOptions o;
    const ElasticMaterial first{E, nu};
    if (a->upper.empty()) {
      require(a->upper_modulus.empty() && a->upper_poisson.empty(),
              "--upper-modulus/--upper-poisson: apply to UPPER, which is not given (LOWER alone is pressed against a "
              "rigid flat)");
      o.contact_modulus = unwrap(contact_modulus(first));
    } else if (a->upper_modulus == "rigid") {
      require(a->upper_poisson.empty(), "--upper-poisson: a rigid UPPER has none");
      o.contact_modulus = unwrap(contact_modulus(first));
    } else {
      ElasticMaterial second = first;
      if (!a->upper_modulus.empty())
        second.modulus =
            parse_quantity(a->upper_modulus, "--upper-modulus", kPressureUnits, "a modulus such as 70GPa, or rigid");
      if (!a->upper_poisson.empty())
        second.poisson = parse_quantity(a->upper_poisson, "--upper-poisson", {{"", 1}}, "a number");
      o.contact_modulus = unwrap(contact_modulus(first, second));
    }
    if (!a->hardness.empty()) {
      o.hardness = parse_quantity(a->hardness, "--hardness", kPressureUnits, "a pressure such as 2GPa");
      require(o.hardness > 0, fmt::format("--hardness '{}': expected a pressure > 0", a->hardness));
    }
    require(std::isfinite(a->tolerance) && a->tolerance > 0 && a->tolerance < 1,
            fmt::format("--tolerance {}: expected a number in (0, 1)", a->tolerance));
    o.tolerance = a->tolerance;
    o.periodic = a->periodic;
    o.threads = a->threads;
    o.stiffness = !a->no_stiffness;
    o.keep_fields = false;
    std::vector<Warning> warnings;
    const bool in_place = predict_flag(a->predict_words, "in_place");
    const Conditioning cond = conditioning(a->cond, form_to_remove(a->detrend, false));
    Surface lower = read(a->lower, *a, cond, warnings);
    std::string record = lower.record;
    if (!a->upper.empty()) {
      Surface upper = read(a->upper, *a, cond, warnings);
      require(upper.is_map == lower.is_map,
              fmt::format("{} and {}: a profile and a map; give two profiles or two maps", a->lower, a->upper));
      record += "; " + upper.record;
      if (lower.is_map)
        lower.map = unwrap(composite_topography(lower.map, upper.map, !in_place, a->lower, a->upper));
      else
        lower.profile = unwrap(composite_topography(lower.profile, upper.profile, !in_place, a->lower, a->upper));
    } else {
      require(!in_place, "--in-place: applies to UPPER, which is not given");
    }
    const std::vector<ContactLoad> loads = parse_loads(a->loads, lower.is_map);
    const std::vector<ContactResult> results = lower.is_map ? unwrap(solve_contact_curve(lower.map, loads, o))
                                                            : unwrap(solve_contact_curve(lower.profile, loads, o));
    double wall = 0;
    for (const ContactResult& r : results) {
      wall += r.wall_time;
      for (const Warning& w : r.warnings) add_warning(warnings, w);
    }
    if (a->json) {
      RunRecord run;
      run.lower = a->lower;
      if (!a->upper.empty()) run.upper = a->upper;
      run.kind = lower.is_map ? "map" : "profile";
      run.conditioning = record;
      run.wall_time = wall;
      run.warnings = warnings;
      nlohmann::json j;
      if (results.size() == 1)
        put_columns(j, contact_columns(), results.front());
      else
        put_columns(j, contact_curve_columns(), ContactCurve{results});
      put_columns(j, run_record_columns(), run);
      print_json(j);
    } else {
      const ContactResult& f = results.front();
      fmt::print("frictal contact: {}{} ({}, {} x {} points, {}), E* = {:.5g} Pa{}\n", a->lower,
                 a->upper.empty() ? " on a rigid flat" : " against " + a->upper, lower.is_map ? "map" : "profile", f.nx,
                 f.ny, f.periodic ? "periodic" : "not periodic", f.contact_modulus,
                 f.hardness > 0 ? fmt::format(", H = {:.5g} Pa", f.hardness) : std::string());
      for (const ContactResult& r : results) {
        fmt::print(
            "  load {} (nominal {:.5g} Pa): contact {:.4g} % ({}), max pressure {:.5g} Pa, mean separation {}, "
            "approach {}, stiffness {}\n",
            r.is_map ? si_text(r.force, "N") : si_text(r.force, "N/m"), r.nominal_pressure, 100 * r.contact_fraction,
            r.is_map ? si_text(r.contact_area, "m^2") : si_text(r.contact_length, "m"), r.max_pressure,
            si_text(r.mean_separation, "m"), si_text(r.approach, "m"),
            r.is_map ? si_text(r.stiffness, "N/m") : si_text(r.stiffness, "N/m per m"));
      }
      fmt::print("  conditioning: {}\n", record);
      print_warnings(warnings);
    }
    return 0;
  };
}

FRICTAL_COMMAND({"contact",
                 "Elastic normal contact of rough surfaces against a flat: contact area, pressure, mean separation "
                 "and stiffness at given loads",
                 setup, 40});

}  // namespace
}  // namespace frictal::cli
