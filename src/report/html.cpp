#include "meridian/report/html.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/version.hpp"
#include "meridian/report/web_assets.hpp"

namespace meridian::report {
namespace {

constexpr const char* kStyle = R"CSS(
:root { --ink:#1d2733; --muted:#5b6878; --line:#d5dbe3; --pass:#1a7f37; --fail:#c62828; --accent:#0b5cad; }
* { box-sizing: border-box; }
body { font-family: "DejaVu Sans", "Liberation Sans", Arial, "Noto Sans CJK SC", "Noto Sans CJK JP",
       "Noto Sans CJK TC", "WenQuanYi Zen Hei", sans-serif; color: var(--ink);
       margin: 0 auto; max-width: 1000px; padding: 24px; font-size: 14px; line-height: 1.45; }
h1 { font-size: 24px; margin: 0 0 4px; }
h2 { font-size: 19px; margin: 28px 0 10px; padding-bottom: 4px; border-bottom: 2px solid var(--line); }
h3 { font-size: 16px; margin: 20px 0 8px; }
.subtitle { color: var(--muted); margin-bottom: 14px; }
table { border-collapse: collapse; margin: 6px 0 12px; width: 100%; }
th, td { border: 1px solid var(--line); padding: 3px 7px; vertical-align: top; }
th { background: #f1f4f8; text-align: left; font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
caption { caption-side: top; text-align: left; font-weight: 600; padding: 4px 0; }
.kv td:first-child { width: 34%; color: var(--muted); }
.note { color: var(--muted); font-size: 12px; margin-top: -6px; }
.pass { color: var(--pass); font-weight: 700; }
.fail { color: var(--fail); font-weight: 700; }
.highlight { border: 2px solid var(--accent); border-radius: 6px; padding: 10px 14px; margin: 10px 0; }
.highlight .label { color: var(--muted); }
.highlight .value { font-size: 22px; font-weight: 700; }
.highlight.alarm { border: 4px solid var(--fail); background: #fdecea; }
.highlight.alarm .value { color: var(--fail); }
.highlight.alarm .detail { color: var(--fail); font-size: 24px; font-weight: 800; margin-top: 6px; }
table.signatures td { height: 34px; vertical-align: bottom; }
table.signatures td:first-child { width: 22%; color: var(--muted); vertical-align: top; }
table.signatures td.blank { width: 30%; }
.notes li { margin: 2px 0; }
td.source { color: var(--muted); font-size: 11px; }
.warnings { border-left: 4px solid var(--fail); padding-left: 10px; }
figure.plot { margin: 10px 0 16px; }
figure.plot figcaption { color: var(--muted); font-size: 12px; }
.vega { min-height: 40px; }
footer { margin-top: 30px; color: var(--muted); font-size: 11px; border-top: 1px solid var(--line); padding-top: 6px; }
@page { size: A4; margin: 14mm 12mm 16mm;
  @bottom-right { content: "page " counter(page) " of " counter(pages); font-size: 8pt; color: #5b6878;
                  font-family: "DejaVu Sans", sans-serif; } }
section.page-break { break-after: page; }
@media print {
  body { max-width: none; padding: 0; font-size: 10.5pt; }
  h2 { break-after: avoid; }
  h3 { break-after: avoid; }
  table, figure.plot, .highlight, .kv { break-inside: avoid; }
  a { color: inherit; text-decoration: none; }
}
)CSS";

// Collects errors before the libraries load, so a failure anywhere is seen.
constexpr const char* kErrorCapture = R"JS(
window.__meridianErrors = [];
window.addEventListener('error', function (e) { window.__meridianErrors.push(String(e.message || e)); });
window.addEventListener('unhandledrejection', function (e) { window.__meridianErrors.push(String(e.reason)); });
(function () { var orig = console.error; console.error = function () {
  window.__meridianErrors.push(Array.prototype.map.call(arguments, String).join(' '));
  return orig.apply(console, arguments); }; })();
)JS";

constexpr const char* kRender = R"JS(
(function () {
  var nodes = Array.prototype.slice.call(document.querySelectorAll('[data-vega-spec]'));
  var body = document.body;
  body.setAttribute('data-plots-expected', String(nodes.length));
  var jobs = nodes.map(function (div) {
    try {
      var spec = JSON.parse(document.getElementById(div.getAttribute('data-vega-spec')).textContent);
      return vegaEmbed(div, spec, { renderer: 'svg', actions: false });
    } catch (err) { return Promise.reject(err); }
  });
  Promise.allSettled(jobs).then(function (results) {
    var rendered = 0;
    results.forEach(function (r, i) {
      if (r.status === 'rejected') window.__meridianErrors.push('plot ' + nodes[i].id + ': ' + String(r.reason));
      else {
        var svg = nodes[i].querySelector('svg');
        if (svg && svg.querySelectorAll('path, rect, circle, line, text').length > 0) rendered++;
        else window.__meridianErrors.push('plot ' + nodes[i].id + ': nothing drawn');
      }
    });
    body.setAttribute('data-plots-rendered', String(rendered));
    body.setAttribute('data-render-errors', JSON.stringify(window.__meridianErrors));
    body.setAttribute('data-render-status', 'complete');
  });
})();
)JS";

// JSON inside <script>: "</" must not close the element.
std::string script_safe(std::string s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '<' && i + 1 < s.size() && s[i + 1] == '/') {
      out += "<\\/";
      ++i;
    } else {
      out += s[i];
    }
  }
  return out;
}

