// The page shell, escaping and PNG data: URIs of tools/html_page.h.
#include "tools/html_page.h"

#include <cmath>
#include <cstdio>

#include "gltf/png.h"

namespace qf::render::html {
namespace {

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = std::uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? std::uint32_t(bytes[i + 1]) << 8 : 0) |
                            (i + 2 < bytes.size() ? std::uint32_t(bytes[i + 2]) : 0);
    out += kDigits[n >> 18 & 63];
    out += kDigits[n >> 12 & 63];
    out += i + 1 < bytes.size() ? kDigits[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

// Shared by every page: light, compact, images on a checker-free grey as they were drawn.
constexpr const char* kStyle = R"(
body{font:14px/1.4 system-ui,sans-serif;margin:16px 24px;color:#1d1d1f;background:#fafafa}
h1{font-size:20px;margin:0 0 4px}h2{font-size:16px;margin:24px 0 8px;border-bottom:1px solid #ddd;padding-bottom:2px}
.meta{color:#555}.note{color:#7a4b00;background:#fff4dc;border:1px solid #f0d9a8;padding:6px 10px;border-radius:4px}
table{border-collapse:collapse;font-variant-numeric:tabular-nums}th,td{padding:3px 8px;border-bottom:1px solid #e4e4e4;text-align:right;vertical-align:middle}
th{background:#f0f0f0;position:sticky;top:0}th:first-child,td:first-child,td.text,th.text{text-align:left}td{white-space:nowrap}
table.sortable th{cursor:pointer;user-select:none}table.sortable th:hover{background:#e2e2e2}
th.asc::after{content:" \25B2"}th.desc::after{content:" \25BC"}
img{display:block}img.px{image-rendering:pixelated}
figure{margin:0;display:inline-flex;flex-direction:column;align-items:center;gap:2px}
figcaption{font-size:12px;color:#555;white-space:nowrap}
.row{display:flex;flex-wrap:wrap;align-items:flex-end;gap:12px;margin:6px 0 14px}
.fail{color:#b00020}.ok{color:#1b7a2e}.warn li{color:#7a4b00}
code{font-size:12px;background:#eee;padding:0 3px;border-radius:3px}
)";

// Click a header cell of a sortable table: its rows sorted by that column (numbers by value, from
// data-sort when a cell has it), again to reverse.
constexpr const char* kScript = R"(
for (const table of document.querySelectorAll('table.sortable')) {
  const heads = table.tHead.rows[0].cells;
  for (let c = 0; c < heads.length; ++c) heads[c].addEventListener('click', () => {
    const up = !heads[c].classList.contains('asc');
    for (const h of heads) h.classList.remove('asc', 'desc');
    heads[c].classList.add(up ? 'asc' : 'desc');
    const key = (r) => { const d = r.cells[c]; const v = d.dataset.sort ?? d.textContent; const n = parseFloat(v); return isNaN(n) ? v : n; };
    const rows = [...table.tBodies[0].rows];
    rows.sort((a, b) => { const x = key(a), y = key(b); const s = typeof x === 'number' && typeof y === 'number' ? x - y : String(x).localeCompare(String(y)); return up ? s : -s; });
    for (const r of rows) table.tBodies[0].appendChild(r);
  });
}
)";

}  // namespace

std::string escape(std::string_view text) {
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

std::string attr(const nlohmann::json& value) { return escape(value.is_string() ? value.get<std::string>() : value.dump()); }

std::string png_data_uri(const Image& image) {
  std::vector<std::uint8_t> rgb(std::size_t(image.width) * std::size_t(image.height) * 3);
  for (std::size_t p = 0, n = rgb.size() / 3; p < n; ++p)
    for (int c = 0; c < 3; ++c) rgb[3 * p + c] = image.rgba[4 * p + c];
  return "data:image/png;base64," + base64(encode_png(rgb.data(), image.width, image.height, 3));
}

std::string img(const Image& image, const std::string& alt, const std::string& css_class) {
  return "<img src=\"" + png_data_uri(image) + "\" width=\"" + std::to_string(image.width) + "\" height=\"" + std::to_string(image.height) +
         "\" alt=\"" + escape(alt) + "\"" + (css_class.empty() ? "" : " class=\"" + css_class + "\"") + ">";
}

std::string page(const std::string& title, const std::string& body, const std::string& style, const std::string& script) {
  return "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + escape(title) + "</title>\n<style>" + kStyle + style +
         "</style></head>\n<body>\n" + body + "\n<script>" + kScript + script + "</script>\n</body></html>\n";
}

std::string fixed(const nlohmann::json& value, int digits) {
  if (!value.is_number()) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, value.get<double>());
  return buf;
}

std::string bytes_text(double bytes) {
  char buf[64];
  if (bytes < 1024) std::snprintf(buf, sizeof buf, "%.0f B", bytes);
  else if (bytes < 1024 * 1024) std::snprintf(buf, sizeof buf, "%.1f KB", bytes / 1024);
  else std::snprintf(buf, sizeof buf, "%.2f MB", bytes / (1024 * 1024));
  return buf;
}

}  // namespace qf::render::html
