// Image files for qf-render and qf-diff, on OpenImageIO (the one file that includes it): PNG/EXR
// writing, reading, contact sheets. The metrics are image_metrics.h (no OpenImageIO: qf-bake
// measures with them without loading its ~250 libraries).
#pragma once

#include <string>
#include <vector>

#include "runtime_gl/scene.h"
#include "measure/image_metrics.h"

namespace qf::render {

// Writes an opaque PNG (the RGB channels; alpha dropped), atomically. The same pixels give the
// same bytes.
void save_png(const std::string& path, const Image& image);

// Reads an 8-bit image file (PNG, or anything OpenImageIO reads) as RGBA (opaque where it has no
// alpha). Throws InputError ("render.image") naming the file.
Image load_image(const std::string& path);

// Tiles images (all the same size) in rows of `columns`, on `background`, with an optional
// caption under each (rendered with DejaVu Sans when the font is installed; left out otherwise).
Image contact_sheet(const std::vector<Image>& images, int columns, Rgb8 background,
                    const std::vector<std::string>& captions = {});

// Writes a float RGB image (e.g. a difference image) as OpenEXR (half floats, zip), atomically.
void save_exr(const std::string& path, const std::vector<float>& rgb, int width, int height);
}  // namespace qf::render