// A CSS string literal: quotes and backslashes escaped, and '<' as an escape
// so no "</style>" can appear.
std::string css_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += std::string("\\") + c;
    else if (c == '<') out += "\\3c ";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out + "\"";
}

// Inlined library code may contain "</script" inside strings; split it.
std::string inline_script(std::string_view js) {
  std::string out(js);
  std::size_t pos = 0;
  while ((pos = out.find("</script", pos)) != std::string::npos) {
    out.replace(pos, 8, "<\\/script");
    pos += 9;
  }
  return out;
}

struct Renderer {
  std::string out;
  int plot_count = 0;

  void block(const Paragraph& p) { out += "<p>" + html_escape(p.text) + "</p>\n"; }
  void block(const KeyValueList& k) {
    out += "<table class=\"kv\">";
    if (!k.title.empty()) out += "<caption>" + html_escape(k.title) + "</caption>";
    for (const auto& kv : k.items)
      out += "<tr><td>" + html_escape(kv.key) + "</td><td>" + html_escape(kv.value) + "</td></tr>";
    out += "</table>\n";
  }
  void block(const Table& t) {
    out += "<table>";
    if (!t.title.empty()) out += "<caption>" + html_escape(t.title) + "</caption>";
    out += "<thead><tr>";
    for (const auto& c : t.columns) out += "<th>" + html_escape(c) + "</th>";
    out += "</tr></thead><tbody>";
    for (const auto& row : t.rows) {
      out += "<tr>";
      for (std::size_t i = 0; i < row.size(); ++i) {
        const bool num = i < t.numeric.size() && t.numeric[i];
        out += (num ? "<td class=\"num\">" : "<td>") + html_escape(row[i]) + "</td>";
      }
      out += "</tr>";
    }
    out += "</tbody></table>\n";
    if (!t.note.empty()) out += "<p class=\"note\">" + html_escape(t.note) + "</p>\n";
  }
  void block(const CheckList& c) {
    out += "<table class=\"checks\">";
    if (!c.title.empty()) out += "<caption>" + html_escape(c.title) + "</caption>";
    const bool sources = std::any_of(c.checks.begin(), c.checks.end(), [](const CheckRow& k) { return !k.source.empty(); });
    auto heading = [&](std::size_t i, const char* fallback) {
      return html_escape(i < c.columns.size() ? c.columns[i] : std::string(fallback));
    };
    auto verdict = [&](std::size_t i, const char* fallback) {
      return html_escape(i < c.verdicts.size() ? c.verdicts[i] : std::string(fallback));
    };
    out += "<thead><tr><th>" + heading(0, "check") + "</th><th>" + heading(1, "value") + "</th><th>" +
           heading(2, "limit") + "</th><th>" + heading(3, "result") + "</th>" +
           (sources ? "<th>" + heading(4, "source of the limit") + "</th>" : std::string()) + "</tr></thead><tbody>";
    for (const auto& k : c.checks) {
      out += fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"{}\">{}</td>",
                         html_escape(k.name), html_escape(k.value), html_escape(k.tolerance),
                         k.pass ? "pass" : "fail", k.pass ? verdict(0, "PASS") : verdict(1, "FAIL"));
      if (sources) out += "<td class=\"source\">" + html_escape(k.source) + "</td>";
      out += "</tr>";
    }
    if (c.checks.empty()) out += "<tr><td colspan=\"4\">" + verdict(2, "no check applies") + "</td></tr>";
    out += "</tbody></table>\n";
  }
  void block(const Plot& p) {
    const int n = ++plot_count;
    out += fmt::format("<figure class=\"plot\" id=\"plot-{}-figure\">", n);
    if (!p.title.empty()) out += "<h4>" + html_escape(p.title) + "</h4>";
    out += fmt::format("<div class=\"vega\" id=\"plot-{0}\" data-vega-spec=\"plot-{0}-spec\"></div>", n);
    out += fmt::format("<script type=\"application/json\" id=\"plot-{}-spec\">{}</script>", n,
                       script_safe(p.spec.dump()));
    if (!p.caption.empty()) out += "<figcaption>" + html_escape(p.caption) + "</figcaption>";
    out += "</figure>\n";
  }
  void block(const Notes& n) {
    if (n.items.empty()) return;
    out += std::string("<div class=\"notes") + (n.warning ? " warnings" : "") + "\">";
    if (!n.title.empty()) out += "<h4>" + html_escape(n.title) + "</h4>";
    out += "<ul>";
    for (const auto& i : n.items) out += "<li>" + html_escape(i) + "</li>";
    out += "</ul></div>\n";
  }
  void block(const Signatures& s) {
    out += "<table class=\"signatures\"><thead><tr><th></th>";
    for (const auto& c : s.columns) out += "<th>" + html_escape(c) + "</th>";
    out += "</tr></thead><tbody>";
    for (const auto& p : s.people)
      out += "<tr><td>" + html_escape(p.key) + "</td><td>" + html_escape(p.value) +
             "</td><td class=\"blank\"></td><td class=\"blank\"></td></tr>";
    out += "</tbody></table>\n";
  }
  void block(const Highlight& h) {
    out += std::string("<div class=\"highlight") + (h.alarm ? " alarm" : "") + "\"><div class=\"label\">" +
           html_escape(h.label) +
           "</div><div class=\"value\">" + html_escape(h.value) + "</div>";
    if (!h.detail.empty()) out += "<div class=\"detail\">" + html_escape(h.detail) + "</div>";
    out += "</div>\n";
  }
};

}  // namespace

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

