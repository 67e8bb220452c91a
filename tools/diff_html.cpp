// The diff page (tools/diff_html.h).
#include "tools/diff_html.h"

#include <sstream>

#include "core/file_io.h"
#include "tools/html_page.h"

namespace qf::render {
namespace {

using OJson = nlohmann::ordered_json;

std::string pair_text(const OJson& v, int digits = -1) {
  const auto one = [&](const OJson& x) { return x.is_null() ? std::string("-") : digits >= 0 ? html::fixed(x, digits) : x.dump(); };
  return v.is_array() && v.size() == 2 ? one(v[0]) + " &rarr; " + one(v[1]) : one(v);
}

// A changed manifest: its recommended chain before and after, the measured figures that changed,
// the impostor levels' bytes; then the keys that changed.
std::string manifest_block(const OJson& f) {
  std::ostringstream h;
  if (f.contains("recommended_chain")) {
    const OJson& c = f["recommended_chain"];
    h << "<h4>Recommended chain</h4><table class=\"chain-change\"><tr><th>old</th><td class=\"text\" data-chain=\"old\">"
      << (c["old"].is_null() ? "none" : html::escape(c["old"].get<std::string>())) << "</td></tr><tr><th>new</th><td class=\"text\" data-chain=\"new\">"
      << (c["new"].is_null() ? "none" : html::escape(c["new"].get<std::string>())) << "</td></tr></table>\n";
  }
  if (f.contains("measured_errors")) {
    const OJson& me = f["measured_errors"];
    h << "<h4>Measured errors that changed (worst PSNR drop <span class=\"worst-drop\" data-value=\"" << html::attr(me["worst_psnr_drop"]) << "\">"
      << me["worst_psnr_drop"].dump() << "</span> dB)</h4><table class=\"sortable errors\"><thead><tr><th>what</th><th>PSNR dB</th><th>IoU</th><th class=\"text\">file</th>"
      << "</tr></thead><tbody>";
    for (const OJson& e : me["changes"])
      h << "<tr data-what=\"" << html::attr(e["what"]) << "\" data-psnr-old=\"" << html::attr(e["psnr"][0]) << "\" data-psnr-new=\""
        << html::attr(e["psnr"][1]) << "\"><td>" << html::escape(e["what"].get<std::string>()) << "</td><td>" << pair_text(e["psnr"], 2) << "</td><td>"
        << pair_text(e["iou"], 3) << "</td><td class=\"text\">" << (e.contains("file") ? html::escape(e["file"][0].get<std::string>() + " -> " + e["file"][1].get<std::string>()) : "")
        << "</td></tr>";
    h << "</tbody></table>\n";
  }
  if (f.contains("impostor_levels")) {
    const OJson& il = f["impostor_levels"];
    h << "<h4>Impostor levels</h4><table><thead><tr><th>file</th><th>quads</th><th>texels</th><th>bytes</th></tr></thead><tbody>";
    for (const OJson& l : il["levels"])
      h << "<tr><td>" << html::escape(l["file"].get<std::string>()) << "</td><td>" << pair_text(l["primitives"]) << "</td><td>" << pair_text(l["texels"])
        << "</td><td>" << pair_text(l["bytes"]) << "</td></tr>";
    h << "<tr><td>all levels</td><td></td><td></td><td>" << pair_text(il["bytes_total"]) << "</td></tr></tbody></table>\n";
  }
  if (f.contains("changed_keys")) {
    h << "<p class=\"meta\">changed keys:";
    for (const OJson& k : f["changed_keys"]) h << " <code>" << html::escape(k.get<std::string>()) << "</code>";
    h << "</p>\n";
  }
  return h.str();
}

// A changed .glb: structure and texels in a line each, then per view old | new | difference.
std::string glb_block(const OJson& f, const DiffPictures* p) {
  std::ostringstream h;
  if (f.contains("note")) h << "<p class=\"note\">" << html::escape(f["note"].get<std::string>()) << "</p>";
  if (f.contains("structure")) {
    const OJson& st = f["structure"];
    if (st.contains("quads"))
      h << "<p class=\"meta\">level " << pair_text(st["level"]) << ", quads " << pair_text(st["quads"]) << " (+" << st["quads_added"].dump() << " -"
        << st["quads_removed"].dump() << " by domain), normal angle max " << st["normal_angle_max_degrees"].dump() << "&deg;, mean error "
        << pair_text(st["mean_error"]) << "</p>";
    else
      h << "<p class=\"meta\">" << html::escape(st["old"].dump()) << " &rarr; " << html::escape(st["new"].dump()) << "</p>";
  }
  if (f.contains("texels")) {
    const OJson& t = f["texels"];
    h << "<p class=\"meta\">texels " << t["old"]["texels"].dump() << " &rarr; " << t["new"]["texels"].dump();
    if (t.contains("changed_share")) h << ", changed share " << t["changed_share"].dump();
    h << "</p>";
  }
  if (!f.contains("images")) return h.str();
  const OJson& im = f["images"];
  h << "<p>" << im["views"].dump() << " views at " << im["size"].dump() << " px: PSNR min <b>" << html::fixed(im["psnr_min"], 2) << "</b> dB, mean "
    << html::fixed(im["psnr_mean"], 2) << " dB; changed pixels max " << im["changed_share_max"].dump() << "</p>\n";
  if (!p) return h.str();
  // One column per view: old over new over the difference, its PSNR under them.
  h << "<div class=\"views\">";
  for (std::size_t v = 0; v < p->old_views.size(); ++v) {
    const OJson& pv = im["per_view"][v];
    const std::string k = std::to_string(v);
    h << "<figure class=\"view\" data-view=\"" << v << "\" data-psnr=\"" << html::attr(pv["psnr"]) << "\">" << html::img(p->old_views[v], "old, view " + k)
      << html::img(p->new_views[v], "new, view " + k) << html::img(p->diff_views[v], "|old - new| x 4, view " + k) << "<figcaption>view " << k << ": "
      << html::fixed(pv["psnr"], 2) << " dB<br>changed " << html::fixed(pv["changed_share"], 4) << "</figcaption></figure>";
  }
  h << "</div><p class=\"meta\">Rows: old, new, |old - new| x 4 (black: no change).</p>\n";
  return h.str();
}

}  // namespace

std::string diff_page(const OJson& r, const std::map<std::string, DiffPictures>& pictures) {
  std::ostringstream h;
  const OJson& s = r["summary"];
  const std::string verdict = r["verdict"].get<std::string>();
  h << "<h1>qf-diff: <span id=\"verdict\" data-value=\"" << html::attr(r["verdict"]) << "\" class=\"" << (verdict == "different" ? "fail" : "ok") << "\">"
    << html::escape(verdict) << "</span></h1>\n<p class=\"meta\">old <code>" << html::escape(r["old"].get<std::string>()) << "</code> &rarr; new <code>"
    << html::escape(r["new"].get<std::string>()) << "</code>:";
  for (const char* k : {"identical", "changed", "added", "removed"})
    h << " <span id=\"summary-" << k << "\" data-value=\"" << s[k].dump() << "\">" << s[k].dump() << " " << k << "</span>";
  const OJson& t = r["thresholds"];
  h << "</p>\n<p class=\"meta\">thresholds: PSNR &ge; " << t["min_psnr"].dump() << " dB per view, changed pixels &le; " << t["max_changed_share"].dump()
    << ", quads added/removed &le; " << t["max_quad_change_share"].dump() << ", measured PSNR drop &le; " << t["max_error_drop"].dump() << " dB</p>\n";
  // The files that are not identical, in a table, then one section for each changed one.
  h << "<h2>Files that differ</h2>\n<table id=\"files\" class=\"sortable\"><thead><tr><th>file</th><th>status</th><th>verdict</th><th>bytes</th>"
       "<th>PSNR min dB</th><th>PSNR mean dB</th></tr></thead><tbody>\n";
  std::ostringstream sections, same;
  std::size_t identical = 0;
  for (const OJson& f : r["files"]) {
    const std::string name = f["name"].get<std::string>(), status = f["status"].get<std::string>();
    if (status == "identical") {
      same << (identical++ ? ", " : "") << "<code>" << html::escape(name) << "</code>";
      continue;
    }
    const bool within = f["within_thresholds"].get<bool>();
    const OJson im = f.contains("images") ? f["images"] : OJson::object();
    h << "<tr data-file=\"" << html::attr(name) << "\" data-status=\"" << status << "\" data-within=\"" << (within ? "true" : "false") << "\"";
    if (im.contains("psnr_min")) h << " data-psnr-min=\"" << html::attr(im["psnr_min"]) << "\" data-psnr-mean=\"" << html::attr(im["psnr_mean"]) << "\"";
    h << "><td>" << (status == "changed" ? "<a href=\"#" + html::attr(name) + "\">" + html::escape(name) + "</a>" : html::escape(name)) << "</td><td>"
      << status << "</td><td class=\"" << (within ? "ok" : "fail") << "\">" << (within ? "within" : "beyond") << "</td><td>"
      << (f.contains("bytes") ? pair_text(f["bytes"]) : "-") << "</td><td>" << html::fixed(im.value("psnr_min", OJson()), 2) << "</td><td>"
      << html::fixed(im.value("psnr_mean", OJson()), 2) << "</td></tr>\n";
    if (status != "changed") continue;
    const auto p = pictures.find(name);
    sections << "<section class=\"changed\" data-file=\"" << html::attr(name) << "\"><h3 id=\"" << html::attr(name) << "\">" << html::escape(name)
             << " <span class=\"" << (within ? "ok" : "fail") << "\">(" << (within ? "within thresholds" : "beyond thresholds") << ")</span></h3>\n"
             << (file_extension(name) == "json" ? manifest_block(f) : glb_block(f, p == pictures.end() ? nullptr : &p->second)) << "</section>\n";
  }
  h << "</tbody></table>\n" << sections.str();
  h << "<h2>Identical</h2>\n<p id=\"identical\" data-count=\"" << identical << "\">" << (identical ? same.str() : "none") << "</p>\n";
  return html::page("qf-diff: " + verdict, h.str(), ".views{display:flex;flex-wrap:wrap;gap:10px}.views figure img{margin-bottom:3px}h4{margin:10px 0 4px;font-size:13px}");
}

}  // namespace qf::render
