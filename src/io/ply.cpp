// PLY (Stanford polygon format), ascii and binary of either byte order. The
// header declares elements and their properties; only vertex x/y/z and the face
// index list are kept, every other property and element is read past by type
// so that files with normals, colors, texture lists or extra elements load.
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "ember/error.hpp"
#include "ember/io/mesh_io.hpp"
#include "io/text_scanner.hpp"
#include "io/writer_support.hpp"

namespace ember {
namespace {

using io_detail::TextScanner;

enum class PlyType { I8, U8, I16, U16, I32, U32, F32, F64 };

std::optional<PlyType> parse_type(std::string_view t) {
  struct Entry {
    std::string_view a, b;
    PlyType type;
  };
  static constexpr std::array<Entry, 8> kTypes = {{{"char", "int8", PlyType::I8},
                                                   {"uchar", "uint8", PlyType::U8},
                                                   {"short", "int16", PlyType::I16},
                                                   {"ushort", "uint16", PlyType::U16},
                                                   {"int", "int32", PlyType::I32},
                                                   {"uint", "uint32", PlyType::U32},
                                                   {"float", "float32", PlyType::F32},
                                                   {"double", "float64", PlyType::F64}}};
  for (const Entry& e : kTypes)
    if (t == e.a || t == e.b) return e.type;
  return std::nullopt;
}

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::I8:
    case PlyType::U8: return 1;
    case PlyType::I16:
    case PlyType::U16: return 2;
    case PlyType::I32:
    case PlyType::U32:
    case PlyType::F32: return 4;
    case PlyType::F64: return 8;
  }
  return 0;
}

bool is_integral(PlyType t) { return t != PlyType::F32 && t != PlyType::F64; }

struct PlyProperty {
  std::string_view name;
  PlyType type = PlyType::F32;  // item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::U8;
};

struct PlyElement {
  std::string_view name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> props;
  std::size_t line = 0;
};

enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

/// Binary values; errors give the absolute byte offset.
class BinarySource {
 public:
  static constexpr bool kAscii = false;
  BinarySource(std::string_view bytes, std::size_t start, bool big, std::string_view name)
      : bytes_(bytes), pos_(start), swap_(big != (std::endian::native == std::endian::big)), name_(name) {}

  /// Errors point at the start of the value last read (or about to be read).
  [[noreturn]] void fail(std::string_view what) const { io_detail::fail_at_offset(name_, value_start_, what); }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  bool at_end() {
    mark();
    return pos_ == bytes_.size();
  }
  /// Makes the next error point at the current position.
  void mark() { value_start_ = pos_; }
  std::string trailing_description() const { return std::to_string(remaining()) + " bytes"; }
  void begin_value(std::string_view) {}
  void end_record() {}

  double real(PlyType t, std::string_view what) {
    const double v = value(t, what);
    if (!std::isfinite(v)) fail(std::string(what) + " is not finite");
    return v;
  }
  std::int64_t integer(PlyType t, std::string_view what) { return static_cast<std::int64_t>(value(t, what)); }
  void skip(PlyType t, std::string_view what) {
    value_start_ = pos_;
    need(type_size(t), what);
    pos_ += type_size(t);
  }

