// frictal surface koch|wm|sawtooth|sine|self-affine — generate a profile and write it as CSV.
#include "common.hpp"
#include "frictal/generators.hpp"
#include "frictal/stats.hpp"

namespace frictal::cli {
namespace {

struct SurfaceArgs {
  std::string out;
  bool curve = false;
  // koch
  KochParams koch;
  double koch_alpha_deg = 5;
  // wm
  WmParams wm;
  std::string wm_exponent = "printed";
  bool wm_deterministic = false;
  // sawtooth
  SawtoothParams saw;
  double saw_angle_deg = 20;
  // sine
  SineParams sine;
  // self-affine
  SelfAffineParams sa;
};

void write_and_report(const std::string& out, const Profile& p, const char* what) {
  unwrap(write_profile_csv(out, p));
  const auto s = profile_stats(p);
  fmt::print(stderr, "frictal: wrote {} profile, {} points over {:.6g} m, rms height {:.6g} m, max slope {:.4g} deg -> {}\n",
             what, p.size(), s.length, s.rms_height, to_deg(s.max_slope), out);
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<SurfaceArgs>();
  app.require_subcommand(1);
  auto out_opt = [&](CLI::App* sub) { sub->add_option("-o,--output", a->out, "Output CSV file (x_m,z_m)")->required(); };

  auto* koch = app.add_subcommand("koch", "Triadic Koch surface K_n (paper Sec. III), bumps outward");
  koch->add_option("-n,--iterations", a->koch.iterations, "Number of iterations n (0..10)")->capture_default_str();
  koch->add_option("--alpha", a->koch_alpha_deg, "Base angle of the triangles alpha (degrees, (0, 60])")->capture_default_str();
  koch->add_option("--wavelength", a->koch.wavelength, "Wavelength lambda (m)")->capture_default_str();
  koch->add_option("--length", a->koch.length, "Block length L_b, a whole number of wavelengths (m)")->capture_default_str();
  koch->add_flag("--curve", a->curve, "Write the (possibly folded) curve instead of its upper envelope");
  out_opt(koch);

  auto* wm = app.add_subcommand("wm", "Weierstrass-Mandelbrot profile (Eq. 14-17)");
  wm->add_option("-D,--dimension", a->wm.dimension, "Fractal dimension D in [1, 2]")->capture_default_str();
  wm->add_option("--gamma", a->wm.gamma, "Wavelength density gamma > 1")->capture_default_str();
  wm->add_option("--n-max", a->wm.n_max, "Highest wavelength index n_max (0..60)")->capture_default_str();
  wm->add_option("--longest-wavelength", a->wm.longest_wavelength, "Longest wavelength L (m)")->capture_default_str();
  wm->add_option("--length", a->wm.length, "Profile length L_b (m)")->capture_default_str();
  wm->add_option("--rms", a->wm.rms_height, "RMS height about the mean (m); <= 0 keeps G = 1")->capture_default_str();
  wm->add_option("--seed", a->wm.seed, "Seed of the random phases")->capture_default_str();
  wm->add_flag("--deterministic", a->wm_deterministic, "Zero phases (Eq. 17) instead of random ones (Eq. 14)");
  wm->add_option("--exponent", a->wm_exponent, "printed: gamma^{2(D-2)n} as Eq. 14 prints; common: gamma^{(D-2)n}")
      ->check(CLI::IsMember({"printed", "common"}))->capture_default_str();
  wm->add_option("--spacing", a->wm.spacing, "Point spacing dx (m); default L_s/10 (Eq. 16)");
  out_opt(wm);

  auto* saw = app.add_subcommand("sawtooth", "Asymmetric sawtooth");
  saw->add_option("--rise-angle", a->saw_angle_deg, "Slope of the rising flank (degrees, (0, 90))")->capture_default_str();
  saw->add_option("--rise-fraction", a->saw.rise_fraction, "Fraction of the wavelength that rises (0, 1)")->capture_default_str();
  saw->add_option("--wavelength", a->saw.wavelength, "Wavelength (m)")->capture_default_str();
  saw->add_option("--length", a->saw.length, "Length, whole wavelengths (m)")->capture_default_str();
  out_opt(saw);

  auto* sine = app.add_subcommand("sine", "Sinusoid z = A sin(2 pi x / lambda)");
  sine->add_option("--amplitude", a->sine.amplitude, "Amplitude A (m)")->capture_default_str();
  sine->add_option("--wavelength", a->sine.wavelength, "Wavelength lambda (m)")->capture_default_str();
  sine->add_option("--length", a->sine.length, "Length, whole wavelengths (m)")->capture_default_str();
  sine->add_option("--points-per-wavelength", a->sine.points_per_wavelength, "Samples per wavelength (>= 4)")->capture_default_str();
  out_opt(sine);

  auto* sa = app.add_subcommand("self-affine", "Random self-affine profile (midpoint displacement)");
  sa->add_option("--points", a->sa.points, "Number of points")->capture_default_str();
  sa->add_option("--length", a->sa.length, "Length (m)")->capture_default_str();
  sa->add_option("--hurst", a->sa.hurst, "Hurst exponent H in (0, 1]")->capture_default_str();
  sa->add_option("--rms", a->sa.rms_height, "RMS height (m)")->capture_default_str();
  sa->add_option("--seed", a->sa.seed, "Seed")->capture_default_str();
  out_opt(sa);

  return [a, koch, wm, saw, sine, sa]() {
    if (koch->parsed()) {
      a->koch.alpha = a->koch_alpha_deg * kDeg;
      if (a->curve) {
        Curve c = unwrap(koch_curve(a->koch));
        unwrap(write_profile_csv(a->out, c));
        fmt::print(stderr, "frictal: wrote Koch curve K{}, {} points -> {}\n", a->koch.iterations, c.size(), a->out);
      } else {
        write_and_report(a->out, unwrap(koch_profile(a->koch)), "Koch");
      }
    } else if (wm->parsed()) {
      a->wm.stochastic = !a->wm_deterministic;
      a->wm.exponent = (a->wm_exponent == "common") ? WmExponent::Common : WmExponent::Printed;
      write_and_report(a->out, unwrap(wm_profile(a->wm)), "Weierstrass-Mandelbrot");
    } else if (saw->parsed()) {
      a->saw.rise_angle = a->saw_angle_deg * kDeg;
      write_and_report(a->out, unwrap(sawtooth_profile(a->saw)), "sawtooth");
    } else if (sine->parsed()) {
      write_and_report(a->out, unwrap(sine_profile(a->sine)), "sine");
    } else if (sa->parsed()) {
      write_and_report(a->out, unwrap(self_affine_profile(a->sa)), "self-affine");
    }
    return 0;
  };
}

FRICTAL_COMMAND({"surface", "Generate a surface profile (Koch, Weierstrass-Mandelbrot, sawtooth, sine, self-affine)", setup, 10});

}  // namespace
}  // namespace frictal::cli
