// EXT_meshopt_compression decoding (see meshopt_decode.h).
#include "gltf/meshopt_decode.h"

#include <meshoptimizer.h>

#include <limits>
#include <stdexcept>

namespace qf {
namespace {

[[noreturn]] void broken(const std::string& what) { throw std::runtime_error(what); }

}  // namespace

std::uint64_t meshopt_decoded_bytes(const MeshoptView& v) {
  if (v.stride != 0 && v.count > std::numeric_limits<std::uint64_t>::max() / v.stride) return 0;
  return v.count * v.stride;
}

void check_meshopt_view(const MeshoptView& v) {
  const std::string at = v.mode + " (byteStride " + std::to_string(v.stride) + ", count " + std::to_string(v.count) + ")";
  if (v.mode == "ATTRIBUTES") {
    if (v.stride == 0 || v.stride > 256 || v.stride % 4 != 0) broken("mode " + at + ": byteStride must be a multiple of 4 up to 256");
  } else if (v.mode == "TRIANGLES" || v.mode == "INDICES") {
    if (v.stride != 2 && v.stride != 4) broken("mode " + at + ": byteStride must be 2 or 4");
    if (v.mode == "TRIANGLES" && v.count % 3 != 0) broken("mode " + at + ": count must be a multiple of 3");
    if (v.filter != "NONE") broken("mode " + at + ": filter " + v.filter + " applies to ATTRIBUTES only");
  } else {
    broken("unknown mode '" + v.mode + "' (ATTRIBUTES, TRIANGLES or INDICES)");
  }
  if (v.filter == "OCTAHEDRAL" && v.stride != 4 && v.stride != 8) broken("filter OCTAHEDRAL needs byteStride 4 or 8, not " + std::to_string(v.stride));
  if (v.filter == "QUATERNION" && v.stride != 8) broken("filter QUATERNION needs byteStride 8, not " + std::to_string(v.stride));
  if (v.filter != "NONE" && v.filter != "OCTAHEDRAL" && v.filter != "QUATERNION" && v.filter != "EXPONENTIAL")
    broken("unknown filter '" + v.filter + "' (NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL)");
  if (v.count > 0 && meshopt_decoded_bytes(v) == 0) broken("count x byteStride overflows");
}

std::vector<std::uint8_t> meshopt_decode(const std::uint8_t* data, std::size_t size, const MeshoptView& v) {
  check_meshopt_view(v);
  const auto count = static_cast<std::size_t>(v.count), stride = static_cast<std::size_t>(v.stride);
  std::vector<std::uint8_t> out(count * stride);
  if (count == 0) return out;
  // 1. The extension's vertex codec is version 0 (header byte 0xa0). meshoptimizer 1.x also decodes
  //    its version 1 (0xa1), which only KHR_meshopt_compression allows: refused here by name, as
  //    Debian's 0.18 refused it, instead of reading a stream the file's extension does not define.
  if (v.mode == "ATTRIBUTES" && size > 0 && data[0] != 0xa0)
    broken("the ATTRIBUTES stream's header byte is " + std::to_string(data[0]) +
           ", not 160 (0xa0: the vertex codec version 0 that EXT_meshopt_compression defines)");
  // 2. The codec: each returns non-zero when the stream is truncated or malformed.
  int rc = 0;
  if (v.mode == "ATTRIBUTES") rc = meshopt_decodeVertexBuffer(out.data(), count, stride, data, size);
  else if (v.mode == "TRIANGLES") rc = meshopt_decodeIndexBuffer(out.data(), count, stride, data, size);
  else rc = meshopt_decodeIndexSequence(out.data(), count, stride, data, size);
  if (rc != 0)
    broken("the " + v.mode + " stream of " + std::to_string(size) + " bytes does not decode to " + std::to_string(count) + " elements of " +
           std::to_string(stride) + " bytes (meshoptimizer error " + std::to_string(rc) + ": truncated or corrupt)");
  // 3. The filter, in place (its input is whatever the codec produced: any bytes are defined).
  if (v.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), count, stride);
  else if (v.filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), count, stride);
  else if (v.filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), count, stride);
  return out;
}

}  // namespace qf
