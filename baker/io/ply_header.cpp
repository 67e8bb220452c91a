// PLY header parsing and the property types (see ply_header.h).
#include "io/ply_header.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>

#include "core/error.h"
#include "io/reader_util.h"

namespace qf::ply {
namespace {

using io::quote_token;

std::optional<Type> parse_type(std::string_view s) {
  if (s == "char" || s == "int8") return Type::kInt8;
  if (s == "uchar" || s == "uint8") return Type::kUInt8;
  if (s == "short" || s == "int16") return Type::kInt16;
  if (s == "ushort" || s == "uint16") return Type::kUInt16;
  if (s == "int" || s == "int32") return Type::kInt32;
  if (s == "uint" || s == "uint32") return Type::kUInt32;
  if (s == "float" || s == "float32") return Type::kFloat32;
  if (s == "double" || s == "float64") return Type::kFloat64;
  return std::nullopt;
}

// "format FORMAT 1.0".
Format format_line(io::Tokenizer& tok, const std::string& path, const std::string& where) {
  const std::string_view f = tok.next(), version = tok.next();
  Format format;
  if (f == "ascii") format = Format::kAscii;
  else if (f == "binary_little_endian") format = Format::kBinaryLE;
  else if (f == "binary_big_endian") format = Format::kBinaryBE;
  else
    throw InputError("ply.header.format", path, where,
                     "unknown format " + quote_token(f) +
                         ", expected ascii, binary_little_endian or binary_big_endian");
  if (version != "1.0")
    throw InputError("ply.header.format", path, where, "unsupported version " + quote_token(version) + ", expected 1.0");
  return format;
}

// "element NAME COUNT".
Element element_line(io::Tokenizer& tok, const std::string& path, const std::string& where, std::size_t line_no) {
  Element e;
  e.name = std::string(tok.next());
  long long count = -1;
  if (e.name.empty() || !io::parse_int64(tok.next(), count) || count < 0)
    throw InputError("ply.header.syntax", path, where, "expected 'element NAME COUNT' with COUNT >= 0");
  e.count = static_cast<std::uint64_t>(count);
  e.header_line = line_no;
  return e;
}

// "property TYPE NAME" or "property list COUNT_TYPE TYPE NAME".
Property property_line(io::Tokenizer& tok, const std::string& path, const std::string& where) {
  Property prop;
  std::string_view t = tok.next();
  if (t == "list") {
    prop.is_list = true;
    const std::string_view ct = tok.next();
    const auto count_type = parse_type(ct);
    if (!count_type)
      throw InputError("ply.header.property_type", path, where, "unsupported list count type " + quote_token(ct));
    if (!is_integer_type(*count_type))
      throw InputError("ply.header.property_type", path, where, "list count type must be an integer type, not " + quote_token(ct));
    prop.count_type = *count_type;
    t = tok.next();
  }
  const auto type = parse_type(t);
  if (!type)
    throw InputError("ply.header.property_type", path, where,
                     "unsupported property type " + quote_token(t) +
                         ", expected one of char uchar short ushort int uint float double (or int8..float64)");
  prop.type = *type;
  prop.name = std::string(tok.next());
  if (prop.name.empty()) throw InputError("ply.header.syntax", path, where, "property without a name");
  return prop;
}

}  // namespace

Dest vertex_dest(const std::string& n) {
  if (n == "x") return Dest::kX;
  if (n == "y") return Dest::kY;
  if (n == "z") return Dest::kZ;
  if (n == "nx" || n == "normal_x") return Dest::kNX;
  if (n == "ny" || n == "normal_y") return Dest::kNY;
  if (n == "nz" || n == "normal_z") return Dest::kNZ;
  if (n == "red" || n == "diffuse_red" || n == "r") return Dest::kRed;
  if (n == "green" || n == "diffuse_green" || n == "g") return Dest::kGreen;
  if (n == "blue" || n == "diffuse_blue" || n == "b") return Dest::kBlue;
  // "scale" is the splat radius in several point-splatting tools. "confidence" (Stanford scans) is
  // a quality weight in [0,1], not a length, so it is not read as a radius.
  if (n == "radius" || n == "scale") return Dest::kRadius;
  return Dest::kSkip;
}

std::size_t type_size(Type t) {
  switch (t) {
    case Type::kInt8: case Type::kUInt8: return 1;
    case Type::kInt16: case Type::kUInt16: return 2;
    case Type::kInt32: case Type::kUInt32: case Type::kFloat32: return 4;
    case Type::kFloat64: return 8;
  }
  return 0;
}

bool is_integer_type(Type t) { return t != Type::kFloat32 && t != Type::kFloat64; }

const char* type_name(Type t) {
  switch (t) {
    case Type::kInt8: return "char";
    case Type::kUInt8: return "uchar";
    case Type::kInt16: return "short";
    case Type::kUInt16: return "ushort";
    case Type::kInt32: return "int";
    case Type::kUInt32: return "uint";
    case Type::kFloat32: return "float";
    case Type::kFloat64: return "double";
  }
  return "?";
}

long long integer_min(Type t) {
  switch (t) {
    case Type::kInt8: return std::numeric_limits<std::int8_t>::min();
    case Type::kInt16: return std::numeric_limits<std::int16_t>::min();
    case Type::kInt32: return std::numeric_limits<std::int32_t>::min();
    default: return 0;
  }
}
long long integer_max(Type t) {
  switch (t) {
    case Type::kInt8: return std::numeric_limits<std::int8_t>::max();
    case Type::kUInt8: return std::numeric_limits<std::uint8_t>::max();
    case Type::kInt16: return std::numeric_limits<std::int16_t>::max();
    case Type::kUInt16: return std::numeric_limits<std::uint16_t>::max();
    case Type::kInt32: return std::numeric_limits<std::int32_t>::max();
    case Type::kUInt32: return std::numeric_limits<std::uint32_t>::max();
    default: return 0;
  }
}
std::string type_range(Type t) { return std::to_string(integer_min(t)) + ".." + std::to_string(integer_max(t)); }

// ---------------------------------------------------------------------------------------------
// Header

Header parse_header(ByteView bytes, const std::string& path) {
  Header h;
  const char* begin = reinterpret_cast<const char*>(bytes.data());
  const char* end = begin + bytes.size();
  // 1. Magic: "ply" alone on the first line.
  if (bytes.size() < 4 || std::memcmp(begin, "ply", 3) != 0 || (begin[3] != '\n' && begin[3] != '\r'))
    throw InputError("ply.header.magic", path, at_byte(0), "expected the line 'ply' at the start of the file");
  // 2. One keyword line at a time up to end_header.
  const char* p = begin;
  std::size_t line_no = 0;
  bool have_format = false, done = false;
  while (!done) {
    if (p >= end)
      throw InputError("ply.header.truncated", path, at_line(line_no),
                       "file ends inside the header; expected 'end_header'");
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
    if (!nl)
      throw InputError("ply.header.truncated", path, at_line(line_no + 1),
                       "file ends inside the header; expected 'end_header'");
    ++line_no;
    std::string_view line(p, static_cast<std::size_t>(nl - p));
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    p = nl + 1;
    if (line_no > 100000)
      throw InputError("ply.header.truncated", path, at_line(line_no), "header longer than 100000 lines");
    io::Tokenizer tok(line.data(), line.data() + line.size(), line_no);
    const std::string_view key = tok.next();
    const std::string where = at_line(line_no);
    if (line_no == 1) continue;  // "ply"
    if (key == "comment" || key == "obj_info") {
      if (key == "comment") {
        std::string_view text = line.substr(std::min(line.size(), std::size_t{8}));
        h.comments.emplace_back(text);
      }
    } else if (key == "format") {
      h.format = format_line(tok, path, where);
      have_format = true;
    } else if (key == "element") {
      h.elements.push_back(element_line(tok, path, where, line_no));
    } else if (key == "property") {
      if (h.elements.empty())
        throw InputError("ply.header.syntax", path, where, "'property' before any 'element' line");
      h.elements.back().props.push_back(property_line(tok, path, where));
    } else if (key == "end_header") {
      done = true;
    } else {
      throw InputError("ply.header.syntax", path, where,
                       "unknown header line " + quote_token(key) +
                           ", expected format, element, property, comment, obj_info or end_header");
    }
  }
  if (!have_format) throw InputError("ply.header.format", path, at_line(2), "missing 'format' line");
  h.body_offset = static_cast<std::size_t>(p - begin);
  h.body_line = line_no + 1;
  return h;
}

}  // namespace qf::ply
