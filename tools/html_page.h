// The pieces every page quasiflat writes for a browser is built from (tools/report_html.h: the
// bake's report.html and the batch's page; tools/diff_html.h: qf-diff --html): text escaped for
// HTML, images as PNG data: URIs, and the page shell with its inline style and sorting script.
// Pages are self-contained (no network, no other file) and deterministic: the same figures and
// pixels give the same bytes.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

#include "runtime_gl/scene.h"

namespace qf::render::html {

// Text for an element or an attribute value: & < > " ' escaped.
std::string escape(std::string_view text);

// A JSON value as a data-* attribute carries it (its dump, escaped): a number is written as the
// JSON writes it, so a test reads back exactly the figure of manifest.json.
std::string attr(const nlohmann::json& value);

// An image's RGB channels as a PNG data: URI (opaque; alpha dropped).
std::string png_data_uri(const Image& image);

// <img> of `image` at its own size in pixels (CSS may scale it), with alt text and classes.
std::string img(const Image& image, const std::string& alt, const std::string& css_class = "");

// A whole page: the title, the shared style (plus `style`), `body`, and the shared script (which
// makes every table.sortable sortable by clicking its header cells) plus `script`.
std::string page(const std::string& title, const std::string& body, const std::string& style = "", const std::string& script = "");

// A number for people: `digits` after the point ("-" for null or non-numbers); bytes as KB/MB.
std::string fixed(const nlohmann::json& value, int digits);
std::string bytes_text(double bytes);

}  // namespace qf::render::html
