#include "meridian/io/dov_files.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/track.hpp"
#include "meridian/io/record_reader.hpp"
#include "gravity_model_ref.hpp"

namespace meridian::io {
namespace {

constexpr double kAs = units::kArcsecond;

std::string element_name(const char* prefix, int i, int j) {
  return fmt::format("{}_{}{}", prefix, i + 1, j + 1);
}

struct LineColumns {
  std::size_t time = 0, lat = 0, lon = 0, height = 0, speed = 0;
  std::optional<std::size_t> eta, xi;  // the model columns (absent: a gravity model gives them)
  std::array<std::size_t, 9> lgu{}, ins{};
  std::array<std::string, 9> lgu_names, ins_names;
  std::optional<std::size_t> truth_eta, truth_xi;
};

LineColumns find_columns(RecordReader& rr) {
  if (rr.header().empty())
    throw InputError("a line file needs a header line naming its columns (time_s, lat_deg, …)",
                     ErrorContext{rr.source(), std::nullopt, {}});
  LineColumns c;
  c.time = rr.require_column("time_s");
  c.lat = rr.require_column("lat_deg");
  c.lon = rr.require_column("lon_deg");
  c.height = rr.require_column("height_m");
  c.speed = rr.require_column("speed_m_s");
  c.eta = rr.find_column("model_eta_arcsec");
  c.xi = rr.find_column("model_xi_arcsec");
  if (c.eta.has_value() != c.xi.has_value())
    throw InputError("give both model_eta_arcsec and model_xi_arcsec, or neither (and a gravity "
                     "model in the configuration)",
                     ErrorContext{rr.source(), rr.header_line(), {}});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      c.lgu_names[3 * i + j] = element_name("lgu", i, j);
      c.ins_names[3 * i + j] = element_name("ins", i, j);
      c.lgu[3 * i + j] = rr.require_column(c.lgu_names[3 * i + j]);
      c.ins[3 * i + j] = rr.require_column(c.ins_names[3 * i + j]);
    }
  c.truth_eta = rr.find_column("truth_eta_arcsec");
  c.truth_xi = rr.find_column("truth_xi_arcsec");
  if (c.truth_eta.has_value() != c.truth_xi.has_value())
    throw InputError("give both truth_eta_arcsec and truth_xi_arcsec, or neither",
                     ErrorContext{rr.source(), rr.header_line(), {}});
  return c;
}

/// The CSV column(s) of a dov::Sample member, as the user wrote them: "model_eta_rad" →
/// "model_eta_arcsec", "ins_body_to_nav" → "ins_11…ins_33" (a matrix check concerns all nine).
std::string sample_column(const std::string& member) {
  if (member == "lat_rad") return "lat_deg";
  if (member == "lon_rad") return "lon_deg";
  if (member == "model_eta_rad") return "model_eta_arcsec";
  if (member == "model_xi_rad") return "model_xi_arcsec";
  if (member == "lgu_body_to_nav") return "lgu_11…lgu_33";
  if (member == "ins_body_to_nav") return "ins_11…ins_33";
  if (member == "attitude_difference") return "lgu_11…lgu_33, ins_11…ins_33";
  return member;  // time_s, height_m, speed_m_s: the same name
}

/// "samples[12].time_s" → 12; the filter's "epoch 12" (= samples[12]) → 12.
std::optional<std::size_t> sample_index(const std::string& field) {
  std::string digits;
  for (const std::string prefix : {"samples[", "epoch "}) {
    if (field.rfind(prefix, 0) != 0) continue;
    for (std::size_t i = prefix.size(); i < field.size() && field[i] >= '0' && field[i] <= '9'; ++i)
      digits += field[i];
  }
  if (digits.empty() || digits.size() > 18) return std::nullopt;
  return static_cast<std::size_t>(std::stoull(digits));
}

}  // namespace

