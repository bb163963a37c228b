#include "meridian/io/dov_jobs.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/track.hpp"
#include "meridian/io/dov_binary.hpp"
#include "meridian/io/dov_writers.hpp"
#include "meridian/io/source_map.hpp"
#include "gravity_model_ref.hpp"

namespace meridian::io {
namespace {

constexpr std::size_t kLineBlock = std::size_t{1} << 16;  // samples read at a time

/// The global model that gives η_G, ξ_G (loaded once) and the note that says so.
struct ModelValues {
  gravity::GravityModelData data;
  std::optional<gravity::GravityField> field;
  gravity::TrackOptions track;
  std::string note;
};

// "egm96 (to degree 360)" as the configuration names it; the note gives the degree loaded.
std::string model_text(const DovGravityModel& m) {
  return m.max_degree > 0 ? fmt::format("{} (to degree {})", m.source, m.max_degree) : m.source;
}

// Exactly one source of η_G, ξ_G (dov_jobs.hpp): the line's model columns or the model the
// configuration names, loaded here (nullptr: the line's columns).
std::unique_ptr<ModelValues> model_values(const DovConfig& config, const DovLineReader& reader) {
  if (config.gravity_model && reader.has_model_values())
    throw InputError(fmt::format("{} has model_eta_arcsec, model_xi_arcsec columns and the "
                                 "configuration names a gravity model: give one source of eta_G, "
                                 "xi_G",
                                 reader.source()),
                     {"", std::nullopt, "gravity_model"});
  if (!config.gravity_model && !reader.has_model_values())
    throw InputError("no model_eta_arcsec, model_xi_arcsec columns and no gravity_model in the "
                     "configuration: the filter needs the global model's eta_G, xi_G",
                     {reader.source(), std::nullopt, {}});
  if (!config.gravity_model) return nullptr;
  const DovGravityModel& ref = *config.gravity_model;
  auto m = std::make_unique<ModelValues>();
  m->data = detail::load_named_model(ref.lookup, ref.max_degree);
  m->field.emplace(std::move(m->data));  // takes the coefficients (the metadata stays)
  m->note = fmt::format(
      "model values eta_G, xi_G from the gravity model {} (degree {}): the astronomic deflection "
      "of its plumb line at each sample, evaluated along the line within {}\"",
      m->data.name.empty() ? ref.source : m->data.name, m->field->max_degree(),
      units::rad_to_arcsec(m->track.tolerance_rad));
  return m;
}

/// A DovLineReader as the workflow's sample source: with a gravity model reads blocks of
/// kLineBlock samples (the track evaluator's chunk) and fills in the model values, without one
/// reads the chunks the workflow asks for straight into its vectors; either way it remembers
/// where each sample is in the file (for a CSV, line = k + offset with the offset stored only
/// where it changes: flat memory for the usual file).
class LineSource final : public dov::SampleSource {
 public:
  LineSource(const DovConfig& config, DovLineReader& reader, const ModelValues* model)
      : config_(config), reader_(reader), model_(model) {}

  std::size_t next(std::vector<dov::Sample>& samples, std::vector<dov::Truth>& truth,
                   std::size_t max) override {
    if (!model_) return next_direct(samples, truth, max);
    if (at_ == block_.samples.size()) {
      if (!reader_.next(block_, kLineBlock)) {
        samples.clear();
        truth.clear();
        return 0;
      }
      begin_block();
      fill_model_values();
    }
    const std::size_t n = std::min(std::max<std::size_t>(max, 1), block_size_ - at_);
    const auto from = static_cast<std::ptrdiff_t>(at_);
    const auto to = static_cast<std::ptrdiff_t>(at_ + n);
    samples.assign(block_.samples.begin() + from, block_.samples.begin() + to);
    truth.clear();
    if (!block_.truth.empty()) truth.assign(block_.truth.begin() + from, block_.truth.begin() + to);
    at_ += n;
    return n;
  }
  bool has_truth() const override { return reader_.has_truth(); }
  std::optional<std::size_t> size_hint() const override {
    if (const auto c = reader_.count()) return static_cast<std::size_t>(*c);
    return std::nullopt;
  }
  dov::Origin origin() const override {
    return {config_.file, config_.line_path,
            config_.gravity_model ? model_text(*config_.gravity_model) : std::string()};
  }
  std::vector<std::string> notes() const override {
    if (model_) return {model_->note};
    return {};
  }
  std::vector<std::string> warnings() const override {
    const std::vector<std::string> ignored = reader_.ignored_columns();
    if (ignored.empty()) return {};
    return {fmt::format(
        "{}: column{} {} not used (a misspelt optional column such as model_eta_arcsec or "
        "truth_eta_arcsec is not read; docs/file-formats.md lists the names)",
        reader_.source(), ignored.size() == 1 ? "" : "s",
        fmt::format("{} {}", fmt::join(ignored, ", "), ignored.size() == 1 ? "is" : "are"))};
  }

