// The output tables' optional and nested columns (frictal/outputs.hpp): a column written only
// where its value has it, and objects of another table under one key, as the generic writers
// see them (row_of, has_output, rows); the tilt report's objects of settings in text units.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "frictal/outputs.hpp"
#include "frictal/surface_spec.hpp"
#include "frictal/tilt.hpp"

namespace {

using frictal::Column;
using frictal::Columns;
using frictal::OutputRow;

struct Point {
  double x = 0;      // m
  double angle = 0;  // rad
};

struct Shape {
  std::optional<double> size;  // m
  std::optional<Point> centre;
  std::optional<std::vector<Point>> corners;
};

const Columns<Point>& point_columns() {
  static const Columns<Point> cols = {
      frictal::column<Point>("x_m", "m", "abscissa", [](const Point& p) { return p.x; }),
      frictal::column<Point>("angle_deg", "deg", "angle", [](const Point& p) { return p.angle; }),
  };
  return cols;
}

const Columns<Shape>& shape_columns() {
  static const Columns<Shape> cols = {
      frictal::only_if(frictal::column<Shape>("size_m", "m", "size", [](const Shape& s) { return *s.size; }),
                       [](const Shape& s) { return s.size.has_value(); }),
      frictal::object_column<Shape>("centre", "point", "the centre", point_columns(),
                                    [](const Shape& s) { return s.centre; }),
      frictal::list_column<Shape>(
          "corners", "point", "the corners", point_columns(), [](const Shape& s) { return s.corners; }, "-"),
  };
  return cols;
}

TEST(Outputs, AbsentValuesHaveNoOutput) {
  const Shape empty;
  for (const Column<Shape>& c : shape_columns()) EXPECT_FALSE(frictal::has_output(c, empty)) << c.key;
  Shape s;
  s.size = 2.5;
  EXPECT_TRUE(frictal::has_output(shape_columns()[0], s));
  EXPECT_DOUBLE_EQ(std::get<double>(shape_columns()[0].si(s)), 2.5);
  EXPECT_FALSE(frictal::has_output(shape_columns()[1], s));
}

// One Python key rule: the JSON key without its unit suffix (Python's values are SI); "-" keeps a
// column out of Python's dicts, and a Python-only column (JSON key "") names its key.
TEST(Outputs, PythonKeyIsTheJsonKeyWithoutItsUnitSuffix) {
  EXPECT_EQ(frictal::python_key("theta_max_forward_deg"), "theta_max_forward");
  EXPECT_EQ(frictal::python_key("rms_height_m"), "rms_height");
  EXPECT_EQ(frictal::python_key("contact_area_m2"), "contact_area");
  EXPECT_EQ(frictal::python_key("contact_stiffness_n_per_m"), "contact_stiffness");
  EXPECT_EQ(frictal::python_key("max_pressure_pa"), "max_pressure");
  EXPECT_EQ(frictal::python_key("load_n"), "load");
  EXPECT_EQ(frictal::python_key("speed_m_s"), "speed");
  EXPECT_EQ(frictal::python_key("rate_per_s"), "rate");
  EXPECT_EQ(frictal::python_key("mass_kg"), "mass");
  EXPECT_EQ(frictal::python_key("time_step_s"), "time_step");
  EXPECT_EQ(frictal::python_key("valid_points"), "valid_points");
  EXPECT_EQ(frictal::python_key("_m"), "_m");  // a suffix alone is a key, not a unit
  EXPECT_EQ(shape_columns()[0].python, "size");
  EXPECT_EQ(point_columns()[0].python, "x");
  EXPECT_EQ(point_columns()[1].python, "angle");
  EXPECT_EQ(frictal::python_key("x_m", "-"), "");
  EXPECT_EQ(frictal::python_key("", "gap"), "gap");
}

TEST(Outputs, NestedColumnsDeclareTheirTableAndKeys) {
  const Columns<Shape>& c = shape_columns();
  EXPECT_EQ(c[1].unit, "object:point");
  EXPECT_EQ(c[1].python, "centre");  // the JSON key (no unit suffix) by default
  EXPECT_EQ(c[2].unit, "list:point");
  EXPECT_EQ(c[2].python, "");  // "-": not in Python's dicts
  EXPECT_FALSE(c[1].si);
  EXPECT_TRUE(c[1].rows);
}

TEST(Outputs, NestedObjectsAreRowsOfTheirTable) {
  Shape s;
  s.centre = Point{1e-6, std::numbers::pi / 4};
  s.corners = std::vector<Point>{{0, 0}, {2e-6, std::numbers::pi / 2}, {3e-6, -std::numbers::pi}};
  const std::vector<OutputRow> centre = shape_columns()[1].rows(s);
  ASSERT_EQ(centre.size(), 1u);
  ASSERT_EQ(centre[0].size(), 2u);
  EXPECT_EQ(centre[0][0].info.key, "x_m");
  EXPECT_EQ(centre[0][0].info.python, "x");
  EXPECT_DOUBLE_EQ(std::get<double>(centre[0][0].si), 1e-6);
  // SI in the row; the interface unit's conversion is the writer's: 45 degrees.
  EXPECT_EQ(centre[0][1].info.unit, "deg");
  EXPECT_DOUBLE_EQ(std::get<double>(frictal::to_interface(centre[0][1].info.unit, centre[0][1].si)), 45.0);
  const std::vector<OutputRow> corners = shape_columns()[2].rows(s);
  ASSERT_EQ(corners.size(), 3u);
  EXPECT_DOUBLE_EQ(std::get<double>(frictal::to_interface("deg", corners[1][1].si)), 90.0);
  EXPECT_DOUBLE_EQ(std::get<double>(frictal::to_interface("deg", corners[2][1].si)), -180.0);
  s.corners = std::vector<Point>{};  // present and empty: an empty list, not a missing key
  EXPECT_TRUE(frictal::has_output(shape_columns()[2], s));
  EXPECT_TRUE(shape_columns()[2].rows(s).empty());
}

TEST(Outputs, RowsLeaveOutAbsentColumns) {
  Shape with, without;
  with.size = 1;
  // Only the columns with a value or objects are row fields.
  EXPECT_EQ(frictal::row_of(shape_columns(), with).size(), 1u);
  EXPECT_TRUE(frictal::row_of(shape_columns(), without).empty());
}

// A row of a table with nested columns holds their objects, so that tables nest to any depth; a
// nested field keeps its Python key (Python's writer nests dicts as the CLI's nests objects).
TEST(Outputs, NestedColumnsNestInRows) {
  Shape s;
  s.size = 1;
  s.centre = Point{1e-6, 0};
  s.corners = std::vector<Point>{{0, 0}, {2e-6, 0}};
  const OutputRow r = frictal::row_of(shape_columns(), s);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_FALSE(r[0].nested);
  EXPECT_TRUE(r[1].nested);
  EXPECT_EQ(r[1].info.unit, "object:point");
  EXPECT_EQ(r[1].info.python, "centre");
  ASSERT_EQ(r[1].rows.size(), 1u);
  EXPECT_DOUBLE_EQ(std::get<double>(r[1].rows[0][0].si), 1e-6);
  EXPECT_TRUE(r[2].nested);
  EXPECT_EQ(r[2].info.unit, "list:point");
  ASSERT_EQ(r[2].rows.size(), 2u);
  EXPECT_DOUBLE_EQ(std::get<double>(r[2].rows[1][0].si), 2e-6);
}

// Rows of numbers and maps of objects declare their table in the unit; their rows are the
// table's rows, as a list column's.
TEST(Outputs, RowsAndMapColumnsDeclareTheirTable) {
  struct Named {
    std::string name;
    double x = 0;
  };
  static const Columns<Named> named = {
      frictal::column<Named>(
          "name", "text", "name", [](const Named& n) { return n.name; }, "-"),
      frictal::column<Named>(
          "x_m", "m", "abscissa", [](const Named& n) { return n.x; }, "-"),
  };
  const std::vector<Named> items = {{"a", 1}, {"b", 2}};
  const auto f = [&](const Shape&) { return std::optional(items); };
  const Column<Shape> rows = frictal::rows_column<Shape>("xs", "named", "rows", named, f, "-");
  const Column<Shape> map = frictal::map_column<Shape>("by_name", "named", "map", named, f, "-");
  EXPECT_EQ(rows.unit, "rows:named");
  EXPECT_EQ(map.unit, "map:named");
  // Python's array of the rows: (rows, columns).
  EXPECT_EQ(rows.shape(Shape{}), (std::vector<std::size_t>{2, 2}));
  const std::vector<OutputRow> r = map.rows(Shape{});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(std::get<std::string>(r[1][0].si), "b");
  EXPECT_DOUBLE_EQ(std::get<double>(r[1][1].si), 2.0);
}

// A data map is one nested row whose fields are named by the data (an empty key kept), each
// value with its entry's unit; its Python key is its key unless given.
TEST(Outputs, DataMapsAreOneRowKeyedByTheirData) {
  const auto entries = [](const Shape& s) {
    std::vector<frictal::MapEntry> e{{"", "count", 3.0}, {"2", "count", 4.0}};
    if (s.size) e.push_back({"size", "1", *s.size});
    return e;
  };
  const Column<Shape> by = frictal::data_map_column<Shape>("done_by", "counts", entries);
  const Column<Shape> json_only = frictal::data_map_column<Shape>("done_by", "counts", entries, "-");
  EXPECT_EQ(by.unit, "map");
  EXPECT_TRUE(frictal::is_nested_unit(by.unit));
  EXPECT_EQ(by.python, "done_by");
  EXPECT_TRUE(json_only.python.empty());
  Shape s;
  EXPECT_TRUE(frictal::has_output(by, s));  // an empty map is written too
  s.size = 0.5;
  const OutputRow r = frictal::row_of(Columns<Shape>{by}, s);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].nested);
  ASSERT_EQ(r[0].rows.size(), 1u);
  const OutputRow& m = r[0].rows[0];
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0].info.key, "");
  EXPECT_EQ(m[0].info.python, "");
  EXPECT_EQ(m[1].info.key, "2");
  EXPECT_EQ(m[1].info.python, "2");
  EXPECT_EQ(m[1].info.unit, "count");
  EXPECT_DOUBLE_EQ(std::get<double>(m[1].si), 4.0);
  EXPECT_EQ(m[2].info.unit, "1");
  EXPECT_DOUBLE_EQ(std::get<double>(m[2].si), 0.5);
}

