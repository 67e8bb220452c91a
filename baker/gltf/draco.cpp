// Draco compression (see draco.h; decoding is draco_decode.cpp).
#include "gltf/draco.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <algorithm>
#include <memory>
#include <string>
#include <stdexcept>

namespace qf {

DracoOutput draco_compress(const DracoInput& in) {
  const int faces = static_cast<int>(in.positions.size() / 9);
  if (faces == 0) throw std::runtime_error("draco: no triangles");
  // 1. The triangle soup; Finalize merges equal corners into shared points.
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(faces);
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nrm = in.normals.empty() ? -1 : builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int col = in.colors.empty() ? -1 : builder.AddAttribute(draco::GeometryAttribute::COLOR, 4, draco::DT_UINT16, true);
  for (int f = 0; f < faces; ++f) {
    const std::size_t v = static_cast<std::size_t>(f) * 3;
    builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &in.positions[3 * v], &in.positions[3 * v + 3], &in.positions[3 * v + 6]);
    if (nrm >= 0)
      builder.SetAttributeValuesForFace(nrm, draco::FaceIndex(f), &in.normals[3 * v], &in.normals[3 * v + 3], &in.normals[3 * v + 6]);
    if (col >= 0)
      builder.SetAttributeValuesForFace(col, draco::FaceIndex(f), &in.colors[4 * v], &in.colors[4 * v + 4], &in.colors[4 * v + 8]);
  }
  std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  if (!mesh) throw std::runtime_error("draco: building the mesh failed");
  // 2. Encode (edgebreaker, default speed) with quantised positions and normals.
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
  if (!status.ok()) throw std::runtime_error("draco: " + status.error_msg_string());
  DracoOutput out;
  out.bytes.assign(buffer.data(), buffer.data() + buffer.size());
  // 3. Decode to describe what a reader will get.
  draco::DecoderBuffer dbuf;
  dbuf.Init(buffer.data(), buffer.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&dbuf);
  if (!decoded.ok()) throw std::runtime_error("draco: decoding our own output failed");
  const draco::Mesh& d = *decoded.value();
  out.vertices = d.num_points();
  out.indices = static_cast<std::size_t>(d.num_faces()) * 3;
  const draco::PointAttribute* p = d.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  out.min = {INFINITY, INFINITY, INFINITY};
  out.max = {-INFINITY, -INFINITY, -INFINITY};
  for (draco::PointIndex i(0); i < d.num_points(); ++i) {
    float v[3];
    p->GetMappedValue(i, v);
    for (int k = 0; k < 3; ++k) out.min[static_cast<std::size_t>(k)] = std::min(out.min[static_cast<std::size_t>(k)], double(v[k])),
                                out.max[static_cast<std::size_t>(k)] = std::max(out.max[static_cast<std::size_t>(k)], double(v[k]));
  }
  out.position_id = static_cast<int>(p->unique_id());
  if (const auto* a = d.GetNamedAttribute(draco::GeometryAttribute::NORMAL)) out.normal_id = static_cast<int>(a->unique_id());
  if (const auto* a = d.GetNamedAttribute(draco::GeometryAttribute::COLOR)) out.color_id = static_cast<int>(a->unique_id());
  return out;
}

}  // namespace qf