  /// Where sample k (of the whole line) is: "line.csv:LINE: column" or "line.bin: sample k:
  /// member".
  ErrorContext context(std::size_t k, const std::string& member) const {
    if (reader_.binary() || offsets_.empty() || k < offsets_.front().first)
      return {reader_.source(), std::nullopt,
              member.empty() ? fmt::format("sample {}", k)
                             : fmt::format("sample {}: {}", k, reader_.column_of(member))};
    auto it = std::upper_bound(offsets_.begin(), offsets_.end(), k,
                               [](std::size_t v, const auto& e) { return v < e.first; });
    --it;
    return {reader_.source(), static_cast<int>(static_cast<long long>(k) + it->second),
            reader_.column_of(member)};
  }

  /// Where point i of the block whose model values are being computed is (the track
  /// evaluator's "track[i]"): its sample's position columns.
  ErrorContext model_point(std::size_t i) const {
    const std::size_t n = block_.samples.size();
    ErrorContext c = context(first_ + std::min(i, n > 0 ? n - 1 : 0), {});
    c.field = reader_.binary() ? c.field + ": lat_rad, lon_rad, height_m"
                               : std::string("lat_deg, lon_deg, height_m");
    return c;
  }

  const std::string& file() const { return reader_.source(); }

 private:
  // Nothing to fill in: read straight into the caller's vectors (swapped with the reader's,
  // both keep their capacity) instead of copying each sample out of a block.
  std::size_t next_direct(std::vector<dov::Sample>& samples, std::vector<dov::Truth>& truth,
                          std::size_t max) {
    if (!reader_.next(block_, std::max<std::size_t>(max, 1))) {
      samples.clear();
      truth.clear();
      return 0;
    }
    begin_block();
    samples.swap(block_.samples);
    truth.swap(block_.truth);
    return block_size_;
  }

  // block_ holds the samples that follow the last block: note where they are in the file.
  void begin_block() {
    first_ += block_size_;
    block_size_ = block_.samples.size();
    at_ = 0;
    for (std::size_t i = 0; i < block_.lines.size(); ++i) {
      const long long offset = static_cast<long long>(block_.lines[i]) -
                               static_cast<long long>(first_ + i);
      if (offsets_.empty() || offsets_.back().second != offset)
        offsets_.emplace_back(first_ + i, offset);
    }
  }

  // η_G, ξ_G of the block from the model: the astronomic deflection along the line. An error
  // names "track[i]", point i of the block (model_point).
  void fill_model_values() {
    const std::size_t n = block_.samples.size();
    points_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const dov::Sample& s = block_.samples[i];
      points_[i] = {s.lat_rad, s.lon_rad, s.height_m};
    }
    const gravity::TrackResult values = gravity::evaluate_track(
        *model_->field, points_, gravity::Quantities::Deflection, model_->track);
    for (std::size_t i = 0; i < n; ++i) {
      dov::Sample& s = block_.samples[i];
      s.model_eta_rad = values.values[i].eta_astro_rad;
      s.model_xi_rad = values.values[i].xi_astro_rad;
    }
  }

