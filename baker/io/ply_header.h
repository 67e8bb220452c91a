// PLY header: the property types, the element layout and parse_header, apart from the body
// readers of ply_read.cpp (one job per file). Internal to baker/io.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/file_io.h"

namespace qf::ply {

enum class Type : std::uint8_t { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };
enum class Format { kAscii, kBinaryLE, kBinaryBE };

// Where a vertex property's value goes.
enum class Dest : std::uint8_t { kSkip, kX, kY, kZ, kNX, kNY, kNZ, kRed, kGreen, kBlue, kRadius };

struct Property {
  std::string name;
  bool is_list = false;
  Type count_type = Type::kUInt8;  // lists only
  Type type = Type::kFloat32;      // value type (element type for lists)
  Dest dest = Dest::kSkip;
  bool is_face_indices = false;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> props;
  std::size_t header_line = 0;
};

struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  std::vector<std::string> comments;
  std::size_t body_offset = 0;  // first byte after "end_header\n"
  std::size_t body_line = 0;    // line number of the first body line (ascii)
};

std::size_t type_size(Type t);
bool is_integer_type(Type t);
const char* type_name(Type t);
// The range of an integer type (the value range a binary file of that type can hold).
long long integer_min(Type t);
long long integer_max(Type t);
std::string type_range(Type t);

// Where a vertex property of this name goes (kSkip: not read).
Dest vertex_dest(const std::string& name);

// Reads and checks the header. Throws InputError("ply.header.*") naming the file and the line.
Header parse_header(ByteView bytes, const std::string& path);

}  // namespace qf::ply
