// frictal surface koch|wm|sawtooth|sine|self-affine|fourier — generate a profile and write it as CSV
// (or X3P).
// The generators and their options come from the library's surface specification
// (frictal/surface_spec.hpp), shared with signature, tilt and dimension.
#include "frictal/stats.hpp"
#include "options.hpp"

namespace frictal::cli {
namespace {

struct SurfaceArgs {
  std::string out;
  bool curve = false;
  GeneratorOptions gen;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<SurfaceArgs>();
  app.require_subcommand(1);
  add_generator_subcommands(app, a->gen, true, "");
  app.add_option("-o,--output", a->out,
                 "Output file: CSV (x_m,z_m), or X3P for a name ending in .x3p (binary, keeps the spacing); - "
                 "writes CSV to standard output")
      ->required();
  app.add_flag("--curve", a->curve, "koch: write the (possibly folded) curve instead of its upper envelope");
  return [a]() {
    // Formats frictal reads but does not write: a CSV under such a name would mislead other tools.
    for (const char* ext : {".npy", ".gwy", ".gsf", ".sdf", ".sur", ".ibw", ".nrrd", ".spm", ".nid", ".mat"})
      if (has_extension(a->out, ext))
        throw UsageError(
            fmt::format("-o {}: frictal surface writes CSV (x_m,z_m; any other name) or X3P (.x3p, "
                        "binary with its spacing), not {}",
                        a->out, ext));
    const bool x3p = has_extension(a->out, ".x3p");
    const SurfaceSpec spec = *a->gen.spec();
    if (a->curve && spec.generator != "koch")
      throw UsageError(fmt::format("--curve: only the koch generator makes a folded curve, not {}", spec.generator));
    if (a->curve) {
      if (x3p) throw UsageError("--curve: a folded curve is not a profile on a uniform grid; write it as CSV");
      const Curve c = unwrap(generate_curve(spec));
      write_output(a->out, [&](const std::string& p) { return write_profile_csv(p, c); });
      fmt::print(stderr, "frictal: wrote koch curve, {} points -> {}\n", c.size(), a->out);
      return 0;
    }
    const Profile p = unwrap(generate_profile(spec));
    write_output(a->out,
                 [&](const std::string& path) { return x3p ? write_x3p(path, p) : write_profile_csv(path, p); });
    const auto s = profile_stats(p);
    fmt::print(stderr,
               "frictal: wrote {} profile, {} points over {:.6g} m, rms height {:.6g} m, max slope {:.4g} deg -> {}\n",
               spec.generator, p.size(), s.length, s.rms_height, to_deg(s.max_slope), a->out);
    return 0;
  };
}

FRICTAL_COMMAND({"surface",
                 "Generate a surface profile (Koch, Weierstrass-Mandelbrot, sawtooth, sine, self-affine, Fourier)",
                 setup, 10});

}  // namespace
}  // namespace frictal::cli
