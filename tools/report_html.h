// The pages a bake and a batch write for people (tools/html_page.h builds them): what the numbers
// of manifest.json and report.json look like, without rendering anything by hand.
//   bake_page:  OUTDIR/report.html: the input beside every impostor level, mesh LOD and point
//               impostor, each drawn by the engine method at its own on-screen size and at 256 px;
//               per file its bytes, texels, GPU bytes and measured error; the recommended chain
//               (else the impostor levels) as bands along the screen-size axis; the warnings.
//   batch_page: one page over a batch's assets (sortable, thumbnails, failures with their
//               messages) linking each asset's report.html.
// qf-bake hands bake_page to the baker as AssetOptions::report_page (the baker does not link the
// renderer), as it hands it the measuring.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "io/model_io.h"
#include "pipeline/asset.h"

namespace qf::render {

struct BakePageOptions {
  ReadOptions read;        // how the input is read again (as the bake read it)
  // Every file is drawn at this size, beside the input; and at its own size where that is smaller
  // (a file made for more pixels is shown at this size only: one drawing less, and a page of
  // bunny00 at half the bytes).
  int near_pixels = 256;
};

// The bake's report.html. One headless GL context, one view (the same for every file, the input
// framed), at most two sizes per file: its own (max_screen_pixels; the point impostor's size at its
// switch distance) and near_pixels. Without a GL driver the page has every figure and no image, and says
// why. The page carries its figures as data-* attributes equal to the manifest's (a test reads
// them). Throws the loaders' InputErrors.
std::string bake_page(const AssetBake& bake, const std::string& input_path, const BakePageOptions& options = {});

// The id of the input drawn at near_pixels on every bake page with images: the batch page shows it
// as the asset's thumbnail.
constexpr const char* kThumbnailId = "input-near";

// The batch's page from its report (schemas/batch-report.schema.json): one sortable row per asset
// (status, time, points, primitives, texels, files, warnings, the error message of a failure), the
// thumbnail of each asset's report.html and a link to it (relative to `page_dir`, where the page is
// written; assets live in the report's "output" folder).
std::string batch_page(const nlohmann::json& report, const std::string& page_dir);

}  // namespace qf::render
