// Task kind 'areal-tilt': the 3D tilt test on MuJoCo (frictal/areal_tilt.hpp, docs/mujoco.md)
// against its matched prediction, on one generated pair of maps. Parameters: `pair` = "fourier"
// (a Fourier-filtered random lower map and an upper map from the next seed, turned over, plane
// removed: nodes, upper_nodes, hurst, anisotropy = how many times longer the correlation is
// along y, rms_slope; rolloff at 8 and cut-off at 2.5 node spacings) or "grooves" (A sin(2 pi
// (i -+ j) / m) on dx = a, dy = a tan(groove_angle), m = groove_period, 90 deg: across d;
// mirror = 1 takes i + j; A = rms_slope a m / (2 pi), i.e. rms_slope is then the grooves'
// largest slope across them; the upper face an upper_nodes window in place); the lower map 1 mm
// wide, sliding along x. `sample` only numbers repetitions (seed_from).
// Each task runs the block free to move sideways and locked, and the matched prediction
// (areal_tilt_hold) from each simulated rest. Not available in a build without MuJoCo.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/core.h>

#include "frictal/analysis.hpp"
#include "frictal/areal_tilt.hpp"
#include "frictal/study.hpp"
#include "study/kind_common.hpp"
#include "study/table_params.hpp"
#include "util/random.hpp"

namespace frictal::study {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kWidth = 1e-3;  // the lower map's width (m)

// The run's outputs, from the areal tilt test's table (areal_tilt_run_columns(): the numbers of
// frictal areal-tilt --json, declared once there), for the block free and locked.
constexpr std::initializer_list<ColumnOutput> kFreeRun = {
    {"friction_angle_deg", "simulated_free_deg", "MuJoCo's run-away increment, block free to move sideways"},
    {"ran_away", "ran_away_free", "block free"},
    {"unsettled_increments", "unsettled_free", "block free"},
    {"steps", "steps_free", "block free"},
    {"steering_deg", nullptr, "block free: the angle from d to its run-away"},
    "spheres"};
constexpr std::initializer_list<ColumnOutput> kLockedRun = {
    {"friction_angle_deg", "simulated_locked_deg", "MuJoCo's run-away increment, block locked to d"},
    {"ran_away", "ran_away_locked", "block locked"},
    {"unsettled_increments", "unsettled_locked", "block locked"},
    {"steps", "steps_locked", "block locked"}};

/// A Fourier-filtered random map of n x n nodes on spacing a: a sum of cosines over the
/// wavevectors 2 pi (kx, ky) / (2 (n - 1) a) with Gaussian coefficients, filtered flat below the
/// rolloff (8 spacings) and as q^-(1 + H) up to the cut-off (2.5 spacings), q measured with the
/// y component multiplied by `anisotropy`; zero mean, scaled to the rms slope (central
/// differences, one-sided at the edges).
Map fourier_map(std::size_t n, double a, double hurst, double anisotropy, double rms_slope, std::uint64_t seed) {
  util::Rng rng(seed);
  const double P = 2 * double(n - 1) * a;
  const double qr = 2 * kPi / (8 * a), qs = 2 * kPi / (2.5 * a);
  const int kmax = int(std::ceil(qs * P / (2 * kPi)));
  Map m;
  m.nx = m.ny = n;
  m.dx = m.dy = a;
  m.heights.assign(n * n, 0.0);
  for (int ky = 0; ky <= kmax; ++ky)
    for (int kx = -kmax; kx <= kmax; ++kx) {
      if (ky == 0 && kx <= 0) continue;  // one of each pair +-q
      const double qx = 2 * kPi * kx / P, qy = 2 * kPi * ky / P;
      const double q = std::hypot(qx, anisotropy * qy);
      const double c = rng.normal(), s = rng.normal();
      if (q > qs) continue;
      const double amp = std::pow(std::max(q, qr), -(1 + hurst));
      for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i) {
          const double ph = qx * double(i) * a + qy * double(j) * a;
          m.heights[j * n + i] += amp * (c * std::cos(ph) + s * std::sin(ph));
        }
    }
  double mean = 0;
  for (double z : m.heights) mean += z;
  mean /= double(n * n);
  double g2 = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      auto d = [&](std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1) {
        return (m.at(i1, j1) - m.at(i0, j0)) / (double(i1 - i0 + j1 - j0) * a);
      };
      const double gx = d(i > 0 ? i - 1 : i, i + 1 < n ? i + 1 : i, j, j);
      const double gy = d(i, i, j > 0 ? j - 1 : j, j + 1 < n ? j + 1 : j);
      g2 += gx * gx + gy * gy;
    }
  const double scale = rms_slope / std::sqrt(g2 / double(n * n));
  for (double& z : m.heights) z = (z - mean) * scale;
  return m;
}

