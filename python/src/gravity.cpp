// meridian._core.gravity: a loaded model (data + GravityField) and its batch
// evaluation on flat float64 arrays. Broadcasting, shapes and dtypes are
// python/meridian/gravity.py's business; here the arrays are 1-D, contiguous
// and of one length, and the work runs with the GIL released.

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <thread>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "bindings.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/gravity_circle.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/points.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/io/gravity_jobs.hpp"
#include "meridian/io/gravity_model_lookup.hpp"
#include "meridian/io/source_map.hpp"

namespace py = pybind11;

namespace meridian::python {
namespace {

namespace mg = meridian::gravity;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A model ready to evaluate: what its file states and the synthesis engine.
struct Model {
  mg::ModelInfo info;
  std::vector<std::string> warnings;
  std::shared_ptr<const mg::GravityField> field;
  unsigned threads = 1;  ///< threads of a batch (FieldOptions::threads resolved)
};

// A model loaded (or made) the CLI's way (io/gravity_jobs.hpp), for Python.
Model make_model(io::LoadedModel loaded, unsigned threads) {
  std::vector<std::string> warnings = mg::model_warnings(loaded.info);
  return {std::move(loaded.info), std::move(warnings), std::make_shared<const mg::GravityField>(std::move(loaded.field)),
          threads ? threads : std::max(1u, std::thread::hardware_concurrency())};
}

// Points per call of the batch evaluation: bounds the FieldValues buffer (88 bytes a
// point) to 5.8 MB whatever the input's length, while each call still has thousands of
// vector blocks to spread over the threads.
constexpr std::size_t kChunk = 65536;

const double* data_of(const Array& a) { return a.data(); }

// The engine's field names ("lat", "lon", "h") as the Python arguments are called.
std::string argument_name(const std::string& engine_field) {
  if (engine_field == "lat") return "lat_deg";
  if (engine_field == "lon") return "lon_deg";
  if (engine_field == "h") return "h_m";
  return engine_field;
}

// ξ, η (arcsec) and, when `geoid`, N (m) at the points i of the flat arrays.
// Field names of errors: "<argument>[i]" for a bad point (InputError, as
// GravityField::check_point), "points[i]" for a value that is not finite
// (NumericalError), i the index in the flat arrays.
py::tuple evaluate(const Model& model, const Array& lat_deg, const Array& lon_deg, const Array& h_m, bool geoid) {
  if (lat_deg.ndim() != 1 || lon_deg.ndim() != 1 || h_m.ndim() != 1)
    throw InputError("lat_deg, lon_deg and h_m must be 1-D here (meridian.gravity broadcasts them)");
  const auto n = static_cast<std::size_t>(lat_deg.shape(0));
  if (static_cast<std::size_t>(lon_deg.shape(0)) != n || static_cast<std::size_t>(h_m.shape(0)) != n)
    throw InputError(fmt::format("lat_deg, lon_deg and h_m must have one length (got {}, {}, {})", n,
                                 lon_deg.shape(0), h_m.shape(0)));
  Array xi(static_cast<py::ssize_t>(n)), eta(static_cast<py::ssize_t>(n));
  std::optional<Array> geoid_m;
  if (geoid) geoid_m.emplace(static_cast<py::ssize_t>(n));
  const double *lat = data_of(lat_deg), *lon = data_of(lon_deg), *h = data_of(h_m);
  double *xo = xi.mutable_data(), *eo = eta.mutable_data(), *no = geoid ? geoid_m->mutable_data() : nullptr;
  const mg::Quantities what = geoid ? mg::Quantities::All : mg::Quantities::Deflection;
  auto point = [&](std::size_t i) -> mg::GeodeticPoint {
    return {units::deg_to_rad(lat[i]), units::deg_to_rad(lon[i]), h[i]};
  };
  {
    py::gil_scoped_release released;
    // Every point first, as GravityField::evaluate does for its batch: bad input fails
    // before any work is done.
    for (std::size_t i = 0; i < n; ++i) {
      try {
        mg::GravityField::check_point(point(i));
      } catch (Error& e) {
        e.relocate({"", std::nullopt, fmt::format("{}[{}]", argument_name(e.context().field), i)});
        throw;
      }
    }
    std::vector<mg::GeodeticPoint> points(std::min(n, kChunk));
    for (std::size_t i0 = 0; i0 < n; i0 += kChunk) {
      const std::size_t m = std::min(kChunk, n - i0);
      for (std::size_t k = 0; k < m; ++k) points[k] = point(i0 + k);
      // The engine numbers the points of this chunk; errors name the caller's.
      io::SourceMap caller_points;
      caller_points.add_rows("points", [i0](std::size_t k, const std::string&) {
        return ErrorContext{"", std::nullopt, fmt::format("points[{}]", i0 + k)};
      });
      const std::vector<mg::FieldValues> v = io::located(
          caller_points, [&] { return model.field->evaluate(std::span<const mg::GeodeticPoint>(points.data(), m), what); });
      for (std::size_t k = 0; k < m; ++k) {
        xo[i0 + k] = units::rad_to_arcsec(v[k].xi_rad);
        eo[i0 + k] = units::rad_to_arcsec(v[k].eta_rad);
        if (no) no[i0 + k] = v[k].geoid_m;
      }
    }
  }
  return py::make_tuple(xi, eta, geoid ? py::object(*geoid_m) : py::object(py::none()));
}

// ξ, η (″) and, when `geoid`, N (m) on the grid lat_deg (rows) × lon_deg (columns) at
// one height: gravity::evaluate_parallels (gravity/gravity_circle.hpp: a GravityCircle per
// row, the Legendre sums once per latitude, then O(max order) per longitude; the same values
// as GravityField::evaluate to rounding), rows spread over the model's threads. Arrays of
// shape (rows, columns).
// Errors: InputError "lat_deg[i]", "lon_deg[j]", "h_m" for bad input (checked before any
// work); NumericalError "points[i, j]" for a value that is not finite.
py::tuple grid(const Model& model, const Array& lat_deg, const Array& lon_deg, double h_m, bool geoid) {
  if (lat_deg.ndim() != 1 || lon_deg.ndim() != 1) throw InputError("lat_deg and lon_deg must be 1-D here");
  const auto rows = static_cast<std::size_t>(lat_deg.shape(0)), cols = static_cast<std::size_t>(lon_deg.shape(0));
  const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)};
  Array xi(shape), eta(shape);
  std::optional<Array> geoid_m;
  if (geoid) geoid_m.emplace(shape);
  const double *lat = lat_deg.data(), *lon = lon_deg.data();
  double *xo = xi.mutable_data(), *eo = eta.mutable_data(), *no = geoid ? geoid_m->mutable_data() : nullptr;
  const mg::Quantities what = geoid ? mg::Quantities::All : mg::Quantities::Deflection;
  {
    py::gil_scoped_release released;
    auto check = [&](const mg::GeodeticPoint& p, const char* name, std::size_t i) {
      try {
        mg::GravityField::check_point(p);
      } catch (Error& e) {
        const std::string arg = argument_name(e.context().field);
        e.relocate({"", std::nullopt, arg == "h_m" ? arg : fmt::format("{}[{}]", name, i)});
        throw;
      }
    };
    for (std::size_t i = 0; i < rows; ++i) check({units::deg_to_rad(lat[i]), 0.0, h_m}, "lat_deg", i);
    for (std::size_t j = 0; j < cols; ++j) check({0.0, units::deg_to_rad(lon[j]), h_m}, "lon_deg", j);
    std::vector<double> lat_rad(rows), lon_rad(cols);
    for (std::size_t i = 0; i < rows; ++i) lat_rad[i] = units::deg_to_rad(lat[i]);
    for (std::size_t j = 0; j < cols; ++j) lon_rad[j] = units::deg_to_rad(lon[j]);
    mg::evaluate_parallels(*model.field, lat_rad, lon_rad, h_m, what, model.threads,
                           [&](std::size_t i, std::span<const mg::FieldValues> v) {
                             for (std::size_t j = 0; j < cols; ++j) {
                               const std::size_t k = i * cols + j;
                               xo[k] = units::rad_to_arcsec(v[j].xi_rad);
                               eo[k] = units::rad_to_arcsec(v[j].eta_rad);
                               if (no) no[k] = v[j].geoid_m;
                             }
                           });
  }
  return py::make_tuple(xi, eta, geoid ? py::object(*geoid_m) : py::object(py::none()));
}

