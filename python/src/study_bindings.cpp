// frictal._core — bindings of studies (study.hpp): run a study file into a store, and read a
// store back (status, report, export, rows, the registry of task kinds). The same library
// functions as `frictal study ...`; library errors raise ValueError (OSError for I/O).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "frictal/study.hpp"

namespace py = pybind11;
using namespace frictal;
using namespace frictal::study;

namespace {

template <class T>
T ok(Result<T> r) {
  if (!r) {
    if (r.error().code == ErrorCode::Io) {
      PyErr_SetString(PyExc_OSError, r.error().message.c_str());
      throw py::error_already_set();
    }
    throw py::value_error(r.error().message);
  }
  return std::move(r).value();
}

/// A study table's Python dict: each column by the generic writer (bindings.hpp), a data map
/// (unit "map", frictal/outputs.hpp) as a dict of its entries under their keys, each value as the
/// generic writer holds a value of its entry's unit (an int for "count", a numpy array for a list).
template <class T>
py::dict study_dict(const Columns<T>& cols, const T& value) {
  py::dict d;
  for (const Column<T>& c : cols) {
    if (c.python.empty() || !has_output(c, value)) continue;
    if (c.unit != "map") {
      py_detail::put_columns(d, Columns<T>{c}, value);
      continue;
    }
    py::dict m;
    for (const OutputRow& r : c.rows(value))
      for (const OutputField& f : r)
        m[py::str(f.info.python)] = py_detail::py_value(f.info.unit, f.si, f.shape, f.fixed);
    d[py::str(c.python)] = m;
  }
  return d;
}

std::unique_ptr<Store> open_existing(const std::string& path) { return ok(Store::open_existing(path)); }

}  // namespace