Result<TaskOutput> run_areal_tilt_task(const Params& p, std::uint64_t seed) {
  if (!mujoco_available()) return areal_tilt(Map{}, Map{}, {}).error();
  if (Status st = only_known_parameters(p, {&areal_tilt_settings()},
                                        {"pair", "nodes", "upper_nodes", "hurst", "anisotropy", "rms_slope",
                                         "groove_angle", "groove_period", "mirror", "sample"},
                                        "areal-tilt");
      !st)
    return st.error();
  for (const char* fixed : {"lateral", "angle"})
    if (p.count(fixed))
      return make_error(fmt::format(
          "parameter '{}': set by the areal-tilt kind (every pair runs free and locked, sliding along +x)", fixed));
  auto model_values = table_values(areal_tilt_settings(), p);
  if (!model_values) return model_values.error();
  auto model = make_areal_tilt_options(*model_values);
  if (!model) return model.error();
  using kind_detail::take;
  Error err;
  std::string pair;
  double hurst = 0, anis = 0, slope = 0, angle = 0;
  std::int64_t n = 0, w = 0, period = 0, mirror = 0;
  if (!take(get_string(p, "pair", "fourier"), pair, err) || !take(get_int(p, "nodes", 48), n, err) ||
      !take(get_int(p, "upper_nodes", 12), w, err) || !take(get_real(p, "hurst", 0.8), hurst, err) ||
      !take(get_real(p, "anisotropy", 1.0), anis, err) || !take(get_real(p, "rms_slope", 0.2), slope, err) ||
      !take(get_real(p, "groove_angle", 90.0), angle, err) || !take(get_int(p, "groove_period", 10), period, err) ||
      !take(get_int(p, "mirror", 0), mirror, err))
    return err;
  if (pair != "fourier" && pair != "grooves")
    return make_error(fmt::format("parameter 'pair': expected fourier or grooves, got '{}'", pair));
  if (n < 8 || n > 256) return make_error(fmt::format("parameter 'nodes': expected 8..256, got {}", n));
  if (w < 1 || w > n) return make_error(fmt::format("parameter 'upper_nodes': expected 1..nodes, got {}", w));
  if (!(hurst > 0 && hurst <= 1)) return make_error(fmt::format("parameter 'hurst': expected (0, 1], got {}", hurst));
  if (!(anis >= 1 && anis <= 100))
    return make_error(fmt::format("parameter 'anisotropy': expected 1..100, got {}", anis));
  if (!(slope > 0 && slope < 2))
    return make_error(fmt::format("parameter 'rms_slope': expected (0, 2), got {}", slope));
  if (!(angle >= 10 && angle <= 90))
    return make_error(fmt::format("parameter 'groove_angle': expected 10..90 deg, got {}", angle));
  if (mirror != 0 && mirror != 1) return make_error(fmt::format("parameter 'mirror': expected 0 or 1, got {}", mirror));
  if (period < 4) return make_error(fmt::format("parameter 'groove_period': expected >= 4 nodes, got {}", period));

  const std::size_t N = std::size_t(n), W = std::size_t(w);
  const double a = kWidth / double(N - 1);
  Map f, g;
  ArealTiltOptions o = *model;  // the model's and protocol's settings (areal_tilt_settings())
  if (pair == "fourier") {
    auto plane = parse_detrend("plane");
    if (!plane) return plane.error();
    auto lf = detrend(fourier_map(N, a, hurst, anis, slope, seed), *plane);
    auto ug = detrend(fourier_map(W, a, hurst, anis, slope, seed + 0x9e3779b97f4a7c15ULL), *plane);
    if (!lf) return lf.error();
    if (!ug) return ug.error();
    f = *lf;
    g = *ug;
  } else {
    const bool across = angle >= 90 - 1e-9;
    f.nx = f.ny = N;
    f.dx = a;
    f.dy = across ? a : a * std::tan(angle * kPi / 180);
    const double A = slope * a * double(period) / (2 * kPi);
    for (std::size_t j = 0; j < N; ++j)
      for (std::size_t i = 0; i < N; ++i) {
        const double ph = across ? double(i) : (mirror != 0 ? double(i + j) : double(i) - double(j));
        f.heights.push_back(A * std::sin(2 * kPi * ph / double(period)));
      }
    const std::size_t i0 = (N - W) / 2;
    g.nx = g.ny = W;
    g.dx = f.dx;
    g.dy = f.dy;
    g.x0 = double(i0) * f.dx;
    g.y0 = double(i0) * f.dy;
    for (std::size_t j = 0; j < W; ++j)
      for (std::size_t i = 0; i < W; ++i) g.heights.push_back(f.at(i + i0, j + i0));
    o.turn_over_upper = false;
  }
  TaskOutput out;
  auto& s = out.scalars;
  for (const bool lock : {false, true}) {
    const std::string tag = lock ? "locked" : "free";
    o.lock_lateral = lock;
    o.start_offset = {0, 0};
    auto sim = areal_tilt(f, g, o);
    if (!sim) return sim.error();
    ArealTiltOptions c = o;
    c.start_offset = sim->rest_offset;
    auto hold = areal_tilt_hold(f, g, c);
    if (!hold) return hold.error();
    put_outputs(out, areal_tilt_run_columns(), *sim, lock ? kLockedRun : kFreeRun);
    const double fa = s["simulated_" + tag + "_deg"], pr = hold->hold_angle * 180 / kPi;
    const double step = o.tilt_step * 180 / kPi;
    // Within 0.2 deg of the simulated bracket (reading - one increment, reading].
    const double miss = pr > fa ? pr - fa : std::max(0.0, fa - step - pr);
    s["matched_" + tag + "_deg"] = pr;
    s["miss_" + tag + "_deg"] = miss;
    s["within_" + tag] = miss <= 0.2 ? 1.0 : 0.0;
    // The prediction's conditioning: each slip's end moved by one sphere radius.
    auto spread = areal_tilt_hold_spread(f, g, c, *hold);
    if (!spread) return spread.error();
    const double lo = spread->low * 180 / kPi, hi = spread->high * 180 / kPi;
    const double miss_range = lo > fa ? lo - fa : std::max(0.0, fa - step - hi);
    s["spread_low_" + tag + "_deg"] = lo;
    s["spread_high_" + tag + "_deg"] = hi;
    s["ambiguous_slips_" + tag] = double(spread->ambiguous);
    s["within_spread_" + tag] = miss_range <= 0.2 ? 1.0 : 0.0;
    // The rigid block put down in the seat where the simulated one stood before its run-away, at
    // that tilt: do the two hold equally long from the same seat? (NaN: no seat.)
    s["seated_" + tag + "_deg"] = std::numeric_limits<double>::quiet_NaN();
    s["seat_tilt_" + tag + "_deg"] = std::numeric_limits<double>::quiet_NaN();
    if (auto seat = areal_tilt_last_seat(*sim)) {
      ArealTiltOptions c2 = o;
      c2.start_offset = {(*seat)[1], (*seat)[2]};
      c2.coarse_tilt_step = o.tilt_step;
      auto seated = areal_tilt_hold(f, g, c2, kArealHoldResolution, 1e-7, (*seat)[0]);
      if (!seated) return seated.error();
      s["seated_" + tag + "_deg"] = seated->hold_angle * 180 / kPi;
      s["seat_tilt_" + tag + "_deg"] = (*seat)[0] * 180 / kPi;
    }
    if (!lock) {
      s["matched_steering_deg"] = hold->steering * 180 / kPi;
    }
  }
  s["free_minus_locked_deg"] = s["simulated_free_deg"] - s["simulated_locked_deg"];
  return out;
}