  const DovConfig& config_;
  DovLineReader& reader_;
  const ModelValues* model_;
  DovLine block_;
  std::size_t first_ = 0;       // index of block_'s first sample in the line
  std::size_t block_size_ = 0;  // samples in block_
  std::size_t at_ = 0;          // next sample of block_ to hand out
  std::vector<std::pair<std::size_t, long long>> offsets_;  // (first sample, line − k)
  std::vector<gravity::GeodeticPoint> points_;
};

// The line's rows in the error locator: a sample (and the filter's epoch, which is the sample)
// at its place in the file, a model point at its sample, the line as a whole at its file.
void add_line(SourceMap& sources, const LineSource& line) {
  const auto sample = [&line](std::size_t k, const std::string& member) {
    return line.context(k, member);
  };
  sources.add_rows("samples", sample);
  sources.add_rows("epoch", sample);
  sources.add_rows("track",
                   [&line](std::size_t i, const std::string&) { return line.model_point(i); });
  sources.add_place("samples", {line.file(), std::nullopt, {}});
}

// A line given as columns: "samples[k].lat_rad" → "lat_deg[3]", "truth[k].eta_rad" →
// "truth_eta_arcsec[k]" (the arrays the user gave), other fields as they are.
void add_columns(SourceMap& sources) {
  // The field as it was: "samples[k].member", "samples[k]".
  const auto as_given = [](const char* array, std::size_t k, const std::string& member) {
    return fmt::format("{}[{}]{}{}", array, k, member.empty() ? "" : ".", member);
  };
  sources.add_rows("samples", [as_given](std::size_t k, const std::string& member) {
    static const std::set<std::string> kArrays = {
        "time_s",        "lat_rad",      "lon_rad",         "height_m",       "speed_m_s",
        "model_eta_rad", "model_xi_rad", "lgu_body_to_nav", "ins_body_to_nav"};
    return ErrorContext{"", std::nullopt,
                        kArrays.count(member) ? fmt::format("{}[{}]", dov_line_column(member), k)
                                              : as_given("samples", k, member)};
  });
  sources.add_rows("truth", [as_given](std::size_t k, const std::string& member) {
    const char* array = member == "eta_rad"  ? "truth_eta_arcsec"
                        : member == "xi_rad" ? "truth_xi_arcsec"
                                             : nullptr;
    return ErrorContext{"", std::nullopt,
                        array ? fmt::format("{}[{}]", array, k) : as_given("truth", k, member)};
  });
}

// `dov convert` writes a CSV to a name ending in .csv (any case) or to "-".
bool names_csv(const std::string& path) {
  if (path == "-") return true;
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext == ".csv";
}

// The line of `reader` as a line CSV, a block at a time, atomically (or to `standard_output`
// for "-"); returns the sample count.
std::uint64_t convert_to_csv(DovLineReader& reader, const DovConversion& c,
                             std::ostream& standard_output) {
  std::optional<AtomicFileWriter> file;
  if (c.output != "-") file.emplace(c.output);
  const auto put = [&](const std::string& text) {
    if (file)
      file->write(text);
    else
      standard_output << text;
  };
  put(dov_line_csv_header(c.model_values, c.truth, "Converted from " + c.input));
  DovLine chunk;
  std::string text;
  std::uint64_t count = 0;
  while (reader.next(chunk, kLineBlock)) {
    text.clear();
    append_dov_line_csv_rows(text, chunk.samples, chunk.truth, c.model_values, c.truth);
    put(text);
    count += chunk.samples.size();
  }
  if (file) file->commit();
  return count;
}

// The line of `reader` in the binary format, a block at a time: the header's count is written
// last (AtomicFileWriter::write_at), the file renamed into place only when complete.
std::uint64_t convert_to_binary(DovLineReader& reader, const DovConversion& c) {
  AtomicFileWriter out(c.output);
  out.write(dov_binary_header(0, c.model_values, c.truth));
  DovLine chunk;
  std::string bytes;
  std::uint64_t count = 0;
  while (reader.next(chunk, kLineBlock)) {
    bytes.clear();
    for (std::size_t k = 0; k < chunk.samples.size(); ++k)
      append_dov_binary_record(bytes, chunk.samples[k], c.truth ? &chunk.truth[k] : nullptr,
                               c.model_values, c.truth);
    out.write(bytes);
    count += chunk.samples.size();
  }
  out.write_at(0, dov_binary_header(count, c.model_values, c.truth));
  out.commit();
  return count;
}

}  // namespace

dov::Result run_dov_stream(const DovConfig& config, const dov::EpochOutputs& outputs,
                           Progress* progress) {
  SourceMap sources;  // the configuration's keys; the line's rows once it is open
  sources.add_document(config.file, config.lines);
  DovLineReader reader(config.line_path);  // its own errors name the line file
  const std::unique_ptr<ModelValues> model =
      located(sources, [&] { return model_values(config, reader); });
  LineSource line(config, reader, model.get());
  add_line(sources, line);
  return located(sources,
                 [&] { return dov::process_stream(line, config.options, outputs, progress); });
}

dov::Result run_dov(const DovConfig& config, Progress* progress) {
  return run_dov_stream(config, {{}, dov::kAllEpochs}, progress);
}

dov::Result run_dov_columns(const DovLineColumns& line, const std::string& options_file,
                            Progress* progress) {
  dov::Input in = dov_input(line);
  const DovConfig c = read_dov_config(options_file);
  if (c.gravity_model)
    throw InputError(
        "a line given as arrays carries its model values (model_eta_arcsec, model_xi_arcsec): "
        "no gravity_model",
        {c.file, std::nullopt, "gravity_model"});
  in.options = c.options;
  SourceMap sources;
  add_columns(sources);
  return located(sources, [&] { return dov::process(in, progress); });
}

DovConversion convert_dov_line(const std::string& input, const std::string& output,
                               std::ostream& standard_output) {
  DovLineReader reader(input);
  DovConversion c;
  c.input = input;
  c.output = output;
  c.model_values = reader.has_model_values();
  c.truth = reader.has_truth();
  c.ignored_columns = reader.ignored_columns();
  c.samples = names_csv(output) ? convert_to_csv(reader, c, standard_output)
                                : convert_to_binary(reader, c);
  return c;
}

std::string dov_conversion_text(const DovConversion& c) {
  std::string text;
  const std::vector<std::string>& ignored = c.ignored_columns;
  if (!ignored.empty())  // neither output has room for them: say so
    text += fmt::format("warning: {}: column{} {} not converted (not a line column; a "
                        "misspelt optional column is not read)\n",
                        c.input, ignored.size() == 1 ? "" : "s", fmt::join(ignored, ", "));
  text += fmt::format("{}: {} samples{}{}\n", c.output == "-" ? "stdout" : c.output, c.samples,
                      c.model_values ? ", model values" : ", no model values",
                      c.truth ? ", truth" : "");
  return text;
}

}  // namespace meridian::io
