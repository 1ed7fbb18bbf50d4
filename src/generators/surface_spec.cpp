// Surface specification (surface_spec.hpp): one table of fields per generator, bound to the
// generator's parameter struct (whose initialisers are the defaults).
#include "frictal/surface_spec.hpp"

#include <algorithm>
#include <numbers>

#include <fmt/core.h>

#include "settings/binding.hpp"

namespace frictal {
namespace {

using settings_detail::bind;
using settings_detail::bind_choice;
using settings_detail::Binding;
using settings_detail::with_defaults;

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A field with a range; `type` is set by bind() from the member's C++ type.
Field F(std::string name, std::string unit, double min, double max, bool min_open, bool max_open, std::string help,
        char short_name = 0) {
  Field f;
  f.name = std::move(name);
  f.unit = std::move(unit);
  f.min = min;
  f.max = max;
  f.min_open = min_open;
  f.max_open = max_open;
  f.help = std::move(help);
  f.short_name = short_name;
  return f;
}

const std::vector<Binding<KochParams>>& koch_table() {
  static const auto t = with_defaults<KochParams>(
      {bind<KochParams>(F("iterations", "", 0, 10, false, false, "Number of Koch iterations n (K_n)", 'n'),
                        [](KochParams& p) -> int& { return p.iterations; }),
       bind<KochParams>(F("alpha", "rad", 0, kPi / 3 + 1e-12, true, false, "Base angle of the Koch triangles alpha"),
                        [](KochParams& p) -> double& { return p.alpha; }),
       bind<KochParams>(F("wavelength", "m", 0, kInf, true, false, "Wavelength lambda: base of the K_0 triangles"),
                        [](KochParams& p) -> double& { return p.wavelength; }),
       bind<KochParams>(
           F("length", "m", 0, kInf, true, false, "Length L_b of the surface, a whole number of wavelengths"),
           [](KochParams& p) -> double& { return p.length; })},
      KochParams{});
  return t;
}

const std::vector<Binding<WmParams>>& wm_table() {
  static const auto t = with_defaults<WmParams>(
      {bind<WmParams>(F("dimension", "", 1, 2, false, false, "Fractal dimension D", 'D'),
                      [](WmParams& p) -> double& { return p.dimension; }),
       bind<WmParams>(F("gamma", "", 1, kInf, true, false, "Wavelength density gamma"),
                      [](WmParams& p) -> double& { return p.gamma; }),
       bind<WmParams>(F("n_max", "", 0, 60, false, false, "Highest wavelength index n_max"),
                      [](WmParams& p) -> int& { return p.n_max; }),
       bind<WmParams>(F("longest_wavelength", "m", 0, kInf, true, false, "Longest wavelength L"),
                      [](WmParams& p) -> double& { return p.longest_wavelength; }),
       bind<WmParams>(F("length", "m", 0, kInf, true, false, "Length L_b of the surface"),
                      [](WmParams& p) -> double& { return p.length; }),
       bind<WmParams>(F("rms_height", "m", -kInf, kInf, false, false, "RMS height about the mean; <= 0 keeps G = 1 m"),
                      [](WmParams& p) -> double& { return p.rms_height; }),
       bind<WmParams>(F("stochastic", "", 0, 1, false, false, "Random phases (Eq. 14); false: zero phases (Eq. 17)"),
                      [](WmParams& p) -> bool& { return p.stochastic; }),
       bind<WmParams>(F("seed", "", 0, 9.2e18, false, false, "Seed of the random phases or heights"),
                      [](WmParams& p) -> std::uint64_t& { return p.seed; }),
       bind_choice<WmParams>(
           F("exponent", "", 0, 0, false, false,
             "Exponent of Eq. 14: printed gamma^{2(D-2)n} or common gamma^{(D-2)n}"),
           [](WmParams& p) -> WmExponent& { return p.exponent; },
           std::vector<std::pair<std::string, WmExponent>>{{"printed", WmExponent::Printed},
                                                           {"common", WmExponent::Common}}),
       bind<WmParams>(F("spacing", "m", 0, kInf, false, false, "Point spacing dx; 0: L_s / 10 (Eq. 16)"),
                      [](WmParams& p) -> double& { return p.spacing; })},
      WmParams{});
  return t;
}

const std::vector<Binding<SawtoothParams>>& sawtooth_table() {
  static const auto t = with_defaults<SawtoothParams>(
      {bind<SawtoothParams>(F("rise_angle", "rad", 0, kPi / 2, true, true, "Slope angle of the rising flank"),
                            [](SawtoothParams& p) -> double& { return p.rise_angle; }),
       bind<SawtoothParams>(F("rise_fraction", "", 0, 1, true, true, "Fraction of the wavelength that rises"),
                            [](SawtoothParams& p) -> double& { return p.rise_fraction; }),
       bind<SawtoothParams>(F("wavelength", "m", 0, kInf, true, false, "Wavelength lambda"),
                            [](SawtoothParams& p) -> double& { return p.wavelength; }),
       bind<SawtoothParams>(
           F("length", "m", 0, kInf, true, false, "Length L_b of the surface, a whole number of wavelengths"),
           [](SawtoothParams& p) -> double& { return p.length; })},
      SawtoothParams{});
  return t;
}

const std::vector<Binding<SineParams>>& sine_table() {
  static const auto t = with_defaults<SineParams>(
      {bind<SineParams>(F("amplitude", "m", 0, kInf, false, false, "Amplitude A of z = A sin(2 pi x / lambda)"),
                        [](SineParams& p) -> double& { return p.amplitude; }),
       bind<SineParams>(F("wavelength", "m", 0, kInf, true, false, "Wavelength lambda"),
                        [](SineParams& p) -> double& { return p.wavelength; }),
       bind<SineParams>(
           F("length", "m", 0, kInf, true, false, "Length L_b of the surface, a whole number of wavelengths"),
           [](SineParams& p) -> double& { return p.length; }),
       bind<SineParams>(F("points_per_wavelength", "", 4, 1e7, false, false, "Samples per wavelength"),
                        [](SineParams& p) -> int& { return p.points_per_wavelength; })},
      SineParams{});
  return t;
}

const std::vector<Binding<SelfAffineParams>>& self_affine_table() {
  static const auto t = with_defaults<SelfAffineParams>(
      {bind<SelfAffineParams>(F("points", "", 16, 5e8, false, false, "Number of points"),
                              [](SelfAffineParams& p) -> std::size_t& { return p.points; }),
       bind<SelfAffineParams>(F("length", "m", 0, kInf, true, false, "Length L_b of the surface"),
                              [](SelfAffineParams& p) -> double& { return p.length; }),
       bind<SelfAffineParams>(F("hurst", "", 0, 1, true, false, "Hurst exponent H"),
                              [](SelfAffineParams& p) -> double& { return p.hurst; }),
       bind<SelfAffineParams>(
           F("rms_height", "m", -kInf, kInf, false, false, "RMS height about the mean; <= 0 keeps the raw heights"),
           [](SelfAffineParams& p) -> double& { return p.rms_height; }),
       bind<SelfAffineParams>(F("seed", "", 0, 9.2e18, false, false, "Seed of the random phases or heights"),
                              [](SelfAffineParams& p) -> std::uint64_t& { return p.seed; })},
      SelfAffineParams{});
  return t;
}

const std::vector<Binding<FourierSelfAffineParams>>& fourier_table() {
  using P = FourierSelfAffineParams;
  static const auto t = with_defaults<P>(
      {bind<P>(F("points", "", 8, 67108864, false, false, "Samples per period N (the profile has N + 1 points)"),
               [](P& p) -> std::size_t& { return p.points; }),
       bind<P>(F("length", "m", 0, kInf, true, false, "Length L_b of the surface, its period"),
               [](P& p) -> double& { return p.length; }),
       bind<P>(F("hurst", "", 0, 1, true, false, "Hurst exponent H"), [](P& p) -> double& { return p.hurst; }),
       bind<P>(F("rolloff_wavelength", "m", 0, kInf, true, false,
                 "Rolloff wavelength 2 pi / q_r: the power spectrum is flat at longer wavelengths"),
               [](P& p) -> double& { return p.rolloff_wavelength; }),
       bind<P>(F("short_cutoff_wavelength", "m", 0, kInf, true, false,
                 "Short cutoff wavelength 2 pi / q_s: no power at shorter wavelengths"),
               [](P& p) -> double& { return p.short_cutoff_wavelength; }),
       bind<P>(F("rms_height", "m", 0, kInf, true, false, "RMS height about the mean (exact)"),
               [](P& p) -> double& { return p.rms_height; }),
       bind_choice<P>(
           F("amplitudes", "", 0, 0, false, false,
             "Fourier amplitudes: gaussian (random process) or fixed (exact spectrum, random phases)"),
           [](P& p) -> FourierAmplitudes& { return p.amplitudes; },
           std::vector<std::pair<std::string, FourierAmplitudes>>{{"gaussian", FourierAmplitudes::Gaussian},
                                                                  {"fixed", FourierAmplitudes::Fixed}}),
       bind<P>(F("seed", "", 0, 9.2e18, false, false, "Seed of the random phases or heights"),
               [](P& p) -> std::uint64_t& { return p.seed; })},
      P{});
  return t;
}

template <class P>
Result<P> typed(const SurfaceSpec& spec, const char* generator, const std::vector<Binding<P>>& table) {
  if (spec.generator != generator)
    return make_error(fmt::format("surface specification: generator is '{}', not '{}'", spec.generator, generator));
  return settings_detail::apply(table, P{}, spec.values, spec.generator);
}

template <class P>
Result<ValueSet> all_values(const SurfaceSpec& spec, const std::vector<Binding<P>>& table) {
  auto p = settings_detail::apply(table, P{}, spec.values, spec.generator);
  if (!p) return p.error();
  return settings_detail::values_of(table, *p);
}

}  // namespace

const std::vector<GeneratorInfo>& surface_generators() {
  static const std::vector<GeneratorInfo> g = {
      {"koch", "Triadic Koch surface K_n (paper Sec. III), bumps outward", settings_detail::fields_of(koch_table())},
      {"wm", "Weierstrass-Mandelbrot profile (Eq. 14-17)", settings_detail::fields_of(wm_table())},
      {"sawtooth", "Asymmetric sawtooth", settings_detail::fields_of(sawtooth_table())},
      {"sine", "Sinusoid z = A sin(2 pi x / lambda)", settings_detail::fields_of(sine_table())},
      {"self-affine", "Random self-affine profile (midpoint displacement)",
       settings_detail::fields_of(self_affine_table())},
      {"fourier",
       "Periodic random self-affine profile by Fourier filtering (flat below the rolloff, q^-(1+2H) to the cutoff)",
       settings_detail::fields_of(fourier_table())},
  };
  return g;
}

const GeneratorInfo* find_generator(std::string_view name) {
  for (const GeneratorInfo& g : surface_generators())
    if (g.name == name) return &g;
  return nullptr;
}

std::vector<std::string> generator_names() {
  std::vector<std::string> n;
  for (const GeneratorInfo& g : surface_generators()) n.push_back(g.name);
  return n;
}

Result<KochParams> koch_params(const SurfaceSpec& s) { return typed(s, "koch", koch_table()); }
Result<WmParams> wm_params(const SurfaceSpec& s) { return typed(s, "wm", wm_table()); }
Result<SawtoothParams> sawtooth_params(const SurfaceSpec& s) { return typed(s, "sawtooth", sawtooth_table()); }
Result<SineParams> sine_params(const SurfaceSpec& s) { return typed(s, "sine", sine_table()); }
Result<SelfAffineParams> self_affine_params(const SurfaceSpec& s) {
  return typed(s, "self-affine", self_affine_table());
}
Result<FourierSelfAffineParams> fourier_params(const SurfaceSpec& s) { return typed(s, "fourier", fourier_table()); }

Status validate(const SurfaceSpec& spec) {
  auto v = surface_values(spec);
  if (!v) return v.error();
  if (spec.generator == "fourier") {  // checks between parameters, before any generation
    auto p = fourier_params(spec);
    if (!p) return p.error();
    return validate(*p);
  }
  return Ok{};
}

Result<SurfaceSpec> make_surface_spec(const std::string& generator, const ValueSet& si_values) {
  SurfaceSpec s{generator, si_values};
  // Normalise the values to the fields' types (e.g. 3.0 -> 3 for an integer).
  if (const GeneratorInfo* g = find_generator(generator)) {
    for (auto& [name, v] : s.values)
      if (const Field* f = find_field(g->fields, name)) {
        auto c = check_si_value(*f, v);
        if (!c) return with_prefix(generator + ": ", c.error());
        v = *c;
      }
  }
  if (Status st = validate(s); !st) return st.error();
  return s;
}

Result<ValueSet> surface_values(const SurfaceSpec& spec) {
  if (spec.generator == "koch") return all_values(spec, koch_table());
  if (spec.generator == "wm") return all_values(spec, wm_table());
  if (spec.generator == "sawtooth") return all_values(spec, sawtooth_table());
  if (spec.generator == "sine") return all_values(spec, sine_table());
  if (spec.generator == "self-affine") return all_values(spec, self_affine_table());
  if (spec.generator == "fourier") return all_values(spec, fourier_table());
  std::string hint;
  if (std::string n = nearest_word(spec.generator, generator_names()); !n.empty())
    hint = fmt::format(" (did you mean '{}'?)", n);
  return make_error(
      fmt::format("unknown surface generator '{}'{}; expected koch, wm, sawtooth, sine, self-affine or fourier",
                  spec.generator, hint));
}

Result<Profile> generate_profile(const SurfaceSpec& spec) {
  if (spec.generator == "koch") {
    auto p = koch_params(spec);
    if (!p) return p.error();
    return koch_profile(*p);
  }
  if (spec.generator == "wm") {
    auto p = wm_params(spec);
    if (!p) return p.error();
    return wm_profile(*p);
  }
  if (spec.generator == "sawtooth") {
    auto p = sawtooth_params(spec);
    if (!p) return p.error();
    return sawtooth_profile(*p);
  }
  if (spec.generator == "sine") {
    auto p = sine_params(spec);
    if (!p) return p.error();
    return sine_profile(*p);
  }
  if (spec.generator == "self-affine") {
    auto p = self_affine_params(spec);
    if (!p) return p.error();
    return self_affine_profile(*p);
  }
  if (spec.generator == "fourier") {
    auto p = fourier_params(spec);
    if (!p) return p.error();
    return fourier_self_affine_profile(*p);
  }
  auto v = surface_values(spec);  // the unknown-generator error
  return v.error();
}

Result<Curve> generate_curve(const SurfaceSpec& spec) {
  if (spec.generator == "koch") {
    auto p = koch_params(spec);
    if (!p) return p.error();
    return koch_curve(*p);
  }
  auto p = generate_profile(spec);
  if (!p) return p.error();
  return as_curve(*p);
}

Result<double> surface_period(const SurfaceSpec& spec) {
  auto v = surface_values(spec);
  if (!v) return v.error();
  // A fourier profile repeats only after its whole length: no repeat within a block.
  if (spec.generator == "wm" || spec.generator == "self-affine" || spec.generator == "fourier") return 0.0;
  return as_real(v->at("wavelength"));
}

Result<double> surface_scale(const SurfaceSpec& spec) {
  auto v = surface_values(spec);
  if (!v) return v.error();
  if (spec.generator == "wm") return as_real(v->at("longest_wavelength"));
  if (spec.generator == "self-affine") return as_real(v->at("length")) / 10;
  if (spec.generator == "fourier") return std::min(as_real(v->at("rolloff_wavelength")), as_real(v->at("length")));
  return as_real(v->at("wavelength"));
}

}  // namespace frictal
