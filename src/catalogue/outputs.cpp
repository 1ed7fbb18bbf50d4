// Every output table (frictal/outputs.hpp): the typed tables of the result types, declared beside
// them in their modules, and the declarations of what the front ends print around them (the
// inputs a command echoes, nested objects, the outputs of commands whose result is composed in
// the front end). `frictal columns` prints this list; a test checks every key a command or a
// Python function prints against it.
#include <algorithm>
#include <string_view>

#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/areal_tilt.hpp"
#include "frictal/conditioning.hpp"
#include "frictal/contact.hpp"
#include "frictal/fractal.hpp"
#include "frictal/hold.hpp"
#include "frictal/io.hpp"
#include "frictal/outputs.hpp"
#include "frictal/predict.hpp"
#include "frictal/scan_stats.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"
#include "frictal/study.hpp"
#include "frictal/tilt.hpp"
#include "frictal/version.hpp"
#include "frictal/warnings.hpp"

namespace frictal {

namespace {

/// A declared column (no value here: the front end writes it). python "" = JSON only, "=" = in Python
/// by the rule (python_key: the key without its unit suffix, SI), "-" none.
ColumnInfo ci(std::string key, std::string unit, std::string help, std::string python = "-") {
  if (python == "=") python = python_key(key);
  if (python == "-") python.clear();
  return {std::move(key), std::move(unit), std::move(help), std::move(python)};
}
/// A Python-only column.
ColumnInfo py(std::string python, std::string unit, std::string help) {
  return {"", std::move(unit), std::move(help), std::move(python)};
}

}  // namespace

BuildInfo build_info() { return {version(), git_commit(), build_type(), mujoco_available()}; }

const Columns<BuildInfo>& build_info_columns() {
  using T = BuildInfo;
  static const Columns<T> cols = {
      column<T>("version", "text", "frictal's version", [](const T& b) { return b.version; }),
      column<T>("git_commit", "text", "the commit built", [](const T& b) { return b.git_commit; }),
      column<T>("build_type", "text", "CMake build type", [](const T& b) { return b.build_type; }),
      column<T>("mujoco", "flag", "the 3D tilt test is available", [](const T& b) { return b.mujoco; }),
  };
  return cols;
}

const Columns<RunRecord>& run_record_columns() {
  using T = RunRecord;
  // A text field written when it has a value; `python`: "" = in Python by the rule, "-" = not.
  auto text = [](std::string key, std::string help, std::optional<std::string> T::*field, std::string python) {
    return only_if(column<T>(
                       std::move(key), "text", std::move(help), [field](const T& r) { return *(r.*field); }, python),
                   [field](const T& r) { return (r.*field).has_value(); });
  };
  // A number written when it has a value.
  auto number = [](std::string key, std::string unit, std::string help, std::optional<double> T::*field) {
    return only_if(
        column<T>(
            std::move(key), std::move(unit), std::move(help), [field](const T& r) { return *(r.*field); }, "-"),
        [field](const T& r) { return (r.*field).has_value(); });
  };
  static const Columns<T> cols = {
      text("lower", "the lower surface (file or generator)", &T::lower, "-"),
      text("upper", "the upper surface, as measured (turned over to face the lower)", &T::upper, "-"),
      text("file", "the surface file read", &T::file, "-"),
      text("format", "the file's format as read", &T::format, ""),
      text("kind", "profile or map", &T::kind, ""),
      text("method", "the method the numbers come from", &T::method, "-"),
      text("slopes", "the slope method of the signature: exact or spline", &T::slopes, "-"),
      number("surface_slope_max_deg", "deg", "steepest slope of either surface", &T::surface_slope_max),
      text("conditioning", "every conditioning step applied first (crop, spikes, form), with its numbers",
           &T::conditioning, ""),
      list_column<T>("warnings", "warning",
                     "warnings: implausible inputs or results (frictal warnings lists the codes)", warning_columns(),
                     [](const T& r) { return r.warnings; }),
      number("wall_time_s", "s", "wall time of the computation", &T::wall_time),
      number("hold_wall_time_s", "s", "wall time of the signature and the hold analysis together (one pass)",
             &T::hold_wall_time),
  };
  return cols;
}

namespace {

std::vector<OutputTable> make_tables() {
  std::vector<OutputTable> t;
  t.push_back({"prediction",
               "frictal predict --json, Python frictal.predict(...).to_dict() (attributes: the Python keys, SI), the "
               "report's embedded JSON",
               infos(prediction_columns())});
  t.back().columns.push_back(ci("warnings", "list:warning", "the warnings of the inputs and the result", "warnings"));
  t.push_back({"command", "what commands print beside their results: the inputs they were given and how they ran",
               infos(run_record_columns())});

  t.push_back({"warning", "one warning: its code (frictal warnings) and message", infos(warning_columns())});
  t.push_back(
      {"histogram", "a density: bin edges and density (units in the parent key's help)", infos(histogram_columns())});
  t.push_back({"signature", "frictal signature --json; Python frictal.signature(...)", infos(signature_columns())});
  t.push_back({"contact",
               "frictal contact --json (one load: these keys; several: a list of them under 'curve'); Python "
               "frictal.contact(...) (SI under the same keys)",
               infos(contact_columns())});
  t.back().columns.push_back(py("pressure", "list", "fields=True: the pressure at every point (Pa; maps: (ny, nx))"));
  t.back().columns.push_back(py("gap", "list", "fields=True: the gap at every point (m; maps: (ny, nx))"));
  t.push_back({"contact_curve", "frictal contact --json with several loads", infos(contact_curve_columns())});
  t.push_back({"contacts",
               "Python frictal.signature(..., keep_contacts=True)['contacts']; the columns of frictal signature "
               "--contacts: every contact",
               infos(contact_list_columns())});
  t.push_back({"friction", "the rigid bound (Eq. 6) and Eq. 18's low end: signature --json, Python predict_friction",
               infos(friction_columns())});
  t.push_back({"friction_backward", "the rigid bound sliding towards -x: signature --json",
               infos(friction_backward_columns())});
  t.push_back(
      {"hold", "the hold analysis: signature --json (flat keys), Python hold_angle(...)", infos(hold_columns())});
  t.push_back({"hold_start", "one drop (--start-offset): signature --json", infos(hold_start_columns())});
  t.push_back(
      {"hold_distribution", "Python hold_angle(...)['forward'|'backward']", infos(hold_distribution_columns())});
  t.push_back(
      {"hold_statistics", "the statistics over drops of a hold angle (Python)", infos(hold_statistics_columns())});
  t.push_back({"hold_basins", "the basins of a distribution (Python)", infos(hold_basins_columns())});
  t.push_back({"hold_drop", "one drop (Python hold_angle(..., start_offset=)['start'])", infos(hold_drop_columns())});
  t.push_back({"profile_stats", "frictal stats --json of a profile; Python profile_stats(...)",
               infos(profile_stats_columns())});
  t.push_back({"profile_scan_stats", "the scan quantities of a profile: stats --json, Python profile_stats",
               infos(profile_scan_stats_columns())});
  t.push_back({"map_stats", "frictal stats --json of a map; Python map_stats(...)", infos(map_stats_columns())});
  t.push_back({"map_grid", "a map's grid: stats --json, info --json", infos(map_grid_columns())});
  t.push_back({"map_scan_stats", "the scan quantities of a map: stats --json, Python map_stats",
               infos(map_scan_stats_columns())});
  t.push_back({"tilt", "frictal tilt --json; Python frictal.tilt(...)", infos(tilt_columns())});
  t.push_back({"tilt_scales", "tilt --json 'scales'", infos(tilt_scales_columns())});
  t.push_back({"tilt_estimate", "tilt --json 'estimate'", infos(tilt_estimate_columns())});
  t.push_back({"tilt_stage_times", "tilt --json 'stage_time_s' (s)", infos(tilt_stage_time_columns())});
  t.push_back({"tilt_scaling", "tilt --json 'scaled_defaults'", infos(tilt_scaling_columns())});
  t.push_back({"tilt_surface",
               "tilt --json 'surface': the files or the generator (beside a generator's parameters, the keys of "
               "frictal settings GENERATOR)",
               infos(tilt_surface_columns())});
  t.push_back({"tilt_scaled_setting", "one setting scaled to the surfaces (JSON: the setting's text unit; Python: SI)",
               infos(tilt_scaled_setting_columns())});
  t.push_back({"tilt_series", "Python frictal.tilt(...)['series']: one sample per output interval",
               infos(tilt_series_columns())});
  t.push_back(
      {"tilt_frames", "Python frictal.read_tilt_frames(...): a frames file read back", infos(tilt_frames_columns())});
  t.push_back({"dimension", "frictal dimension --json; Python divider_dimension, box_dimension, psd_dimension",
               infos(fractal_fit_columns())});
  t.push_back({"koch_dimension", "frictal dimension koch --method eq13 --json", infos(koch_dimension_columns())});
  t.push_back({"info", "frictal info --json: what a surface file holds; Python read_surface(...)",
               infos(surface_data_columns())});
  t.back().columns.insert(t.back().columns.end(),
                          {py("heights", "m", "the map's heights (ny, nx), NaN where not measured"),
                           py("dx", "m", "node spacing along x"), py("dy", "m", "node spacing along y")});
  t.push_back({"info_channel", "one channel of a file (frictal info --json)", infos(channel_info_columns())});
  t.push_back({"warning_code", "frictal warnings --json: every warning code", infos(warning_code_columns())});
  t.push_back({"formats", "frictal formats --json: every readable format", infos(format_list_columns())});
  t.push_back({"format", "one readable format (frictal formats --json)", infos(format_info_columns())});
  t.push_back({"areal",
               "frictal areal --json; Python areal_signature(...): the areal signature of two blocks along a direction",
               infos(areal_signature_columns())});
  {
    std::vector<ColumnInfo> bound = infos(areal_bound_columns());
    t.back().columns.insert(t.back().columns.end(), bound.begin(), bound.end());
  }
  t.push_back({"areal_hold",
               "frictal areal --lateral|--drops|--start-offset --json; Python areal_hold(...) (SI, no unit suffix)",
               infos(areal_hold_columns())});
  t.push_back({"offset_xy", "a point as a row of numbers [x_m, y_m] (areal --json's drop_offsets_m)",
               infos(offset_xy_columns())});
  t.push_back({"anisotropy", "frictal anisotropy --json; Python anisotropy(...) (arrays over directions)",
               infos(anisotropy_columns())});
  t.push_back({"anisotropy_direction", "one direction of frictal anisotropy --json", infos(anisotropy_row_columns())});
  t.push_back({"areal_tilt",
               "frictal areal-tilt --json (the MuJoCo run and the predictions matched to it); Python areal_tilt(...) "
               "(SI, no unit suffix)",
               infos(areal_tilt_report_columns())});
  t.push_back({"tilt_stop", "a stop of the block as a row of numbers [tilt_deg, x_m, y_m] (areal-tilt --json)",
               infos(tilt_stop_columns())});
  t.push_back({"areal_tilt_increment",
               "one increment of the 3D run as a row of numbers (areal-tilt --json's increment_trace)",
               infos(areal_tilt_increment_columns())});
  t.push_back({"areal_tilt_hold", "Python areal_tilt_hold(...): the continuous model of one drop",
               infos(areal_tilt_hold_columns())});
  t.push_back({"conditioning", "Python condition(...)[1]: what each conditioning step did",
               infos(conditioning_record_columns())});
  t.push_back({"build_info", "Python build_info(): the build of the compiled core", infos(build_info_columns())});
  t.push_back({"autocorrelation", "Python autocorrelation(...)", infos(autocorrelation_columns())});
  t.push_back({"map_data", "Python read_map(...): the heights and the grid", infos(map_data_columns())});
  t.push_back({"stats_extras",
               "what frictal stats --json adds with --tip-radius, --acf, --histograms; Python profile_stats and "
               "map_stats with tip_radius (profile_stats: slope_pdf always)",
               infos(stats_extras_columns())});
  // Studies (frictal study status|report --json; Python study_status, study_run, study_rows).
  t.push_back({"study_status", "frictal study status --json; Python study_status(store)",
               infos(study::study_status_columns())});
  t.push_back({"study_tasks", "task counts of a store or a run", infos(study::study_tasks_columns())});
  t.push_back({"study_part", "one part of a study's status", infos(study::study_part_columns())});
  t.push_back({"study_run", "Python study_run(...), study_run_many(...)", infos(study::study_run_columns())});
  t.push_back({"study_report",
               "frictal study report --json: the findings as data (docs/studies.md)",
               {ci("reports", "list:study_findings", "one report per store"),
                ci("conclusions", "list:study_conclusion", "one verdict per claim over every store"),
                ci("claims", "list:study_claim", "the catalogue of claims")}});
  t.push_back({"study_findings",
               "the findings of one store",
               {ci("study", "text", "the study"), ci("title", "text", "the report's title"),
                ci("findings", "list:study_finding", "each check of a claim on a part")}});
  t.push_back({"study_finding",
               "one check of a claim on one part",
               {ci("claim_id", "text", "the claim checked"), ci("source", "text", "paper or frictal"),
                ci("figures", "count", "figures of the paper it concerns"), ci("part", "text", "the part"),
                ci("claim", "text", "the claim as stated"), ci("criterion", "text", "the criterion, with numbers"),
                ci("numbers", "list", "the numbers behind it"), ci("verdict", "text", "supported, not supported, ..."),
                ci("cause", "text", "the measured cause")}});
  t.push_back({"study_claim",
               "a claim of the paper or of frictal",
               {ci("id", "text", "stable id"), ci("source", "text", "paper or frictal"),
                ci("statement", "text", "the claim"), ci("where", "text", "where it is made"),
                ci("figures", "count", "figures"), ci("applies_to", "text", "which parts it applies to"),
                ci("superseded_by", "text", "the frictal findings that replace it")}});
  t.push_back({"study_conclusion",
               "the verdict on one claim",
               {ci("id", "text", "the claim"), ci("source", "text", "paper or frictal"),
                ci("statement", "text", "the claim"), ci("where", "text", "where it is made"),
                ci("figures", "count", "figures"), ci("applies_to", "text", "which parts it applies to"),
                ci("superseded_by", "text", "the findings that replace it"),
                ci("verdict", "text", "supported, superseded or not supported"),
                ci("cause", "text", "the measured causes"), ci("uncaused", "text", "parts with no measured cause"),
                ci("checks", "list:study_check", "each part's verdict")}});
  t.push_back({"study_check",
               "one part's verdict on a claim",
               {ci("study", "text", "the study"), ci("part", "text", "the part"), ci("verdict", "text", "the verdict"),
                ci("cause", "text", "the measured cause")}});
  t.push_back({"study_row", "Python study_rows(store): one done task", infos(study::study_row_columns())});
  return t;
}

}  // namespace

const std::vector<OutputTable>& output_tables() {
  static const std::vector<OutputTable> tables = make_tables();
  return tables;
}

const OutputTable* find_output_table(std::string_view name) {
  const auto& t = output_tables();
  auto it = std::find_if(t.begin(), t.end(), [&](const OutputTable& x) { return x.name == name; });
  return it == t.end() ? nullptr : &*it;
}

}  // namespace frictal