void areal_tilt_part(const std::string& part, const std::vector<TaskRow>& rows, Report& rep) {
  std::string t =
      "\n| task | simulated free | matched free | its spread | simulated locked | matched locked | its spread | "
      "steering (sim / matched) |\n"
      "|---|---|---|---|---|---|---|---|\n";
  int n = 0, in_free = 0, in_locked = 0, spread_in = 0, ill = 0;
  double steer = 0, fml = 0;
  auto get = [](const std::map<std::string, double>& sc, const std::string& k) {
    const auto it = sc.find(k);
    return it == sc.end() ? std::nan("") : it->second;
  };
  auto range = [&](const std::map<std::string, double>& sc, const std::string& tag) {
    const double lo = get(sc, "spread_low_" + tag + "_deg"), hi = get(sc, "spread_high_" + tag + "_deg");
    return std::isfinite(lo) ? fmt::format("{:.2f}–{:.2f}", lo, hi) : std::string("–");
  };
  for (const auto& r : rows) {
    const auto& s = r.output.scalars;
    if (!s.count("simulated_free_deg")) continue;
    ++n;
    in_free += s.at("within_free") > 0.5;
    in_locked += s.at("within_locked") > 0.5;
    steer += std::abs(s.at("steering_deg"));
    fml += s.at("free_minus_locked_deg");
    for (const char* tag : {"free", "locked"}) {
      spread_in += get(s, std::string("within_spread_") + tag) > 0.5;
      ill +=
          get(s, std::string("spread_high_") + tag + "_deg") - get(s, std::string("spread_low_") + tag + "_deg") > 0.2;
    }
    t += fmt::format("| {} | {:.1f} | {:.3f}{} | {} | {:.1f} | {:.3f}{} | {} | {:.1f} / {:.1f} |\n", r.id,
                     s.at("simulated_free_deg"), s.at("matched_free_deg"), s.at("within_free") > 0.5 ? "" : " ✗",
                     range(s, "free"), s.at("simulated_locked_deg"), s.at("matched_locked_deg"),
                     s.at("within_locked") > 0.5 ? "" : " ✗", range(s, "locked"), s.at("steering_deg"),
                     s.at("matched_steering_deg"));
  }
  if (n == 0) return;
  rep.lines.push_back(fmt::format("\n## Part '{}' (areal-tilt): {} pairs", part, n));
  rep.lines.push_back(t);
  rep.lines.push_back(fmt::format(
      "\nWithin 0.2° of the matched prediction: {} of {} free, {} of {} locked; mean free − locked {:+.2f}°, "
      "mean |steering| {:.1f}°. The spread is the least and largest hold angle of the rigid block when one slip's "
      "end is moved by a sphere radius (areal_tilt_hold_spread): wider than 0.2° in {} of {} runs (an "
      "ill-conditioned drop), and MuJoCo's reading lies within 0.2° of it in {} of {}.",
      in_free, n, in_locked, n, fml / n, steer / n, ill, 2 * n, spread_in, 2 * n));
  Finding f;
  f.claim_id = "areal-matched-prediction";
  f.part = part;
  f.claim = fmt::format(
      "Part '{}': MuJoCo's tilt test agrees within 0.2° with the matched quasi-static prediction "
      "on every pair, free and locked (docs/mujoco.md, \"The 0.2° target\").",
      part);
  f.supported = in_free == n && in_locked == n;
  f.evidence.push_back(fmt::format("free {}/{}, locked {}/{} within 0.2° (docs/mujoco.md)", in_free, n, in_locked, n));
  // A free miss that the rigid block matches from the simulated block's last seat (the blocks agree
  // seat by seat and part where a slip ends), or whose simulated path leaves the predicted one
  // (steering apart by more than 5 deg): that names it. Other misses are unexplained.
  if (!f.supported && in_locked == n) {
    std::string list;
    int apart = 0, seated_agree = 0, in_spread = 0;
    for (const auto& r : rows) {
      const auto& sc = r.output.scalars;
      if (!sc.count("within_free") || sc.at("within_free") > 0.5) continue;
      const double ds = std::abs(sc.at("steering_deg") - sc.at("matched_steering_deg"));
      if (ds > 5) ++apart;
      const double fa = sc.at("simulated_free_deg");
      const double seated = sc.count("seated_free_deg") ? sc.at("seated_free_deg") : std::nan("");
      // Within 0.2 deg of the simulated bracket (reading - one increment, reading], as `within`.
      const bool agree = std::isfinite(seated) && seated <= fa + 0.2 && seated >= fa - 0.1 - 0.2;
      seated_agree += agree;
      in_spread += get(sc, "within_spread_free") > 0.5;
      list +=
          fmt::format("{}task {}: {:.2f}° against {:.2f}° (spread {}), steering {:.1f}° against {:.1f}°{}",
                      list.empty() ? "" : "; ", r.id, fa, sc.at("matched_free_deg"), range(sc, "free"),
                      sc.at("steering_deg"), sc.at("matched_steering_deg"),
                      std::isfinite(seated) ? fmt::format(", from the seat at {:.1f}° the rigid block holds to {:.2f}°",
                                                          sc.at("seat_tilt_free_deg"), seated)
                                            : std::string());
    }
    if (seated_agree == n - in_free)
      f.cause = fmt::format(
          "each free miss holds as long as the rigid block put down in its last seat (the simulated block's stop "
          "before its run-away): the two agree seat by seat and part where a slip ends, the simulated block "
          "caught at another stop than the rigid block's gradient-flow slip ({}); locked, the same pairs agree{}",
          list,
          in_spread == n - in_free
              ? "; each lies within 0.2° of the spread that the rigid block reaches when one slip's end moves by a "
                "sphere radius"
              : "");
    else if (apart == n - in_free)
      f.cause = fmt::format(
          "each free miss is a block whose simulated path leaves the predicted one, so it is caught at another stop "
          "than the rigid quasi-static block ({}); locked, the same pairs agree",
          list);
  }
  rep.findings.push_back(f);
  // Within the prediction's conditioning: the reading against the spread of hold angles that the rigid
  // block reaches when one slip's end is moved by a sphere radius.
  {
    Finding h;
    h.claim_id = "areal-prediction-spread";
    h.part = part;
    h.claim = fmt::format(
        "Part '{}': MuJoCo's reading lies within 0.2° of the range of hold angles that the rigid quasi-static "
        "block reaches when one slip's end is moved by a sphere radius (areal_tilt_hold_spread), free and locked.",
        part);
    h.supported = spread_in == 2 * n;
    h.evidence.push_back(
        fmt::format("{} of {} runs within 0.2° of that range; the range is wider than 0.2° in {} of "
                    "{} (drops whose hold angle hinges on where a slip ends)",
                    spread_in, 2 * n, ill, 2 * n));
    rep.findings.push_back(h);
  }
  // Seat by seat: the rigid block put down where the simulated one sat before its run-away.
  int seated_n = 0, seated_in = 0;
  double seated_worst = 0;
  for (const auto& r : rows) {
    const auto& sc = r.output.scalars;
    for (const char* tag : {"free", "locked"}) {
      const auto it = sc.find(std::string("seated_") + tag + "_deg");
      if (it == sc.end() || !std::isfinite(it->second)) continue;
      const double fa = sc.at(std::string("simulated_") + tag + "_deg"), se = it->second;
      const double miss = se > fa ? se - fa : std::max(0.0, fa - 0.1 - se);  // from the bracket, as `miss`
      ++seated_n;
      seated_in += miss <= 0.2;
      seated_worst = std::max(seated_worst, miss);
    }
  }
  if (seated_n > 0) {
    Finding g;
    g.claim_id = "areal-seat-by-seat";
    g.part = part;
    g.claim = fmt::format(
        "Part '{}': from the seat where the simulated block sat before its run-away, the rigid quasi-static block "
        "(areal_tilt_hold put down there at that tilt) runs away within 0.2° of MuJoCo, free and locked: the two "
        "agree seat by seat.",
        part);
    g.supported = seated_in == seated_n;
    g.evidence.push_back(
        fmt::format("criterion: within 0.2° of the simulated bracket; {} of {} runs, largest miss {:.3f}°", seated_in,
                    seated_n, seated_worst));
    rep.findings.push_back(g);
  }
}

}  // namespace

