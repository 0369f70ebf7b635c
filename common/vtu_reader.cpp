// Reading .vtu frames back: see vtu_reader.h.
//
// The XML part is scanned tag by tag (no general XML parser: the files are ours, and anything
// unexpected is refused with its byte offset). Appended data is addressed from the byte after
// the '_' that opens <AppendedData>, as VTK does; each array's compressed blocks are inflated
// with zlib's uncompress into exactly the size the header announces, and a size that does not
// match is an error rather than a silently short array.
#include "common/vtu_reader.h"

#include <zlib.h>

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>

#include "common/error.h"
#include "common/whole_file.h"

namespace nmm {
namespace {

struct Tag {
  std::string name;  // "DataArray", "/PointData", ...
  std::map<std::string, std::string> attr;
  std::size_t begin = 0, end = 0;  // '<' and one past '>'
  bool self_closing = false;
};

class Parser {
 public:
  Parser(const std::string& s, const std::string& name) : s_(s), name_(name) {}

  [[noreturn]] void fail(std::size_t at, const std::string& what) const {
    throw InputError(name_, "byte " + std::to_string(at), what);
  }

  /// The next tag at or after `from` (skipping <?xml ...?>); false at the end.
  bool next_tag(std::size_t from, Tag& t) const {
    std::size_t lt = s_.find('<', from);
    while (lt != std::string::npos && lt + 1 < s_.size() && s_[lt + 1] == '?')
      lt = s_.find('<', s_.find("?>", lt) == std::string::npos ? s_.size() : s_.find("?>", lt));
    if (lt == std::string::npos) return false;
    const std::size_t gt = s_.find('>', lt);
    if (gt == std::string::npos) fail(lt, "unterminated tag");
    t = Tag{};
    t.begin = lt;
    t.end = gt + 1;
    std::size_t p = lt + 1;
    while (p < gt && !std::isspace(static_cast<unsigned char>(s_[p])) && s_[p] != '/') ++p;
    if (p == lt + 1 && s_[p] == '/') {  // closing tag
      ++p;
      while (p < gt && !std::isspace(static_cast<unsigned char>(s_[p]))) ++p;
    }
    t.name = s_.substr(lt + 1, p - lt - 1);
    t.self_closing = s_[gt - 1] == '/';
    // attributes: key="value"
    while (p < gt) {
      while (p < gt && (std::isspace(static_cast<unsigned char>(s_[p])) || s_[p] == '/')) ++p;
      if (p >= gt) break;
      const std::size_t eq = s_.find('=', p);
      if (eq == std::string::npos || eq > gt || eq + 1 >= gt || s_[eq + 1] != '"')
        fail(p, "malformed attribute in <" + t.name + ">");
      const std::size_t close = s_.find('"', eq + 2);
      if (close == std::string::npos || close > gt) fail(eq, "unterminated attribute value");
      t.attr[s_.substr(p, eq - p)] = s_.substr(eq + 2, close - eq - 2);
      p = close + 1;
    }
    return true;
  }

