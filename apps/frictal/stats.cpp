// frictal stats FILE — statistics of a profile.
#include "common.hpp"
#include "frictal/stats.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string file;
  bool json = false;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("file", a->file, "Profile file")->required();
  app.add_flag("--json", a->json, "Print one JSON object");
  return [a]() {
    const Profile p = load_profile(a->file);
    const ProfileStats s = profile_stats(p);
    if (a->json) {
      nlohmann::json j;
      j["file"] = a->file;
      j["points"] = s.points;
      j["length_m"] = s.length;
      j["mean_height_m"] = s.mean_height;
      j["rms_height_m"] = s.rms_height;
      j["rms_slope"] = s.rms_slope;
      j["max_slope_deg"] = to_deg(s.max_slope);
      j["mean_slope_deg"] = to_deg(s.mean_slope);
      print_json(j);
    } else {
      fmt::print("{}: {} points over {:.6g} m\n  rms height {:.6g} m (about the mean {:.6g} m)\n  rms slope {:.6g}\n"
                 "  max slope {:.4f} deg\n",
                 a->file, s.points, s.length, s.rms_height, s.mean_height, s.rms_slope, to_deg(s.max_slope));
    }
    return 0;
  };
}

FRICTAL_COMMAND({"stats", "Statistics of a profile: rms height, rms slope, max slope", setup, 30});

}  // namespace
}  // namespace frictal::cli
