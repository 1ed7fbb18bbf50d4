// frictal._core.contact: elastic normal contact of rough surfaces (frictal/contact.hpp), the same
// library call and numbers as `frictal contact`; dicts with the contact table's Python keys (SI).
#include "bindings.hpp"
#include "frictal/contact.hpp"

namespace py = pybind11;
using namespace frictal;
using frictal::py_detail::ok;

namespace {

std::vector<double> as_values(const py::object& v) {
  if (v.is_none()) return {};
  if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) return {v.cast<double>()};
  return v.cast<std::vector<double>>();
}

}  // namespace

void frictal_bind_contact(py::module_& m) {
  m.def(
      "contact",
      [](const py::object& lower, const py::object& upper, const py::object& load, const py::object& pressure,
         double modulus, double poisson, std::optional<double> upper_modulus, std::optional<double> upper_poisson,
         double hardness, bool periodic, bool in_place, double spacing, const std::string& format,
         const std::string& unit, double tolerance, bool stiffness, bool fields, unsigned threads, py::kwargs kw) {
        // The conditioning: the fields of conditioning_settings() (one form for both surfaces, a
        // line or a plane unless detrend says otherwise).
        const Conditioning c =
            py_detail::conditioning_keywords(
                kw, "contact",
                {"load", "pressure", "modulus", "poisson", "upper_modulus", "upper_poisson", "hardness", "periodic",
                 "in_place", "spacing", "format", "unit", "tolerance", "stiffness", "fields", "threads"})
                .of_surface(false);
        const std::vector<double> forces = as_values(load), pressures = as_values(pressure);
        if (forces.empty() == pressures.empty())
          throw py::value_error(
              "contact: give load= (the force: N for maps, N/m for profiles) or pressure= (nominal, Pa), one of them");
        ContactOptions o;
        const ElasticMaterial first{modulus, poisson};
        if (upper.is_none()) {
          if (upper_modulus || upper_poisson)
            throw py::value_error("upper_modulus/upper_poisson: apply to upper, which is not given");
          o.contact_modulus = ok(contact_modulus(first));
        } else if (upper_modulus && std::isinf(*upper_modulus)) {
          o.contact_modulus = ok(contact_modulus(first));  // a rigid upper body
        } else {
          const ElasticMaterial second{upper_modulus.value_or(modulus), upper_poisson.value_or(poisson)};
          o.contact_modulus = ok(contact_modulus(first, second));
        }
        o.hardness = hardness;
        o.periodic = periodic;
        o.tolerance = tolerance;
        o.stiffness = stiffness;
        o.keep_fields = fields;
        o.threads = threads;
        std::vector<Warning> warnings;
        auto conditioned = [&](const py::object& obj, const char* what, std::string& record) {
          PredictSurface s = py_detail::to_surface(obj, spacing, format, unit, what);
          for (const Warning& w : s.reader_warnings) add_warning(warnings, w);
          if (s.is_map) {
            ConditionedMap cm = ok(condition(s.map, c, s.name));
            for (Warning& w : check_map(cm.map, s.name, {}, rms_height_as_read(s.map.heights)))
              add_warning(warnings, std::move(w));
            s.map = std::move(cm.map);
            record = cm.record.text();
          } else {
            ConditionedProfile cp = ok(condition(s.profile, c, s.name));
            for (Warning& w : check_profile(cp.profile, s.name, {}, rms_height_as_read(s.profile.z)))
              add_warning(warnings, std::move(w));
            std::vector<Warning> resampled;
            s.profile = ok(equally_spaced(cp.profile, s.name, resampled));
            for (Warning& w : resampled) add_warning(warnings, std::move(w));
            record = cp.record.text();
          }
          return s;
        };
        std::string record;
        PredictSurface lo = conditioned(lower, "lower", record);
        if (!upper.is_none()) {
          std::string upper_record;
          PredictSurface up = conditioned(upper, "upper", upper_record);
          record += "; " + upper_record;
          if (up.is_map != lo.is_map) throw py::value_error("contact: a profile and a map; give two of one kind");
          if (lo.is_map)
            lo.map = ok(composite_topography(lo.map, up.map, !in_place, lo.name, up.name));
          else
            lo.profile = ok(composite_topography(lo.profile, up.profile, !in_place, lo.name, up.name));
        } else if (in_place) {
          throw py::value_error("in_place: applies to upper, which is not given");
        }
        std::vector<ContactLoad> loads;
        for (double f : forces) loads.push_back({ContactLoadKind::Force, f});
        for (double p : pressures) loads.push_back({ContactLoadKind::Pressure, p});
        const std::vector<ContactResult> results = ok(py_detail::nogil([&] {
          return lo.is_map ? solve_contact_curve(lo.map, loads, o) : solve_contact_curve(lo.profile, loads, o);
        }));
        py::list out;
        for (const ContactResult& r : results) {
          py::dict d = py_detail::to_dict(contact_columns(), r);
          RunRecord run;
          run.kind = lo.is_map ? "map" : "profile";
          run.conditioning = record;
          run.warnings = warnings;
          for (const Warning& x : r.warnings) add_warning(*run.warnings, x);
          py_detail::put_columns(d, run_record_columns(), run);
          out.append(d);
        }
        if (results.size() == 1 && (py::isinstance<py::float_>(load) || py::isinstance<py::int_>(load) ||
                                    py::isinstance<py::float_>(pressure) || py::isinstance<py::int_>(pressure)))
          return py::object(out[0]);
        return py::object(out);
      },
      py::arg("lower"), py::arg("upper") = py::none(), py::kw_only(), py::arg("load") = py::none(),
      py::arg("pressure") = py::none(), py::arg("modulus"), py::arg("poisson"), py::arg("upper_modulus") = py::none(),
      py::arg("upper_poisson") = py::none(), py::arg("hardness") = 0.0, py::arg("periodic") = false,
      py::arg("in_place") = false, py::arg("spacing") = 0.0, py::arg("format") = "auto", py::arg("unit") = "",
      py::arg("tolerance") = ContactOptions{}.tolerance, py::arg("stiffness") = true, py::arg("fields") = false,
      py::arg("threads") = 1u,
      ("Elastic normal contact (as `frictal contact`; runs without the GIL; no warnings.warn: frictal.contact issues "
       "them). lower alone: an elastic body (modulus E in Pa, poisson nu) pressed against a rigid flat; with upper: "
       "two bodies (upper_modulus/upper_poisson, default the same; upper_modulus=inf: a rigid upper) whose composite "
       "topography "
       "(upper turned over unless in_place) meets a rigid flat. Surfaces: paths, Profiles, dicts from read_surface/"
       "read_map or arrays of heights with spacing (m). load: the force (N for maps, N/m per unit depth for profiles) "
       "or pressure: the nominal pressure (Pa), a number or a list (a load curve). hardness H (Pa, 0: none) caps the "
       "pressure; periodic: the surface repeats with its length (else padded); detrend/crop/remove_spikes as "
       "frictal.condition. Returns a dict (one number given) or a list of dicts with the keys of `frictal columns` "
       "table contact (SI), kind, conditioning, warnings and with fields=True pressure (Pa) and gap (m) (shape "
       "(ny, nx) for maps). The conditioning's keywords are the fields of conditioning_settings() (SI; crop also a "
       "sequence of metres):\n" +
       py_detail::keyword_doc(conditioning_settings()))
          .c_str());
}