 private:
  void need(std::size_t n, std::string_view what) const {
    if (remaining() < n) fail("file ends inside " + std::string(what));
  }
  template <class T>
  T load() {
    unsigned char buf[sizeof(T)];
    std::memcpy(buf, bytes_.data() + pos_, sizeof(T));
    if (swap_)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(buf[i], buf[sizeof(T) - 1 - i]);
    T v;
    std::memcpy(&v, buf, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  // Every PLY type converts to double exactly (32-bit integers included).
  double value(PlyType t, std::string_view what) {
    value_start_ = pos_;
    need(type_size(t), what);
    switch (t) {
      case PlyType::I8: return load<std::int8_t>();
      case PlyType::U8: return load<std::uint8_t>();
      case PlyType::I16: return load<std::int16_t>();
      case PlyType::U16: return load<std::uint16_t>();
      case PlyType::I32: return load<std::int32_t>();
      case PlyType::U32: return load<std::uint32_t>();
      case PlyType::F32: return load<float>();
      case PlyType::F64: return load<double>();
    }
    return 0;
  }

  std::string_view bytes_;
  std::size_t pos_;
  std::size_t value_start_ = pos_;
  bool swap_;
  std::string_view name_;
};

/// ASCII values, one record per line; errors give the line.
class AsciiSource {
 public:
  static constexpr bool kAscii = true;
  explicit AsciiSource(TextScanner& s) : s_(s) {}

  [[noreturn]] void fail(std::string_view what) const { s_.fail(what); }
  std::size_t remaining() const { return s_.remaining(); }
  bool at_end() { return s_.at_end(); }
  std::string trailing_description() { return "data " + io_detail::quote(s_.token()); }
  void mark() {}
  void begin_value(std::string_view what) {
    if (!s_.more_on_line()) s_.fail("expected " + std::string(what) + ", found end of line");
  }
  void end_record() {
    if (s_.more_on_line())
      s_.fail("unexpected extra value " + io_detail::quote(s_.token()) + " at the end of the record");
    s_.next_line();
  }

  double real(PlyType t, std::string_view what) {
    begin_value(what);
    return is_integral(t) ? static_cast<double>(s_.integer(what)) : s_.real(what);
  }
  std::int64_t integer(PlyType, std::string_view what) {
    begin_value(what);
    return s_.integer(what);
  }
  void skip(PlyType, std::string_view what) {
    begin_value(what);
    s_.token();
  }

 private:
  TextScanner& s_;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
};

PlyHeader parse_header(TextScanner& s) {
  PlyHeader h;
  if (s.token() != "ply") s.fail("not a PLY file (expected 'ply' on the first line)");
  s.next_line();
  bool have_format = false;
  for (;;) {
    const std::string_view kw = s.token();
    if (kw.empty()) s.fail("file ends inside the PLY header (no 'end_header')");
    if (kw == "end_header") {
      if (s.more_on_line()) s.fail("unexpected text after 'end_header'");
      s.next_line();
      break;
    }
    if (kw == "format") {
      const std::string_view f = s.more_on_line() ? s.token() : std::string_view{};
      if (f == "ascii")
        h.format = PlyFormat::Ascii;
      else if (f == "binary_little_endian")
        h.format = PlyFormat::BinaryLittle;
      else if (f == "binary_big_endian")
        h.format = PlyFormat::BinaryBig;
      else
        s.fail("unknown PLY format " + io_detail::quote(f));
      have_format = true;
    } else if (kw == "element") {
      PlyElement e;
      e.line = s.line();
      if (!s.more_on_line()) s.fail("element without a name");
      e.name = s.token();
      if (!s.more_on_line()) s.fail("element '" + std::string(e.name) + "' without a count");
      const std::int64_t n = s.integer("element count");
      if (n < 0) s.fail("negative element count " + std::to_string(n));
      if (e.name == "vertex" && n > static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max()))
        s.fail("vertex count " + std::to_string(n) + " exceeds the 2^32-1 vertices ember supports");
      e.count = static_cast<std::uint64_t>(n);
      h.elements.push_back(e);
    } else if (kw == "property") {
      if (h.elements.empty()) s.fail("property before any element");
      PlyProperty p;
      const auto type_token = [&s](const char* what) {
        const std::string_view t = s.more_on_line() ? s.token() : std::string_view{};
        const auto type = parse_type(t);
        if (!type) s.fail(std::string("unknown PLY ") + what + " type " + io_detail::quote(t));
        return *type;
      };
      if (s.more_on_line() && s.accept("list")) {
        p.is_list = true;
        p.count_type = type_token("list count");
        if (!is_integral(p.count_type)) s.fail("list count type must be an integer type");
      }
      p.type = type_token("property");
      if (!s.more_on_line()) s.fail("property without a name");
      p.name = s.token();
      h.elements.back().props.push_back(p);
    } else if (kw != "comment" && kw != "obj_info") {
      s.fail("unknown PLY header line " + io_detail::quote(kw));
    }
    s.next_line();
  }
  if (!have_format) s.fail("PLY header has no 'format' line");
  return h;
}

template <class Source>
class PlyBody {
 public:
  PlyBody(const PlyHeader& h, Source& src) : h_(h), src_(src) {}

