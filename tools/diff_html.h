// qf-diff --html DIR: the diff report as a page for people (and a CI artefact): for every changed
// .glb its old, new and difference images from the same cameras with the PSNR between them, the
// manifest's changes (the recommended chain, the measured errors, the levels' bytes), and what was
// added, removed or left identical. Built with tools/html_page.h; self-contained.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <string>

#include "tools/diff.h"

namespace qf::render {

// The page of `report` (diff_bakes' JSON) with `pictures` (DiffOptions::pictures of the same run).
// Its figures are carried as data-* attributes equal to the report's (a test reads them).
std::string diff_page(const nlohmann::ordered_json& report, const std::map<std::string, DiffPictures>& pictures);

}  // namespace qf::render
