// frictal areal LOWER [UPPER] — the areal signature of two rigid blocks sliding along one
// direction (the upper block turned over onto the lower one; default: LOWER against itself).
#include "frictal/areal.hpp"
#include "common.hpp"
#include "frictal/analysis.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string lower, upper, output;
  double angle = 0;
  double step = 0, offset_max = 0;
  double atomic_friction = 0;
  std::string detrend = "plane";
  std::string contact_slope = "lower";
  bool in_place = false;
  bool json = false;
  unsigned threads = 0;
  InputOptions input;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("lower", a->lower, "Lower block's map (X3P, Gwyddion text)")->required();
  app.add_option("upper", a->upper, "Upper block's map as measured (default: the lower map)");
  app.add_option("--angle", a->angle, "Sliding direction (deg from +x towards +y)");
  app.add_option("--step", a->step, "Offset step (m; default min(dx, dy))");
  app.add_option("--max-offset", a->offset_max, "Largest offset (m; default half the lower map along the direction)");
  add_atomic_friction_option(app, a->atomic_friction);
  app.add_option("--detrend", a->detrend, "Remove none, mean, plane or poly:N from both maps first (default plane)");
  app.add_option("--contact-slope", a->contact_slope, "lower (Eq. 3, default) or mean (of both faces)");
  app.add_flag("--in-place", a->in_place, "UPPER is the upper face already in place (not turned over)");
  app.add_option("-o,--output", a->output,
                 "Write offset_m,lift_m,theta_rad,contact_x_m,contact_y_m to this CSV (- for standard output)");
  app.add_option("--threads", a->threads, "Worker threads (0 = all cores)");
  app.add_flag("--json", a->json, "Print one JSON object");
  add_input_options(app, a->input);
  return [a]() {
    require(std::isfinite(a->angle), "--angle must be a finite number of degrees");
    require(a->step >= 0 && a->offset_max >= 0, "--step and --max-offset must be >= 0 (metres)");
    require(std::isfinite(a->atomic_friction) && a->atomic_friction >= 0,
            "--atomic-friction must be a finite number >= 0");
    const Detrend dt = unwrap(parse_detrend(a->detrend));
    auto load = [&](const std::string& path) {
      const SurfaceData s = load_surface(path, a->input);
      if (!s.is_map) throw UsageError(fmt::format("{}: a line profile; the areal signature needs maps", path));
      return unwrap(detrend(s.map, dt));
    };
    const Map f = load(a->lower);
    const Map g = a->upper.empty() ? f : load(a->upper);
    ArealSignatureOptions o;
    o.step = a->step;
    o.offset_max = a->offset_max;
    o.threads = a->threads;
    o.turn_over_upper = !a->in_place;
    if (a->contact_slope == "mean")
      o.contact_slope = ArealContactSlope::Mean;
    else if (a->contact_slope != "lower")
      throw UsageError(fmt::format("--contact-slope '{}' not understood (expected lower or mean)", a->contact_slope));
    const ArealSignature r = unwrap(areal_signature(f, g, a->angle * kDeg, o));
    const FrictionPrediction p = unwrap(predict_friction(a->atomic_friction, r.theta_max_forward, r.contact_slope_std));
    if (!a->output.empty()) {
      std::string buf = "offset_m,lift_m,theta_rad,contact_x_m,contact_y_m\n";
      for (std::size_t k = 0; k < r.offset.size(); ++k)
        buf += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", r.offset[k], r.lift[k], r.theta[k],
                           r.contact_x[k], r.contact_y[k]);
      write_text_output(a->output, buf);
    }
    require(!(a->json && a->output == "-"), "--json and -o - would both write to standard output; choose one");
    if (a->json) {
      nlohmann::json j;
      j["lower"] = a->lower;
      j["upper"] = a->upper.empty() ? a->lower : a->upper;
      j["direction_deg"] = a->angle;
      j["offsets"] = r.offset.size();
      j["theta_max_forward_deg"] = to_deg(r.theta_max_forward);
      j["theta_max_backward_deg"] = to_deg(r.theta_max_backward);
      j["theta_max_lift_deg"] = to_deg(r.theta_max_lift);
      j["contact_slope_mean_deg"] = to_deg(r.contact_slope_mean);
      j["contact_slope_std_deg"] = to_deg(r.contact_slope_std);
      j["friction_angle_deg"] = to_deg(p.friction_angle);
      j["friction_coefficient"] = p.friction_coefficient;
      j["friction_coefficient_low"] = p.friction_coefficient_low;
      j["evaluated_nodes"] = r.evaluated_nodes;
      print_json(j);
    } else {
      fmt::print(
          a->output == "-" ? stderr : stdout,
          "{} on {} along {} deg: {} offsets\n  theta_max forward {:.4f} deg, backward {:.4f} deg, sigma {:.4f} deg\n"
          "  friction angle {:.4f} deg, mu = {:.5f} (low {:.5f})\n",
          a->upper.empty() ? a->lower : a->upper, a->lower, a->angle, r.offset.size(), to_deg(r.theta_max_forward),
          to_deg(r.theta_max_backward), to_deg(r.contact_slope_std), to_deg(p.friction_angle), p.friction_coefficient,
          p.friction_coefficient_low);
    }
    return 0;
  };
}

FRICTAL_COMMAND({"areal", "Areal signature of two rigid blocks (maps) sliding along a direction", setup, 75});

}  // namespace
}  // namespace frictal::cli
