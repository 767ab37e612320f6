// The Python module `pcsketch` (python/README.md): numpy arrays in, drawings out. Keyword options are the flags of
// `pcsketch draw` (cli/options.h: add_draw_options), parsed by the same CLI11 checks and then validate(): the same
// names, ranges and messages as the command line.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "options.h"
#include "views.h"
#include "pcsketch/pcsketch.h"

namespace py = pybind11;

namespace pcsketch::python {
namespace {

/// A keyword argument as the command line would spell it: `no_denoise=True` → "--no-denoise", `view=(1, 0, 0)` →
/// "--view 1,0,0", `size=(800, 600)` → "--size 800x600", `shadow_k=[0.25, 0.5]` → "--shadow-k 0.25 0.5".
void append_flag(CLI::App& app, const std::string& key, const py::handle& value, std::vector<std::string>& argv) {
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  const CLI::Option* option = app.get_option_no_throw(flag);
  if (option == nullptr) throw py::type_error("unexpected keyword argument '" + key + "' (no flag " + flag + ")");
  if (value.is_none()) return;
  if (option->get_items_expected_max() == 0) {  // a flag: True sets it, False leaves the default
    if (!py::isinstance<py::bool_>(value)) throw py::type_error(flag + ": expected True or False");
    if (value.cast<bool>()) argv.push_back(flag);
    return;
  }
  argv.push_back(flag);
  if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value)) {
    argv.push_back(py::str(value));
    return;
  }
  std::vector<std::string> items;
  for (const py::handle item : value.cast<py::sequence>()) items.push_back(py::str(item));
  if (option->get_items_expected_max() > 1) {
    argv.insert(argv.end(), items.begin(), items.end());
    return;
  }
  const std::string separator = flag == "--size" ? "x" : ",";
  std::string joined;
  for (const std::string& item : items) joined += (joined.empty() ? "" : separator) + item;
  argv.push_back(joined);
}

/// `options` with the keyword arguments applied, checked as `pcsketch draw` checks its flags.
/// @throws ValueError with the CLI's message for a bad value, TypeError for an unknown name.
DrawOptions apply_options(DrawOptions options, const py::kwargs& kwargs) {
  CLI::App app{"pcsketch"};
  cli::ViewRequest views;
  cli::add_camera_options(&app, options.camera, views);
  cli::add_draw_options(&app, options);
  cli::add_memory_option(&app, options.max_memory_gb);
  std::vector<std::string> argv;
  for (const auto& [key, value] : kwargs) append_flag(app, py::str(key), value, argv);
  std::reverse(argv.begin(), argv.end());  // CLI11 takes the arguments last first
  try {
    app.parse(argv);
  } catch (const CLI::ParseError& e) {
    throw py::value_error(one_line(e.what()));
  }
  // The CLI's view rules: conflicting view flags refused, up alone the three-quarter view.
  const std::vector<cli::NamedCamera> cameras = cli::resolve_views(options.camera, views);
  if (cameras.size() != 1) throw py::value_error("views, turntable: one view per draw(); call draw() once per view");
  options.camera = cameras.front().camera;
  validate(options);
  return options;
}

/// An (N, k) array of `T` copied out of `array`. @throws ValueError naming `what` for another shape.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> rows_of(const py::handle& array, py::ssize_t k,
                                                                  const std::string& what) {
  auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(1) != k)
    throw py::value_error(what + ": expected an array of shape (N, " + std::to_string(k) + ")");
  return a;
}

/// The points (and normals) as a binary PLY in memory: the reader's finishing step (non-finite points dropped, far
/// clouds recentred on a double origin, exact duplicates collapsed) then treats an array as `pcsketch draw` treats
/// the same points in a file.
std::string ply_bytes(const py::handle& points_in, const py::handle& normals_in) {
  static_assert(std::endian::native == std::endian::little, "the PLY is written in the machine's byte order");
  const auto points = rows_of<double>(points_in, 3, "points");
  const py::ssize_t n = points.shape(0);
  py::array_t<float, py::array::c_style | py::array::forcecast> normals;
  if (!normals_in.is_none()) {
    normals = rows_of<float>(normals_in, 3, "normals");
    if (normals.shape(0) != n) throw py::value_error("normals: expected as many rows as points");
  }
  const bool has_normals = !normals_in.is_none();
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
                    "\nproperty double x\nproperty double y\nproperty double z\n" +
                    (has_normals ? "property float nx\nproperty float ny\nproperty float nz\n" : "") + "end_header\n";
  const std::size_t header = ply.size(), row = 3 * sizeof(double) + (has_normals ? 3 * sizeof(float) : 0);
  ply.resize(header + static_cast<std::size_t>(n) * row);
  for (py::ssize_t i = 0; i < n; ++i) {
    char* out = ply.data() + header + static_cast<std::size_t>(i) * row;
    std::memcpy(out, points.data(i, 0), 3 * sizeof(double));
    if (has_normals) std::memcpy(out + 3 * sizeof(double), normals.data(i, 0), 3 * sizeof(float));
  }
  return ply;
}