DovLine read_dov_line(std::istream& in, const std::string& source) {
  RecordReader rr(in, source);
  const LineColumns c = find_columns(rr);
  DovLine out;
  out.source = source;
  out.has_model_values = c.eta.has_value();
  RecordChunk chunk;
  while (rr.next(chunk, 16384)) {
    for (std::size_t k = 0; k < chunk.size(); ++k) {
      const Record r = chunk[k];
      dov::Sample s;
      s.time_s = r.number(c.time);
      s.lat_rad = r.angle(c.lat).rad();
      if (!(std::abs(s.lat_rad) <= units::kPi / 2))  // found by fuzz_dov_line
        throw InputError(fmt::format("latitude {}° is beyond ±90°", s.lat_rad / units::kDegree),
                         r.context(c.lat));
      s.lon_rad = r.angle(c.lon).rad();
      s.height_m = r.number(c.height);
      s.speed_m_s = r.number(c.speed);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          s.lgu_body_to_nav(i, j) = r.number(c.lgu[3 * i + j]);
          s.ins_body_to_nav(i, j) = r.number(c.ins[3 * i + j]);
        }
      if (c.eta) {
        s.model_eta_rad = r.number(*c.eta) * kAs;
        s.model_xi_rad = r.number(*c.xi) * kAs;
      } else {
        s.model_eta_rad = s.model_xi_rad = std::numeric_limits<double>::quiet_NaN();
      }
      out.samples.push_back(s);
      out.lines.push_back(r.line());
      if (c.truth_eta) {
        dov::Truth t;
        t.eta_rad = r.number(*c.truth_eta) * kAs;
        t.xi_rad = r.number(*c.truth_xi) * kAs;
        out.truth.push_back(t);
      }
    }
  }
  return out;
}

DovLine read_dov_line_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError(fmt::format("cannot open line file {}", path), ErrorContext{path, {}, {}});
  return read_dov_line(f, path);
}

std::string dov_line_csv(const dov::Input& input, const std::string& settings) {
  std::string out = "# meridian dov line: C_b^n (lgu_ij) and C_b^n' (ins_ij), rows E, N, U\n";
  if (!settings.empty()) {
    std::string one_line = settings;
    for (char& ch : one_line)
      if (ch == '\n' || ch == '\r') ch = ' ';
    out += "# " + one_line + "\n";
  }
  out += "time_s,lat_deg,lon_deg,height_m,speed_m_s";
  for (const char* p : {"lgu", "ins"})
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out += "," + element_name(p, i, j);
  out += ",model_eta_arcsec,model_xi_arcsec";
  const bool truth = !input.truth.empty();
  if (truth) out += ",truth_eta_arcsec,truth_xi_arcsec";
  out += "\n";
  for (std::size_t k = 0; k < input.samples.size(); ++k) {
    const dov::Sample& s = input.samples[k];
    out += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", s.time_s,
                       s.lat_rad / units::kDegree, s.lon_rad / units::kDegree, s.height_m,
                       s.speed_m_s);
    for (const Eigen::Matrix3d* m : {&s.lgu_body_to_nav, &s.ins_body_to_nav})
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out += fmt::format(",{:.17g}", (*m)(i, j));
    out += fmt::format(",{:.17g},{:.17g}", s.model_eta_rad / kAs, s.model_xi_rad / kAs);
    if (truth)
      out += fmt::format(",{:.17g},{:.17g}", input.truth[k].eta_rad / kAs,
                         input.truth[k].xi_rad / kAs);
    out += "\n";
  }
  return out;
}