py::dict info_dict(const Model& m) {
  py::dict d;
  d["name"] = m.info.name;
  d["source_file"] = m.info.source_file;
  d["max_degree"] = m.info.max_degree;
  d["file_max_degree"] = m.info.file_max_degree;
  d["gm_m3_s2"] = m.info.gm_m3_s2;
  d["radius_m"] = m.info.radius_m;
  d["tide_system"] = m.info.tide_system;
  d["normalization"] = mg::normalization_text(m.info);
  d["description"] = m.info.description;
  return d;
}

}  // namespace

void bind_gravity(py::module_& m) {
  py::class_<Model>(m, "Model", "A gravity model and its synthesis engine (immutable; thread-safe)")
      .def_property_readonly("info", &info_dict, "What the model's file states (dict)")
      .def_property_readonly("warnings", [](const Model& x) { return x.warnings; },
                             "What a user must know about the metadata (gravity/points.hpp model_warnings)")
      .def_property_readonly("max_degree", [](const Model& x) { return x.info.max_degree; })
      .def("evaluate", &evaluate, py::arg("lat_deg"), py::arg("lon_deg"), py::arg("h_m"), py::arg("geoid"),
           "(xi_arcsec, eta_arcsec, geoid_m or None) at the points of three 1-D float64 arrays of one length")
      .def("grid", &grid, py::arg("lat_deg"), py::arg("lon_deg"), py::arg("h_m"), py::arg("geoid"),
           "(xi_arcsec, eta_arcsec, geoid_m or None) on the grid of 1-D lat_deg x 1-D lon_deg at one height, "
           "a GravityCircle per row");

  m.def(
      "open",
      [](const std::string& name_or_path, int max_degree, unsigned threads) {
        py::gil_scoped_release released;
        return make_model(io::load_gravity_field({name_or_path, max_degree, threads}), threads);
      },
      py::arg("name_or_path"), py::arg("max_degree") = -1, py::arg("threads") = 0,
      "Load a model (.gfc, .egm, or a name on the GeographicLib search path; io/gravity_model_lookup.hpp)");
  m.def(
      "synthetic",
      [](int degree, std::uint64_t seed, unsigned threads) {
        py::gil_scoped_release released;
        mg::SyntheticModelOptions o;
        o.max_degree = degree;
        o.seed = seed;
        return make_model(io::prepare_model(mg::make_synthetic_model(o), threads), threads);
      },
      py::arg("degree"), py::arg("seed"), py::arg("threads") = 0,
      "A synthetic model (gravity/synthetic.hpp make_synthetic_model)");
  m.def("search_path", [] {
    std::vector<std::string> r;
    for (const auto& p : io::gravity_search_path()) r.push_back(p.string());
    return r;
  });
}

}  // namespace meridian::python
