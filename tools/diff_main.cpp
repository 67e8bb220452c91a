// qf-diff OLD NEW: how two bakes differ (tools/diff.h), for people (text) or CI (--json).
// Exit codes: 0 identical or within the thresholds, 1 beyond them, 2 bad usage or unreadable
// input (a comparison that could not be made is not a pass), 3 internal error, 4 an --html or
// --images output that cannot be written.
#include <filesystem>
#include <iostream>
#include <map>

#include "cli/args.h"
#include "cli/program.h"
#include "core/error.h"
#include "core/file_io.h"
#include "tools/diff.h"
#include "tools/diff_html.h"

namespace {

// qf-diff takes no command word: one unnamed command (cli/program.h).
qf::cli::CommandSpec diff_spec() {
  return {"", "OLD NEW [options]", "compare two bakes: two .glb files or two output folders",
      "First whether they are byte-identical. If not, for each changed .glb a structural diff: level,\n"
      "quads matched by domain (added, removed), neighbour-graph edges, how the matched quads' planes\n"
      "moved and their errors changed, texel statistics (and the share of texels changed when the\n"
      "atlases have the same sizes); then an image diff: both drawn by runtime_gl from --views canonical\n"
      "views framing both (PSNR, share of changed pixels; EXR and PNG difference images with --images).\n"
      "Compressed .glb files (meshopt, quantized, Draco, KTX2, WebP) are decoded and compared as drawn.\n"
      "Folders pair their files by relative path; report.json, report.html and batch-report*.json\n"
      "(times, pages) and hidden files are left out; added or removed files are beyond any threshold.\n"
      "Exit status: 0 identical or within the thresholds, 1 beyond them, 2 bad usage or unreadable input,\n"
      "3 internal error, 4 the --html or --images output cannot be written (disk full, read-only).",
      {{"json", 0, "", "", "print the report as JSON (default: text)"},
       {"min-psnr", 0, "DB", "40", "a changed .glb passes when every view's PSNR is at least DB"},
       {"max-changed", 0, "SHARE", "0.005", "... and at most this share of each view's pixels changed"},
       {"pixel-tolerance", 0, "LEVELS", "2", "a pixel (texel) changed when a channel differs by more (0..255)"},
       {"max-quad-change", 0, "SHARE", "0", "... and at most this share of a level's quads added or removed"},
       {"max-error-drop", 0, "DB", "0.5", "a changed manifest passes when no measured figure (a level at a size, a chain band) falls by more"},
       {"views", 0, "N", "6", "canonical views per .glb"},
       {"size", 0, "PX", "128", "image side of each view"},
       {"images", 0, "DIR", "", "write DIR/NAME.diff.exr (float |old - new|, views stacked) and .diff.png (x4) per changed .glb"},
       {"html", 0, "DIR", "", "also write DIR/index.html, a self-contained page: per changed .glb its old, new and difference\n"
                             "(x4) images from every view with their PSNR; the manifest's chain and measured-error changes;\n"
                             "what was added, removed or identical (for people, or as a CI artefact)"},
       {"no-render", 0, "", "", "bytes and structure only: texel changes take the place of pixel changes"}},
      2, 2, "qf-diff"};
}

int run(const qf::cli::ParsedArgs& args) {
  qf::render::DiffOptions o;
  o.thresholds.min_psnr = args.get_double("min-psnr", o.thresholds.min_psnr, 0, 1000);
  o.thresholds.max_changed = args.get_double("max-changed", o.thresholds.max_changed, 0, 1);
  o.thresholds.pixel_tolerance = static_cast<int>(args.get_int("pixel-tolerance", o.thresholds.pixel_tolerance, 0, 255));
  o.thresholds.max_quad_change = args.get_double("max-quad-change", o.thresholds.max_quad_change, 0, 1);
  o.thresholds.max_error_drop = args.get_double("max-error-drop", o.thresholds.max_error_drop, 0, 1000);
  o.views = static_cast<int>(args.get_int("views", o.views, 1, 1000));
  o.size = static_cast<int>(args.get_int("size", o.size, 8, 4096));
  o.images = args.get("images");
  o.render = !args.flag("no-render");
  std::map<std::string, qf::render::DiffPictures> pictures;
  const std::string html = args.get("html");
  if (!html.empty()) o.pictures = &pictures;
  const nlohmann::ordered_json report = qf::render::diff_bakes(args.positional[0], args.positional[1], o);
  if (!html.empty()) {
    std::filesystem::create_directories(html);
    const std::string page = qf::render::diff_page(report, pictures);
    qf::write_file_atomically(html + "/index.html", [&](std::ostream& out) { out << page; });
  }
  if (args.flag("json")) std::cout << report.dump(2) << "\n";
  else std::cout << qf::render::diff_text(report);
  return report["verdict"] == "different" ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Exit 1 means "different": an input that cannot be read is 2, not a difference.
  const qf::cli::Program program{"qf-diff", "", "", "", {{diff_spec(), run}}, 0, "", nullptr, static_cast<int>(qf::ExitCode::kUsage)};
  return qf::cli::run_program(program, argc, argv);
}
