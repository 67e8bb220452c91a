// The files an asset names besides itself (glTF buffers and images, OBJ mtllib, MTL map_Kd),
// confined to the asset's folder: a farm bakes files it did not make, and a reference through
// "../", "%2e%2e/", an absolute path or a symlink must not read another file of the machine.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace qf::io {

// glTF URIs are percent-encoded (RFC 3986): "%2e%2e" is "..". Malformed escapes stay as written.
std::string percent_decoded(const std::string& uri);

// The folder references of the model at `model_path` must stay in, canonical (symlinks
// resolved): `root_option` (qf-bake --asset-root) when non-empty, else the model's own folder.
std::filesystem::path asset_root(const std::string& model_path, const std::string& root_option);

// Where `reference` (already decoded; '/'-separated, relative to `base_folder`, or absolute) leads,
// every symlink on the way resolved, or nullopt when it leaves `root` (canonical) at any step:
// a ".." above it, an absolute path or a symlink target outside it. Nothing outside `root` is
// looked at, so the answer says nothing about the files there. The path found may not exist.
std::optional<std::filesystem::path> resolve_inside(const std::filesystem::path& root, const std::filesystem::path& base_folder,
                                                    const std::string& reference);

// resolve_inside, refusing what it cannot follow: InputError("<prefix>.outside_asset", file,
// where) naming `written` (the reference as the file writes it) and the root, the same message
// whatever the file it named; InputError("<prefix>.not_regular_file") for a reference inside the
// root that names a folder, FIFO, device or socket (a FIFO would hang the reader). A missing file
// is returned as it is: the caller decides whether that is an error.
std::filesystem::path confined_file(const std::filesystem::path& root, const std::filesystem::path& base_folder,
                                    const std::string& reference, const std::string& written, const std::string& file,
                                    const std::string& prefix, const std::string& where);

}  // namespace qf::io