/// World coordinates (origin + point) of `points` as an (N, 3) float64 array.
py::array_t<double> world_array(const std::vector<Vec3f>& points, const Vec3d& origin) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int c = 0; c < 3; ++c) o(static_cast<py::ssize_t>(i), c) = origin[c] + static_cast<double>(points[i][c]);
  return out;
}

/// An (N, k) float32 array of fixed-size Eigen vectors.
template <class Vec>
py::array_t<float> float_rows(const std::vector<Vec>& rows) {
  constexpr py::ssize_t k = Vec::RowsAtCompileTime;
  py::array_t<float> out({static_cast<py::ssize_t>(rows.size()), k});
  if (!rows.empty()) std::memcpy(out.mutable_data(), rows.data(), rows.size() * k * sizeof(float));
  return out;
}

/// The result of prepare(): the analysed cloud and the options it was analysed with (draw()'s defaults).
struct PreparedCloud {
  std::shared_ptr<const Prepared> prepared;
  DrawOptions options;
  Warnings warnings;
};

/// A drawing and how its SVG/PDF/PNG are rendered.
struct PyDrawing {
  Drawing drawing;
  render::RenderOptions render;
  Warnings warnings;
};

/// One stroke, its arrays copied out for numpy.
struct PyStroke {
  std::string kind;
  bool visible, closed;
  float grey;
  py::array_t<float> image_points, widths, half_widths;
  py::array_t<double> points;
};

PreparedCloud prepare_points(const py::handle& points, const py::handle& normals, const py::kwargs& kwargs) {
  const DrawOptions options = apply_options({}, kwargs);
  const std::string bytes = ply_bytes(points, normals);
  py::gil_scoped_release release;
  io::ReadResult read = io::read_point_cloud_from_memory(bytes, "points");
  io::check_scale(read.cloud, "points");
  validate_memory(options, read.cloud.size(), "points");
  auto prepared = std::make_shared<const Prepared>(prepare(std::move(read.cloud), options));
  Warnings warnings = read.warnings;
  warnings.insert(warnings.end(), prepared->warnings.begin(), prepared->warnings.end());
  return {std::move(prepared), options, std::move(warnings)};
}

PyDrawing draw_prepared(const PreparedCloud& cloud, const py::kwargs& kwargs) {
  const DrawOptions options = apply_options(cloud.options, kwargs);
  // The analysis is done: options of prepare() given here would be silently ignored.
  const nlohmann::json before = cloud.options.to_json(), after = options.to_json();
  for (const char* part : {"surface", "features", "boundary", "scene"})
    if (before[part] != after[part])
      throw py::value_error(std::string("options of the analysis (") + part + ") go to prepare(), not draw()");
  py::gil_scoped_release release;
  DrawResult result = draw_view(*cloud.prepared, options.camera, options);
  return {std::move(result.drawing), options.render, std::move(result.warnings)};
}

py::list strokes_of(const PyDrawing& d) {
  py::list out;
  for (const Stroke& s : d.drawing.strokes) {
    py::array_t<float> widths(static_cast<py::ssize_t>(s.widths.size()), s.widths.data());
    py::array_t<float> half(static_cast<py::ssize_t>(s.half_widths.size()), s.half_widths.data());
    out.append(PyStroke{std::string(to_string(s.kind)), s.visible, s.closed, s.grey, float_rows(s.image_points), widths,
                        half, world_array(s.points, d.drawing.origin)});
  }
  return out;
}

py::list regions_of(const PyDrawing& d) {
  py::list out;
  for (const ShadeRegion& r : d.drawing.regions) out.append(py::make_tuple(float_rows(r.polygon), r.grey));
  return out;
}

py::tuple read_file(const std::string& path) {
  io::ReadResult read;
  {
    py::gil_scoped_release release;
    read = io::read_point_cloud(path);
  }
  const PointCloud& c = read.cloud;
  return py::make_tuple(world_array(c.positions, c.origin),
                        c.has_normals() ? py::object(float_rows(c.normals)) : py::object(py::none()));
}

