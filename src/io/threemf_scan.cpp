#include "io/threemf_scan.hpp"

#include <zlib.h>

#include <cstring>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

namespace ember::io_detail {
namespace {

constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();

std::uint64_t sat_add(std::uint64_t a, std::uint64_t b) { return a > kMax - b ? kMax : a + b; }

std::uint32_t u16(std::string_view b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8;
}
std::uint32_t u32(std::string_view b, std::size_t at) { return u16(b, at) | u16(b, at + 2) << 16; }
std::uint64_t u64(std::string_view b, std::size_t at) { return u32(b, at) | std::uint64_t{u32(b, at + 4)} << 32; }

/// The XML of the model parts, tag by tag (no DOM, no allocation per byte).
class ModelScanner {
 public:
  struct Object {
    std::uint64_t triangles = 0;
    std::vector<std::string> children;  // component object ids
  };

  void feed(const char* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      const char c = p[i];
      if (!in_tag_) {
        if (c == '<') in_tag_ = true, tag_.clear();
      } else if (c == '>') {
        in_tag_ = false;
        tag(tag_);
      } else if (tag_.size() < 4096) {
        tag_ += c;
      }
    }
  }
  /// A new part: object ids are per part.
  void next_part() { ++part_; }

  std::unordered_map<std::string, Object> objects;
  std::vector<std::string> items;

 private:
  static std::string_view name_of(std::string_view t) {
    std::size_t e = 0;
    while (e < t.size() && t[e] != ' ' && t[e] != '\t' && t[e] != '\n' && t[e] != '\r' && t[e] != '/') ++e;
    std::string_view n = t.substr(0, e);
    if (const std::size_t colon = n.find(':'); colon != std::string_view::npos) n.remove_prefix(colon + 1);
    return n;
  }
  static std::string attr(std::string_view t, std::string_view key) {
    for (std::size_t at = t.find(key); at != std::string_view::npos; at = t.find(key, at + 1)) {
      if (at == 0 || (t[at - 1] != ' ' && t[at - 1] != '\t' && t[at - 1] != '\n' && t[at - 1] != '\r')) continue;
      std::size_t q = at + key.size();
      while (q < t.size() && (t[q] == ' ' || t[q] == '\t')) ++q;
      if (q >= t.size() || t[q] != '=') continue;
      ++q;
      while (q < t.size() && (t[q] == ' ' || t[q] == '\t')) ++q;
      if (q >= t.size() || (t[q] != '"' && t[q] != '\'')) continue;
      const char quote = t[q];
      const std::size_t end = t.find(quote, q + 1);
      if (end == std::string_view::npos) return {};
      return std::string(t.substr(q + 1, end - q - 1));
    }
    return {};
  }
  std::string key(const std::string& id) const { return std::to_string(part_) + ":" + id; }

  void tag(std::string_view t) {
    if (t.empty() || t[0] == '/') {
      if (name_of(t.substr(t.empty() ? 0 : 1)) == "object") current_.clear();
      return;
    }
    const std::string_view n = name_of(t);
    if (n == "object") {
      current_ = key(attr(t, "id"));
      objects[current_];
      if (!t.empty() && t.back() == '/') current_.clear();
    } else if (n == "triangle") {
      if (!current_.empty()) ++objects[current_].triangles;
    } else if (n == "component") {
      if (!current_.empty()) objects[current_].children.push_back(key(attr(t, "objectid")));
    } else if (n == "item") {
      items.push_back(key(attr(t, "objectid")));
    }
  }

  bool in_tag_ = false;
  std::string tag_;
  std::string current_;
  int part_ = 0;
};

/// Inflates (or copies) one ZIP entry into the scanner; false if it cannot.
bool feed_entry(std::string_view zip, std::size_t local, std::uint32_t method, std::uint64_t csize,
                ModelScanner& scanner) {
  if (local > zip.size() || zip.size() - local < 30 || u32(zip, local) != 0x04034b50) return false;
  const std::size_t data = local + 30 + u16(zip, local + 26) + u16(zip, local + 28);
  if (data > zip.size() || csize > zip.size() - data) return false;
  const char* p = zip.data() + data;
  if (method == 0) {
    scanner.feed(p, static_cast<std::size_t>(csize));
    return true;
  }
  if (method != 8) return false;
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return false;
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(p));
  z.avail_in = static_cast<uInt>(std::min<std::uint64_t>(csize, std::numeric_limits<uInt>::max()));
  char out[1 << 16];
  int rc = Z_OK;
  while (rc == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(out);
    z.avail_out = sizeof out;
    rc = inflate(&z, Z_NO_FLUSH);
    scanner.feed(out, sizeof out - z.avail_out);
    if (rc == Z_BUF_ERROR && z.avail_in == 0) break;
  }
  inflateEnd(&z);
  return rc == Z_STREAM_END;
}

}  // namespace