DovConfig read_dov_config(const std::string& path) {
  const Node root = Node::load_file(path);
  root.allow_only({"line", "zeta", "sigma_model_arcsec", "correlation_length_m",
                   "stationary_speed_m_s", "sigma_obs_arcsec", "sigma_obs_east_arcsec",
                   "sigma_obs_north_arcsec", "initial", "discretisation", "extraction",
                   "max_step_s", "gate_alpha", "statistics_start_s", "gravity_model"});
  DovConfig c;
  c.file = path;
  dov::Options& o = c.options;
  const std::filesystem::path line = root.require("line").string();
  c.line_path = (line.is_absolute() ? line : std::filesystem::path(path).parent_path() / line)
                    .string();
  if (auto n = root.get("zeta")) o.model.zeta = n->positive_number();
  if (auto n = root.get("sigma_model_arcsec")) o.model.sigma_model_rad = n->positive_number() * kAs;
  if (auto n = root.get("correlation_length_m")) o.model.correlation_length_m = n->positive_number();
  if (auto n = root.get("stationary_speed_m_s"))
    o.model.stationary_speed_m_s = n->non_negative_number();
  if (auto n = root.get("sigma_obs_arcsec")) {
    if (root.has("sigma_obs_east_arcsec") || root.has("sigma_obs_north_arcsec"))
      n->fail("give sigma_obs_arcsec or sigma_obs_east_arcsec/sigma_obs_north_arcsec, not both");
    o.sigma_obs_east_rad = o.sigma_obs_north_rad = n->positive_number() * kAs;
  }
  if (auto n = root.get("sigma_obs_east_arcsec")) o.sigma_obs_east_rad = n->positive_number() * kAs;
  if (auto n = root.get("sigma_obs_north_arcsec")) o.sigma_obs_north_rad = n->positive_number() * kAs;
  if (auto init = root.get("initial")) {
    init->allow_only({"phi_e_arcsec", "phi_n_arcsec", "phi_u_arcsec", "eps_u_deg_per_h",
                      "delta_arcsec", "x_arcsec_s"});
    dov::InitialSigmas& s = o.initial;
    if (auto n = init->get("phi_e_arcsec")) s.phi_e_rad = n->positive_number() * kAs;
    if (auto n = init->get("phi_n_arcsec")) s.phi_n_rad = n->positive_number() * kAs;
    if (auto n = init->get("phi_u_arcsec")) s.phi_u_rad = n->positive_number() * kAs;
    if (auto n = init->get("eps_u_deg_per_h"))
      s.eps_u_rad_s = n->positive_number() * units::kDegree / 3600.0;
    if (auto n = init->get("delta_arcsec")) s.delta_rad = n->positive_number() * kAs;
    if (auto n = init->get("x_arcsec_s")) s.x_rad_s = n->positive_number() * kAs;
  }
  if (auto n = root.get("discretisation")) {
    const std::string v = n->string();
    if (v == "exact")
      o.discretisation = dov::DiscretisationMethod::Exact;
    else if (v == "published_first_order")
      o.discretisation = dov::DiscretisationMethod::PublishedFirstOrder;
    else
      n->fail(fmt::format("\"{}\" is not a discretisation (exact, published_first_order)", v));
  }
  if (auto n = root.get("extraction")) {
    const std::string v = n->string();
    if (v == "exact")
      o.extraction = dov::Extraction::Exact;
    else if (v == "skew_symmetric")
      o.extraction = dov::Extraction::SkewSymmetric;
    else
      n->fail(fmt::format("\"{}\" is not an extraction (exact, skew_symmetric)", v));
  }
  if (auto n = root.get("max_step_s")) o.max_step_s = n->positive_number();
  if (auto n = root.get("gate_alpha")) {
    const double a = n->non_negative_number();
    if (!(a == 0.0 || a < 1.0)) n->fail("gate_alpha must be 0 (no gate) or in (0, 1)");
    o.gate_alpha = a;
  }
  if (auto n = root.get("statistics_start_s")) o.statistics_start_s = n->non_negative_number();
  if (auto g = root.get("gravity_model")) {
    // As in gyro campaign files: a file beside the configuration, a path, or a model name.
    g->allow_only({"model", "max_degree"});
    DovGravityModel m;
    m.source = g->require("model").string();
    m.lookup = detail::model_lookup_path(path, m.source);
    if (auto v = g->get("max_degree")) {
      m.max_degree = v->integer();
      if (m.max_degree < 2) v->fail("max_degree must be at least 2");
    }
    c.gravity_model = m;
  }
  c.lines = root.visited_lines();
  return c;
}

