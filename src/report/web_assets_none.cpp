// A build without the report JavaScript (configured with
// MERIDIAN_HTML_REPORTS=AUTO while web/node_modules was missing): no HTML
// reports. render_html() refuses with a message saying how to enable them.
#include "meridian/report/web_assets.hpp"

namespace meridian::report {

const WebAssets& web_assets() {
  static const WebAssets none{{}, {}, {}, {}, false};
  return none;
}

}  // namespace meridian::report
