#pragma once
/// \file json_text.hpp
/// The text of a JSON result, the one way every front end prints one: the CLI's `--json`
/// (indented by 2, a final newline) and the Python package's results (compact, read back
/// by json.loads). Invalid UTF-8 in a string (a file name or label as read) is replaced by
/// U+FFFD instead of failing, so a result is always printed.

#include <string>

#include <nlohmann/json.hpp>

namespace meridian::report {

/// `j` indented by 2 spaces, with a final newline (what `--json` prints and writes).
std::string json_text(const nlohmann::json& j);

/// `j` on one line without spaces (the Python package's transport).
std::string json_compact(const nlohmann::json& j);

}  // namespace meridian::report