namespace {

// η_G, ξ_G of every sample from the model: the astronomic deflection along the line, in chunks
// (the track evaluator keeps its values per point). Returns the note for the result.
std::string fill_model_values(DovLine& line, const DovConfig& config) {
  const DovGravityModel& ref = *config.gravity_model;
  gravity::GravityModelData data;
  try {
    data = detail::load_named_model(ref.lookup, ref.max_degree);
  } catch (Error& e) {
    if (e.context().file.empty()) locate_error(e, config.file, config.lines);
    throw;
  }
  const gravity::GravityField field(data);
  gravity::TrackOptions track;
  constexpr std::size_t kChunk = 1 << 16;
  std::vector<gravity::GeodeticPoint> points;
  for (std::size_t start = 0; start < line.samples.size(); start += kChunk) {
    const std::size_t n = std::min(kChunk, line.samples.size() - start);
    points.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const dov::Sample& s = line.samples[start + i];
      points[i] = {s.lat_rad, s.lon_rad, s.height_m};
    }
    gravity::TrackResult values;
    try {
      values = gravity::evaluate_track(field, points, gravity::Quantities::Deflection, track);
    } catch (Error& e) {
      // "points[i]": the sample's line in the line file
      const std::string& f = e.context().field;
      std::size_t i = 0;
      if (f.rfind("points[", 0) == 0) i = std::strtoull(f.c_str() + 7, nullptr, 10);
      throw InputError(e.message(), {line.source, line.lines[start + std::min(i, n - 1)],
                                     "lat_deg, lon_deg, height_m"});
    }
    for (std::size_t i = 0; i < n; ++i) {
      dov::Sample& s = line.samples[start + i];
      s.model_eta_rad = values.values[i].eta_astro_rad;
      s.model_xi_rad = values.values[i].xi_astro_rad;
    }
  }
  return fmt::format(
      "model values eta_G, xi_G from the gravity model {} (degree {}): the astronomic deflection "
      "of its plumb line at each sample, evaluated along the line within {}\"",
      data.name.empty() ? ref.source : data.name, data.coefficients.max_degree(),
      track.tolerance_rad / kAs);
}

}  // namespace

dov::Result run_dov(const DovConfig& config, Progress* progress) {
  DovLine line = read_dov_line_file(config.line_path);
  std::string model_note;
  if (config.gravity_model && line.has_model_values) {
    InputError e(fmt::format("{} has model_eta_arcsec, model_xi_arcsec columns and the "
                             "configuration names a gravity model: give one source of eta_G, xi_G",
                             line.source),
                 {"", std::nullopt, "gravity_model"});
    locate_error(e, config.file, config.lines);
    throw e;
  }
  if (!config.gravity_model && !line.has_model_values)
    throw InputError("no model_eta_arcsec, model_xi_arcsec columns and no gravity_model in the "
                     "configuration: the filter needs the global model's eta_G, xi_G",
                     {line.source, std::nullopt, {}});
  if (config.gravity_model) model_note = fill_model_values(line, config);
  dov::Input in;
  in.samples = line.samples;
  in.truth = line.truth;
  in.options = config.options;
  try {
    dov::Result r = dov::process(in, progress);
    if (!model_note.empty()) r.notes.push_back(model_note);
    return r;
  } catch (Error& e) {
    if (progress) progress->finish();
    const auto k = sample_index(e.context().field);
    if (k && *k < line.lines.size()) {
      // "samples[k].member" → "line.csv:LINE: column"
      const std::string& f = e.context().field;
      const auto dot = f.find("].");
      ErrorContext c{line.source, line.lines[*k],
                     dot == std::string::npos ? std::string() : sample_column(f.substr(dot + 2))};
      const std::string msg = e.message();
      if (dynamic_cast<ParseError*>(&e)) throw ParseError(msg, c);
      if (dynamic_cast<InputError*>(&e)) throw InputError(msg, c);
      if (dynamic_cast<NumericalError*>(&e)) throw NumericalError(msg, c);
      if (dynamic_cast<IoError*>(&e)) throw IoError(msg, c);
      throw Error(msg, c);
    }
    locate_error(e, config.file, config.lines);
    throw;
  }
}

}  // namespace meridian::io