std::optional<ThreeMfExpansion> scan_3mf_expansion(std::string_view zip) {
  // End of central directory: the last signature in the final 64 KiB + 22 bytes.
  if (zip.size() < 22) return std::nullopt;
  std::size_t eocd = std::string_view::npos;
  const std::size_t lowest = zip.size() > 22 + 65535 ? zip.size() - 22 - 65535 : 0;
  for (std::size_t at = zip.size() - 22 + 1; at-- > lowest;)
    if (u32(zip, at) == 0x06054b50) {
      eocd = at;
      break;
    }
  if (eocd == std::string_view::npos) return std::nullopt;
  std::uint64_t entries = u16(zip, eocd + 10);
  std::uint64_t dir = u32(zip, eocd + 16);
  // Zip64 (lib3mf writes it): the locator just before the record points at the Zip64 record.
  if (dir == 0xffffffff || entries == 0xffff) {
    if (eocd < 20 || u32(zip, eocd - 20) != 0x07064b50) return std::nullopt;
    const std::uint64_t rec = u64(zip, eocd - 20 + 8);
    if (rec > zip.size() || zip.size() - rec < 56 || u32(zip, rec) != 0x06064b50) return std::nullopt;
    entries = u64(zip, rec + 32);
    dir = u64(zip, rec + 48);
  }
  if (dir > zip.size()) return std::nullopt;
  std::size_t at = static_cast<std::size_t>(dir);
  ModelScanner scanner;
  for (std::uint64_t e = 0; e < entries; ++e) {
    if (at > zip.size() || zip.size() - at < 46 || u32(zip, at) != 0x02014b50) return std::nullopt;
    const std::uint32_t method = u16(zip, at + 10);
    std::uint64_t csize = u32(zip, at + 20), usize = u32(zip, at + 24), local = u32(zip, at + 42);
    const std::size_t name_len = u16(zip, at + 28), extra = u16(zip, at + 30), comment = u16(zip, at + 32);
    if (zip.size() - at - 46 < name_len + extra) return std::nullopt;
    // Zip64 extra field: the 8-byte values of the fields that hold 0xffffffff, in this order.
    for (std::size_t x = at + 46 + name_len, end = x + extra; x + 4 <= end;) {
      const std::uint32_t id = u16(zip, x), len = u16(zip, x + 2);
      if (x + 4 + len > end) break;
      if (id == 0x0001) {
        std::size_t v = x + 4;
        for (std::uint64_t* field : {&usize, &csize, &local})
          if (*field == 0xffffffff && v + 8 <= x + 4 + len) *field = u64(zip, v), v += 8;
      }
      x += 4 + len;
    }
    (void)usize;
    const std::string_view name = zip.substr(at + 46, name_len);
    if (name.size() >= 6 && name.substr(name.size() - 6) == ".model") {
      scanner.next_part();
      if (local > zip.size() || !feed_entry(zip, static_cast<std::size_t>(local), method, csize, scanner))
        return std::nullopt;
    }
    at += 46 + name_len + extra + comment;
  }
  // Expanded size per object, memoized; a cycle or a missing object is left to lib3mf.
  struct Size {
    std::uint64_t triangles = 0, instances = 0;
  };
  std::unordered_map<std::string, Size> done;
  std::unordered_map<std::string, bool> active;
  bool broken = false;
  const auto expand = [&](auto&& self, const std::string& id, int depth) -> Size {
    if (auto it = done.find(id); it != done.end()) return it->second;
    const auto obj = scanner.objects.find(id);
    if (obj == scanner.objects.end() || active[id] || depth > 1000) {
      broken = true;
      return {};
    }
    active[id] = true;
    Size s{obj->second.triangles, 1};
    for (const std::string& child : obj->second.children) {
      const Size c = self(self, child, depth + 1);
      s.triangles = sat_add(s.triangles, c.triangles);
      s.instances = sat_add(s.instances, c.instances);
    }
    active[id] = false;
    return done[id] = s;
  };
  ThreeMfExpansion out;
  for (const auto& [id, obj] : scanner.objects) out.stored_triangles = sat_add(out.stored_triangles, obj.triangles);
  for (const std::string& item : scanner.items) {
    const Size s = expand(expand, item, 0);
    out.expanded_triangles = sat_add(out.expanded_triangles, s.triangles);
    out.instances = sat_add(out.instances, s.instances);
  }
  if (broken) return std::nullopt;
  return out;
}

}  // namespace ember::io_detail