bool html_reports_available() { return web_assets().available; }

std::string html_reports_unavailable_message() {
  return "this meridian was built without HTML reports (the report JavaScript in web/node_modules was "
         "missing when it was configured): run `bash scripts/setup.sh`, then configure and build again";
}

std::string report_generator() { return std::string("meridian ") + version(); }

std::string render_html(const Document& doc) {
  const WebAssets& js = web_assets();
  if (!js.available) throw Error(html_reports_unavailable_message());
  Renderer r;
  r.out.reserve(js.vega_js.size() + js.vega_lite_js.size() + js.vega_embed_js.size() + 200000);
  r.out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  r.out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  r.out += "<meta name=\"generator\" content=\"" + html_escape(doc.footer) + "\">\n";
  r.out += "<title>" + html_escape(doc.title) + "</title>\n<style>" + std::string(kStyle) + "</style>\n";
  r.out += "<style>@page { @bottom-left { content: " + css_string(doc.title) +
           "; font-size: 8pt; color: #5b6878; font-family: \"DejaVu Sans\", \"Noto Sans CJK SC\", sans-serif; } }"
           "</style>\n";
  r.out += "<script>" + std::string(kErrorCapture) + "</script>\n</head>\n<body>\n";
  r.out += "<header><h1>" + html_escape(doc.title) + "</h1>";
  if (!doc.subtitle.empty()) r.out += "<div class=\"subtitle\">" + html_escape(doc.subtitle) + "</div>";
  if (!doc.header.empty()) r.block(KeyValueList{"", doc.header});
  r.out += "</header>\n";
  for (const auto& s : doc.sections) {
    const int level = s.level == 3 ? 3 : 2;
    r.out += fmt::format("<section id=\"{}\"{}><h{}>{}</h{}>\n", html_escape(s.id),
                         s.page_break_after ? " class=\"page-break\"" : "", level, html_escape(s.title), level);
    for (const auto& b : s.blocks) std::visit([&](const auto& x) { r.block(x); }, b);
    r.out += "</section>\n";
  }
  r.out += "<footer>" + html_escape(doc.footer) + " · plots: " + html_escape(std::string(js.versions)) +
           " (inlined; the page needs no network)</footer>\n";
  r.out += "<script>" + inline_script(js.vega_js) + "</script>\n";
  r.out += "<script>" + inline_script(js.vega_lite_js) + "</script>\n";
  r.out += "<script>" + inline_script(js.vega_embed_js) + "</script>\n";
  r.out += "<script>" + std::string(kRender) + "</script>\n</body>\n</html>\n";
  return r.out;
}

}  // namespace meridian::report