 private:
  const std::string& s_;
  const std::string& name_;
};

std::uint64_t get_u64(const std::string& s, std::size_t at) {
  std::uint64_t v;
  std::memcpy(&v, s.data() + at, 8);  // little-endian host: checked in parse_vtu
  return v;
}

std::size_t parse_count(const Parser& p, const Tag& t, const char* key) {
  const auto it = t.attr.find(key);
  if (it == t.attr.end()) p.fail(t.begin, "<" + t.name + "> lacks " + key);
  std::size_t v = 0;
  const auto res = std::from_chars(it->second.data(), it->second.data() + it->second.size(), v);
  if (res.ec != std::errc() || res.ptr != it->second.data() + it->second.size())
    p.fail(t.begin, std::string(key) + "=\"" + it->second + "\" is not a count");
  return v;
}

// One array's raw bytes from appended data starting at `at` (absolute offset in the file).
std::string inflate_appended(const Parser& p, const std::string& s, std::size_t at) {
  if (at + 24 > s.size()) p.fail(at, "appended array header runs past the end of the file");
  const std::uint64_t nblocks = get_u64(s, at), block = get_u64(s, at + 8),
                      last = get_u64(s, at + 16);
  if (nblocks > (s.size() - at) / 8 || block == 0 || last > block)
    p.fail(at, "implausible compression header (blocks " + std::to_string(nblocks) + ", size " +
                   std::to_string(block) + ")");
  std::size_t data = at + 24 + 8 * nblocks;
  if (data > s.size()) p.fail(at, "compression header runs past the end of the file");
  std::string raw;
  for (std::uint64_t b = 0; b < nblocks; ++b) {
    const std::uint64_t csize = get_u64(s, at + 24 + 8 * b);
    if (csize > s.size() - data) p.fail(data, "compressed block runs past the end of the file");
    const std::uint64_t want = (b + 1 == nblocks && last != 0) ? last : block;
    // zlib cannot expand more than about 1032:1, so a larger claim is damage — and refusing it
    // keeps a corrupt header from asking for an allocation of its own choosing.
    if (want > 1032 * csize + 64)
      p.fail(at, "block " + std::to_string(b) + " claims " + std::to_string(want) +
                     " bytes from " + std::to_string(csize) + " compressed");
    const std::size_t old = raw.size();
    raw.resize(old + want);
    uLongf got = static_cast<uLongf>(want);
    if (uncompress(reinterpret_cast<Bytef*>(raw.data() + old), &got,
                   reinterpret_cast<const Bytef*>(s.data() + data), static_cast<uLong>(csize)) != Z_OK ||
        got != want)
      p.fail(data, "zlib block " + std::to_string(b) + " does not inflate to " +
                       std::to_string(want) + " bytes");
    data += csize;
  }
  return raw;
}

}  // namespace

PolygonGrid parse_vtu(const std::string& s, const std::string& name) {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  if (first != 1) throw std::logic_error("parse_vtu: big-endian hosts are not supported");

  Parser p(s, name);
  Tag t;
  if (!p.next_tag(0, t) || t.name != "VTKFile") p.fail(0, "not a VTK XML file (no <VTKFile>)");
  if (t.attr["type"] != "UnstructuredGrid") p.fail(t.begin, "not an UnstructuredGrid");
  if (t.attr.count("byte_order") && t.attr["byte_order"] != "LittleEndian")
    p.fail(t.begin, "byte_order " + t.attr["byte_order"] + " is not read");
  const bool compressed = t.attr.count("compressor") != 0;
  if (compressed && t.attr["compressor"] != "vtkZLibDataCompressor")
    p.fail(t.begin, "compressor " + t.attr["compressor"] + " is not read");
  if (compressed && t.attr["header_type"] != "UInt64")
    p.fail(t.begin, "header_type must be UInt64 (as nmm writes)");

  struct Pending {
    Tag tag;
    std::string section;
  };
  std::vector<Pending> arrays;
  std::size_t npoints = 0, ncells = 0;
  bool have_piece = false;
  std::size_t appended = std::string::npos;  // offset of the first byte after '_'
  std::string section;
  std::size_t at = t.end;
  while (p.next_tag(at, t)) {
    at = t.end;
    if (t.name == "Piece") {
      if (have_piece) p.fail(t.begin, "more than one <Piece> (not a frame nmm wrote)");
      have_piece = true;
      npoints = parse_count(p, t, "NumberOfPoints");
      ncells = parse_count(p, t, "NumberOfCells");
    } else if (t.name == "PointData" || t.name == "CellData" || t.name == "Points" ||
               t.name == "Cells") {
      section = t.self_closing ? "" : t.name;
    } else if (t.name.size() > 1 && t.name[0] == '/' && t.name.substr(1) == section) {
      section.clear();
    } else if (t.name == "DataArray") {
      if (section.empty()) p.fail(t.begin, "<DataArray> outside PointData, CellData, Points, Cells");
      arrays.push_back({t, section});
      if (!t.self_closing) {  // inline (ascii) data: skip to its end
        const std::size_t close = s.find("</DataArray>", t.end);
        if (close == std::string::npos) p.fail(t.begin, "unterminated <DataArray>");
        arrays.back().tag.end = t.end;  // data between tag.end and close
        at = close + 12;
      }
    } else if (t.name == "AppendedData") {
      if (t.attr["encoding"] != "raw") p.fail(t.begin, "appended data encoding must be raw");
      const std::size_t us = s.find('_', t.end);
      if (us == std::string::npos) p.fail(t.end, "appended data lacks its '_' marker");
      appended = us + 1;
      break;  // binary from here on: no more tags to read
    }
  }
  if (!have_piece) p.fail(0, "no <Piece>");

  PolygonGrid g;
  g.offsets.clear();
  bool have_points = false, have_conn = false, have_offsets = false;
  for (const Pending& a : arrays) {
    const Tag& tag = a.tag;
    const std::string type = tag.attr.count("type") ? tag.attr.at("type") : "";
    const std::string array_name = tag.attr.count("Name") ? tag.attr.at("Name") : "";
    const std::string format = tag.attr.count("format") ? tag.attr.at("format") : "";
    const int comps =
        tag.attr.count("NumberOfComponents") ? static_cast<int>(parse_count(p, tag, "NumberOfComponents")) : 1;
    if (comps < 1) p.fail(tag.begin, "NumberOfComponents must be at least 1");
    const std::size_t width = type == "Float64" ? 8 : type == "Int32" ? 4 : type == "UInt8" ? 1 : 0;
    if (width == 0) p.fail(tag.begin, "array '" + array_name + "': type '" + type + "' is not read");
    std::vector<double> f64;
    std::vector<std::int32_t> i32;
    if (format == "ascii") {
      if (tag.self_closing) p.fail(tag.begin, "ascii array '" + array_name + "' has no values");
      const std::size_t close = s.find("</DataArray>", tag.end);
      if (close == std::string::npos) p.fail(tag.begin, "unterminated <DataArray>");
      const char* c = s.data() + tag.end;
      const char* e = s.data() + close;
      while (true) {
        while (c < e && std::isspace(static_cast<unsigned char>(*c))) ++c;
        if (c >= e) break;
        if (width == 8) {
          char* stop = nullptr;
          const double v = std::strtod(c, &stop);
          if (stop == c || stop > e) p.fail(static_cast<std::size_t>(c - s.data()), "not a number in array '" + array_name + "'");
          f64.push_back(v);
          c = stop;
        } else {
          long long v = 0;
          const auto res = std::from_chars(c, e, v);
          if (res.ec != std::errc()) p.fail(static_cast<std::size_t>(c - s.data()), "not an integer in array '" + array_name + "'");
          i32.push_back(static_cast<std::int32_t>(v));
          c = res.ptr;
        }
      }
    } else if (format == "appended") {
      if (appended == std::string::npos) p.fail(tag.begin, "appended array but no <AppendedData>");
      if (!compressed) p.fail(tag.begin, "uncompressed appended data is not read (nmm compresses)");
      const std::size_t off = parse_count(p, tag, "offset");
      if (off > s.size() - appended) p.fail(tag.begin, "offset beyond the end of the file");
      const std::string raw = inflate_appended(p, s, appended + off);
      if (raw.size() % width != 0) p.fail(appended + off, "array '" + array_name + "' is not whole values");
      const std::size_t n = raw.size() / width;
      if (width == 8) {
        f64.resize(n);
        std::memcpy(f64.data(), raw.data(), raw.size());
      } else if (width == 4) {
        i32.resize(n);
        std::memcpy(i32.data(), raw.data(), raw.size());
      } else {
        i32.assign(raw.begin(), raw.end());
        for (auto& v : i32) v = static_cast<std::uint8_t>(v);
      }
    } else {
      p.fail(tag.begin, "array '" + array_name + "': format '" + format + "' is not read");
    }
    const std::size_t count = width == 8 ? f64.size() : i32.size();
    auto expect = [&](std::size_t want) {
      if (count != want)
        p.fail(tag.begin, "array '" + array_name + "' has " + std::to_string(count) +
                              " values, expected " + std::to_string(want));
    };
    if (a.section == "Points") {
      if (width != 8 || comps != 3) p.fail(tag.begin, "Points must be Float64 with 3 components");
      expect(3 * npoints);
      g.points = std::move(f64);
      have_points = true;
    } else if (a.section == "Cells") {
      if (array_name == "types") {
        expect(ncells);
        // Every cell a polygon (the elements), or every one a line (the flow network's part).
        if (!i32.empty()) g.cell_type = static_cast<std::uint8_t>(i32.front() == PolygonGrid::kLine ? PolygonGrid::kLine : PolygonGrid::kPolygon);
        for (std::int32_t v : i32)
          if (v != g.cell_type)
            p.fail(tag.begin, "a cell is not a polygon (type " + std::to_string(v) + ")" +
                                  (g.cell_type == PolygonGrid::kLine ? " among lines" : ""));
      } else if (array_name == "connectivity" && width == 4) {
        g.connectivity = std::move(i32);
        have_conn = true;
      } else if (array_name == "offsets" && width == 4) {
        expect(ncells);
        g.offsets.push_back(0);
        g.offsets.insert(g.offsets.end(), i32.begin(), i32.end());
        have_offsets = true;
      } else {
        p.fail(tag.begin, "unexpected cell array '" + array_name + "' of type " + type);
      }
    } else {
      const bool point = a.section == "PointData";
      expect(static_cast<std::size_t>(comps) * (point ? npoints : ncells));
      GridArray ga;
      ga.name = array_name;
      ga.components = comps;
      if (width == 8) {
        ga.type = GridArray::Type::Float64;
        ga.f64 = std::move(f64);
      } else {
        ga.type = GridArray::Type::Int32;
        ga.i32 = std::move(i32);
      }
      (point ? g.point_data : g.cell_data).push_back(std::move(ga));
    }
  }
  if (!have_points || !have_conn || !have_offsets)
    p.fail(0, "Points, connectivity or offsets missing");
  try {
    check_grid(g);
  } catch (const std::logic_error& e) {
    p.fail(0, std::string("inconsistent cells: ") + e.what());
  }
  return g;
}

PolygonGrid read_vtu(const std::string& path) { return parse_vtu(read_text_file(path), path); }

}  // namespace nmm