  Mesh read() {
    std::uint64_t vertex_count = 0;
    bool have_vertices = false;
    for (const PlyElement& e : h_.elements) {
      if (e.name == "vertex") vertex_count = e.count, have_vertices = true;
      if (e.name == "tristrips") src_.fail("PLY triangle strips (element 'tristrips') are not supported");
    }
    if (vertex_count > std::numeric_limits<std::uint32_t>::max())
      src_.fail("too many vertices (" + std::to_string(vertex_count) + ")");
    for (const PlyElement& e : h_.elements) {
      check_fits(e);
      if (e.name == "vertex")
        read_vertices(e);
      else if (e.name == "face")
        read_faces(e, vertex_count, have_vertices);
      else
        skip_element(e);
    }
    if (!src_.at_end())
      src_.fail("unexpected " + src_.trailing_description() + " after the last element the header declares");
    return std::move(mesh_);
  }

 private:
  // Each record needs a minimum number of bytes (binary: the fixed sizes;
  // ascii: a digit and a separator per value, the file's last separator may be
  // missing), so a count beyond that is a broken header; rejecting it before
  // reserving keeps memory bounded for any input.
  void check_fits(const PlyElement& e) {
    src_.mark();
    std::uint64_t min_record = 0;
    for (const PlyProperty& p : e.props)
      min_record += Source::kAscii ? 2 : p.is_list ? type_size(p.count_type) : type_size(p.type);
    if (e.count == 0) return;
    if (e.props.empty()) src_.fail("element '" + std::string(e.name) + "' has records but no properties");
    if (e.count - 1 > src_.remaining() / min_record)
      src_.fail("header declares " + std::to_string(e.count) + " '" + std::string(e.name) + "' elements but only " +
                std::to_string(src_.remaining()) + " bytes remain");
  }

  void read_vertices(const PlyElement& e) {
    int axis_prop[3] = {-1, -1, -1};
    for (std::size_t i = 0; i < e.props.size(); ++i) {
      const PlyProperty& p = e.props[i];
      for (int a = 0; a < 3; ++a)
        if (p.name == std::string_view("xyz" + a, 1)) {
          if (p.is_list) src_.fail("vertex property '" + std::string(p.name) + "' must not be a list");
          axis_prop[a] = static_cast<int>(i);
        }
    }
    for (int a = 0; a < 3; ++a)
      if (axis_prop[a] < 0) src_.fail(std::string("vertex element has no '") + "xyz"[a] + "' property");
    mesh_.vertices.resize(e.count);
    for (std::uint64_t v = 0; v < e.count; ++v) {
      double xyz[3] = {0, 0, 0};
      for (std::size_t i = 0; i < e.props.size(); ++i) {
        const PlyProperty& p = e.props[i];
        const int a = static_cast<int>(i) == axis_prop[0]   ? 0
                      : static_cast<int>(i) == axis_prop[1] ? 1
                      : static_cast<int>(i) == axis_prop[2] ? 2
                                                            : -1;
        if (a >= 0)
          xyz[a] = src_.real(p.type, kAxisWhat[a]);
        else
          skip_property(p);
      }
      src_.end_record();
      mesh_.vertices[v] = {xyz[0], xyz[1], xyz[2]};
    }
  }

