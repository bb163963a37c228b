#include "meridian/io/dov_files.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/dov/euler.hpp"
#include "meridian/io/dov_binary.hpp"
#include "meridian/io/record_reader.hpp"
#include "dov_names.hpp"
#include "input_limits.hpp"
#include "gravity_model_ref.hpp"

namespace meridian::io {
namespace {

constexpr double kAs = units::kArcsecond;

struct LineColumns {
  std::size_t time = 0, lat = 0, lon = 0, height = 0, speed = 0;
  std::optional<std::size_t> eta, xi;  // the model columns (absent: a gravity model gives them)
  std::array<std::size_t, 9> lgu{}, ins{};
  std::array<std::string, 9> lgu_names, ins_names;
  // Euler angles instead of a matrix (dov/euler.hpp): heading, pitch, roll columns
  bool lgu_euler = false, ins_euler = false;
  std::array<std::size_t, 3> lgu_hpr{}, ins_hpr{};
  std::optional<std::size_t> truth_eta, truth_xi;
  std::vector<std::string> ignored;  // header columns not used above
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
  // Each attitude as a matrix (p_11 … p_33) or as Euler angles (p_heading_deg, p_pitch_deg,
  // p_roll_deg), never both.
  for (const char* p : {"lgu", "ins"}) {
    const bool lgu = std::string(p) == "lgu";
    const std::string prefix(p);
    const auto matrix = rr.find_column(prefix + "_11");
    const auto heading = rr.find_column(prefix + "_heading_deg");
    if (matrix && heading)
      throw InputError(fmt::format("give {0}_11…{0}_33 or {0}_heading_deg, {0}_pitch_deg, "
                                   "{0}_roll_deg, not both",
                                   prefix),
                       ErrorContext{rr.source(), rr.header_line(), {}});
    if (heading) {
      (lgu ? c.lgu_euler : c.ins_euler) = true;
      std::array<std::size_t, 3>& hpr = lgu ? c.lgu_hpr : c.ins_hpr;
      hpr[0] = *heading;
      hpr[1] = rr.require_column(prefix + "_pitch_deg");
      hpr[2] = rr.require_column(prefix + "_roll_deg");
      continue;
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        std::string& name = (lgu ? c.lgu_names : c.ins_names)[3 * i + j];
        name = detail::dov_element_column(p, i, j);
        (lgu ? c.lgu : c.ins)[3 * i + j] = rr.require_column(name);
      }
  }
  c.truth_eta = rr.find_column("truth_eta_arcsec");
  c.truth_xi = rr.find_column("truth_xi_arcsec");
  if (c.truth_eta.has_value() != c.truth_xi.has_value())
    throw InputError("give both truth_eta_arcsec and truth_xi_arcsec, or neither",
                     ErrorContext{rr.source(), rr.header_line(), {}});
  std::vector<bool> used(rr.header().size(), false);
  auto use = [&](std::optional<std::size_t> i) {
    if (i && *i < used.size()) used[*i] = true;
  };
  for (auto i : {c.time, c.lat, c.lon, c.height, c.speed}) use(i);
  for (auto i : {c.eta, c.xi, c.truth_eta, c.truth_xi}) use(i);
  for (bool lgu : {true, false}) {
    if (lgu ? c.lgu_euler : c.ins_euler)
      for (auto i : lgu ? c.lgu_hpr : c.ins_hpr) use(i);
    else
      for (auto i : lgu ? c.lgu : c.ins) use(i);
  }
  for (std::size_t i = 0; i < used.size(); ++i)
    if (!used[i]) c.ignored.push_back(rr.header()[i].name);
  return c;
}

/// The CSV column(s) of a dov::Sample member, as the user wrote them: "model_eta_rad" →
/// "model_eta_arcsec", "ins_body_to_nav" → "ins_11…ins_33" (a matrix check concerns all nine)
/// or "ins_heading_deg, ins_pitch_deg, ins_roll_deg" for Euler angles.
std::string sample_column(const std::string& member, bool lgu_euler, bool ins_euler) {
  const auto attitude = [](const char* p, bool euler) {
    return euler ? fmt::format("{0}_heading_deg, {0}_pitch_deg, {0}_roll_deg", p)
                 : fmt::format("{0}_11…{0}_33", p);
  };
  if (member == "lgu_body_to_nav") return attitude("lgu", lgu_euler);
  if (member == "ins_body_to_nav") return attitude("ins", ins_euler);
  if (member == "attitude_difference")
    return attitude("lgu", lgu_euler) + ", " + attitude("ins", ins_euler);
  return dov_line_column(member);
}

/// The binary format's name of a dov::Sample member (the record's fields, dov_binary.hpp).
std::string binary_column(const std::string& member) {
  if (member == "lgu_body_to_nav") return "lgu_11…lgu_33";
  if (member == "ins_body_to_nav") return "ins_11…ins_33";
  if (member == "attitude_difference") return "lgu_11…lgu_33, ins_11…ins_33";
  return member;  // the record's fields carry the member names
}

}  // namespace

std::string dov_line_column(const std::string& member) {
  if (member == "lat_rad") return "lat_deg";
  if (member == "lon_rad") return "lon_deg";
  if (member == "model_eta_rad") return "model_eta_arcsec";
  if (member == "model_xi_rad") return "model_xi_arcsec";
  return member;
}

struct DovLineReader::Impl {
  std::ifstream file;
  std::unique_ptr<RecordReader> csv;
  LineColumns columns;
  RecordChunk chunk;
  std::unique_ptr<DovBinaryReader> bin;
  std::string source;
};

DovLineReader::DovLineReader(std::istream& in, const std::string& source)
    : impl_(std::make_unique<Impl>()) {
  start_csv(in, source);
}

DovLineReader::DovLineReader(const std::string& path) : impl_(std::make_unique<Impl>()) {
  detail::check_readable_path(path);
  impl_->file.open(path, std::ios::binary);
  if (!impl_->file)
    throw IoError(fmt::format("cannot open line file {}", path), ErrorContext{path, {}, {}});
  // By content: the binary format's magic, else the CSV.
  char head[kDovBinaryMagic.size()] = {};
  impl_->file.read(head, sizeof head);
  const auto got = static_cast<std::size_t>(impl_->file.gcount());
  impl_->file.clear();
  impl_->file.seekg(0);
  if (is_dov_binary(head, got)) {
    impl_->source = path;
    impl_->bin = std::make_unique<DovBinaryReader>(impl_->file, path);
  } else {
    start_csv(impl_->file, path);
  }
}

DovLineReader::~DovLineReader() = default;
DovLineReader::DovLineReader(DovLineReader&&) noexcept = default;

void DovLineReader::start_csv(std::istream& in, const std::string& source) {
  impl_->source = source;
  impl_->csv = std::make_unique<RecordReader>(in, source);
  impl_->columns = find_columns(*impl_->csv);
}

const std::string& DovLineReader::source() const { return impl_->source; }
std::string DovLineReader::column_of(const std::string& member) const {
  if (impl_->bin) return binary_column(member);
  return sample_column(member, impl_->columns.lgu_euler, impl_->columns.ins_euler);
}
bool DovLineReader::binary() const { return impl_->bin != nullptr; }
bool DovLineReader::has_model_values() const {
  return impl_->bin ? impl_->bin->has_model() : impl_->columns.eta.has_value();
}
bool DovLineReader::has_truth() const {
  return impl_->bin ? impl_->bin->has_truth() : impl_->columns.truth_eta.has_value();
}
std::vector<std::string> DovLineReader::ignored_columns() const {
  return impl_->bin ? std::vector<std::string>{} : impl_->columns.ignored;
}
std::optional<std::uint64_t> DovLineReader::count() const {
  if (impl_->bin) return impl_->bin->count();
  return std::nullopt;
}

bool DovLineReader::next(DovLine& chunk, std::size_t max) {
  chunk.source = impl_->source;
  chunk.binary = binary();
  chunk.has_model_values = has_model_values();
  chunk.samples.clear();
  chunk.truth.clear();
  chunk.lines.clear();
  max = std::max<std::size_t>(max, 1);
  if (impl_->bin) return impl_->bin->next(chunk.samples, &chunk.truth, max) > 0;
  const LineColumns& c = impl_->columns;
  if (!impl_->csv->next(impl_->chunk, max)) return false;
  const RecordChunk& records = impl_->chunk;
  chunk.samples.reserve(records.size());
  chunk.lines.reserve(records.size());
  for (std::size_t k = 0; k < records.size(); ++k) {
    const Record r = records[k];
    dov::Sample& s = chunk.samples.emplace_back();
    s.time_s = r.number(c.time);
    s.lat_rad = r.angle(c.lat).rad();
    if (!(std::abs(s.lat_rad) <= units::kPi / 2))  // found by fuzz_dov_line
      throw InputError(fmt::format("latitude {}° is beyond ±90°", s.lat_rad / units::kDegree),
                       r.context(c.lat));
    s.lon_rad = r.angle(c.lon).rad();
    s.height_m = r.number(c.height);
    s.speed_m_s = r.number(c.speed);
    for (const bool lgu : {true, false}) {
      Eigen::Matrix3d& m = lgu ? s.lgu_body_to_nav : s.ins_body_to_nav;
      if (lgu ? c.lgu_euler : c.ins_euler) {
        const auto& hpr = lgu ? c.lgu_hpr : c.ins_hpr;
        m = dov::body_to_nav_from_euler(r.angle(hpr[0]).rad(), r.angle(hpr[1]).rad(),
                                        r.angle(hpr[2]).rad());
        continue;
      }
      const auto& col = lgu ? c.lgu : c.ins;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m(i, j) = r.number(col[3 * i + j]);
    }
    if (c.eta) {
      s.model_eta_rad = r.number(*c.eta) * kAs;
      s.model_xi_rad = r.number(*c.xi) * kAs;
    } else {
      s.model_eta_rad = s.model_xi_rad = std::numeric_limits<double>::quiet_NaN();
    }
    chunk.lines.push_back(r.line());
    if (c.truth_eta) {
      dov::Truth& t = chunk.truth.emplace_back();
      t.eta_rad = r.number(*c.truth_eta) * kAs;
      t.xi_rad = r.number(*c.truth_xi) * kAs;
    }
  }
  return true;
}

namespace {

// The whole line of `reader`, chunk by chunk.
DovLine read_all(DovLineReader& reader) {
  DovLine out, chunk;
  out.source = reader.source();
  out.binary = reader.binary();
  out.has_model_values = reader.has_model_values();
  out.ignored_columns = reader.ignored_columns();
  while (reader.next(chunk, 65536)) {
    out.samples.insert(out.samples.end(), chunk.samples.begin(), chunk.samples.end());
    out.truth.insert(out.truth.end(), chunk.truth.begin(), chunk.truth.end());
    out.lines.insert(out.lines.end(), chunk.lines.begin(), chunk.lines.end());
  }
  return out;
}

}  // namespace

DovLine read_dov_line(std::istream& in, const std::string& source) {
  DovLineReader reader(in, source);
  return read_all(reader);
}

DovLine read_dov_line_file(const std::string& path) {
  DovLineReader reader(path);
  return read_all(reader);
}


namespace {

// The model-error and observation keys (arc-seconds in the file, radians in the options).
void read_noise_keys(const Node& root, dov::Options& o) {
  if (auto n = root.get("zeta")) o.model.zeta = n->positive_number();
  if (auto n = root.get("sigma_model_arcsec")) o.model.sigma_model_rad = n->positive_number() * kAs;
  if (auto n = root.get("correlation_length_m")) o.model.correlation_length_m = n->positive_number();
  if (auto n = root.get("stationary_speed_m_s")) {
    if (root.has("speed_sigma_m_s"))
      n->fail("give stationary_speed_m_s or speed_sigma_m_s (the threshold is then "
              "stationary_sigma_factor x speed_sigma_m_s), not both");
    o.model.stationary_speed_m_s = n->non_negative_number();
  }
  if (auto n = root.get("speed_sigma_m_s")) o.speed_sigma_m_s = n->positive_number();
  if (auto n = root.get("stationary_sigma_factor")) {
    if (!root.has("speed_sigma_m_s")) n->fail("stationary_sigma_factor needs speed_sigma_m_s");
    o.stationary_sigma_factor = n->positive_number();
  }
  if (auto n = root.get("stationary_min_duration_s"))
    o.stationary_min_duration_s = n->non_negative_number();
  if (auto n = root.get("sigma_obs_arcsec")) {
    if (root.has("sigma_obs_east_arcsec") || root.has("sigma_obs_north_arcsec"))
      n->fail("give sigma_obs_arcsec or sigma_obs_east_arcsec/sigma_obs_north_arcsec, not both");
    o.sigma_obs_east_rad = o.sigma_obs_north_rad = n->positive_number() * kAs;
  }
  if (auto n = root.get("sigma_obs_east_arcsec")) o.sigma_obs_east_rad = n->positive_number() * kAs;
  if (auto n = root.get("sigma_obs_north_arcsec")) o.sigma_obs_north_rad = n->positive_number() * kAs;
}

// `initial:` the σ of the initial state.
void read_initial(const Node& init, dov::InitialSigmas& s) {
  init.allow_only({"phi_e_arcsec", "phi_n_arcsec", "phi_u_arcsec", "eps_u_deg_per_h",
                   "delta_arcsec", "x_arcsec_s"});
  if (auto n = init.get("phi_e_arcsec")) s.phi_e_rad = n->positive_number() * kAs;
  if (auto n = init.get("phi_n_arcsec")) s.phi_n_rad = n->positive_number() * kAs;
  if (auto n = init.get("phi_u_arcsec")) s.phi_u_rad = n->positive_number() * kAs;
  if (auto n = init.get("eps_u_deg_per_h"))
    s.eps_u_rad_s = n->positive_number() * units::kDegree / 3600.0;
  if (auto n = init.get("delta_arcsec")) s.delta_rad = n->positive_number() * kAs;
  if (auto n = init.get("x_arcsec_s")) s.x_rad_s = n->positive_number() * kAs;
}

// The method keys: discretisation, extraction, steps, transport rate, gate, statistics.
void read_method_keys(const Node& root, dov::Options& o) {
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
  if (auto n = root.get("transport_rate")) o.transport_rate = n->boolean();
  if (auto n = root.get("transport_rate_baseline_s")) {
    if (!o.transport_rate) n->fail("transport_rate_baseline_s needs transport_rate: true");
    o.transport_rate_baseline_s = n->positive_number();
  }
  if (auto n = root.get("gate_alpha")) {
    const double a = n->non_negative_number();
    if (!(a == 0.0 || a < 1.0)) n->fail("gate_alpha must be 0 (no gate) or in (0, 1)");
    o.gate_alpha = a;
  }
  if (auto n = root.get("statistics_start_s")) o.statistics_start_s = n->non_negative_number();
  if (auto n = root.get("whiteness_alpha")) {
    const double a = n->positive_number();
    if (!(a < 1.0)) n->fail("whiteness_alpha must be in (0, 1)");
    o.whiteness_alpha = a;
  }
}

// `gravity_model:` as in gyro campaign files: a file beside the configuration at `path`, a
// path, or a model name.
DovGravityModel read_gravity_model(const Node& g, const std::string& path) {
  g.allow_only({"model", "max_degree"});
  DovGravityModel m;
  m.source = g.require("model").string();
  m.lookup = detail::model_lookup_path(path, m.source);
  if (auto v = g.get("max_degree")) {
    m.max_degree = v->integer();
    if (m.max_degree < 2) v->fail("max_degree must be at least 2");
  }
  return m;
}

}  // namespace

DovConfig read_dov_config(const std::string& path) {
  const Node root = Node::load_file(path);
  root.allow_only({"line", "zeta", "sigma_model_arcsec", "correlation_length_m",
                   "stationary_speed_m_s", "sigma_obs_arcsec", "sigma_obs_east_arcsec",
                   "sigma_obs_north_arcsec", "initial", "discretisation", "extraction",
                   "max_step_s", "gate_alpha", "statistics_start_s", "gravity_model",
                   "transport_rate", "transport_rate_baseline_s", "speed_sigma_m_s",
                   "stationary_sigma_factor", "stationary_min_duration_s", "whiteness_alpha"});
  DovConfig c;
  c.file = path;
  const std::filesystem::path line = root.require("line").string();
  c.line_path = (line.is_absolute() ? line : std::filesystem::path(path).parent_path() / line)
                    .string();
  read_noise_keys(root, c.options);
  if (auto init = root.get("initial")) read_initial(*init, c.options.initial);
  read_method_keys(root, c.options);
  if (auto g = root.get("gravity_model")) c.gravity_model = read_gravity_model(*g, path);
  c.lines = root.visited_lines();
  return c;
}

}  // namespace meridian::io