TaskKind areal_tilt_kind() {
  TaskKind k;
  k.name = "areal-tilt";
  k.description =
      "3D tilt test of two maps on MuJoCo (free and locked) against the matched quasi-static prediction "
      "(docs/mujoco.md)";
  k.version = 3;  // 2: the seated predictions; 3: the spread
  k.run = run_areal_tilt_task;
  k.cost = [](const Params& p) {
    const double w = kind_detail::number(p, "upper_nodes", 12);
    return 1.0 + 0.02 * w * w;  // ~10 s for 144 spheres, ~20 s for 1,024 (docs/mujoco.md, "Speed")
  };
  k.uses_seed = true;
  k.outputs = {
      {"matched_free_deg", "deg", "matched prediction (areal_tilt_hold) from the simulated rest, free"},
      {"miss_free_deg", "deg", "distance of the prediction from the simulated bracket, free"},
      {"within_free", "1", "1 when within 0.2 deg, free"},
      {"seated_free_deg", "deg",
       "the rigid block's hold angle from the simulated block's last seat before its run-away (areal_tilt_hold "
       "with start_tilt), free; NaN without one"},
      {"seat_tilt_free_deg", "deg", "the tilt of that seat, free"},
      {"spread_low_free_deg", "deg",
       "least hold angle of the rigid block when one slip's end is moved by a sphere radius (areal_tilt_hold_spread), "
       "free"},
      {"spread_high_free_deg", "deg", "largest such hold angle, free"},
      {"ambiguous_slips_free", "1", "slips from whose moved ends the rigid block settles in another seat, free"},
      {"within_spread_free", "1", "1 when the simulated bracket lies within 0.2 deg of that range, free"},
      {"matched_locked_deg", "deg", "matched prediction from the simulated rest, locked"},
      {"miss_locked_deg", "deg", "distance of the prediction from the simulated bracket, locked"},
      {"within_locked", "1", "1 when within 0.2 deg, locked"},
      {"seated_locked_deg", "deg", "the same from the locked block's last seat"},
      {"seat_tilt_locked_deg", "deg", "the tilt of that seat, locked"},
      {"spread_low_locked_deg", "deg", "the same least hold angle, locked"},
      {"spread_high_locked_deg", "deg", "largest such hold angle, locked"},
      {"ambiguous_slips_locked", "1", "slips from whose moved ends the rigid block settles in another seat, locked"},
      {"within_spread_locked", "1", "1 when the simulated bracket lies within 0.2 deg of that range, locked"},
      {"matched_steering_deg", "deg", "the same in the matched prediction"},
      {"free_minus_locked_deg", "deg", "simulated free minus locked"},
  };
  for (const auto& run : {outputs_of("areal_tilt", areal_tilt_run_columns(), kFreeRun),
                          outputs_of("areal_tilt", areal_tilt_run_columns(), kLockedRun)})
    k.outputs.insert(k.outputs.end(), run.begin(), run.end());
  k.report = areal_tilt_part;
  return k;
}

}  // namespace frictal::study
