// frictal — the tilt test's frames as VTK XML PolyData (.vtp) with a ParaView time index (.pvd)
// (tilt.hpp, docs/dem.md sec. 4).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "frictal/tilt.hpp"

namespace frictal {

void tilt_frame_polygon(const TiltResult& r, const TiltFrame& f, int b, std::vector<double>& x,
                        std::vector<double>& y) {
  const std::vector<double>& lx = b == 0 ? r.lower_polygon_x : r.upper_polygon_x;
  const std::vector<double>& ly = b == 0 ? r.lower_polygon_y : r.upper_polygon_y;
  const double c = std::cos(f.angle[b]), s = std::sin(f.angle[b]);
  x.resize(lx.size());
  y.resize(lx.size());
  for (std::size_t i = 0; i < lx.size(); ++i) {
    x[i] = f.position[b].x + (c * lx[i] - s * ly[i]);
    y[i] = f.position[b].y + (s * lx[i] + c * ly[i]);
  }
}

void rounded_outline(const std::vector<double>& x, const std::vector<double>& y, double radius, double max_arc_step,
                     std::vector<double>& ox, std::vector<double>& oy) {
  ox.clear();
  oy.clear();
  const std::size_t n = x.size();
  if (n < 3) return;
  // Orientation (shoelace): outward normals point right of the edges of a counter-clockwise polygon.
  double area2 = 0;
  for (std::size_t i = 0; i < n; ++i) area2 += x[i] * y[(i + 1) % n] - x[(i + 1) % n] * y[i];
  const double orient = area2 >= 0 ? 1.0 : -1.0;
  auto normal = [&](std::size_t i, double& nx, double& ny) {  // of edge i -> i+1
    const double dx = x[(i + 1) % n] - x[i], dy = y[(i + 1) % n] - y[i], l = std::hypot(dx, dy);
    nx = l > 0 ? orient * dy / l : 0.0;
    ny = l > 0 ? -orient * dx / l : 0.0;
  };
  for (std::size_t i = 0; i < n; ++i) {
    double ax, ay, bx, by;  // normals of the edge ending at i and of the edge starting at i
    normal((i + n - 1) % n, ax, ay);
    normal(i, bx, by);
    const double a0 = std::atan2(ay, ax);
    double turn = std::atan2(ax * by - ay * bx, ax * bx + ay * by) * orient;  // > 0: convex corner
    if (turn > 0) {
      const int steps = std::max(1, static_cast<int>(std::ceil(turn / max_arc_step)));
      for (int k = 0; k <= steps; ++k) {
        const double t = a0 + orient * turn * k / steps;
        ox.push_back(x[i] + radius * std::cos(t));
        oy.push_back(y[i] + radius * std::sin(t));
      }
    } else {  // concave (or straight): the two offset ends, joined directly
      ox.push_back(x[i] + radius * ax);
      oy.push_back(y[i] + radius * ay);
      if (turn < 0) {
        ox.push_back(x[i] + radius * bx);
        oy.push_back(y[i] + radius * by);
      }
    }
  }
}

namespace {

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

void field_data(std::FILE* f, const TiltFrame& fr) {
  const double deg = 180 / std::numbers::pi;
  fmt::print(f, "<FieldData>\n");
  auto one = [&](const char* name, double v) {
    fmt::print(f, "<DataArray type=\"Float64\" Name=\"{}\" NumberOfTuples=\"1\" format=\"ascii\">{:.17g}</DataArray>\n",
               name, v);
  };
  one("time_s", fr.time);
  one("tilt_deg", fr.tilt * deg);
  one("normal_force_N", fr.normal_force);
  one("tangential_force_N", fr.tangential_force);
  one("force_angle_deg", std::atan2(fr.tangential_force, fr.normal_force) * deg);
  fmt::print(f, "</FieldData>\n");
}

Status write_bodies(const std::string& path, const TiltResult& r, const TiltFrame& fr, double radius) {
  File f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open for writing", path));
  std::vector<double> px, py;  // all points; cells: core polygons then outlines
  std::vector<std::size_t> poly_end, line_end;
  std::vector<double> x, y, ox, oy;
  for (int b = 0; b < 2; ++b) {
    tilt_frame_polygon(r, fr, b, x, y);
    px.insert(px.end(), x.begin(), x.end());
    py.insert(py.end(), y.begin(), y.end());
    poly_end.push_back(px.size());
  }
  for (int b = 0; b < 2; ++b) {
    tilt_frame_polygon(r, fr, b, x, y);
    rounded_outline(x, y, radius, 5 * std::numbers::pi / 180, ox, oy);
    ox.push_back(ox.front());  // closed line
    oy.push_back(oy.front());
    px.insert(px.end(), ox.begin(), ox.end());
    py.insert(py.end(), oy.begin(), oy.end());
    line_end.push_back(px.size());
  }
  std::FILE* o = f.get();
  fmt::print(o, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
  fmt::print(o, "<PolyData>\n");
  field_data(o, fr);
  fmt::print(o,
             "<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"2\" NumberOfStrips=\"0\" "
             "NumberOfPolys=\"2\">\n",
             px.size());
  fmt::print(o, "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (std::size_t i = 0; i < px.size(); ++i) fmt::print(o, "{:.17g} {:.17g} 0\n", px[i], py[i]);
  fmt::print(o, "</DataArray>\n</Points>\n");
  auto cells = [&](const char* tag, std::size_t begin, const std::vector<std::size_t>& ends) {
    fmt::print(o, "<{}>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n", tag);
    for (std::size_t i = begin; i < ends.back(); ++i) fmt::print(o, "{} ", i);
    fmt::print(o, "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for (std::size_t e : ends) fmt::print(o, "{} ", e - begin);
    fmt::print(o, "\n</DataArray>\n</{}>\n", tag);
  };
  cells("Lines", poly_end.back(), line_end);
  cells("Polys", 0, poly_end);
  // Cell order in VTK PolyData: verts, lines, strips, polys.
  fmt::print(o,
             "<CellData Scalars=\"body\">\n<DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">0 1 0 1"
             "</DataArray>\n<DataArray type=\"Int32\" Name=\"kind\" format=\"ascii\">1 1 0 0</DataArray>\n"
             "</CellData>\n");
  fmt::print(o, "</Piece>\n</PolyData>\n</VTKFile>\n");
  if (std::ferror(o)) return make_error(ErrorCode::Io, fmt::format("{}: write failed", path));
  return Ok{};
}

Status write_contacts(const std::string& path, const TiltFrame& fr) {
  File f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open for writing", path));
  std::FILE* o = f.get();
  const std::size_t n = fr.contacts.size();
  fmt::print(o, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
  fmt::print(o, "<PolyData>\n");
  field_data(o, fr);
  fmt::print(o,
             "<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
             "NumberOfPolys=\"0\">\n",
             n, n);
  fmt::print(o, "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (const auto& c : fr.contacts) fmt::print(o, "{:.17g} {:.17g} 0\n", c.point.x, c.point.y);
  fmt::print(o,
             "</DataArray>\n</Points>\n<Verts>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (std::size_t i = 0; i < n; ++i) fmt::print(o, "{} ", i);
  fmt::print(o, "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (std::size_t i = 0; i < n; ++i) fmt::print(o, "{} ", i + 1);
  fmt::print(o, "\n</DataArray>\n</Verts>\n<PointData Vectors=\"normal_force\">\n");
  auto vec = [&](const char* name, auto get) {
    fmt::print(o, "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" format=\"ascii\">\n", name);
    for (const auto& c : fr.contacts) {
      const dem::Vec2 v = get(c);
      fmt::print(o, "{:.17g} {:.17g} 0\n", v.x, v.y);
    }
    fmt::print(o, "</DataArray>\n");
  };
  vec("normal", [](const dem::ContactForce& c) { return c.normal; });
  vec("normal_force", [](const dem::ContactForce& c) {
    return dem::Vec2{c.normal_force * c.normal.x, c.normal_force * c.normal.y};
  });
  vec("tangential_force", [](const dem::ContactForce& c) {  // t = normal turned by +90 deg
    return dem::Vec2{-c.tangential_force * c.normal.y, c.tangential_force * c.normal.x};
  });
  fmt::print(o, "<DataArray type=\"Float64\" Name=\"overlap\" format=\"ascii\">\n");
  for (const auto& c : fr.contacts) fmt::print(o, "{:.17g} ", c.overlap);
  fmt::print(o, "\n</DataArray>\n<DataArray type=\"Int32\" Name=\"vertex_body\" format=\"ascii\">\n");
  for (const auto& c : fr.contacts) fmt::print(o, "{} ", c.vertex_body);
  fmt::print(o, "\n</DataArray>\n</PointData>\n</Piece>\n</PolyData>\n</VTKFile>\n");
  if (std::ferror(o)) return make_error(ErrorCode::Io, fmt::format("{}: write failed", path));
  return Ok{};
}

}  // namespace

Result<std::vector<std::string>> write_tilt_vtk(const std::string& dir, const TiltResult& r, double radius) {
  if (r.frames.empty()) return make_error("write_tilt_vtk: the result has no frames (frame_interval > 0)");
  if (!(radius >= 0) || !std::isfinite(radius))
    return make_error(fmt::format("write_tilt_vtk: radius = {} m: expected >= 0", radius));
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return make_error(ErrorCode::Io, fmt::format("{}: cannot create the directory: {}", dir, ec.message()));
  std::vector<std::string> written;
  const std::string pvd = (fs::path(dir) / "tilt.pvd").string();
  File f(std::fopen(pvd.c_str(), "w"), &std::fclose);
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open for writing", pvd));
  written.push_back(pvd);
  fmt::print(f.get(),
             "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
             "byte_order=\"LittleEndian\">\n<Collection>\n");
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    const TiltFrame& fr = r.frames[i];
    const std::string b = fmt::format("bodies_{:05d}.vtp", i), c = fmt::format("contacts_{:05d}.vtp", i);
    if (Status s = write_bodies((fs::path(dir) / b).string(), r, fr, radius); !s.ok()) return s.error();
    if (Status s = write_contacts((fs::path(dir) / c).string(), fr); !s.ok()) return s.error();
    written.push_back((fs::path(dir) / b).string());
    written.push_back((fs::path(dir) / c).string());
    fmt::print(f.get(), "<DataSet timestep=\"{:.9g}\" part=\"0\" file=\"{}\"/>\n", fr.time, b);
    fmt::print(f.get(), "<DataSet timestep=\"{:.9g}\" part=\"1\" file=\"{}\"/>\n", fr.time, c);
  }
  fmt::print(f.get(), "</Collection>\n</VTKFile>\n");
  if (std::ferror(f.get())) return make_error(ErrorCode::Io, fmt::format("{}: write failed", pvd));
  return written;
}

}  // namespace frictal
