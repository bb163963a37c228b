#pragma once
/// \file web_assets.hpp
/// The JavaScript libraries inlined into HTML reports, embedded into the
/// library at build time from the npm packages pinned in web/package-lock.json
/// (installed by scripts/setup.sh). No download ever happens at report time.
/// A build configured without them (MERIDIAN_HTML_REPORTS=AUTO and no
/// web/node_modules) has no HTML reports: `available` is false.

#include <string_view>

namespace meridian::report {

struct WebAssets {
  std::string_view vega_js;        ///< vega/build/vega.min.js
  std::string_view vega_lite_js;   ///< vega-lite/build/vega-lite.min.js
  std::string_view vega_embed_js;  ///< vega-embed/build/vega-embed.min.js
  std::string_view versions;       ///< e.g. "vega 6.4.0, vega-lite 6.5.0, vega-embed 7.3.0"
  bool available = true;           ///< false: this build has no HTML reports
};

const WebAssets& web_assets();

}  // namespace meridian::report