/// The classes prepare() and draw() return.
void bind_results(py::module_& m) {
  py::class_<PreparedCloud>(m, "Prepared")
      .def("draw", &draw_prepared,
           "Draws one view: view=(x, y, z), up=(x, y, z), size=(w, h), azimuth=..., and the other view, "
           "thickness, shadow and output flags of `pcsketch draw` as keyword options.")
      .def_property_readonly(
          "points",
          [](const PreparedCloud& c) { return world_array(c.prepared->cloud.positions, c.prepared->cloud.origin); },
          "(N, 3) float64: the points analysed (outliers and points thinned on scan lines left out, denoised), "
          "world coordinates")
      .def_property_readonly(
          "normals", [](const PreparedCloud& c) { return float_rows(c.prepared->cloud.normals); },
          "(N, 3) float32: their oriented normals")
      .def_property_readonly(
          "spacing", [](const PreparedCloud& c) { return c.prepared->surface.spacing; },
          "mean point spacing h, the unit of the length options")
      .def_readonly("warnings", &PreparedCloud::warnings);

  py::class_<PyStroke>(m, "Stroke")
      .def_readonly("kind", &PyStroke::kind, "contour, ridge, valley, hatch or boundary")
      .def_readonly("visible", &PyStroke::visible)
      .def_readonly("closed", &PyStroke::closed)
      .def_readonly("grey", &PyStroke::grey, "ink level, 0 black ... 1 white")
      .def_readonly("image_points", &PyStroke::image_points, "(S, 2) float32 pixels, origin top-left, v down")
      .def_readonly("points", &PyStroke::points, "(S, 3) float64 world coordinates")
      .def_readonly("widths", &PyStroke::widths, "(S,) float32 width per vertex, pixels")
      .def_readonly("half_widths", &PyStroke::half_widths, "(2 per segment,) float32, pixels");

  py::class_<PyDrawing>(m, "Drawing")
      .def_property_readonly("width", [](const PyDrawing& d) { return d.drawing.width; })
      .def_property_readonly("height", [](const PyDrawing& d) { return d.drawing.height; })
      .def_property_readonly("strokes", &strokes_of, "list of Stroke, in paint order")
      .def_property_readonly("regions", &regions_of, "list of (polygon (K, 2) float32 pixels, grey) shade regions")
      .def_readonly("warnings", &PyDrawing::warnings)
      .def(
          "svg",
          [](const PyDrawing& d) {
            py::gil_scoped_release release;
            return render::svg_string(d.drawing, d.render);
          },
          "The SVG document (Inkscape layers), as `pcsketch draw -o x.svg` writes it.")
      .def(
          "json",
          [](const PyDrawing& d) {
            py::gil_scoped_release release;
            return render::to_json(d.drawing).dump();
          },
          "Every stroke as JSON, as `pcsketch draw --json` writes it.")
      .def(
          "write",
          [](const PyDrawing& d, const std::string& path) {
            py::gil_scoped_release release;
            render::write_drawing(d.drawing, path, d.render);
          },
          py::arg("path"), "Writes .svg, .png, .pdf or .json, chosen by the extension.");
}

}  // namespace
}  // namespace pcsketch::python

PYBIND11_MODULE(pcsketch, m) {
  using namespace pcsketch;
  using namespace pcsketch::python;
  m.doc() = "Pen-and-ink sketch drawings of point clouds. Keyword options are the flags of `pcsketch draw`.";
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  // OptionError is an Error: a bad option value is a ValueError, as for any Python function; the message names the
  // flag as the CLI does.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const OptionError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });

  m.def("read", &read_file, py::arg("path"),
        "Reads a point cloud file (PLY, LAS, XYZ/PTS/TXT/CSV, PCD, OFF, OBJ): (points (N, 3) float64 in world "
        "coordinates, normals (N, 3) float32 or None).");
  m.def("prepare", &prepare_points, py::arg("points"), py::arg("normals") = py::none(),
        "Analyses an (N, 3) array of points (normals optional): neighbourhoods, normals, curvature, ridge and valley "
        "lines. Keyword options: the flags of `pcsketch draw` (neighbours=24, alpha=0.15, no_denoise=True, ...); "
        "view options given here become draw()'s defaults.");
  m.def("keep_freed_memory", &keep_freed_memory,
        "For a script that draws large clouds: glibc's malloc keeps the memory a stage frees for the next one "
        "instead of returning it to the kernel (as the pcsketch command does). Process-wide; call it once at start.");

  bind_results(m);
}
