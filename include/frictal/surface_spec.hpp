// frictal — surface specification: a generator (koch, wm, sawtooth, sine, self-affine, fourier) and its
// parameters as one value, validated against one table of fields per generator (settings.hpp).
// Every front end builds surfaces through it: `frictal surface|signature|tilt|dimension <gen>`
// options, study TOML keys, Python keywords and JSON keys are the table's names, so a generator
// or a parameter is added here and nowhere else. SI units (m, rad) inside.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "frictal/generators.hpp"
#include "frictal/geometry.hpp"
#include "frictal/result.hpp"
#include "frictal/settings.hpp"

namespace frictal {

/// One generator: its name, a one-line description and its parameter table.
struct GeneratorInfo {
  std::string name;         ///< "koch", "wm", "sawtooth", "sine", "self-affine", "fourier"
  std::string description;  ///< one line (paper section or equation)
  std::vector<Field> fields;
};

/// Every generator, in a fixed order (koch, wm, sawtooth, sine, self-affine, fourier).
const std::vector<GeneratorInfo>& surface_generators();
/// The generator of that name, or nullptr.
const GeneratorInfo* find_generator(std::string_view name);
/// The generators' names, in order.
std::vector<std::string> generator_names();

/// A generated surface: generator name and parameter values in SI (absent: the default).
struct SurfaceSpec {
  std::string generator = "koch";
  ValueSet values;
};

/// A checked specification: the generator exists, every name is one of its fields (else an
/// error naming the nearest), every value has the field's type and range.
Result<SurfaceSpec> make_surface_spec(const std::string& generator, const ValueSet& si_values);
/// The same check of an existing specification.
Status validate(const SurfaceSpec& spec);

/// Every parameter of the specification with defaults filled in (SI).
Result<ValueSet> surface_values(const SurfaceSpec& spec);

/// The surface as a curve: Koch's full (possibly folded) curve; the profile of the others.
Result<Curve> generate_curve(const SurfaceSpec& spec);
/// The surface as a single-valued profile (Koch: the upper envelope of the curve).
Result<Profile> generate_profile(const SurfaceSpec& spec);

/// Period of the generated surface within a block, for the tilt test's offset range (unit: m):
/// the wavelength of koch, sawtooth and sine; 0 for wm and self-affine (not periodic) and for
/// fourier (its profile is periodic, but with the whole length as period, so it does not repeat
/// within the block).
Result<double> surface_period(const SurfaceSpec& spec);
/// A horizontal length characteristic of the surface (unit: m): the period when periodic, the
/// longest wavelength L of a WM profile, a tenth of a self-affine profile's length, the rolloff
/// wavelength of a fourier profile (at most its length). The tilt
/// test's run-away distance defaults to it.
Result<double> surface_scale(const SurfaceSpec& spec);

/// Typed parameters of a specification (errors if the generator differs or a value is invalid).
Result<KochParams> koch_params(const SurfaceSpec& spec);
Result<WmParams> wm_params(const SurfaceSpec& spec);
Result<SawtoothParams> sawtooth_params(const SurfaceSpec& spec);
Result<SineParams> sine_params(const SurfaceSpec& spec);
Result<SelfAffineParams> self_affine_params(const SurfaceSpec& spec);
Result<FourierSelfAffineParams> fourier_params(const SurfaceSpec& spec);

}  // namespace frictal