TEST(Outputs, ListsCarryTheirShapeAndFixedLength) {
  struct Grid {
    std::size_t nx = 3, ny = 2;
    std::vector<double> values = {1, 2, 3, 4, 5, 6};
  };
  const Columns<Grid> cols = {
      frictal::with_shape(frictal::column<Grid>(
                              "", "m", "values", [](const Grid& g) { return g.values; }, "values"),
                          [](const Grid& g) {
                            return std::vector<std::size_t>{g.ny, g.nx};
                          }),
      frictal::fixed_length(frictal::column<Grid>(
          "", "count", "points",
          [](const Grid& g) {
            return std::vector<double>{double(g.nx), double(g.ny)};
          },
          "points")),
  };
  const OutputRow r = frictal::row_of(cols, Grid{});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].shape, (std::vector<std::size_t>{2, 3}));
  EXPECT_FALSE(r[0].fixed);
  EXPECT_TRUE(r[1].shape.empty());
  EXPECT_TRUE(r[1].fixed);
}

TEST(Outputs, WarningsAreRowsOfCodeAndMessage) {
  const frictal::Warning w("scale", "heights 8 m");
  const OutputRow r = frictal::row_of(frictal::warning_columns(), w);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].info.key, "code");
  EXPECT_EQ(std::get<std::string>(r[0].si), "scale");
  EXPECT_EQ(std::get<std::string>(r[1].si), "heights 8 m");
}