  void read_faces(const PlyElement& e, std::uint64_t vertex_count, bool have_vertices) {
    int list_prop = -1;
    for (std::size_t i = 0; i < e.props.size(); ++i)
      if (e.props[i].is_list && (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index"))
        list_prop = static_cast<int>(i);
    if (list_prop < 0) src_.fail("face element has no 'vertex_indices' or 'vertex_index' list property");
    if (!is_integral(e.props[list_prop].type)) src_.fail("face indices must have an integer type");
    if (!have_vertices && e.count > 0) src_.fail("faces but no 'vertex' element");
    mesh_.face_offsets.reserve(e.count + 1);
    mesh_.indices.reserve(e.count * 3);
    for (std::uint64_t f = 0; f < e.count; ++f) {
      for (std::size_t i = 0; i < e.props.size(); ++i) {
        const PlyProperty& p = e.props[i];
        if (static_cast<int>(i) != list_prop) {
          skip_property(p);
          continue;
        }
        const std::int64_t n = src_.integer(p.count_type, "face vertex count");
        if (n < 3)
          src_.fail("face " + std::to_string(f) + " has " + std::to_string(n) + " vertices (at least 3 needed)");
        for (std::int64_t k = 0; k < n; ++k) {
          const std::int64_t idx = src_.integer(p.type, "face index");
          if (idx < 0 || static_cast<std::uint64_t>(idx) >= vertex_count)
            src_.fail("face index " + std::to_string(idx) + " out of range (file has " + std::to_string(vertex_count) +
                      " vertices)");
          mesh_.indices.push_back(static_cast<std::uint32_t>(idx));
        }
        if (mesh_.indices.size() > std::numeric_limits<std::uint32_t>::max()) src_.fail("too many face indices");
        mesh_.face_offsets.push_back(static_cast<std::uint32_t>(mesh_.indices.size()));
      }
      src_.end_record();
    }
  }

  void skip_element(const PlyElement& e) {
    for (std::uint64_t r = 0; r < e.count; ++r) {
      for (const PlyProperty& p : e.props) skip_property(p);
      src_.end_record();
    }
  }

  void skip_property(const PlyProperty& p) {
    if (!p.is_list) return src_.skip(p.type, "property value");
    const std::int64_t n = src_.integer(p.count_type, "list count");
    if (n < 0) src_.fail("negative list count " + std::to_string(n));
    for (std::int64_t k = 0; k < n; ++k) src_.skip(p.type, "list value");
  }

  static constexpr std::string_view kAxisWhat[3] = {"vertex x coordinate", "vertex y coordinate",
                                                    "vertex z coordinate"};
  const PlyHeader& h_;
  Source& src_;
  Mesh mesh_;
};

}  // namespace

Mesh read_ply(std::string_view bytes, std::string_view name) {
  bytes = io_detail::skip_bom(bytes);
  TextScanner s(bytes, name, /*multiline=*/true, 0);
  const PlyHeader h = parse_header(s);
  if (h.format == PlyFormat::Ascii) {
    AsciiSource src(s);
    return PlyBody<AsciiSource>(h, src).read();
  }
  const auto start = static_cast<std::size_t>(s.position() - bytes.data());
  BinarySource src(bytes, start, h.format == PlyFormat::BinaryBig, name);
  return PlyBody<BinarySource>(h, src).read();
}

std::string write_ply(const Mesh& mesh, std::span<const Provenance> provenance) {
  io_detail::check_mesh_for_writing(mesh, "PLY");
  const bool sources = !provenance.empty();
  if (sources && provenance.size() != mesh.face_count())
    throw Error("PLY: " + std::to_string(provenance.size()) + " provenance entries for " +
                std::to_string(mesh.face_count()) + " faces; give one per face (or none)");
  std::size_t largest_face = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) largest_face = std::max(largest_face, mesh.face_size(f));
  const bool wide_count = largest_face > 255;
  const bool wide_index = mesh.vertices.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by ember\n";
  if (sources) out += "comment face operand: index of the Boolean's input mesh; source_face: face index within it\n";
  out += "element vertex ";
  io_detail::append_uint(out, mesh.vertices.size());
  out += "\nproperty double x\nproperty double y\nproperty double z\nelement face ";
  io_detail::append_uint(out, mesh.face_count());
  out += wide_count ? "\nproperty list uint " : "\nproperty list uchar ";
  out += wide_index ? "uint vertex_indices\n" : "int vertex_indices\n";
  if (sources) out += "property uint operand\nproperty uint source_face\n";
  out += "end_header\n";
  const std::size_t header = out.size();
  out.resize(header + mesh.vertices.size() * 24 + mesh.face_count() * (wide_count ? 4 : 1) + mesh.indices.size() * 4 +
             (sources ? mesh.face_count() * 8 : 0));
  char* p = out.data() + header;
  const auto put = [&p](auto v) {
    unsigned char buf[sizeof v];
    std::memcpy(buf, &v, sizeof v);
    if constexpr (std::endian::native == std::endian::big)
      for (std::size_t i = 0; i < sizeof v / 2; ++i) std::swap(buf[i], buf[sizeof v - 1 - i]);
    std::memcpy(p, buf, sizeof v);
    p += sizeof v;
  };
  for (const Vec3d& v : mesh.vertices) put(v.x), put(v.y), put(v.z);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    if (wide_count)
      put(static_cast<std::uint32_t>(mesh.face_size(f)));
    else
      put(static_cast<std::uint8_t>(mesh.face_size(f)));
    for (std::uint32_t i : mesh.face(f)) put(i);
    if (sources) put(provenance[f].operand), put(provenance[f].face);
  }
  return out;
}

}  // namespace ember
