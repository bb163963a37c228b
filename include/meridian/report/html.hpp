#pragma once
/// \file html.hpp
/// A self-contained HTML report: a document model (sections of tables,
/// checks, key-value lists, notes and Vega-Lite plots) and its renderer.
/// The page inlines the Vega, Vega-Lite and vega-embed JavaScript that was
/// embedded into the library at build time, so it opens offline and can be
/// mailed or archived as one file. Print CSS lays it out for A4.
///
/// Workflows add a report by mapping their result structs to a Document
/// (see gyro_html.hpp); they never write HTML themselves.

#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace meridian::report {

struct KeyValue {
  std::string key;
  std::string value;
};

/// A paragraph of plain text (escaped on output).
struct Paragraph {
  std::string text;
};

/// A titled list of key–value pairs (inputs, settings, coordinates).
struct KeyValueList {
  std::string title;
  std::vector<KeyValue> items;
};

/// A table of preformatted cells. Numeric columns are right-aligned.
struct Table {
  std::string title;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> numeric;  ///< per column; empty = all left-aligned
  std::string note;           ///< shown under the table
};

/// One tolerance check.
struct CheckRow {
  std::string name;
  std::string value;
  std::string tolerance;
  bool pass = true;
  std::string source;   ///< where the limit comes from; a column shown when any row has one
};

struct CheckList {
  std::string title;
  std::vector<CheckRow> checks;
  /// Headings of the check, value, limit, result and source columns (the sheet's language).
  std::vector<std::string> columns = {"check", "value", "limit", "result", "source of the limit"};
  /// Words for a passed and a failed check, and the text when no check applies.
  std::vector<std::string> verdicts = {"PASS", "FAIL", "no check applies"};
};

/// A Vega-Lite plot: the specification with its data inline.
struct Plot {
  std::string title;
  nlohmann::json spec;
  std::string caption;
};

/// Notes or warnings (warnings are highlighted).
struct Notes {
  std::string title;
  std::vector<std::string> items;
  bool warning = false;
};

/// A prominent result line, e.g. "Grid azimuth C→D  136°35'23.1" ± 7.2"".
/// With `alarm` (a failed check, a result not to be used) the box is red and
/// the detail is set in large type.
struct Highlight {
  std::string label;
  std::string value;
  std::string detail;
  bool alarm = false;
};

/// A block of signature lines for the people who answer for the result
/// (observer, computed by, checked by, …): role, the name as recorded (may
/// be empty), and blank space for signature and date.
struct Signatures {
  std::vector<KeyValue> people;  ///< key: role, value: name
  /// Headings of the name, signature and date columns (the sheet's language).
  std::vector<std::string> columns = {"name", "signature", "date"};
};

using Block = std::variant<Paragraph, KeyValueList, Table, CheckList, Plot, Notes, Highlight, Signatures>;

struct Section {
  std::string id;      ///< HTML id (letters, digits, '-'); used by tests to find sections
  std::string title;
  std::vector<Block> blocks;
  int level = 2;       ///< heading level 2 or 3
  bool page_break_after = false;  ///< printing starts a new page after this section
};

/// Printed pages carry the title (left) and "page N of M" (right) in the
/// bottom margin.
struct Document {
  std::string title;
  std::string subtitle;
  std::vector<KeyValue> header;   ///< inputs and settings shown under the title
  std::vector<Section> sections;
  std::string footer;             ///< e.g. "meridian 0.1.0"
};

/// True when this build embeds the report JavaScript and can write HTML
/// reports (see web_assets.hpp).
bool html_reports_available();

/// What to do to get HTML reports in a build without them (one sentence).
std::string html_reports_unavailable_message();

/// "meridian <version>": the generator named in every report's footer.
std::string report_generator();

/// Render the whole page. Every Plot becomes a container rendered by
/// vega-embed (SVG renderer). When rendering finishes the page sets
/// `data-render-status="complete"`, `data-plots-expected`,
/// `data-plots-rendered` and `data-render-errors` (a JSON array of console
/// errors and failed plots) on <body>, so a headless browser can check it.
/// Throws Error with html_reports_unavailable_message() in a build without
/// HTML reports.
std::string render_html(const Document& doc);

/// Escape text for HTML element content and attribute values.
std::string html_escape(const std::string& text);

}  // namespace meridian::report
