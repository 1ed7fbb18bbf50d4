// The claims that the studies check (the paper's, then frictal's own findings), and one verdict
// per claim over every part that checks it (docs/studies.md "Findings as data"). The kinds' report
// sections check them; the Markdown and JSON reports and the reproduction page are written from
// the findings and conclusions.
#include <fmt/core.h>

#include "frictal/study.hpp"

namespace frictal::study {

const std::vector<Claim>& claims() {
  static const std::vector<Claim> list = {
      // ------------------------------------------------------------- the paper's claims
      {"koch-theta-max",
       true,
       "The signature maximum theta_max of the Koch surfaces K0, K1, K2, K3 is 1, 1, 2, 3 times alpha.",
       "Sec. III, Fig. 4, 6",
       {4, 6},
       "koch-signature parts (the signature of K0-K3)",
       {}},
      {"koch-steepest-edge",
       true,
       "The steepest edge of the Koch curve K_n is (n + 1) alpha.",
       "Sec. III, Fig. 3",
       {3},
       "koch-signature parts (the folded curve of K_n)",
       {}},
      {"koch-length-ratio",
       true,
       "Each iteration of the Koch construction multiplies the length of the curve by (2 + 1/cos alpha)/3.",
       "Sec. III, Fig. 3",
       {3},
       "koch-signature parts with consecutive iterations at one alpha",
       {}},
      {"eq6-simulation",
       true,
       "The tilt test of two spheropolygon blocks slides at the signature prediction phi = theta_max + atan(mu_a).",
       "Sec. IV C, Eq. 6, Fig. 5, 6, 7, 8, 10",
       {5, 6, 7, 8, 10},
       "tilt parts (Koch blocks)",
       {"tilt-hold-angle"}},
      {"eq6-atomic-friction",
       true,
       "The atomic friction angle adds to the signature maximum: phi - theta_max = atan(mu_a), the same for every "
       "surface.",
       "Eq. 6, Fig. 8",
       {8},
       "koch-signature and tilt parts with several mu_a",
       {}},
      {"mu-grows-with-dimension",
       true,
       "The friction coefficient grows with the fractal dimension of the Koch surface.",
       "Fig. 10",
       {10},
       "koch-signature parts (mu_a = 0, several alpha)",
       {}},
      {"divider-dimension",
       true,
       "The divider method recovers the dimension of Eq. 13 on the most iterated Koch curve; fewer iterations show "
       "the same scaling over a narrower range.",
       "Sec. IV C 3, Fig. 9",
       {9},
       "divider parts",
       {}},
      {"wm-contact-below-surface",
       true,
       "The maximum contact slope of a pair of WM profiles is smaller than their maximum surface slope.",
       "Sec. V C, Fig. 15, 16",
       {15, 16},
       "wm-pair-statistics parts",
       {}},
      {"wm-slopes-grow-with-dimension",
       true,
       "Maximum contact and surface slopes increase with D.",
       "Fig. 15",
       {15},
       "wm-pair-statistics parts",
       {}},
      {"wm-slopes-grow-with-resolution",
       true,
       "Maximum contact and surface slopes increase with n_max (finer wavelengths).",
       "Fig. 14",
       {14},
       "wm-pair-statistics parts with several n_max",
       {}},
      {"wm-contact-slope-limit",
       true,
       "As n_max grows the maximum contact slope tends to a finite value for D < 1.5 and keeps growing for D > 1.5.",
       "Sec. V C, VI, Fig. 14",
       {14},
       "wm-pair-statistics parts with three or more n_max",
       {}},
      {"wm-slope-std-grow-with-dimension",
       true,
       "The standard deviations of contact and surface slopes grow with D, increasingly fast above D ~ 1.5.",
       "Fig. 17, 18",
       {17, 18},
       "wm-pair-statistics parts",
       {}},
      {"wm-contact-narrower",
       true,
       "The contact slopes of a pair of WM profiles are distributed more narrowly than the surface slopes.",
       "Sec. V C, Fig. 16",
       {16},
       "wm-pair-statistics parts (at their largest n_max)",
       {}},
      {"wm-rougher-with-dimension",
       true,
       "At equal rms height the WM profile gets rougher with D: its rms slope grows with D.",
       "Fig. 12",
       {12},
       "wm-pair-statistics parts with several D",
       {}},
      {"wm-phases-keep-rms-slope",
       true,
       "The random WM profile (Eq. 14) has every mode's amplitude of the deterministic one (Eq. 17), hence the same "
       "rms slope.",
       "Sec. V A, Fig. 11",
       {11},
       "wm-pair-statistics parts with compare_phases",
       {}},
      {"wm-spline-matches-linear",
       true,
       "At the sampling of Eq. 16 (L_s/10) the cubic spline and the polyline give the same contact-slope statistics.",
       "Sec. V B, Fig. 13",
       {13},
       "wm-pair-statistics parts with compare_slopes",
       {}},
      {"eq18-range",
       true,
       "The friction angle of random pairs in the tilt test lies in the range [theta_max - sigma, theta_max] + "
       "theta_a.",
       "Sec. V D, Eq. 18",
       {},
       "wm-tilt parts on the paper's protocol (constant rate, free settling)",
       {"dynamic-hold-bracket"}},
      // ------------------------------------------------------------- frictal's own findings
      {"tilt-hold-angle",
       false,
       "A Koch tilt test reads the hold angle of the rounded blocks from where the block rests (hold.hpp: the "
       "quasi-static process on the lift), within 0.1 deg, or a model warning flags the run.",
       "docs/analysis.md, \"What a tilt test reads: the hold angle\"",
       {5, 6, 7, 8, 10},
       "tilt parts (Koch blocks)",
       {}},
      {"tilt-sphero-prediction",
       false,
       "A Koch tilt test reads the spheropolygon prediction (the signature of the rounded blocks), within 0.1 deg, or "
       "a model warning flags the run.",
       "docs/dem.md sec. 6, \"Both predictions in every run, and the model warnings\"",
       {5, 6, 7, 8, 10},
       "tilt parts (Koch blocks)",
       {}},
      {"quasi-static-hold",
       false,
       "The quasi-static tilt of random pairs reads the hold angle phi_qs of the rounded blocks from where the block "
       "rests, within 0.1 deg, in at least 95 % of the pairs.",
       "docs/dem.md sec. 6, \"The quasi-static protocol against the hold angle\"",
       {},
       "wm-tilt parts, quasi-static protocol",
       {}},
      {"dynamic-hold-bracket",
       false,
       "The constant-rate tilt of random pairs from rest reads an angle between the inertial bound phi_in and the "
       "quasi-static hold angle phi_qs (0.1 deg of slack) in at least 90 % of the pairs that no warning flags.",
       "docs/dem.md sec. 4, \"A constant-rate test from rest\"",
       {},
       "wm-tilt parts, constant rate from rest (settling = relax)",
       {}},
      {"eq18-over-drops",
       false,
       "Eq. 18's range holds the central 90 % of the hold angles that repeated drops of a block on the same pair give, "
       "in at least 90 % of the pairs.",
       "docs/analysis.md, \"What a tilt test reads: the hold angle\"; docs/dem.md sec. 6",
       {},
       "wm-tilt parts on the paper's protocol (their pairs)",
       {}},
      {"runaway-independent",
       false,
       "The friction angle of the tilt test of random pairs does not depend on the run-away distance (0.5, 1, 2 "
       "lambda) that defines the slide.",
       "docs/dem.md sec. 6, \"Random pairs: the wm-tilt study\"",
       {},
       "wm-tilt parts on the paper's protocol",
       {}},
      {"sphero-closer-than-rigid",
       false,
       "On random pairs the spheropolygon prediction (signature with the spheroradius) is closer to the simulated "
       "angle than the rigid one.",
       "docs/dem.md sec. 6, \"Random pairs: the wm-tilt study\"",
       {},
       "wm-tilt parts on the paper's protocol",
       {}},
      {"areal-matched-prediction",
       false,
       "MuJoCo's 3D tilt test agrees within 0.2 deg with the matched quasi-static prediction on every pair of maps, "
       "block free and locked.",
       "docs/mujoco.md, \"The 0.2° target\"",
       {},
       "areal-tilt parts",
       {}},
      {"areal-prediction-spread",
       false,
       "MuJoCo's reading lies within 0.2 deg of the hold angles that the rigid quasi-static block reaches when one "
       "slip's end is moved by a sphere radius, free and locked.",
       "docs/mujoco.md, \"The prediction's spread\"",
       {},
       "areal-tilt parts",
       {}},
      {"areal-seat-by-seat",
       false,
       "From the seat where MuJoCo's block sat before its run-away, the rigid quasi-static block runs away within 0.2 "
       "deg of MuJoCo, free and locked.",
       "docs/mujoco.md, \"The study areal-tilt (pairs not tuned on)\"",
       {},
       "areal-tilt parts",
       {}},
  };
  return list;
}

const Claim* find_claim(const std::string& id) {
  for (const auto& c : claims())
    if (c.id == id) return &c;
  return nullptr;
}

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::Supported: return "supported";
    case Verdict::Superseded: return "superseded";
    case Verdict::NotSupported: break;
  }
  return "not supported";
}

