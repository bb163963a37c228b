#pragma once
/// \file gyro_files.hpp
/// Readers for gyro-theodolite field-book files (YAML, or JSON as is).
/// The formats are documented in docs/file-formats.md. Readers turn a file
/// into plain structs; errors name the file, line and field.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "meridian/io/document.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/instrument_spec.hpp"
#include "meridian/gyro/reduce.hpp"

namespace meridian::io {

/// Contents of a `meridian gyro reduce` (or `transit-factor`) file.
struct GyroReduceFile {
  std::string file;
  gyro::ReduceInput input;
  FieldLines lines;       ///< where each field was read (io::SourceMap)
};

/// Read a reduce file. Throws ParseError/InputError with file, line, field.
GyroReduceFile read_gyro_reduce_file(const std::filesystem::path& path);

/// Contents of a `meridian gyro campaign` file.
struct CampaignFile {
  std::string file;
  gyro::CampaignInput campaign;  ///< its gravity_model, if any, is named, not loaded
  FieldLines lines;              ///< where each field was read (io::SourceMap)
};

CampaignFile read_campaign_file(const std::filesystem::path& path);
/// The same from a document already parsed (Node::load_text, Node::load_tree_json: the browser
/// field book's); its file name is root.file() (a relative gravity_model path is taken from there).
CampaignFile read_campaign_document(const Node& root);

}  // namespace meridian::io
