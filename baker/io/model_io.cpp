// Format dispatch by file extension: read_model, decode_model and write_point_set.
#include <ostream>

#include "core/error.h"
#include "core/file_io.h"
#include "io/model_io.h"

namespace qf {

void write_point_set(const std::string& path, const PointSet& points) {
  const std::string ext = file_extension(path);
  if (ext == "ply") return write_ply(path, points);
  if (ext == "xyz") return write_xyz(path, points, false);
  if (ext == "pwn") return write_xyz(path, points, true);
  if (ext == "qs") {
    if (!points.has_normals())
      throw InputError("convert.needs_normals", path, "", "a .qs file needs normals and this point set has none");
    if (!points.has_radii())
      throw InputError("convert.needs_radii", path, "", "a .qs file needs splat radii and this point set has none");
    if (points.size() == 0) throw InputError("convert.empty", path, "", "a .qs file needs at least one point");
    const std::vector<std::uint8_t> bytes = encode_qsplat(points);
    return write_file_atomically(path, [&](std::ostream& out) {
      out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    });
  }
  throw UsageError("cannot write point sets as '." + ext + "' (" + path + "); supported: .ply .qs .xyz .pwn");
}

Model read_model(const std::string& path, const ReadOptions& options, ReadReport* report) {
  const std::string ext = file_extension(path);
  Model m;
  if (ext == "ply") return read_ply(path, options, report);
  if (ext == "qs") m.points = read_qsplat(path, options, report);
  else if (ext == "xyz") m.points = read_xyz(path, false, options, report);
  else if (ext == "pwn") m.points = read_xyz(path, true, options, report);
  else if (ext == "las" || ext == "laz") m.points = read_las(path, options, report);
  else if (ext == "off") m.is_mesh = true, m.mesh = read_off(path, options, report);
  else if (ext == "obj") m.is_mesh = true, m.mesh = read_obj(path, options, report);
  else if (ext == "gltf" || ext == "glb") m.is_mesh = true, m.mesh = read_gltf(path, options, report);
  else
    throw UsageError("unknown input format '." + ext + "' (" + path +
                     "); supported: .ply .qs .xyz .pwn .las .laz (point sets), .ply .off .obj .gltf .glb (meshes)");
  return m;
}

Model decode_model(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report) {
  const std::string ext = file_extension(path);
  Model m;
  if (ext == "ply") return decode_ply(bytes, path, options, report);
  if (ext == "qs") m.points = decode_qsplat(bytes, path, report);
  else if (ext == "xyz") m.points = decode_xyz(bytes, path, false, options, report);
  else if (ext == "pwn") m.points = decode_xyz(bytes, path, true, options, report);
  else if (ext == "las" || ext == "laz") m.points = decode_las(bytes, path, options, report);
  else if (ext == "off") m.is_mesh = true, m.mesh = decode_off(bytes, path, options, report);
  else if (ext == "obj") m.is_mesh = true, m.mesh = decode_obj(bytes, path, options, report);
  else if (ext == "gltf" || ext == "glb") m.is_mesh = true, m.mesh = decode_gltf(bytes, path, options, report);
  else
    throw UsageError("unknown input format '." + ext + "' (" + path +
                     "); supported: .ply .qs .xyz .pwn .las .laz (point sets), .ply .off .obj .gltf .glb (meshes)");
  return m;
}

std::optional<std::size_t> streamed_point_count(const std::string& path) {
  const std::string ext = file_extension(path);
  try {
    if (ext == "las" || ext == "laz") return static_cast<std::size_t>(las_point_count(path));
    if (ext == "ply")
      if (const std::optional<std::uint64_t> n = ply_point_count(path)) return static_cast<std::size_t>(*n);
  } catch (const InputError&) {
    // read whole: the reader says what is wrong
  }
  return std::nullopt;
}

void stream_point_set(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report,
                      std::size_t block_points, const std::function<void(PointSet&)>& block) {
  const std::string ext = file_extension(path);
  if (ext == "las" || ext == "laz") return stream_las(bytes, path, report, block_points, block);
  if (ext == "ply") return stream_ply(bytes, path, options, report, block_points, block);
  throw UsageError(path + ": only LAS/LAZ and PLY point sets are read as a stream");
}

void stream_point_set(const std::string& path, const ReadOptions& options, ReadReport* report, std::size_t block_points,
                      const std::function<void(PointSet&)>& block) {
  const std::string ext = file_extension(path);
  if (ext == "las" || ext == "laz") return stream_las(path, report, block_points, block);
  if (ext != "ply") throw UsageError(path + ": only LAS/LAZ and PLY point sets are read as a stream");
  const InputFile file(path, InputFile::Access::kStreamed);
  stream_ply(file.bytes(), path, options, report, block_points, block, &file);
}

const std::vector<std::string>& point_set_extensions() {
  static const std::vector<std::string> e{"ply", "qs", "xyz", "pwn", "las", "laz"};
  return e;
}
const std::vector<std::string>& mesh_extensions() {
  static const std::vector<std::string> e{"ply", "off", "obj", "gltf", "glb"};
  return e;
}

}  // namespace qf