Result<std::vector<Conclusion>> conclude(const std::vector<Report>& reports) {
  std::vector<Conclusion> out;
  for (const auto& c : claims()) {
    Conclusion k;
    k.claim = c;
    for (const auto& r : reports)
      for (const auto& f : r.findings)
        if (f.claim_id == c.id) k.checks.push_back({r.study, f.part, f.supported, f.cause});
    if (!k.checks.empty()) out.push_back(std::move(k));
  }
  for (const auto& r : reports)
    for (const auto& f : r.findings)
      if (!find_claim(f.claim_id))
        return make_error(
            fmt::format("study '{}', part '{}': the finding \"{}\" names claim '{}', which is not in "
                        "the catalogue (src/study/claims.cpp)",
                        r.study, f.part, f.claim, f.claim_id));
  auto supported = [&](const std::string& id) {
    for (const auto& k : out)
      if (k.claim.id == id) {
        for (const auto& ch : k.checks)
          if (!ch.supported) return false;
        return true;
      }
    return false;  // not checked: supersedes nothing
  };
  for (auto& k : out) {
    bool all = true;
    for (const auto& ch : k.checks) {
      if (ch.supported) continue;
      all = false;
      const std::string where = ch.study + "/" + ch.part;
      if (ch.cause.empty())
        k.uncaused.push_back(where);
      else
        k.cause += (k.cause.empty() ? "" : "; ") + where + ": " + ch.cause;
    }
    if (all) {
      k.verdict = Verdict::Supported;
      continue;
    }
    bool replaced = !k.claim.superseded_by.empty();
    for (const auto& id : k.claim.superseded_by) replaced = replaced && supported(id);
    k.verdict = replaced ? Verdict::Superseded : Verdict::NotSupported;
  }
  return out;
}

}  // namespace frictal::study