TEST(Outputs, RunRecordWritesTheFieldsGiven) {
  frictal::RunRecord run;
  run.file = "a.csv";
  run.warnings = std::vector<frictal::Warning>{};
  std::vector<std::string> written;
  for (const Column<frictal::RunRecord>& c : frictal::run_record_columns())
    if (frictal::has_output(c, run)) written.push_back(c.key);
  EXPECT_EQ(written, (std::vector<std::string>{"file", "warnings"}));
}

/// The field `key` of `row`, or nullptr.
const frictal::OutputField* field(const OutputRow& row, const std::string& key) {
  for (const frictal::OutputField& f : row)
    if (f.info.key == key) return &f;
  return nullptr;
}

TEST(Outputs, TiltSettingsAndSurfaceAreSettingsInTextUnits) {
  // A Koch surface of alpha = 20 deg, n = 2 and a largest tilt of 30 deg, both given in SI: the
  // "settings" and "surface" objects hold them in the text units of their tables (degrees, an
  // integer) under the tables' names, beside the generator's name; the inputs' warnings given
  // are the report's, before the run's.
  constexpr double kDeg = std::numbers::pi / 180;
  frictal::TiltResult result;
  result.warnings.emplace_back("rotation", "turned");
  frictal::TiltConfig config = frictal::default_tilt_config();
  config.max_tilt = 30 * kDeg;
  frictal::TiltSurface surface;
  surface.generator = "koch";
  surface.parameters = &frictal::find_generator("koch")->fields;
  surface.values = {{"alpha", 20 * kDeg}, {"iterations", std::int64_t{2}}};
  const std::vector<frictal::Warning> warnings = {{"reader", "a.csv: read as"}, result.warnings.front()};
  const OutputRow row =
      frictal::row_of(frictal::tilt_columns(), frictal::TiltReport{result, config, nullptr, &surface, &warnings});

  const frictal::OutputField* settings = field(row, "settings");
  ASSERT_TRUE(settings && settings->nested && settings->rows.size() == 1u);
  const frictal::OutputField* max_tilt = field(settings->rows[0], "max_tilt");
  ASSERT_TRUE(max_tilt);
  EXPECT_EQ(max_tilt->info.unit, "deg");
  EXPECT_NEAR(std::get<double>(frictal::to_interface(max_tilt->info.unit, max_tilt->si)), 30.0, 1e-12);
  const frictal::OutputField* predict = field(settings->rows[0], "predict");
  ASSERT_TRUE(predict);
  EXPECT_EQ(predict->info.unit, "flag");
  EXPECT_TRUE(std::get<bool>(predict->si));
  EXPECT_EQ(settings->rows[0].size(), frictal::tilt_settings().size());

  const frictal::OutputField* s = field(row, "surface");
  ASSERT_TRUE(s && s->nested && s->rows.size() == 1u);
  ASSERT_TRUE(field(s->rows[0], "generator"));
  EXPECT_EQ(std::get<std::string>(field(s->rows[0], "generator")->si), "koch");
  const frictal::OutputField* alpha = field(s->rows[0], "alpha");
  ASSERT_TRUE(alpha);
  EXPECT_NEAR(std::get<double>(frictal::to_interface(alpha->info.unit, alpha->si)), 20.0, 1e-12);
  const frictal::OutputField* iterations = field(s->rows[0], "iterations");
  ASSERT_TRUE(iterations);
  EXPECT_EQ(iterations->info.unit, "count");
  EXPECT_EQ(std::get<double>(iterations->si), 2.0);
  EXPECT_FALSE(field(s->rows[0], "lower"));  // files only
  // Only the parameters given, and the name: no key of the table beyond them.
  EXPECT_EQ(s->rows[0].size(), 3u);

  const frictal::OutputField* w = field(row, "warnings");
  ASSERT_TRUE(w && w->rows.size() == 2u);
  EXPECT_EQ(std::get<std::string>(w->rows[0][0].si), "reader");
  EXPECT_EQ(std::get<std::string>(w->rows[1][0].si), "rotation");

  // Without the inputs: no surface, the run's warnings alone; a file's surface names the files.
  const OutputRow bare = frictal::row_of(frictal::tilt_columns(), frictal::TiltReport{result, config});
  EXPECT_FALSE(field(bare, "surface"));
  ASSERT_TRUE(field(bare, "warnings") && field(bare, "warnings")->rows.size() == 1u);
  frictal::TiltSurface files;
  files.lower = files.upper = "a.csv";
  files.conditioning = "form: line";
  const OutputRow measured =
      frictal::row_of(frictal::tilt_columns(), frictal::TiltReport{result, config, nullptr, &files});
  std::vector<std::string> keys;
  for (const frictal::OutputField& f : field(measured, "surface")->rows[0]) keys.push_back(f.info.key);
  EXPECT_EQ(keys, (std::vector<std::string>{"lower", "upper", "conditioning"}));
}

}  // namespace
