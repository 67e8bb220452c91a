// Reading and writing every supported file format (architecture.md, "io/").
//
// Point sets: PLY (ascii / binary LE / binary BE), QSplat .qs, XYZ, PWN, LAS / LAZ.
// Triangle meshes: PLY with a face element, OFF (also COFF/NOFF/NCOFF), OBJ (+ MTL), glTF 2.0.
// Every reader throws InputError with the file, the line or byte offset and what was expected;
// it never returns partial data.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/file_io.h"
#include "core/types.h"

namespace qf {

struct ReadOptions {
  // Non-finite (NaN/Inf) coordinates are an error by default; with this on, such points (or mesh
  // vertices, with the triangles using them) are dropped and counted in ReadReport.
  bool drop_nonfinite = false;
  // Point sets: drop the outliers, points more than this many times the set's median spacing from
  // their 8 nearest neighbours (analysis/neighborhoods.h drop_outliers: a scanner's mixed pixels
  // and strays); 0 keeps every point. Not the format readers' job (read_model ignores it): the
  // bake's loader applies it (pipeline/asset.h load_point_set), and so does the loader of the
  // measuring's and report.html's truth (measure/any_scene.h load_input), so both see one set.
  // qf-bake sets 10 (--outliers).
  float outlier_factor = 0.0f;
  // The folder an asset's external files (glTF buffers and images, OBJ mtllib, MTL map_Kd) must
  // resolve inside, symlinks followed (io/asset_files.h); empty: the asset's own folder. A
  // reference leading outside is an InputError. qf-bake --asset-root.
  std::string asset_root;
  // Bytes reading may take (glTF and OBJ: decoded images, glTF: mesh instances), checked from the
  // headers and counts before anything is decoded; 0: the memory available (core/memory.h).
  // qf-bake --max-memory.
  std::size_t memory_limit = 0;
};

struct ReadReport {
  std::string format;               // e.g. "ply (binary_little_endian)", "qsplat", "off"
  std::size_t dropped_nonfinite = 0;  // points/vertices dropped under drop_nonfinite
  std::size_t dropped_triangles = 0;  // triangles dropped with them
  std::size_t dropped_outliers = 0;   // points dropped under outlier_factor (by the loaders)
  std::size_t polygons_triangulated = 0;  // faces with more than 3 corners, split into fans
  std::size_t fragments = 0;        // QSplat: data fragments read
  std::size_t skipped_primitives = 0;  // glTF: point and line primitives (only triangles are baked)
  std::vector<std::string> warnings;   // what was read but not honoured (glTF skins, morph targets)
  // What the file's header says, as (key, value) in the reader's order (LAS/LAZ: version, point
  // format, scale, offset, the origin the points were moved by, VLRs, ...); empty for most formats.
  std::vector<std::pair<std::string, std::string>> header;
};

// A file's content: a point set or a triangle mesh.
struct Model {
  bool is_mesh = false;
  PointSet points;    // when !is_mesh
  TriangleMesh mesh;  // when is_mesh
};

// Reads any supported file, choosing the reader by extension (ply, qs, xyz, pwn, las, laz, off, obj,
// gltf, glb).
// Throws UsageError for an unknown extension.
Model read_model(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);

// Per-format readers, for callers that already know the format. `path` names the file in errors.
Model read_ply(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
PointSet read_qsplat(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
PointSet read_xyz(const std::string& path, bool require_normals, const ReadOptions& options = {},
                  ReadReport* report = nullptr);
// LAS 1.0–1.4, point data formats 0–10 (extra bytes past the standard record allowed), and LAZ
// (LASzip-compressed LAS, decoded with laz-perf 3.4.0: formats 0–3 and 6–8, chunked; the header
// says whether a file is compressed, whatever its extension). Positions are the records' integers
// x scale + offset, computed in double; when float cannot hold them to the file's resolution
// (|coordinate| > 2^23 x scale, e.g. UTM), they are moved by an origin (the header box's centre,
// rounded to whole units), given in a comment "origin X Y Z ..." and in ReadReport::header.
// Colours (formats 2, 3, 5, 7, 8, 10): 16-bit values scaled to 8 bits (high byte), or taken as
// they are when none exceeds 255. Classification (formats 0–5: its low 5 bits; 6–10: the byte)
// becomes the scalar field "classification". The file is read a block of records or one LAZ chunk
// at a time. Errors: "las.*" (header, VLRs, body), "laz.*" (LASzip VLR, chunk table, chunks).
PointSet read_las(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
// The formats' parts of stream_point_set and streamed_point_count (below): LAS/LAZ, and PLY files
// without faces (ply_point_count: nullopt for one with faces).
std::uint64_t las_point_count(const std::string& path);
void stream_las(const std::string& path, ReadReport* report, std::size_t block_points, const std::function<void(PointSet&)>& block);
void stream_las(ByteView bytes, const std::string& path, ReadReport* report, std::size_t block_points,
                const std::function<void(PointSet&)>& block);
std::optional<std::uint64_t> ply_point_count(const std::string& path);
// `file`, when the bytes are its (streamed), has the pages read released block by block.
void stream_ply(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report, std::size_t block_points,
                const std::function<void(PointSet&)>& block, const InputFile* file = nullptr);
TriangleMesh read_off(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
TriangleMesh read_obj(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
// glTF 2.0 (.gltf with external or data-URI buffers and images, .glb): the default scene (else the
// root nodes) as one mesh in world space: every node transform composed down the tree (mirroring
// ones keep their winding), TRIANGLES / strips / fans (points and lines skipped and counted), any
// index type, NORMAL (primitives without it flat, as glTF draws them), COLOR_0, and per material
// baseColorFactor x baseColorTexture (its texCoord set and KHR_texture_transform applied to the
// texture coordinates, its sampler's wraps), alphaMode and alphaCutoff. KHR_draco_mesh_compression
// is decoded; other required extensions are refused (InputError "gltf.unsupported_extension").
// Skins are read in their bind pose and morph targets ignored, with a warning in the report.
// Errors name the JSON path: "meshes[0].primitives[1].indices: index 12 out of range (8 vertices)".
TriangleMesh read_gltf(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);

// Point sets too big to hold whole (the out-of-core bake, pipeline/out_of_core.h): LAS/LAZ files
// and PLY files without faces are read a block at a time, each block of at most `block_points`
// points (in file order) handed to `block`, which may take its arrays. The rules are the whole
// read's: the same points, attributes and errors (non-finite points refused or dropped per block;
// LAS colours 8- or 16-bit as the whole file says: where a file's colours are 16-bit their first
// value past 255 settles it, where they are not the file is read twice). An error after some
// blocks throws as the whole read does: whatever took the blocks must be discarded.
// streamed_point_count: the points a file's header declares when it streams, else nullopt (other
// formats, PLY meshes, files whose header does not parse: read those whole; read_model reports
// what is wrong with them). stream_point_set throws UsageError for a file that does not stream.
std::optional<std::size_t> streamed_point_count(const std::string& path);
void stream_point_set(const std::string& path, const ReadOptions& options, ReadReport* report, std::size_t block_points,
                      const std::function<void(PointSet&)>& block);
// The same on bytes in memory (the fuzz targets).
void stream_point_set(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report,
                      std::size_t block_points, const std::function<void(PointSet&)>& block);

// The same readers on bytes already in memory (the path readers map the file and call these; the
// fuzz targets of tests/fuzz call them directly). `path` names the file in errors; decode_model
// chooses the reader by its extension, as read_model does.
Model decode_model(ByteView bytes, const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
Model decode_ply(ByteView bytes, const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
PointSet decode_xyz(ByteView bytes, const std::string& path, bool require_normals, const ReadOptions& options = {},
                    ReadReport* report = nullptr);
PointSet decode_las(ByteView bytes, const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
TriangleMesh decode_off(ByteView bytes, const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
TriangleMesh decode_obj(ByteView bytes, const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
// External buffers and images are read relative to `path`'s folder.
TriangleMesh decode_gltf(ByteView bytes, const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);

// QSplat in memory. decode_qsplat names `path` in errors and returns the leaves in depth-first
// tree order. encode_qsplat needs normals and radii (it writes colours when the set has them,
// comments as a comment fragment); `leaf_order`, if given, receives the input index of each leaf
// in the order decode_qsplat will return them (the writer reorders points spatially).
PointSet decode_qsplat(ByteView bytes, const std::string& path, ReadReport* report = nullptr);
std::vector<std::uint8_t> encode_qsplat(const PointSet& points, std::vector<std::uint32_t>* leaf_order = nullptr);

// Writers. All write atomically (temporary name, then rename).
// PLY: binary little-endian with every attribute the set has (scalars as extra float properties).
void write_ply(const std::string& path, const PointSet& points);
void write_ply(const std::string& path, const TriangleMesh& mesh);
// XYZ: "x y z" per line, plus "nx ny nz" when the set has normals (PWN requires them).
void write_xyz(const std::string& path, const PointSet& points, bool require_normals);

// Writes a point set in the format named by the extension of `path` (ply, qs, xyz, pwn).
// Throws UsageError for other extensions, InputError("convert.needs_normals" / "convert.needs_radii")
// when the set lacks what the format needs (normals for .qs and .pwn, radii for .qs).
void write_point_set(const std::string& path, const PointSet& points);

// A file a model reads besides itself: `name` as the model names it, relative to the model's
// folder ('/'-separated, percent-decoding done), and `path` to open it (the model's folder joined).
struct InputDependency {
  std::string name, path;
};
// The external files `path` reads, found from its text without decoding geometry or images (for
// content keys such as the batch's): a .gltf's or .glb's buffers[].uri and images[].uri that are
// not data: URIs (in file order, buffers first), an .obj's mtllib files and each MTL's map_Kd
// images (relative to the MTL, as the reader takes them). Each named once; files that do not exist
// are listed too (the reader decides whether that is an error). Other formats, or a glTF whose
// JSON does not parse, give none. Throws InputError (file.unreadable) when `path` cannot be read.
std::vector<InputDependency> input_dependencies(const std::string& path);

// The point-set and mesh extensions this build reads, for help texts.
const std::vector<std::string>& point_set_extensions();
const std::vector<std::string>& mesh_extensions();

}  // namespace qf
