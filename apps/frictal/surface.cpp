// frictal surface koch|wm|sawtooth|sine|self-affine|fourier — generate a profile and write it as CSV.
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
  app.add_option("-o,--output", a->out, "Output CSV file (x_m,z_m); - writes to standard output")->required();
  app.add_flag("--curve", a->curve, "koch: write the (possibly folded) curve instead of its upper envelope");
  return [a]() {
    const SurfaceSpec spec = *a->gen.spec();
    if (a->curve && spec.generator != "koch")
      throw UsageError(fmt::format("--curve: only the koch generator makes a folded curve, not {}", spec.generator));
    if (a->curve) {
      const Curve c = unwrap(generate_curve(spec));
      write_output(a->out, [&](const std::string& p) { return write_profile_csv(p, c); });
      fmt::print(stderr, "frictal: wrote koch curve, {} points -> {}\n", c.size(), a->out);
      return 0;
    }
    const Profile p = unwrap(generate_profile(spec));
    write_output(a->out, [&](const std::string& path) { return write_profile_csv(path, p); });
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