void frictal_bind_study(py::module_& m) {
  m.def(
      "study_kinds",
      []() -> py::object {
        py::object all = py::module_::import("json").attr("loads")(kinds_json(default_registry()));
        return all["kinds"];
      },
      "The task kinds of this build: a list of dicts (name, description, version, available, reason, outputs with "
      "name/unit/description/array, plots: the plot views scripts/plot_studies.py draws).\n\n"
      "Each output names its unit (SI: m, rad, s; angles in study outputs are in deg as their names say).");
  m.def(
      "study_run",
      [](const std::string& study_file, const std::string& store_path, unsigned threads, bool quick,
         std::vector<std::string> parts, bool skip_unavailable, const std::string& cache) {
        const TaskRegistry reg = default_registry();
        Study s = ok(load_study(study_file, quick, reg));
        auto store = ok(Store::open(store_path, s));
        RunOptions o;
        o.threads = threads;
        o.parts = std::move(parts);
        o.skip_unavailable = skip_unavailable;
        o.cache = cache == "none" ? std::string() : cache == "auto" ? default_cache_path(store_path) : cache;
        RunSummary sum;
        {
          py::gil_scoped_release release;
          sum = ok(run_threads(s, *store, reg, o));
        }
        return py_detail::to_dict(study_run_columns(), StudyRunReport{sum, ok(store->counts())});
      },
      py::arg("study"), py::arg("store"), py::arg("threads") = 0, py::arg("quick") = false,
      py::arg("parts") = std::vector<std::string>{}, py::arg("skip_unavailable") = false, py::arg("cache") = "auto",
      "Runs (or resumes) a study file into an SQLite store on threads (0 = every core); returns a summary dict.\n\n"
      "study, store: file paths; parameters in the study file use SI units (m, s), angles in deg.\n"
      "cache: the result cache shared by the studies of a folder, as `frictal study run --cache`: \"auto\"\n"
      "(results-cache.sqlite beside the store), \"none\", or a file; summary[\"reused\"] counts the tasks taken\n"
      "from it instead of being computed.");
  m.def(
      "study_run_many",
      [](const std::vector<std::string>& study_files, const std::string& store_dir, unsigned threads, bool quick,
         const std::string& cache) {
        const TaskRegistry reg = default_registry();
        std::vector<Study> studies;
        std::vector<std::string> paths;
        for (const auto& f : study_files) {
          studies.push_back(ok(load_study(f, quick, reg)));
          std::string stem = f.substr(f.rfind('/') == std::string::npos ? 0 : f.rfind('/') + 1);
          if (const auto dot = stem.rfind('.'); dot != std::string::npos && dot > 0) stem.resize(dot);
          const std::string path = store_dir + "/" + stem + ".sqlite";
          for (const auto& p : paths)
            if (p == path) throw py::value_error("store_dir: two studies have the file name '" + stem + "'");
          paths.push_back(path);
        }
        std::vector<std::unique_ptr<Store>> stores;
        std::vector<StudyRun> runs;
        for (std::size_t i = 0; i < studies.size(); ++i) {
          stores.push_back(ok(Store::open(paths[i], studies[i])));
          StudyRun r;
          r.study = &studies[i];
          r.store = stores.back().get();
          r.cache = cache == "none" ? std::string() : cache == "auto" ? default_cache_path(paths[i]) : cache;
          runs.push_back(std::move(r));
        }
        RunOptions o;
        o.threads = threads;
        std::vector<RunSummary> sums;
        {
          py::gil_scoped_release release;
          sums = ok(run_threads(runs, reg, o));
        }
        py::list out;
        for (std::size_t i = 0; i < studies.size(); ++i) {
          out.append(py_detail::to_dict(study_run_columns(),
                                        StudyRunReport{sums[i], ok(stores[i]->counts()), studies[i].name, paths[i]}));
        }
        return out;
      },
      py::arg("studies"), py::arg("store_dir"), py::arg("threads") = 0, py::arg("quick") = false,
      py::arg("cache") = "auto",
      "Runs (or resumes) several study files in one pool of threads, as `frictal study run A.toml B.toml\n"
      "--store-dir DIR`: the store of A.toml is store_dir/A.sqlite (the folder must exist); the costliest\n"
      "tasks of all studies start first, and a task two studies share is computed once (counted as reused\n"
      "in the other). Returns one summary dict per study (as study_run's, with \"study\" and \"store\").\n\n"
      "cache: \"auto\" (store_dir/results-cache.sqlite), \"none\", or a file. Parameters in the study files use SI\n"
      "units (m, s), angles in deg.");
  m.def(
      "study_status",
      [](const std::string& path) {
        auto store = open_existing(path);
        const StoreStatus st = ok(store_status(*store, default_registry()));
        return py_detail::to_dict(study_status_columns(), StudyStatusReport{path, st});
      },
      py::arg("store"),
      "How far a store is (as `frictal study status --json`).\n\n"
      "Returns counts of tasks (unitless) and times in s.");
  m.def(
      "study_report", [](const std::string& path) { return render_markdown(ok(report(*open_existing(path)))); },
      py::arg("store"),
      "The report of a store (Markdown): per-part tables and the paper's findings checked.\n\n"
      "Numbers carry their units in the text (deg, m, unitless ratios).");
  m.def(
      "study_findings",
      [](const std::vector<std::string>& paths) {
        std::vector<Report> reports;
        for (const std::string& p : paths) reports.push_back(ok(report(*open_existing(p))));
        const std::string text = ok(render_json(reports));
        return py::module_::import("json").attr("loads")(text);
      },
      py::arg("stores"),
      "The findings of one or more stores as data, the object of `frictal study report --json`: reports (each "
      "store's findings: claim_id, part, claim, criterion, numbers, verdict, cause), conclusions (one verdict per "
      "claim over every store: supported, superseded or not supported, with the measured causes) and the claims "
      "catalogue. Texts and numbers as the CLI prints them (angles in deg, lengths in m, ratios unitless).");
  m.def(
      "study_export",
      [](const std::string& path, const std::string& dir) { return ok(export_csv(*open_existing(path), dir)); },
      py::arg("store"), py::arg("directory"),
      "Writes the store as CSV files under directory (tasks.csv, PART.csv, PART-arrays.csv, PART-pooled-pdfs.csv, "
      "report.md); returns the file names.\n\n"
      "Columns are named with their units (_m, _deg, _s; unitless otherwise).");
  m.def(
      "study_rows",
      [](const std::string& path, const std::string& part, bool arrays) {
        py::list out;
        for (const TaskRow& r : ok(open_existing(path)->rows(part, arrays)))
          out.append(study_dict(study_row_columns(), r));
        return out;
      },
      py::arg("store"), py::arg("part") = "", py::arg("arrays") = true,
      "The done tasks of a store (or of one part): dicts with task_id, part, kind, params, scalars and arrays "
      "(numpy).\n\n"
      "Units: SI (m, rad, s) and deg, as the column names say (_m, _deg, _s).");
}
